//! Chart data of a job: quantities against path distance from the samples kept for
//! drawing, downsampled per pixel column so that peaks survive.

use super::downsample::min_max_per_bucket;
use super::scene::{BarChart, BarGroup, ChartBody, ChartData, LineChart, LineSeries, Quantity};
use crate::core::analysis::samples::PathSamples;

/// Buckets a line chart's series are reduced to (about one per pixel column of a
/// 1200 px chart, each keeping its minimum and maximum).
pub const CHART_BUCKETS: usize = 1200;

/// The values of `quantity` in `samples` (wear is not sampled: `None`).
pub fn sampled(samples: &PathSamples, quantity: Quantity) -> Option<&[Option<f64>]> {
    match quantity {
        Quantity::Alpha => Some(&samples.alpha_deg),
        Quantity::Force => Some(&samples.force_n),
        Quantity::Feed => Some(&samples.feed_mm_min),
        Quantity::Wear => None,
    }
}

/// `quantity` against path distance, one line per `(name, samples)`; lines without a
/// single value are left out, and so is the chart when none is left.
pub fn distance_chart(
    id: &str,
    title: &str,
    quantity: Quantity,
    lines: &[(&str, &PathSamples)],
    limits: Vec<(String, f64)>,
) -> Option<ChartData> {
    let series: Vec<LineSeries> = lines
        .iter()
        .filter_map(|(name, samples)| {
            let values = sampled(samples, quantity)?;
            if values.iter().all(Option::is_none) {
                return None;
            }
            let (x, y) = min_max_per_bucket(&samples.s_mm, values, CHART_BUCKETS);
            Some(LineSeries { name: (*name).to_string(), x, y })
        })
        .collect();
    if series.is_empty() {
        return None;
    }
    Some(ChartData {
        id: id.to_string(),
        title: title.to_string(),
        body: ChartBody::Lines(LineChart {
            x_label: "path distance, mm".to_string(),
            y_label: quantity.caption().to_string(),
            series,
            limits,
        }),
    })
}

/// A bar chart of `groups` over `categories`, without notes or a highlighted category.
pub fn bar_chart(id: &str, title: &str, y_label: &str, categories: Vec<String>, groups: Vec<BarGroup>) -> ChartData {
    let notes = vec![String::new(); categories.len()];
    ChartData {
        id: id.to_string(),
        title: title.to_string(),
        body: ChartBody::Bars(BarChart { y_label: y_label.to_string(), categories, groups, notes, highlight: None }),
    }
}
