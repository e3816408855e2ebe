//! The choice of slice levels: the levels a program cuts at, how they are merged, and that
//! how a path is split does not change them.

use super::*;
use crate::core::analysis::depth_tests::{z_level_roughing, CAVITY_DEPTH_MM, LAYERS, ROUGHING_TOOL_MM};
use crate::core::nc::{parse_gcode, ParseOptions};
use crate::core::toolpath::{Units, P3};
use proptest::prelude::*;

/// A feed move in a straight line from `start` to `end`, mm.
fn line(start: P3, end: P3) -> Move {
    Move { motion: Motion::Linear, start, end, feed_mm_min: Some(100.0), spindle_rpm: None, tool: None, line: 1 }
}

/// A program of `moves`, in mm.
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

/// A ramp down from z = 0 in steps of `step` mm, one 0.5 mm move per step, `steps` long,
/// zig-zagging in x (a straight ramp would be one move).
fn ramp(steps: usize, step: f64) -> Vec<Move> {
    (0..steps)
        .map(|i| {
            let (z0, z1) = (-step * i as f64, -step * (i + 1) as f64);
            let (x0, x1) = if i % 2 == 0 { (0.0, 0.5) } else { (0.5, 0.0) };
            line(P3::new(x0, 0.0, z0), P3::new(x1, 0.0, z1))
        })
        .collect()
}

#[test]
fn slices_follow_the_cutting_levels_of_a_layered_program() {
    let levels = slice_levels(&at_z(&[-10.0, -20.0, -30.0, -20.01]), -32.0, 0.0);
    assert_levels(levels, &[0.0, -10.0, -20.0, -30.0, -32.0]);
}

