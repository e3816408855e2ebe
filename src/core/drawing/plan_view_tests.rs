//! Tests of [`super::render_drawing`].

use super::*;
use crate::core::drawing::golden_tests::small_scene;
use crate::core::drawing::palette::COOL_BINS;
use crate::core::drawing::scene::LayerInfo;
use crate::core::drawing::svg::check_well_formed;
use crate::core::drawing::trace::{trace_path, TraceOptions, TraceValues};
use crate::core::toolpath::{Motion, Move, Plane, Toolpath, Units, P3};
use std::time::Instant;

fn draw(scene: &Scene, options: &DrawOptions) -> String {
    let svg = render_drawing(scene, options).expect("draws");
    check_well_formed(&svg).expect("well-formed");
    svg
}

fn count(svg: &str, needle: &str) -> usize {
    svg.matches(needle).count()
}

#[test]
fn the_default_drawing_shows_everything_the_scene_has() {
    let svg = draw(&small_scene(), &DrawOptions::default());
    for needle in [
        "data-role=\"stock\"",
        "data-role=\"pocket\"",
        "data-role=\"island\"",
        "class=\"feed\"",
        "class=\"rapid\"",
        "class=\"medial\" data-class=\"A\"",
        "class=\"medial\" data-class=\"B\"",
        "class=\"medial\" data-class=\"C\"",
        "class=\"region\" data-kind=\"inner_corner\"",
        "class=\"region-label\"",
        "α 95° · N120–N124",
        "class=\"trochoid\" data-loop-radius=\"2\"",
        "class=\"legend-ramp\" data-quantity=\"alpha\"",
        "class=\"legend-limit\"",
        "40 limit",
        "class=\"scale-bar\"",
        "class=\"legend-rapid\"",
        "class=\"legend-region\"",
        "class=\"legend-trochoid\"",
        "Square pocket with an island",
        "planned — all layers — coloured by engagement α, deg",
    ] {
        assert!(svg.contains(needle), "missing {needle}");
    }
}

#[test]
fn hidden_elements_are_not_drawn() {
    let options =
        DrawOptions { rapids: false, medial: false, regions: false, trochoids: false, ..DrawOptions::default() };
    let svg = draw(&small_scene(), &options);
    for class in ["rapid", "medial", "region", "region-label", "trochoid", "legend-rapid", "legend-region"] {
        assert!(!svg.contains(&format!("class=\"{class}\"")), "{class} drawn");
    }
    assert!(svg.contains("class=\"feed\""));
}

#[test]
fn segments_above_the_alpha_limit_are_in_the_hot_bins() {
    let svg = draw(&small_scene(), &DrawOptions::default());
    let hot = (COOL_BINS..crate::core::drawing::palette::BINS).any(|b| svg.contains(&format!("data-bin=\"{b}\"")));
    assert!(hot);
}

#[test]
fn consecutive_segments_of_one_bin_share_an_element() {
    let svg = draw(&small_scene(), &DrawOptions { color_by: Some(Quantity::Feed), ..DrawOptions::default() });
    // Two feeds: two bins, so two elements however many segments.
    assert_eq!(count(&svg, "class=\"feed\""), 2);
    assert!(svg.contains("coloured by feed, mm/min"));
    assert!(!svg.contains("class=\"legend-limit\""), "no α limit on the feed scale");
}

#[test]
fn a_layer_filter_keeps_only_that_layers_runs() {
    let mut scene = small_scene();
    scene.layers.push(LayerInfo { name: "layer 2".into(), z_top: -5.0, z_bottom: -10.0 });
    let mut second = scene.paths[0].runs[0].clone();
    second.layer = Some(1);
    second.points = vec![[100.0, 100.0], [110.0, 100.0]];
    scene.paths[0].runs.push(second);
    let svg = draw(&scene, &DrawOptions { layer: Some(1), ..DrawOptions::default() });
    assert!(svg.contains("— layer 2"));
    assert!(!svg.contains("class=\"rapid\""), "the rapid is in no layer");
    assert!(!svg.contains("class=\"region\""), "the region is in layer 0");
    assert_eq!(count(&svg, " L"), 1, "one feed segment");
}

#[test]
fn requests_the_scene_cannot_satisfy_are_refused() {
    let scene = small_scene();
    let bad = DrawOptions { color_by: Some(Quantity::Wear), ..DrawOptions::default() };
    assert_eq!(render_drawing(&scene, &bad).unwrap_err().field(), "color");
    let bad = DrawOptions { width_px: MAX_WIDTH_PX + 1, ..DrawOptions::default() };
    assert_eq!(render_drawing(&scene, &bad).unwrap_err().field(), "width");
}

#[test]
fn a_scene_without_paths_draws_its_outlines() {
    let mut scene = small_scene();
    scene.paths.clear();
    let svg = draw(&scene, &DrawOptions::default());
    assert!(svg.contains("class=\"outline\""));
    assert!(!svg.contains("class=\"feed\""));
}

