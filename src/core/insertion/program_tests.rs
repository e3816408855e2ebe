//! The programs the trochoid planner writes: golden files in both dialects of a small
//! rounded box cut in two levels, and the rules every such program follows (a
//! comment before each operation of each level; links that go up in Z first, then over,
//! then down).

use super::tests::box_with_slot;
use super::*;
use crate::core::conditions::CuttingConditions;
use crate::core::fixtures::rounded_box;
use crate::core::golden::check_program_goldens;
use crate::core::nc::{write_program, WriterOptions};
use crate::core::progress::NoProgress;
use crate::core::tool::{EndMill, ToolType};
use crate::core::toolpath::{labels_of, Motion, Move, Step};

/// Room for float error in heights, mm.
const Z_TOL_MM: f64 = 1e-9;

/// A 30 × 20 mm box with corners of radius 6: trochoids where the contour-parallel path
/// would slot along its middle, the contour-parallel path round them.
fn small_box() -> Pocket {
    rounded_box(30.0, 20.0, 6.0)
}

/// The 10 mm end mill at seed 004's conditions, 6 mm deep in two levels of 3 mm.
fn two_level_spec() -> InsertionSpec {
    let tool = EndMill { tool_type: ToolType::Square, diameter_mm: 10.0, flutes: 6, corner_radius_mm: 0.0 };
    let roughing = CuttingConditions { spindle_rpm: 4800.0, fz_mm: 0.1, rd_mm: 0.5, ad_mm: 3.0 };
    let grooving = CuttingConditions { spindle_rpm: 4800.0, fz_mm: 0.1, rd_mm: 0.5, ad_mm: 10.0 };
    InsertionSpec { sample_spacing_mm: Some(0.1), ..InsertionSpec::new(tool, roughing, grooving, 0.0, -6.0) }
}

/// Checks the rules of a planner's path: every rapid moves in Z alone or in XY alone, and
/// every one in XY is above the feed moves on both sides of it (Z up first, then over, then
/// down); the first move starts at `safe_z_mm`.
pub(crate) fn assert_links_go_up_over_and_down(path: &[Move], safe_z_mm: f64) {
    assert!(path.first().is_some_and(|m| (m.start.z - safe_z_mm).abs() <= Z_TOL_MM), "{:?}", path.first());
    let feed_z = |m: &Move| m.start.z.max(m.end.z);
    for (i, m) in path.iter().enumerate().filter(|(_, m)| matches!(m.motion, Motion::Rapid)) {
        let moves_xy = (m.end.x - m.start.x).hypot(m.end.y - m.start.y) > Z_TOL_MM;
        if !moves_xy {
            continue;
        }
        assert!((m.end.z - m.start.z).abs() <= Z_TOL_MM, "move {i} moves in XY and Z: {m:?}");
        let before = path[..i].iter().rev().find(|m| !matches!(m.motion, Motion::Rapid));
        let after = path[i + 1..].iter().find(|m| !matches!(m.motion, Motion::Rapid));
        for cut in before.into_iter().chain(after) {
            assert!(m.end.z > feed_z(cut) - Z_TOL_MM, "move {i} goes over at {} below a cut {cut:?}", m.end.z);
        }
    }
}

#[test]
fn a_small_rounded_box_cut_in_two_levels_matches_its_golden_programs_in_both_dialects() {
    let plan = plan_insertion(&small_box(), &two_level_spec(), None, &NoProgress).unwrap();
    assert!(plan.verification.passed, "{:?}", plan.verification);
    assert_eq!(plan.levels_mm, [-3.0, -6.0]);
    check_program_goldens(&plan.toolpath, "small box", "trochoids_fanuc.nc", "trochoids_linuxcnc_numbered.ngc");
}

