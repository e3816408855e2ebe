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
//! for a limit is the largest `p` whose loop stays under it (the engagement grows with the
//! pitch), found by Brent's method on the loop's peak engagement less the limit.

use crate::core::zero_crossing::zero_crossing;
use std::f64::consts::{PI, TAU};

/// Loop angles examined per turn when looking for the largest engagement.
pub const LOOP_ANGLE_STEPS: usize = 720;

/// Smallest pitch the planner writes, mm: below it a trochoid is a slot cut in tiny steps
/// and the region belongs to z-cut division (seed 004 §2.3).
pub const MIN_PITCH_MM: f64 = 0.01;

/// Length of the overlap of the arcs `[−a, a]` and `[δ − b, δ + b]` of a circle (rad; half
/// lengths `a`, `b` at most π, centres `δ` apart, `0 ≤ δ ≤ π`): the second arc may also reach
/// the first round the far side, at `δ − 2π`.
fn centred_arc_overlap_rad(a: f64, b: f64, delta: f64) -> f64 {
    let overlap = |centre: f64| (a.min(centre + b) - (-a).max(centre - b)).max(0.0);
    overlap(delta) + overlap(delta - TAU)
}

/// Engagement (rad) of a tool of radius `r` whose centre is at `v` from the centre of a swept
/// disc of radius `w` (material outside it), travelling in the unit direction `t`.
pub fn engagement_outside_disc_rad(v: (f64, f64), t: (f64, f64), w_mm: f64, r_mm: f64) -> f64 {
    engagement_at_rad(v, (v.0 * v.0 + v.1 * v.1).sqrt(), t, w_mm, r_mm)
}

/// [`engagement_outside_disc_rad`] with `d_mm = |v|`: the material arc, centred on `v`, met
/// with the leading half of the tool, centred on `t`; the angle between the two from one
/// `atan2` of their cross and dot products (exact near 0 and π, where an `acos` is not).
fn engagement_at_rad(v: (f64, f64), d_mm: f64, t: (f64, f64), w_mm: f64, r_mm: f64) -> f64 {
    if d_mm <= f64::EPSILON {
        return if r_mm > w_mm { PI } else { 0.0 };
    }
    let kappa = material_arc_cosine(d_mm, w_mm, r_mm);
    if kappa >= 1.0 {
        return 0.0;
    }
    let half = kappa.max(-1.0).acos();
    let delta = (v.0 * t.1 - v.1 * t.0).abs().atan2(v.0 * t.0 + v.1 * t.1);
    centred_arc_overlap_rad(half, PI / 2.0, delta)
}

/// The cosine of the half-angle of the tool's edge that lies outside a swept disc of radius
/// `w_mm`, the tool's centre `d_mm` from the disc's centre (1 or more: none of it).
fn material_arc_cosine(d_mm: f64, w_mm: f64, r_mm: f64) -> f64 {
    (w_mm * w_mm - d_mm * d_mm - r_mm * r_mm) / (2.0 * r_mm * d_mm)
}

/// How much above the cosine of half the peak so far the cosine of a material arc must be for
/// [`loop_peak_deg`] to pass over it unmeasured: far above the rounding of either.
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

/// Whether the loop of [`loop_engagement_deg`] engages more than `limit_deg` anywhere: its
/// peak, found passing over the angles that cannot raise it ([`loop_peak_deg`]).
pub fn loop_exceeds(rho_prev_mm: f64, rho_mm: f64, pitch_mm: f64, r_mm: f64, limit_deg: f64) -> bool {
    limit_deg < 180.0 && loop_peak_deg(rho_prev_mm, rho_mm, pitch_mm, r_mm, &mut 0) > limit_deg
}

/// The loop angles (indices `lo..hi` of [`loop_angles`]) whose material arc is certainly no
/// longer than the cosine `short_arc` says, so [`loop_peak_deg`] passes over each of them.
///
/// The arc's cosine `κ(d) = (w² − r² − d²)/(2rd)` falls as the distance `d` of the tool
/// centre from the previous loop's centre grows, and `d² = p² + ρ² + 2pρ·cos φ` grows with
/// `cos φ`: the short arcs are the angles whose cosine is at most one bound, one range of
/// indices about φ = π. The range is narrowed by [`SHORT_ARC_INDEX_MARGIN`] steps at both
/// ends, so that no rounding can pass over an angle the measure would take; an empty range
/// when `κ` does not fall with `d` or the loop does not move.
fn short_arc_indices(rho_mm: f64, pitch_mm: f64, w_mm: f64, r_mm: f64, short_arc: f64) -> (usize, usize) {
    let a = w_mm * w_mm - r_mm * r_mm;
    let spread = 2.0 * pitch_mm * rho_mm;
    if a <= 0.0 || spread <= f64::EPSILON || !short_arc.is_finite() {
        return (0, 0);
    }
    // κ(d*) = short_arc: d*² + 2r·short_arc·d* − a = 0.
    let rs = r_mm * short_arc;
    let d_star = -rs + (rs * rs + a).sqrt();
    if d_star <= 0.0 {
        return (0, 0);
    }
    let cos_bound = (d_star * d_star - pitch_mm * pitch_mm - rho_mm * rho_mm) / spread;
    if cos_bound < -1.0 {
        return (0, 0);
    }
    let step = TAU / LOOP_ANGLE_STEPS as f64;
    let from = (cos_bound.min(1.0).acos() / step).floor() as usize + SHORT_ARC_INDEX_MARGIN;
    let to = (LOOP_ANGLE_STEPS + 1).saturating_sub(from);
    if from >= to {
        return (0, 0);
    }
    (from, to)
}

