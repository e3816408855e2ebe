//! Golden files: small drawings and charts compared byte for byte with
//! `src/core/drawing/golden/*.svg`. Run with `UPDATE_GOLDEN=1` to rewrite them (then look
//! at them and commit them).

use super::chart::render_chart;
use super::display_units::LengthUnit;
use super::plan_view::{render_drawing, DrawOptions};
use super::scene::*;
use super::svg::check_well_formed;
use std::collections::BTreeMap;
use std::path::PathBuf;

/// A 50 × 50 mm square pocket in its stock with a 10 × 10 island, one layer, a rapid, two
/// feed loops coloured by α (a corner above the limit, marked critical), the medial axis
/// in three classes and a trochoid span.
pub(super) fn small_scene() -> Scene {
    let square = |x0: f64, y0: f64, x1: f64, y1: f64| vec![[x0, y0], [x1, y0], [x1, y1], [x0, y1]];
    let outer = vec![[5.0, 5.0], [45.0, 5.0], [45.0, 40.0], [45.0, 45.0], [40.0, 45.0], [5.0, 45.0], [5.0, 5.0]];
    let outer_alpha = vec![30.0, 30.0, 35.0, 95.0, 70.0, 32.0, 30.0];
    let inner = vec![[25.0, 15.0], [35.0, 15.0], [35.0, 35.0], [15.0, 35.0], [15.0, 15.0], [25.0, 15.0]];
    let inner_alpha = vec![12.0, 12.0, 20.0, 25.0, 38.0, 38.0];
    let run = |points: Vec<[f64; 2]>, alpha: Vec<f64>, feed: f64| Run {
        layer: Some(0),
        rapid: false,
        values: BTreeMap::from([
            (Quantity::Alpha, alpha.iter().map(|&a| Some(a as f32)).collect()),
            (Quantity::Feed, alpha.iter().map(|_| Some(feed as f32)).collect()),
        ]),
        points,
        z: Vec::new(),
        lines: Vec::new(),
        s_mm: Vec::new(),
    };
    let rapid = Run {
        layer: None,
        rapid: true,
        points: vec![[5.0, 5.0], [25.0, 15.0]],
        values: BTreeMap::from([(Quantity::Alpha, vec![None, None]), (Quantity::Feed, vec![None, None])]),
        z: Vec::new(),
        lines: Vec::new(),
        s_mm: Vec::new(),
    };
    let medial = |class: MedialClass, points: Vec<[f64; 2]>| MedialEdge {
        class,
        layer: Some(0),
        points,
        min_radius_mm: 5.0,
        max_radius_mm: 10.0,
    };
    Scene {
        title: "Square pocket with an island".into(),
        tool_diameter_mm: Some(6.0),
        alpha_limit_deg: Some(40.0),
        outlines: vec![
            Outline { role: OutlineRole::Stock, points: square(-10.0, -10.0, 60.0, 60.0) },
            Outline { role: OutlineRole::Pocket, points: square(0.0, 0.0, 50.0, 50.0) },
            Outline { role: OutlineRole::Island, points: square(20.0, 20.0, 30.0, 30.0) },
        ],
        layers: vec![LayerInfo { name: "layer 1 (z −5)".into(), z_top: 0.0, z_bottom: -5.0 }],
        paths: vec![ScenePath {
            name: "planned".into(),
            runs: vec![run(outer, outer_alpha, 1200.0), rapid, run(inner, inner_alpha, 1500.0)],
            detail_mm: Some(0.0025),
        }],
        medial: vec![
            medial(MedialClass::A, vec![[0.0, 0.0], [20.0, 20.0]]),
            medial(MedialClass::A, vec![[50.0, 0.0], [30.0, 20.0]]),
            medial(MedialClass::A, vec![[0.0, 50.0], [20.0, 30.0]]),
            medial(MedialClass::A, vec![[50.0, 50.0], [30.0, 30.0]]),
            medial(MedialClass::B, vec![[20.0, 40.0], [30.0, 40.0]]),
            medial(MedialClass::C, vec![[40.0, 20.0], [40.0, 30.0]]),
        ],
        regions: vec![RegionMark {
            kind: "inner_corner".into(),
            path: "planned".into(),
            layer: Some(0),
            points: vec![[45.0, 38.0], [45.0, 45.0], [38.0, 45.0]],
            max_alpha_deg: 95.0,
            start_line: 120,
            end_line: 124,
        }],
        trochoids: vec![TrochoidMark {
            layer: Some(0),
            points: vec![[20.0, 40.0], [30.0, 40.0]],
            loop_radius_mm: 2.0,
            pitch_mm: None,
            path: None,
        }],
        charts: vec![line_chart(), bar_chart()],
    }
}