#[test]
fn the_stepovers_of_a_three_d_program_are_merged_down_to_the_slice_limit() {
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
fn every_layer_of_a_z_level_roughing_is_a_slice_though_none_reaches_the_share_of_a_layer() {
    // 58 layers 0.6 mm apart down a 35 mm cavity, each under 2 % of the feed length.
    let path = z_level_roughing();
    let wanted = Levels::of(&path, -CAVITY_DEPTH_MM, 0.0, ROUGHING_TOOL_MM).wanted();
    assert_eq!(wanted.slices(), LAYERS);
    // By their share of the feed length alone, they would be merged down to the limit.
    assert_eq!(slice_levels(&path, -CAVITY_DEPTH_MM, 0.0).len(), MAX_SLICES + 1);
}

#[test]
fn merged_to_a_budget_the_levels_keep_the_top_the_floor_and_the_bottom_and_merge_ramp_ends_first() {
    // Ramp ends between the layers of the roughing, then 20 slices for all of them.
    let mut moves = z_level_roughing().moves;
    moves.extend(ramp(300, 0.1));
    let levels = Levels::of(&program(moves), -CAVITY_DEPTH_MM, 0.0, ROUGHING_TOOL_MM);
    let wanted = levels.clone().wanted();
    assert_eq!(wanted.slices(), LAYERS, "every ramp end is merged away before a layer");
    let z = levels.merged_to(20).z();
    assert_eq!(z.len(), 21);
    let floor = -CAVITY_DEPTH_MM * (LAYERS - 1) as f64 / LAYERS as f64;
    assert!(z[0] == 0.0 && (z[19] - floor).abs() < 1e-9 && z[20] == -CAVITY_DEPTH_MM, "{z:?}");
    let layer = |l: f64| (l / (CAVITY_DEPTH_MM / LAYERS as f64)).round() * CAVITY_DEPTH_MM / LAYERS as f64;
    assert!(z.iter().all(|&l| (l - layer(l)).abs() < 1e-9), "a ramp end is a level: {z:?}");
}

/// A move of a connected test program: a line, or an arc about (`x`, `y`), to (`x`, `y`,
/// `z`) or at its start's height when `flat`.
#[derive(Debug, Clone, Copy)]
struct Step {
    arc: bool,
    clockwise: bool,
    flat: bool,
    x: f64,
    y: f64,
    z: f64,
    /// The arc's sweep, radians.
    sweep: f64,
}

/// Steps within a 30 mm square, down to 6 mm deep.
fn steps() -> impl Strategy<Value = Vec<Step>> {
    let step = (any::<bool>(), any::<bool>(), any::<bool>(), 0.0f64..30.0, 0.0f64..30.0, -6.0f64..0.0, 0.5f64..3.0);
    proptest::collection::vec(
        step.prop_map(|(arc, clockwise, flat, x, y, z, sweep)| Step { arc, clockwise, flat, x, y, z, sweep }),
        1..40,
    )
}

/// The feed moves of `steps` from (−5, 15, −1), one after the other.
fn connected(steps: &[Step]) -> Vec<Move> {
    let mut at = P3::new(-5.0, 15.0, -1.0);
    let mut moves = Vec::new();
    for s in steps {
        let z = if s.flat { at.z } else { s.z };
        let radius = (at.x - s.x).hypot(at.y - s.y);
        let m = if s.arc && radius > 0.5 {
            let a0 = (at.y - s.y).atan2(at.x - s.x);
            let a1 = if s.clockwise { a0 - s.sweep } else { a0 + s.sweep };
            let end = P3::new(s.x + radius * a1.cos(), s.y + radius * a1.sin(), z);
            let center = P3::new(s.x, s.y, at.z);
            Move { motion: Motion::Arc { center, clockwise: s.clockwise, plane: Plane::Xy, turns: 0 }, ..line(at, end) }
        } else {
            line(at, P3::new(s.x, s.y, z))
        };
        at = m.end;
        moves.push(m);
    }
    moves
}

/// `m` split at the fractions `at` of its way (sorted, apart), into moves along the same
/// line or the same arc.
fn split(m: &Move, at: &[f64]) -> Vec<Move> {
    let point = |t: f64| match m.motion {
        Motion::Arc { center, clockwise, .. } => {
            let (s, e, c) = ((m.start.x, m.start.y, m.start.z), (m.end.x, m.end.y, m.end.z), (center.x, center.y, 0.0));
            let sweep = crate::core::toolpath::arc_sweep(s, e, c, clockwise, 0);
            let radius = (s.0 - c.0).hypot(s.1 - c.1);
            let a = (s.1 - c.1).atan2(s.0 - c.0) + t * sweep;
            P3::new(c.0 + radius * a.cos(), c.1 + radius * a.sin(), m.start.z + t * (m.end.z - m.start.z))
        }
        _ => P3::new(
            m.start.x + t * (m.end.x - m.start.x),
            m.start.y + t * (m.end.y - m.start.y),
            m.start.z + t * (m.end.z - m.start.z),
        ),
    };
    let mut ends: Vec<P3> = at.iter().map(|&t| point(t)).collect();
    ends.push(m.end);
    let mut start = m.start;
    ends.into_iter()
        .map(|end| {
            let motion = match m.motion {
                Motion::Arc { center, clockwise, plane, turns } => {
                    Motion::Arc { center: P3::new(center.x, center.y, start.z), clockwise, plane, turns }
                }
                other => other,
            };
            let piece = Move { motion, start, end, ..*m };
            start = end;
            piece
        })
        .collect()
}

/// `moves` with each split at its fractions of `cuts` (apart by at least 0.02).
fn split_all(moves: &[Move], cuts: &[Vec<f64>]) -> Vec<Move> {
    moves
        .iter()
        .zip(cuts.iter().chain(std::iter::repeat(&Vec::new())))
        .flat_map(|(m, at)| {
            let mut at = at.clone();
            at.sort_by(f64::total_cmp);
            at.dedup_by(|b, a| *b - *a < 0.02);
            split(m, &at)
        })
        .collect()
}

/// A program of `steps` and, for each move, up to three fractions to split it at.
fn program_and_cuts() -> impl Strategy<Value = (Vec<Step>, Vec<Vec<f64>>)> {
    steps().prop_flat_map(|steps| {
        let n = steps.len();
        (Just(steps), proptest::collection::vec(proptest::collection::vec(0.05f64..0.95, 0..3), n))
    })
}

/// `true` when two lists of levels are the same up to rounding.
fn same_levels(a: &[f64], b: &[f64]) -> bool {
    a.len() == b.len() && a.iter().zip(b).all(|(x, y)| (x - y).abs() < 1e-9)
}

#[test]
fn a_full_circle_split_in_two_halves_is_one_level_like_the_circle() {
    // A helix turn down 1 mm about (10, 10), whole or in two halves.
    let (start, center) = (P3::new(15.0, 10.0, -2.0), P3::new(10.0, 10.0, -2.0));
    let turn = Move {
        motion: Motion::Arc { center, clockwise: false, plane: Plane::Xy, turns: 0 },
        ..line(start, P3::new(15.0, 10.0, -3.0))
    };
    let halves = split(&turn, &[0.5]);
    assert_eq!(halves.len(), 2);
    assert!((halves[0].end.x - 5.0).abs() < 1e-9 && (halves[0].end.z + 2.5).abs() < 1e-12);
    let whole = slice_levels(&program(vec![turn]), -10.0, 0.0);
    assert_levels(slice_levels(&program(halves), -10.0, 0.0), &whole);
    assert_eq!(whole.len(), 4, "{whole:?}");
}

proptest! {
    #[test]
    fn splitting_moves_along_their_lines_and_arcs_leaves_the_levels_as_they_were(
        (steps, cuts) in program_and_cuts(),
    ) {
        let moves = connected(&steps);
        let (whole, pieces) = (program(moves.clone()), program(split_all(&moves, &cuts)));
        for diameter in [f64::INFINITY, 2.0] {
            let a = Levels::of(&whole, -8.0, 0.0, diameter).wanted().z();
            let b = Levels::of(&pieces, -8.0, 0.0, diameter).wanted().z();
            prop_assert!(same_levels(&a, &b), "whole {a:?}, split {b:?}");
        }
    }
}

#[test]
fn the_split_proptest_program_reaches_both_arcs_and_layers() {
    // The helpers make what the property needs: arcs, and flat moves at one level.
    let s = |arc: bool, flat: bool, x: f64, y: f64| Step { arc, clockwise: false, flat, x, y, z: -3.0, sweep: 1.0 };
    let moves = connected(&[s(false, false, 0.0, 15.0), s(true, true, 10.0, 15.0), s(false, true, 20.0, 20.0)]);
    assert!(matches!(moves[1].motion, Motion::Arc { .. }));
    assert!(moves[1..].iter().all(|m| m.start.z == -3.0 && m.end.z == -3.0));
    let pieces = split_all(&moves, &[vec![], vec![0.3, 0.6], vec![0.5]]);
    assert_eq!(pieces.len(), 6);
    assert!(pieces.windows(2).all(|w| w[0].end == w[1].start));
}

/// Engagements of a path and of the same path split apart within this, deg: the samples
/// lie elsewhere along the moves (each move is sampled from its own start).
const SPLIT_ALPHA_TOLERANCE_DEG: f64 = 1.0;
/// Removed volumes of a path and of the same path split apart within this share.
const SPLIT_VOLUME_TOLERANCE: f64 = 0.005;

proptest! {
    #![proptest_config(ProptestConfig::with_cases(12))]

    #[test]
    fn an_analysis_of_moves_split_along_their_lines_and_arcs_finds_the_same_engagement_and_volume(
        (steps, cuts) in program_and_cuts(),
    ) {
        use crate::core::analysis::{analyze, AnalysisSpec, StockRegion};
        use crate::core::stock::Rect;
        use crate::core::tool::{EndMill, ToolType};
        let block = Rect { x_min: 0.0, y_min: 0.0, x_max: 30.0, y_max: 30.0 };
        let tool = EndMill { tool_type: ToolType::Square, diameter_mm: 4.0, flutes: 4, corner_radius_mm: 0.0 };
        let spec = AnalysisSpec {
            default_spindle_rpm: Some(9600.0),
            ..AnalysisSpec::new(tool, vec![StockRegion::Rect(block)], 0.0, -8.0)
        };
        let moves = connected(&steps);
        let progress = &crate::core::progress::NoProgress;
        let whole = analyze(&program(moves.clone()), &spec, progress).expect("analyses").summary;
        let split = analyze(&program(split_all(&moves, &cuts)), &spec, progress).expect("analyses").summary;
        let (a, b) = (whole.alpha_deg.max, split.alpha_deg.max);
        prop_assert!((a - b).abs() <= SPLIT_ALPHA_TOLERANCE_DEG, "α max {a} whole, {b} split");
        let (v, w) = (whole.removed_volume_mm3, split.removed_volume_mm3);
        prop_assert!((v - w).abs() <= SPLIT_VOLUME_TOLERANCE * v.max(1.0), "removed {v} mm³ whole, {w} split");
    }
}
