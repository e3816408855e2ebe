//! Closed contours: loops of vertices joined by lines and arcs (DXF LWPOLYLINE semantics).

use super::point::{Bounds, Point};
use super::segment::Segment;
use crate::core::error::CoreError;
use serde::{Deserialize, Serialize};

/// A vertex of a loop (mm) with the bulge of the segment leaving it.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Vertex {
    /// x coordinate (mm).
    pub x: f64,
    /// y coordinate (mm).
    pub y: f64,
    /// Bulge of the segment from this vertex to the next: `tan(sweep/4)`, positive
    /// counter-clockwise, 0 for a straight line (as in DXF LWPOLYLINE group 42).
    #[serde(default)]
    pub bulge: f64,
}

impl Vertex {
    /// The vertex `(x, y)` (mm) whose outgoing segment has `bulge`.
    pub const fn new(x: f64, y: f64, bulge: f64) -> Vertex {
        Vertex { x, y, bulge }
    }

    /// The vertex's position (mm).
    pub fn point(&self) -> Point {
        Point::new(self.x, self.y)
    }
}

/// A closed contour: the last vertex connects back to the first.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Loop {
    /// The vertices in order; `vertices[i].bulge` shapes the segment to `vertices[i + 1]`.
    pub vertices: Vec<Vertex>,
}

impl Loop {
    /// The loop through `vertices` (not validated: see [`Loop::validate`]).
    pub fn new(vertices: Vec<Vertex>) -> Loop {
        Loop { vertices }
    }

    /// The axis-aligned rectangle, counter-clockwise from `(x_min, y_min)` (mm).
    pub fn rectangle(x_min: f64, y_min: f64, x_max: f64, y_max: f64) -> Loop {
        Loop::new(vec![
            Vertex::new(x_min, y_min, 0.0),
            Vertex::new(x_max, y_min, 0.0),
            Vertex::new(x_max, y_max, 0.0),
            Vertex::new(x_min, y_max, 0.0),
        ])
    }

    /// The circle of centre `(cx, cy)` and radius `r` (mm) as two counter-clockwise half
    /// circles starting at its rightmost point.
    pub fn circle(cx: f64, cy: f64, r: f64) -> Loop {
        Loop::new(vec![Vertex::new(cx + r, cy, 1.0), Vertex::new(cx - r, cy, 1.0)])
    }

    /// The segment leaving vertex `i` (`i < vertices.len()`).
    pub fn segment(&self, i: usize) -> Segment {
        let n = self.vertices.len();
        let (a, b) = (self.vertices[i], self.vertices[(i + 1) % n]);
        Segment::new(a.point(), b.point(), a.bulge)
    }