/// Loop angle steps by which [`short_arc_indices`] narrows its range at each end: one step
/// changes the cosine by far more than any rounding of `d`.
const SHORT_ARC_INDEX_MARGIN: usize = 2;

/// The largest engagement (deg) of the loop of [`loop_engagement_deg`], found without
/// measuring the angles that cannot raise it: the scan starts at loop angle `*hint` (the
/// index of [`loop_angles`] where the last loop of a search peaked, left where this one
/// peaks), and an angle whose material arc is no longer than the largest engagement so far
/// is passed over, a range of them about φ = π without a distance ([`short_arc_indices`]).
fn loop_peak_deg(rho_prev_mm: f64, rho_mm: f64, pitch_mm: f64, r_mm: f64, hint: &mut usize) -> f64 {
    let w = rho_prev_mm + r_mm;
    let angles = loop_angles();
    let at = |i: usize| {
        let (s, c) = angles[i];
        ((pitch_mm + rho_mm * c, rho_mm * s), (-s, c))
    };
    let (v, t) = at(*hint);
    let mut peak = engagement_outside_disc_rad(v, t, w, r_mm);
    // Material arcs whose cosine is at least this are no longer than the peak.
    let shorter = |peak: f64| (0.5 * peak).cos() + SHORT_ARC_MARGIN;
    let mut short_arc = shorter(peak);
    let (lo, hi) = short_arc_indices(rho_mm, pitch_mm, w, r_mm, short_arc);
    for i in (0..lo).chain(hi..LOOP_ANGLE_STEPS) {
        let (v, t) = at(i);
        let d = (v.0 * v.0 + v.1 * v.1).sqrt();
        if d > f64::EPSILON && material_arc_cosine(d, w, r_mm) >= short_arc {
            continue;
        }
        let alpha = engagement_at_rad(v, d, t, w, r_mm);
        if alpha > peak {
            (peak, *hint) = (alpha, i);
            short_arc = shorter(peak);
        }
    }
    peak.to_degrees()
}

/// How close the pitch search brackets the largest pitch that fits, mm: the last bits of a
/// pitch, as close as the 48 bisection steps it replaced came (the plans are sensitive to
/// it: a micrometre less pitch changed the slot box's path by 1.2 %, and pitches 5e-14 mm
/// shorter moved the README plan's kinematic time by 1 %).
const PITCH_TOLERANCE_MM: f64 = 4e-15;

/// The largest pitch in `(0, max_pitch_mm]` whose loop (radius `rho(p)` at that pitch, after
/// a loop of radius `rho_prev_mm`) stays at or under `alpha_limit_deg`; `None` when even
/// [`MIN_PITCH_MM`] does not. The loop's peak engagement less the limit is brought to zero by
/// Brent's method ([`zero_crossing`]), keeping the side that fits.
pub fn pitch_for_limit(
    rho_prev_mm: f64,
    rho_at: impl Fn(f64) -> f64,
    r_mm: f64,
    alpha_limit_deg: f64,
    max_pitch_mm: f64,
) -> Option<f64> {
    pitch_for_limit_remembering(rho_prev_mm, rho_at, r_mm, alpha_limit_deg, max_pitch_mm, &mut PeakMemo::default())
}

/// [`pitch_for_limit`], taking the peaks of loops found before from `memo` and leaving the
/// new ones there.
pub fn pitch_for_limit_remembering(
    rho_prev_mm: f64,
    rho_at: impl Fn(f64) -> f64,
    r_mm: f64,
    alpha_limit_deg: f64,
    max_pitch_mm: f64,
    memo: &mut PeakMemo,
) -> Option<f64> {
    if alpha_limit_deg >= 180.0 {
        return Some(max_pitch_mm);
    }
    let mut over = |p: f64| memo.peak_deg(rho_prev_mm, rho_at(p), p, r_mm) - alpha_limit_deg;
    let over_max = over(max_pitch_mm);
    if over_max <= 0.0 {
        return Some(max_pitch_mm);
    }
    if max_pitch_mm <= MIN_PITCH_MM {
        return None;
    }
    let over_min = over(MIN_PITCH_MM);
    if over_min > 0.0 {
        return None;
    }
    Some(zero_crossing(MIN_PITCH_MM, over_min, max_pitch_mm, over_max, PITCH_TOLERANCE_MM, over).at_most_zero)
}

