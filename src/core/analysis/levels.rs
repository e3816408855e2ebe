//! The z levels that bound a layer's stock slices (MODEL.md §6, issue 32 item 2).
//!
//! The candidates are the heights the program's feed moves start and end at, a run of
//! moves that continue one another (see [`super::continued`]) counted as the one move it
//! is: how a path is split does not change its slices. Candidates closer than
//! [`MIN_SLICE_MM`] are one level. Every level the program cuts flat for a real length (a
//! *layer level*: a roughing or finishing layer, see [`Levels::of`]) is wanted; the other
//! levels (ramp ends, the stepovers of a 3-D pass) are merged down to [`MAX_SLICES`]
//! slices. Where the stock memory budget holds fewer slices than wanted (see
//! [`super::budget`]), levels are merged further, layer levels last: a slice that a
//! layer's passes cut only a sliver of would lose, for every later pass, the material the
//! layer left below it.

use super::continued::continues;
use super::slices::Z_CONTACT_EPS_MM;
use crate::core::toolpath::move_length;
use crate::core::toolpath::{Motion, Move, Plane, Toolpath};

/// z levels closer than this are one level, mm.
pub const MIN_SLICE_MM: f64 = 0.05;
/// Levels this much closer than [`MIN_SLICE_MM`] are still apart: layers a program steps
/// down by exactly the smallest slice differ by it only up to rounding, mm.
pub(super) const LEVEL_ROUNDING_MM: f64 = 1e-9;
/// Slices the levels that are not layer levels are merged down to, and the fewest slices
/// the stock memory budget may leave (below it the cell is coarsened instead).
pub const MAX_SLICES: usize = 16;
/// A level the program cuts flat for at least this share of its feed length is a layer
/// level (a roughing or finishing layer). The flat stepovers of a 3-D finishing pass (a
/// fraction of a millimetre each) stay far below it; each layer of a program that roughs
/// in up to fifty layers reaches it (deeper programs' layers reach
/// [`LAYER_LEVEL_DIAMETERS`]).
pub const LAYER_LEVEL_SHARE: f64 = 0.02;
/// A level the program cuts flat for at least this many tool diameters is a layer level
/// too, whatever its share: each of the 58 layers of a z-level roughing (under 2 % of its
/// feed length each) cuts far more, and a stepover of a 3-D pass far less.
pub const LAYER_LEVEL_DIAMETERS: f64 = 10.0;

/// A level: its z, the flat length cut at that z itself, and the flat length of all the
/// heights merged into it, mm.
#[derive(Debug, Clone, Copy)]
struct Level {
    z: f64,
    flat_at_z_mm: f64,
    flat_mm: f64,
}

/// The levels of a layer's slices, top first, bottom last.
#[derive(Debug, Clone)]
pub struct Levels {
    levels: Vec<Level>,
    /// 1 when the level above the bottom is the program's floor (kept, as the top and
    /// the bottom are), else 0.
    floor: usize,
    /// A level cut flat for at least this is a layer level, mm.
    layer_mm: f64,
}

impl Levels {
    /// The levels `path` cuts at in a layer from `z_bottom` to `z_top`, with a tool of
    /// `tool_diameter_mm`, before any is merged for the slice limit or the budget.
    ///
    /// Each candidate weighs the XY length the path cuts flat at it. Candidates closer
    /// than [`MIN_SLICE_MM`] are one level, at the heaviest of them (the highest on a
    /// tie), weighing all of them: a layer a program roughs at stays exact beside the end
    /// of a ramp just above it. A level weighing at least [`LAYER_LEVEL_SHARE`] of the
    /// feed length or [`LAYER_LEVEL_DIAMETERS`] tool diameters is a layer level. The top,
    /// the bottom and the deepest level the program cuts (its floor, at the deepest height
    /// among those merged into it) are never merged away.
    pub fn of(path: &Toolpath, z_bottom: f64, z_top: f64, tool_diameter_mm: f64) -> Levels {
        let mut candidates: Vec<(f64, f64)> = runs(path)
            .into_iter()
            // A flat run's length counts once, at its level.
            .flat_map(|r| [(r.start_z, r.flat_mm), (r.end_z, 0.0)])
            .filter(|&(z, _)| z < z_top - MIN_SLICE_MM && z > z_bottom + MIN_SLICE_MM)
            .collect();
        candidates.sort_by(|a, b| b.0.total_cmp(&a.0));
        // Candidates at one height are one, their lengths summed, at the z of the longest
        // flat run among them (a layer stays exact beside a ramp's end a rounding above it):
        // (z, the summed length, the longest).
        let mut heights: Vec<(f64, f64, f64)> = Vec::with_capacity(candidates.len());
        for (z, flat_mm) in candidates {
            match heights.last_mut() {
                Some(last) if last.0 - z <= Z_CONTACT_EPS_MM => {
                    if flat_mm > last.2 {
                        (last.0, last.2) = (z, flat_mm);
                    }
                    last.1 += flat_mm;
                }
                _ => heights.push((z, flat_mm, flat_mm)),
            }
        }
        let deepest = heights.last().map(|h| h.0);
        let fixed = Level { z: z_top, flat_at_z_mm: f64::INFINITY, flat_mm: f64::INFINITY };
        let mut levels: Vec<Level> = Vec::with_capacity(heights.len() + 2);
        levels.push(fixed);
        for (z, flat_mm, _) in heights {
            match levels.last_mut() {
                Some(last) if last.z - z < MIN_SLICE_MM - LEVEL_ROUNDING_MM => {
                    if flat_mm > last.flat_at_z_mm {
                        (last.z, last.flat_at_z_mm) = (z, flat_mm);
                    }
                    last.flat_mm += flat_mm;
                }
                _ => levels.push(Level { z, flat_at_z_mm: flat_mm, flat_mm }),
            }
        }
        // The deepest level the program cuts is its floor: the stock below it is never cut,
        // and a slice reaching past it would be cut through. It lies at the deepest height
        // of its level (not the heaviest), and is kept, as the top and bottom are.
        let floor = usize::from(levels.len() > 1);
        if let (Some(z), true, Some(last)) = (deepest, floor == 1, levels.last_mut()) {
            last.z = z;
        }
        levels.push(Level { z: z_bottom, ..fixed });
        let feed_mm: f64 = path.moves.iter().filter(|m| !matches!(m.motion, Motion::Rapid)).map(move_length).sum();
        let layer_mm = (LAYER_LEVEL_SHARE * feed_mm).min(LAYER_LEVEL_DIAMETERS * tool_diameter_mm);
        Levels { levels, floor, layer_mm }
    }

