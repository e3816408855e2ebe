//! Engagement geometry of 2.5-D side milling (MODEL.md §2, from seed 002 Fig. 4 and
//! seed 003): engagement angle, engagement arc length, feed at the cutting point and
//! maximum undeformed chip thickness.
//!
//! Lengths are in mm, angles in radians (the API converts to degrees).

use crate::core::error::require_positive;
use crate::core::CoreError;
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

/// The shape of the machined surface at the cutting point.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum Contour {
    /// A straight cut.
    Straight,
    /// An inner (concave) arc of machined-surface radius `R` > tool radius.
    Concave { surface_radius_mm: f64 },
    /// An outer (convex) arc of machined-surface radius `R`.
    Convex { surface_radius_mm: f64 },
}

/// The engagement of the tool at one point.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Engagement {
    /// Engagement angle α (rad), 0..=π.
    pub angle_rad: f64,
    /// Engagement arc length `L = r·α` (mm).
    pub arc_length_mm: f64,
    /// `fz_p / fz_c`: feed per tooth at the cutting point over feed per tooth at the
    /// tool centre (1 on a straight cut).
    pub cutting_point_feed_ratio: f64,
}

/// Engagement angle of a straight cut, `α = acos(1 − Rd/r)` (MODEL.md §2).
/// A radial depth of a full diameter or more is a full slot, α = π.
pub fn straight_engagement_angle_rad(radial_depth_mm: f64, tool_radius_mm: f64) -> f64 {
    let cos_alpha = 1.0 - radial_depth_mm / tool_radius_mm;
    cos_alpha.clamp(-1.0, 1.0).acos()
}

/// Engagement angle on a concave arc (MODEL.md §2, seed 002 Fig. 4):
/// `cos α = ((R − Rd)² − Rc² − r²) / (2·Rc·r)` with `Rc = R − r`.
pub fn concave_engagement_angle_rad(surface_radius_mm: f64, radial_depth_mm: f64, tool_radius_mm: f64) -> f64 {
    let centre_radius = surface_radius_mm - tool_radius_mm;
    let previous = surface_radius_mm - radial_depth_mm;
    let cos_alpha = (previous * previous - centre_radius * centre_radius - tool_radius_mm * tool_radius_mm)
        / (2.0 * centre_radius * tool_radius_mm);
    cos_alpha.clamp(-1.0, 1.0).acos()
}

/// Engagement angle on a convex arc (MODEL.md §2):
/// `cos α = ((R + Rd)² − Rc² − r²) / (−2·Rc·r)` with `Rc = R + r`.
pub fn convex_engagement_angle_rad(surface_radius_mm: f64, radial_depth_mm: f64, tool_radius_mm: f64) -> f64 {
    let centre_radius = surface_radius_mm + tool_radius_mm;
    let previous = surface_radius_mm + radial_depth_mm;
    let cos_alpha = (previous * previous - centre_radius * centre_radius - tool_radius_mm * tool_radius_mm)
        / (-2.0 * centre_radius * tool_radius_mm);
    cos_alpha.clamp(-1.0, 1.0).acos()
}

/// Feed-per-tooth ratio at the cutting point, `fz_p / fz_c = |PO| / Rc` (MODEL.md §2;
/// seed 000 Eq. 1 read per tooth). Concave: `|PO| = Rc + r = R`; convex: `|PO| = Rc − r = R`.
pub fn cutting_point_feed_ratio(contour: Contour, tool_radius_mm: f64) -> f64 {
    match contour {
        Contour::Straight => 1.0,
        Contour::Concave { surface_radius_mm } => surface_radius_mm / (surface_radius_mm - tool_radius_mm),
        Contour::Convex { surface_radius_mm } => surface_radius_mm / (surface_radius_mm + tool_radius_mm),
    }
}

/// Maximum undeformed chip thickness of a down cut (MODEL.md §2):
/// `t_m = fz_p·sin α` for α ≤ 90°, else `t_m = fz_p` (mm, as `fz_p`).
pub fn max_chip_thickness_mm(cutting_point_fz_mm: f64, engagement_angle_rad: f64) -> f64 {
    if engagement_angle_rad <= PI / 2.0 {
        cutting_point_fz_mm * engagement_angle_rad.sin()
    } else {
        cutting_point_fz_mm
    }
}

