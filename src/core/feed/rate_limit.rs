//! The limit on how fast the feed may change along the path (seed 000, test #3; MODEL.md
//! §4): a backward and a forward pass, as a velocity planner does, so the feed has come
//! down before a point that needs a low feed, and never exceeds the unlimited profile.

/// Limits `feeds` (mm/min, one per point, `steps_mm[i]` the path length from point i−1
/// to i) so that the feed changes by at most `max_change_per_mm` between neighbours.
/// The result is never above the input at any point.
pub fn limit_feed_change(feeds: &[f64], steps_mm: &[f64], max_change_per_mm: f64) -> Vec<f64> {
    let mut out = feeds.to_vec();
    // Forward: the feed may rise only so fast.
    for i in 1..out.len() {
        out[i] = out[i].min(out[i - 1] + max_change_per_mm * steps_mm[i]);
    }
    // Backward: it must have come down before a low point.
    for i in (0..out.len().saturating_sub(1)).rev() {
        out[i] = out[i].min(out[i + 1] + max_change_per_mm * steps_mm[i + 1]);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    #[test]
    fn the_feed_comes_down_before_a_slow_point() {
        let feeds = [1000.0, 1000.0, 1000.0, 100.0, 1000.0, 1000.0];
        let steps = [0.0, 1.0, 1.0, 1.0, 1.0, 1.0];
        let out = limit_feed_change(&feeds, &steps, 300.0);
        let expected = [1000.0, 700.0, 400.0, 100.0, 400.0, 700.0];
        assert!(out.iter().zip(expected).all(|(a, b)| (a - b).abs() < 1e-9), "{out:?}");
    }

    proptest! {
        #[test]
        fn the_limited_profile_is_never_above_the_unlimited_and_respects_the_rate(
            feeds in proptest::collection::vec(1.0f64..10_000.0, 2..200),
            step in 0.01f64..2.0,
            rate in 1.0f64..5_000.0,
        ) {
            let steps = vec![step; feeds.len()];
            let out = limit_feed_change(&feeds, &steps, rate);
            for i in 0..feeds.len() {
                prop_assert!(out[i] <= feeds[i] + 1e-9);
                if i > 0 {
                    prop_assert!((out[i] - out[i - 1]).abs() <= rate * step + 1e-6);
                }
            }
        }
    }
}
