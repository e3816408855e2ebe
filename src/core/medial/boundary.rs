//! The pocket's boundary as one flat list of segments, with the exact clearance of a point and
//! its foot points (seed 004 §2.1: the clearance radius `R` of a medial-axis point is the
//! distance to the nearest boundary point, i.e. the radius of the largest inscribed circle).

use crate::core::geometry::{Bounds, Pocket, Point, Segment};
use std::ops::Range;

/// The segments of the outer loop and of every island, loop after loop, each loop's segments
/// in order (the outer loop counter-clockwise, islands clockwise, as in [`Pocket`]).
#[derive(Debug, Clone)]
pub(crate) struct Boundary {
    /// All segments, loop after loop.
    pub segments: Vec<Segment>,
    /// Exact bounding box of each segment.
    bounds: Vec<Bounds>,
    /// The range of `segments` that belongs to each loop (the outer loop first).
    pub loops: Vec<Range<usize>>,
}

impl Boundary {
    /// Flattens the pocket's loops.
    pub fn of_pocket(pocket: &Pocket) -> Boundary {
        let mut segments = Vec::new();
        let mut loops = Vec::new();
        for lp in std::iter::once(&pocket.outer).chain(&pocket.islands) {
            let first = segments.len();
            segments.extend(lp.segments());
            loops.push(first..segments.len());
        }
        let bounds = segments.iter().map(Segment::bounds).collect();
        Boundary { segments, bounds, loops }
    }

    /// The segment before `segment` in its loop (cyclically): the other segment meeting at its
    /// start vertex.
    pub fn previous(&self, segment: usize) -> usize {
        let range = self.loops.iter().find(|r| r.contains(&segment)).cloned().unwrap_or(segment..segment + 1);
        if segment == range.start {
            range.end - 1
        } else {
            segment - 1
        }
    }

    /// The segment after `segment` in its loop (cyclically): the other segment meeting at its
    /// end vertex.
    pub fn next(&self, segment: usize) -> usize {
        let range = self.loops.iter().find(|r| r.contains(&segment)).cloned().unwrap_or(segment..segment + 1);
        if segment + 1 == range.end {
            range.start
        } else {
            segment + 1
        }
    }

    /// The exact distance from `p` to the boundary (mm), by [`Segment::distance_mm`] over all
    /// segments (a segment whose box is farther than the best distance so far is skipped).
    pub fn clearance_mm(&self, p: Point) -> f64 {
        self.clearance_among(p, 0..self.segments.len())
    }

    /// The distance from `p` to the nearest of the segments `candidates` (mm): the exact
    /// clearance of `p` when they hold its nearest segment (see [`Boundary::segments_within`]).
    pub fn clearance_among(&self, p: Point, candidates: impl IntoIterator<Item = usize>) -> f64 {
        let mut best = f64::INFINITY;
        for k in candidates {
            if box_distance_mm(&self.bounds[k], p) < best {
                best = best.min(self.segments[k].distance_mm(p));
            }
        }
        best
    }

    /// Puts into `out` (cleared first) the segments whose boxes come within `reach_mm` of `c`:
    /// they hold the nearest segment of every point within `h` of `c` when `reach_mm` is at
    /// least the clearance of `c` plus `2·h` (that point's nearest segment is at most its
    /// clearance, at most `clearance(c) + h`, from it, so at most `clearance(c) + 2·h` from `c`).
    pub fn segments_within(&self, c: Point, reach_mm: f64, out: &mut Vec<usize>) {
        out.clear();
        out.extend((0..self.segments.len()).filter(|&k| box_distance_mm(&self.bounds[k], c) <= reach_mm));
    }

    /// The boundary point nearest to `p`.
    pub fn nearest_point(&self, p: Point) -> Point {
        let mut best = (f64::INFINITY, p);
        for s in &self.segments {
            let q = s.point_at(s.parameter_of(p));
            let d = q.distance_mm(p);
            if d < best.0 {
                best = (d, q);
            }
        }
        best.1
    }

