//! Whether two rasters of one grid hold the same cells over a rectangle. A probe reads
//! only cells (its 2 × 2 stencil, see [`Raster::is_material_at`]; the tile counts it may
//! also read only tell how far its answer holds), so where two rasters hold the same
//! cells, every probe gives the same answer on both.

use super::Raster;

/// Rows of fewer cells than this are compared cell by cell (a library call costs more).
const SHORT_ROW_CELLS: usize = 32;
/// A probe this far beyond a reach still reads only the rectangle, cells (rounding).
const ROUNDING_CELLS: f64 = 1.0;

/// A rectangle of cells: columns and rows, each a half-open range.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct CellRect {
    pub columns: (usize, usize),
    pub rows: (usize, usize),
}

impl CellRect {
    /// `true` when `other` lies inside `self`.
    pub fn contains(&self, other: &CellRect) -> bool {
        self.columns.0 <= other.columns.0
            && other.columns.1 <= self.columns.1
            && self.rows.0 <= other.rows.0
            && other.rows.1 <= self.rows.1
    }

    /// `true` when cell (i, j) lies inside.
    pub fn holds(&self, (i, j): (usize, usize)) -> bool {
        (self.columns.0..self.columns.1).contains(&i) && (self.rows.0..self.rows.1).contains(&j)
    }

    /// `true` when no cell lies inside.
    pub fn is_empty(&self) -> bool {
        self.columns.0 >= self.columns.1 || self.rows.0 >= self.rows.1
    }

    /// The cells of `self` outside `other`, as at most four rectangles (the rows below
    /// and above `other`, then the columns left and right of it in the rows between);
    /// empty ones are left out.
    pub fn minus(&self, other: &CellRect) -> impl Iterator<Item = CellRect> {
        let clamp = |v: usize, (lo, hi): (usize, usize)| v.clamp(lo, hi);
        let (r0, r1) = (clamp(other.rows.0, self.rows), clamp(other.rows.1, self.rows));
        let (c0, c1) = (clamp(other.columns.0, self.columns), clamp(other.columns.1, self.columns));
        let middle = (r0, r1.max(r0));
        [
            CellRect { columns: self.columns, rows: (self.rows.0, r0) },
            CellRect { columns: self.columns, rows: (r1.max(r0), self.rows.1) },
            CellRect { columns: (self.columns.0, c0), rows: middle },
            CellRect { columns: (c1.max(c0), self.columns.1), rows: middle },
        ]
        .into_iter()
        .filter(|r| !r.is_empty())
    }
}

impl Raster {
    /// The cells read by every probe within `reach_mm` of `(x, y)`, and of the points up
    /// to `ahead_cells` further along the unit vector `dir`.
    pub fn cells_read_near(&self, (x, y): (f64, f64), reach_mm: f64, dir: (f64, f64), ahead_cells: f64) -> CellRect {
        let (gx, gy) = self.grid_position(x, y);
        let reach = reach_mm * self.inv_cell + ROUNDING_CELLS;
        let span = |g: f64, d: f64, n: usize| {
            let (lo, hi) = (g - reach + (d * ahead_cells).min(0.0), g + reach + (d * ahead_cells).max(0.0));
            // Positions lo..hi read cells floor(lo)..=floor(hi) + 1.
            let first = lo.max(0.0) as usize;
            let end = (hi.max(0.0) as usize + 2).min(n);
            (first.min(end), end)
        };
        CellRect { columns: span(gx, dir.0, self.nx), rows: span(gy, dir.1, self.ny) }
    }

    /// The first cell of `rect` (row by row) where `self` and `other`, two rasters of
    /// one grid, differ; `None` when they hold the same cells there.
    pub fn first_difference(&self, other: &Raster, rect: CellRect) -> Option<(usize, usize)> {
        debug_assert!(self.nx == other.nx && self.ny == other.ny, "rasters of different grids");
        let (c0, c1) = rect.columns;
        (rect.rows.0..rect.rows.1).find_map(|j| {
            let cells = j * self.nx + c0..j * self.nx + c1;
            let (a, b) = (&self.f[cells.clone()], &other.f[cells]);
            // Short stretches byte by byte; long ones with the library's comparison.
            let same = if a.len() < SHORT_ROW_CELLS { a.iter().zip(b).all(|(u, v)| u == v) } else { a == b };
            (!same).then(|| (c0 + a.iter().zip(b).position(|(u, v)| u != v).unwrap_or(0), j))
        })
    }

    /// A cell of `rect` in the row or the column of cell `c` where `self` and `other`
    /// differ, if any.
    pub fn first_difference_across(
        &self,
        other: &Raster,
        rect: CellRect,
        (i, j): (usize, usize),
    ) -> Option<(usize, usize)> {
        let row =
            (rect.rows.0..rect.rows.1).contains(&j).then_some(CellRect { columns: rect.columns, rows: (j, j + 1) });
        let column =
            (rect.columns.0..rect.columns.1).contains(&i).then_some(CellRect { columns: (i, i + 1), rows: rect.rows });
        [row, column].into_iter().flatten().find_map(|line| self.first_difference(other, line))
    }

