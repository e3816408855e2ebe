//! One segment of a contour: a straight line or a circular arc between two points, the arc
//! given by its DXF bulge `tan(sweep/4)` (positive = counter-clockwise).

use super::point::{cross, dot, Bounds, Point};
use serde::{Deserialize, Serialize};
use std::f64::consts::{FRAC_PI_2, PI, TAU};

/// A segment whose bulge magnitude is at most this is a straight line: its sagitta is then at
/// most 5e-8 × its chord (0.05 µm on a 1 m chord), and the radius of the arc (≥ chord / 4e-7)
/// would be too large for stable circle arithmetic.
pub const STRAIGHT_BULGE: f64 = 1e-7;

/// Circle data of an arc segment.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct ArcGeometry {
    /// Centre (mm).
    pub center: Point,
    /// Radius (mm).
    pub radius_mm: f64,
    /// Direction of the start point seen from the centre (rad, in (−π, π]).
    pub start_angle_rad: f64,
    /// Signed sweep (rad): positive counter-clockwise, |sweep| < 2π.
    pub sweep_rad: f64,
}

impl ArcGeometry {
    /// Where `angle_rad` lies along the sweep as a fraction of it, if it lies within the sweep
    /// widened by `tol_rad` at both ends (the fraction is then clamped to [0, 1]).
    pub fn sweep_fraction(&self, angle_rad: f64, tol_rad: f64) -> Option<f64> {
        let span = self.sweep_rad.abs();
        let along = ((angle_rad - self.start_angle_rad) * self.sweep_rad.signum()).rem_euclid(TAU);
        if along <= span + tol_rad {
            Some((along / span).min(1.0))
        } else if along >= TAU - tol_rad {
            Some(0.0)
        } else {
            None
        }
    }

    /// The point of the circle in direction `angle_rad` (mm).
    pub fn point_at_angle(&self, angle_rad: f64) -> Point {
        self.center.offset(self.radius_mm * angle_rad.cos(), self.radius_mm * angle_rad.sin())
    }
}

/// A straight line (`bulge` ≈ 0) or a circular arc from `start` to `end` (mm).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Segment {
    /// Start point (mm).
    pub start: Point,
    /// End point (mm).
    pub end: Point,
    /// `tan(sweep/4)`: 0 for a line, ±1 for a half circle, positive counter-clockwise.
    pub bulge: f64,
}

impl Segment {
    /// The segment from `start` to `end` with the given bulge.
    pub fn new(start: Point, end: Point, bulge: f64) -> Segment {
        Segment { start, end, bulge }
    }

    /// The straight line from `start` to `end`.
    pub fn line(start: Point, end: Point) -> Segment {
        Segment::new(start, end, 0.0)
    }

    /// The arc of the circle (`center`, `radius_mm`) from direction `start_angle_rad` over the
    /// signed `sweep_rad` (|sweep| < 2π).
    pub fn from_arc(center: Point, radius_mm: f64, start_angle_rad: f64, sweep_rad: f64) -> Segment {
        let arc = ArcGeometry { center, radius_mm, start_angle_rad, sweep_rad };
        Segment::new(
            arc.point_at_angle(start_angle_rad),
            arc.point_at_angle(start_angle_rad + sweep_rad),
            (sweep_rad / 4.0).tan(),
        )
    }

    /// `true` for an arc, `false` for a straight line (see [`STRAIGHT_BULGE`]).
    pub fn is_arc(&self) -> bool {
        self.bulge.abs() > STRAIGHT_BULGE
    }

    /// Distance from start to end (mm).
    pub fn chord_mm(&self) -> f64 {
        self.start.distance_mm(self.end)
    }

    /// Signed sweep (rad), 0 for a line.
    pub fn sweep_rad(&self) -> f64 {
        if self.is_arc() {
            4.0 * self.bulge.atan()
        } else {
            0.0
        }
    }

