//! The in-process stock of one z slice as a raster of clamped signed distances
//! (MODEL.md §6). Each cell keeps the distance from its centre to the material boundary
//! (positive in material), clamped to ±[`SDF_CLAMP_CELLS`] cells and stored in one byte;
//! a probe interpolates bilinearly, which places a smooth boundary to a small fraction of
//! a cell. Memory grows with the stock area (one byte per cell), not with the path.
//!
//! Only the cells a probe can read beside a material cell need their distance: an air
//! cell that no longer has material next to it keeps whatever value at or below zero it
//! had when the last material near it was removed (capsule updates leave it alone, see
//! [`Raster::clear_capsule_rows`]). Such a value underestimates the distance to the
//! material that is left, which is all that is read from it.

mod alike;
mod along;
mod arc_rows;
mod arc_sweep;
mod area;
mod band;
mod capsule;
mod capsule_rows;
mod cells;
mod certified_air;
mod compare;
#[cfg(test)]
mod test_blocks;
mod tiles;
mod written;

pub use arc_rows::ArcRows;
pub use arc_sweep::{ArcSweep, MAX_ARC_SWEEP_RAD};
pub use capsule::Capsule;
pub use capsule_rows::CapsuleRows;
pub use cells::{resample, Grid};
pub use compare::CellRect;
pub use tiles::Certified;
use tiles::Tiles;
pub use written::WriteMark;
use written::Written;

/// Distances are clamped to this many cells either side of the boundary. A probe
/// interpolates the 2 × 2 cells around its point; where the boundary crosses them, each
/// lies within a diagonal (√2 cells) of it, so a clamp beyond √2 never changes where a
/// probe places the boundary, and the cells beyond it need no exact distance.
pub const SDF_CLAMP_CELLS: f64 = 1.5;
/// Stored units per cell of distance (so ±1.5 cells fit an i8).
const UNITS_PER_CELL: f64 = 84.0;
/// A nearest cell at least this far from the boundary (stored units: √2/2 of a cell,
/// rounded up) decides a probe without interpolation.
const DECISIVE: u8 = (std::f64::consts::FRAC_1_SQRT_2 * UNITS_PER_CELL) as u8 + 1;
const _: () = assert!(SDF_CLAMP_CELLS > std::f64::consts::SQRT_2);
/// The stored value of "far inside material" / "far outside".
const FULL: i8 = (SDF_CLAMP_CELLS * UNITS_PER_CELL) as i8;
/// Segments shorter than this are treated as a single disc, mm.
const DEGENERATE_SEGMENT_MM: f64 = 1e-12;
/// Side of the square blocks whose material cells are counted, in cells: a probe skips
/// a slice when no block under the tool holds material.
const BLOCK_CELLS: usize = 16;

/// A rectangle, mm.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Rect {
    pub x_min: f64,
    pub y_min: f64,
    pub x_max: f64,
    pub y_max: f64,
}

/// Signed distance from `(x, y)` to the boundary of `r`: positive inside.
pub fn rect_signed_distance(r: &Rect, x: f64, y: f64) -> f64 {
    let dx = (r.x_min - x).max(x - r.x_max);
    let dy = (r.y_min - y).max(y - r.y_max);
    if dx <= 0.0 && dy <= 0.0 {
        -dx.max(dy)
    } else {
        -(dx.max(0.0).hypot(dy.max(0.0)))
    }
}

/// A rectangle of blocks of material counts: first and last column, first and last row.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct BlockRange {
    pub columns: (usize, usize),
    pub rows: (usize, usize),
}

impl BlockRange {
    /// `true` when block (column, row) is one of `self`.
    pub fn holds(&self, (column, row): (usize, usize)) -> bool {
        (self.columns.0..=self.columns.1).contains(&column) && (self.rows.0..=self.rows.1).contains(&row)
    }

    /// `true` when `other` lies inside `self`.
    pub fn contains(&self, other: &BlockRange) -> bool {
        self.columns.0 <= other.columns.0
            && other.columns.1 <= self.columns.1
            && self.rows.0 <= other.rows.0
            && other.rows.1 <= self.rows.1
    }
}