    /// The segments in order, the closing one last.
    pub fn segments(&self) -> impl Iterator<Item = Segment> + '_ {
        (0..self.vertices.len()).map(move |i| self.segment(i))
    }

    /// Signed enclosed area (mm²): positive for a counter-clockwise loop. Exact for arcs: the
    /// polygon of the vertices plus, per arc, the circular segment `r²·(θ − sin θ)/2`.
    pub fn signed_area(&self) -> f64 {
        let Some(origin) = self.vertices.first().map(Vertex::point) else {
            return 0.0;
        };
        let mut twice_polygon = 0.0;
        let mut arcs = 0.0;
        for seg in self.segments() {
            let (ax, ay) = origin.vector_to(seg.start);
            let (bx, by) = origin.vector_to(seg.end);
            twice_polygon += ax * by - bx * ay;
            if let Some((_, r)) = seg.circle() {
                let theta = seg.sweep_rad();
                arcs += 0.5 * r * r * (theta - theta.sin());
            }
        }
        0.5 * twice_polygon + arcs
    }

    /// `true` when the loop runs counter-clockwise (positive signed area).
    pub fn is_ccw(&self) -> bool {
        self.signed_area() > 0.0
    }

    /// The same region traversed the other way: first vertex kept, the others reversed, each
    /// bulge negated and moved to the vertex that now starts its segment.
    pub fn reversed(&self) -> Loop {
        let n = self.vertices.len();
        let vertices = (0..n)
            .map(|k| {
                let v = self.vertices[(n - k) % n];
                Vertex::new(v.x, v.y, -self.vertices[n - 1 - k].bulge)
            })
            .collect();
        Loop::new(vertices)
    }

    /// Total length of the segments (mm).
    pub fn perimeter_mm(&self) -> f64 {
        self.segments().map(|s| s.length_mm()).sum()
    }

    /// Exact bounding box, arcs' extreme points included.
    pub fn bounds(&self) -> Bounds {
        self.segments().fold(Bounds::EMPTY, |acc, s| acc.union(s.bounds()))
    }

    /// Calls `emit(x)` for each crossing of the row at `y` with the loop, in segment order,
    /// under the half-open rule of [`Segment::row_crossings`] (always an even number).
    pub fn for_each_row_crossing(&self, y: f64, mut emit: impl FnMut(f64)) {
        for seg in self.segments() {
            seg.row_crossings(y, &mut emit);
        }
    }

    /// Appends the x of each crossing of the row at `y` with the loop to `out` (unsorted).
    pub fn row_crossings(&self, y: f64, out: &mut Vec<f64>) {
        self.for_each_row_crossing(y, |x| out.push(x));
    }

    /// The x-intervals `[a, b)` of the row at `y` inside the loop, sorted and disjoint, into
    /// `out` (cleared first; no other allocation).
    pub fn row_intervals(&self, y: f64, out: &mut Vec<(f64, f64)>) {
        out.clear();
        self.for_each_row_crossing(y, |x| out.push((x, x)));
        pair_crossings(out);
    }

    /// `true` when `(x, y)` lies inside (even–odd rule, which for a valid loop is the same as a
    /// non-zero winding number). Consistent with [`Loop::row_intervals`]: inside exactly when
    /// `x` lies in one of the half-open intervals `[a, b)` of row `y`.
    pub fn contains(&self, x: f64, y: f64) -> bool {
        let mut inside = false;
        self.for_each_row_crossing(y, |xc| {
            if xc > x {
                inside = !inside;
            }
        });
        inside
    }

    /// Checks the loop (see [`super::validate::validate_loop`]); `field` names it in errors,
    /// e.g. `outer` gives `outer[3]`.
    pub fn validate(&self, field: &str) -> Result<(), CoreError> {
        super::validate::validate_loop(self, field)
    }
}

