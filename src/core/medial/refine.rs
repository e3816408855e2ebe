//! Moving the Voronoi vertices onto the true medial axis, and their contacts with the boundary.
//!
//! A circumcentre of boundary samples is equidistant from the samples, not from the lines and
//! arcs between them: it lies off the true axis by about `h²/(16·R)` (sampling step `h`, e.g.
//! 0.6 % of `h` on the L-shape at h = 1 mm). Each point of the axis is therefore moved, by Newton's
//! method, to where its two nearest contacts (three at a junction) are equally far: the
//! definition of the medial axis (seed 004 §2.1: centres of maximal inscribed circles touching
//! the boundary at two or more points).

use super::boundary::Boundary;
use crate::core::geometry::Point;

/// At most this many Newton steps per point.
const MAX_NEWTON_STEPS: usize = 12;

/// Newton stops once the contacts' distances differ by less than this (mm).
const EQUIDISTANCE_TOL_MM: f64 = 1e-10;

/// Two contacts whose directions from the point differ by less than this touch the same side
/// (e.g. a line and the arc continuing it tangentially): they do not pin the point (rad).
const MIN_CONTACT_ANGLE_RAD: f64 = 1.0 * std::f64::consts::PI / 180.0;

/// Below this determinant the three contacts of a junction do not fix a point (two of them
/// face the same way) and only the nearest two are made equidistant.
const MIN_JUNCTION_DET: f64 = 1e-6;

/// One contact of a point with the boundary.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Contact {
    /// Where it touches (mm).
    pub point: Point,
    /// Its distance from the point (mm).
    pub distance_mm: f64,
}

/// The contacts of `p` with its generating segments ([`Boundary::contact`]), nearest first;
/// a contact seen from `p` within [`MIN_CONTACT_ANGLE_RAD`] of a nearer one touches the same
/// side (a vertex reached from both its segments, a line and its tangent arc) and is dropped.
pub(crate) fn contacts(boundary: &Boundary, generators: &[usize], p: Point) -> Vec<Contact> {
    let mut all: Vec<Contact> = generators
        .iter()
        .filter_map(|&s| boundary.contact(s, p))
        .map(|point| Contact { point, distance_mm: point.distance_mm(p) })
        .filter(|c| c.distance_mm > 0.0)
        .collect();
    all.sort_by(|a, b| a.distance_mm.total_cmp(&b.distance_mm));
    let min_cos = MIN_CONTACT_ANGLE_RAD.cos();
    let mut kept: Vec<Contact> = Vec::with_capacity(all.len());
    for c in all {
        let (u, v) = (p.vector_to(c.point), c.distance_mm);
        let same_side = kept.iter().any(|k| {
            let w = p.vector_to(k.point);
            (u.0 * w.0 + u.1 * w.1) / (v * k.distance_mm) > min_cos
        });
        if !same_side {
            kept.push(c);
        }
    }
    kept
}

/// `p` moved to where its nearest `wanted` contacts (2, or 3 at a junction) are equally far,
/// by at most `max_move_mm`; `p` itself when that fails (fewer contacts, or too far a move)
/// or when `inside` refuses the result.
pub(crate) fn refine(
    boundary: &Boundary,
    generators: &[usize],
    p: Point,
    wanted: usize,
    max_move_mm: f64,
    inside: impl Fn(Point) -> bool,
) -> Point {
    let mut q = p;
    for _ in 0..MAX_NEWTON_STEPS {
        let c = contacts(boundary, generators, q);
        if c.len() < 2 {
            return p;
        }
        let unit = |k: usize| {
            let (dx, dy) = c[k].point.vector_to(q);
            (dx / c[k].distance_mm, dy / c[k].distance_mm)
        };
        let u0 = unit(0);
        let row = |k: usize| {
            let u = unit(k);
            ((u0.0 - u.0, u0.1 - u.1), c[0].distance_mm - c[k].distance_mm)
        };
        let (g1, f1) = row(1);
        let mut spread = f1.abs();
        let mut step = None;
        if wanted >= 3 && c.len() >= 3 {
            let (g2, f2) = row(2);
            spread = spread.max(f2.abs());
            let det = g1.0 * g2.1 - g1.1 * g2.0;
            if det.abs() >= MIN_JUNCTION_DET {
                step = Some(((-f1 * g2.1 + f2 * g1.1) / det, (-f2 * g1.0 + f1 * g2.0) / det));
            }
        }
        if spread <= EQUIDISTANCE_TOL_MM {
            break;
        }
        let norm2 = g1.0 * g1.0 + g1.1 * g1.1;
        let (dx, dy) = step.unwrap_or((-f1 * g1.0 / norm2, -f1 * g1.1 / norm2));
        q = q.offset(dx, dy);
        if q.distance_mm(p) > max_move_mm {
            return p;
        }
    }
    if inside(q) {
        q
    } else {
        p
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::core::geometry::{Loop, Pocket, Vertex};

    /// Tolerance of converged results (mm).
    const TOL_MM: f64 = 1e-9;

    fn l_boundary() -> Boundary {
        let l = Loop::new(
            [(0.0, 0.0), (60.0, 0.0), (60.0, 20.0), (20.0, 20.0), (20.0, 60.0), (0.0, 60.0)]
                .iter()
                .map(|&(x, y)| Vertex::new(x, y, 0.0))
                .collect(),
        );
        Boundary::of_pocket(&Pocket::new(l, vec![]).unwrap())
    }

    #[test]
    fn a_point_near_the_reflex_corner_moves_onto_the_parabola() {
        // Equidistant from y = 0 and the reflex vertex (20, 20): y = 10 + (x − 20)²/40.
        let b = l_boundary();
        let q = refine(&b, &[0, 2, 3], Point::new(15.0, 10.0), 2, 1.0, |_| true);
        let c = contacts(&b, &[0, 2, 3], q);
        assert_eq!(c.len(), 2);
        assert!((c[0].distance_mm - c[1].distance_mm).abs() < TOL_MM);
        // Newton moves across the axis, so x stays close to 15.
        assert!((q.y - (10.0 + (q.x - 20.0).powi(2) / 40.0)).abs() < TOL_MM);
    }

    #[test]
    fn a_junction_moves_to_the_point_equidistant_from_three_sides() {
        // The junction of the L's leg end: equidistant from y = 0, x = 60 and y = 20.
        let b = l_boundary();
        let q = refine(&b, &[0, 1, 2], Point::new(49.9, 10.05), 3, 1.0, |_| true);
        assert!(q.near(Point::new(50.0, 10.0), TOL_MM));
    }

    #[test]
    fn a_point_that_would_leave_the_pocket_or_move_too_far_stays() {
        let b = l_boundary();
        let p = Point::new(15.0, 10.0);
        assert!(refine(&b, &[0, 2, 3], p, 2, 1.0, |_| false).near(p, 0.0));
        assert!(refine(&b, &[0, 2, 3], p, 2, 1e-3, |_| true).near(p, 0.0));
    }
}