/// A clamped signed-distance raster of material over a rectangle.
#[derive(Debug, Clone)]
pub struct Raster {
    x0: f64,
    y0: f64,
    cell_mm: f64,
    inv_cell: f64,
    nx: usize,
    ny: usize,
    f: Vec<i8>,
    /// Cells holding material (value > 0) per block of BLOCK_CELLS × BLOCK_CELLS.
    blocks: Vec<u32>,
    bx: usize,
    /// Material counts over small tiles, to certify probes far from the boundary.
    tiles: Tiles,
    /// The last capsule applied cleared its end disc (see [`Raster::clear_capsule_after`]).
    end_disc_cleared: bool,
    /// Counts the writes: what was read from the raster holds while it is unchanged.
    version: u64,
    /// Which blocks were written since each mark (see [`Raster::copy_written_since`]).
    written: Written,
    /// Tests compare capsule updates with and without leaving tiles alone, and with band
    /// cells taken one by one.
    #[cfg(test)]
    update_every_cell: bool,
    #[cfg(test)]
    band_cell_by_cell: bool,
}

impl Raster {
    /// An empty raster (no material) covering `bounds` (plus a margin of the clamp width)
    /// with square cells of `cell_mm`.
    pub fn new(bounds: Rect, cell_mm: f64) -> Raster {
        let (x0, y0, nx, ny) = Raster::layout(bounds, cell_mm);
        Raster {
            x0,
            y0,
            cell_mm,
            inv_cell: 1.0 / cell_mm,
            nx,
            ny,
            f: vec![-FULL; nx * ny],
            blocks: vec![0; nx.div_ceil(BLOCK_CELLS) * ny.div_ceil(BLOCK_CELLS)],
            bx: nx.div_ceil(BLOCK_CELLS),
            tiles: Tiles::new(nx, ny),
            end_disc_cleared: false,
            version: 0,
            written: Written::new(nx.div_ceil(BLOCK_CELLS) * ny.div_ceil(BLOCK_CELLS)),
            #[cfg(test)]
            update_every_cell: false,
            #[cfg(test)]
            band_cell_by_cell: false,
        }
    }

    /// The origin and the size in cells of the raster [`Raster::new`] makes.
    fn layout(bounds: Rect, cell_mm: f64) -> (f64, f64, usize, usize) {
        // A whole number of cells, so the grid keeps its phase whatever the clamp.
        let margin = (SDF_CLAMP_CELLS.ceil() + 1.0) * cell_mm;
        let x0 = bounds.x_min - margin;
        let y0 = bounds.y_min - margin;
        let nx = (((bounds.x_max + margin - x0) / cell_mm).ceil() as usize).max(2);
        let ny = (((bounds.y_max + margin - y0) / cell_mm).ceil() as usize).max(2);
        (x0, y0, nx, ny)
    }

    /// The number of cells of the raster [`Raster::new`] makes, without making it.
    pub fn cell_count(bounds: Rect, cell_mm: f64) -> usize {
        let (_, _, nx, ny) = Raster::layout(bounds, cell_mm);
        nx * ny
    }

    pub fn size(&self) -> (usize, usize) {
        (self.nx, self.ny)
    }

    pub fn cell_mm(&self) -> f64 {
        self.cell_mm
    }

    /// Bytes of raster memory.
    pub fn memory_bytes(&self) -> usize {
        self.f.len()
    }

    fn row_y(&self, j: usize) -> f64 {
        self.y0 + (j as f64 + 0.5) * self.cell_mm
    }

    fn col_x(&self, i: usize) -> f64 {
        self.x0 + (i as f64 + 0.5) * self.cell_mm
    }

    #[inline]
    fn encode(&self, d_mm: f64) -> i8 {
        let v = (d_mm * self.inv_cell).clamp(-SDF_CLAMP_CELLS, SDF_CLAMP_CELLS) * UNITS_PER_CELL;
        // Round half away from zero without a libm call.
        (v + 0.5f64.copysign(v)) as i8
    }

