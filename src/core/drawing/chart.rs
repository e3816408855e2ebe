//! Charts of a job as SVG: line charts (a quantity against path distance, with limits)
//! and bar charts (see [`super::bar_chart`]). Elements carry a `class` (`axis`, `grid`,
//! `tick-label`, `series`, `limit`, `bar`, …) and `data-` attributes.

use super::bar_chart::draw_bars;
use super::downsample::min_max_per_bucket;
use super::legend::{draw_entries, Entry, Swatch};
use super::palette::{self, series_color};
use super::scene::{ChartBody, ChartData, LineChart};
use super::svg::{text_width, Anchor, Attrs, Num, PathData, Svg};
use super::ticks::{decimals_for, label, nice_ticks};

/// Size unit: fonts and strokes scale with the width relative to this, px.
const REFERENCE_WIDTH_PX: f64 = 800.0;
const MIN_UNIT: f64 = 0.7;
const MAX_UNIT: f64 = 2.0;
/// Smallest chart, px.
const MIN_SIDE_PX: f64 = 100.0;
/// Margin, title font and text font, in size units.
const MARGIN: f64 = 12.0;
const TITLE_FONT: f64 = 15.0;
pub(super) const FONT: f64 = 12.0;
/// About this many intervals on an axis.
const X_TICKS: usize = 6;
const Y_TICKS: usize = 5;
/// Tick length, in size units.
const TICK: f64 = 4.0;
/// Line width of a series and of a limit, in size units.
const SERIES_STROKE: f64 = 1.5;
const LIMIT_STROKE: f64 = 1.2;

/// Renders `chart` as an SVG document of `width_px` × `height_px` (at least 100 px each).
pub fn render_chart(chart: &ChartData, width_px: u32, height_px: u32) -> String {
    let width = f64::from(width_px).max(MIN_SIDE_PX);
    let height = f64::from(height_px).max(MIN_SIDE_PX);
    let k = (width / REFERENCE_WIDTH_PX).clamp(MIN_UNIT, MAX_UNIT);
    let mut svg = Svg::new(width, height, &chart.title, "dieplan-chart");
    svg.rect(0.0, 0.0, width, height, Attrs::new().class("background").str("fill", "#ffffff"));
    let margin = MARGIN * k;
    svg.text(
        (margin, margin + TITLE_FONT * k),
        TITLE_FONT * k,
        Anchor::Start,
        &chart.title,
        Attrs::new().class("title"),
    );
    let top = margin + TITLE_FONT * k * 1.5;
    let layout = Layout { width, height, k, top };
    match &chart.body {
        ChartBody::Lines(lines) if has_points(lines) => draw_lines(&mut svg, lines, &layout),
        ChartBody::Bars(bars) if !bars.categories.is_empty() && !bars.groups.is_empty() => {
            draw_bars(&mut svg, bars, &layout)
        }
        _ => no_data(&mut svg, &layout),
    }
    svg.finish()
}

/// Sizes shared by the chart kinds.
#[derive(Debug, Clone, Copy)]
pub(super) struct Layout {
    pub width: f64,
    pub height: f64,
    /// Size unit.
    pub k: f64,
    /// Below the title.
    pub top: f64,
}

impl Layout {
    pub fn margin(&self) -> f64 {
        MARGIN * self.k
    }

    pub fn font(&self) -> f64 {
        FONT * self.k
    }
}

fn has_points(lines: &LineChart) -> bool {
    lines.series.iter().any(|s| s.x.iter().zip(&s.y).any(|(x, y)| x.is_finite() && y.is_some_and(f64::is_finite)))
}

fn no_data(svg: &mut Svg, layout: &Layout) {
    let at = (layout.width / 2.0, (layout.top + layout.height) / 2.0);
    svg.text(
        at,
        layout.font() * 1.2,
        Anchor::Middle,
        "no data",
        Attrs::new().class("no-data").show("fill", palette::INK),
    );
}

/// The plot area and its axes' ranges.
#[derive(Debug, Clone, Copy)]
pub(super) struct Plot {
    pub top: f64,
    pub bottom: f64,
    pub y_min: f64,
    pub y_max: f64,
}

impl Plot {
    pub fn y_px(&self, y: f64) -> f64 {
        self.bottom - (y - self.y_min) / (self.y_max - self.y_min) * (self.bottom - self.top)
    }
}

/// Draws the legend row under the title; returns its bottom.
pub(super) fn legend_row(svg: &mut Svg, names: &[String], layout: &Layout) -> f64 {
    let entries: Vec<Entry> = names
        .iter()
        .enumerate()
        .map(|(i, name)| Entry {
            class: "legend-series",
            swatch: Swatch::Band { color: series_color(i), opacity: 1.0 },
            label: name.clone(),
        })
        .collect();
    draw_entries(svg, &entries, (layout.margin(), layout.top), layout.width - layout.margin(), layout.k)
}

/// Draws the y axis (grid, ticks, labels, rotated caption) for `ticks` on a plot
/// `left..right` × `top..bottom`; returns the plot with its y range.
pub(super) fn y_axis(svg: &mut Svg, ticks: &[f64], caption: &str, area: (f64, f64, f64, f64), layout: &Layout) -> Plot {
    let (left, right, top, bottom) = area;
    let plot = Plot { top, bottom, y_min: ticks[0], y_max: ticks[ticks.len() - 1] };
    let font = layout.font();
    let decimals = decimals_for(ticks.get(1).map_or(1.0, |t| t - ticks[0]));
    svg.group(Attrs::new().class("y-axis"));
    for &t in ticks {
        let y = plot.y_px(t);
        svg.line(
            (left, y),
            (right, y),
            Attrs::new().class("grid").show("stroke", palette::GRID).num("stroke-width", 1.0),
        );
        svg.line((left - TICK * layout.k, y), (left, y), Attrs::new().show("stroke", palette::INK));
        let text = label(t, decimals);
        svg.text(
            (left - TICK * layout.k * 1.5, y + font * 0.35),
            font,
            Anchor::End,
            &text,
            Attrs::new().class("tick-label"),
        );
    }
    let cx = layout.margin() + font;
    let cy = (top + bottom) / 2.0;
    let rotate = format!("rotate(-90 {} {})", Num(cx), Num(cy));
    svg.text((cx, cy), font, Anchor::Middle, caption, Attrs::new().class("axis-label").str("transform", &rotate));
    svg.line((left, top), (left, bottom), Attrs::new().class("axis").show("stroke", palette::INK));
    svg.end_group();
    plot
}

