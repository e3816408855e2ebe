//! Material counts over small square tiles of a raster, and per tile how many tiles of
//! its neighbourhood are not all air / not all material. A probe whose tile has a
//! uniform neighbourhood decides a whole disc around it: the probe's predicate reads
//! only the 2 × 2 cells around a point, and all of them lie in that neighbourhood.

/// Side of a tile, cells.
pub const TILE_CELLS: usize = 8;
/// Neighbourhood radii, tiles (Chebyshev): level 1 is the 3 × 3 tiles around a tile,
/// level 2 the 5 × 5.
const LEVEL_RADII: [usize; 2] = [1, 2];
/// Material cells in a tile whose cells all hold material.
const CELLS_PER_TILE: u8 = (TILE_CELLS * TILE_CELLS) as u8;
/// Counts per tile in [`Tiles::mixed`]: not air, then not material, per level.
const COUNTS: usize = 2 * LEVEL_RADII.len();
/// Tiles around the raster's tiles in [`Tiles::mixed`], so that no neighbourhood is
/// clipped at the raster's edge (their counts are never read).
const MARGIN: usize = LEVEL_RADII[LEVEL_RADII.len() - 1];
/// Side of the largest neighbourhood, tiles.
const SIDE: usize = 2 * MARGIN + 1;
/// Per tile of the largest neighbourhood around a tile (row, then column), per level: 1
/// when the level's neighbourhood holds it, else 0.
const REACH: [[[u8; LEVEL_RADII.len()]; SIDE]; SIDE] = reach();

const fn reach() -> [[[u8; LEVEL_RADII.len()]; SIDE]; SIDE] {
    let mut table = [[[0; LEVEL_RADII.len()]; SIDE]; SIDE];
    let mut row = 0;
    while row < SIDE {
        let mut column = 0;
        while column < SIDE {
            let (dy, dx) = (row.abs_diff(MARGIN), column.abs_diff(MARGIN));
            let ring = if dy > dx { dy } else { dx };
            let mut l = 0;
            while l < LEVEL_RADII.len() {
                if ring <= LEVEL_RADII[l] {
                    table[row][column][l] = 1;
                }
                l += 1;
            }
            column += 1;
        }
        row += 1;
    }
    table
}

/// How far around a point a uniform neighbourhood reaches.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Certified {
    /// Nothing beyond the point itself.
    No,
    /// Every point within [`Certified::cells`] (Chebyshev, cells) has the same state.
    Level(usize),
}

impl Certified {
    /// Radius of the uniform disc, cells: a stencil base cell in tile `t` and a point
    /// within `TILE_CELLS · radius − 1` cells keep the point's 2 × 2 cells inside the
    /// neighbourhood of that radius.
    pub fn cells(self) -> f64 {
        match self {
            Certified::No => 0.0,
            Certified::Level(l) => (TILE_CELLS * LEVEL_RADII[l - 1] - 1) as f64,
        }
    }

    /// The levels, smallest first.
    pub fn levels() -> impl Iterator<Item = Certified> {
        (1..=LEVEL_RADII.len()).map(Certified::Level)
    }
}

/// Per-tile counts of one raster.
#[derive(Debug, PartialEq)]
pub struct Tiles {
    /// Tiles per row and per column.
    tx: usize,
    ty: usize,
    /// Material cells per tile.
    material: Vec<u8>,
    /// Per tile and level: tiles of the neighbourhood that are not all air, then tiles
    /// that are not all material (tiles outside the raster count as air, not material).
    /// Rows of `stride` tiles, with a [`MARGIN`] around the raster's tiles.
    mixed: Vec<[u8; COUNTS]>,
    stride: usize,
    /// Per row of tiles, one bit per tile that holds material (bit `ti % 64` of word
    /// `ti / 64`), so that runs of tiles without material are passed over at once.
    holding: Vec<u64>,
    /// Words of `holding` per row of tiles.
    words: usize,
}

/// Tiles per word of [`Tiles::holding`].
const TILES_PER_WORD: usize = u64::BITS as usize;

impl Clone for Tiles {
    fn clone(&self) -> Tiles {
        let mut copy = Tiles { material: Vec::new(), mixed: Vec::new(), holding: Vec::new(), ..*self };
        copy.clone_from(self);
        copy
    }

    /// Into the memory this one holds.
    fn clone_from(&mut self, source: &Tiles) {
        let Tiles { tx, ty, material, mixed, stride, holding, words } = source;
        (self.tx, self.ty, self.stride, self.words) = (*tx, *ty, *stride, *words);
        self.material.clone_from(material);
        self.mixed.clone_from(mixed);
        self.holding.clone_from(holding);
    }
}

