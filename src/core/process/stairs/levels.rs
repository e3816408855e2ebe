//! The rings of one z level: where the tool's tip may go at that height (the region the
//! tip field leaves), its edge and the offsets inward at the radial depth, keeping those
//! that come within the tool's reach of material the roughing left above the level.

use super::distance::distance_to_mm;
use super::rings::{rings, Ring};
use super::surface::Surface;

/// Material thinner than this over the level is none, mm (**assumed**: below any
/// intermediate roughing's allowance).
pub const MATERIAL_MIN_MM: f64 = 0.01;

/// Most rings one level may offset inward (a guard against a degenerate radial depth on a
/// huge cavity; the request's checks keep far below it).
pub const MAX_RINGS_PER_LEVEL: usize = 4000;

/// A ring to cut and how far it lies inside the level's edge (0: the edge itself).
#[derive(Debug, Clone)]
pub struct LevelRing {
    pub offset: usize,
    pub ring: Ring,
}

/// What the tip may do at one level.
pub struct Level<'a> {
    pub surface: &'a Surface,
    /// `z − tip height` per cell: where it is ≥ 0 the tip may go down to the level.
    pub room_mm: Vec<f64>,
}

impl<'a> Level<'a> {
    /// The level `z_mm` over `surface`, whose tip heights are `tip_mm`.
    pub fn new(surface: &'a Surface, tip_mm: &[f64], z_mm: f64) -> Level<'a> {
        Level { surface, room_mm: tip_mm.iter().map(|t| z_mm - t).collect() }
    }

    /// Whether the tip may stand at `(x, y)` (the cell holding it, and off the grid never).
    pub fn allows(&self, x: f64, y: f64) -> bool {
        self.surface.cell_at(x, y).is_some_and(|c| self.room_mm[c] >= 0.0)
    }

    /// The rings to cut at `z_mm` with a tool of `radius_mm`, offset by `rd_mm`: the edge of
    /// the region the tip may reach and its offsets inward, each kept when one of its points
    /// comes within the tool's radius of material left above the level.
    pub fn rings(&self, z_mm: f64, radius_mm: f64, rd_mm: f64) -> Vec<LevelRing> {
        let s = self.surface;
        let g = &s.grid;
        let material: Vec<bool> =
            (0..g.cells()).map(|c| s.roughed_mm[c] > s.height_mm[c].max(z_mm) + MATERIAL_MIN_MM).collect();
        if !material.iter().any(|&m| m) || !self.room_mm.iter().any(|&r| r >= 0.0) {
            return Vec::new();
        }
        let to_material = distance_to_mm(g, &material);
        let outside: Vec<bool> = self.room_mm.iter().map(|&r| r < 0.0).collect();
        let depth = distance_to_mm(g, &outside);
        let half_cell = g.cell_mm / 2.0;
        // No ring deeper than the deepest point within reach of the material is kept.
        let deepest = (0..g.cells())
            .filter(|&c| to_material[c] <= radius_mm + half_cell && depth[c].is_finite())
            .map(|c| depth[c])
            .fold(0.0, f64::max);
        // Along every segment (a straight stretch keeps only its ends), at half a cell.
        let near = |x: f64, y: f64| s.cell_at(x, y).is_some_and(|c| to_material[c] <= radius_mm + half_cell);
        let within_reach = |ring: &Ring| {
            (0..ring.len()).any(|k| {
                let (a, b) = (ring[k], ring[(k + 1) % ring.len()]);
                let n = (a.distance_mm(b) / half_cell).ceil().max(1.0) as usize;
                (0..n).any(|i| {
                    let t = i as f64 / n as f64;
                    near(a.x + (b.x - a.x) * t, a.y + (b.y - a.y) * t)
                })
            })
        };
        let mut out = Vec::new();
        for offset in 0..MAX_RINGS_PER_LEVEL {
            let found = if offset == 0 {
                rings(g, &self.room_mm, 0.0)
            } else {
                let inset = offset as f64 * rd_mm + half_cell;
                if inset > deepest + half_cell {
                    break;
                }
                rings(g, &depth, inset)
            };
            if found.is_empty() {
                break;
            }
            out.extend(found.into_iter().filter(within_reach).map(|ring| LevelRing { offset, ring }));
        }
        out
    }
}
