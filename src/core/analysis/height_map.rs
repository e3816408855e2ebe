//! The stock a job left as a height map, for the page's 3-D view (issue 32 item 5): per
//! cell of a grid, the top of the material there.
//!
//! A kept stock ([`super::kept`]) is a stack of slices, top first, each a raster of which
//! cells hold material. A cell's **top** is the `z_top` of the highest slice whose cell
//! holds material; a cell no slice holds material in (cut through the layer, or never
//! stock: outside a pocket's contour) has its top at the layer's bottom. Every cell with
//! material has its top above the layer's bottom, so the bottom itself means "no material"
//! without a special value.
//!
//! **Downsampling.** A height map of at most `max_cells` cells gathers square blocks of
//! `block × block` kept cells, the smallest block that fits, and gives each the **highest**
//! top in it: conservative, as a stock for collision checks is (material is never drawn
//! lower than it is). The blocks of the last column and row may reach past the kept grid;
//! they take the tops of the kept cells they cover.

use super::kept::KeptStock;
use crate::core::stock::Grid;

/// Cells of a height map unless asked otherwise (256 × 256).
pub const DEFAULT_HEIGHT_MAP_CELLS: usize = 256 * 256;
/// The fewest cells a height map may be asked for (2 × 2).
pub const MIN_HEIGHT_MAP_CELLS: usize = 4;
/// The most cells a height map may be asked for (1024 × 1024: 4 MiB of f32).
pub const MAX_HEIGHT_MAP_CELLS: usize = 1024 * 1024;

/// A kept stock's tops over a grid.
#[derive(Debug, Clone, PartialEq)]
pub struct HeightMap {
    /// The height map's grid: the kept grid's origin, its cell times `block`.
    pub grid: Grid,
    /// Kept cells per side of a height-map cell.
    pub block: usize,
    /// The layer's top and bottom, mm.
    pub z_top_mm: f64,
    pub z_bottom_mm: f64,
    /// Per cell, row by row from the bottom (y up), the top of the material, mm; the
    /// layer's bottom where there is none.
    pub tops_mm: Vec<f32>,
}

impl HeightMap {
    /// Cells that hold material somewhere in the layer.
    pub fn material_cells(&self) -> usize {
        let bottom = self.z_bottom_mm as f32;
        self.tops_mm.iter().filter(|&&t| t > bottom).count()
    }
}

/// The smallest block (kept cells per side) that brings `grid` to at most `max_cells`
/// cells (at least one cell).
pub fn block_for(grid: &Grid, max_cells: usize) -> usize {
    let max_cells = max_cells.max(1);
    let fits = |b: usize| grid.nx.div_ceil(b).saturating_mul(grid.ny.div_ceil(b)) <= max_cells;
    // The block of a square root of the ratio is close; step up from just below it.
    let ratio = grid.cells() as f64 / max_cells as f64;
    let mut block = (ratio.sqrt().floor() as usize).max(1);
    while !fits(block) {
        block += 1;
    }
    block
}

/// The tops of `kept` at its own cells (see the module's doc), mm, row by row from the
/// bottom.
pub fn cell_tops_mm(kept: &KeptStock) -> Vec<f32> {
    let bottom = kept.z_bottom() as f32;
    let mut tops = vec![f32::NEG_INFINITY; kept.grid.cells()];
    let mut previous = None;
    for slice in &kept.slices {
        // Slices that share a raster hold the same material: the first of them is highest.
        if previous == Some(slice.raster) {
            continue;
        }
        previous = Some(slice.raster);
        let Some(cells) = kept.rasters.get(slice.raster) else { continue };
        let z = slice.z_top as f32;
        for (top, &cell) in tops.iter_mut().zip(cells) {
            if cell > 0 && top.is_infinite() {
                *top = z;
            }
        }
    }
    for top in &mut tops {
        if top.is_infinite() {
            *top = bottom;
        }
    }
    tops
}

/// The height map of `kept` in at most `max_cells` cells (clamped to
/// [`MIN_HEIGHT_MAP_CELLS`]..=[`MAX_HEIGHT_MAP_CELLS`]), each the highest top of its block.
pub fn height_map(kept: &KeptStock, max_cells: usize) -> HeightMap {
    let g = kept.grid;
    let block = block_for(&g, max_cells.clamp(MIN_HEIGHT_MAP_CELLS, MAX_HEIGHT_MAP_CELLS));
    let (nx, ny) = (g.nx.div_ceil(block), g.ny.div_ceil(block));
    let cell_tops = cell_tops_mm(kept);
    let mut tops = vec![f32::NEG_INFINITY; nx * ny];
    if g.nx > 0 {
        for (j, row) in cell_tops.chunks_exact(g.nx).enumerate() {
            let out = &mut tops[(j / block) * nx..][..nx];
            for (top, cells) in out.iter_mut().zip(row.chunks(block)) {
                *top = cells.iter().copied().fold(*top, f32::max);
            }
        }
    }
    let grid = Grid { x0_mm: g.x0_mm, y0_mm: g.y0_mm, cell_mm: g.cell_mm * block as f64, nx, ny };
    HeightMap { grid, block, z_top_mm: kept.z_top(), z_bottom_mm: kept.z_bottom(), tops_mm: tops }
}

#[cfg(test)]
#[path = "height_map_tests.rs"]
mod tests;
