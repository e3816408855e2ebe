//! Removing the area swept by the tool from a [`Raster`]: a capsule (the set of points
//! within `r` of a segment) per update. Cells deep inside it become "far outside", cells
//! in a band of the clamp width around its edge get their distance to it; along a path,
//! only the leading crescent of each capsule changes anything.

use super::capsule_rows::CapsuleRows;
use super::tiles::TILE_CELLS;
use super::{Raster, BLOCK_CELLS, DEGENERATE_SEGMENT_MM, FULL};

/// A capsule whose direction has an x component below this is treated as parallel to
/// the rows when its start line is located.
const MIN_ROW_SLOPE: f64 = 1e-6;
/// Cells compared at once when skipping runs of "far outside" cells (and when comparing
/// rasters, see [`super::alike`]).
pub(super) const WORD_CELLS: usize = 8;
/// Eight "far outside" cells as one word.
const FAR_OUTSIDE_WORD: u64 = u64::from_ne_bytes([(-FULL) as u8; WORD_CELLS]);
// A tile's stretch of a row is one word and lies in one block of material counts.
const _: () = assert!(WORD_CELLS == TILE_CELLS && BLOCK_CELLS.is_multiple_of(TILE_CELLS));

impl Raster {
    /// Removes the area swept by a disc of radius `r` moving from `a` to `b` (a capsule).
    pub fn clear_capsule(&mut self, a: (f64, f64), b: (f64, f64), r: f64) {
        self.clear_capsule_after(a, b, r, false);
    }

    /// As [`Raster::clear_capsule`]; with `disc_at_a_cleared`, the previous capsule given
    /// to this raster ended at `a` with the same radius, so only the leading crescent
    /// changes: cells behind `a` (whose nearest point of the segment is `a`) already hold
    /// their distance, and when that capsule was applied, cells deep inside the disc about
    /// `a` are already cleared.
    /// Returns `false` when no material lies near the capsule (nothing changed; see
    /// [`Raster::skip_capsule`]).
    pub fn clear_capsule_after(&mut self, a: (f64, f64), b: (f64, f64), r: f64, disc_at_a_cleared: bool) -> bool {
        self.clear_capsule_rows(&mut CapsuleRows::new(self, a, b, r, disc_at_a_cleared))
    }

    /// The grid's origin, cell and size, which rasters sharing capsule rows must share.
    pub(super) fn grid(&self) -> (f64, f64, f64, usize, usize) {
        (self.x0, self.y0, self.cell_mm, self.nx, self.ny)
    }

    /// What [`Raster::clear_capsule_after`] does to a raster with no material near the
    /// capsule, known without looking: nothing, and the capsule's end disc is not
    /// remembered as cleared.
    pub fn skip_capsule(&mut self) {
        self.end_disc_cleared = false;
    }

    /// `true` when a capsule update leaves the tile of cell (i, j) as it is: it has no
    /// material near (see [`Raster::clear_capsule_rows`]).
    #[inline]
    pub(super) fn left_alone(&self, i: usize, j: usize) -> bool {
        !self.updates_every_cell() && self.tiles.without_material_near(i, j)
    }

    /// Tests compare the updates with those that leave no cell alone.
    #[inline]
    pub(super) fn updates_every_cell(&self) -> bool {
        #[cfg(test)]
        if self.update_every_cell {
            return true;
        }
        false
    }

    /// Tests compare the updates with those that take every band cell one by one.
    #[inline]
    pub(super) fn band_cell_by_cell(&self) -> bool {
        #[cfg(test)]
        if self.band_cell_by_cell {
            return true;
        }
        false
    }

    /// `true` when the `WORD_CELLS` cells from index `k` are all "far outside".
    #[inline]
    pub(super) fn far_outside_word(&self, k: usize) -> bool {
        let mut word = [0u8; WORD_CELLS];
        for (b, &v) in word.iter_mut().zip(&self.f[k..k + WORD_CELLS]) {
            *b = v as u8;
        }
        u64::from_ne_bytes(word) == FAR_OUTSIDE_WORD
    }

