//! Intersections of two segments (line–line, line–arc, arc–arc), touching included.

use super::point::{cross, dot, Point};
use super::segment::Segment;
use super::POINT_EPS_MM;
use crate::core::tolerance::RATIO_EPS;
use std::f64::consts::TAU;

/// One common point of two segments.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Intersection {
    /// Where the segments meet (mm).
    pub point: Point,
    /// Fraction of the first segment's length at which the point lies.
    pub t_self: f64,
    /// Fraction of the second segment's length at which the point lies.
    pub t_other: f64,
}

/// All common points of two segments.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Intersections {
    /// The isolated common points (crossings and touchings), or with `overlap` one point
    /// inside the shared part.
    pub points: Vec<Intersection>,
    /// `true` when the segments share a piece of positive length (collinear lines or arcs of
    /// one circle running over each other).
    pub overlap: bool,
}

impl Intersections {
    /// `true` when the segments have no common point.
    pub fn is_empty(&self) -> bool {
        self.points.is_empty() && !self.overlap
    }
}

impl Segment {
    /// The common points of `self` and `other`. Points within [`POINT_EPS_MM`] (plus a
    /// relative 1e-12 of the coordinates' size) of both segments count: touching is meeting.
    pub fn intersections(&self, other: &Segment) -> Intersections {
        let tol = tolerance_mm(self, other);
        let mut candidates: Vec<Point> = Vec::new();
        let mut overlap_at: Option<Point> = None;
        match (self.circle(), other.circle()) {
            (None, None) => line_line(self, other, tol, &mut candidates, &mut overlap_at),
            (Some(circle), None) => line_circle(other, circle, tol, &mut candidates),
            (None, Some(circle)) => line_circle(self, circle, tol, &mut candidates),
            (Some(a), Some(b)) => circle_circle(self, other, a, b, tol, &mut candidates, &mut overlap_at),
        }
        for q in [self.start, self.end, other.start, other.end] {
            candidates.push(q);
        }
        let mut result = Intersections::default();
        if let Some(point) = overlap_at {
            result.overlap = true;
            result.points.push(self.intersection_at(other, point));
            return result;
        }
        for q in candidates {
            let on_both = self.distance_mm(q) <= tol && other.distance_mm(q) <= tol;
            if on_both && result.points.iter().all(|i| !i.point.near(q, tol)) {
                result.points.push(self.intersection_at(other, q));
            }
        }
        result
    }

    fn intersection_at(&self, other: &Segment, point: Point) -> Intersection {
        Intersection { point, t_self: self.parameter_of(point), t_other: other.parameter_of(point) }
    }
}

/// The distance within which two points are one for this pair of segments (mm).
fn tolerance_mm(a: &Segment, b: &Segment) -> f64 {
    let mut scale: f64 = 0.0;
    for s in [a, b] {
        for p in [s.start, s.end] {
            scale = scale.max(p.x.abs()).max(p.y.abs());
        }
        if let Some((_, r)) = s.circle() {
            scale = scale.max(r);
        }
    }
    POINT_EPS_MM + RATIO_EPS * scale
}

fn line_line(a: &Segment, b: &Segment, tol: f64, out: &mut Vec<Point>, overlap: &mut Option<Point>) {
    let da = a.start.vector_to(a.end);
    let db = b.start.vector_to(b.end);
    let (la, lb) = (dot(da, da).sqrt(), dot(db, db).sqrt());
    if la <= 0.0 || lb <= 0.0 {
        return;
    }
    let denom = cross(da, db);
    if denom.abs() > RATIO_EPS * la * lb {
        let w = a.start.vector_to(b.start);
        let t = cross(w, db) / denom;
        out.push(a.start.offset(t * da.0, t * da.1));
        return;
    }
    // Parallel: collinear when b's end points lie on a's line.
    let off = |p: Point| cross(da, a.start.vector_to(p)).abs() / la;
    if off(b.start) > tol || off(b.end) > tol {
        return;
    }
    let along = |p: Point| dot(da, a.start.vector_to(p)) / la;
    let (u0, u1) = (along(b.start), along(b.end));
    let lo = u0.min(u1).max(0.0);
    let hi = u0.max(u1).min(la);
    if hi - lo > tol {
        let mid = 0.5 * (lo + hi) / la;
        *overlap = Some(a.start.offset(mid * da.0, mid * da.1));
    }
}

fn line_circle(line: &Segment, (c, r): (Point, f64), tol: f64, out: &mut Vec<Point>) {
    let d = line.start.vector_to(line.end);
    let len2 = dot(d, d);
    if len2 <= 0.0 {
        return;
    }
    let t_foot = dot(line.start.vector_to(c), d) / len2;
    let foot = line.start.offset(t_foot * d.0, t_foot * d.1);
    let dist = foot.distance_mm(c);
    if dist > r + tol {
        return;
    }
    if (dist - r).abs() <= tol {
        out.push(foot);
        return;
    }
    let h = ((r - dist) * (r + dist)).max(0.0).sqrt() / len2.sqrt();
    out.push(foot.offset(h * d.0, h * d.1));
    out.push(foot.offset(-h * d.0, -h * d.1));
}