/// Most loop peaks a [`PeakMemo`] keeps; past them it starts afresh (**assumed**: a loop's
/// search evaluates a few dozen pitches, and equal loops need only the last loop's; 4096
/// entries take about 200 kB, where a trochoid of ever new loops would otherwise fill the
/// map without bound).
pub const MAX_REMEMBERED_PEAKS: usize = 1 << 12;

/// The peak engagements found for loops (by the bits of the previous loop's radius, the
/// loop's radius, the pitch and the tool's radius). A trochoid of equal loops (a slot of
/// even width) searches the same pitches loop after loop: each peak is then found once. A
/// peak does not depend on where its search started, so a remembered one is the one the
/// search would find.
#[derive(Debug, Default)]
pub struct PeakMemo {
    peaks: rustc_hash::FxHashMap<[u64; 4], f64>,
    /// Where the last search peaked (see [`loop_peak_deg`]).
    hint: usize,
}

impl PeakMemo {
    /// The peak (deg) of [`loop_engagement_deg`] for these loops, remembered or found.
    fn peak_deg(&mut self, rho_prev_mm: f64, rho_mm: f64, pitch_mm: f64, r_mm: f64) -> f64 {
        let key = [rho_prev_mm.to_bits(), rho_mm.to_bits(), pitch_mm.to_bits(), r_mm.to_bits()];
        if let Some(&peak) = self.peaks.get(&key) {
            return peak;
        }
        let peak = loop_peak_deg(rho_prev_mm, rho_mm, pitch_mm, r_mm, &mut self.hint);
        if self.peaks.len() >= MAX_REMEMBERED_PEAKS {
            self.peaks.clear();
        }
        self.peaks.insert(key, peak);
        peak
    }
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
    fn pitches_found_with_remembered_peaks_are_the_pitches_found_afresh() {
        let mut memo = PeakMemo::default();
        // Equal loops, then loops growing with the pitch, then equal loops again.
        for (k, rho) in [1.0, 1.0, 1.0, 1.2, 1.5, 1.0, 1.0].into_iter().enumerate() {
            let grow = if k == 4 { 0.3 } else { 0.0 };
            let remembered = pitch_for_limit_remembering(rho, |p| rho + grow * p, 5.0, 38.0, 0.5, &mut memo);
            let afresh = pitch_for_limit(rho, |p| rho + grow * p, 5.0, 38.0, 0.5);
            assert_eq!(remembered.map(f64::to_bits), afresh.map(f64::to_bits), "loop {k}");
        }
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
        fn the_peak_found_passing_over_short_arcs_is_the_largest_engagement_of_every_angle(
            rho_prev in 0.2f64..6.0, rho in 0.2f64..6.0, pitch in 0.0f64..2.0, hint in 0usize..LOOP_ANGLE_STEPS
        ) {
            let mut at = hint;
            let peak = loop_peak_deg(rho_prev, rho, pitch, 5.0, &mut at);
            let every = loop_engagement_deg(rho_prev, rho, pitch, 5.0);
            proptest::prop_assert!((peak - every).abs() <= 1e-9, "{} against {}", peak, every);
        }
    }

    /// The engagement counted edge direction by edge direction: those outside the swept disc
    /// and in the leading half, `n` of them round the tool.
    fn counted_engagement_rad(v: (f64, f64), t: (f64, f64), w: f64, r: f64, n: usize) -> f64 {
        let step = TAU / n as f64;
        let inside = (0..n)
            .map(|k| (k as f64 + 0.5) * step)
            .filter(|&a| {
                let u = (a.cos(), a.sin());
                let edge = (v.0 + r * u.0, v.1 + r * u.1);
                edge.0.hypot(edge.1) > w && u.0 * t.0 + u.1 * t.1 > 0.0
            })
            .count();
        inside as f64 * step
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig::with_cases(256))]
        #[test]
        fn the_engagement_outside_a_disc_is_the_edge_in_material_and_in_the_leading_half(
            x in -12.0f64..12.0, y in -12.0f64..12.0, heading in 0.0f64..TAU, w in 0.5f64..10.0
        ) {
            let t = (heading.cos(), heading.sin());
            let exact = engagement_outside_disc_rad((x, y), t, w, 5.0);
            let counted = counted_engagement_rad((x, y), t, w, 5.0, 20_000);
            proptest::prop_assert!((exact - counted).abs() <= 4.0 * TAU / 20_000.0, "{exact} {counted}");
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
