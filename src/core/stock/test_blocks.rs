//! What the stock's tests share: a block of material, and checks of a raster's cells.

use super::tiles::Tiles;
use super::{rect_signed_distance, Raster, Rect, BLOCK_CELLS};

/// The side of [`block`], mm.
pub const SIDE: f64 = 40.0;

/// A square block of material, 40 mm on a side, in cells of 0.1 mm.
pub fn block() -> Raster {
    let rect = Rect { x_min: 0.0, y_min: 0.0, x_max: SIDE, y_max: SIDE };
    let mut r = Raster::new(rect, 0.1);
    r.paint(
        true,
        |y, out| {
            if (0.0..SIDE).contains(&y) {
                out.push((0.0, SIDE))
            }
        },
        |x, y, _| rect_signed_distance(&rect, x, y),
    );
    r
}

/// `true` when cell `k` and a material cell lie in one 2 × 2 quad, which a probe reads.
pub fn shares_a_probe_with_material(r: &Raster, k: usize) -> bool {
    let (i, j) = (k % r.nx, k / r.nx);
    let near = |n: usize, len: usize| n.saturating_sub(1)..(n + 2).min(len);
    near(j, r.ny).any(|jj| near(i, r.nx).any(|ii| r.f[jj * r.nx + ii] > 0))
}

/// Whether the block and the tile counts the raster keeps are those of its cells.
pub fn counts_of_the_cells(raster: &Raster) -> (bool, bool) {
    let mut blocks = vec![0u32; raster.blocks.len()];
    let mut tiles = Tiles::new(raster.nx, raster.ny);
    for j in 0..raster.ny {
        for i in 0..raster.nx {
            if raster.f[j * raster.nx + i] > 0 {
                blocks[(j / BLOCK_CELLS) * raster.bx + i / BLOCK_CELLS] += 1;
                tiles.update(i, j, true);
            }
        }
    }
    (blocks == raster.blocks, tiles == raster.tiles)
}
