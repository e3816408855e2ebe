use super::*;
use crate::core::analysis::{analyze_with, StockRegion};
use crate::core::conditions::CuttingConditions;
use crate::core::cycles::test_support::*;
use crate::core::engagement::concave_engagement_angle_rad;
use crate::core::progress::NoProgress;
use crate::core::stock::Rect;
use crate::core::tolerance::approx_eq;
use crate::core::toolpath::Motion;
use std::f64::consts::PI;

/// Seed 004 Table 2 (2): 10 mm straight, 6 flutes, S 4800, fz 0.1, Rd 0.5, Ad 10.
fn expansion_setup() -> CycleSetup {
    let c = CuttingConditions { spindle_rpm: 4800.0, fz_mm: 0.1, rd_mm: 0.5, ad_mm: 10.0 };
    CycleSetup { retract_z_mm: Some(RETRACT_Z), ..CycleSetup::new(c, 6, CLEARANCE_Z) }
}

/// The 20 mm bored hole opened to 40 mm, 10 mm deep.
fn hole() -> SpiralParams {
    SpiralParams {
        center: Point::new(0.0, 0.0),
        start_radius_mm: 10.0,
        final_radius_mm: 20.0,
        tool_radius_mm: R10,
        rd_mm: None,
        z_top_mm: 0.0,
        z_bottom_mm: -10.0,
        max_ad_mm: None,
        direction: CutDirection::Climb,
    }
}

fn arcs_about(c: &Cycle, x: f64) -> Vec<f64> {
    c.moves
        .iter()
        .filter_map(arc_radii)
        .filter(|(_, _, centre)| approx_eq(centre.0, x, 1e-12) && approx_eq(centre.1, 0.0, 1e-12))
        .map(|(rs, re, _)| {
            assert!(approx_eq(rs, re, 1e-9));
            rs
        })
        .collect()
}

#[test]
fn the_radii_grow_by_rd_per_turn_to_a_final_circle_at_r1_minus_r() {
    let c = spiral_hole_expansion(&hole(), &expansion_setup()).unwrap();
    assert_continuous(&c.moves);
    assert_tangent_at(&c.moves, -10.0, 1e-9);
    // ρ from 5 to 15 at 0.5 per turn: 20 turns.
    assert_eq!(c.report.steps, 20);
    let about_a = arcs_about(&c, 0.0);
    assert_eq!(about_a.len(), 21);
    for (k, rho) in about_a.iter().take(20).enumerate() {
        assert!(approx_eq(*rho, 5.0 + 0.5 * k as f64, 1e-9), "turn {k}: {rho}");
    }
    assert!(approx_eq(*about_a.last().unwrap(), 15.0, 1e-12), "final circle at R1 − r");
    let about_b = arcs_about(&c, 0.25);
    assert_eq!(about_b.len(), 20);
    for w in about_b.windows(2) {
        assert!(approx_eq(w[1] - w[0], 0.5, 1e-9));
    }
    let last = c.moves.iter().rev().find(|m| matches!(m.motion, Motion::Arc { .. })).unwrap();
    assert!(last.start == last.end && approx_eq(last.start.x, 15.0, 1e-12));
    assert!(c.moves.iter().all(|m| !matches!(m.motion, Motion::Arc { clockwise: true, .. })));
}

#[test]
fn a_growth_that_does_not_divide_gives_equal_turns_below_rd() {
    let p = SpiralParams { final_radius_mm: 17.3, ..hole() };
    let c = spiral_hole_expansion(&p, &expansion_setup()).unwrap();
    assert_eq!(c.report.steps, 15);
    let about_a = arcs_about(&c, 0.0);
    let step = 7.3 / 15.0;
    for w in about_a.windows(2) {
        assert!(approx_eq(w[1] - w[0], step, 1e-9) && step <= 0.5);
    }
    assert!(approx_eq(*about_a.last().unwrap(), 12.3, 1e-12));
}

#[test]
fn a_hole_the_size_of_the_tool_starts_at_the_centre() {
    let p = SpiralParams { start_radius_mm: R10, final_radius_mm: 8.0, ..hole() };
    let c = spiral_hole_expansion(&p, &expansion_setup()).unwrap();
    assert_continuous(&c.moves);
    let first_arc = c.moves.iter().find(|m| matches!(m.motion, Motion::Arc { .. })).unwrap();
    assert!(approx_eq(first_arc.start.x, 0.0, 1e-12) && approx_eq(first_arc.start.y, 0.0, 1e-12));
    assert!(approx_eq(*arcs_about(&c, 0.0).last().unwrap(), 3.0, 1e-12));
}

#[test]
fn a_deep_hole_is_expanded_level_by_level() {
    let p = SpiralParams { z_bottom_mm: -25.0, ..hole() };
    let c = spiral_hole_expansion(&p, &expansion_setup()).unwrap();
    assert_eq!(c.report.levels, 3);
    assert!(approx_eq(c.report.turns, 3.0 * 21.0, 0.0));
    assert_continuous(&c.moves);
}

#[test]
fn the_spiral_clears_the_ring_with_the_engagement_of_a_concave_cut_at_rd() {
    let c = spiral_hole_expansion(&hole(), &expansion_setup()).unwrap();
    let stock = StockRegion::Rect(Rect { x_min: -30.0, y_min: -30.0, x_max: 30.0, y_max: 30.0 });
    let open = StockRegion::Circle { cx: 0.0, cy: 0.0, r: 10.0 };
    let mut alpha_max = 0.0f64;
    let a = analyze_with(&c.toolpath(), &spec(vec![stock], vec![open], 0.0, -10.0), &NoProgress, |s| {
        alpha_max = alpha_max.max(s.contact.alpha_rad.to_degrees());
    })
    .unwrap();
    let expected_area = PI * (400.0 - 100.0);
    let removed = a.summary.slices[0].removed_area_mm2;
    // The tightest cut is the first, at R = 10.5 mm with Rd = 0.5.
    let bound = concave_engagement_angle_rad(10.5, 0.5, R10).to_degrees();
    eprintln!("spiral 20 → 40 mm: removed {removed:.1} vs {expected_area:.1} mm², α max {alpha_max:.1}° (concave bound {bound:.1}°)");
    assert!((removed - expected_area).abs() / expected_area < 0.01);
    assert!(alpha_max <= bound + 1.0, "{alpha_max} vs {bound}");
}

#[test]
fn holes_the_spiral_cannot_expand_are_refused() {
    let err = |p: SpiralParams| spiral_hole_expansion(&p, &expansion_setup()).unwrap_err().to_string();
    assert!(err(SpiralParams { start_radius_mm: 4.0, ..hole() }).starts_with("start_radius_mm"));
    assert!(err(SpiralParams { final_radius_mm: 10.0, ..hole() }).starts_with("final_radius_mm"));
    assert!(err(SpiralParams { rd_mm: Some(0.0), ..hole() }).starts_with("rd_mm"));
    assert!(err(SpiralParams { z_top_mm: 5.0, ..hole() }).starts_with("z_top_mm"));
}
