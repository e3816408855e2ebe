use super::*;
use crate::core::analysis::{analyze, StockRegion};
use crate::core::cycles::test_support::*;
use crate::core::progress::NoProgress;
use crate::core::stock::Rect;
use crate::core::tolerance::approx_eq;
use crate::core::toolpath::Motion;
use std::f64::consts::PI;

/// A slot along +x from the origin, from z 0 down to −10, in one level (Ad 10).
fn slot(width: f64, length: f64) -> SlotParams {
    SlotParams {
        start: Point::new(0.0, 0.0),
        end: Point::new(length, 0.0),
        width_mm: width,
        tool_radius_mm: R10,
        allowance_mm: 0.0,
        pitch_mm: None,
        z_top_mm: 0.0,
        z_bottom_mm: -10.0,
        max_ad_mm: None,
        direction: CutDirection::Climb,
        entry: Entry::Plunge,
    }
}

/// Area the slot's cycle removes from a solid box, and the stadium's area `w·L + π·w²/4`.
fn cleared(p: &SlotParams, c: &Cycle) -> (f64, f64) {
    let (w, l) = (p.width_mm, p.end.x);
    let stock = StockRegion::Rect(Rect { x_min: -w, y_min: -w, x_max: l + w, y_max: w });
    let mut s = spec(vec![stock], vec![], 0.0, -10.0);
    s.sample_spacing_mm = Some(0.25);
    s.cell_mm = Some(0.2);
    let a = analyze(&c.toolpath(), &s, &NoProgress).unwrap();
    let removed: f64 = a.summary.removed_volume_mm3 / 10.0;
    (removed, w * l + PI * w * w / 4.0)
}

fn check_table_1_slot(width: f64, length: f64, rho: f64) {
    let p = slot(width, length);
    let c = trochoidal_slot(&p, &grooving_setup()).unwrap();
    assert!(approx_eq(slot_loop_radius_mm(width, R10, 0.0), rho, 1e-12));
    assert_eq!(c.report.levels, 1);
    assert_eq!(c.report.loops, (length / 0.5).ceil() as usize + 1);
    assert_continuous(&c.moves);
    assert_tangent_at(&c.moves, -10.0, 1e-9);
    for m in c.moves.iter().filter(|m| matches!(m.motion, Motion::Arc { .. })) {
        let (rs, re, _) = arc_radii(m).unwrap();
        assert!(approx_eq(rs, rho, 1e-9) && approx_eq(re, rho, 1e-9));
    }
    let (removed, expected) = cleared(&p, &c);
    eprintln!(
        "{width} × {length} mm slot: ρ {rho} mm, {} loops, removed {removed:.1} mm² vs {expected:.1} mm² ({:+.3} %), {:.2} min",
        c.report.loops,
        100.0 * (removed - expected) / expected,
        c.report.time_min
    );
    assert!((removed - expected).abs() / expected < 0.01, "{removed} vs {expected}");
}

#[test]
fn the_20_by_60_mm_slot_of_seed_004_table_1_is_cleared_by_loops_of_radius_5() {
    check_table_1_slot(20.0, 60.0, 5.0);
}

#[test]
fn the_12_by_800_mm_slot_of_seed_004_table_1_is_cleared_by_loops_of_radius_1() {
    check_table_1_slot(12.0, 800.0, 1.0);
}

#[test]
fn a_deep_slot_is_cut_in_equal_levels_no_deeper_than_the_axial_depth() {
    let p = SlotParams { z_bottom_mm: -10.0, max_ad_mm: Some(2.5), ..slot(12.0, 10.0) };
    let c = trochoidal_slot(&p, &grooving_setup()).unwrap();
    assert_eq!(c.report.levels, 4);
    assert_eq!(c.report.loops, 4 * 21);
    assert_continuous(&c.moves);
    let mut levels: Vec<f64> =
        c.moves.iter().filter(|m| matches!(m.motion, Motion::Arc { .. })).map(|m| m.start.z).collect();
    levels.dedup();
    assert_eq!(levels, vec![-2.5, -5.0, -7.5, -10.0]);
    // Between levels the tool leaves by the retract height.
    let rapids_up = c.moves.iter().filter(|m| matches!(m.motion, Motion::Rapid) && approx_eq(m.end.z, RETRACT_Z, 0.0));
    assert!(rapids_up.count() >= 4);
}

#[test]
fn a_slot_no_wider_than_the_tool_plus_allowance_is_refused() {
    let err = trochoidal_slot(&slot(10.0, 20.0), &grooving_setup()).unwrap_err().to_string();
    assert!(err.starts_with("width_mm") && err.contains("z-cut division"), "{err}");
    let p = SlotParams { allowance_mm: 1.0, ..slot(12.0, 20.0) };
    assert!(trochoidal_slot(&p, &grooving_setup()).unwrap_err().to_string().starts_with("width_mm"));
    let p = SlotParams { end: Point::new(0.0, 0.0), ..slot(12.0, 20.0) };
    assert!(trochoidal_slot(&p, &grooving_setup()).unwrap_err().to_string().starts_with("end"));
}
