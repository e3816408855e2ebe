//! The rows of cells a capsule update touches, found once for every raster of one grid
//! (see [`Raster::clear_capsule_rows`]): the slices of a layer take the same capsules.

use super::capsule::{Capsule, FrontHalf};
use super::tiles::TILE_CELLS;
use super::{Raster, SDF_CLAMP_CELLS};

/// The cells of each row one capsule update touches. The rows are found when first
/// needed (not when no raster has material near); one value serves capsule after capsule
/// without allocating again ([`CapsuleRows::set`]).
pub struct CapsuleRows {
    a: (f64, f64),
    b: (f64, f64),
    r: f64,
    disc_at_a_cleared: bool,
    grid: (f64, f64, f64, usize, usize),
    /// The capsule widened by the band.
    outer: Capsule,
    /// Where material near the capsule is looked for: centre and reach, mm.
    near: ((f64, f64), f64),
    /// Row range, and whether the capsule misses the raster's rows.
    rows: (usize, usize),
    off_raster: bool,
    spans: Vec<RowSpans>,
    found: bool,
}

/// What a capsule update does in one row: band cells in two stretches, cells cleared
/// between them, and, when the disc at the start is already cleared, the cells of that
/// stretch that need no clearing.
struct RowSpans {
    j: usize,
    bands: [(usize, usize); 2],
    inside: (usize, usize),
    start_disc: (usize, usize),
}

impl CapsuleRows {
    /// The rows of the capsule swept by a disc of radius `r` from `a` to `b` on the grid
    /// of `grid` (see [`Raster::clear_capsule_after`] for `disc_at_a_cleared`).
    pub fn new(grid: &Raster, a: (f64, f64), b: (f64, f64), r: f64, disc_at_a_cleared: bool) -> CapsuleRows {
        CapsuleRows::with_spans(grid, a, b, r, disc_at_a_cleared, Vec::new())
    }

    /// Makes these the rows of another capsule, as [`CapsuleRows::new`], keeping the
    /// memory of the spans.
    pub fn set(&mut self, grid: &Raster, a: (f64, f64), b: (f64, f64), r: f64, disc_at_a_cleared: bool) {
        let mut spans = std::mem::take(&mut self.spans);
        spans.clear();
        *self = CapsuleRows::with_spans(grid, a, b, r, disc_at_a_cleared, spans);
    }

    /// As [`CapsuleRows::new`], the spans to be found into `spans` (empty).
    fn with_spans(
        grid: &Raster,
        a: (f64, f64),
        b: (f64, f64),
        r: f64,
        disc_at_a_cleared: bool,
        spans: Vec<RowSpans>,
    ) -> CapsuleRows {
        let reach = SDF_CLAMP_CELLS * grid.cell_mm;
        let y_lo = a.1.min(b.1) - r - reach;
        let y_hi = a.1.max(b.1) + r + reach;
        let rows = grid.index_range(y_lo, y_hi, grid.y0, grid.ny);
        let centre = ((a.0 + b.0) / 2.0, (a.1 + b.1) / 2.0);
        let half = ((b.0 - a.0).hypot(b.1 - a.1)) / 2.0 + r + reach;
        CapsuleRows {
            a,
            b,
            r,
            disc_at_a_cleared,
            grid: grid.grid(),
            outer: Capsule::new(a, b, r + reach),
            near: (centre, half),
            rows,
            off_raster: rows.1 == 0,
            spans,
            found: false,
        }
    }

    /// Finds the rows' spans on `grid`, unless they are already found.
    fn find_rows(&mut self, grid: &Raster) {
        if self.found {
            return;
        }
        self.found = true;
        let (a, r, outer) = (self.a, self.r, &self.outer);
        let reach = SDF_CLAMP_CELLS * grid.cell_mm;
        let inner = Capsule::new(a, self.b, (r - reach).max(0.0));
        let disc_at_a_cleared = self.disc_at_a_cleared;
        self.spans.extend((self.rows.0..self.rows.1).filter_map(|j| {
            let y = grid.row_y(j);
            let (lo, hi) = outer.row_interval(y)?;
            let (from, to) = grid.cell_range(lo, hi);
            let (in_from, in_to) = inner.row_interval(y).map_or((from, from), |(l, h)| grid.cell_range(l, h));
            let (in_from, in_to) = (in_from.max(from), in_to.max(in_from.max(from)));
            // Band cells behind the start by more than a cell need no test.
            let (front_from, front_to) = match disc_at_a_cleared.then(|| outer.front_half_line(y)).flatten() {
                Some(FrontHalf::Above(x)) => (grid.cell_range(x - grid.cell_mm, f64::INFINITY).0, to),
                Some(FrontHalf::Below(x)) => (from, grid.cell_range(f64::NEG_INFINITY, x + grid.cell_mm).1),
                None => (from, to),
            };
            let bands = [(from.max(front_from), in_from.min(front_to)), (in_to.max(front_from), to.min(front_to))];
            let (skip_from, skip_to) = match disc_at_a_cleared.then(|| inner.disc_chord(a, y)).flatten() {
                Some((l, h)) => grid.cell_range(l, h),
                None => (in_from, in_from),
            };
            let start_disc = (skip_from.clamp(in_from, in_to), skip_to.clamp(in_from, in_to));
            Some(RowSpans { j, bands, inside: (in_from, in_to), start_disc })
        }));
    }
}

