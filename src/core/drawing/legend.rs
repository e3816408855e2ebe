//! The legend of a plan view: the colour ramp with its ticks, the entries for what else
//! is drawn, and the scale bar.

use super::display_units::{caption_in, length_label, LengthUnit};
use super::palette::{quantity_bin_color, Rgb, ValueScale, BINS, INK};
use super::scene::Quantity;
use super::svg::{text_width, Anchor, Attrs, Svg};
use super::ticks::{round_down, value_label};

/// Font size of legend text, in size units.
pub const LEGEND_FONT: f64 = 12.0;
/// Height of the colour ramp, in size units.
const RAMP_HEIGHT: f64 = 14.0;
/// Length of a tick below the ramp, in size units.
const TICK_LENGTH: f64 = 4.0;
/// Width of an entry's swatch, in size units.
const SWATCH_WIDTH: f64 = 26.0;
/// Space after a swatch and after an entry, in size units.
const SWATCH_GAP: f64 = 6.0;
const ENTRY_GAP: f64 = 20.0;
/// Height of a row of entries, in size units.
const ENTRY_ROW: f64 = 20.0;
/// The scale bar is at most this fraction of the drawing's width.
const SCALE_BAR_FRACTION: f64 = 0.2;
/// Height of the scale bar's end ticks, in size units.
const SCALE_BAR_TICK: f64 = 6.0;

/// How an entry's swatch looks.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Swatch {
    /// A line, dashed or solid, of a width in size units.
    Line { color: Rgb, width: f64, dashed: bool },
    /// A translucent band.
    Band { color: Rgb, opacity: f64 },
    /// A filled area with its outline, dashed or solid.
    Area { stroke: Rgb, fill: Rgb, dashed: bool },
}

/// One legend entry.
#[derive(Debug, Clone, PartialEq)]
pub struct Entry {
    /// `class` of the entry (`legend-rapid`, …).
    pub class: &'static str,
    pub swatch: Swatch,
    pub label: String,
}

/// Draws the colour ramp of `scale` from `(x, y)` (top left of the caption) `width` px
/// wide, with min/max (and limit) ticks; returns the bottom of its labels. A feed's caption
/// and labels are in `unit` per minute (its `data-` attributes stay in mm/min).
pub fn draw_ramp(
    svg: &mut Svg,
    at: (f64, f64),
    width: f64,
    k: f64,
    (scale, quantity): (&ValueScale, Quantity),
    unit: LengthUnit,
) -> f64 {
    let font = LEGEND_FONT * k;
    let (x, y) = at;
    // The scale in data attributes: the page reads a colour bin's values from them.
    let mut group = Attrs::new()
        .class("legend-ramp")
        .str("data-quantity", quantity.as_str())
        .show("data-min", scale.min)
        .show("data-max", scale.max);
    if let Some(limit) = scale.limit {
        group = group.show("data-limit", limit);
    }
    svg.group(group);
    let caption = caption_in(quantity.caption(), unit);
    svg.text((x, y + font), font, Anchor::Start, &caption, Attrs::new().class("legend-caption"));
    let shown = |v: f64| if quantity == Quantity::Feed { unit.of_mm(v) } else { v };
    let ramp_top = y + font * 1.5;
    let ramp_h = RAMP_HEIGHT * k;
    let bin_w = width / BINS as f64;
    for bin in 0..BINS {
        // Overlap by a pixel fraction so no hairline gaps show between bins.
        let w = if bin + 1 < BINS { bin_w + 0.5 } else { bin_w };
        svg.rect(
            x + bin as f64 * bin_w,
            ramp_top,
            w,
            ramp_h,
            Attrs::new().show("fill", quantity_bin_color(quantity, bin)),
        );
    }
    svg.rect(x, ramp_top, width, ramp_h, Attrs::new().str("fill", "none").show("stroke", INK).num("stroke-width", 0.5));
    let tick_top = ramp_top + ramp_h;
    let label_y = tick_top + TICK_LENGTH * k + font;
    let limit = (quantity == Quantity::Alpha).then_some(scale.limit).flatten();
    // Ticks, most important first; a label overlapping one already placed is left out.
    let mut ticks: Vec<(f64, String, &str)> = Vec::new();
    if let Some(l) = limit {
        ticks.push((l, format!("{} limit", value_label(l)), "legend-limit"));
    }
    ticks.push((scale.min, value_label(shown(scale.min)), "legend-min"));
    let max = value_label(shown(scale.max));
    let top = if scale.top_clipped { format!("≥ {max}") } else { max };
    ticks.push((scale.max, top, "legend-max"));
    let mut placed: Vec<(f64, f64)> = Vec::new();
    for (value, text, class) in ticks {
        let tx = x + scale.position(value) * width;
        let w = text_width(&text, font);
        let left = (tx - w / 2.0).clamp(x - font, x + width + font - w);
        if placed.iter().any(|&(a, b)| left < b + font * 0.5 && left + w > a - font * 0.5) {
            continue;
        }
        placed.push((left, left + w));
        svg.line(
            (tx, tick_top - if class == "legend-limit" { ramp_h } else { 0.0 }),
            (tx, tick_top + TICK_LENGTH * k),
            Attrs::new()
                .class(class)
                .show("stroke", INK)
                .num("stroke-width", if class == "legend-limit" { 1.5 } else { 1.0 }),
        );
        svg.text((left, label_y), font, Anchor::Start, &text, Attrs::new().class(class));
    }
    svg.end_group();
    label_y + font * 0.3
}

