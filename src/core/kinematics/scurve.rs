//! Jerk-limited (S-curve, "double S") speed changes, in closed form.
//!
//! A change of speed by `Δv` that starts and ends at zero acceleration, with acceleration at
//! most `a` and jerk at most `j`, takes at least (Biagiotti & Melchiorri, *Trajectory
//! Planning for Automatic Machines and Robots*, 2008, §3.4):
//!
//! - `Δv/a + a/j` when `Δv ≥ a²/j` (jerk up, constant `a`, jerk down);
//! - `2·sqrt(Δv/j)` otherwise (`a` is never reached).
//!
//! The profile is point-symmetric about its middle, so the distance it covers is the mean
//! speed times its duration: `(v₀ + v₁)/2 · T`. With an infinite jerk both reduce to the
//! trapezoidal `Δv/a`.

/// Relative precision of the speed searches (bisection).
const SEARCH_RELATIVE_TOLERANCE: f64 = 1e-14;

/// Cap on bisection steps (the tolerance is reached in about 50).
const SEARCH_MAX_STEPS: usize = 200;

/// Shortest time (s) of a jerk-limited change of speed by `dv_mm_s`.
pub fn ramp_time_s(dv_mm_s: f64, accel_mm_s2: f64, jerk_mm_s3: f64) -> f64 {
    if dv_mm_s <= 0.0 {
        0.0
    } else if dv_mm_s * jerk_mm_s3 >= accel_mm_s2 * accel_mm_s2 {
        dv_mm_s / accel_mm_s2 + accel_mm_s2 / jerk_mm_s3
    } else {
        2.0 * (dv_mm_s / jerk_mm_s3).sqrt()
    }
}

/// Distance (mm) covered by the fastest jerk-limited change between two speeds (either order).
pub fn ramp_distance_mm(v0_mm_s: f64, v1_mm_s: f64, accel_mm_s2: f64, jerk_mm_s3: f64) -> f64 {
    0.5 * (v0_mm_s + v1_mm_s) * ramp_time_s((v1_mm_s - v0_mm_s).abs(), accel_mm_s2, jerk_mm_s3)
}

/// Time (s) to cover `length_mm`, entering at `v_in` and leaving at `v_out` (at zero
/// acceleration both), never faster than `cap` (mm/s): speed up to a peak, cruise at `cap`
/// if there is room, slow down.
///
/// When even the monotone change between `v_in` and `v_out` does not fit (the entry and exit
/// speeds come from a constant-acceleration plan, which a jerk limit may not follow), the
/// time is that of the change from the lower of the two that just covers `length_mm`, ending
/// below the higher one: a profile the machine can follow, never faster than the plan.
pub fn hill_time_s(v_in: f64, v_out: f64, cap: f64, length_mm: f64, accel_mm_s2: f64, jerk_mm_s3: f64) -> f64 {
    let cap = cap.max(v_in).max(v_out);
    let ramps = |v: f64| {
        ramp_distance_mm(v_in, v, accel_mm_s2, jerk_mm_s3) + ramp_distance_mm(v_out, v, accel_mm_s2, jerk_mm_s3)
    };
    let ramp_times =
        |v: f64| ramp_time_s(v - v_in, accel_mm_s2, jerk_mm_s3) + ramp_time_s(v - v_out, accel_mm_s2, jerk_mm_s3);
    let at_cap = ramps(cap);
    if at_cap <= length_mm {
        return ramp_times(cap) + (length_mm - at_cap) / cap;
    }
    let lowest_peak = v_in.max(v_out);
    if ramps(lowest_peak) < length_mm {
        let peak = bisect(lowest_peak, cap, |v| ramps(v) < length_mm);
        return ramp_times(peak);
    }
    let low = v_in.min(v_out);
    let end = bisect(low, lowest_peak, |v| ramp_distance_mm(low, v, accel_mm_s2, jerk_mm_s3) < length_mm);
    ramp_time_s(end - low, accel_mm_s2, jerk_mm_s3)
}

/// The boundary in `[lo, hi]` where `below` turns from true to false (`below` monotone).
fn bisect(mut lo: f64, mut hi: f64, below: impl Fn(f64) -> bool) -> f64 {
    for _ in 0..SEARCH_MAX_STEPS {
        if hi - lo <= SEARCH_RELATIVE_TOLERANCE * hi {
            break;
        }
        let mid = 0.5 * (lo + hi);
        if below(mid) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

#[cfg(test)]
mod tests {
    use super::*;

    const A: f64 = 2000.0;
    const J: f64 = 50000.0;

    #[test]
    fn a_large_speed_change_reaches_the_acceleration_limit_and_adds_a_over_j() {
        let dv = 100.0;
        assert!((ramp_time_s(dv, A, J) - (dv / A + A / J)).abs() < 1e-15);
    }

    #[test]
    fn the_two_ramp_formulas_meet_at_a_squared_over_j() {
        let dv = A * A / J;
        let below = ramp_time_s(dv * (1.0 - 1e-12), A, J);
        assert!((below - ramp_time_s(dv, A, J)).abs() < 1e-9);
    }

    #[test]
    fn a_hill_with_room_to_cruise_is_two_ramps_and_a_cruise() {
        let t = hill_time_s(0.0, 0.0, 100.0, 100.0, A, J);
        assert!((t - (1.0 + 100.0 / A + A / J)).abs() < 1e-12);
    }

    #[test]
    fn a_monotone_change_that_does_not_fit_ends_below_its_target() {
        // From 40 to 45 mm/s in 0.29 mm: the jerk-limited ramp needs 0.85 mm.
        let t = hill_time_s(40.0, 45.0, 60.0, 0.29, A, J);
        assert!(t > 0.29 / 45.0 && t < 0.29 / 40.0, "{t}");
    }
}
