//! Charts in the unit a page shows lengths in: the API and the stored charts are in mm;
//! a page set to inches asks for its charts in inches, and their path distances (`…, mm`
//! axes) and feeds (`mm/min` axes) are converted, with the axes' captions.

use super::scene::{ChartBody, ChartData, LineChart};
use crate::core::nc::MM_PER_INCH;
use serde::{Deserialize, Serialize};

/// The unit a chart's lengths are shown in: `mm`, or `inch` (in, in/min).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, utoipa::ToSchema)]
#[serde(rename_all = "snake_case")]
pub enum LengthUnit {
    #[default]
    Mm,
    Inch,
}

/// The caption of an axis in mm, its unit converted; `None` when it has no length in it.
fn caption_in_inches(caption: &str) -> Option<String> {
    if caption.contains("mm/min") {
        Some(caption.replace("mm/min", "in/min"))
    } else {
        caption.strip_suffix(", mm").map(|head| format!("{head}, in"))
    }
}

/// `chart` with its lengths and feeds in `unit` (bar charts have none: unchanged).
pub fn in_unit(chart: &ChartData, unit: LengthUnit) -> ChartData {
    let mut chart = chart.clone();
    if unit == LengthUnit::Mm {
        return chart;
    }
    if let ChartBody::Lines(LineChart { x_label, y_label, series, limits }) = &mut chart.body {
        if let Some(caption) = caption_in_inches(x_label) {
            *x_label = caption;
            series.iter_mut().flat_map(|s| s.x.iter_mut()).for_each(|x| *x /= MM_PER_INCH);
        }
        if let Some(caption) = caption_in_inches(y_label) {
            *y_label = caption;
            series.iter_mut().flat_map(|s| s.y.iter_mut().flatten()).for_each(|y| *y /= MM_PER_INCH);
            limits.iter_mut().for_each(|(_, y)| *y /= MM_PER_INCH);
        }
    }
    chart
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::core::drawing::scene::LineSeries;

    fn chart(y_label: &str) -> ChartData {
        let series = vec![LineSeries { name: "planned".into(), x: vec![0.0, 254.0], y: vec![Some(2540.0), None] }];
        let body = LineChart {
            x_label: "path distance, mm".into(),
            y_label: y_label.into(),
            series,
            limits: vec![("max".into(), 5080.0)],
        };
        ChartData { id: "feed".into(), title: "Feed".into(), body: ChartBody::Lines(body) }
    }

    #[test]
    fn in_inches_path_distance_and_feed_are_divided_by_25_4_and_their_captions_follow() {
        let ChartBody::Lines(l) = in_unit(&chart("feed, mm/min"), LengthUnit::Inch).body else { panic!("not lines") };
        assert_eq!((l.x_label.as_str(), l.y_label.as_str()), ("path distance, in", "feed, in/min"));
        assert_eq!(l.series[0].x, [0.0, 10.0]);
        assert_eq!(l.series[0].y, [Some(100.0), None]);
        assert_eq!(l.limits[0].1, 200.0);
    }

    #[test]
    fn angles_and_forces_keep_their_values_and_mm_changes_nothing() {
        let ChartBody::Lines(l) = in_unit(&chart("engagement α, deg"), LengthUnit::Inch).body else {
            panic!("not lines")
        };
        assert_eq!((l.y_label.as_str(), l.series[0].y[0], l.limits[0].1), ("engagement α, deg", Some(2540.0), 5080.0));
        assert_eq!(in_unit(&chart("feed, mm/min"), LengthUnit::Mm), chart("feed, mm/min"));
    }
}
