//! Which blocks of a raster's cells were written since a mark, so that a copy of the raster
//! taken earlier is brought up to date by copying those blocks alone
//! ([`Raster::copy_written_since`]) instead of every cell. The slices of a layer's stock
//! (see [`crate::core::analysis::stack`]) share one raster while they are alike and take a
//! copy each time an update cuts them apart: along a trochoid program the same slice is
//! cut apart, joined and cut apart again dozens of times, while its loops write a few
//! blocks of a raster of a million cells in between.

use super::{Raster, BLOCK_CELLS};

/// The blocks' last writes, as epochs: each mark starts a new one.
#[derive(Debug, PartialEq, Eq)]
pub(super) struct Written {
    /// The epoch writes now belong to; every mark handed out is older.
    epoch: u64,
    /// Per block (rows of `bx` blocks, as the raster's material counts), the epoch of its
    /// last write.
    at: Vec<u64>,
}

/// A point in a raster's writes: the blocks written after it are those
/// [`Raster::copy_written_since`] copies.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct WriteMark(u64);

impl Clone for Written {
    fn clone(&self) -> Written {
        Written { epoch: self.epoch, at: self.at.clone() }
    }

    /// Into the memory this one holds.
    fn clone_from(&mut self, source: &Written) {
        self.epoch = source.epoch;
        self.at.clone_from(&source.at);
    }
}

impl Written {
    /// `blocks` blocks, none written since any mark.
    pub(super) fn new(blocks: usize) -> Written {
        Written { epoch: 1, at: vec![0; blocks] }
    }

    /// Records a write of block `b`.
    #[inline]
    pub(super) fn stamp(&mut self, b: usize) {
        self.at[b] = self.epoch;
    }

    /// Records writes of blocks [b0, b1] (one row of blocks).
    #[inline]
    pub(super) fn stamp_run(&mut self, b0: usize, b1: usize) {
        self.at[b0..=b1].fill(self.epoch);
    }

    /// Records a write of every block.
    pub(super) fn stamp_all(&mut self) {
        self.at.fill(self.epoch);
    }
}

impl Raster {
    /// Records that cells [i0, i1) of row `j` were written.
    #[inline]
    pub(super) fn written_in_row(&mut self, j: usize, i0: usize, i1: usize) {
        if i0 < i1 {
            let row = (j / BLOCK_CELLS) * self.bx;
            self.written.stamp_run(row + i0 / BLOCK_CELLS, row + (i1 - 1) / BLOCK_CELLS);
        }
    }

    /// Records that the block holding cell (i, j) was written.
    #[inline]
    pub(super) fn written_at(&mut self, i: usize, j: usize) {
        self.written.stamp((j / BLOCK_CELLS) * self.bx + i / BLOCK_CELLS);
    }

    /// Marks the raster's writes so far: [`Raster::copy_written_since`] with the mark
    /// copies the blocks written after it.
    pub fn mark_writes(&mut self) -> WriteMark {
        let mark = WriteMark(self.written.epoch);
        self.written.epoch += 1;
        mark
    }

    /// Makes this raster `source` again, copying only the cells of the blocks `source` wrote
    /// since `mark` (and everything but its cells: counts, version, the capsule it
    /// remembers, its marks). This raster must have been a copy of `source` on its grid
    /// when `source` handed out `mark`: it then holds `source`'s cells in every block, but
    /// those where it differed from `source` already and was not written since (a stock's
    /// slices share one raster while they hold cells no probe tells apart, see
    /// [`Raster::probes_alike`]). Returns the cells copied.
    pub fn copy_written_since(&mut self, source: &Raster, mark: WriteMark) -> usize {
        if self.grid() != source.grid() || self.written.at.len() != source.written.at.len() {
            // Not a copy of it: every cell.
            self.copy_from(source);
            return self.f.len();
        }
        let (nx, bx) = (self.nx, self.bx);
        let written_since = |b: &u64| *b > mark.0;
        let mut copied = 0;
        for (by, row_of_blocks) in source.written.at.chunks(bx).enumerate() {
            let mut b = 0;
            while b < bx {
                if !written_since(&row_of_blocks[b]) {
                    b += 1;
                    continue;
                }
                // A run of blocks written, copied row by row.
                let first = b;
                while b < bx && written_since(&row_of_blocks[b]) {
                    b += 1;
                }
                let (i0, i1) = (first * BLOCK_CELLS, (b * BLOCK_CELLS).min(nx));
                for j in by * BLOCK_CELLS..((by + 1) * BLOCK_CELLS).min(self.ny) {
                    let cells = j * nx + i0..j * nx + i1;
                    self.f[cells.clone()].copy_from_slice(&source.f[cells]);
                    copied += i1 - i0;
                }
            }
        }
        self.copy_all_but_cells(source);
        copied
    }

    /// Makes this raster `source` again, every cell copied (into the memory it holds).
    pub fn copy_from(&mut self, source: &Raster) {
        self.f.clone_from(&source.f);
        self.copy_all_but_cells(source);
    }