/// Draws `entries` in rows from `(x, y)` (top left), wrapping before `max_x`; returns the
/// bottom of the last row.
pub fn draw_entries(svg: &mut Svg, entries: &[Entry], at: (f64, f64), max_x: f64, k: f64) -> f64 {
    if entries.is_empty() {
        return at.1;
    }
    let font = LEGEND_FONT * k;
    let (mut x, mut y) = at;
    svg.group(Attrs::new().class("legend-entries"));
    for entry in entries {
        let w = SWATCH_WIDTH * k + SWATCH_GAP * k + text_width(&entry.label, font);
        if x + w > max_x && x > at.0 {
            x = at.0;
            y += ENTRY_ROW * k;
        }
        let mid = y + ENTRY_ROW * k / 2.0;
        let (from, to) = ((x, mid), (x + SWATCH_WIDTH * k, mid));
        let attrs = Attrs::new().class(entry.class);
        match entry.swatch {
            Swatch::Line { color, width, dashed } => {
                let mut a = attrs.show("stroke", color).num("stroke-width", width * k);
                if dashed {
                    a = a.str("stroke-dasharray", &format!("{:.1} {:.1}", 4.0 * k, 3.0 * k));
                }
                svg.line(from, to, a);
            }
            Swatch::Band { color, opacity } => {
                let h = ENTRY_ROW * k * 0.5;
                svg.rect(x, mid - h / 2.0, SWATCH_WIDTH * k, h, attrs.show("fill", color).num("fill-opacity", opacity));
            }
            Swatch::Area { stroke, fill, dashed } => {
                let h = ENTRY_ROW * k * 0.6;
                let mut a = attrs.show("fill", fill).show("stroke", stroke).num("stroke-width", k);
                if dashed {
                    a = a.str("stroke-dasharray", &format!("{:.1} {:.1}", 4.0 * k, 2.0 * k));
                }
                svg.rect(x, mid - h / 2.0, SWATCH_WIDTH * k, h, a);
            }
        }
        let tx = x + (SWATCH_WIDTH + SWATCH_GAP) * k;
        svg.text((tx, mid + font * 0.35), font, Anchor::Start, &entry.label, Attrs::new());
        x += w + ENTRY_GAP * k;
    }
    svg.end_group();
    y + ENTRY_ROW * k
}

/// Draws a scale bar of a round length (1, 2 or 5 × 10^k of `unit`) ending at `right`
/// (px), its bar at `y`, for a drawing of `px_per_mm` and `drawing_width` px.
pub fn draw_scale_bar(
    svg: &mut Svg,
    (right, y): (f64, f64),
    px_per_mm: f64,
    drawing_width: f64,
    k: f64,
    unit: LengthUnit,
) {
    let length = round_down(unit.of_mm(drawing_width * SCALE_BAR_FRACTION / px_per_mm));
    if length <= 0.0 {
        return;
    }
    let length_mm = length * unit.mm();
    let font = LEGEND_FONT * k;
    let w = length_mm * px_per_mm;
    let left = right - w;
    let stroke = Attrs::new().show("stroke", INK).num("stroke-width", 1.5 * k);
    svg.group(
        Attrs::new()
            .class("scale-bar")
            .str("data-length-mm", &value_label(length_mm))
            .str("data-length", &value_label(length))
            .str("data-unit", unit.symbol()),
    );
    svg.line((left, y), (right, y), stroke.clone());
    svg.line((left, y - SCALE_BAR_TICK * k), (left, y), stroke.clone());
    svg.line((right, y - SCALE_BAR_TICK * k), (right, y), stroke);
    let label = length_label(length_mm, unit);
    svg.text((left + w / 2.0, y - SCALE_BAR_TICK * k - font * 0.3), font, Anchor::Middle, &label, Attrs::new());
    svg.end_group();
}