impl Tiles {
    /// Counts for an all-air raster of `nx` × `ny` cells.
    pub fn new(nx: usize, ny: usize) -> Tiles {
        let (tx, ty) = (nx.div_ceil(TILE_CELLS), ny.div_ceil(TILE_CELLS));
        let mut counts = [0u8; COUNTS];
        for (l, r) in LEVEL_RADII.iter().enumerate() {
            counts[LEVEL_RADII.len() + l] = ((2 * r + 1) * (2 * r + 1)) as u8;
        }
        let words = tx.div_ceil(TILES_PER_WORD);
        let stride = tx + 2 * MARGIN;
        Tiles {
            tx,
            ty,
            material: vec![0; tx * ty],
            mixed: vec![counts; stride * (ty + 2 * MARGIN)],
            stride,
            holding: vec![0; words * ty],
            words,
        }
    }

    /// Adds the material cells of row `j` (every cell of it, in order) to the tiles'
    /// counts, leaving the neighbourhood counts to [`Tiles::spread_counts`].
    pub fn count_row(&mut self, j: usize, row: &[i8]) {
        let tiles = &mut self.material[(j / TILE_CELLS) * self.tx..];
        for (ti, cells) in row.chunks(TILE_CELLS).enumerate() {
            // (At most a tile's cells, which fit the count's type.)
            tiles[ti] += cells.iter().filter(|&&v| v > 0).count() as u8;
        }
    }

    /// Sets the neighbourhood counts from the material counts, which were counted
    /// ([`Tiles::count_row`]) into the counts of an all-air raster.
    pub fn spread_counts(&mut self) {
        for tj in 0..self.ty {
            for ti in 0..self.tx {
                let material = self.material[tj * self.tx + ti];
                if material > 0 {
                    self.spread(ti, tj, 0, true);
                }
                if material == CELLS_PER_TILE {
                    self.spread(ti, tj, LEVEL_RADII.len(), false);
                }
            }
        }
    }

    /// Records that cell (i, j) gained (`gained`) or lost its material. (Tests build
    /// counts with it; rasters count whole rows, then losses a tile's stretch at a time.)
    #[cfg(test)]
    pub fn update(&mut self, i: usize, j: usize, gained: bool) {
        let (ti, tj) = (i / TILE_CELLS, j / TILE_CELLS);
        let t = tj * self.tx + ti;
        let before = self.material[t];
        let after = if gained { before + 1 } else { before - 1 };
        self.material[t] = after;
        // A tile turns from air to not air (or back) between 0 and 1 material cells,
        // from not material to material (or back) between 63 and 64.
        if before.min(after) == 0 {
            self.spread(ti, tj, 0, gained);
        }
        if before.max(after) == CELLS_PER_TILE {
            self.spread(ti, tj, LEVEL_RADII.len(), !gained);
        }
    }

    /// Records that `lost` (at least one) material cells of the tile holding cell (i, j)
    /// were cleared.
    #[inline]
    pub fn lose(&mut self, i: usize, j: usize, lost: usize) {
        let (ti, tj) = (i / TILE_CELLS, j / TILE_CELLS);
        let t = tj * self.tx + ti;
        let before = self.material[t];
        // (At most a tile's cells, which fit the count's type.)
        let after = before - lost as u8;
        self.material[t] = after;
        if before == CELLS_PER_TILE {
            self.spread(ti, tj, LEVEL_RADII.len(), true);
        }
        if after == 0 {
            self.spread(ti, tj, 0, false);
        }
    }

    /// Records that every material cell of tile (ti, tj) (at least one) was cleared;
    /// returns how many.
    #[inline]
    pub fn empty(&mut self, ti: usize, tj: usize) -> u8 {
        let t = tj * self.tx + ti;
        let lost = self.material[t];
        self.material[t] = 0;
        if lost == CELLS_PER_TILE {
            self.spread(ti, tj, LEVEL_RADII.len(), true);
        }
        self.spread(ti, tj, 0, false);
        lost
    }

    /// Adds (`more`) or removes one mixed tile at (ti, tj) from the counts of `offset`
    /// (0: not air, LEVEL_RADII.len(): not material) of its neighbours.
    fn spread(&mut self, ti: usize, tj: usize, offset: usize, more: bool) {
        if offset == 0 {
            // The tile itself turns from air to not air, or back.
            let (word, bit) = (&mut self.holding[tj * self.words + ti / TILES_PER_WORD], 1 << (ti % TILES_PER_WORD));
            *word = if more { *word | bit } else { *word & !bit };
        }
        // The neighbourhood's corner: the margin keeps it inside `mixed`. Every tile of
        // the largest neighbourhood is visited, adding 0 where a level does not reach:
        // no clipping and no branch.
        let corner = tj * self.stride + ti;
        let step = if more { 1 } else { u8::MAX };
        for (n, reach) in REACH.iter().enumerate() {
            let row = &mut self.mixed[corner + n * self.stride..][..SIDE];
            for (counts, levels) in row.iter_mut().zip(reach) {
                for (count, &inside) in counts[offset..offset + LEVEL_RADII.len()].iter_mut().zip(levels) {
                    // (Wrapping: adding u8::MAX takes one away.)
                    *count = count.wrapping_add(step * inside);
                }
            }
        }
    }