/// The tightest concave surface a tool follows, as `R/r` (seed 004 §2.2: "trochoid cycles
/// was subject to an excessive tool load when R/r < 1.1", the z-cut-division class C). A
/// tool-centre path that turns tighter than `Rc = (1.1 − 1)·r` no longer follows a
/// machined surface: the tool pivots about a point near its own centre.
pub const PIVOT_SURFACE_RATIO: f64 = 1.1;

/// The centre-path radius the cutting-point correction is computed at: the path's own
/// radius `Rc`, or the pivot radius `(1.1 − 1)·r` where the path turns tighter (a pivot,
/// see [`PIVOT_SURFACE_RATIO`]), mm. This bounds `|PO|/Rc` at `1.1 / 0.1 = 11` on the
/// concave side, where the papers' correction (MODEL.md §2, seed 000 Eq. 1) would grow
/// without bound as `Rc → 0`.
pub fn pivot_bounded_centre_radius_mm(centre_radius_mm: f64, tool_radius_mm: f64) -> f64 {
    centre_radius_mm.max((PIVOT_SURFACE_RATIO - 1.0) * tool_radius_mm)
}

/// Chord between two successive tooth passes at the cutting point, mm: the cutting point
/// turns about the centre of curvature `O` by `Δθ = fz_c / Rc` per tooth on a circle of
/// radius `|PO| = ratio · Rc`, so its passes are `2·|PO|·sin(Δθ/2)` apart (at most the
/// circle's diameter). Equal to `fz_p = fz_c · |PO| / Rc` (MODEL.md §2) to first order;
/// shorter where a tooth turns the tool a large angle (`fz_c` comparable to `Rc`). On a
/// straight path (`Rc` infinite) it is `fz_c · ratio`.
pub fn tooth_pass_chord_mm(centre_fz_mm: f64, cutting_point_ratio: f64, centre_radius_mm: f64) -> f64 {
    let fz_p = centre_fz_mm * cutting_point_ratio;
    if !centre_radius_mm.is_finite() || centre_radius_mm <= 0.0 {
        return fz_p;
    }
    let turn_rad = (centre_fz_mm / centre_radius_mm).min(PI);
    if turn_rad < SMALL_TURN_RAD {
        // 2·sin(Δθ/2) = Δθ·(1 − Δθ²/24 + …), the rest below 10⁻¹³ here.
        return fz_p * (1.0 - turn_rad * turn_rad / 24.0);
    }
    let po = cutting_point_ratio * centre_radius_mm;
    (2.0 * po * (turn_rad / 2.0).sin()).min(fz_p)
}

/// Below this turn per tooth the chord of [`tooth_pass_chord_mm`] is taken from its
/// series (no sine on the simulation's hot path), rad.
const SMALL_TURN_RAD: f64 = 1e-3;
/// `1 − cos α ≥ α²/2 − α⁴/24 ≥ (1/2 − (π/2)²/24)·α²` for α ≤ π/2: a lower bound of the
/// engaged depth that needs no cosine.
const ENGAGED_DEPTH_LOWER_FACTOR: f64 = 0.5 - PI * PI / 4.0 / 24.0;

/// Depth of material a tooth engaging `α` reaches from its edge, mm: the radial depth of
/// the straight cut of the same engagement, `Rd = r·(1 − cos α)` (MODEL.md §2, inverted);
/// a full slot (α = π) reaches the diameter.
pub fn engaged_depth_mm(tool_radius_mm: f64, engagement_angle_rad: f64) -> f64 {
    tool_radius_mm * (1.0 - engagement_angle_rad.clamp(0.0, PI).cos())
}

/// Where one tooth cuts: what bounds its chip besides the feed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ToothCut {
    /// Engagement angle α, rad.
    pub alpha_rad: f64,
    /// `fz_p / fz_c` at the cutting point (pivot-bounded, see
    /// [`pivot_bounded_centre_radius_mm`]).
    pub cutting_point_ratio: f64,
    /// Curvature radius of the tool-centre path (pivot-bounded), mm; infinite on a
    /// straight path.
    pub centre_radius_mm: f64,
    pub tool_radius_mm: f64,
}