    /// Centre and radius (mm) of an arc, computed without trigonometry; `None` for a line.
    pub fn circle(&self) -> Option<(Point, f64)> {
        if !self.is_arc() {
            return None;
        }
        let b = self.bulge;
        let (dx, dy) = self.start.vector_to(self.end);
        let k = (1.0 - b * b) / (4.0 * b);
        let center = Point::new(0.5 * (self.start.x + self.end.x) - dy * k, 0.5 * (self.start.y + self.end.y) + dx * k);
        let radius = self.chord_mm() * (1.0 + b * b) / (4.0 * b.abs());
        Some((center, radius))
    }

    /// Full circle data of an arc; `None` for a line.
    pub fn arc(&self) -> Option<ArcGeometry> {
        let (center, radius_mm) = self.circle()?;
        let (sx, sy) = center.vector_to(self.start);
        Some(ArcGeometry { center, radius_mm, start_angle_rad: sy.atan2(sx), sweep_rad: self.sweep_rad() })
    }

    /// Length along the segment (mm): `chord·(1 + b²)·atan(b)/b` for an arc.
    pub fn length_mm(&self) -> f64 {
        let chord = self.chord_mm();
        if self.is_arc() {
            let b = self.bulge;
            chord * (1.0 + b * b) * b.atan() / b
        } else {
            chord
        }
    }

    /// The point at fraction `t` ∈ [0, 1] of the length (mm); the exact end points at 0 and 1.
    pub fn point_at(&self, t: f64) -> Point {
        if t <= 0.0 {
            return self.start;
        }
        if t >= 1.0 {
            return self.end;
        }
        match self.arc() {
            Some(arc) => arc.point_at_angle(arc.start_angle_rad + t * arc.sweep_rad),
            None => self.start.offset(t * (self.end.x - self.start.x), t * (self.end.y - self.start.y)),
        }
    }

    /// The point halfway along the segment, computed without trigonometry (mm).
    pub fn midpoint(&self) -> Point {
        let b = if self.is_arc() { self.bulge } else { 0.0 };
        let (dx, dy) = self.start.vector_to(self.end);
        Point::new(0.5 * (self.start.x + self.end.x) + 0.5 * b * dy, 0.5 * (self.start.y + self.end.y) - 0.5 * b * dx)
    }

    /// The same segment traversed from `end` to `start`.
    pub fn reversed(&self) -> Segment {
        Segment::new(self.end, self.start, -self.bulge)
    }

    /// Fraction of the length at which the point of the segment nearest to `p` lies.
    pub fn parameter_of(&self, p: Point) -> f64 {
        match self.arc() {
            Some(arc) => {
                let (px, py) = arc.center.vector_to(p);
                let span = arc.sweep_rad.abs();
                let along = ((py.atan2(px) - arc.start_angle_rad) * arc.sweep_rad.signum()).rem_euclid(TAU);
                if along <= span {
                    along / span
                } else if along - span < TAU - along {
                    1.0
                } else {
                    0.0
                }
            }
            None => {
                let d = self.start.vector_to(self.end);
                let len2 = dot(d, d);
                if len2 > 0.0 {
                    (dot(self.start.vector_to(p), d) / len2).clamp(0.0, 1.0)
                } else {
                    0.0
                }
            }
        }
    }

    /// Distance from `p` to the nearest point of the segment (mm).
    pub fn distance_mm(&self, p: Point) -> f64 {
        match self.arc() {
            Some(arc) => {
                let (px, py) = arc.center.vector_to(p);
                if arc.sweep_fraction(py.atan2(px), 0.0).is_some() {
                    (px.hypot(py) - arc.radius_mm).abs()
                } else {
                    p.distance_mm(self.start).min(p.distance_mm(self.end))
                }
            }
            None => p.distance_mm(self.point_at(self.parameter_of(p))),
        }
    }