    /// Clears the material of cells [from, to) of row `j`, which lie inside the capsule by
    /// at least the clamp width, a tile's width at a time: the material cells of each
    /// stretch are counted and the block and tile counts updated once. Only material
    /// needs clearing (see [`Raster::clear_capsule_rows`]): tiles with no material are
    /// not read.
    pub(super) fn clear_cells(&mut self, j: usize, from: usize, to: usize) {
        if from >= to {
            return;
        }
        let row = j * self.nx;
        let (tj, last) = (j / TILE_CELLS, (to - 1) / TILE_CELLS);
        let mut t = from / TILE_CELLS;
        loop {
            if !self.updates_every_cell() {
                match self.tiles.next_holding_material(tj, t, last) {
                    Some(next) => t = next,
                    None => break,
                }
            }
            if t > last {
                break;
            }
            let (i, end) = ((t * TILE_CELLS).max(from), ((t + 1) * TILE_CELLS).min(to));
            t += 1;
            let cleared = if end - i == WORD_CELLS {
                self.far_outside_word(row + i)
            } else {
                self.f[row + i..row + end].iter().all(|&v| v == -FULL)
            };
            if !cleared {
                let cells = &mut self.f[row + i..row + end];
                let lost = cells.iter().filter(|&&v| v > 0).count();
                cells.fill(-FULL);
                self.version += 1;
                self.written_at(i, j);
                if lost > 0 {
                    self.blocks[(j / BLOCK_CELLS) * self.bx + i / BLOCK_CELLS] -= lost as u32;
                    self.tiles.lose(i, j, lost);
                }
            }
        }
    }
}

impl Raster {
    /// Clears the material of the whole tiles [t0, t1) of row of tiles `tj`, whose cells
    /// all lie inside the capsule by at least the clamp width: the tiles' material counts
    /// are what they lose. As in [`Raster::clear_cells`], tiles with no material are not
    /// read.
    pub(super) fn clear_tiles(&mut self, tj: usize, t0: usize, t1: usize) {
        let mut t = t0;
        while t < t1 {
            match self.tiles.next_holding_material(tj, t, t1 - 1) {
                Some(next) => t = next,
                None => break,
            }
            let (i, j0) = (t * TILE_CELLS, tj * TILE_CELLS);
            let lost = self.tiles.empty(t, tj);
            for j in j0..(j0 + TILE_CELLS).min(self.ny) {
                self.f[j * self.nx + i..j * self.nx + i + TILE_CELLS].fill(-FULL);
            }
            self.blocks[(j0 / BLOCK_CELLS) * self.bx + i / BLOCK_CELLS] -= u32::from(lost);
            self.version += 1;
            self.written_at(i, j0);
            t += 1;
        }
    }
}

/// Where a row meets the half-plane ahead of a capsule's start.
pub(super) enum FrontHalf {
    /// Ahead for x above this.
    Above(f64),
    /// Ahead for x below this.
    Below(f64),
}

/// The distance to a segment from points of one row that all lie beside it.
pub(super) struct Beside {
    a_x: f64,
    /// The row's y from the segment's start.
    py: f64,
    dir: (f64, f64),
}

impl Beside {
    /// The distance from `(x, row)` to the segment's line (see `line_distance`).
    #[inline]
    pub(super) fn distance(&self, x: f64) -> f64 {
        let (ux, uy) = self.dir;
        line_distance((x - self.a_x, self.py), (ux, uy))
    }

    /// `true` when the segment runs exactly along the rows (its direction has no y
    /// component at all, ±0): [`Beside::distance`] then gives the same bits at every x of
    /// the row, since (x − a.x)·0 is a zero whatever x.
    #[inline]
    pub(super) fn same_along_row(&self) -> bool {
        self.dir.1.to_bits() << 1 == 0
    }
}

/// Distance from the point `p` (relative to a point of a line) to the line along the unit
/// vector `u`. One function for the band's stretches and its single cells, so both give
/// the same bits.
#[inline]
fn line_distance(p: (f64, f64), u: (f64, f64)) -> f64 {
    (p.0 * u.1 - p.1 * u.0).abs()
}