    /// The levels the analysis wants: every layer level, and as many of the others as
    /// leave [`MAX_SLICES`] slices (none when the layer levels alone make more).
    pub fn wanted(mut self) -> Levels {
        self.merge_to(MAX_SLICES, false);
        self
    }

    /// These levels merged down to `slices` slices, the levels that are not layer levels
    /// first; never the top, the floor or the bottom.
    pub fn merged_to(mut self, slices: usize) -> Levels {
        self.merge_to(slices, true);
        self
    }

    /// The number of slices between the levels.
    pub fn slices(&self) -> usize {
        self.levels.len() - 1
    }

    /// The levels' z, top first, mm.
    pub fn z(&self) -> Vec<f64> {
        self.levels.iter().map(|l| l.z).collect()
    }

    /// Merges inner levels away one by one down to `slices` slices, always the one whose
    /// neighbours are closest, taken first among the levels that are not layer levels;
    /// layer levels only when `layers_too`.
    fn merge_to(&mut self, slices: usize, layers_too: bool) {
        let layer_mm = self.layer_mm;
        while self.levels.len() > slices + 1 {
            let inner = 1..self.levels.len() - 1 - self.floor;
            let light = inner.clone().any(|i| self.levels[i].flat_mm < layer_mm);
            if !light && !layers_too {
                return;
            }
            // The thinnest slice two neighbours would make, among the lighter levels if any.
            let levels = &self.levels;
            let gap = |i: usize| levels[i - 1].z - levels[i + 1].z;
            let drop =
                inner.filter(|&i| !light || levels[i].flat_mm < layer_mm).min_by(|&a, &b| gap(a).total_cmp(&gap(b)));
            match drop {
                Some(i) => self.levels.remove(i),
                None => return,
            };
        }
    }
}

/// The slice boundaries for `path` in a layer from `z_bottom` to `z_top`, top first: the
/// levels [`Levels::wanted`] with layer levels by their share of the feed length alone
/// (the analysis also counts them by the tool's diameter, and merges them to its memory
/// budget).
pub fn slice_levels(path: &Toolpath, z_bottom: f64, z_top: f64) -> Vec<f64> {
    Levels::of(path, z_bottom, z_top, f64::INFINITY).wanted().z()
}

/// A run of feed moves that continue one another: where it starts and ends, and the
/// length of its moves that cut flat, mm.
struct Run {
    start_z: f64,
    end_z: f64,
    flat_mm: f64,
}

/// The runs of feed moves of `path`, in order: each move that continues the one before
/// it (see [`continues`]) joins its run.
fn runs(path: &Toolpath) -> Vec<Run> {
    let mut runs: Vec<Run> = Vec::new();
    let mut previous: Option<&Move> = None;
    for m in &path.moves {
        if matches!(m.motion, Motion::Rapid) {
            previous = None;
            continue;
        }
        let flat_mm = if cuts_flat(m) { move_length(m) } else { 0.0 };
        match (previous, runs.last_mut()) {
            (Some(p), Some(run)) if continues(p, m) => {
                run.end_z = m.end.z;
                run.flat_mm += flat_mm;
            }
            _ => runs.push(Run { start_z: m.start.z, end_z: m.end.z, flat_mm }),
        }
        previous = Some(m);
    }
    runs
}

/// `true` when the move cuts at one z level: a line or an arc in the XY plane whose ends
/// lie at the same height.
fn cuts_flat(m: &Move) -> bool {
    let in_xy = match m.motion {
        Motion::Linear => true,
        Motion::Arc { plane, .. } => plane == Plane::Xy,
        Motion::Rapid => false,
    };
    in_xy && (m.end.z - m.start.z).abs() <= Z_CONTACT_EPS_MM
}

#[cfg(test)]
#[path = "levels_tests.rs"]
mod tests;
