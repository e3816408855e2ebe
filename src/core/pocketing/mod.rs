//! Contour-parallel roughing of a pocket (MODEL.md §8 step 4, seed 004 Table 1): successive
//! offsets of the contour at the radial depth of cut, written as lines and true arcs, cut
//! from the inside out in the climb direction and linked into one continuous path.
//!
//! # Geometry
//!
//! The tool centre may go where every point of the wall (outer loop and islands) is at least
//! `r + allowance` away: the first offset of the pocket by `r + allowance` (outer loop inward,
//! islands outward). Each next loop is that region offset by a further `Rd`
//! ([`PocketingSpec::radial_depth_mm`]) until nothing is left. The offsets are
//! `cavalier_contours` shape offsets, which keep arcs as arcs (the outer loop's convex corners
//! stay sharp inward, an island's corners become arcs of radius `r + allowance + k·Rd`),
//! handle islands and split the region where it narrows.
//!
//! Every point of the first offset region lies less than `Rd` from one of the loops (a point
//! not in offset `k + 1` is closer than `Rd` to loop `k`), so with `Rd ≤ r` the tool sweeps the
//! whole region `r + allowance` from the walls: no ridge between loops, no core left in the
//! middle, no cusp at the sharp corners of the inner loops. Between straight parallel loops
//! `Rd < 2r` would already leave no ridge, but the corners of the inner loops and the last
//! core need `Rd ≤ r`, which [`contour_parallel`] therefore requires. What the tool cannot
//! reach at all (inner corners of the wall, necks narrower than `2(r + allowance)`) stays:
//! that is the rest-machining planner's business, not this module's.
//!
//! # Direction (climb milling)
//!
//! The spindle turns clockwise seen from above (M3, a right-hand tool). Climb (down) milling
//! has each tooth enter the chip at its thickest and leave it at the finished surface, which
//! with a clockwise tool happens when the material lies to the **right** of the direction of
//! travel (the G41 side). Around the outer wall of a pocket the material is outside the loop,
//! so climb milling runs **counter-clockwise** seen from +Z; around an island the material is
//! inside the island, so the tool runs **clockwise**. In general every loop keeps its offset
//! region on its left, which is the orientation `cavalier_contours` returns; conventional
//! milling (`climb: false`) reverses every loop.
//!
//! # Order and links
//!
//! The offsets form a tree (a region may split into several as it shrinks). Each branch is
//! cut from its innermost loop outwards, ending with the finishing pass `r + allowance` from
//! the wall; a region whose branches have all been cut is cut after them. Within a branch the
//! next loop starts at the point nearest to where the last one ended and is reached by a
//! straight feed move, kept only if it stays inside the region of that loop (so it can cross
//! no island and gouge no wall). Where a straight link is not possible, and at the start of
//! every branch, the tool retracts to `safe_z_mm`, moves over at the rapid rate and plunges at
//! the plunge feed; these entry points are listed in [`PocketPath::entries`] so that the caller
//! can open them first (helical boring or a pre-drilled hole, MODEL.md §8 step 1).
//!
//! # Corner loops
//!
//! With [`PocketingSpec::corner_loops`], every sharp corner where a ring turns towards its
//! region (by [`CORNER_LOOP_MIN_TURN_DEG`] or more) gets a circle before it, cut first, so
//! that the corner, deeper than the sides, is cut in two steps of about half its depth
//! (seed 004 §3.3, Fig. 11: what the expert's CAM did for the conventional baseline). The
//! circle's size and place, and where it is left out, are in [`corners`]. The innermost
//! loop of each branch is slotted and gets none.

mod corners;
pub use corners::{corner_loop_radius_mm, CornerLoop, CORNER_LOOP_MIN_TURN_DEG};
mod emit;
mod offsets;
pub use offsets::unreachable_area_mm2;
mod order;
mod seam;

use crate::core::error::{require_finite, require_positive};
use crate::core::geometry::{fmt_mm, Pocket};
use crate::core::toolpath::Toolpath;
use crate::core::CoreError;
use serde::{Deserialize, Serialize};

/// Most offset loops one region may need (beyond it the step-over is too small for the pocket).
pub const MAX_OFFSET_LEVELS: usize = 10_000;