/// The set of points within `r` of a segment.
pub struct Capsule {
    a: (f64, f64),
    b: (f64, f64),
    r: f64,
    /// Unit direction and length, when the segment is not degenerate.
    dir: Option<((f64, f64), f64)>,
    /// Where a row crosses the band |n·(q − a)| < r (n the normal): x = a.x + slope·dy
    /// ± half, dy = y − a.y (None when the segment runs along the rows).
    across: Option<(f64, f64)>,
    /// Where a row crosses the band 0 ≤ u·(q − a) ≤ len: x = a.x + slope·dy + [0, span]
    /// (None when the segment runs across the rows).
    along: Option<(f64, f64)>,
}

impl Capsule {
    pub fn new(a: (f64, f64), b: (f64, f64), r: f64) -> Capsule {
        let (dx, dy) = (b.0 - a.0, b.1 - a.1);
        let len = dx.hypot(dy);
        let dir = (len > DEGENERATE_SEGMENT_MM).then(|| ((dx / len, dy / len), len));
        let across = dir.and_then(|((ux, uy), _)| (uy.abs() >= DEGENERATE_SEGMENT_MM).then(|| (ux / uy, r / uy.abs())));
        let along = dir.and_then(|((ux, uy), len)| (ux.abs() >= DEGENERATE_SEGMENT_MM).then(|| (-uy / ux, len / ux)));
        Capsule { a, b, r, dir, across, along }
    }

    /// Where the row at `y` leaves the half-plane behind the start (None: the row runs
    /// along the start line or the segment is degenerate; test each cell).
    pub(super) fn front_half_line(&self, y: f64) -> Option<FrontHalf> {
        let ((ux, _), _) = self.dir?;
        let (slope, _) = self.along?;
        if ux.abs() < MIN_ROW_SLOPE {
            return None;
        }
        let x = self.a.0 + slope * (y - self.a.1);
        Some(if ux > 0.0 { FrontHalf::Above(x) } else { FrontHalf::Below(x) })
    }

    /// Distance from `q` to the segment: beside it, the distance to its line (no square
    /// root); beyond either end, to that end. With `skip_behind`, `None` when `q` projects
    /// before the start (its nearest point is `a`).
    #[inline]
    pub(super) fn distance_unless_behind(&self, q: (f64, f64), skip_behind: bool) -> Option<f64> {
        let (px, py) = (q.0 - self.a.0, q.1 - self.a.1);
        match self.dir {
            Some(((ux, uy), len)) => {
                let t = px * ux + py * uy;
                if skip_behind && t <= 0.0 {
                    return None;
                }
                Some(if (0.0..=len).contains(&t) {
                    line_distance((px, py), (ux, uy))
                } else {
                    let t = t.clamp(0.0, len);
                    let (ex, ey) = (px - t * ux, py - t * uy);
                    (ex * ex + ey * ey).sqrt()
                })
            }
            None => Some((px * px + py * py).sqrt()),
        }
    }

    /// Where the points from `(x_lo, y)` to `(x_hi, y)` all lie beside the segment (their
    /// nearest point is inside it; with `skip_behind`, not its start), how to find their
    /// distance to it, as [`Capsule::distance_unless_behind`] does.
    #[inline]
    pub(super) fn beside_all(&self, x_lo: f64, x_hi: f64, y: f64, skip_behind: bool) -> Option<Beside> {
        let ((ux, uy), len) = self.dir?;
        let py = y - self.a.1;
        // The projection is monotonic along the row: its ends bound it.
        let along = |x: f64| (x - self.a.0) * ux + py * uy;
        let (t_lo, t_hi) = (along(x_lo), along(x_hi));
        let inside = |t: f64| (0.0..=len).contains(&t) && !(skip_behind && t <= 0.0);
        (inside(t_lo) && inside(t_hi)).then_some(Beside { a_x: self.a.0, py, dir: (ux, uy) })
    }

    /// The chord of the disc of radius `r` about `c` on the line at `y`.
    pub(super) fn disc_chord(&self, c: (f64, f64), y: f64) -> Option<(f64, f64)> {
        let dy = y - c.1;
        let h2 = self.r * self.r - dy * dy;
        (h2 > 0.0).then(|| {
            let h = h2.sqrt();
            (c.0 - h, c.0 + h)
        })
    }

