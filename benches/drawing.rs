//! `cargo bench --bench drawing`: traces a synthetic ~1-million-sample path (about 53 m
//! of contour-parallel loops with corner arcs, α per 0.05 mm sample) into a scene path,
//! renders its plan view and a line chart of α, and prints the times and sizes. A second
//! case cuts the same path into ~1 million 0.05 mm linear moves with a value per move (CAM
//! output of tiny segments). With `DRAWING_BENCH_SVG=DIR` the drawings are written there.

use dieplan::core::analysis::sampling::point_on;
use dieplan::core::drawing::chart::render_chart;
use dieplan::core::drawing::downsample::min_max_per_bucket;
use dieplan::core::drawing::plan_view::{render_drawing, DrawOptions};
use dieplan::core::drawing::scene::{ChartBody, ChartData, LineChart, LineSeries, Quantity, Scene};
use dieplan::core::drawing::synthetic::{alpha_at, alpha_samples, long_loops};
use dieplan::core::drawing::trace::{trace_path, TraceOptions, TraceValues};
use dieplan::core::toolpath::move_length;
use dieplan::core::toolpath::{Motion, Move, Toolpath};
use std::time::Instant;

/// Sample spacing of the per-sample values, mm.
const SPACING_MM: f64 = 0.05;
/// Repetitions of each measured step (the best is reported).
const RUNS: usize = 5;

/// The same path as ~0.05 mm linear moves (arcs included), and α per move.
fn dense(path: &Toolpath) -> (Toolpath, Vec<Option<f64>>) {
    let mut moves = Vec::new();
    let mut alpha = Vec::new();
    let mut s = 0.0;
    for m in &path.moves {
        let length = move_length(m);
        let steps = ((length / SPACING_MM).ceil() as usize).max(1);
        let mut from = m.start;
        for k in 1..=steps {
            let to = point_on(m, k as f64 / steps as f64).0;
            let motion = if matches!(m.motion, Motion::Rapid) { Motion::Rapid } else { Motion::Linear };
            moves.push(Move { motion, start: from, end: to, ..*m });
            s += length / steps as f64;
            alpha.push(Some(alpha_at(s)));
            from = to;
        }
    }
    (Toolpath { moves, ..path.clone() }, alpha)
}

fn save(name: &str, svg: &str) {
    if let Ok(dir) = std::env::var("DRAWING_BENCH_SVG") {
        let file = std::path::Path::new(&dir).join(name);
        std::fs::write(&file, svg).unwrap_or_else(|e| panic!("{}: {e}", file.display()));
    }
}

fn best<T>(mut f: impl FnMut() -> T) -> (T, f64) {
    let mut best = f64::INFINITY;
    let mut out = None;
    for _ in 0..RUNS {
        let start = Instant::now();
        out = Some(f());
        best = best.min(start.elapsed().as_secs_f64());
    }
    (out.expect("ran"), best)
}

fn main() {
    let path = long_loops();
    let total: f64 = path.moves.iter().map(move_length).sum();
    let (s, alpha) = alpha_samples(total, SPACING_MM);
    let values = TraceValues::new().per_sample(Quantity::Alpha, &s, &alpha);
    let (traced, trace_secs) = best(|| trace_path("planned", &path, &values, &[], &TraceOptions::default()));
    let vertices: usize = traced.runs.iter().map(|r| r.points.len()).sum();
    println!(
        "trace: {} moves, {:.1} m, {} samples → {} runs, {} vertices in {:.1} ms",
        path.moves.len(),
        total / 1000.0,
        s.len(),
        traced.runs.len(),
        vertices,
        trace_secs * 1e3
    );
    let scene = Scene { title: "bench".into(), alpha_limit_deg: Some(40.0), paths: vec![traced], ..Scene::default() };
    let (svg, render_secs) = best(|| render_drawing(&scene, &DrawOptions::default()).expect("draws"));
    println!("plan view: {:.2} MB in {:.1} ms", svg.len() as f64 / 1e6, render_secs * 1e3);
    save("samples.svg", &svg);

    let (dense_path, per_move) = dense(&path);
    let values = TraceValues::new().per_move(Quantity::Alpha, &per_move);
    let (traced, trace_secs) = best(|| trace_path("planned", &dense_path, &values, &[], &TraceOptions::default()));
    let vertices: usize = traced.runs.iter().map(|r| r.points.len()).sum();
    println!(
        "trace (dense): {} moves of ≤ {SPACING_MM} mm, value per move → {} runs, {} vertices in {:.1} ms",
        dense_path.moves.len(),
        traced.runs.len(),
        vertices,
        trace_secs * 1e3
    );
    let scene = Scene { title: "bench".into(), alpha_limit_deg: Some(40.0), paths: vec![traced], ..Scene::default() };
    let (svg, render_secs) = best(|| render_drawing(&scene, &DrawOptions::default()).expect("draws"));
    println!("plan view (dense): {:.2} MB in {:.1} ms", svg.len() as f64 / 1e6, render_secs * 1e3);
    save("dense.svg", &svg);

    let chart_width = 1000;
    let ((x, y), down_secs) = best(|| min_max_per_bucket(&s, &alpha, chart_width));
    let chart = ChartData {
        id: "alpha".into(),
        title: "α".into(),
        body: ChartBody::Lines(LineChart {
            x_label: "s, mm".into(),
            y_label: "α, deg".into(),
            series: vec![LineSeries { name: "planned".into(), x, y }],
            limits: vec![("α limit".into(), 40.0)],
        }),
    };
    let (chart_svg, chart_secs) = best(|| render_chart(&chart, chart_width as u32, 400));
    save("chart.svg", &chart_svg);
    println!(
        "chart: {} samples → {} points in {:.1} ms, rendered {:.0} kB in {:.2} ms",
        s.len(),
        match &chart.body {
            ChartBody::Lines(l) => l.series[0].x.len(),
            ChartBody::Bars(_) => 0,
        },
        down_secs * 1e3,
        chart_svg.len() as f64 / 1e3,
        chart_secs * 1e3
    );
}
