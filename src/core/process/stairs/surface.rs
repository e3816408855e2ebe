//! The die's surface under a cavity given in layers, as a height field: each layer's
//! contour is the cavity's section at the layer's bottom (what its roughing cuts down to),
//! and between two sections the surface runs straight from the upper section's edge down to
//! the lower one's, as the sections of a smooth die surface (a sloped wall or floor) lie
//! (seed 004 case II's slanted bottom). Where two layers share a contour the wall between
//! them is vertical; inside the last section the floor is flat.
//!
//! A point between the edges of sections `k` (height `z_k`) and `k + 1` (`z_{k+1}`) lies at
//! `z_k + (z_{k+1} − z_k) · d_k / (d_k + d_{k+1})`, `d_{k+1}` its distance to section `k + 1`
//! and `d_k` its distance to section `k`'s edge straight away from there (along the line from
//! the nearest point of section `k + 1` through it). So a floor sloping between the sections
//! meets a wall both share as the plane it is: the wall is vertical, and the point's height
//! is read across the slope, not towards the wall. The roughing left it at `z_k` (a vertical end mill cuts
//! each layer's contour to its bottom): the material between that and the surface is the
//! stair step the intermediate roughing removes. A 3-axis tool cannot undercut, so each
//! section is taken within the one above it.

use super::distance::nearest_feature;
use crate::core::process::cavity::Cavity;
use crate::core::stock::Grid;

/// What the surface of a cavity is, cell by cell.
#[derive(Debug, Clone)]
pub struct Surface {
    pub grid: Grid,
    /// The die's surface, mm (the top of the stock outside the cavity).
    pub height_mm: Vec<f64>,
    /// How deep the roughing cut, mm: the bottom of the deepest layer whose section holds
    /// the cell (the top outside the cavity).
    pub roughed_mm: Vec<f64>,
    /// The highest the roughing may have left material there, mm: the top of that layer
    /// (its tool leaves rest material up to it in corners and necks it cannot reach).
    pub rest_top_mm: Vec<f64>,
    /// The top of the cavity, mm.
    pub top_mm: f64,
}

impl Surface {
    /// The surface of `cavity` on a grid of `cell_mm` covering its first layer and
    /// `margin_mm` around it.
    pub fn of(cavity: &Cavity, cell_mm: f64, margin_mm: f64) -> Surface {
        let top_mm = cavity.top_mm();
        let bounds = cavity.layers.first().map(|l| l.pocket.bounds());
        let grid = match bounds {
            Some(b) => Grid {
                x0_mm: b.x_min - margin_mm,
                y0_mm: b.y_min - margin_mm,
                cell_mm,
                nx: ((b.x_max - b.x_min + 2.0 * margin_mm) / cell_mm).ceil().max(1.0) as usize,
                ny: ((b.y_max - b.y_min + 2.0 * margin_mm) / cell_mm).ceil().max(1.0) as usize,
            },
            None => Grid { x0_mm: 0.0, y0_mm: 0.0, cell_mm, nx: 1, ny: 1 },
        };
        let sections = sections(cavity, &grid);
        let n = grid.cells();
        let mut height_mm = vec![top_mm; n];
        let mut roughed_mm = vec![top_mm; n];
        let mut rest_top_mm = vec![top_mm; n];
        // The deepest section of every cell (sections nest, so it is the count of those that
        // hold it).
        let deepest: Vec<Option<usize>> =
            (0..n).map(|c| sections.iter().take_while(|s| s.inside[c]).count().checked_sub(1)).collect();
        let half_cell = cell_mm / 2.0;
        for (k, s) in sections.iter().enumerate() {
            let Some(next) = sections.get(k + 1) else {
                for c in (0..n).filter(|&c| deepest[c] == Some(k)) {
                    height_mm[c] = s.z_mm;
                    roughed_mm[c] = s.z_mm;
                    rest_top_mm[c] = s.top_mm;
                }
                continue;
            };
            let ring: Vec<usize> = (0..n).filter(|&c| deepest[c] == Some(k)).collect();
            if ring.is_empty() {
                continue;
            }
            let to_next = nearest_feature(&grid, &next.inside);
            for c in ring {
                let (b, q) = to_next[c];
                // Cell centres lie half a cell inside the edges they are measured from.
                let b = (b - half_cell).max(0.0);
                let a = (distance_to_edge(&grid, &s.inside, c, q) - half_cell).max(0.0);
                let t = if a + b > 0.0 && a.is_finite() && b.is_finite() { a / (a + b) } else { 0.0 };
                height_mm[c] = s.z_mm + (next.z_mm - s.z_mm) * t;
                roughed_mm[c] = s.z_mm;
                rest_top_mm[c] = s.top_mm;
            }
        }
        Surface { grid, height_mm, roughed_mm, rest_top_mm, top_mm }
    }

