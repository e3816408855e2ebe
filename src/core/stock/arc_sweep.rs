//! The area a disc sweeps along a circular arc of the tool-centre path: the points within
//! a distance of the arc. A stretch of a G2/G3 move is applied to the rasters as one such
//! area (see [`Raster::clear_arc_rows`]) instead of many short chords, and the probe
//! tests the arc swept since the last update the same way.
//!
//! [`Raster::clear_arc_rows`]: super::Raster::clear_arc_rows

use super::DEGENERATE_SEGMENT_MM;

/// An arc sweeps at most this angle, rad (90°): its angular wedge is convex, and the
/// rectangle around it holds little beside the swept area.
pub const MAX_ARC_SWEEP_RAD: f64 = std::f64::consts::FRAC_PI_2;

/// A circular arc in XY, from `a` to `b` about `center`, counter-clockwise from the
/// direction `lo` to the direction `hi` (the wedge of the arc's angles).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ArcSweep {
    center: (f64, f64),
    radius_mm: f64,
    a: (f64, f64),
    b: (f64, f64),
    /// Unit directions from the centre to the ends, ordered counter-clockwise.
    lo: (f64, f64),
    hi: (f64, f64),
}

/// The x-intervals of a row, at most `N` of them, sorted and disjoint.
#[derive(Debug, Clone, Copy)]
pub struct RowIntervals<const N: usize> {
    pub spans: [(f64, f64); N],
    pub len: usize,
}

impl<const N: usize> RowIntervals<N> {
    fn new() -> Self {
        RowIntervals { spans: [(0.0, 0.0); N], len: 0 }
    }

    /// Adds [lo, hi] (ignored when empty), merged with the intervals it meets. Every
    /// caller adds at most `N` intervals. The intervals are kept sorted and disjoint, so
    /// those [lo, hi] meets are a run: it takes their place.
    fn add(&mut self, lo: f64, hi: f64) {
        if lo.partial_cmp(&hi) != Some(std::cmp::Ordering::Less) {
            return;
        }
        let len = self.len;
        let first = self.spans[..len].iter().take_while(|s| s.1 < lo).count();
        let met = self.spans[first..len].iter().take_while(|s| s.0 <= hi).count();
        let (mut lo, mut hi) = (lo, hi);
        if met > 0 {
            lo = lo.min(self.spans[first].0);
            hi = hi.max(self.spans[first + met - 1].1);
        }
        // The intervals after the run move to follow the merged one.
        let after = first + met;
        self.spans.copy_within(after..len, first + 1);
        self.spans[first] = (lo, hi);
        self.len = first + 1 + (len - after);
    }

    pub fn iter(&self) -> impl Iterator<Item = (f64, f64)> + '_ {
        self.spans[..self.len].iter().copied()
    }
}

impl ArcSweep {
    /// The arc about `center` from `a` to `b` (both at the same distance from it),
    /// counter-clockwise when `ccw`; it sweeps at most half a turn.
    pub fn new(center: (f64, f64), a: (f64, f64), b: (f64, f64), ccw: bool) -> ArcSweep {
        let radius_mm = (a.0 - center.0).hypot(a.1 - center.1);
        let unit = |p: (f64, f64)| {
            let (dx, dy) = (p.0 - center.0, p.1 - center.1);
            let len = dx.hypot(dy);
            if len > DEGENERATE_SEGMENT_MM {
                (dx / len, dy / len)
            } else {
                (1.0, 0.0)
            }
        };
        let (ua, ub) = (unit(a), unit(b));
        let (lo, hi) = if ccw { (ua, ub) } else { (ub, ua) };
        ArcSweep { center, radius_mm, a, b, lo, hi }
    }

    pub fn radius_mm(&self) -> f64 {
        self.radius_mm
    }

    /// `true` when the direction `v` from the centre lies in the arc's wedge (the zero
    /// vector does): left of `lo`, right of `hi`, and not opposite the arc (which the
    /// first two allow of an arc that is a point).
    #[inline]
    fn in_wedge(&self, v: (f64, f64)) -> bool {
        let (lo, hi) = (self.lo, self.hi);
        lo.0 * v.1 - lo.1 * v.0 >= 0.0
            && v.0 * hi.1 - v.1 * hi.0 >= 0.0
            && v.0 * (lo.0 + hi.0) + v.1 * (lo.1 + hi.1) >= 0.0
    }

