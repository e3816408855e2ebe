//! Explicit float tolerances: the core never compares floats with `==`.

/// Lengths closer than this are the same length (mm).
pub const LENGTH_EPS_MM: f64 = 1e-9;

/// Relative tolerance used when a computed ratio must sit on a boundary (e.g. `cos α = ±1`).
pub const RATIO_EPS: f64 = 1e-12;

/// `true` when `a` and `b` differ by at most `tol`.
pub fn approx_eq(a: f64, b: f64, tol: f64) -> bool {
    (a - b).abs() <= tol
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn values_within_the_tolerance_are_equal_and_others_are_not() {
        assert!(approx_eq(1.0, 1.0 + 1e-10, 1e-9));
        assert!(!approx_eq(1.0, 1.0 + 1e-8, 1e-9));
    }
}