    /// Changes whenever a cell changes.
    pub fn version(&self) -> u64 {
        self.version
    }

    /// `false` when no cell within `reach_mm` of `(x, y)` holds material.
    pub fn any_material_near(&self, x: f64, y: f64, reach_mm: f64) -> bool {
        self.blocks_near(x, y, reach_mm).is_some_and(|b| self.any_material_in(b))
    }

    /// The blocks of material counts that cover every cell within `reach_mm` of `(x, y)`
    /// (None: none of the raster).
    pub fn blocks_near(&self, x: f64, y: f64, reach_mm: f64) -> Option<BlockRange> {
        let index = |v: f64, origin: f64, pad: f64| ((v - origin) * self.inv_cell + pad).max(0.0) as usize;
        let (lo_i, lo_j) = (index(x - reach_mm, self.x0, -1.0), index(y - reach_mm, self.y0, -1.0));
        let hi_i = index(x + reach_mm, self.x0, 1.0).min(self.nx - 1);
        let hi_j = index(y + reach_mm, self.y0, 1.0).min(self.ny - 1);
        (lo_i <= hi_i && lo_j <= hi_j).then_some(BlockRange {
            columns: (lo_i / BLOCK_CELLS, hi_i / BLOCK_CELLS),
            rows: (lo_j / BLOCK_CELLS, hi_j / BLOCK_CELLS),
        })
    }

    /// `true` when a cell of the blocks `b` holds material.
    pub fn any_material_in(&self, b: BlockRange) -> bool {
        self.first_material_block_in(b).is_some()
    }

    /// The first block of `b`, row by row, with a cell that holds material, as (column, row).
    pub fn first_material_block_in(&self, b: BlockRange) -> Option<(usize, usize)> {
        (b.rows.0..=b.rows.1).find_map(|bj| {
            let row = &self.blocks[bj * self.bx + b.columns.0..=bj * self.bx + b.columns.1];
            row.iter().position(|&n| n > 0).map(|i| (b.columns.0 + i, bj))
        })
    }

    /// `true` when a cell of block (column, row) holds material.
    pub fn block_holds_material(&self, (column, row): (usize, usize)) -> bool {
        self.blocks.get(row * self.bx + column).is_some_and(|&n| n > 0)
    }

    /// Cells whose centres lie in `[x_lo, x_hi]`, as a half-open index range.
    #[inline]
    fn cell_range(&self, x_lo: f64, x_hi: f64) -> (usize, usize) {
        self.index_range(x_lo, x_hi, self.x0, self.nx)
    }

    /// Indices of the cell centres in `[lo, hi]` along an axis starting at `origin` with
    /// `n` cells, as a half-open range; (0, 0) when there are none. (Integer conversions
    /// instead of `ceil`/`floor`, which are library calls on baseline x86-64.)
    #[inline]
    fn index_range(&self, lo: f64, hi: f64, origin: f64, n: usize) -> (usize, usize) {
        let (v_lo, v_hi) = ((lo - origin) * self.inv_cell - 0.5, (hi - origin) * self.inv_cell - 0.5);
        // (A raster side fits u32, whose conversion to f64 is one instruction.)
        let n_f = f64::from(n as u32);
        // Through i64 (one instruction each way; the raster has far fewer cells): the
        // smallest index ≥ v_lo (v_lo > 0 is false for NaN too) …
        let first = if v_lo > 0.0 {
            let t = v_lo.min(n_f) as i64;
            (t + i64::from((t as f64) < v_lo)) as usize
        } else {
            0
        };
        // … and one past the largest index ≤ v_hi, at most n.
        let end = if v_hi >= 0.0 { ((v_hi.min(n_f) as i64) as usize + 1).min(n) } else { 0 };
        if end <= first {
            return (0, 0);
        }
        (first, end)
    }

