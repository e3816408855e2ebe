//! The plan view of a job as SVG: outlines, one tool path coloured by a quantity, rapids,
//! the medial axis, critical regions, trochoid spans, a legend, a scale bar and a title.
//!
//! Elements carry a `class` (`outline`, `feed`, `rapid`, `medial`, `region`,
//! `region-label`, `trochoid`, `legend-…`, `scale-bar`, `title`) and `data-` attributes
//! (bin, class, kind, lines, …) for the web page and the tests.

use super::display_units::{caption_in, layer_name};
use super::draw_options::resolve;
pub use super::draw_options::{DrawError, DrawOptions, DEFAULT_WIDTH_PX, MAX_WIDTH_PX, MIN_WIDTH_PX};
use super::frame::{Extent, Frame};
use super::frame_axes::draw_frame_axes;
use super::labels::draw_region_labels;
use super::legend::{draw_entries, draw_ramp, draw_scale_bar, Entry, Swatch, LEGEND_FONT};
use super::palette::{self, quantity_bin_color, Rgb, ValueScale};
use super::scene::{MedialClass, OutlineRole, Quantity, Run, Scene, ScenePath};
use super::svg::{text_width, Anchor, Attrs, PathData, Svg};
use super::ticks::value_label;
use super::trochoid_marks::draw_trochoids;
use std::collections::BTreeMap;

/// Size unit: fonts and strokes scale with the width relative to this, px.
const REFERENCE_WIDTH_PX: f64 = 1000.0;
/// Bounds of the size unit: never below 1, so that text keeps its size on a narrow
/// drawing (a phone) and stays readable.
const MIN_UNIT: f64 = 1.0;
const MAX_UNIT: f64 = 2.5;
/// Margin around everything, in size units.
const MARGIN: f64 = 16.0;
/// Smallest title font, as a share of [`TITLE_FONT`], a long title is shrunk to.
const MIN_TITLE_SHRINK: f64 = 0.6;
/// Title font and subtitle font, in size units.
const TITLE_FONT: f64 = 16.0;
const SUBTITLE_FONT: f64 = 12.0;
/// Padding of the scene's extent, as a fraction of its larger side.
const EXTENT_PADDING: f64 = 0.03;
/// The drawing area is at most this many times as high as it is wide.
const MAX_ASPECT: f64 = 1.5;
/// Stroke widths, in size units.
const OUTLINE_STROKE: f64 = 1.2;
const FEED_STROKE: f64 = 2.0;
const RAPID_STROKE: f64 = 0.8;
const MEDIAL_STROKE: f64 = 1.0;
/// Width of a region band without a known tool, and its bounds, in size units.
const REGION_BAND: f64 = 9.0;
const MIN_REGION_BAND: f64 = 6.0;
const MAX_REGION_BAND: f64 = 24.0;
/// The colour ramp's share of the inner width.
const RAMP_FRACTION: f64 = 0.45;