/// Turns the crossings stored as `(x, x)` in `buf` into sorted, disjoint intervals in place:
/// sorts them and pairs them even–odd, dropping empty intervals and merging touching ones.
pub(crate) fn pair_crossings(buf: &mut Vec<(f64, f64)>) {
    buf.sort_unstable_by(|a, b| a.0.total_cmp(&b.0));
    let pairs = buf.len() / 2;
    let mut written = 0;
    for k in 0..pairs {
        let (a, b) = (buf[2 * k].0, buf[2 * k + 1].0);
        if b <= a {
            continue;
        }
        if written > 0 && a <= buf[written - 1].1 {
            buf[written - 1].1 = b;
        } else {
            buf[written] = (a, b);
            written += 1;
        }
    }
    buf.truncate(written);
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::core::geometry::test_support::{bounds_near, loops_near};
    use std::f64::consts::PI;

    /// Tolerance of the exact results (mm, mm²).
    const TOL: f64 = 1e-9;

    /// Relative tolerance of the circle's area.
    const REL_TOL: f64 = 1e-9;

    #[test]
    fn a_rectangle_has_its_exact_area_and_bounds_and_runs_counter_clockwise() {
        let r = Loop::rectangle(1.0, 2.0, 11.0, 7.0);
        assert!((r.signed_area() - 50.0).abs() < TOL);
        assert!(r.is_ccw());
        let expected = Bounds { x_min: 1.0, y_min: 2.0, x_max: 11.0, y_max: 7.0 };
        assert!(bounds_near(&r.bounds(), &expected, TOL));
        assert!((r.perimeter_mm() - 30.0).abs() < TOL);
    }

    #[test]
    fn a_circle_has_area_pi_r_squared_and_its_exact_bounds() {
        let c = Loop::circle(3.0, -2.0, 7.5);
        let exact = PI * 7.5 * 7.5;
        assert!(((c.signed_area() - exact) / exact).abs() < REL_TOL);
        let b = c.bounds();
        assert!((b.x_min + 4.5).abs() < TOL && (b.x_max - 10.5).abs() < TOL);
        assert!((b.y_min + 9.5).abs() < TOL && (b.y_max - 5.5).abs() < TOL);
    }

    #[test]
    fn a_loop_with_bulges_adds_and_removes_circular_segments_exactly() {
        // 20×15 rectangle whose right edge bulges out by a half circle (r = 7.5) and whose
        // top edge bulges in by a half circle (r = 10, dipping to y = 5).
        let lp = Loop::new(vec![
            Vertex::new(0.0, 0.0, 0.0),
            Vertex::new(20.0, 0.0, 1.0),
            Vertex::new(20.0, 15.0, -1.0),
            Vertex::new(0.0, 15.0, 0.0),
        ]);
        let expected = 300.0 + PI * 7.5 * 7.5 / 2.0 - PI * 100.0 / 2.0;
        assert!((lp.signed_area() - expected).abs() < TOL);
        let b = lp.bounds();
        assert!((b.x_min).abs() < TOL && (b.x_max - 27.5).abs() < TOL);
        assert!((b.y_min).abs() < TOL && (b.y_max - 15.0).abs() < TOL);
    }

    #[test]
    fn reversing_flips_the_sign_of_the_area_and_keeps_its_size_and_shape() {
        let lp = Loop::new(vec![
            Vertex::new(0.0, 0.0, 0.3),
            Vertex::new(20.0, 0.0, 1.0),
            Vertex::new(20.0, 10.0, -0.5),
            Vertex::new(0.0, 10.0, 0.0),
        ]);
        let rev = lp.reversed();
        assert!((rev.signed_area() + lp.signed_area()).abs() < TOL);
        assert!(bounds_near(&rev.bounds(), &lp.bounds(), TOL));
        assert!(loops_near(&rev.reversed(), &lp, TOL));
        // Every reversed segment is an original one traversed backwards.
        for seg in rev.segments() {
            let back = seg.reversed();
            assert!(lp.segments().any(|s| s == back));
        }
    }

    #[test]
    fn containment_follows_the_arcs() {
        let c = Loop::circle(0.0, 0.0, 10.0);
        assert!(c.contains(0.0, 0.0));
        assert!(c.contains(7.0, 7.0));
        assert!(!c.contains(7.2, 7.2));
        assert!(!c.contains(0.0, 10.5));
        assert!(c.reversed().contains(7.0, 7.0));
    }

    #[test]
    fn a_row_through_a_vertex_of_a_diamond_counts_it_once() {
        let d = Loop::new(vec![
            Vertex::new(0.0, -10.0, 0.0),
            Vertex::new(10.0, 0.0, 0.0),
            Vertex::new(0.0, 10.0, 0.0),
            Vertex::new(-10.0, 0.0, 0.0),
        ]);
        let mut out = Vec::new();
        d.row_intervals(0.0, &mut out);
        assert_eq!(out.len(), 1);
        assert!((out[0].0 + 10.0).abs() < TOL && (out[0].1 - 10.0).abs() < TOL);
        d.row_intervals(10.0, &mut out);
        assert!(out.is_empty());
        d.row_intervals(-10.0, &mut out);
        assert!(out.is_empty());
    }

    #[test]
    fn loops_round_trip_through_json_with_the_bulge_defaulting_to_zero() {
        let lp: Loop = serde_json::from_str(r#"{"vertices":[{"x":0,"y":0},{"x":1,"y":0,"bulge":1}]}"#).unwrap();
        assert!((lp.vertices[0].bulge).abs() < TOL);
        let back: Loop = serde_json::from_str(&serde_json::to_string(&lp).unwrap()).unwrap();
        assert!(loops_near(&back, &lp, TOL));
    }
}