    /// Paints a region as material (`add`) or as removed. `intervals(y, out)` gives the
    /// sorted, disjoint x-intervals inside the region on the line at `y`;
    /// `distance(x, y, inside)` its signed distance (positive inside), evaluated only in
    /// the band of cells near the boundary, so the boundary is placed exactly. `inside`
    /// says whether the intervals hold `(x, y)`: the sign, for a region whose own inside
    /// test is dear. It is asked row after row (y increasing), along x within a row.
    pub fn paint(
        &mut self,
        add: bool,
        intervals: impl FnMut(f64, &mut Vec<(f64, f64)>),
        distance: impl FnMut(f64, f64, bool) -> f64,
    ) {
        // Never stopped, so always painted whole.
        let _painted = self.paint_until(add, intervals, distance, |_| false);
    }

    /// As [`Raster::paint`], asking `stopped(done)` before each row of its two passes
    /// over the rows, `done` being the share of those rows done (0..1): `false` when it
    /// stopped part of the way (the raster is then partly painted, for dropping).
    pub fn paint_until(
        &mut self,
        add: bool,
        mut intervals: impl FnMut(f64, &mut Vec<(f64, f64)>),
        mut distance: impl FnMut(f64, f64, bool) -> f64,
        mut stopped: impl FnMut(f64) -> bool,
    ) -> bool {
        self.end_disc_cleared = false;
        // (Before any cell: a painting stopped part of the way wrote some.)
        self.written.stamp_all();
        let (nx, ny) = (self.nx, self.ny);
        let rows_done = |pass: usize, j: usize| (pass * ny + j) as f64 / (2 * ny) as f64;
        let mut inside = vec![false; nx * ny];
        let mut out = Vec::new();
        for j in 0..ny {
            if stopped(rows_done(0, j)) {
                return false;
            }
            out.clear();
            intervals(self.row_y(j), &mut out);
            for &(lo, hi) in &out {
                let (a, b) = self.cell_range(lo, hi);
                inside[j * nx + a..j * nx + b].fill(true);
            }
        }
        // Cells within the clamp width of a change of membership get exact distances.
        let band = SDF_CLAMP_CELLS.ceil() as usize + 1;
        let mut near = vec![false; nx * ny];
        for j in 0..ny {
            for i in 0..nx {
                let k = j * nx + i;
                let differs = (i + 1 < nx && inside[k] != inside[k + 1]) || (j + 1 < ny && inside[k] != inside[k + nx]);
                if differs {
                    for jj in j.saturating_sub(band)..(j + band + 2).min(ny) {
                        near[jj * nx + i.saturating_sub(band)..jj * nx + (i + band + 2).min(nx)].fill(true);
                    }
                }
            }
        }
        for j in 0..ny {
            if stopped(rows_done(1, j)) {
                return false;
            }
            for i in 0..nx {
                let k = j * nx + i;
                let v = if near[k] {
                    self.encode(distance(self.col_x(i), self.row_y(j), inside[k]))
                } else if inside[k] {
                    FULL
                } else {
                    -FULL
                };
                self.f[k] = if add { self.f[k].max(v) } else { self.f[k].min(-v) };
            }
        }
        self.recount();
        self.version += 1;
        true
    }

    /// Counts the material cells of every block and tile again, from the cells.
    fn recount(&mut self) {
        self.blocks.fill(0);
        let mut tiles = Tiles::new(self.nx, self.ny);
        for (j, row) in self.f.chunks_exact(self.nx).enumerate() {
            let blocks = &mut self.blocks[(j / BLOCK_CELLS) * self.bx..];
            for (bi, cells) in row.chunks(BLOCK_CELLS).enumerate() {
                blocks[bi] += cells.iter().filter(|&&v| v > 0).count() as u32;
            }
            tiles.count_row(j, row);
        }
        tiles.spread_counts();
        self.tiles = tiles;
    }

    /// `true` when the bilinearly interpolated distance at `(x, y)` is inside material.
    #[inline]
    pub fn is_material(&self, x: f64, y: f64) -> bool {
        self.classify::<false>(self.grid_position(x, y)).0
    }