/// Renders the plan view of `scene` as an SVG document.
pub fn render_drawing(scene: &Scene, options: &DrawOptions) -> Result<String, DrawError> {
    let resolved = resolve(scene, options)?;
    let width = f64::from(options.width_px);
    let k = (width / REFERENCE_WIDTH_PX).clamp(MIN_UNIT, MAX_UNIT);
    let margin = MARGIN * k;
    let layer_ok = |l: Option<usize>| resolved.layer.is_none() || l.is_none() || l == resolved.layer;
    let run_ok = |r: &Run| resolved.layer.is_none() || r.layer == resolved.layer;

    let extent = options.window.unwrap_or_else(|| scene_extent(scene));
    let title_bottom = margin + (TITLE_FONT + SUBTITLE_FONT * 1.6) * k;
    let inner = width - 2.0 * margin;
    let frame = Frame::fit(extent, (margin, title_bottom + margin * 0.5), inner, inner * MAX_ASPECT);
    let legend_top = title_bottom + margin * 0.5 + frame.height_px + margin;
    // The document's height is known only once the legend is laid out: the body and
    // the legend are drawn as fragments first.
    let layer_name = match resolved.layer {
        Some(l) => layer_name(&scene.layers[l], options.unit),
        None => "all layers".into(),
    };
    let path_name = resolved.path.map_or("no path", |p| p.name.as_str());
    let heading = [scene.title.as_str(), path_name, layer_name.as_str()]
        .iter()
        .filter(|s| !s.is_empty())
        .copied()
        .collect::<Vec<_>>()
        .join(" — ");
    let scale = resolved.path.and(resolved.color_by).map(|q| value_scale(scene, q));

    let mut body = Svg::fragment();
    let mut entries: Vec<Entry> = draw_outlines(&mut body, scene, &frame, k);
    if options.medial {
        let classes = draw_medial(&mut body, scene, &frame, k, &layer_ok);
        for class in classes {
            entries.push(Entry {
                class: "legend-medial",
                swatch: Swatch::Line { color: palette::medial_color(class), width: MEDIAL_STROKE * 2.0, dashed: false },
                label: format!("medial axis, class {}", medial_letter(class)),
            });
        }
    }
    let drawn = resolved.path.map(|p| p.name.as_str());
    if options.trochoids && draw_trochoids(&mut body, scene, &frame, k, (false, drawn, options.unit), &layer_ok) {
        entries.push(Entry {
            class: "legend-trochoid",
            swatch: Swatch::Band { color: palette::TROCHOID, opacity: palette::TROCHOID_OPACITY },
            label: "trochoid span (2ρ)".into(),
        });
    }
    let regions: Vec<usize> = match resolved.path {
        Some(p) if options.regions => (0..scene.regions.len())
            .filter(|&i| scene.regions[i].path == p.name && layer_ok(scene.regions[i].layer))
            .collect(),
        _ => Vec::new(),
    };
    let band = scene
        .tool_diameter_mm
        .map_or(REGION_BAND * k, |d| frame.len_px(d).clamp(MIN_REGION_BAND * k, MAX_REGION_BAND * k));
    for &i in &regions {
        let r = &scene.regions[i];
        body.polyline(
            r.points.iter().map(|p| frame.px(*p)),
            Attrs::new()
                .class("region")
                .str("data-kind", &r.kind)
                .show("data-max-alpha", value_label(r.max_alpha_deg))
                .str("data-lines", &format!("{}-{}", r.start_line, r.end_line))
                .str("fill", "none")
                .show("stroke", palette::REGION)
                .num("stroke-opacity", palette::REGION_OPACITY)
                .num("stroke-width", band)
                .str("stroke-linecap", "round")
                .str("stroke-linejoin", "round"),
        );
    }
    if !regions.is_empty() {
        entries.push(Entry {
            class: "legend-region",
            swatch: Swatch::Band { color: palette::REGION, opacity: palette::REGION_OPACITY },
            label: "critical region (α above the limit)".into(),
        });
    }
    if let Some(path) = resolved.path {
        if options.rapids && draw_rapids(&mut body, path, &frame, k, &run_ok) {
            entries.insert(
                0,
                Entry {
                    class: "legend-rapid",
                    swatch: Swatch::Line { color: palette::RAPID, width: RAPID_STROKE * 1.5, dashed: true },
                    label: "rapid".into(),
                },
            );
        }
        let no_value = draw_feed(&mut body, path, resolved.color_by.zip(scale), &frame, k, &run_ok);
        if no_value {
            entries.push(Entry {
                class: "legend-no-value",
                swatch: Swatch::Line { color: palette::NO_VALUE, width: FEED_STROKE * 2.0, dashed: false },
                label: "no value".into(),
            });
        }
    }
    // Spans whose loops are too dense to see at this scale, over the path.
    if options.trochoids && draw_trochoids(&mut body, scene, &frame, k, (true, drawn, options.unit), &layer_ok) {
        entries.push(Entry {
            class: "legend-trochoid-clustered",
            swatch: Swatch::Band { color: palette::TROCHOID, opacity: 1.0 },
            label: "trochoid loops too dense to draw at this scale (zoom in)".into(),
        });
    }
    draw_region_labels(&mut body, scene, &regions, &frame, k, band);
    draw_frame_axes(&mut body, &frame, options.unit, k);

    // Legend: the ramp and the scale bar side by side, the entries below.
    let mut legend = Svg::fragment();
    let mut bottom = legend_top;
    if let (Some(q), Some(scale)) = (resolved.color_by, scale) {
        bottom = draw_ramp(&mut legend, (margin, legend_top), inner * RAMP_FRACTION, k, (&scale, q), options.unit);
    }
    let bar_y = legend_top + LEGEND_FONT * k * 3.0;
    draw_scale_bar(&mut legend, (width - margin, bar_y), frame.scale, inner, k, options.unit);
    bottom = bottom.max(bar_y + LEGEND_FONT * k);
    bottom = draw_entries(&mut legend, &entries, (margin, bottom + margin * 0.5), width - margin, k);
    let height = bottom + margin;

    let mut svg = Svg::new(width, height, &heading, "dieplan-drawing");
    svg.rect(0.0, 0.0, width, height, Attrs::new().class("background").str("fill", "#ffffff"));
    // The scene's title on the first line, its font shrunk (down to a floor) to fit the
    // width; the path, layer and quantity on the second.
    let title_font = (inner / text_width(&scene.title, 1.0)).min(TITLE_FONT * k).max(MIN_TITLE_SHRINK * TITLE_FONT * k);
    svg.text((margin, margin + TITLE_FONT * k), title_font, Anchor::Start, &scene.title, Attrs::new().class("title"));
    let coloured = match resolved.color_by {
        Some(q) => format!("coloured by {}", caption_in(q.caption(), options.unit)),
        None => "no values to colour by".into(),
    };
    let subtitle = format!("{path_name} — {layer_name} — {coloured}");
    let sub_y = margin + (TITLE_FONT + SUBTITLE_FONT * 1.4) * k;
    svg.text((margin, sub_y), SUBTITLE_FONT * k, Anchor::Start, &subtitle, Attrs::new().class("subtitle"));
    draw_frame(&mut svg, &frame, options.window.is_some());
    svg.insert(&body.finish_fragment());
    svg.end_group();
    svg.insert(&legend.finish_fragment());
    Ok(svg.finish())
}

