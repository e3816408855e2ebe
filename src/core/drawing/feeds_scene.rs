//! The scene of a feed optimisation (MODEL.md §3, seed 000): the path before and after,
//! coloured by feed, force and engagement, and feed, force and α against path distance
//! before and after.

use super::analysis_scene::{alpha_limit, layer_of_range, INPUT_PATH};
use super::charts::distance_chart;
use super::outlines::stock_outlines;
use super::paths::{move_feeds, traced, with_lines};
use super::regions::marks_of_regions;
use super::scene::{Quantity, Scene};
use super::trace::layer_of;
use crate::core::analysis::AnalysisSpec;
use crate::core::feed::plan::FeedPlan;
use crate::core::toolpath::Toolpath;

/// The path with the optimised feeds.
pub const OPTIMISED_PATH: &str = "optimised";

/// The scene of `plan` for `input`; `analysis` is the side-milling simulation's spec
/// (`None` for surface finishing, which has no stock to draw). `served_lines` gives, per
/// move of the optimised path, its line in the program served (the text sent, edited, or
/// the program written from JSON moves): the optimised path's vertices and regions name
/// them; the input path keeps the lines of the program sent.
pub fn feeds_scene(input: &Toolpath, plan: &FeedPlan, analysis: Option<&AnalysisSpec>, served_lines: &[u32]) -> Scene {
    let layers: Vec<_> = analysis.map(|a| layer_of_range(a.z_top, a.z_bottom)).into_iter().collect();
    let (before, after) = match &plan.drawing {
        Some(d) => (Some(&d.before), Some(&d.after)),
        None => (None, None),
    };
    // Sampled feeds are per sample; the drawing colours the feed by block, which is what
    // the program says.
    let input_path = traced(INPUT_PATH, input, before, vec![(Quantity::Feed, move_feeds(input))], &layers);
    let served = with_lines(&plan.path, served_lines);
    let optimised = traced(OPTIMISED_PATH, &served, after, vec![(Quantity::Feed, move_feeds(&served))], &layers);
    // A line of the program sent → the first line of the program served that it became.
    let mut first_line = std::collections::HashMap::new();
    for (m, s) in plan.path.moves.iter().zip(&served.moves) {
        first_line.entry(m.line).or_insert(s.line);
    }
    let serve = |line: u32| first_line.get(&line).copied().unwrap_or(line);
    let mut charts = Vec::new();
    if let (Some(b), Some(a)) = (before, after) {
        let lines = [("programmed", b), ("optimised", a)];
        let limit = analysis.map(|s| alpha_limit(s.alpha_limit_deg)).unwrap_or_default();
        charts.extend(distance_chart("feed", "Feed before and after optimisation", Quantity::Feed, &lines, Vec::new()));
        charts.extend(distance_chart(
            "force",
            "Predicted force before and after optimisation",
            Quantity::Force,
            &lines,
            Vec::new(),
        ));
        charts.extend(distance_chart(
            "alpha",
            "Engagement α along the path",
            Quantity::Alpha,
            &[(INPUT_PATH, b)],
            limit,
        ));
    }
    let regions = match (&plan.analysis, before, analysis) {
        (Some(result), Some(samples), Some(_)) => {
            let in_layer = |z: f64| layer_of(z, &layers);
            let mut marks = marks_of_regions(&result.critical_regions, samples, INPUT_PATH, in_layer);
            let copies: Vec<_> = marks
                .iter()
                .map(|m| super::scene::RegionMark {
                    path: OPTIMISED_PATH.to_string(),
                    start_line: serve(m.start_line),
                    end_line: serve(m.end_line),
                    ..m.clone()
                })
                .collect();
            marks.extend(copies);
            marks
        }
        _ => Vec::new(),
    };
    Scene {
        title: format!(
            "Feed optimisation: {} moves, time {:.2} → {:.2} min",
            input.moves.len(),
            plan.before.time_min,
            plan.after.time_min
        ),
        tool_diameter_mm: analysis.map(|a| a.tool.diameter_mm),
        alpha_limit_deg: analysis.map(|a| a.alpha_limit_deg),
        outlines: analysis.map(|a| stock_outlines(&a.stock, &a.open)).unwrap_or_default(),
        layers,
        paths: vec![input_path, optimised],
        medial: Vec::new(),
        regions,
        trochoids: Vec::new(),
        charts,
    }
}