    /// Distance from `q` to the arc, mm: inside its wedge, to its circle; outside, to
    /// the nearer end.
    #[inline]
    pub fn distance(&self, q: (f64, f64)) -> f64 {
        let v = (q.0 - self.center.0, q.1 - self.center.1);
        if self.in_wedge(v) {
            ((v.0 * v.0 + v.1 * v.1).sqrt() - self.radius_mm).abs()
        } else {
            let da = (q.0 - self.a.0).powi(2) + (q.1 - self.a.1).powi(2);
            let db = (q.0 - self.b.0).powi(2) + (q.1 - self.b.1).powi(2);
            da.min(db).sqrt()
        }
    }

    /// The rectangle holding every point within `reach` of the arc: x range, y range.
    pub fn bounds(&self, reach: f64) -> ((f64, f64), (f64, f64)) {
        let (mut x, mut y) =
            ((self.a.0.min(self.b.0), self.a.0.max(self.b.0)), (self.a.1.min(self.b.1), self.a.1.max(self.b.1)));
        // The circle's extremes along the axes that lie on the arc.
        for dir in [(1.0, 0.0), (0.0, 1.0), (-1.0, 0.0), (0.0, -1.0)] {
            if self.in_wedge(dir) {
                let p = (self.center.0 + self.radius_mm * dir.0, self.center.1 + self.radius_mm * dir.1);
                x = (x.0.min(p.0), x.1.max(p.0));
                y = (y.0.min(p.1), y.1.max(p.1));
            }
        }
        ((x.0 - reach, x.1 + reach), (y.0 - reach, y.1 + reach))
    }

    /// x-intervals on the line at `y` that hold every point within `reach` of the arc
    /// (and some more: the ring of the arc's circle, within the arc's rectangle).
    pub fn row_cover(&self, y: f64, reach: f64) -> RowIntervals<2> {
        self.row_cover_within(y, reach, self.bounds(reach).0)
    }

    /// [`ArcSweep::row_cover`], with the x range of the arc's rectangle for `reach`
    /// ([`ArcSweep::bounds`]) found once for all rows.
    pub fn row_cover_within(&self, y: f64, reach: f64, (x_lo, x_hi): (f64, f64)) -> RowIntervals<2> {
        let mut out = RowIntervals::new();
        for (lo, hi) in self.ring(y, (self.radius_mm - reach).max(0.0), self.radius_mm + reach).iter() {
            out.add(lo.max(x_lo), hi.min(x_hi));
        }
        out
    }

    /// x-intervals on the line at `y` of points within `reach` of the arc (only such
    /// points: the discs about its ends, and its ring within its wedge).
    pub fn row_inside(&self, y: f64, reach: f64) -> RowIntervals<4> {
        let mut out = RowIntervals::new();
        if reach <= 0.0 {
            return out;
        }
        for end in [self.a, self.b] {
            let dy = y - end.1;
            let h2 = reach * reach - dy * dy;
            if h2 > 0.0 {
                let h = h2.sqrt();
                out.add(end.0 - h, end.0 + h);
            }
        }
        if let Some((w_lo, w_hi)) = self.wedge_row(y) {
            for (lo, hi) in self.ring(y, (self.radius_mm - reach).max(0.0), self.radius_mm + reach).iter() {
                out.add(lo.max(w_lo), hi.min(w_hi));
            }
        }
        out
    }

    /// The x-intervals of the ring between radii `inner` and `outer` about the centre on
    /// the line at `y`.
    fn ring(&self, y: f64, inner: f64, outer: f64) -> RowIntervals<2> {
        let mut out = RowIntervals::new();
        let dy = y - self.center.1;
        let h_out2 = outer * outer - dy * dy;
        if h_out2 <= 0.0 {
            return out;
        }
        let (cx, h_out) = (self.center.0, h_out2.sqrt());
        let h_in2 = inner * inner - dy * dy;
        if h_in2 > 0.0 {
            let h_in = h_in2.sqrt();
            out.add(cx - h_out, cx - h_in);
            out.add(cx + h_in, cx + h_out);
        } else {
            out.add(cx - h_out, cx + h_out);
        }
        out
    }

