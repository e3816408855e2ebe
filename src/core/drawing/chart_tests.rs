//! Tests of [`super::render_chart`].

use super::*;
use crate::core::drawing::golden_tests::{bar_chart, line_chart};
use crate::core::drawing::scene::{BarChart, BarGroup, LineSeries};
use crate::core::drawing::svg::check_well_formed;

fn render(chart: &ChartData) -> String {
    let svg = render_chart(chart, 800, 400);
    check_well_formed(&svg).expect("well-formed");
    svg
}

fn lines(series: Vec<LineSeries>) -> ChartData {
    ChartData {
        id: "t".into(),
        title: "t".into(),
        body: ChartBody::Lines(LineChart { x_label: "x".into(), y_label: "y".into(), series, limits: vec![] }),
    }
}

/// The `d` of the first series path.
fn series_d(svg: &str) -> &str {
    let at = svg.find("class=\"series\"").expect("a series");
    let start = svg[..at].rfind("d=\"").expect("d") + 3;
    &svg[start..start + svg[start..].find('"').expect("end of d")]
}

#[test]
fn a_line_chart_draws_each_series_its_limit_and_a_legend() {
    let svg = render(&line_chart());
    assert_eq!(svg.matches("class=\"series\"").count(), 2);
    assert!(svg.contains("class=\"series\" data-name=\"input\""));
    assert_eq!(svg.matches("class=\"legend-series\"").count(), 2);
    assert!(svg.contains("class=\"limit\" data-value=\"40.00\""));
    assert!(svg.contains("α limit 40°"));
    assert!(svg.contains("path distance s, mm") && svg.contains("engagement α, deg"));
    assert!(svg.contains("class=\"tick-label\""));
}

#[test]
fn a_gap_splits_the_line() {
    let series = LineSeries {
        name: "a".into(),
        x: vec![0.0, 1.0, 2.0, 3.0, 4.0],
        y: vec![Some(1.0), Some(2.0), None, Some(3.0), Some(1.0)],
    };
    let svg = render(&lines(vec![series]));
    assert_eq!(series_d(&svg).matches('M').count(), 2);
}

#[test]
fn a_lone_point_between_gaps_is_drawn_as_a_dot() {
    let series = LineSeries { name: "a".into(), x: vec![0.0, 1.0, 2.0], y: vec![None, Some(2.0), None] };
    let svg = render(&lines(vec![series]));
    assert!(series_d(&svg).contains("l0 0"));
}

#[test]
fn a_long_series_is_drawn_with_about_two_points_per_column_and_keeps_its_peak() {
    let n = 1_000_000;
    let x: Vec<f64> = (0..n).map(|i| f64::from(i) * 0.05).collect();
    let mut y: Vec<Option<f64>> = x.iter().map(|s| Some(20.0 + (s / 3.0).sin())).collect();
    y[777_777] = Some(150.0);
    let svg = render(&lines(vec![LineSeries { name: "a".into(), x, y }]));
    let points = series_d(&svg).matches(['M', 'L']).count();
    assert!(points <= 2 * 800, "{points} points");
    assert!(svg.contains(">150</text>") || svg.contains(">160</text>"), "the y axis reaches the peak");
}

#[test]
fn a_bar_chart_labels_its_bars_and_marks_missing_values() {
    let svg = render(&bar_chart());
    assert_eq!(svg.matches("class=\"bar\"").count(), 6);
    assert_eq!(svg.matches("class=\"bar-na\"").count(), 2);
    assert!(svg.contains(">n/a</text>"));
    assert!(svg.contains(">41.2</text>"));
    assert!(svg.contains("font-weight=\"bold\">D10 flat</text>"));
    assert!(svg.contains("class=\"highlight\""));
    assert!(svg.contains(">cannot reach</text>"));
    assert_eq!(svg.matches("class=\"legend-series\"").count(), 2);
}

#[test]
fn negative_bars_hang_below_zero() {
    let chart = ChartData {
        id: "b".into(),
        title: "b".into(),
        body: ChartBody::Bars(BarChart {
            y_label: "Δ".into(),
            categories: vec!["a".into(), "b".into()],
            groups: vec![BarGroup { name: "g".into(), values: vec![Some(-5.0), Some(10.0)] }],
            notes: vec![],
            highlight: None,
        }),
    };
    let svg = render(&chart);
    assert!(svg.contains(">-5</text>") && svg.contains(">10</text>"));
}

#[test]
fn empty_charts_say_no_data() {
    let empty_bars = ChartData {
        id: "b".into(),
        title: "b".into(),
        body: ChartBody::Bars(BarChart {
            y_label: "y".into(),
            categories: vec![],
            groups: vec![],
            notes: vec![],
            highlight: None,
        }),
    };
    let all_gaps = LineSeries { name: "a".into(), x: vec![0.0, 1.0], y: vec![None, None] };
    for chart in [lines(vec![]), lines(vec![all_gaps]), empty_bars] {
        assert!(render(&chart).contains(">no data</text>"));
    }
}

#[test]
fn rendering_is_deterministic() {
    assert_eq!(render(&line_chart()), render(&line_chart()));
    assert_eq!(render(&bar_chart()), render(&bar_chart()));
}
