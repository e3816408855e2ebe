//! Drawings and charts in the unit a page shows lengths in: the API and the stored scenes
//! are in mm; a page set to inches asks for its drawings and charts in inches. A chart's
//! path distances (`…, mm` axes) and feeds (`mm/min` axes) are converted, with the axes'
//! captions; a drawing's frame, scale bar, feed legend and length labels are written in
//! the unit (its `frame` element keeps mm, which is what the page maps with).

use super::scene::{ChartBody, ChartData, LayerInfo, LineChart};
use super::ticks::value_label;
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

impl LengthUnit {
    /// Millimetres in one of this unit.
    pub fn mm(self) -> f64 {
        match self {
            LengthUnit::Mm => 1.0,
            LengthUnit::Inch => MM_PER_INCH,
        }
    }

    /// The unit's symbol: `mm` or `in`.
    pub fn symbol(self) -> &'static str {
        match self {
            LengthUnit::Mm => "mm",
            LengthUnit::Inch => "in",
        }
    }

    /// A length given in mm, in this unit.
    pub fn of_mm(self, mm: f64) -> f64 {
        mm / self.mm()
    }
}

/// A length given in mm as a label in `unit`, with its symbol: `0.5 mm`, `0.0197 in`.
pub fn length_label(mm: f64, unit: LengthUnit) -> String {
    format!("{} {}", value_label(unit.of_mm(mm)), unit.symbol())
}

/// The name of `layer` with its heights in `unit`: its name as the job gave it (in mm)
/// for mm; in inches, the name up to its heights (`layer 2`) and its z range in inches.
pub fn layer_name(layer: &LayerInfo, unit: LengthUnit) -> String {
    if unit == LengthUnit::Mm {
        return layer.name.clone();
    }
    let head = layer.name.split(" (z").next().unwrap_or_default();
    let z = |mm: f64| value_label(unit.of_mm(mm));
    format!("{head} (z {} to {} {})", z(layer.z_top), z(layer.z_bottom), unit.symbol())
}

/// A caption with lengths or feeds in mm (`…, mm`, `… mm/min`) in `unit`.
pub fn caption_in(caption: &str, unit: LengthUnit) -> String {
    match unit {
        LengthUnit::Mm => caption.to_string(),
        LengthUnit::Inch => caption_in_inches(caption).unwrap_or_else(|| caption.to_string()),
    }
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
    fn a_length_label_is_written_in_the_unit_with_its_symbol() {
        assert_eq!(length_label(12.7, LengthUnit::Inch), "0.5 in");
        assert_eq!(length_label(5.0, LengthUnit::Mm), "5 mm");
        assert_eq!(caption_in("feed, mm/min", LengthUnit::Inch), "feed, in/min");
        assert_eq!(caption_in("engagement α, deg", LengthUnit::Inch), "engagement α, deg");
        let layer = LayerInfo { name: "layer 2 (z -5.000 to -10.000)".into(), z_top: -5.08, z_bottom: -10.16 };
        assert_eq!(layer_name(&layer, LengthUnit::Inch), "layer 2 (z -0.2 to -0.4 in)");
        assert_eq!(layer_name(&layer, LengthUnit::Mm), layer.name);
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
