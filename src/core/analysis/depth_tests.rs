//! The depth resolution of the stock simulation (issue 32 item 2): as many slices as the
//! program's cutting levels need, within the stock memory budget.

use super::*;
use crate::core::progress::NoProgress;
use crate::core::toolpath::{Move, Units, P3};

/// Depth of the cavity the z-level roughing cuts, mm.
pub(super) const CAVITY_DEPTH_MM: f64 = 35.0;
/// Its layers: Ad 0.6 mm.
pub(super) const LAYERS: usize = 58;
/// Diameter of the end mill that roughs it, mm.
pub(super) const ROUGHING_TOOL_MM: f64 = 6.0;
/// The block the cavity is cut in.
const BLOCK: Rect = Rect { x_min: 0.0, y_min: 0.0, x_max: 40.0, y_max: 30.0 };
/// The passes of a layer: along x from 8 to 32 mm, at y from 8 mm on, 3 mm apart.
const PASSES: usize = 5;
const PASS_X_MM: (f64, f64) = (8.0, 32.0);
const FIRST_PASS_Y_MM: f64 = 8.0;
const STEPOVER_MM: f64 = 3.0;
/// Length along x of the ramp into each layer, mm.
const RAMP_MM: f64 = 6.0;
/// The area the passes clear: 30 × 18 mm less the rounding of the four corners by the
/// tool's radius, mm².
fn cleared_area_mm2() -> f64 {
    let r = ROUGHING_TOOL_MM / 2.0;
    let (x, y) = (PASS_X_MM.1 - PASS_X_MM.0 + 2.0 * r, (PASSES - 1) as f64 * STEPOVER_MM + 2.0 * r);
    x * y - 4.0 * (r * r - std::f64::consts::PI * r * r / 4.0)
}

/// A z-level roughing of a cavity [`CAVITY_DEPTH_MM`] deep in [`LAYERS`] layers: into
/// each a ramp along x from the layer above, back flat to its start, [`PASSES`] passes
/// along x, and back to the start of the next ramp. Each layer cuts about 165 mm flat,
/// under 2 % of the program's feed length.
pub(super) fn z_level_roughing() -> Toolpath {
    let mut moves = Vec::new();
    let mut feed = |start: P3, end: P3| {
        moves.push(Move {
            motion: Motion::Linear,
            start,
            end,
            feed_mm_min: Some(1000.0),
            spindle_rpm: Some(9600.0),
            tool: None,
            line: moves.len() as u32 + 1,
        });
        end
    };
    let (x0, x1) = PASS_X_MM;
    let mut z_above = 0.0;
    for k in 1..=LAYERS {
        let z = -CAVITY_DEPTH_MM * k as f64 / LAYERS as f64;
        let mut at = feed(P3::new(x0, FIRST_PASS_Y_MM, z_above), P3::new(x0 + RAMP_MM, FIRST_PASS_Y_MM, z));
        at = feed(at, P3::new(x0, FIRST_PASS_Y_MM, z));
        for j in 0..PASSES {
            let y = FIRST_PASS_Y_MM + STEPOVER_MM * j as f64;
            if j > 0 {
                at = feed(at, P3::new(at.x, y, z));
            }
            at = feed(at, P3::new(if j % 2 == 0 { x1 } else { x0 }, y, z));
        }
        feed(at, P3::new(x0, FIRST_PASS_Y_MM, z));
        z_above = z;
    }
    Toolpath { moves, events: vec![], source_units: Units::Mm, warnings: vec![] }
}

/// The analysis of the roughing with a `tool_type` end mill and `budget_bytes` of stock
/// memory.
fn roughing_analysis(tool_type: ToolType, budget_bytes: usize) -> Analysis {
    let corner_radius_mm = if tool_type == ToolType::Ball { ROUGHING_TOOL_MM / 2.0 } else { 0.0 };
    let tool = EndMill { tool_type, diameter_mm: ROUGHING_TOOL_MM, flutes: 4, corner_radius_mm };
    let spec = AnalysisSpec {
        stock_memory_bytes: budget_bytes,
        ..AnalysisSpec::new(tool, vec![StockRegion::Rect(BLOCK)], 0.0, -CAVITY_DEPTH_MM)
    };
    analyze(&z_level_roughing(), &spec, &NoProgress).expect("analyses")
}

/// The budget warning of `analysis`, if any.
fn budget_warning(analysis: &Analysis) -> Option<&String> {
    analysis.summary.warnings.iter().find(|w| w.contains("stock memory budget"))
}

