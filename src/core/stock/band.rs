//! The band of a capsule update: the cells within the clamp width of the capsule's edge,
//! which take their distance to it (see [`Raster::clear_capsule_rows`]).

use super::arc_sweep::ArcSweep;
use super::capsule::{Beside, Capsule};
use super::tiles::TILE_CELLS;
use super::{Raster, BLOCK_CELLS, FULL};

/// The path a band's cells take their distance to: a capsule's segment or an arc.
pub(super) trait BandShape {
    /// Distance from `q` to the path; with `skip_behind`, `None` where `q`'s nearest
    /// point is the path's start (see [`Capsule::distance_unless_behind`]).
    fn distance_unless_behind(&self, q: (f64, f64), skip_behind: bool) -> Option<f64>;
    /// Where the points from `(x_lo, y)` to `(x_hi, y)` all lie beside a segment, how to
    /// find their distance to it at once (see [`Capsule::beside_all`]).
    fn beside_all(&self, x_lo: f64, x_hi: f64, y: f64, skip_behind: bool) -> Option<Beside>;
}

impl BandShape for Capsule {
    #[inline]
    fn distance_unless_behind(&self, q: (f64, f64), skip_behind: bool) -> Option<f64> {
        Capsule::distance_unless_behind(self, q, skip_behind)
    }

    #[inline]
    fn beside_all(&self, x_lo: f64, x_hi: f64, y: f64, skip_behind: bool) -> Option<Beside> {
        Capsule::beside_all(self, x_lo, x_hi, y, skip_behind)
    }
}

impl BandShape for ArcSweep {
    /// Every cell of an arc's band takes its distance (nothing is skipped behind).
    #[inline]
    fn distance_unless_behind(&self, q: (f64, f64), _skip_behind: bool) -> Option<f64> {
        Some(self.distance(q))
    }

    #[inline]
    fn beside_all(&self, _x_lo: f64, _x_hi: f64, _y: f64, _skip_behind: bool) -> Option<Beside> {
        None
    }
}

/// Cells of a row taken at once where all lie beside the segment (a tile's stretch).
const STRETCH_CELLS: usize = TILE_CELLS;

impl Raster {
    /// Cells [from, to) of row `j` in the band around the area within `r` of the path
    /// `outer` (a capsule, or an arc) get their distance to that area, where it is
    /// smaller; with `skip_behind`, cells projecting before its start are left alone.
    pub(super) fn band_cells<S: BandShape>(
        &mut self,
        j: usize,
        from: usize,
        to: usize,
        outer: &S,
        r: f64,
        skip_behind: bool,
    ) {
        let row = j * self.nx;
        let y = self.row_y(j);
        let mut changed = false;
        let mut i = from;
        // A tile's stretch at a time: tiles with no material near are left as they are
        // (see [`Raster::clear_capsule_rows`]), as are stretches already far outside.
        while i < to {
            let end = ((i / TILE_CELLS + 1) * TILE_CELLS).min(to);
            if self.left_alone(i, j) || (end - i == STRETCH_CELLS && self.far_outside_word(row + i)) {
                i = end;
                continue;
            }
            if end - i == STRETCH_CELLS && !self.band_cell_by_cell() {
                if let Some(beside) = outer.beside_all(self.col_x(i), self.col_x(end - 1), y, skip_behind) {
                    changed |= self.band_stretch_beside(j, i, &beside, r);
                    i = end;
                    continue;
                }
            }
            let mut lost = 0;
            for i in i..end {
                let q = (self.col_x(i), y);
                let old = self.f[row + i];
                let distance = if old == -FULL { None } else { outer.distance_unless_behind(q, skip_behind) };
                if let Some(d) = distance {
                    // Material stays where it is farther than r from the segment. The cell
                    // is written whether or not it changes (no branch to mispredict); it
                    // can only lose material.
                    let v = self.encode(d - r).min(old);
                    self.f[row + i] = v;
                    changed |= v != old;
                    lost += usize::from(old > 0 && v <= 0);
                }
            }
            self.count_lost_material(i, j, lost);
            i = end;
        }
        if changed {
            self.version += 1;
            self.written_in_row(j, from, to);
        }
    }

    /// The band cells [i, i + `STRETCH_CELLS`) of row `j`, all beside the segment of the
    /// capsule `beside` is of: each takes its distance to the capsule of radius `r` where
    /// that is smaller, as in [`Raster::band_cells`], eight at once without a branch per
    /// cell. Returns `true` when a cell changed.
    fn band_stretch_beside(&mut self, j: usize, i: usize, beside: &Beside, r: f64) -> bool {
        let k = j * self.nx + i;
        let mut new = [self.encode(beside.distance(self.col_x(i)) - r); STRETCH_CELLS];
        if !beside.same_along_row() {
            for (n, v) in new.iter_mut().enumerate().skip(1) {
                *v = self.encode(beside.distance(self.col_x(i + n)) - r);
            }
        }
        let mut old = [0i8; STRETCH_CELLS];
        old.copy_from_slice(&self.f[k..k + STRETCH_CELLS]);
        let mut lost = 0u32;
        let mut changed = false;
        for (n, (v, &o)) in new.iter_mut().zip(&old).enumerate() {
            *v = (*v).min(o);
            changed |= *v != o;
            lost |= u32::from(o > 0 && *v <= 0) << n;
        }
        self.f[k..k + STRETCH_CELLS].copy_from_slice(&new);
        self.count_lost_material(i, j, lost.count_ones() as usize);
        changed
    }

    /// Counts in their block and tile that `lost` cells of a row's stretch in one tile,
    /// from cell (i, j), lost their material.
    #[inline]
    fn count_lost_material(&mut self, i: usize, j: usize, lost: usize) {
        if lost > 0 {
            // (At most a tile's cells, which fit the count's type.)
            self.blocks[(j / BLOCK_CELLS) * self.bx + i / BLOCK_CELLS] -= lost as u32;
            self.tiles.lose(i, j, lost);
        }
    }
}