    /// Where `(x, y)` falls on the grid of cell centres, in cells (cell (i, j) at (i, j)).
    #[inline]
    pub fn grid_position(&self, x: f64, y: f64) -> (f64, f64) {
        ((x - self.x0) * self.inv_cell - 0.5, (y - self.y0) * self.inv_cell - 0.5)
    }

    /// Cells per millimetre.
    pub fn cells_per_mm(&self) -> f64 {
        self.inv_cell
    }

    /// [`Raster::is_material`] at a position on the grid of cell centres.
    #[inline]
    pub fn is_material_at(&self, g: (f64, f64)) -> bool {
        self.classify::<false>(g).0
    }

    /// As [`Raster::is_material_at`], and how far around the position the answer is known
    /// to hold: away from the boundary, the tiles around it may all be air or all material.
    #[inline]
    pub fn probe_at(&self, g: (f64, f64)) -> (bool, Certified) {
        self.classify::<true>(g)
    }

    /// The first of the 2 × 2 cells a probe at grid position `(fx, fy)` reads, (i, j);
    /// `None` off the raster (below 0, NaN, or at the last cell centre or beyond, along
    /// either axis), where a probe answers air without reading a cell.
    #[inline(always)]
    fn base_cell(&self, (fx, fy): (f64, f64)) -> Option<(u32, u32)> {
        // (Also false for NaN.)
        if !(fx >= 0.0 && fy >= 0.0) {
            return None;
        }
        // Through u32 (the raster has far fewer cells per side): cheap conversions.
        let (i, j) = (fx as u32, fy as u32);
        (i as usize + 1 < self.nx && j as usize + 1 < self.ny).then_some((i, j))
    }

    #[inline]
    fn classify<const CERTIFY: bool>(&self, (fx, fy): (f64, f64)) -> (bool, Certified) {
        let Some((i, j)) = self.base_cell((fx, fy)) else {
            return (false, if CERTIFY { self.certified_outside((fx, fy)) } else { Certified::No });
        };
        let (tx, ty) = (fx - f64::from(i), fy - f64::from(j));
        let (i, j) = (i as usize, j as usize);
        let k = j * self.nx + i;
        // The distance is 1-Lipschitz: a nearest cell more than half a diagonal inside or
        // outside decides alone.
        let nearest = self.f[k + usize::from(tx > 0.5) + if ty > 0.5 { self.nx } else { 0 }];
        if nearest.unsigned_abs() >= DECISIVE {
            let material = nearest > 0;
            // Only a material cell at the clamp can lie in a tile neighbourhood of one
            // state; an air cell can hold any value there (capsules leave such tiles
            // alone, see `clear_capsule_rows`).
            let certified = if CERTIFY && (nearest == FULL || !material) {
                self.tiles.certified(i, j, material)
            } else {
                Certified::No
            };
            return (material, certified);
        }
        let (a, b) = (f64::from(self.f[k]), f64::from(self.f[k + 1]));
        let (c, d) = (f64::from(self.f[k + self.nx]), f64::from(self.f[k + self.nx + 1]));
        let bottom = a + (b - a) * tx;
        let top = c + (d - c) * tx;
        let material = bottom + (top - bottom) * ty > 0.0;
        let certified =
            if CERTIFY && !material && nearest <= 0 { self.tiles.certified(i, j, false) } else { Certified::No };
        (material, certified)
    }

    /// How far around a grid position off the raster (where [`Raster::classify`] answers
    /// air without reading a cell: below 0 or at the last cell centre or beyond, along
    /// either axis) every position is off it too.
    fn certified_outside(&self, (fx, fy): (f64, f64)) -> Certified {
        let last = (f64::from(self.nx as u32 - 1), f64::from(self.ny as u32 - 1));
        let beyond = (-fx).max(-fy).max(fx - last.0).max(fy - last.1);
        // (NaN certifies nothing.)
        Certified::levels().take_while(|level| beyond > level.cells()).last().unwrap_or(Certified::No)
    }

    /// Every cell's stored value, row by row (tests compare rasters by them).
    #[cfg(test)]
    pub(crate) fn cell_values(&self) -> &[i8] {
        &self.f
    }

