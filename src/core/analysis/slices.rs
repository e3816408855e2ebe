//! The stock of a layer as a stack of z slices, each a raster (MODEL.md §6): slice
//! boundaries follow the z levels the program cuts at (see [`super::levels`]), so a 2.5-D
//! program is simulated exactly and a 3-D one in steps.
//!
//! Every slice starts as the same raster, and a tool removes material from the slices
//! above its tip, a run of slices from the top: so a slice's material always lies inside
//! the material of the slice below it. Above a slice with no material near the tool,
//! none has any. Slices still alike share one stock (see [`super::stack`]).

pub use super::levels::{slice_levels, LAYER_LEVEL_SHARE, MAX_SLICES, MIN_SLICE_MM};
use crate::core::stock::{ArcRows, BlockRange, CapsuleRows, Raster, WriteMark};

/// A tool tip this close to a slice top does not cut the slice, mm.
pub const Z_CONTACT_EPS_MM: f64 = 1e-6;

/// The stock of one z slice (see [`super::stack`] for slices that share one).
#[derive(Clone)]
pub struct SliceStock {
    pub raster: Raster,
    /// Blocks last found to hold no material: material is only ever removed during a
    /// simulation, so they stay empty.
    empty: Option<BlockRange>,
    /// The block (column, row) last found to hold material: it is looked at first, since
    /// it most often still does.
    material_at: Option<(usize, usize)>,
    /// The last capsule applied to the raster (see [`SliceStock::take_capsule`]).
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

impl SliceStock {
    pub fn new(raster: Raster) -> SliceStock {
        SliceStock { raster, empty: None, material_at: None, last_capsule: None }
    }

    /// Makes this stock `source` again, in the memory it holds: with `since`, a copy of
    /// `source` taken when `source`'s raster handed out the mark, only the cells written
    /// since ([`Raster::copy_written_since`]); without, every cell.
    pub fn copy_from(&mut self, source: &SliceStock, since: Option<WriteMark>) {
        match since {
            Some(mark) => {
                self.raster.copy_written_since(&source.raster, mark);
            }
            None => self.raster.copy_from(&source.raster),
        }
        let SliceStock { raster: _, empty, material_at, last_capsule } = source;
        (self.empty, self.material_at, self.last_capsule) = (*empty, *material_at, *last_capsule);
    }

    /// Applies capsule number `serial` to the raster ([`Raster::clear_capsule_rows`]),
    /// remembering it when it was applied. Returns `false` when no material lies near it.
    /// (A stock two slices share takes it once for both.)
    pub fn take_capsule(&mut self, serial: u64, capsule: &mut CapsuleRows) -> bool {
        self.take(serial, |raster| raster.clear_capsule_rows(capsule))
    }

    /// Applies arc number `serial` (numbered with the capsules) to the raster
    /// ([`Raster::clear_arc_rows`]), as [`SliceStock::take_capsule`] does a capsule.
    pub fn take_arc(&mut self, serial: u64, arc: &mut ArcRows) -> bool {
        self.take(serial, |raster| raster.clear_arc_rows(arc))
    }

    /// Applies update number `serial` with `apply`, remembering it when it was applied.
    fn take(&mut self, serial: u64, apply: impl FnOnce(&mut Raster) -> bool) -> bool {
        let version_before = self.raster.version();
        let applied = apply(&mut self.raster);
        self.last_capsule =
            applied.then(|| TakenCapsule { serial, version_before, version_after: self.raster.version() });
        applied
    }

    /// The last capsule applied to the raster, if the raster has not changed otherwise
    /// since (every change to a slice's raster during a simulation is a capsule).
    pub fn last_capsule(&self) -> Option<TakenCapsule> {
        self.last_capsule.filter(|t| t.version_after == self.raster.version())
    }

    /// As [`Raster::any_material_near`], remembering the answers: while the tool stays
    /// over the same empty blocks, no block is read again, and while a block found to hold
    /// material lies under the tool and still does, no other is read.
    pub fn any_material_near(&mut self, x: f64, y: f64, reach_mm: f64) -> bool {
        let Some(blocks) = self.raster.blocks_near(x, y, reach_mm) else {
            return false;
        };
        if self.material_at.is_some_and(|at| blocks.holds(at) && self.raster.block_holds_material(at)) {
            return true;
        }
        if self.empty.is_some_and(|e| e.contains(&blocks)) {
            return false;
        }
        match self.raster.first_material_block_in(blocks) {
            Some(at) => {
                self.material_at = Some(at);
                true
            }
            None => {
                self.empty = Some(blocks);
                false
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::core::stock::Rect;

    #[test]
    fn material_near_is_looked_up_again_once_the_block_that_held_it_is_cleared() {
        let rect = Rect { x_min: 0.0, y_min: 0.0, x_max: 20.0, y_max: 20.0 };
        let mut raster = Raster::new(rect, 0.1);
        crate::core::analysis::region::paint(
            &mut raster,
            &[crate::core::analysis::region::StockRegion::Rect(rect)],
            &[],
            &crate::core::progress::NoProgress,
        )
        .expect("nothing cancels the painting");
        let mut slice = SliceStock::new(raster);
        assert!(slice.any_material_near(10.0, 10.0, 2.0));
        let first = slice.material_at.expect("the block with material is remembered");
        // The block found first goes; others near the tool still hold material.
        slice.raster.clear_capsule((8.0, 8.0), (8.0, 8.0), 2.5);
        assert!(!slice.raster.block_holds_material(first), "the remembered block still holds material");
        assert!(slice.any_material_near(10.0, 10.0, 2.0));
        assert_ne!(slice.material_at, Some(first));
        // All of it goes.
        slice.raster.clear_capsule((10.0, 10.0), (10.0, 10.0), 6.0);
        assert!(!slice.any_material_near(10.0, 10.0, 2.0));
    }
}
