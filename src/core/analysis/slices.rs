//! The stock of a layer as a stack of z slices, each a raster (MODEL.md §6): slice
//! boundaries follow the z levels the program cuts at, so a 2.5-D program is simulated
//! exactly and a 3-D one in steps.
//!
//! Every slice starts as the same raster, and a tool removes material from the slices
//! above its tip, a run of slices from the top: so a slice's material always lies inside
//! the material of the slice below it. Above a slice with no material near the tool,
//! none has any.

use crate::core::stock::{BlockRange, CapsuleRows, Raster, Rect};
use crate::core::toolpath::{Motion, Toolpath};

/// z levels closer than this are one level, mm.
pub const MIN_SLICE_MM: f64 = 0.05;
/// Most slices one analysis keeps (the thinnest are merged beyond it).
pub const MAX_SLICES: usize = 16;
/// A tool tip this close to a slice top does not cut the slice, mm.
pub const Z_CONTACT_EPS_MM: f64 = 1e-6;

/// One z slice of the stock.
pub struct Slice {
    pub z_bottom: f64,
    pub z_top: f64,
    pub raster: Raster,
    /// Blocks last found to hold no material: material is only ever removed during a
    /// simulation, so they stay empty.
    empty: Option<BlockRange>,
    /// The last capsule applied to the raster (see [`Slice::take_capsule`]).
    last_capsule: Option<TakenCapsule>,
}

/// A capsule applied to a slice's raster: which one, and the raster's versions before
/// and after it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct TakenCapsule {
    /// Numbers the capsules of one simulation: slices given the same capsule share it.
    pub serial: u64,
    pub version_before: u64,
    pub version_after: u64,
}

impl Slice {
    pub fn new(z_top: f64, z_bottom: f64, raster: Raster) -> Slice {
        Slice { z_bottom, z_top, raster, empty: None, last_capsule: None }
    }

    /// Applies capsule number `serial` to the raster ([`Raster::clear_capsule_rows`]),
    /// remembering it when it was applied. Returns `false` when no material lies near it.
    pub fn take_capsule(&mut self, serial: u64, capsule: &mut CapsuleRows) -> bool {
        let version_before = self.raster.version();
        let applied = self.raster.clear_capsule_rows(capsule);
        self.last_capsule =
            applied.then(|| TakenCapsule { serial, version_before, version_after: self.raster.version() });
        applied
    }

    /// The last capsule applied to the raster, if the raster has not changed otherwise
    /// since (every change to a slice's raster during a simulation is a capsule).
    pub fn last_capsule(&self) -> Option<TakenCapsule> {
        self.last_capsule.filter(|t| t.version_after == self.raster.version())
    }

    /// As [`Raster::any_material_near`], remembering an empty answer: while the tool
    /// stays over the same empty blocks, no block is read again.
    pub fn any_material_near(&mut self, x: f64, y: f64, reach_mm: f64) -> bool {
        let Some(blocks) = self.raster.blocks_near(x, y, reach_mm) else {
            return false;
        };
        if self.empty.is_some_and(|e| e.contains(&blocks)) {
            return false;
        }
        let any = self.raster.any_material_in(blocks);
        if !any {
            self.empty = Some(blocks);
        }
        any
    }
}

/// The slice boundaries for `path` in a layer from `z_bottom` to `z_top`, top first.
pub fn slice_levels(path: &Toolpath, z_bottom: f64, z_top: f64) -> Vec<f64> {
    let mut levels: Vec<f64> = path
        .moves
        .iter()
        .filter(|m| !matches!(m.motion, Motion::Rapid))
        .flat_map(|m| [m.start.z, m.end.z])
        .filter(|&z| z < z_top - MIN_SLICE_MM && z > z_bottom + MIN_SLICE_MM)
        .collect();
    levels.push(z_top);
    levels.push(z_bottom);
    levels.sort_by(|a, b| b.total_cmp(a));
    let mut merged: Vec<f64> = Vec::with_capacity(levels.len());
    for z in levels {
        match merged.last() {
            Some(&last) if last - z < MIN_SLICE_MM => {}
            _ => merged.push(z),
        }
    }
    // Keep the bottom exact.
    if let Some(last) = merged.last_mut() {
        *last = z_bottom;
    }
    while merged.len() > MAX_SLICES + 1 {
        // Merge the thinnest slice into its neighbour by dropping an inner level.
        let thinnest = (1..merged.len() - 1)
            .min_by(|&a, &b| (merged[a - 1] - merged[a + 1]).total_cmp(&(merged[b - 1] - merged[b + 1])))
            .unwrap_or(1);
        merged.remove(thinnest);
    }
    merged
}

/// Builds the slices with material painted by `paint`.
pub fn build(levels: &[f64], bounds: Rect, cell_mm: f64, paint: impl Fn(&mut Raster)) -> Vec<Slice> {
    let mut first = Raster::new(bounds, cell_mm);
    paint(&mut first);
    levels.windows(2).map(|w| Slice::new(w[0], w[1], first.clone())).collect()
}

/// How many slices (from the top) a tool tip at `z` cuts.
pub fn slices_cut(slices: &[Slice], z: f64) -> usize {
    slices.iter().take_while(|s| z < s.z_top - Z_CONTACT_EPS_MM).count()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::core::toolpath::{Move, Units, P3};

    fn at_z(z: &[f64]) -> Toolpath {
        let moves = z
            .iter()
            .map(|&z| Move {
                motion: Motion::Linear,
                start: P3::new(0.0, 0.0, z),
                end: P3::new(1.0, 0.0, z),
                feed_mm_min: Some(100.0),
                spindle_rpm: None,
                tool: None,
                line: 1,
            })
            .collect();
        Toolpath { moves, events: vec![], source_units: Units::Mm, warnings: vec![] }
    }

    #[test]
    fn slices_follow_the_cutting_levels_of_a_layered_program() {
        let levels = slice_levels(&at_z(&[-10.0, -20.0, -30.0, -20.01]), -32.0, 0.0);
        assert_eq!(levels, vec![0.0, -10.0, -20.0, -30.0, -32.0]);
    }

    #[test]
    fn a_three_d_program_is_capped_at_the_slice_limit() {
        let z: Vec<f64> = (0..200).map(|i| -0.1 * i as f64).collect();
        let levels = slice_levels(&at_z(&z), -25.0, 0.0);
        assert_eq!(levels.len(), MAX_SLICES + 1);
        assert!((levels[0] - 0.0).abs() < 1e-12 && (levels[MAX_SLICES] + 25.0).abs() < 1e-12);
    }
}