/// Width of the y axis's labels and caption: where the plot's left edge goes.
pub(super) fn y_axis_width(ticks: &[f64], layout: &Layout) -> f64 {
    let font = layout.font();
    let decimals = decimals_for(ticks.get(1).map_or(1.0, |t| t - ticks[0]));
    let widest = ticks.iter().map(|&t| text_width(&label(t, decimals), font)).fold(0.0, f64::max);
    layout.margin() + font * 2.0 + widest + TICK * layout.k * 2.0
}

fn draw_lines(svg: &mut Svg, chart: &LineChart, layout: &Layout) {
    let font = layout.font();
    let names: Vec<String> = chart.series.iter().map(|s| s.name.clone()).collect();
    let legend_bottom = legend_row(svg, &names, layout);
    let finite = |v: f64| v.is_finite().then_some(v);
    let xs = chart.series.iter().flat_map(|s| s.x.iter().copied().filter_map(finite));
    let (x_lo, x_hi) = xs.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| (a.min(x), b.max(x)));
    let ys = chart.series.iter().flat_map(|s| s.y.iter().flatten().copied().filter_map(finite));
    let limits = chart.limits.iter().map(|l| l.1).filter_map(finite);
    let (y_lo, y_hi) = ys.chain(limits).fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), y| (a.min(y), b.max(y)));
    let x_ticks = nice_ticks(x_lo, x_hi, X_TICKS);
    let y_ticks = nice_ticks(y_lo, y_hi, Y_TICKS);

    let left = y_axis_width(&y_ticks, layout);
    let right = layout.width - layout.margin() - font;
    let top = legend_bottom + font * 0.5;
    let bottom = layout.height - layout.margin() - font * 3.2;
    let plot = y_axis(svg, &y_ticks, &chart.y_label, (left, right, top, bottom), layout);
    let (x_min, x_max) = (x_ticks[0], x_ticks[x_ticks.len() - 1]);
    let x_px = |x: f64| left + (x - x_min) / (x_max - x_min) * (right - left);

    // The x axis's scale, so that a page can read the path distance under the pointer.
    let scale = Attrs::new().class("x-axis").num("data-x-min", x_min).num("data-x-max", x_max);
    svg.group(scale.num("data-left", left).num("data-right", right));
    svg.line((left, bottom), (right, bottom), Attrs::new().class("axis").show("stroke", palette::INK));
    let decimals = decimals_for(x_ticks.get(1).map_or(1.0, |t| t - x_ticks[0]));
    for &t in &x_ticks {
        let x = x_px(t);
        svg.line((x, bottom), (x, bottom + TICK * layout.k), Attrs::new().show("stroke", palette::INK));
        let text = label(t, decimals);
        svg.text((x, bottom + TICK * layout.k + font), font, Anchor::Middle, &text, Attrs::new().class("tick-label"));
    }
    let caption_y = layout.height - layout.margin();
    svg.text(((left + right) / 2.0, caption_y), font, Anchor::Middle, &chart.x_label, Attrs::new().class("axis-label"));
    svg.end_group();

    let buckets = (right - left).max(1.0) as usize;
    for (i, series) in chart.series.iter().enumerate() {
        let (x, y) = min_max_per_bucket(&series.x, &series.y, buckets);
        let mut d = PathData::new();
        let mut open = 0usize;
        for (xv, yv) in x.iter().zip(&y) {
            match yv.filter(|v| v.is_finite()) {
                Some(v) if xv.is_finite() => {
                    let p = (x_px(*xv), plot.y_px(v));
                    if open == 0 {
                        d.move_to(p);
                    } else {
                        d.line_to(p);
                    }
                    open += 1;
                }
                _ => {
                    if open == 1 {
                        d.dot();
                    }
                    open = 0;
                }
            }
        }
        if open == 1 {
            d.dot();
        }
        svg.path(
            &d,
            Attrs::new()
                .class("series")
                .str("data-name", &series.name)
                .str("fill", "none")
                .show("stroke", series_color(i))
                .num("stroke-width", SERIES_STROKE * layout.k)
                .str("stroke-linejoin", "round")
                .str("stroke-linecap", "round"),
        );
    }

    for (caption, value) in chart.limits.iter().filter(|l| l.1.is_finite()) {
        let y = plot.y_px(*value);
        svg.group(Attrs::new().class("limit").show("data-value", Num(*value)));
        let dash = format!("{:.1} {:.1}", 6.0 * layout.k, 4.0 * layout.k);
        svg.line(
            (left, y),
            (right, y),
            Attrs::new()
                .show("stroke", palette::REGION)
                .num("stroke-width", LIMIT_STROKE * layout.k)
                .str("stroke-dasharray", &dash),
        );
        svg.text(
            (right - font * 0.3, y - font * 0.35),
            font,
            Anchor::End,
            caption,
            Attrs::new().show("fill", palette::REGION),
        );
        svg.end_group();
    }
}

#[cfg(test)]
#[path = "chart_tests.rs"]
mod tests;
