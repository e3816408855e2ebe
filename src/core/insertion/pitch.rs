//! The pitch of a trochoid that keeps the engagement under a limit (seed 004 §2.2–2.3,
//! MODEL.md §2 and §7).
//!
//! Loop `k` of a trochoid runs round the circle of radius `ρ` about its centre, which lies a
//! pitch `p` ahead of the previous loop's centre. Everything within `W = ρ_prev + r` of the
//! previous centre has been swept; the material the tool meets on loop `k` is what lies
//! outside that disc. At loop angle `φ` the tool centre is `q = c_k + ρ(cos φ, sin φ)`, and
//! a direction `u` of the tool's edge is in material when `|q + r·u − c_prev| > W`, i.e. when
//! the angle between `u` and `v = q − c_prev` is below `acos((W² − |v|² − r²)/(2r|v|))`.
//! The engagement `α(φ)` is the part of that arc in the tool's leading half (the half facing
//! the direction of travel), the measure the analysis takes (MODEL.md §6); the loop's
//! engagement is its largest value over `φ`.
//!
//! This reproduces the simulation: `ρ = 1`, `r = 5`, `p = 0.5` (seed 004's 12 mm slot with
//! a 10 mm tool at the standard Rd) peaks at 64.9°, as the full simulation does. The pitch
//! for a limit is the largest `p` whose loop stays under it (bisection: the engagement grows
//! with the pitch).

use std::f64::consts::{PI, TAU};

/// Loop angles examined per turn when looking for the largest engagement.
pub const LOOP_ANGLE_STEPS: usize = 720;

/// Bisection steps when solving for the pitch (to the last bits of the pitch: the plans are
/// sensitive to it; a micrometre less pitch changed the slot box's path by 1.2 %).
const PITCH_BISECTION_STEPS: usize = 48;

/// Smallest pitch the planner writes, mm: below it a trochoid is a slot cut in tiny steps
/// and the region belongs to z-cut division (seed 004 §2.3).
pub const MIN_PITCH_MM: f64 = 0.01;

/// Length of the overlap of the arcs `[a0, a0 + la]` and `[b0, b0 + lb]` of a circle (rad,
/// lengths at most 2π).
fn arc_overlap_rad(a0: f64, la: f64, b0: f64, lb: f64) -> f64 {
    let s = (b0 - a0).rem_euclid(TAU);
    let overlap = |lo: f64, hi: f64| (hi.min(la) - lo.max(0.0)).max(0.0);
    overlap(s, s + lb) + overlap(s - TAU, s - TAU + lb)
}

/// Engagement (rad) of a tool of radius `r` whose centre is at `v` from the centre of a swept
/// disc of radius `w` (material outside it), travelling in the unit direction `t`.
pub fn engagement_outside_disc_rad(v: (f64, f64), t: (f64, f64), w_mm: f64, r_mm: f64) -> f64 {
    let d = v.0.hypot(v.1);
    if d <= f64::EPSILON {
        return if r_mm > w_mm { PI } else { 0.0 };
    }
    let kappa = material_arc_cosine(d, w_mm, r_mm);
    if kappa >= 1.0 {
        return 0.0;
    }
    let half = kappa.max(-1.0).acos();
    let a_v = v.1.atan2(v.0);
    let a_t = t.1.atan2(t.0);
    arc_overlap_rad(a_v - half, 2.0 * half, a_t - PI / 2.0, PI)
}

/// The cosine of the half-angle of the tool's edge that lies outside a swept disc of radius
/// `w_mm`, the tool's centre `d_mm` from the disc's centre (1 or more: none of it).
fn material_arc_cosine(d_mm: f64, w_mm: f64, r_mm: f64) -> f64 {
    (w_mm * w_mm - d_mm * d_mm - r_mm * r_mm) / (2.0 * r_mm * d_mm)
}

/// How much above cos(limit / 2) the cosine of a material arc must be for [`loop_exceeds`]
/// to pass over it unmeasured: far above the rounding of either.
const SHORT_ARC_MARGIN: f64 = 1e-9;