/// How to rough a pocket with contour-parallel loops.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct PocketingSpec {
    /// Radius of the end mill `r` (mm).
    pub tool_radius_mm: f64,
    /// Radial depth of cut `Rd`: the step-over between successive loops (mm), `0 < Rd ≤ r`.
    pub radial_depth_mm: f64,
    /// Stock left on the walls and islands for the finishing pass (mm, ≥ 0).
    #[serde(default)]
    pub allowance_mm: f64,
    /// z of the tool tip while cutting (mm).
    pub z_mm: f64,
    /// z the tool retracts to between regions (mm), above `z_mm`.
    pub safe_z_mm: f64,
    /// Feed along the loops and links (mm/min).
    pub feed_mm_min: f64,
    /// Feed of the plunges (mm/min).
    pub plunge_feed_mm_min: f64,
    /// Spindle speed (min⁻¹); the spindle turns clockwise (M3).
    pub spindle_rpm: f64,
    /// Climb milling (default) or conventional milling; see the module documentation.
    #[serde(default = "climb_by_default")]
    pub climb: bool,
    /// Cut each sharp corner of a ring in two steps, a circle to about half its depth and
    /// then the ring (seed 004 §3.3; see the module documentation). Off by default: the
    /// circles lengthen the path, and the proposed plan meets its corners with its
    /// constant-force feeds instead (seed 004 §3.2: the tool load variation at the corners
    /// "can be avoided by the feedrate optimization"). The conventional baseline uses them.
    #[serde(default)]
    pub corner_loops: bool,
}

fn climb_by_default() -> bool {
    true
}

/// The roughing path of a pocket and what the caller needs to know about it.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PocketPath {
    /// The moves: positioning, plunges, loops (lines and XY arcs), links and retracts.
    pub toolpath: Toolpath,
    /// Number of closed loops cut (finishing passes around the islands included).
    pub loops: usize,
    /// Number of corner loops cut (0 unless [`PocketingSpec::corner_loops`]).
    pub corner_loops: usize,
    /// Number of separate regions of the first offset: parts of the pocket the tool reaches
    /// only by leaving the material (a wide pocket with a narrow neck has two).
    pub regions: usize,
    /// XY of every plunge, in path order (mm): the first is the start of the path. Each is
    /// where a branch of the offsets begins or a straight link was not possible; open these
    /// points first (helical boring, pre-drilled hole).
    pub entries: Vec<(f64, f64)>,
    /// Things the caller should know (e.g. extra plunges).
    pub warnings: Vec<String>,
}

/// Contour-parallel roughing loops for `pocket` (see the module documentation).
///
/// Errors name the refused field of `spec`; a pocket the tool fits nowhere in is refused with
/// "the tool (r = …) does not fit in the pocket".
pub fn contour_parallel(pocket: &Pocket, spec: &PocketingSpec) -> Result<PocketPath, CoreError> {
    check(spec)?;
    let wall_mm = spec.tool_radius_mm + spec.allowance_mm;
    let tree = offsets::offset_tree(pocket, wall_mm, spec.radial_depth_mm)?;
    if tree.roots.is_empty() {
        return Err(CoreError::unsolvable(
            "tool_radius_mm",
            format!(
                "the tool (r = {} mm) does not fit in the pocket: with the allowance of {} mm it needs a width of at least {} mm",
                fmt_mm(spec.tool_radius_mm),
                fmt_mm(spec.allowance_mm),
                fmt_mm(2.0 * wall_mm)
            ),
        ));
    }
    let cut = order::cut(&tree, spec);
    let mut warnings = Vec::new();
    if cut.entries.len() > tree.roots.len() {
        warnings.push(format!(
            "the path enters the material {} times for {} region(s): the offsets split where the pocket narrows; open each entry first",
            cut.entries.len(),
            tree.roots.len()
        ));
    }
    Ok(PocketPath {
        toolpath: cut.toolpath,
        loops: cut.loops,
        corner_loops: cut.corner_loops,
        regions: tree.roots.len(),
        entries: cut.entries,
        warnings,
    })
}

/// Checks the ranges of `spec`.
fn check(spec: &PocketingSpec) -> Result<(), CoreError> {
    let r = require_positive("tool_radius_mm", spec.tool_radius_mm)?;
    let rd = require_positive("radial_depth_mm", spec.radial_depth_mm)?;
    if rd > r {
        return Err(CoreError::invalid(
            "radial_depth_mm",
            format!(
                "must be at most the tool radius ({} mm), got {} mm: larger step-overs leave uncut material at the corners of the loops",
                fmt_mm(r),
                fmt_mm(rd)
            ),
        ));
    }
    let allowance = require_finite("allowance_mm", spec.allowance_mm)?;
    if allowance < 0.0 {
        return Err(CoreError::invalid("allowance_mm", format!("must be ≥ 0, got {allowance}")));
    }
    let z = require_finite("z_mm", spec.z_mm)?;
    let safe_z = require_finite("safe_z_mm", spec.safe_z_mm)?;
    if safe_z <= z {
        return Err(CoreError::invalid("safe_z_mm", format!("must be above z_mm ({z} mm), got {safe_z} mm")));
    }
    require_positive("feed_mm_min", spec.feed_mm_min)?;
    require_positive("plunge_feed_mm_min", spec.plunge_feed_mm_min)?;
    require_positive("spindle_rpm", spec.spindle_rpm)?;
    Ok(())
}

#[cfg(test)]
mod clearance_tests;
#[cfg(test)]
mod proptests;
#[cfg(test)]
pub(crate) mod test_support;
#[cfg(test)]
mod tests;
