//! Tests of [`super::trace_path`].

use super::*;
use crate::core::analysis::sampling::point_on;
use crate::core::analysis::sampling::{for_each_sample, move_curvatures};
use crate::core::toolpath::{Motion, Move, Plane, Toolpath, Units, P3};
use proptest::prelude::*;

fn mv(motion: Motion, start: P3, end: P3) -> Move {
    Move { motion, start, end, feed_mm_min: Some(1000.0), spindle_rpm: Some(9600.0), tool: None, line: 1 }
}

fn toolpath(moves: Vec<Move>) -> Toolpath {
    Toolpath { moves, events: vec![], source_units: Units::Mm, warnings: vec![] }
}

/// Moves through `points` (feed), starting at the first.
fn polyline(points: &[P3]) -> Vec<Move> {
    points.windows(2).map(|w| mv(Motion::Linear, w[0], w[1])).collect()
}

fn full_circle(r: f64) -> Toolpath {
    let start = P3::new(r, 0.0, -1.0);
    let center = P3::new(0.0, 0.0, -1.0);
    toolpath(vec![mv(Motion::Arc { center, clockwise: false, plane: Plane::Xy, turns: 0 }, start, start)])
}

fn layers() -> Vec<LayerInfo> {
    vec![
        LayerInfo { name: "top".into(), z_top: 0.0, z_bottom: -2.0 },
        LayerInfo { name: "bottom".into(), z_top: -2.0, z_bottom: -4.0 },
    ]
}

fn options(tolerance: f64) -> TraceOptions {
    TraceOptions { tolerance_mm: Some(tolerance), ..TraceOptions::default() }
}

