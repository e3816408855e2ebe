//! The chip thickness and force come from what a tooth can cut: the machine's maximum
//! feed, the pivot bound of the cutting-point correction, the material between
//! successive tooth paths; and the forces outside the model's experiments are flagged.

use super::feed_cap::cap_feeds;
use super::*;
use crate::core::engagement::PIVOT_SURFACE_RATIO;
use crate::core::fixtures::seed_001_ten_mm;
use crate::core::progress::NoProgress;
use crate::core::tool::ToolType;
use crate::core::toolpath::{Move, Plane, Units, P3};

const R: f64 = 5.0;
const S: f64 = 9600.0;
const FLUTES: f64 = 6.0;

fn spec(stock: Rect) -> AnalysisSpec {
    AnalysisSpec {
        tool: EndMill { tool_type: ToolType::Square, diameter_mm: 2.0 * R, flutes: 6, corner_radius_mm: 0.0 },
        stock: vec![StockRegion::Rect(stock)],
        open: vec![],
        z_top: 0.0,
        z_bottom: -10.0,
        force_model: Some(seed_001_ten_mm()),
        default_spindle_rpm: Some(S),
        rapid_mm_min: 20000.0,
        sample_spacing_mm: None,
        cell_mm: None,
        alpha_limit_deg: DEFAULT_ALPHA_LIMIT_DEG,
        series_points: 0,
        stock_memory_bytes: crate::core::analysis::DEFAULT_STOCK_MEMORY_BYTES,
    }
}

fn mv(motion: Motion, start: P3, end: P3, feed: f64, line: u32) -> Move {
    Move { motion, start, end, feed_mm_min: Some(feed), spindle_rpm: Some(S), tool: None, line }
}

/// A full slot through a 100 × 40 block at `feed`, on line 5.
fn slot(feed: f64) -> Toolpath {
    let moves = vec![mv(Motion::Linear, P3::new(-10.0, 20.0, -10.0), P3::new(110.0, 20.0, -10.0), feed, 5)];
    Toolpath { moves, events: vec![], source_units: Units::Mm, warnings: vec![] }
}

const BLOCK: Rect = Rect { x_min: 0.0, y_min: 0.0, x_max: 100.0, y_max: 40.0 };

#[test]
fn an_f9991300_slot_on_a_15000_mm_min_machine_cuts_at_the_machines_feed_and_is_flagged() {
    let (capped, warning) = cap_feeds(slot(9_991_300.0), 15_000.0);
    assert!(warning.is_some_and(|w| w.contains("line 5")));
    let a = analyze(&capped, &spec(BLOCK), &NoProgress).expect("analyses");
    let s = &a.summary;
    // fz = 15000 / (6 · 9600) = 0.26 mm: the chip of a full slot.
    let fz_um = 15_000.0 / (FLUTES * S) * 1000.0;
    assert!((s.t_m_um.max - fz_um).abs() < 0.5, "t_m {} µm", s.t_m_um.max);
    let force = s.force_n.expect("a force").max;
    assert!(force.is_finite() && force < 20_000.0, "force {force} N");
    let outside = s.outside_model.as_ref().expect("a force model");
    assert!(outside.length_mm > 90.0 && outside.max_coded_radius > 10.0, "{outside:?}");
    assert!(outside.arc_length_mm.max > 15.0 && outside.design_arc_length_mm.max < 3.0, "{outside:?}");
    let overload = s.force_overload.as_ref().expect("a force model");
    assert_eq!(overload.lines.first().map(|l| l.line), Some(5));
    assert!(s.warnings.iter().any(|w| w.contains("extrapolated") && w.contains("|X|")), "{:?}", s.warnings);
    assert!(s.warnings.iter().any(|w| w.contains("3 × the tool's standard force") && w.contains("line 5")));
}

#[test]
fn without_a_machine_limit_an_f9991300_chip_is_still_no_thicker_than_the_tool() {
    let a = analyze(&slot(9_991_300.0), &spec(BLOCK), &NoProgress).expect("analyses");
    // The papers' formula gives fz = 173 mm; a full slot reaches the diameter at most.
    assert!(a.summary.t_m_um.max <= 2.0 * R * 1000.0 + 1e-6, "{}", a.summary.t_m_um.max);
}

