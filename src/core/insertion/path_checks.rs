//! What the finished path's geometry alone tells the report: which treatment removes each
//! part of the pocket, what the tool can reach but nothing removes, and where the path comes
//! closer to the walls than it may. None of it needs the stock simulation, so it is found
//! beside the verification, on a core of its own.

use super::cleared::SAME_LEVEL_MM;
use super::compose::LevelMoves;
use super::coverage::Coverage;
use super::spec::InsertionSpec;
use super::verify::{check_gouges, Spot};
use crate::core::geometry::{Pocket, Point};
use crate::core::medial::Boundary;
use crate::core::toolpath::Toolpath;

/// Points closer than this to the reachable area's edge are not counted as left over, mm
/// (the coverage raster's resolution).
const COVERAGE_TOLERANCE_CELLS: f64 = 2.0;

/// The geometric checks of a finished path.
pub struct PathChecks {
    /// Which stretch (by index; [`PathChecks::base_owner`] for the base path) removed each
    /// cell of the pocket first.
    pub coverage: Coverage,
    pub base_owner: u16,
    /// Area the tool can reach that nothing removes, mm², and a point of it.
    pub uncleared_mm2: f64,
    pub uncleared_at: Option<Point>,
    /// Samples closer to the walls than the tool radius plus the allowance, the smallest
    /// margin, and the first of them.
    pub gouges: usize,
    pub min_margin_mm: f64,
    pub first_gouge: Option<Spot>,
}

/// The coverage raster of `pocket` for the tool of `spec`, nothing removed yet, made on a
/// thread of its own: it depends on neither path, so it is made while the treatments are
/// planned and the path composed (where a core idles), not beside the verification.
pub fn coverage_beside(pocket: &Pocket, spec: &InsertionSpec) -> std::thread::JoinHandle<Coverage> {
    let (pocket, r) = (pocket.clone(), spec.r_mm());
    std::thread::spawn(move || Coverage::new(&pocket, &Boundary::of_pocket(&pocket), r))
}

/// Checks `path`, made of `stretch_count` stretches and the base path, whose moves per level
/// are `per_level`, at the cutting `levels`, in `pocket`, starting from its `coverage`
/// raster for the tool of `spec` with nothing removed.
pub fn check_path(
    pocket: &Pocket,
    boundary: &Boundary,
    spec: &InsertionSpec,
    (stretch_count, per_level): (usize, &[LevelMoves]),
    levels: &[f64],
    path: &Toolpath,
    mut coverage: Coverage,
) -> PathChecks {
    let r = spec.r_mm();
    let bottom = levels.iter().copied().fold(f64::INFINITY, f64::min);
    let base_owner = u16::try_from(stretch_count).unwrap_or(u16::MAX - 1);
    if let Some(last) = per_level.last() {
        for (i, moves) in last.stretch_moves.iter().enumerate() {
            coverage.stamp_moves(moves, r, bottom + SAME_LEVEL_MM, u16::try_from(i).unwrap_or(base_owner));
        }
        coverage.stamp_moves(&last.base, r, bottom + SAME_LEVEL_MM, base_owner);
    }
    let tol = COVERAGE_TOLERANCE_CELLS * coverage.cell_mm;
    let (uncleared_mm2, uncleared_at) =
        if bottom.is_finite() { coverage.left_over(r, spec.allowance_mm, tol) } else { (coverage.pocket_area(), None) };
    let (gouges, min_margin_mm, first_gouge) =
        check_gouges(path, pocket, boundary, r, spec.allowance_mm, spec.z_top_mm);
    PathChecks { coverage, base_owner, uncleared_mm2, uncleared_at, gouges, min_margin_mm, first_gouge }
}
