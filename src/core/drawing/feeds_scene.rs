//! The scene of a feed optimisation (MODEL.md §3, seed 000): the path before and after,
//! coloured by feed, force and engagement, and feed, force and α against path distance
//! before and after.

use super::analysis_scene::{alpha_limit, layer_of_range, INPUT_PATH};
use super::charts::distance_chart;
use super::outlines::stock_outlines;
use super::paths::{move_feeds, traced};
use super::regions::marks_of_regions;
use super::scene::{Quantity, Scene};
use super::trace::layer_of;
use crate::core::analysis::AnalysisSpec;
use crate::core::feed::plan::FeedPlan;
use crate::core::toolpath::Toolpath;

/// The path with the optimised feeds.
pub const OPTIMISED_PATH: &str = "optimised";

/// The scene of `plan` for `input`; `analysis` is the side-milling simulation's spec
/// (`None` for surface finishing, which has no stock to draw).
pub fn feeds_scene(input: &Toolpath, plan: &FeedPlan, analysis: Option<&AnalysisSpec>) -> Scene {
    let layers: Vec<_> = analysis.map(|a| layer_of_range(a.z_top, a.z_bottom)).into_iter().collect();
    let (before, after) = match &plan.drawing {
        Some(d) => (Some(&d.before), Some(&d.after)),
        None => (None, None),
    };
    // Sampled feeds are per sample; the drawing colours the feed by block, which is what
    // the program says.
    let input_path = traced(INPUT_PATH, input, before, vec![(Quantity::Feed, move_feeds(input))], &layers);
    let optimised = traced(OPTIMISED_PATH, &plan.path, after, vec![(Quantity::Feed, move_feeds(&plan.path))], &layers);
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
                .map(|m| super::scene::RegionMark { path: OPTIMISED_PATH.to_string(), ..m.clone() })
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
