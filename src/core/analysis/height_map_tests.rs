use super::*;
use crate::core::analysis::analyze_from;
use crate::core::analysis::kept::KeptSlice;
use crate::core::analysis::kept_tests::{passes, spec};
use crate::core::progress::NoProgress;
use proptest::prelude::*;

/// The top at (x, y) mm of a height map.
fn top_at(map: &HeightMap, x: f64, y: f64) -> f32 {
    let g = map.grid;
    let (i, j) = (((x - g.x0_mm) / g.cell_mm) as usize, ((y - g.y0_mm) / g.cell_mm) as usize);
    map.tops_mm[j * g.nx + i]
}

/// The stock a 10 mm slot along y = 20 through the 100 × 40 block from z 0 to −10 left,
/// cut at `levels`.
fn slotted(levels: &[f64]) -> KeptStock {
    let (_, stack) = analyze_from(&passes(20.0, levels), &spec(-10.0), None, &NoProgress, |_| {}).expect("analyses");
    stack.keep(false)
}

#[test]
fn a_slot_cut_to_a_known_depth_has_that_depth_inside_and_the_top_outside() {
    let kept = slotted(&[-5.0]);
    let map = height_map(&kept, MAX_HEIGHT_MAP_CELLS);
    assert_eq!(map.block, 1, "{} × {} kept cells fit", kept.grid.nx, kept.grid.ny);
    assert!((top_at(&map, 50.0, 20.0) - -5.0).abs() < 1e-6, "{}", top_at(&map, 50.0, 20.0));
    assert!((top_at(&map, 50.0, 16.0) - -5.0).abs() < 1e-6);
    for y in [2.0, 10.0, 14.0, 26.0, 38.0] {
        assert!(top_at(&map, 50.0, y).abs() < 1e-6, "y {y}: {}", top_at(&map, 50.0, y));
    }
    assert!(map.z_top_mm.abs() < 1e-9 && (map.z_bottom_mm + 10.0).abs() < 1e-9);
    // 30 of the block's 40 mm hold material from the top: 3000 mm² (the grid reaches a
    // little past the block, with no material there).
    let cell_mm2 = map.grid.cell_mm * map.grid.cell_mm;
    let full_mm2 = map.tops_mm.iter().filter(|t| t.abs() < 1e-6).count() as f64 * cell_mm2;
    assert!((full_mm2 - 3000.0).abs() < 30.0, "{full_mm2} mm²");
    let slot_mm2 = map.tops_mm.iter().filter(|t| (*t + 5.0).abs() < 1e-6).count() as f64 * cell_mm2;
    assert!((slot_mm2 - 1000.0).abs() < 30.0, "{slot_mm2} mm²");
}

#[test]
fn a_slot_cut_through_the_layer_is_at_its_bottom_and_holds_no_material() {
    let kept = slotted(&[-5.0, -10.0]);
    let map = height_map(&kept, MAX_HEIGHT_MAP_CELLS);
    assert!((top_at(&map, 50.0, 20.0) - -10.0).abs() < 1e-6);
    assert!(top_at(&map, 50.0, 5.0).abs() < 1e-6);
    let material_mm2 = map.material_cells() as f64 * map.grid.cell_mm * map.grid.cell_mm;
    assert!((material_mm2 - 3000.0).abs() < 30.0, "{material_mm2} mm² hold material");
}

#[test]
fn a_height_map_of_fewer_cells_keeps_the_highest_top_of_each_block() {
    let kept = slotted(&[-5.0]);
    let map = height_map(&kept, DEFAULT_HEIGHT_MAP_CELLS);
    assert!(map.tops_mm.len() <= DEFAULT_HEIGHT_MAP_CELLS);
    assert!(map.block > 1, "{} × {} kept cells", kept.grid.nx, kept.grid.ny);
    assert!((map.grid.cell_mm - map.block as f64 * kept.grid.cell_mm).abs() < 1e-12);
    assert!((top_at(&map, 50.0, 20.0) - -5.0).abs() < 1e-6);
    // So few cells that a block spans the slot's edge: its top is the top outside it.
    let coarse = height_map(&kept, 64);
    assert!(coarse.tops_mm.len() <= 64 && coarse.block > 1);
    assert!(coarse.tops_mm.iter().all(|t| t.abs() < 1e-6 || (t + 5.0).abs() < 1e-6));
}

#[test]
fn the_number_of_cells_asked_for_is_held_within_its_bounds() {
    let kept = slotted(&[-5.0]);
    assert!(height_map(&kept, 0).tops_mm.len() <= MIN_HEIGHT_MAP_CELLS);
    assert!(height_map(&kept, usize::MAX).tops_mm.len() <= MAX_HEIGHT_MAP_CELLS);
}

/// Any kept stock of up to three slices, each with its own raster.
fn any_kept() -> impl Strategy<Value = KeptStock> {
    (2usize..40, 2usize..40, 1usize..4).prop_flat_map(|(nx, ny, n)| {
        proptest::collection::vec(proptest::collection::vec(-126i8..=126, nx * ny), n).prop_map(move |rasters| {
            let grid = Grid { x0_mm: -3.0, y0_mm: 1.5, cell_mm: 0.25, nx, ny };
            let slices = (0..rasters.len())
                .map(|k| KeptSlice { z_top: -2.0 * k as f64, z_bottom: -2.0 * (k + 1) as f64, raster: k })
                .collect();
            KeptStock { grid, slices, rasters, cavity: false, below: None }
        })
    })
}

proptest! {
    #[test]
    fn every_cell_of_a_height_map_is_the_highest_top_of_the_kept_cells_it_covers(
        kept in any_kept(), max_cells in 1usize..2000,
    ) {
        let map = height_map(&kept, max_cells);
        prop_assert!(map.tops_mm.len() <= max_cells.max(MIN_HEIGHT_MAP_CELLS));
        prop_assert!(map.block == 1 || {
            let g = kept.grid;
            let b = map.block - 1;
            g.nx.div_ceil(b) * g.ny.div_ceil(b) > max_cells.max(MIN_HEIGHT_MAP_CELLS)
        }, "the block is the smallest that fits");
        let tops = cell_tops_mm(&kept);
        let g = kept.grid;
        let mut highest = vec![f32::NEG_INFINITY; map.tops_mm.len()];
        for j in 0..g.ny {
            for i in 0..g.nx {
                let k = (j / map.block) * map.grid.nx + i / map.block;
                highest[k] = highest[k].max(tops[j * g.nx + i]);
                // A cell's top is the top of the first slice holding material there.
                let first = kept.slices.iter().find(|s| kept.rasters[s.raster][j * g.nx + i] > 0);
                let expected = first.map_or(kept.z_bottom(), |s| s.z_top) as f32;
                prop_assert!((tops[j * g.nx + i] - expected).abs() < 1e-6);
            }
        }
        prop_assert!(highest.iter().zip(&map.tops_mm).all(|(a, b)| (a - b).abs() < 1e-6));
    }
}