fn circle_circle(
    a: &Segment,
    b: &Segment,
    (ca, ra): (Point, f64),
    (cb, rb): (Point, f64),
    tol: f64,
    out: &mut Vec<Point>,
    overlap: &mut Option<Point>,
) {
    let d = ca.distance_mm(cb);
    if d <= tol {
        if (ra - rb).abs() <= tol {
            *overlap = common_arc_point(a, b, ra, tol);
        }
        return;
    }
    if d > ra + rb + tol || d < (ra - rb).abs() - tol {
        return;
    }
    let u = (ca.vector_to(cb).0 / d, ca.vector_to(cb).1 / d);
    if (d - (ra + rb)).abs() <= tol || (d - (ra - rb).abs()).abs() <= tol {
        // Tangent: the touching point lies on the line of centres.
        let sign = if (d - (ra + rb)).abs() <= tol || ra > rb { 1.0 } else { -1.0 };
        out.push(ca.offset(sign * ra * u.0, sign * ra * u.1));
        return;
    }
    let along = (d * d + ra * ra - rb * rb) / (2.0 * d);
    let h = ((ra - along) * (ra + along)).max(0.0).sqrt();
    let base = ca.offset(along * u.0, along * u.1);
    out.push(base.offset(-h * u.1, h * u.0));
    out.push(base.offset(h * u.1, -h * u.0));
}

/// For two arcs of one circle: a point inside their common part if it is longer than `tol`.
fn common_arc_point(a: &Segment, b: &Segment, r: f64, tol: f64) -> Option<Point> {
    let (arc_a, arc_b) = (a.arc()?, b.arc()?);
    // Each arc as a counter-clockwise interval [start, start + width].
    let ccw = |arc: &super::segment::ArcGeometry| {
        let w = arc.sweep_rad.abs();
        let s = if arc.sweep_rad > 0.0 { arc.start_angle_rad } else { arc.start_angle_rad + arc.sweep_rad };
        (s, w)
    };
    let ((s1, w1), (s2, w2)) = (ccw(&arc_a), ccw(&arc_b));
    let delta = (s2 - s1).rem_euclid(TAU);
    // b's interval relative to a's start, and its copy one turn earlier.
    let first = (delta, (delta + w2).min(w1));
    let second = (0.0, (delta + w2 - TAU).min(w1));
    for (lo, hi) in [first, second] {
        if (hi - lo) * r > tol {
            return Some(arc_a.point_at_angle(s1 + 0.5 * (lo + hi)));
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Tolerance of exact results (mm).
    const TOL: f64 = 1e-12;

    fn p(x: f64, y: f64) -> Point {
        Point::new(x, y)
    }

    #[test]
    fn crossing_lines_meet_once_at_the_right_point_and_parameters() {
        let a = Segment::line(p(0.0, 0.0), p(10.0, 10.0));
        let b = Segment::line(p(10.0, 0.0), p(0.0, 10.0));
        let hits = a.intersections(&b);
        assert!(!hits.overlap);
        assert_eq!(hits.points.len(), 1);
        let hit = hits.points[0];
        assert!(hit.point.distance_mm(p(5.0, 5.0)) < TOL);
        assert!((hit.t_self - 0.5).abs() < TOL && (hit.t_other - 0.5).abs() < TOL);
    }

    #[test]
    fn collinear_lines_running_over_each_other_overlap_and_end_to_end_ones_touch() {
        let a = Segment::line(p(0.0, 0.0), p(10.0, 0.0));
        assert!(a.intersections(&Segment::line(p(5.0, 0.0), p(15.0, 0.0))).overlap);
        let touch = a.intersections(&Segment::line(p(10.0, 0.0), p(20.0, 0.0)));
        assert!(!touch.overlap);
        assert_eq!(touch.points.len(), 1);
        assert!(a.intersections(&Segment::line(p(0.0, 1.0), p(10.0, 1.0))).is_empty());
    }

    #[test]
    fn a_line_through_a_half_circle_meets_it_only_within_the_sweep() {
        let arc = Segment::new(p(1.0, 0.0), p(-1.0, 0.0), 1.0); // upper half
        let line = Segment::line(p(-2.0, 0.5), p(2.0, 0.5));
        assert_eq!(arc.intersections(&line).points.len(), 2);
        let below = Segment::line(p(-2.0, -0.5), p(2.0, -0.5));
        assert!(arc.intersections(&below).is_empty());
        let tangent = Segment::line(p(-2.0, 1.0), p(2.0, 1.0));
        let hits = arc.intersections(&tangent);
        assert_eq!(hits.points.len(), 1);
        assert!(hits.points[0].point.distance_mm(p(0.0, 1.0)) < TOL);
    }

    #[test]
    fn two_circles_cross_twice_and_arcs_of_one_circle_overlap_or_touch() {
        let a = Segment::new(p(1.0, 0.0), p(-1.0, 0.0), 1.0); // upper half of unit circle
        let b = Segment::new(p(2.0, 0.0), p(0.0, 0.0), 1.0); // upper half around (1, 0)
        let hits = a.intersections(&b);
        assert!(hits.points.iter().any(|h| h.point.distance_mm(p(0.5, 0.75_f64.sqrt())) < TOL));
        let lower = Segment::new(p(-1.0, 0.0), p(1.0, 0.0), 1.0); // lower half, same circle
        let touch = a.intersections(&lower);
        assert!(!touch.overlap);
        assert_eq!(touch.points.len(), 2);
        let quarter = Segment::from_arc(p(0.0, 0.0), 1.0, 0.5, 1.0);
        assert!(a.intersections(&quarter).overlap);
    }
}
