//! The stock the stair-step roughing meets: what the roughing left (the plan's kept stock,
//! which holds the material inside each layer's own contour) with the steps added, the
//! material between the die's surface and the bottom of the layer over it, outside that
//! layer's contour. The roughing's layers never cut there, and their simulations, each on
//! its own contour, did not hold it.
//!
//! The kept slices are cut again at the step's levels, so that every slice holds the steps
//! as they stand across it: a cell holds them where the surface lies below the slice's middle
//! and the roughing's bottom above it (a 2.5-D slice's material is the same over its height,
//! and the middle keeps a wedge's volume). Their edges are painted to the surface's cell.

use super::distance::distance_to_mm;
use super::surface::Surface;
use crate::core::analysis::kept::{KeptSlice, KeptStock};
use crate::core::analysis::slices::Z_CONTACT_EPS_MM;
use crate::core::stock::Raster;

/// What the painting reads off the surface's grid: far outside the steps, mm (the grid
/// reaches past the cavity, so no step lies near its edge).
const OFF_GRID_MM: f64 = 1e3;

/// `kept` with the steps of `surface` in it, cut again at `levels_mm`.
pub fn with_steps(kept: &KeptStock, surface: &Surface, levels_mm: &[f64]) -> Result<KeptStock, String> {
    let mut cuts: Vec<f64> = kept.slices.iter().flat_map(|s| [s.z_top, s.z_bottom]).collect();
    cuts.extend(levels_mm.iter().copied().filter(|&z| z < kept.z_top() && z > kept.z_bottom()));
    cuts.sort_by(|a, b| b.total_cmp(a));
    cuts.dedup_by(|a, b| (*a - *b).abs() <= Z_CONTACT_EPS_MM);
    let mut slices = Vec::with_capacity(cuts.len());
    let mut rasters: Vec<Vec<i8>> = Vec::with_capacity(cuts.len());
    for pair in cuts.windows(2) {
        let (z_top, z_bottom) = (pair[0], pair[1]);
        let (base, _) = kept.rasters_over(z_top, z_bottom);
        let mid = (z_top + z_bottom) / 2.0;
        let steps: Vec<bool> = (0..surface.grid.cells())
            .map(|c| surface.height_mm[c] < mid && mid < surface.roughed_mm[c] && surface.height_mm[c] < surface.top_mm)
            .collect();
        let cells = if steps.iter().any(|&s| s) {
            painted(&kept.rasters[base], kept, surface, &steps)?
        } else {
            kept.rasters[base].clone()
        };
        if rasters.last() != Some(&cells) {
            rasters.push(cells);
        }
        slices.push(KeptSlice { z_top, z_bottom, raster: rasters.len() - 1 });
    }
    let out = KeptStock { grid: kept.grid, slices, rasters, cavity: kept.cavity, below: kept.below.clone() };
    out.validate()?;
    Ok(out)
}

/// The raster `cells` (on `kept`'s grid) with the cells of `steps` (on `surface`'s grid)
/// painted in as material.
fn painted(cells: &[i8], kept: &KeptStock, surface: &Surface, steps: &[bool]) -> Result<Vec<i8>, String> {
    let mut raster = Raster::from_cells(kept.grid, cells.to_vec())?;
    let g = &surface.grid;
    let outside: Vec<bool> = steps.iter().map(|&s| !s).collect();
    let to_outside = distance_to_mm(g, &outside);
    let to_inside = distance_to_mm(g, steps);
    let half_cell = g.cell_mm / 2.0;
    let intervals = |y: f64, out: &mut Vec<(f64, f64)>| {
        out.clear();
        let row = (y - g.y0_mm) / g.cell_mm;
        if row < 0.0 || row >= g.ny as f64 {
            return;
        }
        let base = row as usize * g.nx;
        let mut run: Option<usize> = None;
        for col in 0..=g.nx {
            let on = col < g.nx && steps[base + col];
            match (on, run) {
                (true, None) => run = Some(col),
                (false, Some(first)) => {
                    out.push((g.x0_mm + first as f64 * g.cell_mm, g.x0_mm + col as f64 * g.cell_mm));
                    run = None;
                }
                _ => {}
            }
        }
    };
    // Signed distance to the steps' edge, positive inside: a cell's centre lies half a cell
    // inside the edge it is measured from.
    let distance = |x: f64, y: f64, inside: bool| match surface.cell_at(x, y) {
        Some(c) if inside => (to_outside[c] - half_cell).max(0.0),
        Some(c) => -(to_inside[c] - half_cell).max(0.0),
        None => -OFF_GRID_MM,
    };
    raster.paint(true, intervals, distance);
    Ok(raster.cells().to_vec())
}
