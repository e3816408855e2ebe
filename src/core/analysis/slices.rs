//! The stock of a layer as a stack of z slices, each a raster (MODEL.md §6): slice
//! boundaries follow the z levels the program cuts at, so a 2.5-D program is simulated
//! exactly and a 3-D one in steps. Where levels must be merged, the layers a program cuts
//! flat (its roughing layers) are kept: a slice that a layer's passes cut only a sliver of
//! would lose, for every later pass, the material the layer left below it.
//!
//! Every slice starts as the same raster, and a tool removes material from the slices
//! above its tip, a run of slices from the top: so a slice's material always lies inside
//! the material of the slice below it. Above a slice with no material near the tool,
//! none has any. Slices still alike share one stock (see [`super::stack`]).

use crate::core::stock::{ArcRows, BlockRange, CapsuleRows, Raster};
use crate::core::toolpath::move_length;
use crate::core::toolpath::{Motion, Move, Plane, Toolpath};

/// z levels closer than this are one level, mm.
pub const MIN_SLICE_MM: f64 = 0.05;
/// Levels this much closer than [`MIN_SLICE_MM`] are still apart: layers a program steps
/// down by exactly the smallest slice differ by it only up to rounding, mm.
const LEVEL_ROUNDING_MM: f64 = 1e-9;
/// Most slices one analysis keeps (levels are merged away beyond it, see [`slice_levels`]).
pub const MAX_SLICES: usize = 16;
/// A level the program cuts flat for at least this share of its feed length is a layer
/// level (a roughing or finishing layer): it is merged away only when no other level can
/// be. The flat stepovers of a 3-D finishing pass (a fraction of a millimetre each) stay
/// far below it; each layer of a program that roughs in a few dozen layers reaches it.
pub const LAYER_LEVEL_SHARE: f64 = 0.02;
/// A tool tip this close to a slice top does not cut the slice, mm.
pub const Z_CONTACT_EPS_MM: f64 = 1e-6;

/// The stock of one z slice (see [`super::stack`] for slices that share one).
#[derive(Clone)]
pub struct SliceStock {
    pub raster: Raster,
    /// Blocks last found to hold no material: material is only ever removed during a
    /// simulation, so they stay empty.
    empty: Option<BlockRange>,
    /// The block (column, row) last found to hold material: it is looked at first, since
    /// it most often still does.
    material_at: Option<(usize, usize)>,
    /// The last capsule applied to the raster (see [`SliceStock::take_capsule`]).
    last_capsule: Option<TakenCapsule>,
}

/// A capsule applied to a slice's raster: which one, and the raster's versions before
/// and after it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct TakenCapsule {
    /// Numbers the capsules of one simulation: slices given the same capsule share it.
    pub serial: u64,
    pub version_before: u64,
    pub version_after: u64,
}

impl SliceStock {
    pub fn new(raster: Raster) -> SliceStock {
        SliceStock { raster, empty: None, material_at: None, last_capsule: None }
    }

    /// Applies capsule number `serial` to the raster ([`Raster::clear_capsule_rows`]),
    /// remembering it when it was applied. Returns `false` when no material lies near it.
    /// (A stock two slices share takes it once for both.)
    pub fn take_capsule(&mut self, serial: u64, capsule: &mut CapsuleRows) -> bool {
        self.take(serial, |raster| raster.clear_capsule_rows(capsule))
    }

    /// Applies arc number `serial` (numbered with the capsules) to the raster
    /// ([`Raster::clear_arc_rows`]), as [`SliceStock::take_capsule`] does a capsule.
    pub fn take_arc(&mut self, serial: u64, arc: &mut ArcRows) -> bool {
        self.take(serial, |raster| raster.clear_arc_rows(arc))
    }

    /// Applies update number `serial` with `apply`, remembering it when it was applied.
    fn take(&mut self, serial: u64, apply: impl FnOnce(&mut Raster) -> bool) -> bool {
        let version_before = self.raster.version();
        let applied = apply(&mut self.raster);
        self.last_capsule =
            applied.then(|| TakenCapsule { serial, version_before, version_after: self.raster.version() });
        applied
    }

