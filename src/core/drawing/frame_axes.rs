//! The coordinates along a plan view's frame: round ticks on its bottom and left edges,
//! labelled in the display unit (mm or inch), inside the frame with a white halo so that
//! they read over the drawing at any zoom. The unit is named once, after the last x tick.

use super::display_units::LengthUnit;
use super::frame::Frame;
use super::palette::INK;
use super::svg::{Anchor, Attrs, Svg};
use super::ticks::{decimals_for, label, nice_ticks};

/// Font of the tick labels, in size units.
const AXIS_FONT: f64 = 10.0;
/// Length of a tick into the frame, in size units.
const AXIS_TICK: f64 = 5.0;
/// About one tick per this many px of the frame.
const PX_PER_TICK: f64 = 110.0;
/// Fewest ticks an axis aims at.
const MIN_TICKS: usize = 2;
/// A tick closer than this to a corner of the frame is left out, in size units (its label
/// would meet the other axis's).
const CORNER_CLEARANCE: f64 = 18.0;
/// Width of the labels' white halo, in size units.
const HALO: f64 = 3.0;

/// The round values (in `unit`) of an axis over `lo..hi` mm, `px` long, with the decimals
/// their step needs; only those inside the range.
fn axis_values(lo_mm: f64, hi_mm: f64, px: f64, unit: LengthUnit) -> (Vec<f64>, usize) {
    let (lo, hi) = (unit.of_mm(lo_mm), unit.of_mm(hi_mm));
    let target = ((px / PX_PER_TICK).round() as usize).max(MIN_TICKS);
    let ticks = nice_ticks(lo, hi, target);
    let step = if ticks.len() > 1 { ticks[1] - ticks[0] } else { hi - lo };
    (ticks.into_iter().filter(|t| *t >= lo && *t <= hi).collect(), decimals_for(step))
}

/// Draws the frame's coordinate ticks and labels in `unit` (a `frame-axes` group with
/// `axis-x` and `axis-y` groups; each label's `data-value` is in `unit`).
pub fn draw_frame_axes(svg: &mut Svg, frame: &Frame, unit: LengthUnit, k: f64) {
    let e = frame.extent();
    let (left, top) = frame.px([e.x_min, e.y_max]);
    let (right, bottom) = frame.px([e.x_max, e.y_min]);
    let font = AXIS_FONT * k;
    let tick = AXIS_TICK * k;
    let clear = CORNER_CLEARANCE * k;
    let stroke = Attrs::new().show("stroke", INK).num("stroke-width", 0.8 * k);
    let text = |class: &str, value: f64| {
        Attrs::new()
            .class(class)
            .show("data-value", value)
            .str("fill", "#333333")
            .str("stroke", "#ffffff")
            .num("stroke-width", HALO * k)
            .str("stroke-linejoin", "round")
            .str("paint-order", "stroke")
    };
    svg.group(Attrs::new().class("frame-axes").str("data-unit", unit.symbol()).str("pointer-events", "none"));

    svg.group(Attrs::new().class("axis-x"));
    let (xs, decimals) = axis_values(e.x_min, e.x_max, right - left, unit);
    let last = xs.iter().rposition(|&v| frame.px([v * unit.mm(), e.y_min]).0 < right - clear);
    for (i, &v) in xs.iter().enumerate() {
        let x = frame.px([v * unit.mm(), e.y_min]).0;
        if x < left + clear || x > right - clear {
            continue;
        }
        svg.line((x, bottom), (x, bottom - tick), stroke.clone());
        let mut words = label(v, decimals);
        if Some(i) == last {
            words = format!("{words} {}", unit.symbol());
        }
        svg.text((x, bottom - tick - font * 0.35), font, Anchor::Middle, &words, text("axis-label", v));
    }
    svg.end_group();

    svg.group(Attrs::new().class("axis-y"));
    let (ys, decimals) = axis_values(e.y_min, e.y_max, bottom - top, unit);
    for &v in &ys {
        let y = frame.px([e.x_min, v * unit.mm()]).1;
        if y < top + clear || y > bottom - clear {
            continue;
        }
        svg.line((left, y), (left + tick, y), stroke.clone());
        let words = label(v, decimals);
        let at = (left + tick + font * 0.3, y + font * 0.35);
        svg.text(at, font, Anchor::Start, &words, text("axis-label", v));
    }
    svg.end_group();
    svg.end_group();
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::core::drawing::frame::Extent;

    fn frame() -> Frame {
        Frame::fit(Extent { x_min: 0.0, y_min: 0.0, x_max: 100.0, y_max: 50.0 }, (0.0, 0.0), 1000.0, 1000.0)
    }

    fn labels(out: &str) -> Vec<String> {
        out.split("class=\"axis-label\"")
            .skip(1)
            .filter_map(|s| s.split('>').nth(1).and_then(|t| t.split('<').next()).map(str::to_string))
            .collect()
    }

    #[test]
    fn the_frame_is_labelled_with_round_coordinates_in_mm_and_names_its_unit_once() {
        let mut svg = Svg::fragment();
        draw_frame_axes(&mut svg, &frame(), LengthUnit::Mm, 1.0);
        let out = svg.finish_fragment();
        let l = labels(&out);
        assert!(l.contains(&"10".to_string()) && l.contains(&"40".to_string()), "{l:?}");
        assert_eq!(l.iter().filter(|t| t.ends_with(" mm")).count(), 1, "{l:?}");
        assert!(out.contains("data-unit=\"mm\""));
    }

    #[test]
    fn in_inches_the_ticks_are_round_inches_at_their_place_in_mm() {
        let mut svg = Svg::fragment();
        draw_frame_axes(&mut svg, &frame(), LengthUnit::Inch, 1.0);
        let out = svg.finish_fragment();
        let l = labels(&out);
        assert!(l.iter().any(|t| t.ends_with(" in")), "{l:?}");
        assert!(l.contains(&"1".to_string()) || l.contains(&"1.0".to_string()), "1 in lies within 100 mm: {l:?}");
        // 1 in is at 25.4 mm: 254 px from the left at 10 px/mm.
        assert!(out.contains("<line x1=\"254"), "{out}");
        assert!(out.contains("data-unit=\"in\""));
    }
}