#[test]
fn every_level_comments_each_of_its_operations_and_regions_in_the_order_they_are_cut() {
    let spec = two_level_spec();
    let plan = plan_insertion(&small_box(), &spec, None, &NoProgress).unwrap();
    let labels = labels_of(&plan.toolpath.events, plan.toolpath.moves.len());
    assert!(labels.iter().all(Option::is_some), "every move belongs to a part");
    let text = write_program(&plan.toolpath, &WriterOptions::default());
    let comments: Vec<&str> = text.lines().filter(|l| l.starts_with("(LAYER")).collect();
    // Each level: for each region, its helical entry (unless it starts where the regions
    // before it have swept: then it goes straight down) then its trochoid (or its z-cut);
    // then the contour-parallel path.
    let regions = plan.treatments.len() - 1;
    let mut total = 0;
    let mut straight_down = 0;
    for (k, z) in plan.levels_mm.iter().enumerate() {
        let mut expected = Vec::new();
        for (i, t) in plan.treatments[..regions].iter().enumerate() {
            let hole = (0..plan.toolpath.moves.len()).any(|m| {
                plan.move_treatment[m] == i && plan.move_entry[m] && (plan.toolpath.moves[m].end.z - z).abs() < 1e-9
            });
            straight_down += usize::from(t.kind == TreatmentKind::Trochoid && !hole);
            let steps: &[&str] = match t.kind {
                TreatmentKind::Trochoid if hole => &["HELICAL BORING", "TROCHOIDAL GROOVING"],
                TreatmentKind::Trochoid => &["TROCHOIDAL GROOVING"],
                TreatmentKind::Opening => &["HELICAL BORING", "SPIRAL HOLE EXPANSION"],
                TreatmentKind::ZCut => &["Z-CUT DIVISION"],
                TreatmentKind::Kept => &[],
            };
            expected.extend(steps.iter().map(|s| format!("(LAYER {} Z{z} {s} REGION {})", k + 1, i + 1)));
        }
        expected.push(format!("(LAYER {} Z{z} ROUGH SIDE CUTTING)", k + 1));
        let level: Vec<&str> =
            comments.iter().copied().filter(|c| c.starts_with(&format!("(LAYER {} ", k + 1))).collect();
        assert_eq!(level, expected, "{text}");
        total += expected.len();
    }
    assert!(regions > 0 && comments.len() == total);
    // The trochoids that leave the medial-axis node where an earlier one starts go straight
    // down into its swept disc.
    assert!(straight_down > 0, "{text}");
    // The labels agree with the planner's own record of which move belongs to what (the
    // rapids that lead to a helical entry belong to it, where the record has the trochoid).
    for (i, label) in
        labels.iter().enumerate().filter(|(i, _)| !matches!(plan.toolpath.moves[*i].motion, Motion::Rapid))
    {
        let label = label.unwrap();
        let step = match (plan.treatments[plan.move_treatment[i]].kind, plan.move_entry[i]) {
            (TreatmentKind::Trochoid | TreatmentKind::Opening, true) => Step::HelicalBoring,
            (TreatmentKind::Trochoid, false) => Step::TrochoidalGrooving,
            (TreatmentKind::Opening, false) => Step::SpiralHoleExpansion,
            (TreatmentKind::ZCut, _) => Step::ZCutDivision,
            (TreatmentKind::Kept, _) => spec.base_step,
        };
        assert_eq!(label.step, step, "move {i}");
        assert_eq!(
            label.region.map(|r| r as usize),
            (plan.move_treatment[i] < regions).then_some(plan.move_treatment[i])
        );
    }
}

#[test]
fn the_planners_links_go_up_in_z_first_then_over_then_down() {
    let plan = plan_insertion(&small_box(), &two_level_spec(), None, &NoProgress).unwrap();
    assert_links_go_up_over_and_down(&plan.toolpath.moves, two_level_spec().safe_z_mm);
    let mut narrow_spec = two_level_spec();
    narrow_spec.roughing.ad_mm = 6.0;
    let narrow = plan_insertion(&box_with_slot(10.8), &narrow_spec, None, &NoProgress).unwrap();
    assert!(narrow.treatments.iter().any(|t| t.kind == TreatmentKind::ZCut));
    assert_links_go_up_over_and_down(&narrow.toolpath.moves, narrow_spec.safe_z_mm);
    let text = write_program(&narrow.toolpath, &WriterOptions::default());
    assert!(text.contains(" Z-CUT DIVISION REGION "), "{text}");
}