    /// As [`Raster::first_difference`] over the cells of `rect` outside `known_same`
    /// (where the rasters are known to hold the same cells), if any.
    pub fn first_difference_beyond(
        &self,
        other: &Raster,
        rect: CellRect,
        known_same: Option<CellRect>,
    ) -> Option<(usize, usize)> {
        match known_same {
            Some(known) => rect.minus(&known).find_map(|part| self.first_difference(other, part)),
            None => self.first_difference(other, rect),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::{rect_signed_distance, Rect};
    use super::*;

    /// A 20 × 20 mm block of material, cells of 0.1 mm.
    fn block() -> Raster {
        let rect = Rect { x_min: 0.0, y_min: 0.0, x_max: 20.0, y_max: 20.0 };
        let mut a = Raster::new(rect, 0.1);
        a.paint(true, |_, out| out.push((0.0, 20.0)), |x, y, _| rect_signed_distance(&rect, x, y));
        a
    }

    #[test]
    fn rasters_differ_only_where_one_of_them_was_cut() {
        let a = block();
        let mut b = a.clone();
        b.clear_capsule((15.0, 15.0), (15.0, 15.0), 2.0);
        let far = a.cells_read_near((5.0, 5.0), 2.0, (1.0, 0.0), 20.0);
        assert_eq!(a.first_difference(&b, far), None);
        let near = a.cells_read_near((11.0, 15.0), 2.0, (0.0, 1.0), 0.0);
        let (i, j) = a.first_difference(&b, near).expect("the cut disc is read");
        assert!(near.holds((i, j)));
        // The difference lies within the disc and its band.
        let (x, y) = (0.1 * i as f64 + a.x0 + 0.05, 0.1 * j as f64 + a.y0 + 0.05);
        assert!((x - 15.0).hypot(y - 15.0) < 2.0 + 0.3, "({x}, {y})");
    }

    #[test]
    fn a_difference_is_looked_for_along_the_row_and_the_column_of_a_cell() {
        let a = block();
        let mut b = a.clone();
        b.clear_capsule((10.0, 10.0), (10.0, 10.0), 1.0);
        let all = CellRect { columns: (0, a.nx), rows: (0, a.ny) };
        let (ci, cj) = a.first_difference(&b, all).expect("the cut differs");
        // Along the row of the disc's centre, or its column, a difference is found there.
        let centre = (((10.0 - a.x0) / 0.1) as usize, ((10.0 - a.y0) / 0.1) as usize);
        let (i, j) = a.first_difference_across(&b, all, (3, centre.1)).expect("the centre row crosses the disc");
        assert_eq!(j, centre.1);
        assert!(i.abs_diff(centre.0) <= 12, "{i} vs {}", centre.0);
        let (i, _) = a.first_difference_across(&b, all, (centre.0, 3)).expect("the centre column crosses it");
        assert_eq!(i, centre.0);
        // Far from the disc in both, none.
        assert_eq!(a.first_difference_across(&b, all, (5, 5)), None);
        // Outside the rectangle's rows and columns, nothing is looked at.
        let corner = CellRect { columns: (0, 20), rows: (0, 20) };
        assert_eq!(a.first_difference_across(&b, corner, (ci, cj)), None);
    }

    #[test]
    fn a_rectangle_minus_another_keeps_exactly_the_cells_outside_it() {
        let a = CellRect { columns: (10, 20), rows: (5, 15) };
        for other in [
            CellRect { columns: (12, 22), rows: (3, 13) },
            CellRect { columns: (0, 100), rows: (0, 100) },
            CellRect { columns: (30, 40), rows: (5, 15) },
            CellRect { columns: (14, 16), rows: (8, 9) },
        ] {
            let parts: Vec<CellRect> = a.minus(&other).collect();
            for i in 0..30 {
                for j in 0..30 {
                    let inside = parts.iter().filter(|p| p.holds((i, j))).count();
                    let expected = usize::from(a.holds((i, j)) && !other.holds((i, j)));
                    assert_eq!(inside, expected, "cell ({i}, {j}) minus {other:?}");
                }
            }
        }
    }

    #[test]
    fn a_reach_ahead_widens_the_cells_read_on_the_side_it_points_to() {
        let r = Raster::new(Rect { x_min: 0.0, y_min: 0.0, x_max: 50.0, y_max: 50.0 }, 0.1);
        let here = r.cells_read_near((25.0, 25.0), 3.0, (-1.0, 0.0), 0.0);
        let ahead = r.cells_read_near((25.0, 25.0), 3.0, (-1.0, 0.0), 40.0);
        assert!(ahead.contains(&here) && ahead.columns.0 + 40 == here.columns.0 && ahead.columns.1 == here.columns.1);
        assert_eq!(ahead.rows, here.rows);
    }
}