    /// The x-interval of the capsule on the line at `y` (the capsule is convex).
    pub fn row_interval(&self, y: f64) -> Option<(f64, f64)> {
        let mut lo = f64::INFINITY;
        let mut hi = f64::NEG_INFINITY;
        for chord in [self.disc_chord(self.a, y), self.disc_chord(self.b, y)].into_iter().flatten() {
            lo = lo.min(chord.0);
            hi = hi.max(chord.1);
        }
        if let Some(((ux, uy), len)) = self.dir {
            let dy = y - self.a.1;
            let mut band = (f64::NEG_INFINITY, f64::INFINITY);
            let mut ok = true;
            match self.across {
                Some((slope, half)) => {
                    let x = self.a.0 + slope * dy;
                    band = (x - half, x + half);
                }
                None => ok &= (ux * dy).abs() < self.r,
            }
            match self.along {
                Some((slope, span)) => {
                    let x = self.a.0 + slope * dy;
                    let (p, q) = if span > 0.0 { (x, x + span) } else { (x + span, x) };
                    band = (band.0.max(p), band.1.min(q));
                }
                None => ok &= uy * dy > 0.0 && uy * dy < len,
            }
            if ok && band.0 < band.1 {
                lo = lo.min(band.0);
                hi = hi.max(band.1);
            }
        }
        (lo < hi).then_some((lo, hi))
    }
}

#[cfg(test)]
mod tests {
    use super::super::test_blocks::{block, counts_of_the_cells, shares_a_probe_with_material, SIDE};
    use super::*;
    use proptest::prelude::*;