/// α against path distance for two paths, with a gap and the limit.
pub(super) fn line_chart() -> ChartData {
    let x: Vec<f64> = (0..=300).map(|i| f64::from(i) * 0.5).collect();
    let input: Vec<Option<f64>> = x
        .iter()
        .map(|&s| if (60.0..70.0).contains(&s) { None } else { Some(30.0 + 25.0 * (s / 12.0).sin() + (s / 40.0)) })
        .collect();
    let planned: Vec<Option<f64>> = x.iter().map(|&s| Some(22.0 + 10.0 * (s / 15.0).cos())).collect();
    ChartData {
        id: "alpha".into(),
        title: "Engagement along the path".into(),
        body: ChartBody::Lines(LineChart {
            x_label: "path distance s, mm".into(),
            y_label: "engagement α, deg".into(),
            series: vec![
                LineSeries { name: "input".into(), x: x.clone(), y: input },
                LineSeries { name: "planned".into(), x, y: planned },
            ],
            limits: vec![("α limit 40°".into(), 40.0)],
        }),
    }
}

/// Candidate tools: cost and time, one missing, the chosen one highlighted.
pub(super) fn bar_chart() -> ChartData {
    ChartData {
        id: "candidates".into(),
        title: "Candidate tools".into(),
        body: ChartBody::Bars(BarChart {
            y_label: "cost, € / time, min".into(),
            categories: vec!["D12 flat".into(), "D10 flat".into(), "D8 flat".into(), "D6 ball".into()],
            groups: vec![
                BarGroup { name: "cost, €".into(), values: vec![Some(48.5), Some(41.2), Some(44.0), None] },
                BarGroup { name: "time, min".into(), values: vec![Some(35.0), Some(31.5), Some(38.25), None] },
            ],
            notes: vec!["".into(), "chosen".into(), "".into(), "cannot reach".into()],
            highlight: Some(1),
        }),
    }
}

/// Compares `svg` with the golden file `name`, or rewrites it with `UPDATE_GOLDEN=1`.
fn check_golden(name: &str, svg: &str) {
    check_well_formed(svg).unwrap_or_else(|e| panic!("{name} is not well-formed: {e}"));
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("src/core/drawing/golden").join(name);
    if std::env::var("UPDATE_GOLDEN").is_ok_and(|v| v == "1") {
        std::fs::create_dir_all(path.parent().expect("a folder")).expect("golden folder");
        std::fs::write(&path, svg).expect("golden file written");
        return;
    }
    let expected = std::fs::read_to_string(&path)
        .unwrap_or_else(|e| panic!("{}: {e} (run with UPDATE_GOLDEN=1 to create it)", path.display()));
    assert!(
        expected == svg,
        "{} differs from the rendering (run with UPDATE_GOLDEN=1 to update it, then look at it)",
        path.display()
    );
}

#[test]
fn the_small_scene_drawing_matches_its_golden_file() {
    check_golden("scene.svg", &render_drawing(&small_scene(), &DrawOptions::default()).expect("draws"));
}

#[test]
fn the_small_scene_drawn_in_inches_matches_its_golden_file() {
    let options = DrawOptions { unit: LengthUnit::Inch, color_by: Some(Quantity::Feed), ..DrawOptions::default() };
    check_golden("scene_inch.svg", &render_drawing(&small_scene(), &options).expect("draws"));
}

#[test]
fn the_line_chart_matches_its_golden_file() {
    check_golden("line_chart.svg", &render_chart(&line_chart(), 800, 400));
}

#[test]
fn the_bar_chart_matches_its_golden_file() {
    check_golden("bar_chart.svg", &render_chart(&bar_chart(), 800, 400));
}
