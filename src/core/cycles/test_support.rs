//! Helpers shared by the cycles' tests: setups from MODEL.md §5, analysis specs and checks
//! of continuity, tangency and arc radii.

use super::setup::CycleSetup;
use crate::core::analysis::sampling::point_on;
use crate::core::analysis::{AnalysisSpec, StockRegion, DEFAULT_ALPHA_LIMIT_DEG};
use crate::core::conditions::CuttingConditions;
use crate::core::tool::{EndMill, ToolType};
use crate::core::toolpath::{Motion, Move, Plane};

/// Tool radius of the papers' 10 mm straight end mill, mm.
pub const R10: f64 = 5.0;
/// Clearance and retract heights of the test setups, mm.
pub const CLEARANCE_Z: f64 = 50.0;
pub const RETRACT_Z: f64 = 2.0;

/// Trochoidal grooving, 10 mm straight, 6 flutes (seed 004 Table 2: S 4800, fz 0.05–0.15,
/// Rd 0–0.5, Ad 10).
pub fn grooving_setup() -> CycleSetup {
    let c = CuttingConditions { spindle_rpm: 4800.0, fz_mm: 0.1, rd_mm: 0.5, ad_mm: 10.0 };
    CycleSetup { retract_z_mm: Some(RETRACT_Z), ..CycleSetup::new(c, 6, CLEARANCE_Z) }
}

/// A square end mill of diameter `d` with 6 flutes.
pub fn square(d: f64) -> EndMill {
    EndMill { tool_type: ToolType::Square, diameter_mm: d, flutes: 6, corner_radius_mm: 0.0 }
}

/// An analysis of a layer from `z_top` to `z_bottom` with the 10 mm tool.
pub fn spec(stock: Vec<StockRegion>, open: Vec<StockRegion>, z_top: f64, z_bottom: f64) -> AnalysisSpec {
    AnalysisSpec {
        tool: square(2.0 * R10),
        stock,
        open,
        z_top,
        z_bottom,
        force_model: None,
        default_spindle_rpm: None,
        rapid_mm_min: 20_000.0,
        sample_spacing_mm: None,
        cell_mm: None,
        alpha_limit_deg: DEFAULT_ALPHA_LIMIT_DEG,
        series_points: 0,
        stock_memory_bytes: crate::core::analysis::DEFAULT_STOCK_MEMORY_BYTES,
    }
}

/// Panics unless every move starts exactly where the one before ended and is numbered
/// by its 1-based index.
pub fn assert_continuous(moves: &[Move]) {
    for (i, m) in moves.iter().enumerate() {
        assert_eq!(m.line as usize, i + 1, "line of move {i}");
        if i > 0 {
            assert_eq!(m.start, moves[i - 1].end, "move {i} does not start where move {} ends", i - 1);
        }
    }
}

/// The unit XY tangent of `m` at fraction `t`.
pub fn tangent(m: &Move, t: f64) -> (f64, f64) {
    let (_, d) = point_on(m, t);
    let l = d.0.hypot(d.1);
    (d.0 / l, d.1 / l)
}

/// Panics unless consecutive feed moves at height `z` meet with the same XY direction.
pub fn assert_tangent_at(moves: &[Move], z: f64, tol: f64) {
    let flat: Vec<&Move> = moves
        .iter()
        .filter(|m| !matches!(m.motion, Motion::Rapid) && (m.start.z - z).abs() < 1e-9 && (m.end.z - z).abs() < 1e-9)
        .collect();
    for w in flat.windows(2) {
        if w[0].end != w[1].start {
            continue;
        }
        let (a, b) = (tangent(w[0], 1.0), tangent(w[1], 0.0));
        assert!((a.0 - b.0).hypot(a.1 - b.1) < tol, "lines {} → {}: {a:?} vs {b:?}", w[0].line, w[1].line);
    }
}

/// The XY radius of an arc at its start and at its end, and its centre.
pub fn arc_radii(m: &Move) -> Option<(f64, f64, (f64, f64))> {
    let Motion::Arc { center, plane: Plane::Xy, .. } = m.motion else { return None };
    let rs = (m.start.x - center.x).hypot(m.start.y - center.y);
    let re = (m.end.x - center.x).hypot(m.end.y - center.y);
    Some((rs, re, (center.x, center.y)))
}

/// Points every `step` fraction along each feed move.
pub fn feed_points(moves: &[Move], per_move: usize) -> Vec<(f64, f64, f64)> {
    moves
        .iter()
        .filter(|m| !matches!(m.motion, Motion::Rapid))
        .flat_map(|m| {
            (0..=per_move).map(move |k| {
                let (p, _) = point_on(m, k as f64 / per_move as f64);
                (p.x, p.y, p.z)
            })
        })
        .collect()
}