    /// Exact bounding box: the end points and, for an arc, the extreme points of the circle
    /// that lie within its sweep.
    pub fn bounds(&self) -> Bounds {
        let mut b = Bounds::of_point(self.start);
        b.include(self.end);
        if let Some(arc) = self.arc() {
            let r = arc.radius_mm;
            let extremes = [(0.0, r, 0.0), (FRAC_PI_2, 0.0, r), (PI, -r, 0.0), (-FRAC_PI_2, 0.0, -r)];
            for (angle, dx, dy) in extremes {
                if arc.sweep_fraction(angle, 0.0).is_some() {
                    b.include(arc.center.offset(dx, dy));
                }
            }
        }
        b
    }

    /// Calls `emit(x)` for every crossing of the horizontal line at `y` with the segment.
    ///
    /// Half-open rule: a point of the segment counts as above the line when its y is `> y`,
    /// otherwise as below, and the segment (an arc split at its top and bottom into
    /// y-monotone pieces) crosses where it passes from one side to the other. A row through
    /// a vertex is therefore counted once over the two segments meeting there, a horizontal
    /// edge never crosses, and a closed loop always crosses an even number of times.
    pub fn row_crossings(&self, y: f64, mut emit: impl FnMut(f64)) {
        let (s, e) = (self.start, self.end);
        if !self.is_arc() {
            if (s.y > y) != (e.y > y) {
                let x = s.x + (y - s.y) * (e.x - s.x) / (e.y - s.y);
                emit(x.clamp(s.x.min(e.x), s.x.max(e.x)));
            }
            return;
        }
        // Cheap rejection for arcs up to a half circle: they stay within their sagitta
        // (|b|·chord/2 ≤ |b|·(|dx| + |dy|)/2) of the chord's y-range.
        let b_abs = self.bulge.abs();
        if b_abs <= 1.0 {
            let margin = 0.5 * b_abs * ((e.x - s.x).abs() + (e.y - s.y).abs()) + super::POINT_EPS_MM;
            if s.y.min(e.y) - margin > y || s.y.max(e.y) + margin <= y {
                return;
            }
        }
        let Some((c, r)) = self.circle() else {
            return;
        };
        let (top, bottom) = (c.y + r, c.y - r);
        if s.y.min(e.y).min(bottom) > y || s.y.max(e.y).max(top) <= y {
            return;
        }
        let ccw = self.bulge > 0.0;
        // A circle point lies on the arc iff it is strictly on the bulge side of the chord;
        // extremes within POINT_EPS_MM of the chord are (near) end points: no split there.
        let chord = s.vector_to(e);
        let chord_len = self.chord_mm();
        let on_arc = |py: f64| {
            let side = cross(chord, s.vector_to(Point::new(c.x, py))) / chord_len;
            -side * self.bulge.signum() > super::POINT_EPS_MM
        };
        let (has_top, has_bottom) = (on_arc(top), on_arc(bottom));
        // Counter-clockwise, the right half (x > cx) rises: from there the top comes first.
        let top_first = (s.x > c.x) == ccw;
        let mut ys = [s.y; 4];
        let mut n = 1;
        let splits =
            if top_first { [(has_top, top), (has_bottom, bottom)] } else { [(has_bottom, bottom), (has_top, top)] };
        for (present, split_y) in splits {
            if present {
                ys[n] = split_y;
                n += 1;
            }
        }
        ys[n] = e.y;
        n += 1;
        for k in 1..n {
            let (ya, yb) = (ys[k - 1], ys[k]);
            if (ya > y) != (yb > y) {
                let dy = y - c.y;
                let half = ((r - dy) * (r + dy)).max(0.0).sqrt();
                // Counter-clockwise: rising on the right half; clockwise: rising on the left.
                let right = (yb > ya) == ccw;
                emit(if right { c.x + half } else { c.x - half });
            }
        }
    }
}

#[cfg(test)]
#[path = "segment_tests.rs"]
mod tests;