#[test]
fn the_standard_straight_cut_stays_inside_the_models_experiments() {
    let moves = vec![mv(Motion::Linear, P3::new(-10.0, -4.5, -10.0), P3::new(110.0, -4.5, -10.0), 5760.0, 3)];
    let path = Toolpath { moves, events: vec![], source_units: Units::Mm, warnings: vec![] };
    let a = analyze(&path, &spec(BLOCK), &NoProgress).expect("analyses");
    // Only the entry into the block, where the arc is shorter than the experiments', lies
    // outside; the steady cut sits at the design centre.
    let outside = a.summary.outside_model.expect("a force model");
    assert!(outside.length_mm < 5.0, "{outside:?}");
    assert!(outside.x1.max < 0.1 && outside.x2.max < 0.1, "{outside:?}");
    assert!(outside.furthest.is_some_and(|p| p.x < R), "{outside:?}");
    assert_eq!(a.summary.force_overload.expect("a force model").line_count, 0);
}

#[test]
fn a_centre_path_turning_at_0_3_mm_with_material_outside_gets_the_pivot_bounded_correction() {
    // Along the block's lower edge at Rd 0.5, then a U-turn of radius 0.3 mm away from
    // the material (clockwise: the material outside the turn), and back in the air.
    let arc = Motion::Arc { center: P3::new(60.0, -4.8, -10.0), clockwise: true, plane: Plane::Xy, turns: 0 };
    let moves = vec![
        mv(Motion::Linear, P3::new(-10.0, -4.5, -10.0), P3::new(60.0, -4.5, -10.0), 2000.0, 1),
        mv(arc, P3::new(60.0, -4.5, -10.0), P3::new(60.0, -5.1, -10.0), 2000.0, 2),
        mv(Motion::Linear, P3::new(60.0, -5.1, -10.0), P3::new(40.0, -5.1, -10.0), 2000.0, 3),
    ];
    let path = Toolpath { moves, events: vec![], source_units: Units::Mm, warnings: vec![] };
    let mut on_arc = Vec::new();
    analyze_with(&path, &spec(BLOCK), &NoProgress, |r| {
        if r.sample.line == 2 && r.contact.alpha_rad > 0.0 {
            on_arc.push(*r);
        }
    })
    .expect("analyses");
    assert!(!on_arc.is_empty(), "the turn cuts");
    let bound = PIVOT_SURFACE_RATIO / (PIVOT_SURFACE_RATIO - 1.0);
    let fz_um = 2000.0 / (FLUTES * S) * 1000.0;
    for r in &on_arc {
        assert!(r.cutting_point_ratio <= bound + 1e-9, "ratio {}", r.cutting_point_ratio);
        assert!(r.t_m_um <= bound * fz_um + 1e-9, "t_m {} µm", r.t_m_um);
    }
    assert!(on_arc.iter().any(|r| (r.cutting_point_ratio - bound).abs() < 1e-9), "the bound is reached");
}

#[test]
fn a_slot_cut_in_more_levels_than_slices_keeps_its_floor() {
    // 450 passes 0.01 mm apart down to −4.5 through a 20 × 40 block 5 mm deep: the levels
    // are merged into 16 slices, and the slot's floor stays.
    let moves = (1..=450)
        .map(|i| {
            let z = -0.01 * f64::from(i);
            mv(Motion::Linear, P3::new(-10.0, 20.0, z), P3::new(30.0, 20.0, z), 2000.0, 5)
        })
        .collect();
    let path = Toolpath { moves, events: vec![], source_units: Units::Mm, warnings: vec![] };
    let block = Rect { x_min: 0.0, y_min: 0.0, x_max: 20.0, y_max: 40.0 };
    let s = AnalysisSpec { z_bottom: -5.0, force_model: None, ..spec(block) };
    let a = analyze(&path, &s, &NoProgress).expect("analyses");
    let slot_mm2 = 20.0 * 2.0 * R;
    let removed = a.summary.removed_volume_mm3;
    assert!((removed - slot_mm2 * 4.5).abs() < 0.01 * slot_mm2 * 4.5, "{removed}");
}