    /// The index of the cell that holds `(x, y)`, `None` off the grid.
    pub fn cell_at(&self, x: f64, y: f64) -> Option<usize> {
        let g = &self.grid;
        let (col, row) = ((x - g.x0_mm) / g.cell_mm, (y - g.y0_mm) / g.cell_mm);
        if col < 0.0 || row < 0.0 {
            return None;
        }
        let (col, row) = (col as usize, row as usize);
        (col < g.nx && row < g.ny).then_some(row * g.nx + col)
    }

    /// The centre of cell `c`, mm.
    pub fn centre(&self, c: usize) -> (f64, f64) {
        let g = &self.grid;
        let (col, row) = (c % g.nx, c / g.nx);
        (g.x0_mm + (col as f64 + 0.5) * g.cell_mm, g.y0_mm + (row as f64 + 0.5) * g.cell_mm)
    }

    /// The material the roughing left over the surface at cell `c`, mm of height.
    pub fn stair_mm(&self, c: usize) -> f64 {
        (self.roughed_mm[c] - self.height_mm[c]).max(0.0)
    }
}

/// Cells of a ray are stepped this many times per cell.
const RAY_STEPS_PER_CELL: f64 = 2.0;

/// The distance from cell `c` to the edge of the section `inside`, straight away from cell
/// `from` (the nearest of the next section), mm; to the grid's edge where the ray leaves it.
fn distance_to_edge(grid: &Grid, inside: &[bool], c: usize, from: usize) -> f64 {
    let centre = |k: usize| ((k % grid.nx) as f64 + 0.5, (k / grid.nx) as f64 + 0.5);
    let (px, py) = centre(c);
    let (qx, qy) = centre(from);
    let (dx, dy) = (px - qx, py - qy);
    let len = dx.hypot(dy);
    if len <= 0.0 {
        return f64::INFINITY;
    }
    let (ux, uy) = (dx / len / RAY_STEPS_PER_CELL, dy / len / RAY_STEPS_PER_CELL);
    let (mut x, mut y, mut steps) = (px, py, 0usize);
    loop {
        x += ux;
        y += uy;
        steps += 1;
        if x < 0.0 || y < 0.0 || x >= grid.nx as f64 || y >= grid.ny as f64 {
            break;
        }
        if !inside[y as usize * grid.nx + x as usize] {
            break;
        }
    }
    steps as f64 / RAY_STEPS_PER_CELL * grid.cell_mm
}

/// One section of the cavity: the cells it holds (within the section above), its height and
/// the top of its layer.
struct Section {
    inside: Vec<bool>,
    z_mm: f64,
    top_mm: f64,
}

/// The sections at the layers' bottoms, top first, each within the one above.
fn sections(cavity: &Cavity, grid: &Grid) -> Vec<Section> {
    let mut out: Vec<Section> = Vec::with_capacity(cavity.layers.len());
    let mut intervals = Vec::new();
    for layer in &cavity.layers {
        let mut inside = vec![false; grid.cells()];
        for row in 0..grid.ny {
            let y = grid.y0_mm + (row as f64 + 0.5) * grid.cell_mm;
            layer.pocket.row_intervals(y, &mut intervals);
            for &(x_from, x_to) in &intervals {
                let first = ((x_from - grid.x0_mm) / grid.cell_mm - 0.5).ceil().max(0.0) as usize;
                let last = ((x_to - grid.x0_mm) / grid.cell_mm - 0.5).floor();
                if last < 0.0 {
                    continue;
                }
                let last = (last as usize).min(grid.nx - 1);
                for col in first..=last {
                    inside[row * grid.nx + col] = true;
                }
            }
        }
        if let Some(above) = out.last() {
            inside.iter_mut().zip(&above.inside).for_each(|(i, a)| *i &= *a);
        }
        out.push(Section { inside, z_mm: layer.z_bottom_mm, top_mm: layer.z_top_mm });
    }
    out
}
