//! The scene of an analysis: the stock, the path coloured by engagement, force and
//! feed, its critical regions, and α, force and feed against path distance.

use super::charts::distance_chart;
use super::outlines::stock_outlines;
use super::paths::traced;
use super::regions::marks_of_regions;
use super::scene::{ChartData, LayerInfo, Quantity, RegionMark, Scene, ScenePath};
use super::trace::layer_of;
use crate::core::analysis::samples::PathSamples;
use crate::core::analysis::{Analysis, AnalysisSpec};
use crate::core::toolpath::Toolpath;

/// Name of an analysed path in its scene.
pub const INPUT_PATH: &str = "input";

/// The layer of a stock's z range.
pub fn layer_of_range(z_top: f64, z_bottom: f64) -> LayerInfo {
    LayerInfo { name: format!("z {z_bottom:.3} to {z_top:.3}"), z_top, z_bottom }
}

/// The limit line of an α chart.
pub fn alpha_limit(limit_deg: f64) -> Vec<(String, f64)> {
    vec![(format!("limit {limit_deg}°"), limit_deg)]
}

/// The scene of `analysis` of `path` in `spec`'s stock, with the kept `samples`.
pub fn analysis_scene(path: &Toolpath, spec: &AnalysisSpec, analysis: &Analysis, samples: &PathSamples) -> Scene {
    let layers = vec![layer_of_range(spec.z_top, spec.z_bottom)];
    let scene_path = traced(INPUT_PATH, path, Some(samples), Vec::new(), &layers);
    let in_layer = |z: f64| layer_of(z, &layers);
    let regions = marks_of_regions(&analysis.critical_regions, samples, INPUT_PATH, in_layer);
    let lines = [(INPUT_PATH, samples)];
    let charts = [
        distance_chart(
            "alpha",
            "Engagement α along the path",
            Quantity::Alpha,
            &lines,
            alpha_limit(spec.alpha_limit_deg),
        ),
        distance_chart("force", "Predicted force along the path", Quantity::Force, &lines, Vec::new()),
        distance_chart("feed", "Programmed feed along the path", Quantity::Feed, &lines, Vec::new()),
    ];
    let title = format!(
        "Analysis: {} moves, {} mm {} end mill, {} critical regions",
        path.moves.len(),
        spec.tool.diameter_mm,
        spec.tool.tool_type.as_str(),
        analysis.critical_regions.len()
    );
    stock_scene(title, spec, layers, scene_path, regions, charts.into_iter().flatten().collect())
}

/// The scene of one path simulated in `spec`'s stock (an analysis, a costing).
pub fn stock_scene(
    title: String,
    spec: &AnalysisSpec,
    layers: Vec<LayerInfo>,
    path: ScenePath,
    regions: Vec<RegionMark>,
    charts: Vec<ChartData>,
) -> Scene {
    Scene {
        title,
        tool_diameter_mm: Some(spec.tool.diameter_mm),
        alpha_limit_deg: Some(spec.alpha_limit_deg),
        outlines: stock_outlines(&spec.stock, &spec.open),
        layers,
        paths: vec![path],
        medial: Vec::new(),
        regions,
        trochoids: Vec::new(),
        charts,
    }
}
