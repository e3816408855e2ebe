//! A stock carried from one program to the next (issue 32 item 3): the same as running the
//! two on one stock where the levels are the same, and sensible where they are not.

use super::engine::{simulate, Cutter};
use super::profile::Profile;
use super::*;
use crate::core::progress::NoProgress;
use crate::core::tool::ToolType;
use crate::core::toolpath::{Move, Units, P3};

const BLOCK: Rect = Rect { x_min: 0.0, y_min: 0.0, x_max: 100.0, y_max: 40.0 };

pub(super) fn spec(z_bottom: f64) -> AnalysisSpec {
    let tool = EndMill { tool_type: ToolType::Square, diameter_mm: 10.0, flutes: 6, corner_radius_mm: 0.0 };
    AnalysisSpec {
        default_spindle_rpm: Some(9600.0),
        ..AnalysisSpec::new(tool, vec![StockRegion::Rect(BLOCK)], 0.0, z_bottom)
    }
}

/// The block's outline as a pocket (a cavity), 10 mm deep.
fn pocket_spec() -> AnalysisSpec {
    use crate::core::geometry::{Loop, Pocket, Vertex};
    let v = |x: f64, y: f64| Vertex { x, y, bulge: 0.0 };
    let outer = Loop::new(vec![v(0.0, 0.0), v(100.0, 0.0), v(100.0, 40.0), v(0.0, 40.0)]);
    let pocket = Pocket::new(outer, vec![]).expect("a pocket");
    AnalysisSpec { stock: vec![StockRegion::Pocket(pocket)], ..spec(-10.0) }
}

fn feed(start: P3, end: P3) -> Move {
    Move { motion: Motion::Linear, start, end, feed_mm_min: Some(1000.0), spindle_rpm: None, tool: None, line: 1 }
}

/// Passes across the block along y = `y`, one at each of `levels`, from outside it.
pub(super) fn passes(y: f64, levels: &[f64]) -> Toolpath {
    let mut moves = Vec::new();
    for &z in levels {
        moves.push(feed(P3::new(-10.0, y, 5.0), P3::new(-10.0, y, z)));
        moves.push(feed(P3::new(-10.0, y, z), P3::new(110.0, y, z)));
        moves.push(feed(P3::new(110.0, y, z), P3::new(110.0, y, 5.0)));
        moves.push(Move { motion: Motion::Rapid, ..feed(P3::new(110.0, y, 5.0), P3::new(-10.0, y, 5.0)) });
    }
    Toolpath { moves, events: vec![], source_units: Units::Mm, warnings: vec![] }
}

#[test]
fn a_stack_carried_over_gives_the_samples_of_the_second_program_run_on_after_the_first() {
    let spec = spec(-10.0);
    let (first, second) = (passes(20.0, &[-5.0, -10.0]), passes(24.0, &[-5.0, -10.0]));
    let levels = slices::slice_levels(&second, spec.z_bottom, spec.z_top);
    assert_eq!(levels, slices::slice_levels(&first, spec.z_bottom, spec.z_top), "the two cut the same levels");
    let (_, mut stack) = analyze_from(&first, &spec, None, &NoProgress, |_| {}).expect("analyses");
    let kept = stack.keep(false);
    // On after the first on the same stock …
    let (spacing, _) = resolution(&spec, BLOCK, levels.len() - 1);
    let cutter = Cutter {
        profile: Profile::cylinder(5.0),
        flutes: 6,
        default_spindle_rpm: spec.default_spindle_rpm,
        force_model: None,
        spacing_mm: spacing,
        total_samples: 1,
    };
    let mut on_after = Vec::new();
    simulate(&second, cutter, &mut stack, &NoProgress, |r| on_after.push(format!("{r:?}"))).expect("simulates");
    // … and from the kept stock.
    let mut carried = Vec::new();
    let (analysis, _) =
        analyze_from(&second, &spec, Some(&kept), &NoProgress, |r| carried.push(format!("{r:?}"))).expect("analyses");
    assert_eq!(carried.len(), on_after.len());
    assert!(carried == on_after, "the samples differ");
    // It cuts 4 mm of the wall the first left: not a slot.
    assert!(analysis.summary.alpha_deg.max < 120.0, "{:?}", analysis.summary.alpha_deg);
}