/// `(sin φ, cos φ)` of the [`LOOP_ANGLE_STEPS`] angles around a loop, computed once.
fn loop_angles() -> &'static [(f64, f64)] {
    static ANGLES: std::sync::OnceLock<Vec<(f64, f64)>> = std::sync::OnceLock::new();
    ANGLES.get_or_init(|| (0..LOOP_ANGLE_STEPS).map(|i| (TAU * i as f64 / LOOP_ANGLE_STEPS as f64).sin_cos()).collect())
}

/// The largest engagement (deg) on a loop of radius `rho_mm` whose centre lies `pitch_mm`
/// ahead of the previous loop's centre, that loop of radius `rho_prev_mm`, for a tool of
/// radius `r_mm` (the loops run counter-clockwise; a clockwise trochoid is its mirror image
/// and meets the same engagement).
pub fn loop_engagement_deg(rho_prev_mm: f64, rho_mm: f64, pitch_mm: f64, r_mm: f64) -> f64 {
    let w = rho_prev_mm + r_mm;
    let mut worst: f64 = 0.0;
    for &(s, c) in loop_angles() {
        let v = (pitch_mm + rho_mm * c, rho_mm * s);
        worst = worst.max(engagement_outside_disc_rad(v, (-s, c), w, r_mm));
    }
    worst.to_degrees()
}

/// Whether the loop of [`loop_engagement_deg`] engages more than `limit_deg` anywhere: the
/// same angles, but an angle whose material arc is no longer than the limit is passed over
/// without measuring its leading half, and the first angle above the limit answers.
pub fn loop_exceeds(rho_prev_mm: f64, rho_mm: f64, pitch_mm: f64, r_mm: f64, limit_deg: f64) -> bool {
    let w = rho_prev_mm + r_mm;
    if limit_deg >= 180.0 {
        return false;
    }
    // The engagement is part of the material arc, 2·acos(κ): below the limit when κ is above
    // cos(limit / 2), raised a little so that an angle at the limit itself is measured.
    let short_arc = (0.5 * limit_deg.to_radians()).cos() + SHORT_ARC_MARGIN;
    loop_angles().iter().any(|&(s, c)| {
        let v = (pitch_mm + rho_mm * c, rho_mm * s);
        let d = (v.0 * v.0 + v.1 * v.1).sqrt();
        if d > f64::EPSILON && material_arc_cosine(d, w, r_mm) >= short_arc {
            return false;
        }
        engagement_outside_disc_rad(v, (-s, c), w, r_mm).to_degrees() > limit_deg
    })
}

