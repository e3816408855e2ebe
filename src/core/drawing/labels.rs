//! The labels of the critical regions of a plan view: "α 112° · N120–N180" beside the
//! middle of each region, the highest α first. Where regions are dense their labels would
//! overlap: a region whose label would overlap one already placed joins that label's
//! cluster, which then says how many more regions it covers and spans their lines
//! ("α 180° · N12–N96 · +3 more"), so no region goes unmentioned and no labels collide.
//! Zoomed in (a window), the regions separate and each gets its own label again.

use super::frame::Frame;
use super::palette;
use super::scene::{RegionMark, Scene};
use super::svg::{text_width, Anchor, Attrs, Svg};
use super::ticks::value_label;

/// Labels drawn at most (clusters of the highest α first); the other regions join the
/// nearest label's cluster.
pub const MAX_REGION_LABELS: usize = 12;
/// Font of region labels, in size units.
pub const REGION_FONT: f64 = 11.0;

/// A label placed: its region, its box (px), and the regions it also stands for.
struct Cluster {
    lead: usize,
    anchor: (f64, f64),
    bounds: (f64, f64, f64, f64),
    members: Vec<usize>,
}

fn text_of(r: &RegionMark, members: &[&RegionMark]) -> String {
    let from = members.iter().map(|m| m.start_line).chain([r.start_line]).min().unwrap_or(r.start_line);
    let to = members.iter().map(|m| m.end_line).chain([r.end_line]).max().unwrap_or(r.end_line);
    let more = if members.is_empty() { String::new() } else { format!(" · +{} more", members.len()) };
    format!("α {}° · N{from}–N{to}{more}", value_label(r.max_alpha_deg))
}

/// Draws the labels of `regions` (indices into `scene.regions`), clustered where dense.
pub fn draw_region_labels(svg: &mut Svg, scene: &Scene, regions: &[usize], frame: &Frame, k: f64, band: f64) {
    let mut order: Vec<usize> = regions.iter().copied().filter(|&i| !scene.regions[i].points.is_empty()).collect();
    order.sort_by(|&a, &b| scene.regions[b].max_alpha_deg.total_cmp(&scene.regions[a].max_alpha_deg).then(a.cmp(&b)));
    let font = REGION_FONT * k;
    // A label that would leave the drawing on the right goes left of its region instead.
    let e = frame.extent();
    let right = frame.px([e.x_max, e.y_max]).0;
    let mut clusters: Vec<Cluster> = Vec::new();
    for &i in &order {
        let r = &scene.regions[i];
        let (x, y) = frame.px(r.points[r.points.len() / 2]);
        // Room for a cluster's "+n more" too, so that the label stays inside once grown.
        let w = text_width(&format!("{} · +99 more", text_of(r, &[])), font);
        let mut lx = x + band / 2.0 + 2.0 * k;
        if lx + w > right {
            lx = (x - band / 2.0 - 2.0 * k - w).max(0.0);
        }
        let ly = y - band / 2.0 - 2.0 * k;
        let bx = (lx - 2.0 * k, ly - font, lx + w + 2.0 * k, ly + 0.3 * font);
        let overlapping = clusters
            .iter()
            .position(|p| bx.0 < p.bounds.2 && p.bounds.0 < bx.2 && bx.1 < p.bounds.3 && p.bounds.1 < bx.3);
        let joined = match overlapping {
            Some(c) => Some(c),
            // Past the most labels, a region joins the nearest cluster.
            None if clusters.len() >= MAX_REGION_LABELS => (0..clusters.len()).min_by(|&a, &b| {
                let d = |c: &Cluster| (c.anchor.0 - x).hypot(c.anchor.1 - y);
                d(&clusters[a]).total_cmp(&d(&clusters[b]))
            }),
            None => None,
        };
        match joined {
            Some(c) => clusters[c].members.push(i),
            None => clusters.push(Cluster { lead: i, anchor: (lx, ly), bounds: bx, members: Vec::new() }),
        }
    }
    for c in &clusters {
        let r = &scene.regions[c.lead];
        let members: Vec<&RegionMark> = c.members.iter().map(|&m| &scene.regions[m]).collect();
        let text = text_of(r, &members);
        let w = text_width(&text, font);
        let (lx, ly) = c.anchor;
        let lines = format!("{}-{}", r.start_line, r.end_line);
        let mut attrs = Attrs::new().class("region-label").str("data-kind", &r.kind).str("data-lines", &lines);
        if !members.is_empty() {
            attrs = attrs.show("data-cluster", members.len() + 1);
        }
        svg.group(attrs);
        svg.rect(
            lx - 2.0 * k,
            ly - font,
            w + 4.0 * k,
            font * 1.3,
            Attrs::new()
                .str("fill", "#ffffff")
                .num("fill-opacity", 0.8)
                .show("stroke", palette::REGION)
                .num("stroke-width", 0.6 * k),
        );
        svg.text((lx, ly), font, Anchor::Start, &text, Attrs::new().show("fill", palette::REGION));
        svg.end_group();
    }
}