    /// Where `p` touches segment `segment`: the segment's point nearest to `p`, if it is a
    /// local nearest point of the boundary. A nearest point inside the segment always is; one
    /// at an end vertex only when the neighbouring segment's nearest point is that vertex too
    /// (`p` sees the vertex itself, as around a reflex corner); otherwise the true contact lies
    /// on the neighbour and this segment has none.
    pub fn contact(&self, segment: usize, p: Point) -> Option<Point> {
        let s = &self.segments[segment];
        let t = s.parameter_of(p);
        if t <= 0.0 {
            let before = &self.segments[self.previous(segment)];
            (before.parameter_of(p) >= 1.0).then_some(s.start)
        } else if t >= 1.0 {
            let after = &self.segments[self.next(segment)];
            (after.parameter_of(p) <= 0.0).then_some(s.end)
        } else {
            Some(s.point_at(t))
        }
    }
}

/// Distance from `p` to the box (0 inside it) (mm).
fn box_distance_mm(b: &Bounds, p: Point) -> f64 {
    let dx = (b.x_min - p.x).max(p.x - b.x_max).max(0.0);
    let dy = (b.y_min - p.y).max(p.y - b.y_max).max(0.0);
    dx.hypot(dy)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::core::geometry::Loop;

    /// Tolerance of exact results (mm).
    const TOL_MM: f64 = 1e-12;

    #[test]
    fn the_clearance_of_a_point_is_its_distance_to_the_nearest_side_or_island() {
        let pocket = Pocket::new(Loop::rectangle(0.0, 0.0, 60.0, 40.0), vec![Loop::circle(30.0, 20.0, 5.0)]).unwrap();
        let boundary = Boundary::of_pocket(&pocket);
        assert_eq!(boundary.loops, vec![0..4, 4..6]);
        assert!((boundary.clearance_mm(Point::new(10.0, 20.0)) - 10.0).abs() < TOL_MM);
        assert!((boundary.clearance_mm(Point::new(30.0, 30.0)) - 5.0).abs() < TOL_MM);
        assert!((boundary.clearance_mm(Point::new(3.0, 35.0)) - 3.0).abs() < TOL_MM);
    }

    #[test]
    fn the_segment_before_the_first_of_a_loop_is_the_loops_last() {
        let pocket = Pocket::new(Loop::rectangle(0.0, 0.0, 60.0, 40.0), vec![Loop::circle(30.0, 20.0, 5.0)]).unwrap();
        let boundary = Boundary::of_pocket(&pocket);
        assert_eq!(boundary.previous(0), 3);
        assert_eq!(boundary.previous(2), 1);
        assert_eq!(boundary.previous(4), 5);
        assert_eq!(boundary.previous(5), 4);
        assert_eq!(boundary.next(3), 0);
        assert_eq!(boundary.next(5), 4);
    }

    #[test]
    fn a_point_touches_the_sides_it_projects_onto_and_a_reflex_vertex_it_sees() {
        // The L (0,0)–(60,0)–(60,20)–(20,20)–(20,60)–(0,60); its reflex vertex is (20, 20).
        let l = Loop::new(
            [(0.0, 0.0), (60.0, 0.0), (60.0, 20.0), (20.0, 20.0), (20.0, 60.0), (0.0, 60.0)]
                .iter()
                .map(|&(x, y)| crate::core::geometry::Vertex::new(x, y, 0.0))
                .collect(),
        );
        let boundary = Boundary::of_pocket(&Pocket::new(l, vec![]).unwrap());
        let p = Point::new(15.0, 10.0);
        assert!(boundary.contact(0, p).unwrap().near(Point::new(15.0, 0.0), TOL_MM));
        assert!(boundary.contact(1, p).unwrap().near(Point::new(60.0, 10.0), TOL_MM));
        assert!(boundary.contact(2, p).unwrap().near(Point::new(20.0, 20.0), TOL_MM));
        assert!(boundary.contact(3, p).unwrap().near(Point::new(20.0, 20.0), TOL_MM));
        assert!(boundary.contact(5, p).unwrap().near(Point::new(0.0, 10.0), TOL_MM));
        // Past the reflex vertex the side (60,20)–(20,20) is seen directly: no vertex contact
        // on the side (20,20)–(20,60).
        assert!(boundary.contact(3, Point::new(25.0, 10.0)).is_none());
    }
}
