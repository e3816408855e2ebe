//! Where a closed loop starts: the point of the loop nearest to the tool, the loop rotated
//! (and its segment split) to begin and end there.

use crate::core::geometry::{Loop, Point, Segment, Vertex};

/// A split closer than this to a vertex, along the segment, starts the loop at the vertex
/// instead: no NC block shorter than this comes from a split (mm).
pub(super) const MIN_SPLIT_MM: f64 = 0.01;

/// The point of a loop nearest to a given point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Nearest {
    /// Index of the segment it lies on.
    pub segment: usize,
    /// Fraction of that segment's length at which it lies.
    pub t: f64,
    /// The point (mm).
    pub point: Point,
    /// Its distance from the given point (mm).
    pub distance_mm: f64,
}

/// The point of `lp` nearest to `p` (the first of equally near ones).
pub(super) fn nearest_on_loop(lp: &Loop, p: Point) -> Nearest {
    let mut best = Nearest { segment: 0, t: 0.0, point: lp.vertices[0].point(), distance_mm: f64::INFINITY };
    for (i, seg) in lp.segments().enumerate() {
        let t = seg.parameter_of(p);
        let q = seg.point_at(t);
        let d = q.distance_mm(p);
        if d < best.distance_mm {
            best = Nearest { segment: i, t, point: q, distance_mm: d };
        }
    }
    best
}

/// The point `distance_mm` further along `lp` (in its direction) from `at`, going round the
/// loop at most once.
pub(super) fn advance(lp: &Loop, at: &Nearest, distance_mm: f64) -> Nearest {
    let n = lp.vertices.len();
    let mut left = distance_mm;
    let mut segment = at.segment;
    let mut t = at.t;
    for _ in 0..=n {
        let seg = lp.segment(segment);
        let len = seg.length_mm();
        let rest = (1.0 - t) * len;
        if rest >= left && len > 0.0 {
            let t_new = t + left / len;
            return Nearest { segment, t: t_new, point: seg.point_at(t_new), distance_mm: at.distance_mm };
        }
        left -= rest;
        segment = (segment + 1) % n;
        t = 0.0;
    }
    *at
}

/// `lp` traversed from the point `at` (on segment `at.segment`) round to the same point: the
/// vertices rotated and, unless the point is within [`MIN_SPLIT_MM`] of a vertex, that segment
/// split in two (an arc into two arcs of the same circle).
pub(super) fn starting_at(lp: &Loop, at: &Nearest) -> Loop {
    let n = lp.vertices.len();
    let seg = lp.segment(at.segment);
    let length_mm = seg.length_mm();
    let rotated = |first: usize| -> Vec<Vertex> { (0..n).map(|k| lp.vertices[(first + k) % n]).collect() };
    if at.t * length_mm < MIN_SPLIT_MM {
        return Loop::new(rotated(at.segment));
    }
    if (1.0 - at.t) * length_mm < MIN_SPLIT_MM {
        return Loop::new(rotated((at.segment + 1) % n));
    }
    let point = seg.point_at(at.t);
    let (before, after) = split_bulges(&seg, at.t);
    let mut vertices = Vec::with_capacity(n + 1);
    vertices.push(Vertex::new(point.x, point.y, after));
    vertices.extend(rotated((at.segment + 1) % n));
    if let Some(last) = vertices.last_mut() {
        last.bulge = before;
    }
    Loop::new(vertices)
}

/// The bulges of the two pieces of `seg` cut at fraction `t` of its length: an arc's sweep
/// divides as its length does.
pub(super) fn split_bulges(seg: &Segment, t: f64) -> (f64, f64) {
    if !seg.is_arc() {
        return (0.0, 0.0);
    }
    let sweep = seg.sweep_rad();
    ((t * sweep / 4.0).tan(), ((1.0 - t) * sweep / 4.0).tan())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Tolerance of exact constructions (mm).
    const TOL_MM: f64 = 1e-9;

    #[test]
    fn a_loop_split_on_an_arc_keeps_its_circle_and_its_area() {
        let lp = Loop::circle(0.0, 0.0, 10.0);
        let at = nearest_on_loop(&lp, Point::new(0.0, 30.0));
        assert!((at.distance_mm - 20.0).abs() < TOL_MM && at.point.near(Point::new(0.0, 10.0), TOL_MM));
        let split = starting_at(&lp, &at);
        assert_eq!(split.vertices.len(), 3);
        assert!(split.vertices[0].point().near(Point::new(0.0, 10.0), TOL_MM));
        assert!((split.signed_area() - lp.signed_area()).abs() < TOL_MM);
        for seg in split.segments() {
            let (c, r) = seg.circle().unwrap();
            assert!(c.near(Point::new(0.0, 0.0), TOL_MM) && (r - 10.0).abs() < TOL_MM);
        }
    }

    #[test]
    fn advancing_along_a_loop_crosses_its_vertices() {
        let lp = Loop::rectangle(0.0, 0.0, 60.0, 40.0);
        let at = nearest_on_loop(&lp, Point::new(50.0, -3.0));
        let ahead = advance(&lp, &at, 15.0);
        assert!(ahead.point.near(Point::new(60.0, 5.0), TOL_MM), "{ahead:?}");
        assert_eq!(ahead.segment, 1);
    }

    #[test]
    fn a_point_next_to_a_vertex_starts_the_loop_at_that_vertex() {
        let lp = Loop::rectangle(0.0, 0.0, 60.0, 40.0);
        let at = nearest_on_loop(&lp, Point::new(60.0 - 0.5 * MIN_SPLIT_MM, -3.0));
        let start = starting_at(&lp, &at);
        assert_eq!(start.vertices.len(), 4);
        assert!(start.vertices[0].point().near(Point::new(60.0, 0.0), TOL_MM));
        let mid = starting_at(&lp, &nearest_on_loop(&lp, Point::new(30.0, -3.0)));
        assert_eq!(mid.vertices.len(), 5);
        assert!(mid.vertices[0].point().near(Point::new(30.0, 0.0), TOL_MM));
        assert!(mid.vertices[4].point().near(Point::new(0.0, 0.0), TOL_MM));
        assert!((mid.signed_area() - lp.signed_area()).abs() < TOL_MM);
    }
}
