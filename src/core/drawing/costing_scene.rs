//! The scene of a costing (seed 002 Eq. 4, MODEL.md §9–11): the path coloured by where
//! the tool's life is spent, and charts of the machining time and the cost.

use super::analysis_scene::{alpha_limit, layer_of_range, stock_scene, INPUT_PATH};
use super::charts::{bar_chart, distance_chart};
use super::paths::{traced, wear_rates};
use super::regions::marks_of_regions;
use super::scene::{BarGroup, ChartData, Quantity, Scene};
use super::trace::layer_of;
use crate::core::analysis::{Analysis, AnalysisSpec};
use crate::core::costing::cost::Cost;
use crate::core::costing::wear::WearReport;
use crate::core::kinematics::MachiningTime;
use crate::core::toolpath::Toolpath;

/// Time per part of the program (feed moves, rapids, tool changes, dwells), nominal
/// and kinematic.
fn time_chart(time: &MachiningTime) -> ChartData {
    bar_chart(
        "time",
        "Machining time per part of the program",
        "time, min",
        ["feed moves", "rapids", "tool changes", "dwells"].map(String::from).to_vec(),
        vec![
            BarGroup {
                name: "nominal".to_string(),
                values: [time.feed_nominal_min, time.rapid_nominal_min, time.tool_change_min, time.dwell_min]
                    .map(Some)
                    .to_vec(),
            },
            BarGroup {
                name: "kinematic".to_string(),
                values: [time.feed_kinematic_min, time.rapid_kinematic_min, time.tool_change_min, time.dwell_min]
                    .map(Some)
                    .to_vec(),
            },
        ],
    )
}

/// The cost of seed 002 Eq. 4 by its two terms.
fn cost_chart(cost: &Cost) -> ChartData {
    bar_chart(
        "cost",
        "Cost: machine time and tool",
        &format!("cost, {}", cost.currency),
        ["machine", "tool", "total"].map(String::from).to_vec(),
        vec![BarGroup {
            name: "cost".to_string(),
            values: vec![Some(cost.machine), Some(cost.tool), Some(cost.total)],
        }],
    )
}

/// The scene of the costing of `path` in `spec`'s stock.
pub fn costing_scene(
    path: &Toolpath,
    spec: &AnalysisSpec,
    analysis: &Analysis,
    wear: &WearReport,
    time: &MachiningTime,
    cost: &Cost,
) -> Scene {
    let layers = vec![layer_of_range(spec.z_top, spec.z_bottom)];
    let samples = &wear.samples;
    let scene_path = traced(
        INPUT_PATH,
        path,
        Some(samples),
        vec![(Quantity::Wear, wear_rates(path, &wear.move_consumption))],
        &layers,
    );
    let regions = marks_of_regions(&analysis.critical_regions, samples, INPUT_PATH, |z| layer_of(z, &layers));
    let mut charts = vec![time_chart(time), cost_chart(cost)];
    charts.extend(distance_chart(
        "alpha",
        "Engagement α along the path",
        Quantity::Alpha,
        &[(INPUT_PATH, samples)],
        alpha_limit(spec.alpha_limit_deg),
    ));
    let title = format!(
        "Costing: {:.1} min, {:.1} % of a tool, {:.2} {}",
        time.kinematic_min,
        100.0 * wear.consumption.ratio,
        cost.total,
        cost.currency
    );
    stock_scene(title, spec, layers, scene_path, regions, charts)
}