    /// The x-interval of the arc's wedge on the line at `y` (the wedge is convex), if any.
    fn wedge_row(&self, y: f64) -> Option<(f64, f64)> {
        let dy = y - self.center.1;
        let (mut lo, mut hi) = (f64::NEG_INFINITY, f64::INFINITY);
        // lo × v ≥ 0: lo.x·dy ≥ lo.y·u, u = x − cx.
        let (l, h) = (self.lo, self.hi);
        if l.1.abs() > DEGENERATE_SEGMENT_MM {
            let u = l.0 * dy / l.1;
            if l.1 > 0.0 {
                hi = hi.min(u);
            } else {
                lo = lo.max(u);
            }
        } else if l.0 * dy < 0.0 {
            return None;
        }
        // v × hi ≥ 0: u·hi.y ≥ dy·hi.x.
        if h.1.abs() > DEGENERATE_SEGMENT_MM {
            let u = dy * h.0 / h.1;
            if h.1 > 0.0 {
                lo = lo.max(u);
            } else {
                hi = hi.min(u);
            }
        } else if dy * h.0 > 0.0 {
            return None;
        }
        // Not opposite the arc: u·m.x + dy·m.y ≥ 0, m = lo + hi.
        let m = (l.0 + h.0, l.1 + h.1);
        if m.0.abs() > DEGENERATE_SEGMENT_MM {
            let u = -dy * m.1 / m.0;
            if m.0 > 0.0 {
                lo = lo.max(u);
            } else {
                hi = hi.min(u);
            }
        } else if dy * m.1 < 0.0 {
            return None;
        }
        (lo < hi).then_some((self.center.0 + lo, self.center.0 + hi))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// The distance to the arc by walking along it.
    fn walked_distance(arc: &ArcSweep, center: (f64, f64), start_rad: f64, sweep_rad: f64, q: (f64, f64)) -> f64 {
        (0..=4000)
            .map(|k| {
                let t = start_rad + sweep_rad * f64::from(k) / 4000.0;
                let p = (center.0 + arc.radius_mm * t.cos(), center.1 + arc.radius_mm * t.sin());
                (q.0 - p.0).hypot(q.1 - p.1)
            })
            .fold(f64::INFINITY, f64::min)
    }

    fn arc_of(center: (f64, f64), radius: f64, start_rad: f64, sweep_rad: f64) -> ArcSweep {
        let at = |t: f64| (center.0 + radius * t.cos(), center.1 + radius * t.sin());
        ArcSweep::new(center, at(start_rad), at(start_rad + sweep_rad), sweep_rad > 0.0)
    }

    #[test]
    fn an_arc_that_is_a_point_is_as_far_as_that_point_from_everywhere() {
        let arc = ArcSweep::new((1.0, 2.0), (4.0, 2.0), (4.0, 2.0), true);
        for q in [(4.0, 2.0), (-2.0, 2.0), (1.0, 2.0), (4.0, 6.0), (-3.0, -1.0)] {
            let d = (q.0 - 4.0f64).hypot(q.1 - 2.0);
            assert!((arc.distance(q) - d).abs() < 1e-12, "at {q:?}: {} against {d}", arc.distance(q));
        }
        let inside = arc.row_inside(2.0, 1.0);
        assert_eq!(inside.iter().collect::<Vec<_>>(), vec![(3.0, 5.0)]);
    }

    proptest! {
        #[test]
        fn the_distance_to_an_arc_is_the_distance_to_its_nearest_point(
            center in (-5.0..5.0f64, -5.0..5.0f64),
            radius in 0.1..20.0f64,
            start in 0.0..std::f64::consts::TAU,
            sweep in -MAX_ARC_SWEEP_RAD..MAX_ARC_SWEEP_RAD,
            q in (-30.0..30.0f64, -30.0..30.0f64),
        ) {
            prop_assume!(sweep.abs() > 1e-3);
            let arc = arc_of(center, radius, start, sweep);
            let walked = walked_distance(&arc, center, start, sweep, q);
            // The walk's points are 4000ths of the arc apart.
            let step = radius * sweep.abs() / 4000.0;
            prop_assert!((arc.distance(q) - walked).abs() <= step + 1e-9, "{} against {}", arc.distance(q), walked);
        }

        #[test]
        fn a_rows_cover_holds_every_point_near_the_arc_and_its_inside_only_such_points(
            center in (-5.0..5.0f64, -5.0..5.0f64),
            radius in 0.1..20.0f64,
            start in 0.0..std::f64::consts::TAU,
            sweep in -MAX_ARC_SWEEP_RAD..MAX_ARC_SWEEP_RAD,
            reach in 0.05..8.0f64,
            y in -30.0..30.0f64,
        ) {
            prop_assume!(sweep.abs() > 1e-3);
            let arc = arc_of(center, radius, start, sweep);
            let (cover, inside) = (arc.row_cover(y, reach), arc.row_inside(y, reach));
            for k in 0..=600 {
                let x = -30.0 + 60.0 * f64::from(k) / 600.0;
                let d = arc.distance((x, y));
                let covered = cover.iter().any(|(lo, hi)| (lo..=hi).contains(&x));
                let held = inside.iter().any(|(lo, hi)| (lo..=hi).contains(&x));
                prop_assert!(d > reach - 1e-9 || covered, "({x}, {y}) at {d} is not covered");
                prop_assert!(d < reach + 1e-9 || !held, "({x}, {y}) at {d} is held inside");
            }
        }
    }
}