    /// Area holding material (cells with a positive distance), mm².
    pub fn material_area_mm2(&self) -> f64 {
        self.blocks.iter().map(|&n| f64::from(n)).sum::<f64>() * self.cell_mm * self.cell_mm
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square(side: f64, cell: f64) -> Raster {
        let mut r = Raster::new(Rect { x_min: 0.0, y_min: 0.0, x_max: side, y_max: side }, cell);
        r.paint(
            true,
            |y, out| {
                if (0.0..side).contains(&y) {
                    out.push((0.0, side))
                }
            },
            |x, y, _| rect_signed_distance(&Rect { x_min: 0.0, y_min: 0.0, x_max: side, y_max: side }, x, y),
        );
        r
    }

    #[test]
    fn a_painted_square_holds_its_area_in_material() {
        let r = square(10.0, 0.05);
        assert!((r.material_area_mm2() - 100.0).abs() < 1e-6, "{}", r.material_area_mm2());
        assert!(r.is_material(5.0, 5.0));
        assert!(!r.is_material(-0.1, 5.0) && !r.is_material(5.0, 10.1));
    }

    #[test]
    fn a_boundary_is_placed_to_a_small_fraction_of_a_cell() {
        let r = square(10.0, 0.05);
        assert!(r.is_material(2.0, 9.995) && !r.is_material(2.0, 10.005));
        assert!(r.is_material(9.995, 5.0) && !r.is_material(10.005, 5.0));
    }

    #[test]
    fn clearing_a_capsule_removes_its_area() {
        let mut r = square(40.0, 0.02);
        let before = r.material_area_mm2();
        r.clear_capsule((10.0, 20.0), (30.0, 25.0), 3.0);
        let len = 20.0f64.hypot(5.0);
        let expected = 2.0 * 3.0 * len + std::f64::consts::PI * 9.0;
        let removed = before - r.material_area_mm2();
        assert!((removed - expected).abs() / expected < 0.005, "{removed} vs {expected}");
        assert!(!r.is_material(20.0, 22.5));
        assert!(r.is_material(20.0, 27.0));
    }

    #[test]
    fn the_edge_of_a_cleared_disc_is_exact_between_cell_centres() {
        let mut r = square(20.0, 0.1);
        r.clear_capsule((10.0, 10.0), (10.0, 10.0), 3.0);
        assert!(!r.is_material(12.99, 10.0));
        assert!(r.is_material(13.01, 10.0));
        assert!(!r.is_material(10.0 + 2.99 * 0.6, 10.0 + 2.99 * 0.8));
        assert!(r.is_material(10.0 + 3.01 * 0.6, 10.0 + 3.01 * 0.8));
    }

    #[test]
    fn capsules_partly_outside_the_raster_are_clipped() {
        let mut r = square(10.0, 0.1);
        r.clear_capsule((-5.0, -5.0), (15.0, -5.0), 6.0);
        assert!(!r.is_material(5.0, 0.5));
        assert!(r.is_material(5.0, 1.5));
    }

    #[test]
    fn a_position_off_the_raster_is_air_certified_as_far_as_every_position_around_it_is_off_too() {
        let r = square(10.0, 0.1);
        let (last_i, last_j) = ((r.size().0 - 1) as f64, (r.size().1 - 1) as f64);
        let levels: Vec<Certified> = Certified::levels().collect();
        let (near, far) = (levels[0], levels[levels.len() - 1]);
        // Half a cell short of the nearest reach, and half a cell beyond each reach.
        for (d, expected) in [(near.cells() - 0.5, Certified::No), (near.cells() + 0.5, near), (far.cells() + 0.5, far)]
        {
            // Below, left of, above and right of the raster.
            for g in [(20.0, -d), (-d, 20.0), (20.0, last_j + d), (last_i + d, 20.0)] {
                assert_eq!(r.probe_at(g), (false, expected), "{d} cells off at {g:?}");
            }
        }
        assert_eq!(r.probe_at((f64::NAN, 5.0)), (false, Certified::No));
    }
}