/// Maximum undeformed chip thickness of one tooth at centre feed per tooth `fz_c`, mm:
/// `t_m = fz_p·sin α` (α ≤ 90°) or `fz_p` (MODEL.md §2), never more than the material
/// between successive tooth paths, i.e. the chord between the tooth's passes at the
/// cutting point ([`tooth_pass_chord_mm`]) and the depth of material it engages
/// ([`engaged_depth_mm`]).
pub fn tooth_chip_thickness_mm(centre_fz_mm: f64, cut: &ToothCut) -> f64 {
    let nominal = max_chip_thickness_mm(centre_fz_mm * cut.cutting_point_ratio, cut.alpha_rad);
    let t = nominal.min(tooth_pass_chord_mm(centre_fz_mm, cut.cutting_point_ratio, cut.centre_radius_mm));
    // The depth bound only where it can bite (it never does on the papers' cuts).
    let (r, alpha) = (cut.tool_radius_mm, cut.alpha_rad);
    let surely_deeper = if alpha >= PI / 2.0 { r } else { ENGAGED_DEPTH_LOWER_FACTOR * r * alpha * alpha };
    if t <= surely_deeper {
        t
    } else {
        t.min(engaged_depth_mm(r, alpha))
    }
}

/// Engagement arc length `L = r·α` (MODEL.md §2), mm.
pub fn engagement_arc_length_mm(tool_radius_mm: f64, engagement_angle_rad: f64) -> f64 {
    tool_radius_mm * engagement_angle_rad
}