/// Opens the drawing area: a `frame` element telling the page how mm map onto px
/// (`px = left + (x − x_min)·scale`, `py = top + (y_max − y)·scale`) and, for a window,
/// a group clipped to the area (closed after the body).
fn draw_frame(svg: &mut Svg, frame: &Frame, windowed: bool) {
    let e = frame.extent();
    let (left, top) = frame.px([e.x_min, e.y_max]);
    let attrs = Attrs::new()
        .class("frame")
        .show("data-x-min", e.x_min)
        .show("data-y-min", e.y_min)
        .show("data-x-max", e.x_max)
        .show("data-y-max", e.y_max)
        .show("data-scale", frame.scale)
        .show("data-left", left)
        .show("data-top", top)
        .show("data-windowed", windowed);
    svg.group(attrs);
    svg.end_group();
    let mut area = Attrs::new().class("drawing-area");
    if windowed {
        svg.insert(&format!(
            "<clipPath id=\"drawing-area\"><rect x=\"{left:.2}\" y=\"{top:.2}\" width=\"{:.2}\" height=\"{:.2}\"/></clipPath>\n",
            e.width() * frame.scale,
            frame.height_px
        ));
        area = area.str("clip-path", "url(#drawing-area)");
    }
    svg.group(area);
}

/// The scene's extent: outlines, paths and the medial axis, padded.
fn scene_extent(scene: &Scene) -> Extent {
    let outlines = scene.outlines.iter().flat_map(|o| o.points.iter());
    let paths = scene.paths.iter().flat_map(|p| p.runs.iter().flat_map(|r| r.points.iter()));
    let medial = scene.medial.iter().flat_map(|m| m.points.iter());
    let e = Extent::of_points(outlines.chain(paths).chain(medial));
    let pad = e.width().max(e.height()) * EXTENT_PADDING;
    Extent { x_min: e.x_min - pad, y_min: e.y_min - pad, x_max: e.x_max + pad, y_max: e.y_max + pad }
}

/// Share of the cut length whose values set the top of a colour scale other than α's:
/// the rest, a few short outliers (the full circle at the bottom of a helical entry wears
/// a tool ten times faster than the side cutting), take the top colour instead of
/// washing the rest of the drawing into one colour.
pub const SCALE_TOP_SHARE: f64 = 0.99;

