//! z-cut division (seed 004 §2.3, MODEL.md §7 class C): a depth cut in repeated passes of a
//! reduced axial depth, the levels equally spaced and the last exactly at the bottom.

use crate::core::error::{require_finite, require_positive};
use crate::core::tolerance::LENGTH_EPS_MM;
use crate::core::CoreError;

/// Axial depth of a z-cut division pass in class C regions (R/r < 1.1), mm: seed 004 §2.3
/// says "typically 2~3 mm" (MODEL.md §7); case study II used 0.5 mm.
pub const DEFAULT_ZCUT_AD_MM: f64 = 2.5;

/// Most levels one depth is divided into.
pub const MAX_LEVELS: usize = 100_000;

/// `⌈depth / max_ad⌉`, at least 1, unbounded (for a positive `max_ad_mm`): a depth that is
/// a whole number of steps (to rounding) gets exactly that many.
pub fn step_count(depth_mm: f64, max_ad_mm: f64) -> f64 {
    (depth_mm / max_ad_mm - LENGTH_EPS_MM / max_ad_mm).ceil().max(1.0)
}

/// How many passes [`z_levels`] makes: `⌈depth / max_ad⌉`, at least 1; an error naming
/// `max_ad_mm` when that is more than [`MAX_LEVELS`].
pub fn level_count(z_top_mm: f64, z_bottom_mm: f64, max_ad_mm: f64) -> Result<usize, CoreError> {
    require_finite("z_top_mm", z_top_mm)?;
    require_finite("z_bottom_mm", z_bottom_mm)?;
    require_positive("max_ad_mm", max_ad_mm)?;
    let depth = z_top_mm - z_bottom_mm;
    if depth <= LENGTH_EPS_MM {
        return Err(CoreError::invalid("z_bottom_mm", "must be below z_top_mm"));
    }
    let n = step_count(depth, max_ad_mm);
    if n > MAX_LEVELS as f64 {
        return Err(CoreError::invalid("max_ad_mm", format!("divides the depth into more than {MAX_LEVELS} levels")));
    }
    Ok(n as usize)
}

/// The tool-tip heights of the passes from `z_top_mm` down to `z_bottom_mm`, each at most
/// `max_ad_mm` below the one before (the first below `z_top_mm`): `n = ⌈depth / max_ad⌉`
/// equal steps, top first, the last exactly `z_bottom_mm`.
pub fn z_levels(z_top_mm: f64, z_bottom_mm: f64, max_ad_mm: f64) -> Result<Vec<f64>, CoreError> {
    let n = level_count(z_top_mm, z_bottom_mm, max_ad_mm)?;
    let depth = z_top_mm - z_bottom_mm;
    let step = depth / n as f64;
    let mut levels: Vec<f64> = (1..n).map(|k| z_top_mm - step * k as f64).collect();
    levels.push(z_bottom_mm);
    Ok(levels)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::core::tolerance::approx_eq;

    #[test]
    fn ten_mm_at_two_and_a_half_gives_four_equal_passes_ending_exactly_at_the_bottom() {
        let z = z_levels(0.0, -10.0, DEFAULT_ZCUT_AD_MM).unwrap();
        assert_eq!(z.len(), 4);
        for (k, level) in z.iter().enumerate() {
            assert!(approx_eq(*level, -2.5 * (k + 1) as f64, 1e-12));
        }
        assert!(approx_eq(*z.last().unwrap(), -10.0, 0.0));
    }

    #[test]
    fn a_depth_that_does_not_divide_gets_equal_steps_below_the_limit() {
        let z = z_levels(5.0, -2.0, 2.5).unwrap();
        assert_eq!(z.len(), 3);
        let steps: Vec<f64> =
            std::iter::once(5.0).chain(z.iter().copied()).collect::<Vec<_>>().windows(2).map(|w| w[0] - w[1]).collect();
        for s in &steps {
            assert!(approx_eq(*s, 7.0 / 3.0, 1e-12) && *s <= 2.5);
        }
        assert!(approx_eq(z[2], -2.0, 0.0));
    }

    #[test]
    fn a_depth_within_one_pass_is_one_level_at_the_bottom() {
        assert_eq!(z_levels(0.0, -0.5, 2.5).unwrap(), vec![-0.5]);
    }

    #[test]
    fn a_bottom_above_the_top_or_a_zero_depth_of_cut_is_refused() {
        assert!(z_levels(0.0, 1.0, 2.5).unwrap_err().to_string().starts_with("z_bottom_mm"));
        assert!(z_levels(0.0, -1.0, 0.0).unwrap_err().to_string().starts_with("max_ad_mm"));
        assert!(z_levels(f64::NAN, -1.0, 1.0).is_err());
    }

    proptest::proptest! {
        #[test]
        fn levels_are_equal_steps_no_deeper_than_the_limit(top in -50.0..50.0f64, depth in 0.01..80.0f64, ad in 0.05..12.0f64) {
            let z = z_levels(top, top - depth, ad).unwrap();
            let mut prev = top;
            let first = top - z[0];
            for level in &z {
                proptest::prop_assert!(prev - level <= ad + 1e-9);
                proptest::prop_assert!(approx_eq(prev - level, first, 1e-9));
                prev = *level;
            }
            proptest::prop_assert!(approx_eq(*z.last().unwrap(), top - depth, 0.0));
        }
    }
}