#[test]
fn a_z_level_roughing_of_a_35_mm_cavity_at_ad_0_6_is_simulated_on_its_58_layers() {
    let a = roughing_analysis(ToolType::Square, DEFAULT_STOCK_MEMORY_BYTES);
    assert_eq!(a.summary.slices.len(), LAYERS);
    assert_eq!(a.summary.stock_memory_budget_bytes, DEFAULT_STOCK_MEMORY_BYTES);
    assert!(budget_warning(&a).is_none(), "{:?}", a.summary.warnings);
    let expected = cleared_area_mm2() * CAVITY_DEPTH_MM;
    let removed = a.summary.removed_volume_mm3;
    assert!((removed - expected).abs() / expected < 0.01, "removed {removed} mm³, expected {expected}");
    // Every layer's slice is cut by its own layer's passes, to its full area.
    for s in &a.summary.slices {
        assert!((s.removed_area_mm2 - cleared_area_mm2()).abs() / cleared_area_mm2() < 0.01, "{s:?}");
    }
}

#[test]
fn a_ball_end_mill_s_z_level_roughing_is_simulated_on_its_58_layers_too() {
    let a = roughing_analysis(ToolType::Square, DEFAULT_STOCK_MEMORY_BYTES);
    let ball = roughing_analysis(ToolType::Ball, DEFAULT_STOCK_MEMORY_BYTES);
    // Every layer is a slice's bottom, as with the square end mill, and the ball's corner
    // adds levels between them (see `profile::with_corner_levels`).
    for layer in &a.summary.slices {
        let bottom = |s: &SliceSummary| (s.z_bottom - layer.z_bottom).abs() < 1e-9;
        assert!(ball.summary.slices.iter().any(bottom), "no slice of the ball ends at {}", layer.z_bottom);
    }
    assert!(ball.summary.slices.len() > LAYERS, "{} slices", ball.summary.slices.len());
    assert!(budget_warning(&ball).is_none(), "{:?}", ball.summary.warnings);
    assert!(ball.summary.removed_volume_mm3 > 0.0 && ball.summary.alpha_deg.max > 0.0);
}

#[test]
fn a_budget_that_holds_fewer_slices_than_the_layers_merges_levels_and_says_so() {
    let cell = budget::wanted_cell_mm(&AnalysisSpec::new(
        EndMill { tool_type: ToolType::Square, diameter_mm: ROUGHING_TOOL_MM, flutes: 4, corner_radius_mm: 0.0 },
        vec![StockRegion::Rect(BLOCK)],
        0.0,
        -CAVITY_DEPTH_MM,
    ));
    let slice_bytes = Raster::cell_count(BLOCK, cell) as f64 * budget::RASTER_BYTES_PER_CELL;
    let a = roughing_analysis(ToolType::Square, (20.0 * slice_bytes).ceil() as usize);
    assert_eq!(a.summary.slices.len(), 20);
    assert_eq!(a.summary.cell_mm, cell, "the cell is kept");
    let warning = budget_warning(&a).expect("a warning");
    assert!(warning.starts_with("levels merged to 20 slices of the 58 the program cuts at"), "{warning}");
    // The merged slices still hold all the material the passes clear.
    let expected = cleared_area_mm2() * CAVITY_DEPTH_MM;
    assert!((a.summary.removed_volume_mm3 - expected).abs() / expected < 0.01);
}

#[test]
fn a_budget_too_small_for_sixteen_slices_coarsens_the_cell_and_says_so() {
    let a = roughing_analysis(ToolType::Square, 1 << 20);
    assert_eq!(a.summary.slices.len(), slices::MAX_SLICES);
    assert!(a.summary.cell_mm > 0.06, "cell {}", a.summary.cell_mm);
    assert!(a.summary.raster_memory_bytes <= 1 << 20, "{} bytes", a.summary.raster_memory_bytes);
    let warning = budget_warning(&a).expect("a warning");
    assert!(warning.contains("levels merged to 16 slices of the 58") && warning.contains("coarsened"), "{warning}");
}

#[test]
fn a_budget_of_no_memory_is_refused() {
    let tool = EndMill { tool_type: ToolType::Square, diameter_mm: ROUGHING_TOOL_MM, flutes: 4, corner_radius_mm: 0.0 };
    let spec =
        AnalysisSpec { stock_memory_bytes: 0, ..AnalysisSpec::new(tool, vec![StockRegion::Rect(BLOCK)], 0.0, -1.0) };
    assert!(check(&z_level_roughing(), &spec).is_err());
}