/// The colour scale of quantity `q` over every path of the scene that has it (all
/// layers and both sides of a change: the same colour is the same value in the drawing of
/// the path before and after), with the α limit when colouring by α. α's scale runs to
/// its largest value; the others to the value below which [`SCALE_TOP_SHARE`] of the
/// length lies.
pub fn value_scale(scene: &Scene, q: Quantity) -> ValueScale {
    let mut weighted: Vec<(f64, f64)> = Vec::new();
    for run in scene.paths.iter().flat_map(|p| p.runs.iter()).filter(|r| !r.rapid) {
        let Some(values) = run.values.get(&q) else { continue };
        for (k, v) in values.iter().enumerate() {
            let Some(v) = v.map(f64::from).filter(|v| v.is_finite()) else { continue };
            let length = match (k.checked_sub(1).and_then(|j| run.points.get(j)), run.points.get(k)) {
                (Some(a), Some(b)) => (b[0] - a[0]).hypot(b[1] - a[1]),
                _ => 0.0,
            };
            weighted.push((v, length));
        }
    }
    if weighted.is_empty() {
        return ValueScale { min: 0.0, max: 0.0, limit: None, top_clipped: false };
    }
    weighted.sort_by(|a, b| a.0.total_cmp(&b.0));
    let min = weighted[0].0;
    let max = weighted[weighted.len() - 1].0;
    let limit = if q == Quantity::Alpha { scene.alpha_limit_deg } else { None };
    if q == Quantity::Alpha {
        return ValueScale { min, max, limit, top_clipped: false };
    }
    let total: f64 = weighted.iter().map(|w| w.1).sum();
    let mut below = 0.0;
    let mut top = max;
    for &(v, length) in &weighted {
        below += length;
        if below >= SCALE_TOP_SHARE * total {
            top = v;
            break;
        }
    }
    let top_clipped = top < max && top > min;
    ValueScale { min, max: if top_clipped { top } else { max }, limit, top_clipped }
}

/// Draws the outlines, stock first; returns the legend entries of the roles drawn.
fn draw_outlines(svg: &mut Svg, scene: &Scene, frame: &Frame, k: f64) -> Vec<Entry> {
    const ORDER: [OutlineRole; 4] = [OutlineRole::Stock, OutlineRole::Pocket, OutlineRole::Open, OutlineRole::Island];
    let mut entries = Vec::new();
    for role in ORDER {
        if scene.outlines.iter().any(|o| o.role == role) {
            let (stroke, fill) = palette::outline_colors(role);
            entries.push(Entry {
                class: "legend-outline",
                swatch: Swatch::Area { stroke, fill, dashed: role == OutlineRole::Stock },
                label: outline_label(role).into(),
            });
        }
        for outline in scene.outlines.iter().filter(|o| o.role == role) {
            let (stroke, fill) = palette::outline_colors(role);
            let mut attrs = Attrs::new()
                .class("outline")
                .str("data-role", role_name(role))
                .show("fill", fill)
                .show("stroke", stroke)
                .num("stroke-width", OUTLINE_STROKE * k);
            if role == OutlineRole::Stock {
                attrs = attrs.str("stroke-dasharray", &format!("{:.1} {:.1}", 6.0 * k, 3.0 * k));
            }
            svg.polygon(outline.points.iter().map(|p| frame.px(*p)), attrs);
        }
    }
    entries
}

/// What an outline is, in the legend.
fn outline_label(role: OutlineRole) -> &'static str {
    match role {
        OutlineRole::Stock => "stock",
        OutlineRole::Pocket => "pocket wall",
        OutlineRole::Island => "island",
        OutlineRole::Open => "open at the start",
    }
}

fn role_name(role: OutlineRole) -> &'static str {
    match role {
        OutlineRole::Stock => "stock",
        OutlineRole::Pocket => "pocket",
        OutlineRole::Island => "island",
        OutlineRole::Open => "open",
    }
}

fn medial_letter(class: MedialClass) -> &'static str {
    match class {
        MedialClass::A => "A",
        MedialClass::B => "B",
        MedialClass::C => "C",
    }
}

/// Draws the medial axis, one element per class; returns the classes drawn.
fn draw_medial(
    svg: &mut Svg,
    scene: &Scene,
    frame: &Frame,
    k: f64,
    layer_ok: &dyn Fn(Option<usize>) -> bool,
) -> Vec<MedialClass> {
    let mut drawn = Vec::new();
    for class in [MedialClass::A, MedialClass::B, MedialClass::C] {
        let mut d = PathData::new();
        for edge in scene.medial.iter().filter(|e| e.class == class && layer_ok(e.layer) && e.points.len() >= 2) {
            subpath(&mut d, edge.points.iter().map(|p| frame.px(*p)));
        }
        if !d.is_empty() {
            svg.path(
                &d,
                Attrs::new()
                    .class("medial")
                    .str("data-class", medial_letter(class))
                    .str("fill", "none")
                    .show("stroke", palette::medial_color(class))
                    .num("stroke-width", MEDIAL_STROKE * k)
                    .str("stroke-linejoin", "round"),
            );
            drawn.push(class);
        }
    }
    drawn
}