    #[test]
    fn one_capsules_rows_leave_every_raster_as_its_own_update_would() {
        // Two rasters of one grid with different cuts, as two slices of a layer.
        let (mut upper, mut lower) = (block(), block());
        upper.clear_capsule((5.0, 5.0), (30.0, 12.0), 3.0);
        lower.clear_capsule((5.0, 30.0), (12.0, 8.0), 1.5);
        let (mut upper_alone, mut lower_alone) = (upper.clone(), lower.clone());
        let mut rows = CapsuleRows::new(&upper, (0.0, 0.0), (1.0, 1.0), 2.0, false);
        let mut a = (3.0, 20.0);
        for (k, b) in [(10.0, 21.0), (18.0, 15.0), (25.0, 15.5), (25.0, 30.0)].into_iter().enumerate() {
            // The same value serves capsule after capsule.
            rows.set(&upper, a, b, 2.0, k > 0);
            assert_eq!(lower.clear_capsule_rows(&mut rows), lower_alone.clear_capsule_after(a, b, 2.0, k > 0));
            assert_eq!(upper.clear_capsule_rows(&mut rows), upper_alone.clear_capsule_after(a, b, 2.0, k > 0));
            a = b;
        }
        assert!(upper.f == upper_alone.f && lower.f == lower_alone.f, "cells differ");
        assert!(upper.blocks == upper_alone.blocks && upper.tiles == upper_alone.tiles, "counts differ");
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(48))]

        #[test]
        fn a_path_of_leading_crescents_leaves_the_raster_of_whole_capsules(
            start in (0.0..SIDE, 0.0..SIDE),
            steps in prop::collection::vec((-3.0..3.0f64, -3.0..3.0f64), 1..30),
            radius in 0.3..6.0f64,
        ) {
            let (mut crescents, mut whole) = (block(), block());
            // Cell by cell, in tiles with no material near too.
            crescents.update_every_cell = true;
            whole.update_every_cell = true;
            let mut a = start;
            for (k, d) in steps.iter().enumerate() {
                let b = (a.0 + d.0, a.1 + d.1);
                crescents.clear_capsule_after(a, b, radius, k > 0);
                whole.clear_capsule(a, b, radius);
                a = b;
            }
            // Cells behind a start hold the distance to the previous capsule, computed
            // there through a different segment: equal to a unit of rounding. Only cells
            // a probe reads beside material count: a capsule with no material near is
            // skipped, and the air it would have updated keeps other values.
            let worst = (0..whole.f.len())
                .filter(|&k| shares_a_probe_with_material(&whole, k))
                .map(|k| (i16::from(crescents.f[k]) - i16::from(whole.f[k])).abs())
                .max();
            prop_assert!(worst.unwrap_or(0) <= 1, "cells differ by {:?}", worst);
            let differing_sign = crescents.f.iter().zip(&whole.f).filter(|(p, q)| (**p > 0) != (**q > 0)).count();
            prop_assert!(differing_sign == 0, "{} cells change side", differing_sign);
        }

        #[test]
        fn updates_that_leave_air_far_from_material_alone_change_no_probe_and_no_count(
            start in (0.0..SIDE, 0.0..SIDE),
            steps in prop::collection::vec((-4.0..4.0f64, -4.0..4.0f64), 1..40),
            radius in 0.3..3.0f64,
            probes in prop::collection::vec((0.0..SIDE, 0.0..SIDE), 400),
        ) {
            let (mut skipping, mut every) = (block(), block());
            every.update_every_cell = true;
            let mut a = start;
            let mut near_edges = Vec::new();
            for (k, d) in steps.iter().enumerate() {
                let b = (a.0 + d.0, a.1 + d.1);
                // Points about the edge of the disc at b, where the cells decide.
                for n in 0..16 {
                    let angle = f64::from(n) * std::f64::consts::PI / 8.0;
                    for off in [-0.15, -0.05, 0.0, 0.05, 0.15] {
                        near_edges.push((b.0 + (radius + off) * angle.cos(), b.1 + (radius + off) * angle.sin()));
                    }
                }
                prop_assert_eq!(skipping.clear_capsule_after(a, b, radius, k > 0), every.clear_capsule_after(a, b, radius, k > 0));
                a = b;
            }
            prop_assert!(skipping.blocks == every.blocks && skipping.tiles == every.tiles, "counts differ");
            // Material cells are the same; so is every probe, with what it certifies.
            let differing_material = skipping.f.iter().zip(&every.f).filter(|(p, q)| (**p > 0 || **q > 0) && p != q).count();
            prop_assert!(differing_material == 0, "{} material cells differ", differing_material);
            for (x, y) in probes.into_iter().chain(near_edges) {
                let g = skipping.grid_position(x, y);
                prop_assert_eq!(skipping.probe_at(g), every.probe_at(g), "at ({}, {})", x, y);
            }
            // And a probe inside every quad of cells.
            for j in 0..skipping.ny - 1 {
                for i in 0..skipping.nx - 1 {
                    let g = (i as f64 + 0.3, j as f64 + 0.6);
                    prop_assert_eq!(skipping.probe_at(g), every.probe_at(g), "at cells ({}, {})", i, j);
                }
            }
        }

        #[test]
        fn band_stretches_beside_the_segment_take_the_values_of_band_cells_taken_one_by_one(
            start in (0.0..SIDE, 0.0..SIDE),
            steps in prop::collection::vec((-4.0..4.0f64, -4.0..4.0f64), 1..30),
            radius in 0.3..6.0f64,
        ) {
            let (mut stretches, mut one_by_one) = (block(), block());
            one_by_one.band_cell_by_cell = true;
            let mut a = start;
            for (k, d) in steps.iter().enumerate() {
                // Every fourth step along a row or a column, where stretches run beside.
                let d = match k % 4 { 1 => (d.0, 0.0), 3 => (0.0, d.1), _ => *d };
                let b = (a.0 + d.0, a.1 + d.1);
                prop_assert_eq!(stretches.clear_capsule_after(a, b, radius, k > 0), one_by_one.clear_capsule_after(a, b, radius, k > 0));
                a = b;
            }
            prop_assert!(stretches.f == one_by_one.f, "cells differ");
            prop_assert!(stretches.blocks == one_by_one.blocks && stretches.tiles == one_by_one.tiles, "counts differ");
            prop_assert_eq!(stretches.version, one_by_one.version);
        }

        #[test]
        fn the_block_and_tile_counts_kept_while_clearing_are_those_of_the_cells(
            start in (0.0..SIDE, 0.0..SIDE),
            steps in prop::collection::vec((-4.0..4.0f64, -4.0..4.0f64), 1..12),
            radius in 0.3..6.0f64,
        ) {
            let mut raster = block();
            let mut a = start;
            for (k, d) in steps.iter().enumerate() {
                let b = (a.0 + d.0, a.1 + d.1);
                raster.clear_capsule_after(a, b, radius, k > 0);
                a = b;
            }
            let (blocks, tiles) = counts_of_the_cells(&raster);
            prop_assert!(blocks, "block counts differ");
            prop_assert!(tiles, "tile counts differ");
        }
    }
}