    /// The counts of tile (ti, tj).
    #[inline]
    fn mixed_at(&self, ti: usize, tj: usize) -> &[u8; COUNTS] {
        &self.mixed[(tj + MARGIN) * self.stride + ti + MARGIN]
    }

    /// The first column of tiles in `from..=to` whose tile in row `tj` holds material.
    #[inline]
    pub fn next_holding_material(&self, tj: usize, from: usize, to: usize) -> Option<usize> {
        let row = &self.holding[tj * self.words..(tj + 1) * self.words];
        let mut w = from / TILES_PER_WORD;
        let mut bits = row.get(w)? & (u64::MAX << (from % TILES_PER_WORD));
        loop {
            if bits != 0 {
                let t = w * TILES_PER_WORD + bits.trailing_zeros() as usize;
                return (t <= to).then_some(t);
            }
            w += 1;
            if w * TILES_PER_WORD > to {
                return None;
            }
            bits = *row.get(w)?;
        }
    }

    /// `true` when no cell of the 3 × 3 tiles around the tile of cell (i, j) holds
    /// material (which stays true: material is only ever removed).
    #[inline]
    pub fn without_material_near(&self, i: usize, j: usize) -> bool {
        self.mixed_at(i / TILE_CELLS, j / TILE_CELLS)[0] == 0
    }