/// Distance from `p` to the segment `a`–`b`.
fn to_segment(p: [f64; 2], a: [f64; 2], b: [f64; 2]) -> f64 {
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    let l2 = dx * dx + dy * dy;
    let t = if l2 > 0.0 { (((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / l2).clamp(0.0, 1.0) } else { 0.0 };
    (p[0] - a[0] - t * dx).hypot(p[1] - a[1] - t * dy)
}

/// Distance from `p` to the nearest segment (or lone point) of the traced path.
fn to_traced(p: [f64; 2], path: &ScenePath) -> f64 {
    path.runs
        .iter()
        .flat_map(|r| {
            let pts = &r.points;
            (0..pts.len())
                .map(move |i| if i == 0 { to_segment(p, pts[0], pts[0]) } else { to_segment(p, pts[i - 1], pts[i]) })
        })
        .fold(f64::INFINITY, f64::min)
}

/// Points densely along the original path.
fn dense(path: &Toolpath) -> Vec<[f64; 2]> {
    const PER_MOVE: usize = 64;
    path.moves
        .iter()
        .flat_map(|m| {
            (0..=PER_MOVE).map(move |k| {
                let p = point_on(m, k as f64 / PER_MOVE as f64).0;
                [p.x, p.y]
            })
        })
        .collect()
}

#[test]
fn a_full_circle_traces_within_the_chord_tolerance() {
    let path = full_circle(10.0);
    let traced = trace_path("c", &path, &TraceValues::new(), &[], &options(0.01));
    assert_eq!(traced.runs.len(), 1);
    let run = &traced.runs[0];
    assert!(run.points.len() > 8, "{} points", run.points.len());
    for p in dense(&path) {
        assert!(to_traced(p, &traced) <= 2.0 * 0.01 + 1e-9);
    }
    for p in &run.points {
        assert!((p[0].hypot(p[1]) - 10.0).abs() < 1e-9, "vertices lie on the circle");
    }
    assert_eq!(run.layer, None);
    assert!(run.values.is_empty());
}

#[test]
fn a_straight_line_of_many_moves_collapses_to_its_ends() {
    let points: Vec<P3> = (0..=1000).map(|i| P3::new(f64::from(i) * 0.1, 5.0, -1.0)).collect();
    let path = toolpath(polyline(&points));
    let traced = trace_path("line", &path, &TraceValues::new(), &[], &TraceOptions::default());
    assert_eq!(traced.runs[0].points, vec![[0.0, 5.0], [100.0, 5.0]]);
}

#[test]
fn a_value_changing_bin_keeps_its_vertex() {
    let points: Vec<P3> = (0..=10).map(|i| P3::new(f64::from(i), 0.0, -1.0)).collect();
    let path = toolpath(polyline(&points));
    let feed: Vec<Option<f64>> = (0..10).map(|i| Some(if i < 5 { 100.0 } else { 200.0 })).collect();
    let values = TraceValues::new().per_move(Quantity::Feed, &feed);
    let traced = trace_path("p", &path, &values, &[], &TraceOptions::default());
    let run = &traced.runs[0];
    assert_eq!(run.points, vec![[0.0, 0.0], [5.0, 0.0], [10.0, 0.0]]);
    assert_eq!(run.values[&Quantity::Feed], vec![Some(100.0), Some(100.0), Some(200.0)]);
}

#[test]
fn per_sample_values_colour_the_stretch_where_the_peak_is() {
    let path = toolpath(polyline(&[P3::new(0.0, 0.0, -1.0), P3::new(10.0, 0.0, -1.0), P3::new(20.0, 0.0, -1.0)]));
    let s: Vec<f64> = (1..=200).map(|i| f64::from(i) * 0.1).collect();
    let mut v: Vec<Option<f64>> = s.iter().map(|_| Some(10.0)).collect();
    v[42] = Some(90.0);
    let values = TraceValues::new().per_sample(Quantity::Alpha, &s, &v);
    let traced = trace_path("p", &path, &values, &[], &options(1e-3));
    let run = &traced.runs[0];
    let alpha = &run.values[&Quantity::Alpha];
    // A straight line keeps a vertex where the value changes bin: the peak colours only
    // the stretch of its sample (4.2 to 4.3 mm), the rest stays at 10.
    let peak: Vec<usize> = (0..alpha.len()).filter(|&i| alpha[i] == Some(90.0)).collect();
    assert_eq!(peak.len(), 1, "{alpha:?}");
    let (a, b) = (run.points[peak[0] - 1][0], run.points[peak[0]][0]);
    assert!((a - 4.2).abs() < 1e-9 && (b - 4.3).abs() < 1e-9, "{:?}", run.points);
    assert!(alpha.iter().all(|v| matches!(v, Some(x) if (x - 10.0).abs() < 1e-9 || (x - 90.0).abs() < 1e-9)));
}

#[test]
fn a_vertex_without_samples_inside_takes_the_interpolated_value() {
    let points: Vec<P3> = (0..=4).map(|i| P3::new(f64::from(i) * 0.01, f64::from(i % 2) * 5.0, -1.0)).collect();
    let path = toolpath(polyline(&points));
    // Samples much sparser than the vertices.
    let s = [0.0, 100.0];
    let v = [Some(0.0), Some(100.0)];
    let values = TraceValues::new().per_sample(Quantity::Force, &s, &v);
    let traced = trace_path("p", &path, &values, &[], &options(1e-3));
    let force = &traced.runs[0].values[&Quantity::Force];
    assert!(force.iter().all(|v| v.is_some_and(|f| f > 0.0 && f < 25.0)), "{force:?}");
}

#[test]
fn rapids_get_no_values_and_their_own_runs() {
    let a = P3::new(0.0, 0.0, 5.0);
    let b = P3::new(0.0, 0.0, -1.0);
    let c = P3::new(10.0, 0.0, -1.0);
    let d = P3::new(10.0, 0.0, 5.0);
    let e = P3::new(20.0, 0.0, 5.0);
    let path = toolpath(vec![
        mv(Motion::Rapid, P3::new(0.0, 0.0, 10.0), a),
        mv(Motion::Linear, a, b),
        mv(Motion::Linear, b, c),
        mv(Motion::Rapid, c, d),
        mv(Motion::Rapid, d, e),
    ]);
    let feed = vec![Some(5000.0), Some(300.0), Some(1000.0), Some(5000.0), Some(5000.0)];
    let values = TraceValues::new().per_move(Quantity::Feed, &feed);
    let traced = trace_path("p", &path, &values, &layers(), &TraceOptions::default());
    let styles: Vec<(bool, Option<usize>)> = traced.runs.iter().map(|r| (r.rapid, r.layer)).collect();
    // The plunge ends in the layer: it belongs to it.
    assert_eq!(styles, vec![(true, None), (false, Some(0)), (true, None)]);
    for run in traced.runs.iter().filter(|r| r.rapid) {
        assert!(run.values[&Quantity::Feed].iter().all(Option::is_none));
    }
    assert_eq!(traced.runs[1].points, vec![[0.0, 0.0], [0.0, 0.0], [10.0, 0.0]]);
    assert_eq!(traced.runs[1].values[&Quantity::Feed], vec![Some(300.0), Some(300.0), Some(1000.0)]);
}

#[test]
fn moves_into_another_layer_start_a_new_run() {
    let path = toolpath(polyline(&[
        P3::new(0.0, 0.0, -1.0),
        P3::new(10.0, 0.0, -1.0),
        P3::new(10.0, 0.0, -3.0),
        P3::new(0.0, 0.0, -3.0),
    ]));
    let traced = trace_path("p", &path, &TraceValues::new(), &layers(), &TraceOptions::default());
    let run_layers: Vec<Option<usize>> = traced.runs.iter().map(|r| r.layer).collect();
    assert_eq!(run_layers, vec![Some(0), Some(1)]);
    assert_eq!(traced.runs[1].points, vec![[10.0, 0.0], [0.0, 0.0]]);
    // A vertex on the boundary between layers belongs to the upper one.
    assert_eq!(layer_of(-2.0, &layers()), Some(0));
}

#[test]
fn path_distance_is_measured_as_the_analysis_measures_it() {
    // A rapid, a helix and a line: a spike at a sample's s lands on the vertex there.
    let start = P3::new(10.0, 0.0, 0.0);
    let helix_end = P3::new(-10.0, 0.0, -2.0);
    let path = toolpath(vec![
        mv(Motion::Rapid, P3::new(10.0, 0.0, 20.0), start),
        mv(
            Motion::Arc { center: P3::new(0.0, 0.0, 0.0), clockwise: false, plane: Plane::Xy, turns: 1 },
            start,
            helix_end,
        ),
        mv(Motion::Linear, helix_end, P3::new(-10.0, 30.0, -2.0)),
    ]);
    let mut samples = Vec::new();
    let mut s = 0.0;
    for_each_sample(&path, &move_curvatures(&path), 0.05, |sample| {
        s += sample.step_mm;
        samples.push((s, sample.p));
        true
    });
    let spike = samples.len() - 200; // 10 mm before the end, on the line
    let s_mm: Vec<f64> = samples.iter().map(|x| x.0).collect();
    let v: Vec<Option<f64>> = (0..samples.len()).map(|i| Some(if i == spike { 100.0 } else { 1.0 })).collect();
    let values = TraceValues::new().per_sample(Quantity::Alpha, &s_mm, &v);
    let traced = trace_path("p", &path, &values, &[], &options(0.001));
    let feed = traced.runs.iter().find(|r| !r.rapid).unwrap();
    let alpha = &feed.values[&Quantity::Alpha];
    let peak = alpha.iter().position(|a| a.is_some_and(|a| a > 50.0)).expect("the spike is kept");
    let at = samples[spike].1;
    let (prev, here) = (feed.points[peak - 1], feed.points[peak]);
    assert!(to_segment([at.x, at.y], prev, here) < 1e-6, "the spike's sample is on the stretch that carries it");
    let end = s_mm[s_mm.len() - 1];
    let total: f64 = path.moves.iter().map(move_length).sum();
    assert!((end - total).abs() < 1e-6, "s ends at the 3-D length, rapids included");
}

#[test]
fn a_million_moves_trace_to_a_few_thousand_vertices() {
    // Its speed is measured by `cargo bench --bench drawing`.
    // Contour-parallel squares, 1 mm segments, about 1 M moves (≈ 1 km of path).
    let mut points = vec![P3::new(0.0, 0.0, -1.0)];
    let mut k = 0;
    while points.len() < 1_000_000 {
        let half = 10.0 + f64::from(k % 400) * 0.5;
        for side in 0..4 {
            for i in 0..(2.0 * half) as usize {
                let t = i as f64 - half;
                let p = match side {
                    0 => (t, -half),
                    1 => (half, t),
                    2 => (-t, half),
                    _ => (-half, -t),
                };
                points.push(P3::new(p.0, p.1, -1.0));
            }
        }
        k += 1;
    }
    let path = toolpath(polyline(&points));
    // Two feeds: slower on the far left and right.
    let feed: Vec<Option<f64>> =
        path.moves.iter().map(|m| Some(if m.end.x.abs() > 100.0 { 500.0 } else { 1000.0 })).collect();
    let values = TraceValues::new().per_move(Quantity::Feed, &feed);
    let traced = trace_path("big", &path, &values, &[], &TraceOptions::default());
    let vertices: usize = traced.runs.iter().map(|r| r.points.len()).sum();
    assert!(vertices < 50_000, "{vertices} vertices");
}

/// A random path: linear moves and XY arcs (some helical), with layer changes.
fn arb_path() -> impl Strategy<Value = Toolpath> {
    let step = (0usize..4, -20.0..20.0f64, -20.0..20.0f64, 0usize..3, 0.2..3.0f64, any::<bool>());
    prop::collection::vec(step, 1..40).prop_map(|steps| {
        let mut at = P3::new(0.0, 0.0, -1.0);
        let mut moves = Vec::new();
        for (kind, x, y, z_level, angle, cw) in steps {
            let z = -1.0 - 1.5 * z_level as f64;
            let (motion, end) = match kind {
                0 => (Motion::Rapid, P3::new(x, y, 5.0)),
                1 => (Motion::Linear, P3::new(x, y, z)),
                _ => {
                    let center = P3::new(at.x + x * 0.2, at.y + y * 0.2, at.z);
                    let (dx, dy) = (at.x - center.x, at.y - center.y);
                    let a = if cw { -angle } else { angle };
                    let end = P3::new(
                        center.x + dx * a.cos() - dy * a.sin(),
                        center.y + dx * a.sin() + dy * a.cos(),
                        if kind == 3 { at.z - 0.5 } else { at.z },
                    );
                    (Motion::Arc { center, clockwise: cw, plane: Plane::Xy, turns: 0 }, end)
                }
            };
            moves.push(mv(motion, at, end));
            at = end;
        }
        toolpath(moves)
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn simplified_paths_stay_within_tolerance_and_keep_their_ends(
        path in arb_path(),
        tolerance in 0.005..0.5f64,
        spike in 0usize..40,
    ) {
        let feed: Vec<Option<f64>> = (0..path.moves.len()).map(|i| Some(if i == spike { 900.0 } else { 100.0 + i as f64 })).collect();
        let values = TraceValues::new().per_move(Quantity::Feed, &feed);
        let traced = trace_path("p", &path, &values, &layers(), &options(tolerance));
        let originals = dense(&path);
        let on_path = |p: [f64; 2]| {
            originals.windows(2).map(|w| to_segment(p, w[0], w[1])).fold(f64::INFINITY, f64::min)
        };
        for run in &traced.runs {
            prop_assert!(run.points.len() >= 2);
            for (q, v) in &run.values {
                prop_assert_eq!(v.len(), run.points.len(), "{:?}", q);
            }
            for &p in &run.points {
                prop_assert!(on_path(p) <= tolerance + 1e-6, "vertex {:?} off the path", p);
            }
        }
        // Each run ends where the next starts (the path is continuous): ends are kept.
        for pair in traced.runs.windows(2) {
            let (end, start) = (pair[0].points[pair[0].points.len() - 1], pair[1].points[0]);
            prop_assert!((end[0] - start[0]).hypot(end[1] - start[1]) < 1e-9);
        }
        for p in originals {
            prop_assert!(to_traced(p, &traced) <= 2.0 * tolerance + 1e-6, "{:?} off the trace", p);
        }
        let first = path.moves[0].start;
        let last = path.moves[path.moves.len() - 1].end;
        let runs = &traced.runs;
        if let (Some(r0), Some(rn)) = (runs.first(), runs.last()) {
            prop_assert!((r0.points[0][0] - first.x).hypot(r0.points[0][1] - first.y) < 1e-9);
            let p = rn.points[rn.points.len() - 1];
            prop_assert!((p[0] - last.x).hypot(p[1] - last.y) < 1e-9);
        }
    }
}

#[test]
fn every_kept_vertex_says_its_height_line_and_path_distance() {
    let mut moves = polyline(&[P3::new(0.0, 0.0, -1.0), P3::new(10.0, 0.0, -1.0), P3::new(10.0, 10.0, -3.0)]);
    moves[1].line = 7;
    let traced = trace_path("p", &toolpath(moves), &TraceValues::new(), &layers(), &options(0.01));
    let ends: Vec<(f32, u32, f64)> = traced
        .runs
        .iter()
        .flat_map(|r| r.z.iter().zip(&r.lines).zip(&r.s_mm).map(|((z, l), s)| (*z, *l, *s)))
        .collect();
    let runs_len: usize = traced.runs.iter().map(|r| r.points.len()).sum();
    assert_eq!(ends.len(), runs_len);
    let last = ends.last().unwrap();
    assert_eq!((last.0, last.1), (-3.0, 7));
    assert!((last.2 - (10.0 + 10.0_f64.hypot(2.0))).abs() < 1e-9, "{ends:?}");
    assert!(ends.iter().any(|e| (e.0, e.1) == (-1.0, 1) && (e.2 - 10.0).abs() < 1e-9), "{ends:?}");
}
