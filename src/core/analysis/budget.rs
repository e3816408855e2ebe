//! The memory budget of the stock simulation (issue 32 item 2): how many slices of the
//! layer's rasters an analysis may hold, and how fine their cell may be.
//!
//! A slice's raster takes [`RASTER_BYTES_PER_CELL`] per cell. At the cell the analysis
//! wants, as many slices as the budget holds are kept, never fewer than [`MAX_SLICES`]
//! (levels beyond them are merged, see [`super::levels`]); only when even those do not fit
//! is the cell coarsened. The budget counts every slice with a raster of its own, as if
//! none shared one (see [`super::stack`]): the most a simulation can come to.

use super::levels::MAX_SLICES;
use super::AnalysisSpec;
use crate::core::stock::{Grid, Raster, Rect};

/// The stock memory budget of an analysis unless told otherwise, bytes (1 GiB).
pub const DEFAULT_STOCK_MEMORY_BYTES: usize = 1 << 30;
/// Memory of a raster per cell, bytes: the cell's byte, a u32 count per block of 16 × 16
/// cells, and per tile of 8 × 8 cells a count and four neighbourhood counts (1 + 4/256 +
/// 5/64 ≈ 1.09), rounded up.
pub const RASTER_BYTES_PER_CELL: f64 = 1.1;
/// Bytes in a mebibyte, the unit the warnings give the budget in.
pub const MIB: f64 = 1024.0 * 1024.0;
/// Decimals of the cells the warnings give, mm (a micrometre: the finest cell is 2 µm).
const CELL_DECIMALS: usize = 3;

/// Most slices an analysis keeps, whatever its budget: a bound on the work per sample too
/// (a cylinder's probe walks the slices up from the deepest cut to the first that does not
/// engage; a shaped tool's probes each slice in its corner). A level needs a slice's height
/// ([`super::levels::MIN_SLICE_MM`]) and ten tool diameters of flat cutting to be wanted:
/// 4000 such levels are a 200 mm deep z-level program at 0.05 mm steps.
pub const MOST_SLICES: usize = 4000;

/// How many slices of rasters of `cells` cells each fit in `budget_bytes`.
pub fn slices_that_fit(budget_bytes: usize, cells: usize) -> usize {
    (budget_bytes as f64 / (cells.max(1) as f64 * RASTER_BYTES_PER_CELL)).floor() as usize
}

/// The slices an analysis keeps of the `wanted`, when `fit` fit in its budget: all the
/// wanted that fit, and never fewer than [`MAX_SLICES`] (the cell is coarsened for those)
/// nor more than [`MOST_SLICES`].
pub fn slices_kept(wanted: usize, fit: usize) -> usize {
    wanted.min(fit.max(MAX_SLICES)).min(MOST_SLICES)
}

/// The slices the analysis of `spec` keeps of the `wanted`, and the cell it wants, mm: on
/// the grid of the stock it starts from, if any, else on the wanted cell over `bounds`.
pub fn slices_within(spec: &AnalysisSpec, wanted: usize, bounds: Rect, grid: Option<Grid>) -> (usize, f64) {
    let (cell_mm, cells) = match grid {
        Some(g) => (g.cell_mm, g.cells()),
        None => {
            let cell_mm = wanted_cell_mm(spec);
            (cell_mm, Raster::cell_count(bounds, cell_mm))
        }
    };
    (slices_kept(wanted, slices_that_fit(spec.stock_memory_bytes, cells)), cell_mm)
}

/// The raster cell the analysis of `spec` wants, before the budget, mm.
pub fn wanted_cell_mm(spec: &AnalysisSpec) -> f64 {
    let d = spec.tool.diameter_mm;
    spec.cell_mm.unwrap_or((super::CELL_PER_DIAMETER * d).clamp(super::MIN_CELL_MM, super::MAX_CELL_MM))
}

/// The sample spacing and raster cell an analysis of `spec` uses on `slices` slices over
/// `bounds`: the wanted cell, coarsened where the slices' rasters would not fit in the
/// spec's budget.
pub fn resolution(spec: &AnalysisSpec, bounds: Rect, slices: usize) -> (f64, f64) {
    let d = spec.tool.diameter_mm;
    let spacing =
        spec.sample_spacing_mm.unwrap_or((super::SPACING_PER_DIAMETER * d).min(super::DEFAULT_MAX_SPACING_MM));
    let area = (bounds.x_max - bounds.x_min) * (bounds.y_max - bounds.y_min);
    let floor = (area * slices as f64 * RASTER_BYTES_PER_CELL / spec.stock_memory_bytes as f64).sqrt();
    (spacing, wanted_cell_mm(spec).max(floor))
}

/// What the budget did to an analysis of `spec` that wanted `wanted` (slices, cell in mm)
/// and keeps `kept`, said in its warnings: `None` when it kept every wanted slice at the
/// wanted cell.
pub fn warning(spec: &AnalysisSpec, wanted: (usize, f64), kept: (usize, f64)) -> Option<String> {
    let ((wanted_slices, wanted_cell), (slices, cell_mm)) = (wanted, kept);
    let budget = format!("the stock memory budget ({} MiB)", spec.stock_memory_bytes as f64 / MIB);
    let mm = |v: f64| format!("{v:.CELL_DECIMALS$} mm");
    let merged = (slices < wanted_slices).then(|| {
        format!(
            "levels merged to {slices} slices of the {wanted_slices} the program cuts at: {budget} holds no more at a {} cell",
            mm(cell_mm)
        )
    });
    let coarsened = (cell_mm > wanted_cell).then(|| {
        format!(
            "the raster cell coarsened from {} to {}: {budget} holds no more than {slices} slices of finer ones",
            mm(wanted_cell),
            mm(cell_mm)
        )
    });
    match (merged, coarsened) {
        (Some(m), Some(c)) => Some(format!("{m}; {c}")),
        (m, c) => m.or(c),
    }
}
