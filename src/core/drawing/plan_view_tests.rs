//! Tests of [`super::render_drawing`].

use super::*;
use crate::core::drawing::golden_tests::small_scene;
use crate::core::drawing::palette::COOL_BINS;
use crate::core::drawing::scene::LayerInfo;
use crate::core::drawing::svg::check_well_formed;
use crate::core::drawing::synthetic::{alpha_samples, long_loops};
use crate::core::drawing::trace::{trace_path, TraceOptions, TraceValues};
use crate::core::toolpath::{Motion, Move, Toolpath, Units, P3};

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

/// Sample spacing of the synthetic path's engagement, mm.
const SYNTHETIC_SPACING_MM: f64 = 0.05;

#[test]
fn a_million_sample_scene_stays_small() {
    // Its speed is measured by `cargo bench --bench drawing`.
    let path = long_loops();
    let total: f64 = path.moves.iter().map(crate::core::toolpath::move_length).sum();
    let (s, alpha) = alpha_samples(total, SYNTHETIC_SPACING_MM);
    assert!(s.len() > 500_000, "{} samples", s.len());
    let values = TraceValues::new().per_sample(Quantity::Alpha, &s, &alpha);
    let traced = trace_path("planned", &path, &values, &[], &TraceOptions::default());
    let scene = Scene { alpha_limit_deg: Some(40.0), paths: vec![traced], ..Scene::default() };
    let svg = draw(&scene, &DrawOptions::default());
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

#[test]
fn every_outline_drawn_has_a_legend_entry() {
    let svg = draw(&small_scene(), &DrawOptions::default());
    assert_eq!(count(&svg, "class=\"legend-outline\""), 3, "stock, pocket wall and island");
    for label in [">stock<", ">pocket wall<", ">island<"] {
        assert!(svg.contains(label), "no legend entry {label}");
    }
}

#[test]
fn two_paths_coloured_by_feed_share_one_scale_so_an_unchanged_feed_keeps_its_colour() {
    // "before" at 1200 mm/min throughout, "after" slowed to 600 and sped up to 2400.
    let mut scene = small_scene();
    let mut after = scene.paths[0].clone();
    after.name = "after".into();
    for run in after.runs.iter_mut().filter(|r| !r.rapid) {
        let n = run.points.len();
        let feeds = (0..n).map(|i| Some(if i < n / 2 { 600.0 } else { 2400.0 })).collect();
        run.values.insert(Quantity::Feed, feeds);
    }
    for run in scene.paths[0].runs.iter_mut().filter(|r| !r.rapid) {
        let n = run.points.len();
        run.values.insert(Quantity::Feed, vec![Some(1200.0); n]);
    }
    scene.paths.push(after);
    let options =
        |path: &str| DrawOptions { path: Some(path.into()), color_by: Some(Quantity::Feed), ..DrawOptions::default() };
    let before = draw(&scene, &options("planned"));
    let after = draw(&scene, &options("after"));
    // Both legends run from 600 to 2400; the constant feed is in the ramp's middle, not
    // at its bottom as it would be on a scale of its own.
    for svg in [&before, &after] {
        assert!(svg.contains(">600<") && svg.contains(">2400<"), "{svg}");
    }
    let middle = palette::quantity_bin_color(Quantity::Feed, 10).to_string();
    assert!(before.contains(&format!("data-bin=\"10\" fill=\"none\" stroke=\"{middle}\"")), "{before}");
}

#[test]
fn a_window_is_drawn_anew_at_its_own_scale_clipped_with_labels_at_their_usual_size() {
    use crate::core::drawing::frame::Extent;
    let whole = draw(&small_scene(), &DrawOptions::default());
    let window = Extent { x_min: 35.0, y_min: 35.0, x_max: 50.0, y_max: 50.0 };
    let zoomed = draw(&small_scene(), &DrawOptions { window: Some(window), ..DrawOptions::default() });
    let scale = |svg: &str| -> f64 {
        let at = svg.find("data-scale=\"").expect("a frame") + 12;
        svg[at..].split('"').next().unwrap().parse().unwrap()
    };
    assert!(scale(&zoomed) > 4.0 * scale(&whole), "{} vs {}", scale(&zoomed), scale(&whole));
    assert!(zoomed.contains("clip-path=\"url(#drawing-area)\"") && zoomed.contains("data-windowed=\"true\""));
    assert!(!whole.contains("clip-path"));
    // The region's label and the legend keep their font size.
    for svg in [&whole, &zoomed] {
        assert!(svg.contains("font-size=\"11.00\""), "region label font");
        assert!(svg.contains("α 95° · N120–N124"));
    }
}

#[test]
fn a_window_that_is_not_a_box_is_refused_naming_x_min() {
    use crate::core::drawing::frame::Extent;
    for window in [
        Extent { x_min: 10.0, y_min: 0.0, x_max: 5.0, y_max: 10.0 },
        Extent { x_min: 0.0, y_min: 0.0, x_max: f64::NAN, y_max: 10.0 },
        Extent { x_min: 0.0, y_min: 0.0, x_max: 10.0, y_max: 0.0 },
        Extent { x_min: -1e300, y_min: 0.0, x_max: 1e300, y_max: 10.0 },
        Extent { x_min: 0.0, y_min: f64::NEG_INFINITY, x_max: 10.0, y_max: 10.0 },
    ] {
        let e = render_drawing(&small_scene(), &DrawOptions { window: Some(window), ..DrawOptions::default() });
        assert_eq!(e.unwrap_err().field(), "x_min");
    }
}

#[test]
fn dense_regions_share_one_label_that_counts_them_and_spans_their_lines() {
    let mut scene = small_scene();
    let first = scene.regions[0].clone();
    for k in 1..4u32 {
        let mut r = first.clone();
        r.points = r.points.iter().map(|p| [p[0] - 0.2 * f64::from(k), p[1]]).collect();
        r.max_alpha_deg = 90.0 - f64::from(k);
        r.start_line = 120 + 10 * k;
        r.end_line = 124 + 10 * k;
        scene.regions.push(r);
    }
    let svg = draw(&scene, &DrawOptions::default());
    assert_eq!(count(&svg, "class=\"region-label\""), 1, "one label for four close regions");
    assert!(svg.contains("data-cluster=\"4\""));
    assert!(svg.contains("α 95° · N120–N154 · +3 more"), "{svg}");
    assert_eq!(count(&svg, "class=\"region\""), 4, "every region is still drawn");
}