    /// The last capsule applied to the raster, if the raster has not changed otherwise
    /// since (every change to a slice's raster during a simulation is a capsule).
    pub fn last_capsule(&self) -> Option<TakenCapsule> {
        self.last_capsule.filter(|t| t.version_after == self.raster.version())
    }

    /// As [`Raster::any_material_near`], remembering the answers: while the tool stays
    /// over the same empty blocks, no block is read again, and while a block found to hold
    /// material lies under the tool and still does, no other is read.
    pub fn any_material_near(&mut self, x: f64, y: f64, reach_mm: f64) -> bool {
        let Some(blocks) = self.raster.blocks_near(x, y, reach_mm) else {
            return false;
        };
        if self.material_at.is_some_and(|at| blocks.holds(at) && self.raster.block_holds_material(at)) {
            return true;
        }
        if self.empty.is_some_and(|e| e.contains(&blocks)) {
            return false;
        }
        match self.raster.first_material_block_in(blocks) {
            Some(at) => {
                self.material_at = Some(at);
                true
            }
            None => {
                self.empty = Some(blocks);
                false
            }
        }
    }
}

/// The slice boundaries for `path` in a layer from `z_bottom` to `z_top`, top first.
///
/// Candidates are the z values of the feed moves' ends. Each weighs the XY length the
/// path cuts flat at it. Candidates closer than [`MIN_SLICE_MM`] are one level, at the
/// heaviest of them (the highest on a tie), weighing all of them: a layer a program
/// roughs at stays exact beside the end of a ramp just above it. Beyond [`MAX_SLICES`]
/// slices, inner levels are merged away one by one, always the one whose neighbours are
/// closest, taken first among the levels that are not layer levels (see
/// [`LAYER_LEVEL_SHARE`]). The top, the bottom and the deepest level the program cuts (its
/// floor, at the deepest height among those merged into it) are kept exact.
pub fn slice_levels(path: &Toolpath, z_bottom: f64, z_top: f64) -> Vec<f64> {
    let feeds = || path.moves.iter().filter(|m| !matches!(m.motion, Motion::Rapid));
    let mut candidates: Vec<(f64, f64)> = feeds()
        .flat_map(|m| {
            // A flat move's length counts once, at its level.
            let flat_mm = if cuts_flat(m) { move_length(m) } else { 0.0 };
            [(m.start.z, flat_mm), (m.end.z, 0.0)]
        })
        .filter(|&(z, _)| z < z_top - MIN_SLICE_MM && z > z_bottom + MIN_SLICE_MM)
        .collect();
    candidates.sort_by(|a, b| b.0.total_cmp(&a.0));
    // Candidates at one height are one, their lengths summed, at the z of the longest
    // flat move among them (a layer stays exact beside a ramp's end a rounding above it).
    let mut heights: Vec<(f64, f64, f64)> = Vec::with_capacity(candidates.len());
    for (z, flat_mm) in candidates {
        match heights.last_mut() {
            Some(last) if last.0 - z <= Z_CONTACT_EPS_MM => {
                if flat_mm > last.2 {
                    (last.0, last.2) = (z, flat_mm);
                }
                last.1 += flat_mm;
            }
            _ => heights.push((z, flat_mm, flat_mm)),
        }
    }
    // Levels as (z, the flat length at z, the flat length of the heights merged into it);
    // top first, bottom last, and neither is ever merged away.
    let deepest = heights.last().map(|h| h.0);
    let mut levels: Vec<(f64, f64, f64)> = Vec::with_capacity(heights.len() + 2);
    levels.push((z_top, f64::INFINITY, f64::INFINITY));
    for (z, flat_mm, _) in heights {
        match levels.last_mut() {
            Some(last) if last.0 - z < MIN_SLICE_MM - LEVEL_ROUNDING_MM => {
                if flat_mm > last.1 {
                    (last.0, last.1) = (z, flat_mm);
                }
                last.2 += flat_mm;
            }
            _ => levels.push((z, flat_mm, flat_mm)),
        }
    }
    // The deepest level the program cuts is its floor: the stock below it is never cut, and
    // a slice reaching past it would be cut through. It lies at the deepest height of its
    // level (not the heaviest), and is kept, as the top and bottom are.
    let floor = usize::from(levels.len() > 1);
    if let (Some(z), true, Some(last)) = (deepest, floor == 1, levels.last_mut()) {
        last.0 = z;
    }
    levels.push((z_bottom, f64::INFINITY, f64::INFINITY));
    let layer_mm = LAYER_LEVEL_SHARE * feeds().map(move_length).sum::<f64>();
    while levels.len() > MAX_SLICES + 1 {
        // The thinnest slice two neighbours would make, among the lighter levels if any.
        let inner = 1..levels.len() - 1 - floor;
        let light = inner.clone().any(|i| levels[i].2 < layer_mm);
        let gap = |i: usize| levels[i - 1].0 - levels[i + 1].0;
        let drop =
            inner.filter(|&i| !light || levels[i].2 < layer_mm).min_by(|&a, &b| gap(a).total_cmp(&gap(b))).unwrap_or(1);
        levels.remove(drop);
    }
    levels.into_iter().map(|(z, _, _)| z).collect()
}

