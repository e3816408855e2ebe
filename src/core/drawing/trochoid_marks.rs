//! The trochoid spans of a drawing: bands 2ρ wide along the base path the loops follow.
//! Where the loops' pitch is too small to be seen at the drawing's scale (a span of
//! hundreds of loops, seen whole), the loops would merge into a solid band: the span is
//! clustered instead, drawn over the path as one band with a label giving its loops and
//! pitch; zoomed in far enough to separate them, the loops themselves are drawn.

use super::display_units::{length_label, LengthUnit};
use super::frame::Frame;
use super::labels::REGION_FONT;
use super::palette;
use super::scene::{Scene, TrochoidMark};
use super::svg::{Anchor, Attrs, Svg};
use super::ticks::value_label;

/// Narrowest trochoid band, px.
pub const MIN_TROCHOID_BAND_PX: f64 = 3.0;
/// Smallest pitch of loops drawn one by one, px: below, the span is clustered.
pub const MIN_LOOP_PITCH_PX: f64 = 3.0;
/// Opacity of a clustered span, which hides the loops under it.
const CLUSTER_OPACITY: f64 = 0.85;
/// Width of the white halo around a span's label, size units.
const LABEL_HALO: f64 = 3.0;
/// Shortest clustered span that gets a label, px.
const MIN_LABELLED_SPAN_PX: f64 = 40.0;

/// `true` when the loops of `mark` are too close together to be seen at `frame`'s scale
/// in the drawing of path `drawn` (the path that makes them).
pub fn clustered(mark: &TrochoidMark, frame: &Frame, drawn: Option<&str>) -> bool {
    let of_drawn = mark.path.is_none() || mark.path.as_deref() == drawn;
    of_drawn && mark.pitch_mm.is_some_and(|p| frame.len_px(p) < MIN_LOOP_PITCH_PX)
}

/// Length of a polyline, mm.
fn polyline_mm(points: &[[f64; 2]]) -> f64 {
    points.windows(2).map(|w| (w[1][0] - w[0][0]).hypot(w[1][1] - w[0][1])).sum()
}

/// The point half way along a polyline.
fn midpoint(points: &[[f64; 2]]) -> [f64; 2] {
    let mut left = polyline_mm(points) / 2.0;
    for w in points.windows(2) {
        let step = (w[1][0] - w[0][0]).hypot(w[1][1] - w[0][1]);
        if step >= left && step > 0.0 {
            let t = left / step;
            return [w[0][0] + t * (w[1][0] - w[0][0]), w[0][1] + t * (w[1][1] - w[0][1])];
        }
        left -= step;
    }
    points[points.len() / 2]
}

/// Draws the spans that are (`dense`) or are not clustered at `frame`'s scale; returns
/// whether any was drawn. The open ones go under the path, the clustered ones over it;
/// a clustered span's label gives its pitch in `unit`.
pub fn draw_trochoids(
    svg: &mut Svg,
    scene: &Scene,
    frame: &Frame,
    k: f64,
    (dense, drawn, unit): (bool, Option<&str>, LengthUnit),
    layer_ok: &dyn Fn(Option<usize>) -> bool,
) -> bool {
    let mut any = false;
    let marks = scene.trochoids.iter().filter(|m| layer_ok(m.layer) && !m.points.is_empty());
    for mark in marks.filter(|m| clustered(m, frame, drawn) == dense) {
        let mut attrs = Attrs::new()
            .class(if dense { "trochoid clustered" } else { "trochoid" })
            .show("data-loop-radius", value_label(mark.loop_radius_mm));
        if let Some(pitch) = mark.pitch_mm {
            attrs = attrs.show("data-pitch", value_label(pitch));
        }
        let opacity = if dense { CLUSTER_OPACITY } else { palette::TROCHOID_OPACITY };
        svg.polyline(
            mark.points.iter().map(|p| frame.px(*p)),
            attrs
                .str("fill", "none")
                .show("stroke", palette::TROCHOID)
                .num("stroke-opacity", opacity)
                .num("stroke-width", frame.len_px(2.0 * mark.loop_radius_mm).max(MIN_TROCHOID_BAND_PX))
                .str("stroke-linecap", "round")
                .str("stroke-linejoin", "round"),
        );
        let length_mm = polyline_mm(&mark.points);
        if let (true, Some(pitch)) = (dense && frame.len_px(length_mm) >= MIN_LABELLED_SPAN_PX, mark.pitch_mm) {
            let loops = (length_mm / pitch).round();
            let text = format!("≈{} loops, pitch {}", value_label(loops), length_label(pitch, unit));
            let (x, y) = frame.px(midpoint(&mark.points));
            let font = REGION_FONT * k;
            // A white halo keeps the label readable over the band and the path.
            let halo = Attrs::new().class("trochoid-label").str("paint-order", "stroke").str("stroke", "#ffffff");
            svg.text((x, y + font * 0.35), font, Anchor::Middle, &text, halo.num("stroke-width", LABEL_HALO * k));
        }
        any = true;
    }
    any
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::core::drawing::frame::Extent;

    fn mark(pitch_mm: Option<f64>) -> TrochoidMark {
        let path = Some("planned".to_string());
        TrochoidMark { layer: None, points: vec![[0.0, 0.0], [100.0, 0.0]], loop_radius_mm: 2.0, pitch_mm, path }
    }

    fn frame(px_per_mm: f64) -> Frame {
        let extent = Extent { x_min: 0.0, y_min: 0.0, x_max: 100.0, y_max: 100.0 };
        Frame::fit(extent, (0.0, 0.0), 100.0 * px_per_mm, 100.0 * px_per_mm)
    }

    #[test]
    fn loops_closer_than_three_px_are_clustered_and_separate_once_zoomed_in() {
        let planned = Some("planned");
        assert!(clustered(&mark(Some(0.5)), &frame(2.0), planned), "0.5 mm at 2 px/mm is 1 px");
        assert!(!clustered(&mark(Some(0.5)), &frame(10.0), planned), "at 10 px/mm it is 5 px");
        assert!(!clustered(&mark(None), &frame(0.1), planned), "a span without a pitch is never clustered");
        assert!(!clustered(&mark(Some(0.5)), &frame(2.0), Some("base")), "the base path shows the spans under it");
    }

    #[test]
    fn a_clustered_span_is_drawn_over_the_path_with_its_loops_and_pitch() {
        let scene = Scene { trochoids: vec![mark(Some(0.5))], ..Scene::default() };
        let mut svg = Svg::fragment();
        let planned = Some("planned");
        assert!(!draw_trochoids(&mut svg, &scene, &frame(2.0), 1.0, (false, planned, LengthUnit::Mm), &|_| true));
        assert!(draw_trochoids(&mut svg, &scene, &frame(2.0), 1.0, (true, planned, LengthUnit::Mm), &|_| true));
        let out = svg.finish_fragment();
        assert!(out.contains("class=\"trochoid clustered\"") && out.contains("≈200 loops, pitch 0.5 mm"), "{out}");
    }
}
