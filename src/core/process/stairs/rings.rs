//! Closed iso-lines of a field over a grid (marching squares, the `contour` crate's port of
//! d3-contour, with linear interpolation between cell centres), as the rings a tool follows:
//! each keeps the region where the field is at or above the threshold on its left (outer
//! rings counter-clockwise, holes clockwise: climb milling with the material outside, as
//! [`crate::core::pocketing`] cuts), with the points a straight line would add dropped.

use crate::core::geometry::Point;
use crate::core::medial::douglas_peucker;
use crate::core::stock::Grid;
use contour::ContourBuilder;

/// Points closer than this to the line through their neighbours are dropped, mm
/// (**assumed**: a hundredth of a millimetre, far below an intermediate roughing's
/// allowance and the ball's scallop).
pub const RING_TOLERANCE_MM: f64 = 0.01;

/// A closed ring, its last point joined to its first.
pub type Ring = Vec<Point>;

/// The rings where `values` (one per cell of `grid`) crosses `threshold`.
pub fn rings(grid: &Grid, values: &[f64], threshold: f64) -> Vec<Ring> {
    let builder = ContourBuilder::new(grid.nx, grid.ny, true)
        .x_origin(grid.x0_mm)
        .y_origin(grid.y0_mm)
        .x_step(grid.cell_mm)
        .y_step(grid.cell_mm);
    let Ok(contours) = builder.contours(values, &[threshold]) else {
        return Vec::new();
    };
    let mut out = Vec::new();
    for contour in contours {
        for polygon in contour.geometry() {
            let exterior = polygon.exterior().0.iter().map(|c| Point::new(c.x, c.y)).collect();
            out.extend(oriented(exterior, true));
            for hole in polygon.interiors() {
                out.extend(oriented(hole.0.iter().map(|c| Point::new(c.x, c.y)).collect(), false));
            }
        }
    }
    out
}

/// The ring through `points`, simplified, counter-clockwise for an outer ring and clockwise
/// for a hole; `None` when nothing of it is left.
fn oriented(mut points: Vec<Point>, outer: bool) -> Option<Ring> {
    if points.len() > 1 && points.first() == points.last() {
        points.pop();
    }
    let mut ring = simplified(&points, RING_TOLERANCE_MM);
    if ring.len() < 3 {
        return None;
    }
    if (signed_area_mm2(&ring) > 0.0) != outer {
        ring.reverse();
    }
    Some(ring)
}

/// The ring's signed area, mm² (positive counter-clockwise).
pub fn signed_area_mm2(ring: &[Point]) -> f64 {
    let n = ring.len();
    (0..n).map(|i| ring[i].x * ring[(i + 1) % n].y - ring[(i + 1) % n].x * ring[i].y).sum::<f64>() / 2.0
}

/// The closed ring `points` with every point that lies within `tolerance_mm` of the chord
/// between the points kept around it dropped (Douglas–Peucker on its two halves, from its
/// first point to the point farthest from it and back).
fn simplified(points: &[Point], tolerance_mm: f64) -> Ring {
    if points.len() < 4 {
        return points.to_vec();
    }
    let far = (1..points.len())
        .max_by(|&a, &b| points[0].distance_mm(points[a]).total_cmp(&points[0].distance_mm(points[b])))
        .unwrap_or(1);
    let closed: Vec<Point> = points.iter().copied().chain(std::iter::once(points[0])).collect();
    // Positions alone: no clearance along the ring.
    let flat = vec![0.0; closed.len()];
    let head = douglas_peucker(&closed[..=far], &flat[..=far], tolerance_mm);
    let tail = douglas_peucker(&closed[far..], &flat[far..], tolerance_mm);
    // The tail's first index is `far` (kept by the head) and its last the ring's first again.
    let kept = head.into_iter().chain(tail.into_iter().skip(1).map(|i| i + far)).filter(|&i| i < points.len());
    kept.map(|i| points[i]).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn grid(n: usize, cell_mm: f64) -> Grid {
        Grid { x0_mm: 0.0, y0_mm: 0.0, cell_mm, nx: n, ny: n }
    }

    /// A cone: the field is the distance to the centre of the grid.
    fn cone(g: &Grid, centre: f64) -> Vec<f64> {
        (0..g.cells())
            .map(|c| {
                let (x, y) = ((c % g.nx) as f64 + 0.5, (c / g.nx) as f64 + 0.5);
                ((x * g.cell_mm - centre).powi(2) + (y * g.cell_mm - centre).powi(2)).sqrt()
            })
            .collect()
    }

    #[test]
    fn a_level_of_a_cone_is_one_counter_clockwise_circle_at_its_radius() {
        let g = grid(80, 0.25);
        // The region at or above the threshold is a disc: the field is minus the distance.
        let field: Vec<f64> = cone(&g, 10.0).iter().map(|d| -d).collect();
        let found = rings(&g, &field, -6.0);
        assert_eq!(found.len(), 1);
        let ring = &found[0];
        assert!(signed_area_mm2(ring) > 0.0, "counter-clockwise");
        for p in ring {
            let r = ((p.x - 10.0).powi(2) + (p.y - 10.0).powi(2)).sqrt();
            assert!((r - 6.0).abs() < 0.02, "a point at {r} mm from the centre");
        }
        let area = signed_area_mm2(ring);
        assert!((area / (std::f64::consts::PI * 36.0) - 1.0).abs() < 0.01, "{area}");
    }

    #[test]
    fn a_ring_around_a_hole_runs_clockwise() {
        let g = grid(80, 0.25);
        // At or above the threshold: farther than 4 mm from the centre.
        let found = rings(&g, &cone(&g, 10.0), 4.0);
        let holes: Vec<&Ring> = found.iter().filter(|r| signed_area_mm2(r) < 0.0).collect();
        assert_eq!(holes.len(), 1, "{} rings", found.len());
        assert!((signed_area_mm2(holes[0]) + std::f64::consts::PI * 16.0).abs() < 0.6);
    }

    #[test]
    fn straight_stretches_keep_only_their_corners() {
        let square: Vec<Point> = (0..40)
            .map(|i| {
                let t = f64::from(i) / 10.0;
                match i / 10 {
                    0 => Point::new(t * 10.0, 0.0),
                    1 => Point::new(10.0, (t - 1.0) * 10.0),
                    2 => Point::new(10.0 - (t - 2.0) * 10.0, 10.0),
                    _ => Point::new(0.0, 10.0 - (t - 3.0) * 10.0),
                }
            })
            .collect();
        let kept = simplified(&square, RING_TOLERANCE_MM);
        assert_eq!(kept.len(), 4, "{kept:?}");
    }
}