#[test]
fn an_intermediate_pass_at_ad_2_5_on_a_roughing_at_ad_10_cuts_only_the_wall_it_steps_into() {
    let spec = spec(-20.0);
    // Roughing: a slot through the block at Ad 10, y from 15 to 25.
    let (_, roughed) = analyze_from(&passes(20.0, &[-10.0, -20.0]), &spec, None, &NoProgress, |_| {}).expect("roughs");
    let kept = roughed.keep(false);
    let block_mm3 = 100.0 * 40.0 * 20.0;
    // Intermediate: 1 mm into the wall at y = 25, at Ad 2.5.
    let levels: Vec<f64> = (1..=8).map(|i| -2.5 * f64::from(i)).collect();
    let (after, stack) =
        analyze_from(&passes(21.0, &levels), &spec, Some(&kept), &NoProgress, |_| {}).expect("analyses");
    assert_eq!(stack.len(), 8, "the intermediate pass's own levels");
    // α = acos(1 − 2·ae/D) for ae = 1 mm on D 10: 36.87°.
    let expected = (1.0f64 - 2.0 * 1.0 / 10.0).acos().to_degrees();
    let a = after.summary.alpha_deg;
    assert!((a.max - expected).abs() < 2.0, "α max {} vs {expected}", a.max);
    let removed = 1.0 * 100.0 * 20.0;
    let remaining = block_mm3 - 10.0 * 100.0 * 20.0 - removed;
    assert!(
        (after.summary.removed_volume_mm3 - removed).abs() / removed < 0.02,
        "{}",
        after.summary.removed_volume_mm3
    );
    assert!((after.summary.remaining_volume_mm3 - remaining).abs() / remaining < 0.005);
    // On the block as it was, the same pass is a full slot.
    let (fresh, _) = analyze_from(&passes(21.0, &levels), &spec, None, &NoProgress, |_| {}).expect("analyses");
    assert!(fresh.summary.alpha_deg.max > 170.0);
}

#[test]
fn a_slice_spanning_a_kept_level_holds_the_material_of_the_kept_slice_below() {
    let spec = spec(-20.0);
    // Roughing at −10 only: the slice below −10 is untouched.
    let (_, roughed) = analyze_from(&passes(20.0, &[-10.0]), &spec, None, &NoProgress, |_| {}).expect("roughs");
    let kept = roughed.keep(false);
    // A pass at −12 spans the level at −10: its slice from 0 to −12 is solid, so it slots.
    let (after, _) = analyze_from(&passes(20.0, &[-12.0]), &spec, Some(&kept), &NoProgress, |_| {}).expect("analyses");
    assert!(after.summary.alpha_deg.max > 170.0, "{:?}", after.summary.alpha_deg);
    // A pass at −8 lies inside the roughed slice: no material.
    let (above, _) = analyze_from(&passes(20.0, &[-8.0]), &spec, Some(&kept), &NoProgress, |_| {}).expect("analyses");
    assert!(above.summary.cutting_length_mm < 1e-9, "{}", above.summary.cutting_length_mm);
}

#[test]
fn the_rest_material_of_a_pocket_is_what_the_path_left_in_it_with_a_point_of_it() {
    let spec = pocket_spec();
    let (a, stack) = analyze_from(&passes(20.0, &[-10.0]), &spec, None, &NoProgress, |_| {}).expect("analyses");
    let rest = a.summary.rest_material.expect("a pocket has rest material");
    let left = 30.0 * 100.0 * 10.0;
    assert!((rest.volume_mm3 - left).abs() / left < 0.005, "{}", rest.volume_mm3);
    assert!((rest.volume_mm3 - a.summary.remaining_volume_mm3).abs() < 1e-6);
    let [x, y] = rest.levels[0].point.expect("material is left");
    assert!(stack.raster(0).is_material(x, y) && !(15.0..=25.0).contains(&y));
    assert!(stack.keep(true).cavity);
}

