//! The guide curve of a trochoid (MODEL.md §7): a chain of lines and arcs — a slot's
//! centre line or a medial-axis branch — walked by arc length.

use crate::core::error::CoreError;
use crate::core::geometry::{Point, Segment};
use crate::core::medial::AxisBranch;
use crate::core::tolerance::LENGTH_EPS_MM;

/// Consecutive segments must meet within this, mm.
pub const GUIDE_JOIN_TOLERANCE_MM: f64 = 1e-6;

/// A continuous chain of segments, with the arc length at each vertex.
#[derive(Debug, Clone, PartialEq)]
pub struct Guide {
    segments: Vec<Segment>,
    /// Arc length at the start of each segment, then the total length (one more entry).
    vertex_s_mm: Vec<f64>,
}

impl Guide {
    /// The polyline through `points` (at least two, finite, not all coincident). Coincident
    /// consecutive points give zero-length segments, which are kept so that per-point data
    /// (a clearance per point) still lines up with [`Guide::vertex_s_mm`].
    pub fn polyline(points: &[Point]) -> Result<Guide, CoreError> {
        if points.len() < 2 {
            return Err(CoreError::invalid("guide", "needs at least two points"));
        }
        let segments = points.windows(2).map(|w| Segment::line(w[0], w[1])).collect();
        Guide::from_segments(segments)
    }

    /// The chain of `segments` (lines and arcs), each starting where the one before ends.
    pub fn from_segments(segments: Vec<Segment>) -> Result<Guide, CoreError> {
        if segments.is_empty() {
            return Err(CoreError::invalid("guide", "needs at least one segment"));
        }
        let mut vertex_s_mm = Vec::with_capacity(segments.len() + 1);
        let mut s = 0.0;
        for (i, seg) in segments.iter().enumerate() {
            let coords = [seg.start.x, seg.start.y, seg.end.x, seg.end.y, seg.bulge];
            if coords.iter().any(|v| !v.is_finite()) {
                return Err(CoreError::invalid("guide", format!("segment {i}: coordinates must be finite")));
            }
            if i > 0 && !segments[i - 1].end.near(seg.start, GUIDE_JOIN_TOLERANCE_MM) {
                return Err(CoreError::invalid(
                    "guide",
                    format!("segment {i} does not start where segment {} ends", i - 1),
                ));
            }
            vertex_s_mm.push(s);
            s += seg.length_mm();
        }
        vertex_s_mm.push(s);
        if s <= LENGTH_EPS_MM {
            return Err(CoreError::invalid("guide", "has no length"));
        }
        Ok(Guide { segments, vertex_s_mm })
    }

    /// The guide of a medial-axis branch and its clearance radius `R` at each point (for
    /// [`super::trochoid::LoopRadius::Clearance`]; seed 004 Figure 5).
    pub fn of_axis_branch(branch: &AxisBranch) -> Result<(Guide, Vec<f64>), CoreError> {
        let points: Vec<Point> = branch.points.iter().map(|p| p.point).collect();
        let clearance = branch.points.iter().map(|p| p.clearance_mm).collect();
        Ok((Guide::polyline(&points)?, clearance))
    }

    /// Total length, mm.
    pub fn length_mm(&self) -> f64 {
        self.vertex_s_mm[self.segments.len()]
    }

    /// Arc length at each vertex (segment starts, then the end), mm.
    pub fn vertex_s_mm(&self) -> &[f64] {
        &self.vertex_s_mm
    }

    /// The segments.
    pub fn segments(&self) -> &[Segment] {
        &self.segments
    }

    /// The point at arc length `s_mm` (clamped to the guide).
    pub fn point_at(&self, s_mm: f64) -> Point {
        let s = s_mm.clamp(0.0, self.length_mm());
        // Last segment whose start is at or before s.
        let i = self.vertex_s_mm[..self.segments.len()].partition_point(|&v| v <= s).saturating_sub(1);
        let seg = &self.segments[i];
        let len = self.vertex_s_mm[i + 1] - self.vertex_s_mm[i];
        if len <= LENGTH_EPS_MM {
            return seg.end;
        }
        seg.point_at((s - self.vertex_s_mm[i]) / len)
    }

    /// Linear interpolation by arc length of `values` given at the vertices.
    pub fn interpolate(&self, values: &[f64], s_mm: f64) -> f64 {
        let s = s_mm.clamp(0.0, self.length_mm());
        let k = self.vertex_s_mm.partition_point(|&v| v <= s);
        if k == 0 {
            return values[0];
        }
        if k >= self.vertex_s_mm.len() {
            return values[values.len() - 1];
        }
        let (s0, s1) = (self.vertex_s_mm[k - 1], self.vertex_s_mm[k]);
        let t = if s1 - s0 > LENGTH_EPS_MM { (s - s0) / (s1 - s0) } else { 1.0 };
        values[k - 1] + (values[k] - values[k - 1]) * t
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::core::tolerance::approx_eq;
    use std::f64::consts::PI;

    #[test]
    fn a_polyline_is_walked_by_arc_length() {
        let g = Guide::polyline(&[Point::new(0.0, 0.0), Point::new(10.0, 0.0), Point::new(10.0, 5.0)]).unwrap();
        assert!(approx_eq(g.length_mm(), 15.0, 1e-12));
        let p = g.point_at(12.0);
        assert!(approx_eq(p.x, 10.0, 1e-12) && approx_eq(p.y, 2.0, 1e-12));
        assert!(approx_eq(g.interpolate(&[1.0, 2.0, 4.0], 12.0), 2.8, 1e-12));
        assert!(approx_eq(g.interpolate(&[1.0, 2.0, 4.0], 99.0), 4.0, 0.0));
    }

    #[test]
    fn a_chain_with_an_arc_has_the_arc_length() {
        let line = Segment::line(Point::new(-5.0, -5.0), Point::new(0.0, -5.0));
        let arc = Segment::from_arc(Point::new(0.0, 0.0), 5.0, -PI / 2.0, PI / 2.0);
        let g = Guide::from_segments(vec![line, arc]).unwrap();
        assert!(approx_eq(g.length_mm(), 5.0 + 2.5 * PI, 1e-9));
        let p = g.point_at(5.0 + 1.25 * PI);
        assert!(approx_eq(p.x.hypot(p.y), 5.0, 1e-9) && approx_eq(p.x, -p.y, 1e-9));
    }

    #[test]
    fn a_gap_between_segments_or_a_single_point_is_refused() {
        let a = Segment::line(Point::new(0.0, 0.0), Point::new(1.0, 0.0));
        let b = Segment::line(Point::new(2.0, 0.0), Point::new(3.0, 0.0));
        assert!(Guide::from_segments(vec![a, b]).unwrap_err().to_string().contains("does not start"));
        assert!(Guide::polyline(&[Point::new(1.0, 1.0)]).is_err());
        assert!(Guide::polyline(&[Point::new(1.0, 1.0), Point::new(1.0, 1.0)]).is_err());
    }
}