#[test]
fn every_width_in_bounds_gives_a_well_formed_drawing() {
    for width_px in [MIN_WIDTH_PX, 640, DEFAULT_WIDTH_PX, MAX_WIDTH_PX] {
        let svg = draw(&small_scene(), &DrawOptions { width_px, ..DrawOptions::default() });
        assert!(svg.contains(&format!("width=\"{width_px}.00\"")));
    }
}

/// About 50 m of contour-parallel loops with corner arcs, and α per 0.05 mm sample.
pub(crate) fn long_loops() -> (Toolpath, Vec<f64>, Vec<Option<f64>>) {
    const STEP_MM: f64 = 0.5;
    const CORNER_MM: f64 = 3.0;
    let mut moves = Vec::new();
    let z = -2.0;
    let mut at = P3::new(100.0, 75.0, 5.0);
    let mut push = |motion: Motion, to: P3, moves: &mut Vec<Move>| {
        let line = moves.len() as u32 + 1;
        moves.push(Move { motion, start: at, end: to, feed_mm_min: Some(2000.0), spindle_rpm: None, tool: None, line });
        at = to;
    };
    let mut o = 70.0;
    let mut first = true;
    while o > 2.0 {
        let (x0, y0, x1, y1) = (100.0 - o - 25.0, 75.0 - o, 100.0 + o + 25.0, 75.0 + o);
        let c = CORNER_MM.min(o / 2.0);
        let start = P3::new(x0 + c, y0, z);
        if first {
            push(Motion::Rapid, P3::new(start.x, start.y, 5.0), &mut moves);
            push(Motion::Linear, start, &mut moves);
            first = false;
        } else {
            push(Motion::Linear, start, &mut moves);
        }
        let corners = [(x1, y0, -1.0, 1.0), (x1, y1, -1.0, -1.0), (x0, y1, 1.0, -1.0), (x0, y0, 1.0, 1.0)];
        let mut dir = (1.0, 0.0);
        for (cx, cy, sx, sy) in corners {
            let before = P3::new(cx - dir.0 * c, cy - dir.1 * c, z);
            push(Motion::Linear, before, &mut moves);
            let center = P3::new(cx + sx * c, cy + sy * c, z);
            let next = (-dir.1, dir.0);
            let after = P3::new(cx + next.0 * c, cy + next.1 * c, z);
            push(Motion::Arc { center, clockwise: false, plane: Plane::Xy, turns: 0 }, after, &mut moves);
            dir = next;
        }
        o -= STEP_MM;
    }
    let path = Toolpath { moves, events: vec![], source_units: Units::Mm, warnings: vec![] };
    let total: f64 = path.moves.iter().map(crate::core::analysis::sampling::move_length).sum();
    let n = (total / 0.05) as usize;
    let s: Vec<f64> = (1..=n).map(|i| i as f64 * 0.05).collect();
    let alpha: Vec<Option<f64>> = s
        .iter()
        .map(|&s| {
            let corner = ((s / 7.3).sin() * 0.5 + 0.5).powi(40);
            Some(18.0 + 8.0 * (s / 95.0).sin() + 70.0 * corner)
        })
        .collect();
    (path, s, alpha)
}

#[test]
fn a_million_sample_scene_renders_in_well_under_a_second_and_stays_small() {
    let (path, s, alpha) = long_loops();
    assert!(s.len() > 500_000, "{} samples", s.len());
    let values = TraceValues::new().per_sample(Quantity::Alpha, &s, &alpha);
    let traced = trace_path("planned", &path, &values, &[], &TraceOptions::default());
    let scene = Scene { alpha_limit_deg: Some(40.0), paths: vec![traced], ..Scene::default() };
    let started = Instant::now();
    let svg = draw(&scene, &DrawOptions::default());
    let secs = started.elapsed().as_secs_f64();
    assert!(secs < 1.0, "{secs} s");
    assert!(svg.len() < 5_000_000, "{} bytes", svg.len());
}

#[test]
fn a_short_outlier_takes_the_top_colour_without_stretching_the_wear_scale() {
    let mut moves = Vec::new();
    for k in 0..100 {
        let x = f64::from(k);
        moves.push(Move {
            motion: Motion::Linear,
            start: P3::new(x, 0.0, -1.0),
            end: P3::new(x + 1.0, 0.0, -1.0),
            feed_mm_min: Some(1000.0),
            spindle_rpm: Some(9600.0),
            tool: None,
            line: k + 1,
        });
    }
    let path = Toolpath { moves, events: Vec::new(), source_units: Units::Mm, warnings: Vec::new() };
    // Every millimetre wears 1 %/m but the last, which wears 30 %/m.
    let wear: Vec<Option<f64>> =
        (0..100).map(|k| Some(if k == 99 { 30.0 } else { 1.0 + 0.01 * f64::from(k) })).collect();
    let values = TraceValues::new().per_move(Quantity::Wear, &wear);
    let traced = trace_path("program", &path, &values, &[], &TraceOptions::default());
    let scene = Scene { title: "wear".into(), paths: vec![traced], ..Scene::default() };
    let svg = draw(&scene, &DrawOptions { color_by: Some(Quantity::Wear), ..DrawOptions::default() });
    assert!(svg.contains("≥ 1.98"), "the scale tops out below the outlier and says so");
}