/// The full engagement of a tool of radius `r` cutting `contour` at radial depth `Rd`.
pub fn engagement(contour: Contour, tool_radius_mm: f64, radial_depth_mm: f64) -> Result<Engagement, CoreError> {
    let r = require_positive("tool_radius_mm", tool_radius_mm)?;
    let rd = require_positive("rd_mm", radial_depth_mm)?;
    let angle_rad = match contour {
        Contour::Straight => straight_engagement_angle_rad(rd, r),
        Contour::Concave { surface_radius_mm } => {
            let big_r = require_positive("surface_radius_mm", surface_radius_mm)?;
            if big_r <= r {
                return Err(CoreError::invalid(
                    "surface_radius_mm",
                    format!("a concave surface of radius {big_r} mm cannot be cut by a tool of radius {r} mm"),
                ));
            }
            concave_engagement_angle_rad(big_r, rd, r)
        }
        Contour::Convex { surface_radius_mm } => {
            let big_r = require_positive("surface_radius_mm", surface_radius_mm)?;
            convex_engagement_angle_rad(big_r, rd, r)
        }
    };
    Ok(Engagement {
        angle_rad,
        arc_length_mm: engagement_arc_length_mm(r, angle_rad),
        cutting_point_feed_ratio: cutting_point_feed_ratio(contour, r),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::core::tolerance::approx_eq;

    fn deg(rad: f64) -> f64 {
        rad.to_degrees()
    }

    #[test]
    fn standard_conditions_give_the_chip_thickness_and_arc_length_of_seed_001_table_2() {
        // (D, Rd, fz, t_m µm, L mm) — MODEL.md §2 check numbers.
        for (d, rd, fz, t_um, l_mm) in
            [(6.0, 0.3, 0.04, 17.4, 1.35), (8.0, 0.4, 0.07, 30.5, 1.80), (10.0, 0.5, 0.10, 43.6, 2.26)]
        {
            let e = engagement(Contour::Straight, d / 2.0, rd).unwrap();
            let t_m = max_chip_thickness_mm(fz * e.cutting_point_feed_ratio, e.angle_rad) * 1000.0;
            assert!(approx_eq(t_m, t_um, 0.05), "D{d}: t_m {t_m}");
            assert!(approx_eq(e.arc_length_mm, l_mm, 0.005), "D{d}: L {}", e.arc_length_mm);
        }
    }

    #[test]
    fn the_10_mm_standard_straight_cut_engages_25_8_degrees() {
        let e = engagement(Contour::Straight, 5.0, 0.5).unwrap();
        assert!(approx_eq(deg(e.angle_rad), 25.84, 0.01));
    }

    #[test]
    fn concave_arcs_give_the_angles_and_lengths_of_model_section_3() {
        // R/r, α deg, L mm for the 10 mm tool at Rd 0.5.
        for (ratio, alpha, l) in
            [(3.0, 31.5, 2.75), (2.0, 36.4, 3.18), (1.6, 42.1, 3.68), (1.3, 54.3, 4.74), (1.2, 64.8, 5.66)]
        {
            let e = engagement(Contour::Concave { surface_radius_mm: 5.0 * ratio }, 5.0, 0.5).unwrap();
            assert!(approx_eq(deg(e.angle_rad), alpha, 0.05), "R/r {ratio}: α {}", deg(e.angle_rad));
            assert!(approx_eq(e.arc_length_mm, l, 0.01), "R/r {ratio}: L {}", e.arc_length_mm);
        }
    }

    #[test]
    fn convex_and_concave_arcs_tend_to_the_straight_cut_as_the_radius_grows() {
        let straight = straight_engagement_angle_rad(0.5, 5.0);
        let concave = concave_engagement_angle_rad(1e6, 0.5, 5.0);
        let convex = convex_engagement_angle_rad(1e6, 0.5, 5.0);
        assert!(approx_eq(concave, straight, 1e-5));
        assert!(approx_eq(convex, straight, 1e-5));
        assert!(convex_engagement_angle_rad(10.0, 0.5, 5.0) < straight);
        assert!(concave_engagement_angle_rad(10.0, 0.5, 5.0) > straight);
    }

    #[test]
    fn a_full_slot_engages_half_the_tool() {
        assert!(approx_eq(straight_engagement_angle_rad(10.0, 5.0), PI, 1e-12));
        assert!(approx_eq(straight_engagement_angle_rad(25.0, 5.0), PI, 1e-12));
    }

    #[test]
    fn past_ninety_degrees_the_chip_is_as_thick_as_the_feed_per_tooth() {
        assert!(approx_eq(max_chip_thickness_mm(0.1, 2.0), 0.1, 1e-15));
        assert!(approx_eq(max_chip_thickness_mm(0.1, PI / 6.0), 0.05, 1e-12));
    }

    #[test]
    fn a_concave_surface_tighter_than_the_tool_is_refused_naming_the_field() {
        let err = engagement(Contour::Concave { surface_radius_mm: 4.0 }, 5.0, 0.5).unwrap_err();
        assert!(matches!(err, CoreError::InvalidInput { ref field, .. } if field == "surface_radius_mm"));
    }

    #[test]
    fn a_centre_path_turning_at_0_3_mm_bounds_the_correction_at_the_pivot_radius() {
        // 10 mm tool: the pivot radius is 0.1 r = 0.5 mm, so |PO|/Rc is at most 11
        // instead of 5.3 / 0.3 = 17.7.
        let rc = pivot_bounded_centre_radius_mm(0.3, 5.0);
        assert!(approx_eq(rc, 0.5, 1e-12));
        assert!(approx_eq((rc + 5.0) / rc, 11.0, 1e-12));
        // Surfaces the tool follows keep the papers' correction (MODEL.md §3's R/r 1.3).
        assert!(approx_eq(pivot_bounded_centre_radius_mm(1.5, 5.0), 1.5, 1e-12));
    }

    #[test]
    fn a_chip_is_never_thicker_than_the_material_between_successive_tooth_paths() {
        // A light straight cut (α 8.1°, Rd 0.05 mm) at an absurd 2 mm per tooth: the
        // papers' formula gives 0.28 mm; the tooth meets only 0.05 mm of material.
        let alpha = straight_engagement_angle_rad(0.05, 5.0);
        let cut = ToothCut {
            alpha_rad: alpha,
            cutting_point_ratio: 1.0,
            centre_radius_mm: f64::INFINITY,
            tool_radius_mm: 5.0,
        };
        assert!(max_chip_thickness_mm(2.0, alpha) > 0.28);
        assert!(approx_eq(tooth_chip_thickness_mm(2.0, &cut), 0.05, 1e-9));
        // A full slot at 173 mm per tooth (F9991300 at S9600, z 6) cuts at most the diameter.
        let slot = ToothCut { alpha_rad: PI, ..cut };
        assert!(approx_eq(tooth_chip_thickness_mm(173.0, &slot), 10.0, 1e-9));
        // The standard cut is untouched: 43.6 µm (seed 001 Table 2).
        let standard = ToothCut { alpha_rad: straight_engagement_angle_rad(0.5, 5.0), ..cut };
        assert!(approx_eq(tooth_chip_thickness_mm(0.1, &standard) * 1000.0, 43.6, 0.05));
    }

    #[test]
    fn a_tooth_that_turns_the_tool_half_round_advances_the_chord_not_the_arc() {
        // Rc 0.5 mm, |PO| = 5.5 mm: at fz_c = 0.01 the chord is the arc, fz_p = 0.11;
        // at fz_c = 2 mm a tooth turns the tool by 4 rad: at most the diameter 2·|PO|.
        assert!(approx_eq(tooth_pass_chord_mm(0.01, 11.0, 0.5), 0.11, 1e-5));
        assert!(tooth_pass_chord_mm(2.0, 11.0, 0.5) <= 11.0 + 1e-12);
        assert!(approx_eq(tooth_pass_chord_mm(0.1, 1.0, f64::INFINITY), 0.1, 1e-15));
    }

    #[test]
    fn the_engaged_depth_is_the_radial_depth_of_the_same_straight_cut() {
        assert!(approx_eq(engaged_depth_mm(5.0, straight_engagement_angle_rad(0.5, 5.0)), 0.5, 1e-12));
        assert!(approx_eq(engaged_depth_mm(5.0, PI), 10.0, 1e-12));
    }

    #[test]
    fn the_cutting_point_moves_slower_inside_and_faster_outside() {
        assert!(approx_eq(cutting_point_feed_ratio(Contour::Concave { surface_radius_mm: 10.0 }, 5.0), 2.0, 1e-12));
        assert!(approx_eq(
            cutting_point_feed_ratio(Contour::Convex { surface_radius_mm: 10.0 }, 5.0),
            10.0 / 15.0,
            1e-12
        ));
    }
}

#[cfg(test)]
mod properties {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        #[test]
        fn concave_engages_more_and_convex_less_than_a_straight_cut(
            r in 1.0f64..10.0,
            rd_fraction in 0.01f64..0.9,
            ratio in 1.05f64..50.0,
        ) {
            let rd = rd_fraction * r;
            let straight = straight_engagement_angle_rad(rd, r);
            let concave = concave_engagement_angle_rad(ratio * r, rd, r);
            let convex = convex_engagement_angle_rad(ratio * r, rd, r);
            prop_assert!(concave >= straight - 1e-12);
            prop_assert!(convex <= straight + 1e-12);
            prop_assert!((0.0..=PI).contains(&concave) && (0.0..=PI).contains(&convex));
        }

        #[test]
        fn the_bounded_chip_never_exceeds_the_papers_chip_nor_the_engaged_depth(
            fz in 0.0001f64..200.0,
            alpha in 0.001f64..PI,
            ratio in 0.05f64..11.0,
            rc in 0.01f64..100.0,
        ) {
            let cut = ToothCut { alpha_rad: alpha, cutting_point_ratio: ratio, centre_radius_mm: rc, tool_radius_mm: 5.0 };
            let t = tooth_chip_thickness_mm(fz, &cut);
            prop_assert!(t >= 0.0);
            prop_assert!(t <= max_chip_thickness_mm(fz * ratio, alpha) + 1e-12);
            prop_assert!(t <= engaged_depth_mm(5.0, alpha) + 1e-12);
            let exact = max_chip_thickness_mm(fz * ratio, alpha)
                .min(2.0 * ratio * rc * ((fz / rc).min(PI) / 2.0).sin())
                .min(engaged_depth_mm(5.0, alpha));
            prop_assert!((t - exact).abs() <= 1e-9 * exact.max(1e-9), "{t} against {exact}");
        }

        #[test]
        fn a_tighter_concave_arc_never_engages_less(
            r in 1.0f64..10.0,
            rd_fraction in 0.01f64..0.9,
            ratio in 1.05f64..20.0,
            step in 0.01f64..5.0,
        ) {
            let rd = rd_fraction * r;
            let tight = concave_engagement_angle_rad(ratio * r, rd, r);
            let wide = concave_engagement_angle_rad((ratio + step) * r, rd, r);
            prop_assert!(tight >= wide - 1e-12);
        }
    }
}
