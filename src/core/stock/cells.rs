//! A raster's cells as plain data, to keep a simulated stock after its job and start
//! another job from it (issue 32 item 3): the grid and every cell's stored distance, and
//! the raster rebuilt from them exactly (the same cells, so the same probes).

use super::{Raster, FULL};

/// Where a raster lies: its origin (the corner of cell (0, 0)), its cell and its size.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Grid {
    pub x0_mm: f64,
    pub y0_mm: f64,
    pub cell_mm: f64,
    pub nx: usize,
    pub ny: usize,
}

impl Grid {
    /// Its number of cells.
    pub fn cells(&self) -> usize {
        self.nx.saturating_mul(self.ny)
    }
}

impl Grid {
    /// The grid of cells of `cell_mm` from the lower-left corner of `grids`' union to its
    /// upper-right corner (`None` without grids).
    pub fn covering(grids: &[Grid], cell_mm: f64) -> Option<Grid> {
        let x0_mm = grids.iter().map(|g| g.x0_mm).reduce(f64::min)?;
        let y0_mm = grids.iter().map(|g| g.y0_mm).reduce(f64::min)?;
        let x1 = grids.iter().map(|g| g.x0_mm + g.nx as f64 * g.cell_mm).fold(x0_mm, f64::max);
        let y1 = grids.iter().map(|g| g.y0_mm + g.ny as f64 * g.cell_mm).fold(y0_mm, f64::max);
        let count = |span: f64| ((span / cell_mm) - COVER_SLACK_CELLS).ceil().max(1.0) as usize;
        Some(Grid { x0_mm, y0_mm, cell_mm, nx: count(x1 - x0_mm), ny: count(y1 - y0_mm) })
    }
}

/// A span this close to a whole number of cells takes no extra cell, cells.
const COVER_SLACK_CELLS: f64 = 1e-6;

/// `cells` of grid `from` on grid `to`: each cell's stored distance interpolated bilinearly
/// from the four cell centres of `from` around its centre, as a probe reads it; outside
/// `from`, far outside material.
pub fn resample(cells: &[i8], from: Grid, to: Grid) -> Vec<i8> {
    let at = |i: isize, j: isize| -> f64 {
        let inside = (0..from.nx as isize).contains(&i) && (0..from.ny as isize).contains(&j);
        let k = (j.max(0) as usize) * from.nx + i.max(0) as usize;
        f64::from(if inside { cells[k] } else { -FULL })
    };
    let mut out = Vec::with_capacity(to.cells());
    for row in 0..to.ny {
        let gy = (to.y0_mm + (row as f64 + 0.5) * to.cell_mm - from.y0_mm) / from.cell_mm - 0.5;
        let (j, ty) = (gy.floor() as isize, gy - gy.floor());
        for col in 0..to.nx {
            let gx = (to.x0_mm + (col as f64 + 0.5) * to.cell_mm - from.x0_mm) / from.cell_mm - 0.5;
            let (i, tx) = (gx.floor() as isize, gx - gx.floor());
            let bottom = at(i, j) * (1.0 - tx) + at(i + 1, j) * tx;
            let top = at(i, j + 1) * (1.0 - tx) + at(i + 1, j + 1) * tx;
            out.push((bottom * (1.0 - ty) + top * ty).round().clamp(f64::from(-FULL), f64::from(FULL)) as i8);
        }
    }
    out
}

impl Raster {
    /// The grid of the raster.
    pub fn layout_grid(&self) -> Grid {
        Grid { x0_mm: self.x0, y0_mm: self.y0, cell_mm: self.cell_mm, nx: self.nx, ny: self.ny }
    }

    /// Every cell's stored distance, row by row (bottom row first).
    pub fn cells(&self) -> &[i8] {
        &self.f
    }

    /// The centre of the first cell (row by row from the bottom) as deep in material as
    /// any cell, `(x, y)` mm; `None` without material.
    pub fn deepest_material_point(&self) -> Option<(f64, f64)> {
        let deepest = self.f.iter().copied().max().filter(|&v| v > 0)?;
        let k = self.f.iter().position(|&v| v == deepest)?;
        Some((self.col_x(k % self.nx), self.row_y(k / self.nx)))
    }

