//! "Nice" numbers for axes and scale bars: 1, 2 and 5 × 10^k, and value labels with as
//! many decimals as their spacing needs.

/// The mantissas of round numbers, ascending.
const ROUND_MANTISSAS: [f64; 3] = [1.0, 2.0, 5.0];
/// Relative slack when comparing a tick to the end of its range.
const TICK_SLACK: f64 = 1e-9;

/// The largest 1, 2 or 5 × 10^k not above `length` (`length` > 0); 0 otherwise.
pub fn round_down(length: f64) -> f64 {
    if !(length.is_finite() && length > 0.0) {
        return 0.0;
    }
    let decade = 10f64.powf(length.log10().floor());
    ROUND_MANTISSAS.iter().rev().map(|m| m * decade).find(|&v| v <= length * (1.0 + TICK_SLACK)).unwrap_or(decade)
}

/// The smallest 1, 2 or 5 × 10^k not below `length` (`length` > 0); 1 otherwise.
pub fn round_up(length: f64) -> f64 {
    if !(length.is_finite() && length > 0.0) {
        return 1.0;
    }
    let decade = 10f64.powf(length.log10().floor());
    ROUND_MANTISSAS.iter().map(|m| m * decade).find(|&v| v >= length * (1.0 - TICK_SLACK)).unwrap_or(10.0 * decade)
}

/// Ticks of an axis covering `min..=max` with about `target` intervals: a round step and
/// the multiples of it from below `min` to above `max` (the axis range is the first to the
/// last tick). An empty or degenerate range is widened around its value.
pub fn nice_ticks(min: f64, max: f64, target: usize) -> Vec<f64> {
    let (mut lo, mut hi) = if min.is_finite() && max.is_finite() { (min.min(max), min.max(max)) } else { (0.0, 1.0) };
    if hi - lo <= f64::EPSILON * hi.abs().max(1.0) {
        let pad = if lo.abs() > 0.0 { lo.abs() * 0.1 } else { 1.0 };
        lo -= pad;
        hi += pad;
    }
    let step = round_up((hi - lo) / target.max(1) as f64);
    // A bound within the slack of a tick is that tick.
    let first = (lo / step + TICK_SLACK).floor();
    let last = (hi / step - TICK_SLACK).ceil();
    let count = (last - first) as usize;
    (0..=count).map(|i| clean((first + i as f64) * step)).collect()
}

/// `v` with float dust removed (so 0.30000000000000004 prints as 0.3).
fn clean(v: f64) -> f64 {
    const DUST: f64 = 1e12;
    (v * DUST).round() / DUST
}

/// Decimals needed to tell apart values `step` apart (0 for steps ≥ 1).
pub fn decimals_for(step: f64) -> usize {
    const MAX_DECIMALS: usize = 6;
    if !(step.is_finite() && step > 0.0) || step >= 1.0 {
        return 0;
    }
    ((-step.log10() - TICK_SLACK).ceil().max(0.0) as usize).min(MAX_DECIMALS)
}

/// A value label with `decimals` decimals (`-0` written `0`).
pub fn label(v: f64, decimals: usize) -> String {
    let text = format!("{v:.decimals$}");
    if text.trim_start_matches('-').chars().all(|c| c == '0' || c == '.') {
        text.trim_start_matches('-').to_string()
    } else {
        text
    }
}

/// A label for a single value (a legend tick, a round length): three significant digits
/// (all the integer digits from 100 up), trailing zeros dropped.
pub fn value_label(v: f64) -> String {
    const SIGNIFICANT: i32 = 3;
    const MAX_DECIMALS: i32 = 6;
    if !v.is_finite() || v.abs() < f64::MIN_POSITIVE {
        return "0".into();
    }
    let magnitude = v.abs().log10().floor() as i32;
    let decimals = (SIGNIFICANT - 1 - magnitude).clamp(0, MAX_DECIMALS) as usize;
    let text = label(v, decimals);
    if text.contains('.') {
        text.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        text
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lengths_round_down_to_one_two_or_five_times_a_power_of_ten() {
        assert!((round_down(7.3) - 5.0).abs() < 1e-12);
        assert!((round_down(19.0) - 10.0).abs() < 1e-12);
        assert!((round_down(0.25) - 0.2).abs() < 1e-12);
        assert!((round_down(200.0) - 200.0).abs() < 1e-9);
        assert!((round_up(3.1) - 5.0).abs() < 1e-12);
        assert!((round_up(0.011) - 0.02).abs() < 1e-12);
    }

    #[test]
    fn ticks_cover_the_range_with_a_round_step() {
        let t = nice_ticks(3.0, 97.0, 5);
        assert!((t[0] - 0.0).abs() < 1e-12);
        assert!((t[t.len() - 1] - 100.0).abs() < 1e-12);
        assert!((t[1] - t[0] - 20.0).abs() < 1e-12);
        let from_zero = nice_ticks(0.0, 150.0, 6);
        assert!(from_zero[0].abs() < 1e-12, "a range starting at a tick starts there: {from_zero:?}");
        assert!((from_zero[from_zero.len() - 1] - 150.0).abs() < 1e-12);
        let small = nice_ticks(0.1, 0.35, 5);
        assert!((small[1] - small[0] - 0.05).abs() < 1e-12);
    }

    #[test]
    fn a_single_value_gets_a_range_around_it() {
        let t = nice_ticks(5.0, 5.0, 4);
        assert!(t[0] < 5.0 && t[t.len() - 1] > 5.0);
        let z = nice_ticks(0.0, 0.0, 4);
        assert!(z[0] < 0.0 && z[z.len() - 1] > 0.0);
    }

    #[test]
    fn labels_have_as_many_decimals_as_the_step_needs() {
        assert_eq!(decimals_for(20.0), 0);
        assert_eq!(decimals_for(0.5), 1);
        assert_eq!(decimals_for(0.05), 2);
        assert_eq!(label(-0.0001, 2), "0.00");
        assert_eq!(value_label(0.012345), "0.0123");
        assert_eq!(value_label(1234.6), "1235");
        assert_eq!(value_label(42.26), "42.3");
        assert_eq!(value_label(40.0), "40");
        assert_eq!(value_label(0.5), "0.5");
    }
}