/// `true` when the move cuts at one z level: a line or an arc in the XY plane whose ends
/// lie at the same height.
fn cuts_flat(m: &Move) -> bool {
    let in_xy = match m.motion {
        Motion::Linear => true,
        Motion::Arc { plane, .. } => plane == Plane::Xy,
        Motion::Rapid => false,
    };
    in_xy && (m.end.z - m.start.z).abs() <= Z_CONTACT_EPS_MM
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::core::nc::{parse_gcode, ParseOptions};
    use crate::core::stock::Rect;
    use crate::core::toolpath::{Units, P3};
    use proptest::prelude::*;

    /// A feed move in a straight line from `start` to `end`, mm.
    fn line(start: P3, end: P3) -> Move {
        Move { motion: Motion::Linear, start, end, feed_mm_min: Some(100.0), spindle_rpm: None, tool: None, line: 1 }
    }

    fn program(moves: Vec<Move>) -> Toolpath {
        Toolpath { moves, events: vec![], source_units: Units::Mm, warnings: vec![] }
    }

    /// Levels are the z values of the program, copied: equal to a rounding error at most.
    fn assert_levels(got: Vec<f64>, want: &[f64]) {
        let close = got.len() == want.len() && got.iter().zip(want).all(|(g, w)| (g - w).abs() < 1e-12);
        assert!(close, "levels {got:?}, expected {want:?}");
    }

    /// A 1 mm flat cut at each of `z`.
    fn at_z(z: &[f64]) -> Toolpath {
        program(z.iter().map(|&z| line(P3::new(0.0, 0.0, z), P3::new(1.0, 0.0, z))).collect())
    }

    /// A ramp down from z = 0 in steps of `step` mm, one 0.5 mm move per step, `steps` long.
    fn ramp(steps: usize, step: f64) -> Vec<Move> {
        (0..steps)
            .map(|i| {
                let (z0, z1) = (-step * i as f64, -step * (i + 1) as f64);
                line(P3::new(0.5 * i as f64, 0.0, z0), P3::new(0.5 * (i + 1) as f64, 0.0, z1))
            })
            .collect()
    }

    #[test]
    fn slices_follow_the_cutting_levels_of_a_layered_program() {
        let levels = slice_levels(&at_z(&[-10.0, -20.0, -30.0, -20.01]), -32.0, 0.0);
        assert_levels(levels, &[0.0, -10.0, -20.0, -30.0, -32.0]);
    }

    #[test]
    fn a_three_d_program_is_capped_at_the_slice_limit() {
        let z: Vec<f64> = (0..200).map(|i| -0.1 * i as f64).collect();
        let levels = slice_levels(&at_z(&z), -25.0, 0.0);
        assert_eq!(levels.len(), MAX_SLICES + 1);
        assert!((levels[0] - 0.0).abs() < 1e-12 && (levels[MAX_SLICES] + 25.0).abs() < 1e-12);
    }

    #[test]
    fn a_layer_the_program_roughs_at_stays_exact_beside_the_end_of_a_ramp_just_above_it() {
        // A ramp that ends 0.02 mm above the layer, then 100 mm of roughing at −10.
        let mut moves = vec![line(P3::new(0.0, 0.0, 0.0), P3::new(5.0, 0.0, -9.98))];
        moves.extend((0..10).map(|i| {
            let y = f64::from(i);
            line(P3::new(0.0, y, -10.0), P3::new(10.0, y, -10.0))
        }));
        assert_levels(slice_levels(&program(moves), -12.0, 0.0), &[0.0, -10.0, -12.0]);
    }

    #[test]
    fn a_layer_stays_exact_beside_a_ramp_end_a_rounding_above_it_and_layers_a_smallest_slice_apart_stay() {
        // A ramp ending 2e-7 mm above the layer at −5 (one height with it), and layers at
        // −2.9, −2.95 and −3.0 reached by subtracting 0.05 (a rounding under 0.05 apart).
        let mut moves = vec![line(P3::new(0.0, 0.0, 0.0), P3::new(5.0, 0.0, -5.0 + 2e-7))];
        moves.push(line(P3::new(0.0, 1.0, -5.0), P3::new(100.0, 1.0, -5.0)));
        let mut z = -2.9;
        for _ in 0..3 {
            moves.push(line(P3::new(0.0, 2.0, z), P3::new(100.0, 2.0, z)));
            z -= MIN_SLICE_MM;
        }
        let levels = slice_levels(&program(moves), -8.0, 0.0);
        assert_levels(levels, &[0.0, -2.9, -2.9 - MIN_SLICE_MM, -2.9 - 2.0 * MIN_SLICE_MM, -5.0, -8.0]);
    }

    #[test]
    fn of_two_close_layers_the_one_cut_longer_is_the_level_however_many_moves_cut_it() {
        // 50 mm at −5 in one move, 100 mm at −5.03 in ten.
        let mut moves = vec![line(P3::new(0.0, 0.0, -5.0), P3::new(50.0, 0.0, -5.0))];
        moves.extend((0..10).map(|i| {
            let x = 10.0 * f64::from(i);
            line(P3::new(x, 1.0, -5.03), P3::new(x + 10.0, 1.0, -5.03))
        }));
        assert_levels(slice_levels(&program(moves), -10.0, 0.0), &[0.0, -5.03, -10.0]);
    }

    #[test]
    fn beyond_the_slice_limit_ramp_levels_are_merged_before_layer_levels() {
        // 200 ramp levels 0.1 mm apart, and three layers roughed 50 mm each between them.
        let mut moves = ramp(200, 0.1);
        for z in [-5.03, -10.03, -15.07] {
            moves.push(line(P3::new(0.0, 0.0, z), P3::new(50.0, 0.0, z)));
        }
        let levels = slice_levels(&program(moves), -25.0, 0.0);
        assert_eq!(levels.len(), MAX_SLICES + 1);
        for z in [-5.03, -10.03, -15.07] {
            assert!(levels.iter().any(|&l| (l - z).abs() < 1e-12), "layer {z} merged away: {levels:?}");
        }
        assert!((levels[0] - 0.0).abs() < 1e-12 && (levels[MAX_SLICES] + 25.0).abs() < 1e-12);
    }

    #[test]
    fn the_layers_tiger_nc_roughs_at_are_slice_levels() {
        // tiger.nc roughs at −10, −20, −30 and −31.5 and finishes a relief in 3-D between.
        let file = format!("{}/../shared/data/tiger.nc", env!("CARGO_MANIFEST_DIR"));
        let text = std::fs::read_to_string(&file).unwrap_or_else(|e| panic!("{file}: {e}"));
        let path = parse_gcode(&text, &ParseOptions::default()).expect("tiger.nc parses");
        let levels = slice_levels(&path, -32.0, 0.0);
        assert_eq!(levels.len(), MAX_SLICES + 1);
        for z in [-10.0, -20.0, -30.0, -31.5] {
            assert!(levels.iter().any(|&l| (l - z).abs() < 1e-9), "{z} is not a level: {levels:?}");
        }
    }

    #[test]
    fn the_floor_of_a_program_cut_in_more_levels_than_slices_stays_a_level() {
        // 450 passes 0.01 mm apart down to −4.5 in a 5 mm layer: beyond the slice limit the
        // levels are merged, but a slice from above −4.5 down to −5 would be cut through.
        let z: Vec<f64> = (1..=450).map(|i| -0.01 * f64::from(i)).collect();
        let levels = slice_levels(&at_z(&z), -5.0, 0.0);
        assert_eq!(levels.len(), MAX_SLICES + 1);
        assert!((levels[MAX_SLICES - 1] + 4.5).abs() < 1e-9, "{levels:?}");
        assert!((levels[MAX_SLICES] + 5.0).abs() < 1e-12);
    }

    #[test]
    fn a_layer_thinner_than_the_smallest_slice_is_one_slice() {
        assert_levels(slice_levels(&at_z(&[-0.01]), -0.02, 0.0), &[0.0, -0.02]);
    }

    proptest! {
        #[test]
        fn levels_run_from_top_to_bottom_apart_within_the_limit_and_keep_every_layer(
            // Up to 15 layers, each at least 0.05 mm from the next, cut 100 mm flat …
            steps in proptest::collection::vec(0.05f64..3.0, 0..15),
            // … among ramps anywhere in the layer, each at most 1 mm deep.
            ramps in proptest::collection::vec((0.0f64..1.0, 0.0f64..1.0), 0..120),
        ) {
            let (z_top, z_bottom) = (0.0, -50.0);
            let mut layers = Vec::new();
            let mut z = z_top - MIN_SLICE_MM;
            for step in steps {
                z -= step;
                layers.push(z);
            }
            prop_assume!(layers.last().is_none_or(|&l| l > z_bottom + MIN_SLICE_MM));
            let mut moves: Vec<Move> =
                layers.iter().map(|&z| line(P3::new(0.0, 0.0, z), P3::new(100.0, 0.0, z))).collect();
            let depth = |f: f64| z_top + f * (z_bottom - z_top);
            moves.extend(ramps.iter().map(|&(at, deep)| {
                line(P3::new(0.0, 0.0, depth(at)), P3::new(0.5, 0.0, depth(at) - deep))
            }));
            let levels = slice_levels(&program(moves.clone()), z_bottom, z_top);
            prop_assert!(levels.len() >= 2 && levels.len() <= MAX_SLICES + 1, "{} levels", levels.len());
            prop_assert!((levels[0] - z_top).abs() < 1e-12 && (levels[levels.len() - 1] - z_bottom).abs() < 1e-12);
            // The floor: the deepest height cut.
            let deepest = moves
                .iter()
                .flat_map(|m| [m.start.z, m.end.z])
                .filter(|&z| z > z_bottom + MIN_SLICE_MM && z < z_top - MIN_SLICE_MM)
                .fold(f64::INFINITY, f64::min);
            if deepest.is_finite() {
                let floor = levels[levels.len() - 2];
                prop_assert!((floor - deepest).abs() <= Z_CONTACT_EPS_MM, "floor {deepest} lost: {levels:?}");
            }
            for pair in levels.windows(2) {
                prop_assert!(pair[0] - pair[1] >= MIN_SLICE_MM - LEVEL_ROUNDING_MM, "{pair:?} closer than the smallest slice");
            }
            for z in layers {
                prop_assert!(levels.iter().any(|&l| (l - z).abs() < 1e-12), "layer {z} merged away: {levels:?}");
            }
        }
    }

    #[test]
    fn material_near_is_looked_up_again_once_the_block_that_held_it_is_cleared() {
        let rect = Rect { x_min: 0.0, y_min: 0.0, x_max: 20.0, y_max: 20.0 };
        let mut raster = Raster::new(rect, 0.1);
        crate::core::analysis::region::paint(
            &mut raster,
            &[crate::core::analysis::region::StockRegion::Rect(rect)],
            &[],
            &crate::core::progress::NoProgress,
        )
        .expect("nothing cancels the painting");
        let mut slice = SliceStock::new(raster);
        assert!(slice.any_material_near(10.0, 10.0, 2.0));
        let first = slice.material_at.expect("the block with material is remembered");
        // The block found first goes; others near the tool still hold material.
        slice.raster.clear_capsule((8.0, 8.0), (8.0, 8.0), 2.5);
        assert!(!slice.raster.block_holds_material(first), "the remembered block still holds material");
        assert!(slice.any_material_near(10.0, 10.0, 2.0));
        assert_ne!(slice.material_at, Some(first));
        // All of it goes.
        slice.raster.clear_capsule((10.0, 10.0), (10.0, 10.0), 6.0);
        assert!(!slice.any_material_near(10.0, 10.0, 2.0));
    }
}