impl Raster {
    /// As [`Raster::clear_capsule_after`] with the rows of a capsule found for a raster of
    /// the same grid.
    ///
    /// Air that no probe can read beside material is left as it is. A probe reads the
    /// 2 × 2 cells around its point, and where none of them holds material it answers air
    /// whatever their values. Material is only ever removed, so two kinds of cell never
    /// again share a probe with a material cell: those in a tile with no material in the
    /// 3 × 3 tiles around it (the band skips such tiles), and those deep inside the
    /// capsule (of which only the material is cleared, see `clear_cells`). Their
    /// values stay at or below zero and only underestimate the distance to the material
    /// that is left, so every probe gives the answer it would give had they been updated.
    pub fn clear_capsule_rows(&mut self, capsule: &mut CapsuleRows) -> bool {
        debug_assert!(capsule.grid == self.grid(), "a capsule's rows found on another grid");
        let skip_start_disc = capsule.disc_at_a_cleared && self.end_disc_cleared;
        self.end_disc_cleared = false;
        if capsule.off_raster {
            return false;
        }
        let ((x, y), reach) = capsule.near;
        if !self.any_material_near(x, y, reach) {
            return false;
        }
        capsule.find_rows(self);
        // A row of tiles at a time: the band and the inside cells of each row, except the
        // tiles inside the capsule in every one of their rows, which are cleared whole.
        let spans = &capsule.spans[..];
        let mut first = 0;
        while first < spans.len() {
            let tj = spans[first].j / TILE_CELLS;
            let end = spans[first..].iter().position(|row| row.j / TILE_CELLS != tj).map_or(spans.len(), |n| first + n);
            let group = &spans[first..end];
            first = end;
            let (t0, t1) = self.whole_tiles_inside(group);
            let whole = (t0 * TILE_CELLS, t1 * TILE_CELLS);
            for row in group {
                let j = row.j;
                for (from, to) in row.bands {
                    self.band_cells(j, from, to, &capsule.outer, capsule.r, capsule.disc_at_a_cleared);
                }
                let (in_from, in_to) = row.inside;
                let (skip_from, skip_to) = if skip_start_disc { row.start_disc } else { (in_from, in_from) };
                for (from, to) in [(in_from, skip_from), (skip_to.max(skip_from), in_to)] {
                    // The whole tiles are cleared below.
                    self.clear_cells(j, from, to.min(whole.0).max(from));
                    self.clear_cells(j, from.max(whole.1), to);
                }
            }
            self.clear_tiles(tj, t0, t1);
        }
        self.end_disc_cleared = true;
        true
    }

    /// The columns of tiles [t0, t1) of the row of tiles of `group` (the spans of its
    /// rows, in order) that lie inside the capsule in all of the tile's rows: cleared whole
    /// (see [`Raster::clear_tiles`]). Cells of the start disc among them are cleared
    /// already or cleared again, which changes nothing.
    fn whole_tiles_inside(&self, group: &[RowSpans]) -> (usize, usize) {
        let Some(first) = group.first() else {
            return (0, 0);
        };
        let rows_of_tile = TILE_CELLS.min(self.ny - first.j / TILE_CELLS * TILE_CELLS);
        if group.len() < rows_of_tile || self.updates_every_cell() {
            return (0, 0);
        }
        let from = group.iter().map(|row| row.inside.0).max().unwrap_or(0);
        let to = group.iter().map(|row| row.inside.1).min().unwrap_or(0);
        let (t0, t1) = (from.div_ceil(TILE_CELLS), to / TILE_CELLS);
        if t0 < t1 {
            (t0, t1)
        } else {
            (0, 0)
        }
    }
}