    /// Everything of `source` but its cells.
    fn copy_all_but_cells(&mut self, source: &Raster) {
        let Raster {
            x0,
            y0,
            cell_mm,
            inv_cell,
            nx,
            ny,
            f: _,
            blocks,
            bx,
            tiles,
            end_disc_cleared,
            version,
            written,
            #[cfg(test)]
            update_every_cell,
            #[cfg(test)]
            band_cell_by_cell,
        } = source;
        (self.x0, self.y0, self.cell_mm, self.inv_cell, self.nx, self.ny) = (*x0, *y0, *cell_mm, *inv_cell, *nx, *ny);
        self.blocks.clone_from(blocks);
        self.bx = *bx;
        self.tiles.clone_from(tiles);
        self.end_disc_cleared = *end_disc_cleared;
        self.version = *version;
        self.written.clone_from(written);
        #[cfg(test)]
        {
            self.update_every_cell = *update_every_cell;
            self.band_cell_by_cell = *band_cell_by_cell;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::test_blocks::block;
    use super::super::{ArcRows, ArcSweep};
    use super::*;
    use proptest::prelude::*;

    /// One update of a raster: a capsule (a disc where both ends agree, a slot through
    /// the whole block, clearing whole tiles), or an arc.
    #[derive(Debug, Clone)]
    enum Update {
        Capsule((f64, f64), (f64, f64), f64),
        Arc { center: (f64, f64), from_rad: f64, sweep_rad: f64, radius_mm: f64, tool_mm: f64 },
    }

    impl Update {
        fn apply(&self, raster: &mut Raster) {
            match *self {
                Update::Capsule(a, b, r) => raster.clear_capsule(a, b, r),
                Update::Arc { center, from_rad, sweep_rad, radius_mm, tool_mm } => {
                    let at = |angle: f64| (center.0 + radius_mm * angle.cos(), center.1 + radius_mm * angle.sin());
                    let sweep = ArcSweep::new(center, at(from_rad), at(from_rad + sweep_rad), sweep_rad > 0.0);
                    let mut rows = ArcRows::new(raster, sweep, tool_mm);
                    raster.clear_arc_rows(&mut rows);
                }
            }
        }
    }

    fn update() -> impl Strategy<Value = Update> {
        let point = (-2.0..22.0f64, -2.0..22.0f64);
        prop_oneof![
            (point.clone(), point.clone(), 0.05..4.0f64).prop_map(|(a, b, r)| Update::Capsule(a, b, r)),
            (point.clone(), 0.05..3.0f64).prop_map(|(a, r)| Update::Capsule(a, a, r)),
            (point, -6.0..6.0f64, 0.2..4.0f64, 0.3..3.0f64, -std::f64::consts::PI..std::f64::consts::PI).prop_map(
                |(center, sweep_rad, radius_mm, tool_mm, from_rad)| Update::Arc {
                    center,
                    from_rad,
                    sweep_rad,
                    radius_mm,
                    tool_mm
                }
            ),
        ]
    }

    fn same(a: &Raster, b: &Raster) -> bool {
        a.f == b.f && a.blocks == b.blocks && a.tiles == b.tiles && a.version == b.version && a.written == b.written
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(256))]

        #[test]
        fn a_copy_given_the_blocks_written_since_its_mark_is_the_raster_again_cell_for_cell(
            before in prop::collection::vec(update(), 0..4),
            between in prop::collection::vec(update(), 0..6),
            after in prop::collection::vec(update(), 0..4),
        ) {
            let mut raster = block();
            before.iter().for_each(|u| u.apply(&mut raster));
            let mut early = raster.clone();
            let early_mark = raster.mark_writes();
            between.iter().for_each(|u| u.apply(&mut raster));
            let mut late = raster.clone();
            let late_mark = raster.mark_writes();
            after.iter().for_each(|u| u.apply(&mut raster));
            late.copy_written_since(&raster, late_mark);
            prop_assert!(same(&late, &raster), "the copy marked last differs");
            early.copy_written_since(&raster, early_mark);
            prop_assert!(same(&early, &raster), "the copy marked first differs");
        }
    }

    #[test]
    fn a_copy_takes_only_the_blocks_written_since_its_mark() {
        let mut raster = block();
        let mut copy = raster.clone();
        let mark = raster.mark_writes();
        assert_eq!(copy.copy_written_since(&raster, mark), 0, "nothing written");
        // A disc of 1 mm at cell size 0.1 mm, with its band: a few blocks of 16 × 16 cells.
        raster.clear_capsule((10.0, 10.0), (10.0, 10.0), 1.0);
        let copied = copy.copy_written_since(&raster, mark);
        assert!(copied > 0 && copied <= 4 * 16 * 16 * 4, "{copied} cells copied");
        assert!(same(&copy, &raster));
    }

    #[test]
    fn a_copy_on_another_grid_takes_every_cell() {
        let raster = block();
        let mut other = Raster::new(super::super::Rect { x_min: 0.0, y_min: 0.0, x_max: 5.0, y_max: 5.0 }, 0.2);
        let mark = other.mark_writes();
        assert_eq!(other.copy_written_since(&raster, mark), raster.f.len());
        assert!(same(&other, &raster));
    }
}
