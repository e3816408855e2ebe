//! Bar charts: per category a group of bars (one per [`BarGroup`], one colour each), the
//! value on each bar, "n/a" for a missing value, notes under the categories and the
//! highlighted category in bold with a dashed outline.
//!
//! [`BarGroup`]: super::scene::BarGroup

use super::chart::{legend_row, y_axis, y_axis_width, Layout};
use super::palette::{self, series_color};
use super::scene::BarChart;
use super::svg::{text_width, Anchor, Attrs, Svg};
use super::ticks::{nice_ticks, value_label};

/// About this many intervals on the value axis.
const Y_TICKS: usize = 5;
/// Share of a category's band the bars take.
const BARS_SHARE: f64 = 0.8;
/// Smallest font of a value or category label, px.
const MIN_LABEL_FONT_PX: f64 = 6.0;
/// Value labels are this fraction of the text font at most.
const VALUE_FONT_SHARE: f64 = 0.85;
/// Notes are in this fraction of the text font.
const NOTE_FONT_SHARE: f64 = 0.85;
/// Colour of notes and "n/a".
const MUTED: palette::Rgb = palette::Rgb(0x75, 0x75, 0x75);

pub(super) fn draw_bars(svg: &mut Svg, chart: &BarChart, layout: &Layout) {
    let font = layout.font();
    let names: Vec<String> = chart.groups.iter().map(|g| g.name.clone()).collect();
    let legend_bottom = legend_row(svg, &names, layout);
    let values = chart.groups.iter().flat_map(|g| g.values.iter().flatten().copied().filter(|v| v.is_finite()));
    let (lo, hi) = values.fold((0.0f64, 0.0f64), |(a, b), v| (a.min(v), b.max(v)));
    let ticks = nice_ticks(lo, hi, Y_TICKS);
    let has_notes = chart.notes.iter().any(|n| !n.is_empty());
    let left = y_axis_width(&ticks, layout);
    let right = layout.width - layout.margin();
    let top = legend_bottom + font * 1.2;
    let bottom = layout.height - layout.margin() - font * if has_notes { 2.6 } else { 1.4 };
    let plot = y_axis(svg, &ticks, &chart.y_label, (left, right, top, bottom), layout);
    let zero = plot.y_px(0.0);
    svg.line((left, zero), (right, zero), Attrs::new().class("axis").show("stroke", palette::INK));

    let n = chart.categories.len();
    let band = (right - left) / n as f64;
    let bar_w = band * BARS_SHARE / chart.groups.len() as f64;
    for (c, category) in chart.categories.iter().enumerate() {
        let x0 = left + band * c as f64;
        let highlighted = chart.highlight == Some(c);
        let mut attrs = Attrs::new().class("category").show("data-index", c);
        if highlighted {
            attrs = attrs.str("data-highlight", "true");
        }
        svg.group(attrs);
        if highlighted {
            let dash = format!("{:.1} {:.1}", 4.0 * layout.k, 3.0 * layout.k);
            svg.rect(
                x0 + 1.0,
                top,
                band - 2.0,
                bottom - top,
                Attrs::new()
                    .class("highlight")
                    .str("fill", "none")
                    .show("stroke", palette::INK)
                    .num("stroke-width", 1.2 * layout.k)
                    .str("stroke-dasharray", &dash),
            );
        }
        let bars_left = x0 + band * (1.0 - BARS_SHARE) / 2.0;
        for (g, group) in chart.groups.iter().enumerate() {
            let x = bars_left + bar_w * g as f64;
            let value = group.values.get(c).copied().flatten().filter(|v| v.is_finite());
            let text = value.map_or_else(|| "n/a".to_string(), value_label);
            let vfont = fit_font(&text, bar_w * 0.95, font * VALUE_FONT_SHARE);
            let cx = x + bar_w / 2.0;
            match value {
                Some(v) => {
                    let y = plot.y_px(v);
                    svg.rect(
                        x,
                        y.min(zero),
                        bar_w * 0.92,
                        (y - zero).abs(),
                        Attrs::new().class("bar").str("data-group", &group.name).show("fill", series_color(g)),
                    );
                    let ty = if v >= 0.0 { y - vfont * 0.3 } else { y + vfont * 1.1 };
                    svg.text((cx, ty), vfont, Anchor::Middle, &text, Attrs::new().class("bar-value"));
                }
                None => {
                    let ty = zero - vfont * 0.3;
                    let attrs = Attrs::new().class("bar-na").str("data-group", &group.name).show("fill", MUTED);
                    svg.text((cx, ty), vfont, Anchor::Middle, &text, attrs);
                }
            }
        }
        let cfont = fit_font(category, band * 0.95, font);
        let mut attrs = Attrs::new().class("category-label");
        if highlighted {
            attrs = attrs.str("font-weight", "bold");
        }
        let cx = x0 + band / 2.0;
        svg.text((cx, bottom + font * 1.1), cfont, Anchor::Middle, category, attrs);
        if let Some(note) = chart.notes.get(c).filter(|n| !n.is_empty()) {
            let nfont = fit_font(note, band * 0.95, font * NOTE_FONT_SHARE);
            let attrs = Attrs::new().class("note").show("fill", MUTED).str("font-style", "italic");
            svg.text((cx, bottom + font * 2.3), nfont, Anchor::Middle, note, attrs);
        }
        svg.end_group();
    }
}

/// The font size (at most `font`, at least [`MIN_LABEL_FONT_PX`]) at which `text` fits
/// `width`.
fn fit_font(text: &str, width: f64, font: f64) -> f64 {
    let at_one = text_width(text, 1.0);
    if at_one <= 0.0 {
        return font;
    }
    (width / at_one).min(font).max(MIN_LABEL_FONT_PX)
}