    /// How far the state `material` of a point whose 2 × 2 cells start at cell (i, j)
    /// is known to hold.
    #[inline]
    pub fn certified(&self, i: usize, j: usize, material: bool) -> Certified {
        // Read through a reference, the counts are tested one at a time, a branch each,
        // which the processor predicts: a walk of certified probes along a line (see
        // `certified_ahead`) then places its next probe before this one's reads arrive.
        // (Compared as values, both were read and the level selected without a branch,
        // and such a walk waited for every read: tiger.nc at 0.05 mm took 6 % longer.)
        let counts = self.mixed_at(i / TILE_CELLS, j / TILE_CELLS);
        let base = if material { LEVEL_RADII.len() } else { 0 };
        match (1..=LEVEL_RADII.len()).rev().find(|&l| counts[base + l - 1] == 0) {
            Some(l) => Certified::Level(l),
            None => Certified::No,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_tile_far_from_material_is_certified_air_at_both_levels() {
        let mut t = Tiles::new(80, 80);
        assert_eq!(t.certified(40, 40, false), Certified::Level(2));
        // One material cell three tiles away leaves level 2 at (40, 40) but not at a tile
        // two tiles from it.
        t.update(40 + 3 * TILE_CELLS, 40, true);
        assert_eq!(t.certified(40, 40, false), Certified::Level(2));
        assert_eq!(t.certified(40 + TILE_CELLS, 40, false), Certified::Level(1));
        assert_eq!(t.certified(40 + 2 * TILE_CELLS, 40, false), Certified::No);
        t.update(40 + 3 * TILE_CELLS, 40, false);
        assert_eq!(t.certified(40 + 2 * TILE_CELLS, 40, false), Certified::Level(2));
    }

    #[test]
    fn only_tiles_surrounded_by_full_tiles_are_certified_material() {
        let mut t = Tiles::new(80, 80);
        for j in 0..80 {
            for i in 0..80 {
                t.update(i, j, true);
            }
        }
        assert_eq!(t.certified(40, 40, true), Certified::Level(2));
        // Tiles at the edge of the raster have neighbours outside it.
        assert_eq!(t.certified(0, 40, true), Certified::No);
        assert_eq!(t.certified(TILE_CELLS, 40, true), Certified::Level(1));
        t.update(40, 40, false);
        assert_eq!(t.certified(40 + TILE_CELLS, 40, true), Certified::No);
        assert_eq!(t.certified(40 + 2 * TILE_CELLS, 40, true), Certified::Level(1));
        assert_eq!(t.certified(40, 40, false), Certified::No);
    }

    #[test]
    fn the_next_tile_holding_material_is_found_across_words_and_forgotten_once_cleared() {
        // 200 tiles to a row: four words.
        let mut t = Tiles::new(200 * TILE_CELLS, 3 * TILE_CELLS);
        let row = TILE_CELLS + 3;
        for tile in [5, 70, 130] {
            t.update(tile * TILE_CELLS + 2, row, true);
        }
        assert_eq!(t.next_holding_material(1, 0, 199), Some(5));
        assert_eq!(t.next_holding_material(1, 6, 199), Some(70));
        assert_eq!(t.next_holding_material(1, 71, 129), None, "the range ends before tile 130");
        assert_eq!(t.next_holding_material(1, 71, 130), Some(130));
        assert_eq!(t.next_holding_material(0, 0, 199), None, "another row of tiles");
        t.update(70 * TILE_CELLS + 2, row, false);
        assert_eq!(t.next_holding_material(1, 6, 199), Some(130));
        t.lose(130 * TILE_CELLS, row, 1);
        assert_eq!(t.next_holding_material(1, 6, 199), None);
        assert_eq!(t.next_holding_material(1, 0, 4), None);
    }

    #[test]
    fn emptying_a_tile_at_once_gives_the_counts_of_losing_its_cells_one_by_one() {
        for cells in [1, 17, TILE_CELLS * TILE_CELLS] {
            let mut at_once = Tiles::new(80, 80);
            for n in 0..cells {
                at_once.update(24 + n % TILE_CELLS, 32 + n / TILE_CELLS, true);
            }
            let mut one_by_one = at_once.clone();
            assert_eq!(usize::from(at_once.empty(3, 4)), cells);
            for n in 0..cells {
                one_by_one.update(24 + n % TILE_CELLS, 32 + n / TILE_CELLS, false);
            }
            assert_eq!(at_once, one_by_one, "{cells} cells");
        }
    }

    #[test]
    fn the_neighbourhood_counts_are_the_mixed_tiles_around_each_tile_at_the_edges_too() {
        // 7 × 5 tiles with material in a corner, along an edge and inside; then some lost.
        let (tx, ty) = (7, 5);
        let mut t = Tiles::new(tx * TILE_CELLS, ty * TILE_CELLS - 3);
        let fill = |t: &mut Tiles, (ti, tj): (usize, usize), cells: usize, gained: bool| {
            for n in 0..cells {
                t.update(ti * TILE_CELLS + n % TILE_CELLS, tj * TILE_CELLS + n / TILE_CELLS, gained);
            }
        };
        for (tile, cells) in [((0, 0), 64), ((1, 0), 64), ((6, 2), 5), ((3, 2), 64), ((3, 4), 40), ((6, 4), 40)] {
            fill(&mut t, tile, cells, true);
        }
        fill(&mut t, (1, 0), 1, false);
        fill(&mut t, (6, 2), 5, false);
        let material = |ti: usize, tj: usize| t.material[tj * tx + ti];
        for tj in 0..ty {
            for ti in 0..tx {
                for (l, &r) in LEVEL_RADII.iter().enumerate() {
                    let around = |pick: &dyn Fn(u8) -> bool| {
                        let (mut n, side) = (0, 2 * r + 1);
                        for nj in (tj as i64 - r as i64)..=(tj + r) as i64 {
                            for ni in (ti as i64 - r as i64)..=(ti + r) as i64 {
                                let inside = (0..tx as i64).contains(&ni) && (0..ty as i64).contains(&nj);
                                // Tiles off the raster are air.
                                let m = if inside { material(ni as usize, nj as usize) } else { 0 };
                                n += usize::from(pick(m));
                            }
                        }
                        assert!(n <= side * side);
                        n as u8
                    };
                    let counts = t.mixed_at(ti, tj);
                    assert_eq!(counts[l], around(&|m| m > 0), "not air, level {}, tile ({ti}, {tj})", l + 1);
                    assert_eq!(
                        counts[LEVEL_RADII.len() + l],
                        around(&|m| m < CELLS_PER_TILE),
                        "not material, level {}, tile ({ti}, {tj})",
                        l + 1
                    );
                }
            }
        }
    }

    #[test]
    fn counting_whole_rows_gives_the_counts_of_cell_by_cell_updates() {
        // A disc of material with a hole, on a raster whose sides are not whole tiles.
        let (nx, ny) = (83, 77);
        let cells: Vec<i8> = (0..nx * ny)
            .map(|k| {
                let (x, y) = ((k % nx) as f64 - 40.0, (k / nx) as f64 - 38.0);
                let r = x.hypot(y);
                if r < 35.0 && r > 9.0 {
                    100
                } else {
                    -100
                }
            })
            .collect();
        let mut by_cell = Tiles::new(nx, ny);
        for (k, &v) in cells.iter().enumerate() {
            if v > 0 {
                by_cell.update(k % nx, k / nx, true);
            }
        }
        let mut by_row = Tiles::new(nx, ny);
        for (j, row) in cells.chunks_exact(nx).enumerate() {
            by_row.count_row(j, row);
        }
        by_row.spread_counts();
        assert_eq!(by_row, by_cell);
    }
}