    /// The raster of `grid` holding `cells` (as [`Raster::cells`] gave them). `Err` says
    /// what is wrong: a grid that is not finite or positive, a cell count that is not the
    /// grid's, or a value beyond the clamp.
    pub fn from_cells(grid: Grid, cells: Vec<i8>) -> Result<Raster, String> {
        if !(grid.x0_mm.is_finite() && grid.y0_mm.is_finite() && grid.cell_mm.is_finite() && grid.cell_mm > 0.0) {
            return Err("the grid's origin and cell must be finite, the cell above 0".to_string());
        }
        if grid.nx < 2 || grid.ny < 2 || u32::try_from(grid.nx.max(grid.ny)).is_err() {
            return Err(format!("a grid of {} × {} cells", grid.nx, grid.ny));
        }
        if cells.len() != grid.cells() {
            return Err(format!("{} cells for a grid of {} × {}", cells.len(), grid.nx, grid.ny));
        }
        if cells.iter().any(|v| v.unsigned_abs() > FULL.unsigned_abs()) {
            return Err(format!("a cell beyond ±{FULL}"));
        }
        let bounds = super::Rect { x_min: grid.x0_mm, y_min: grid.y0_mm, x_max: grid.x0_mm, y_max: grid.y0_mm };
        let mut raster = Raster::new(bounds, grid.cell_mm);
        raster.x0 = grid.x0_mm;
        raster.y0 = grid.y0_mm;
        raster.nx = grid.nx;
        raster.ny = grid.ny;
        raster.bx = grid.nx.div_ceil(super::BLOCK_CELLS);
        raster.blocks = vec![0; raster.bx * grid.ny.div_ceil(super::BLOCK_CELLS)];
        raster.written = super::Written::new(raster.blocks.len());
        raster.f = cells;
        raster.recount();
        Ok(raster)
    }
}

#[cfg(test)]
mod tests {
    use super::super::test_blocks::block;
    use super::*;

    #[test]
    fn cells_brought_onto_a_covering_grid_keep_their_values_and_are_far_outside_beyond() {
        let from = Grid { x0_mm: 1.0, y0_mm: 2.0, cell_mm: 0.5, nx: 2, ny: 2 };
        let other = Grid { x0_mm: 0.0, y0_mm: 2.0, cell_mm: 0.5, nx: 4, ny: 3 };
        let to = Grid::covering(&[from, other], 0.5).expect("two grids");
        assert_eq!(to, Grid { x0_mm: 0.0, y0_mm: 2.0, cell_mm: 0.5, nx: 4, ny: 3 });
        let cells = [10, -20, 30, 40];
        assert_eq!(resample(&cells, from, from), cells);
        let moved = resample(&cells, from, to);
        // Cell (i, j) of `from` is cell (i + 2, j) of `to`; the rest is far outside.
        assert_eq!(&moved[2..4], &[10, -20]);
        assert_eq!(&moved[6..8], &[30, 40]);
        assert!(moved[..2].iter().chain(&moved[4..6]).chain(&moved[8..]).all(|&v| v == -FULL), "{moved:?}");
    }

    #[test]
    fn a_raster_rebuilt_from_its_cells_holds_the_same_cells_counts_and_probes() {
        let mut raster = block();
        raster.clear_capsule((2.0, 2.0), (6.0, 5.0), 1.3);
        let again = Raster::from_cells(raster.layout_grid(), raster.cells().to_vec()).expect("its own cells");
        assert_eq!(again.cells(), raster.cells());
        assert_eq!(again.layout_grid(), raster.layout_grid());
        assert!((again.material_area_mm2() - raster.material_area_mm2()).abs() < 1e-12);
        for (x, y) in [(2.0, 2.0), (4.0, 3.4), (4.0, 4.9), (7.5, 7.5), (-1.0, 0.0)] {
            let g = raster.grid_position(x, y);
            assert_eq!(again.probe_at(g), raster.probe_at(g), "at ({x}, {y})");
        }
    }

    #[test]
    fn cells_that_do_not_fit_the_grid_or_the_clamp_are_refused() {
        let raster = block();
        let grid = raster.layout_grid();
        assert!(Raster::from_cells(grid, vec![0; grid.cells() - 1]).is_err());
        assert!(Raster::from_cells(grid, vec![i8::MIN; grid.cells()]).is_err());
        assert!(Raster::from_cells(Grid { cell_mm: f64::NAN, ..grid }, raster.cells().to_vec()).is_err());
        assert!(Raster::from_cells(Grid { nx: 1, ny: grid.cells(), ..grid }, raster.cells().to_vec()).is_err());
    }
}