/// Vertices closer than this to the last one drawn are left out, px: the scene keeps more
/// detail than a whole view can show (for the windows zoomed into), and a drawing never
/// needs more than its pixels.
const RENDER_DETAIL_PX: f64 = 0.25;

/// Appends a subpath through `points`, leaving out the vertices within
/// [`RENDER_DETAIL_PX`] of the last one drawn (the last vertex is always drawn).
fn subpath(d: &mut PathData, points: impl IntoIterator<Item = (f64, f64)>) {
    let mut last: Option<(f64, f64)> = None;
    let mut skipped: Option<(f64, f64)> = None;
    for p in points {
        match last {
            None => d.move_to(p),
            Some(l) if (p.0 - l.0).hypot(p.1 - l.1) < RENDER_DETAIL_PX => {
                skipped = Some(p);
                continue;
            }
            Some(_) => d.line_to(p),
        }
        last = Some(p);
        skipped = None;
    }
    if let Some(p) = skipped {
        d.line_to(p);
    }
}

/// Draws the rapid runs as one dashed element; returns whether any was drawn.
fn draw_rapids(svg: &mut Svg, path: &ScenePath, frame: &Frame, k: f64, run_ok: &dyn Fn(&Run) -> bool) -> bool {
    let mut d = PathData::new();
    for run in path.runs.iter().filter(|r| r.rapid && run_ok(r) && r.points.len() >= 2) {
        subpath(&mut d, run.points.iter().map(|p| frame.px(*p)));
    }
    if d.is_empty() {
        return false;
    }
    svg.path(
        &d,
        Attrs::new()
            .class("rapid")
            .str("fill", "none")
            .show("stroke", palette::RAPID)
            .num("stroke-width", RAPID_STROKE * k)
            .str("stroke-dasharray", &format!("{:.1} {:.1}", 4.0 * k, 3.0 * k)),
    );
    true
}

/// Draws the feed runs: consecutive segments of one colour bin as one subpath, all the
/// subpaths of a bin in one element (hotter bins on top). Returns whether some segment
/// had no value.
fn draw_feed(
    svg: &mut Svg,
    path: &ScenePath,
    coloring: Option<(Quantity, ValueScale)>,
    frame: &Frame,
    k: f64,
    run_ok: &dyn Fn(&Run) -> bool,
) -> bool {
    // Bin per segment: `None` = no value; a plain path has one bin.
    let mut by_bin: BTreeMap<Option<usize>, PathData> = BTreeMap::new();
    for run in path.runs.iter().filter(|r| !r.rapid && run_ok(r) && r.points.len() >= 2) {
        let values = coloring.and_then(|(q, _)| run.values.get(&q));
        let bin_of = |i: usize| match (coloring, values) {
            (Some((_, scale)), Some(v)) => v.get(i).copied().flatten().map(|x| scale.bin(f64::from(x))),
            (Some(_), None) => None,
            (None, _) => Some(0),
        };
        let mut start = 0;
        while start + 1 < run.points.len() {
            let bin = bin_of(start + 1);
            let mut end = start + 1;
            while end + 1 < run.points.len() && bin_of(end + 1) == bin {
                end += 1;
            }
            let d = by_bin.entry(bin).or_default();
            subpath(d, run.points[start..=end].iter().map(|p| frame.px(*p)));
            start = end;
        }
    }
    let no_value = coloring.is_some() && by_bin.contains_key(&None);
    for (bin, d) in &by_bin {
        let color: Rgb = match (coloring, bin) {
            (None, _) => palette::PLAIN_FEED,
            (Some(_), None) => palette::NO_VALUE,
            (Some((q, _)), Some(b)) => quantity_bin_color(q, *b),
        };
        let mut attrs = Attrs::new().class("feed");
        if let (Some(_), Some(b)) = (coloring, bin) {
            attrs = attrs.show("data-bin", b);
        }
        svg.path(
            d,
            attrs
                .str("fill", "none")
                .show("stroke", color)
                .num("stroke-width", FEED_STROKE * k)
                .str("stroke-linejoin", "round")
                .str("stroke-linecap", "round"),
        );
    }
    no_value
}

#[cfg(test)]
#[path = "plan_view_tests.rs"]
mod tests;
