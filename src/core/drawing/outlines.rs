//! Outlines of a scene: pocket boundaries, islands and stock regions as polygons, their
//! arcs divided finely enough to look round.

use super::scene::{Outline, OutlineRole};
use crate::core::analysis::StockRegion;
use crate::core::geometry::{Loop, Pocket};

/// Largest angle one chord of an outline's arc spans, rad (5°: a 10 mm circle is 72
/// chords, off by 0.01 mm at most).
pub const OUTLINE_CHORD_RAD: f64 = 5.0 * std::f64::consts::PI / 180.0;

/// The loop as a polygon, arcs divided into chords of at most [`OUTLINE_CHORD_RAD`].
pub fn loop_polygon(contour: &Loop) -> Vec<[f64; 2]> {
    let mut points = Vec::new();
    for segment in contour.segments() {
        let n =
            if segment.is_arc() { (segment.sweep_rad().abs() / OUTLINE_CHORD_RAD).ceil().max(1.0) as usize } else { 1 };
        for k in 0..n {
            let p = segment.point_at(k as f64 / n as f64);
            points.push([p.x, p.y]);
        }
    }
    points
}

/// A pocket's boundary and islands.
pub fn pocket_outlines(pocket: &Pocket) -> Vec<Outline> {
    let mut out = vec![Outline { role: OutlineRole::Pocket, points: loop_polygon(&pocket.outer) }];
    out.extend(pocket.islands.iter().map(|i| Outline { role: OutlineRole::Island, points: loop_polygon(i) }));
    out
}

/// A stock region as outlines of `role` (a pocket-shaped region keeps its islands).
pub fn region_outlines(region: &StockRegion, role: OutlineRole) -> Vec<Outline> {
    match region {
        StockRegion::Rect(r) => vec![Outline {
            role,
            points: vec![[r.x_min, r.y_min], [r.x_max, r.y_min], [r.x_max, r.y_max], [r.x_min, r.y_max]],
        }],
        StockRegion::Circle { cx, cy, r } => {
            vec![Outline { role, points: loop_polygon(&Loop::circle(*cx, *cy, *r)) }]
        }
        StockRegion::Pocket(p) => {
            let mut out = vec![Outline { role, points: loop_polygon(&p.outer) }];
            out.extend(p.islands.iter().map(|i| Outline { role: OutlineRole::Island, points: loop_polygon(i) }));
            out
        }
    }
}

/// The stock (material at the start) and the regions already open.
pub fn stock_outlines(stock: &[StockRegion], open: &[StockRegion]) -> Vec<Outline> {
    let mut out: Vec<Outline> = stock.iter().flat_map(|r| region_outlines(r, OutlineRole::Stock)).collect();
    out.extend(open.iter().flat_map(|r| region_outlines(r, OutlineRole::Open)));
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_circle_becomes_a_polygon_whose_vertices_lie_on_it() {
        let points = loop_polygon(&Loop::circle(1.0, 2.0, 5.0));
        assert_eq!(points.len(), 72);
        for p in points {
            assert!(((p[0] - 1.0).hypot(p[1] - 2.0) - 5.0).abs() < 1e-9);
        }
    }

    #[test]
    fn a_rectangle_keeps_its_four_corners() {
        assert_eq!(loop_polygon(&Loop::rectangle(0.0, 0.0, 3.0, 2.0)).len(), 4);
    }
}