/// The largest pitch in `(0, max_pitch_mm]` whose loop (radius `rho(p)` at that pitch, after
/// a loop of radius `rho_prev_mm`) stays at or under `alpha_limit_deg`; `None` when even
/// [`MIN_PITCH_MM`] does not.
pub fn pitch_for_limit(
    rho_prev_mm: f64,
    rho_at: impl Fn(f64) -> f64,
    r_mm: f64,
    alpha_limit_deg: f64,
    max_pitch_mm: f64,
) -> Option<f64> {
    let fits = |p: f64| !loop_exceeds(rho_prev_mm, rho_at(p), p, r_mm, alpha_limit_deg);
    if fits(max_pitch_mm) {
        return Some(max_pitch_mm);
    }
    if max_pitch_mm <= MIN_PITCH_MM || !fits(MIN_PITCH_MM) {
        return None;
    }
    let (mut lo, mut hi) = (MIN_PITCH_MM, max_pitch_mm);
    for _ in 0..PITCH_BISECTION_STEPS {
        let mid = 0.5 * (lo + hi);
        if fits(mid) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    Some(lo)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::core::tolerance::approx_eq;

    #[test]
    fn seed_004s_slot_trochoid_at_the_standard_rd_peaks_at_65_degrees() {
        // 12 mm slot, 10 mm tool: ρ = 1 mm, p = Rd = 0.5 mm (MODEL.md §7).
        let alpha = loop_engagement_deg(1.0, 1.0, 0.5, 5.0);
        assert!(approx_eq(alpha, 64.9, 0.3), "{alpha}");
    }

    #[test]
    fn larger_loops_and_smaller_pitches_engage_less() {
        assert!(loop_engagement_deg(5.0, 5.0, 0.5, 5.0) < loop_engagement_deg(2.0, 2.0, 0.5, 5.0));
        assert!(loop_engagement_deg(1.0, 1.0, 0.2, 5.0) < loop_engagement_deg(1.0, 1.0, 0.5, 5.0));
        assert!(approx_eq(loop_engagement_deg(1.0, 1.0, 0.0, 5.0), 0.0, 1e-9));
    }

    #[test]
    fn the_pitch_for_40_degrees_in_a_12_mm_slot_is_about_a_quarter_millimetre() {
        let p = pitch_for_limit(1.0, |_| 1.0, 5.0, 40.0, 0.5).unwrap();
        assert!(p > 0.15 && p < 0.3, "{p}");
        assert!(loop_engagement_deg(1.0, 1.0, p, 5.0) <= 40.0 + 1e-9);
        assert!(loop_engagement_deg(1.0, 1.0, p * 1.05, 5.0) > 40.0);
    }

    #[test]
    fn at_the_design_limit_of_39_degrees_a_12_mm_slot_takes_0_19_mm_and_loops_of_the_tool_radius_0_57_mm() {
        let most = 5.0 * (1.0 - 40f64.to_radians().cos());
        let slot = pitch_for_limit(1.0, |_| 1.0, 5.0, 39.0, most).unwrap();
        let wide = pitch_for_limit(5.0, |_| 5.0, 5.0, 39.0, most).unwrap();
        assert!(approx_eq(slot, 0.19, 0.01) && approx_eq(wide, 0.57, 0.01), "{slot} {wide}");
    }

    #[test]
    fn a_loop_that_meets_the_limit_at_the_requested_pitch_keeps_it() {
        assert!(approx_eq(pitch_for_limit(5.0, |_| 5.0, 5.0, 40.0, 0.5).unwrap(), 0.5, 0.0));
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig::with_cases(48))]
        #[test]
        fn the_pitch_found_keeps_the_loop_under_the_limit_and_is_the_largest_that_does(
            rho in 0.5f64..5.0, limit in 25.0f64..70.0, max_p in 0.1f64..1.0
        ) {
            if let Some(p) = pitch_for_limit(rho, |_| rho, 5.0, limit, max_p) {
                proptest::prop_assert!(p <= max_p && loop_engagement_deg(rho, rho, p, 5.0) <= limit);
                if p < max_p {
                    proptest::prop_assert!(loop_engagement_deg(rho, rho, (p * 1.01).min(max_p), 5.0) > limit - 0.5);
                }
            }
        }
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig::with_cases(256))]
        #[test]
        fn a_loop_exceeds_a_limit_exactly_when_its_largest_engagement_is_above_it(
            rho_prev in 0.2f64..6.0, rho in 0.2f64..6.0, pitch in 0.0f64..3.0, limit in 5.0f64..175.0
        ) {
            let worst = loop_engagement_deg(rho_prev, rho, pitch, 5.0);
            proptest::prop_assert_eq!(loop_exceeds(rho_prev, rho, pitch, 5.0, limit), worst > limit);
        }
    }

    #[test]
    fn a_loop_far_too_small_for_the_limit_has_no_pitch() {
        assert_eq!(pitch_for_limit(0.001, |_| 0.001, 5.0, 5.0, 0.5), None);
    }

    #[test]
    fn a_straight_tool_in_a_straight_cut_engages_as_the_engagement_formula_says() {
        // A tool inside a swept disc of radius W, its edge Rd beyond the disc, moving
        // tangentially: a straight cut of depth Rd when the disc is large.
        let (w, r, rd) = (1e6, 5.0, 0.5);
        let alpha = engagement_outside_disc_rad((w - r + rd, 0.0), (0.0, 1.0), w, r).to_degrees();
        let expected = (1.0 - rd / r).acos().to_degrees();
        assert!(approx_eq(alpha, expected, 0.01), "{alpha} vs {expected}");
    }
}