#[test]
fn below_the_kept_bottom_lies_the_stock_as_it_was_given_down_to_its_floor() {
    use super::kept::{keep, Floor};
    // The layer from 0 to −20 of a box whose bottom is at −30: a slot roughed at Ad 10.
    let spec = spec(-20.0);
    let (_, roughed) = analyze_from(&passes(20.0, &[-10.0, -20.0]), &spec, None, &NoProgress, |_| {}).expect("roughs");
    let kept = keep(&roughed, &spec, None, Floor::At(-30.0), false).expect("keeps");
    assert_eq!(kept.floor(), Some(Floor::At(-30.0)));
    // On down the slot to −25: the layer reaches −25, the slot above is the kept one, and
    // below −20 the tool slots through the box's footprint.
    let (deeper, stack) =
        analyze_from(&passes(20.0, &[-20.0, -25.0]), &spec, Some(&kept), &NoProgress, |_| {}).expect("analyses");
    let bottoms: Vec<f64> = stack.slices().iter().map(|s| s.z_bottom).collect();
    assert_eq!(bottoms, vec![-20.0, -25.0]);
    assert!(deeper.summary.alpha_deg.max > 170.0, "{:?}", deeper.summary.alpha_deg);
    let slot = 10.0 * 100.0 * 5.0;
    assert!((deeper.summary.removed_volume_mm3 - slot).abs() / slot < 0.02, "{}", deeper.summary.removed_volume_mm3);
    // A pass at −40 cuts down to the box's bottom and no further; only the slice below the
    // kept bottom holds material, so the kept slot is not cut again.
    let (deepest, stack) =
        analyze_from(&passes(20.0, &[-40.0]), &spec, Some(&kept), &NoProgress, |_| {}).expect("analyses");
    assert_eq!(stack.slices().last().map(|s| s.z_bottom), Some(-30.0));
    let slot = 10.0 * 100.0 * 10.0;
    assert!((deepest.summary.removed_volume_mm3 - slot).abs() / slot < 0.02, "{}", deepest.summary.removed_volume_mm3);
    // Its own kept stock passes on what lies under it.
    let again = keep(&stack, &spec, Some(&kept), Floor::Unbounded, false).expect("keeps");
    assert_eq!((again.z_bottom(), again.floor()), (-30.0, Some(Floor::At(-30.0))));
    // Under a stock kept without it, nothing is known: the deeper pass is refused.
    let unknown = kept::KeptStock { below: None, ..kept };
    let refused = analyze_from(&passes(20.0, &[-25.0]), &spec, Some(&unknown), &NoProgress, |_| {});
    assert!(
        matches!(refused, Err(CoreError::InvalidInput { ref field, .. }) if field == "stock.from_job"),
        "{:?}",
        refused.err()
    );
}

#[test]
fn under_a_pocket_its_cavity_runs_on_down_in_its_outline() {
    use super::kept::{keep, Floor};
    let spec = pocket_spec();
    let (_, cut) = analyze_from(&passes(20.0, &[-10.0]), &spec, None, &NoProgress, |_| {}).expect("analyses");
    let kept = keep(&cut, &spec, None, Floor::Unbounded, true).expect("keeps");
    let (deeper, stack) =
        analyze_from(&passes(20.0, &[-10.0, -50.0]), &spec, Some(&kept), &NoProgress, |_| {}).expect("analyses");
    assert_eq!(stack.slices().last().map(|s| s.z_bottom), Some(-50.0));
    // The slot on down from −10 to −50, and the cavity's rest beside it.
    let slot = 10.0 * 100.0 * 40.0;
    assert!((deeper.summary.removed_volume_mm3 - slot).abs() / slot < 0.02, "{}", deeper.summary.removed_volume_mm3);
    let rest = deeper.summary.rest_material.expect("a cavity");
    let left = 30.0 * 100.0 * 50.0;
    assert!((rest.volume_mm3 - left).abs() / left < 0.01, "{}", rest.volume_mm3);
}
