//! Feed moves that continue one another: a straight line split into pieces along itself,
//! or an arc or helix split into pieces about the same centre. The choice of the stock's
//! slice levels (see [`super::levels`]) takes such a run as the one move it is, so that the
//! slices do not depend on how a CAM system or a planner split the path.

use crate::core::toolpath::{arc_sweep, in_plane, Motion, Move, Plane, PlanePoint, P3};

/// Two moves continue one another when the joint, the centres, the radii and the helix's
/// rise lie this close to what one move would have, mm: NC programs write coordinates to
/// a micrometre, so a move split in a program is off its line by up to half of that.
pub const CONTINUATION_TOLERANCE_MM: f64 = 1e-3;

/// `true` when feed move `b`, right after feed move `a`, goes on as `a` went: the same
/// straight line in the same direction, or the same arc or helix (same plane, centre,
/// radius, direction and rise per radian).
pub fn continues(a: &Move, b: &Move) -> bool {
    if distance(a.end, b.start) > CONTINUATION_TOLERANCE_MM {
        return false;
    }
    match (a.motion, b.motion) {
        (Motion::Linear, Motion::Linear) => along_one_line(a, b),
        (
            Motion::Arc { center: ca, clockwise: cw_a, plane: pa, turns: ta },
            Motion::Arc { center: cb, clockwise: cw_b, plane: pb, turns: tb },
        ) if pa == pb && cw_a == cw_b => {
            let first = ArcPiece::of(a, ca, cw_a, pa, ta);
            let second = ArcPiece::of(b, cb, cw_b, pb, tb);
            first.goes_on_as(&second)
        }
        _ => false,
    }
}

/// `true` when straight moves `a` and `b` run one way along one line: the joint lies on
/// the chord from `a`'s start to `b`'s end, and `b` does not turn back.
fn along_one_line(a: &Move, b: &Move) -> bool {
    let (u, v) = (minus(a.end, a.start), minus(b.end, b.start));
    let forward = u.0 * v.0 + u.1 * v.1 + u.2 * v.2 > 0.0;
    forward && off_chord(a.start, b.end, a.end) <= CONTINUATION_TOLERANCE_MM
}

/// An arc move in its plane's coordinates (u, v, axial).
struct ArcPiece {
    start: PlanePoint,
    end: PlanePoint,
    center: PlanePoint,
    /// Signed sweep, radians.
    sweep: f64,
}

impl ArcPiece {
    /// Arc move `m` about `center`, in `plane`.
    fn of(m: &Move, center: P3, clockwise: bool, plane: Plane, turns: u32) -> ArcPiece {
        let (start, end, center) = in_plane(m.start, m.end, center, plane);
        ArcPiece { start, end, center, sweep: arc_sweep(start, end, center, clockwise, turns) }
    }

    /// The radius at the start, mm.
    fn radius(&self) -> f64 {
        (self.start.0 - self.center.0).hypot(self.start.1 - self.center.1)
    }

    /// `true` when `next` lies on this arc's circle (or helix) carried on: the same centre
    /// and radius in the plane, and the same rise per radian along the axis.
    fn goes_on_as(&self, next: &ArcPiece) -> bool {
        let tol = CONTINUATION_TOLERANCE_MM;
        let same_center = (self.center.0 - next.center.0).hypot(self.center.1 - next.center.1) <= tol;
        let same_radius = (self.radius() - next.radius()).abs() <= tol;
        let rise_per_radian = (self.end.2 - self.start.2) / self.sweep;
        let same_rise = (next.start.2 + rise_per_radian * next.sweep - next.end.2).abs() <= tol;
        same_center && same_radius && same_rise
    }
}

/// `b - a`, as a tuple.
fn minus(b: P3, a: P3) -> (f64, f64, f64) {
    (b.x - a.x, b.y - a.y, b.z - a.z)
}

/// Distance between two points, mm.
fn distance(a: P3, b: P3) -> f64 {
    let d = minus(b, a);
    (d.0 * d.0 + d.1 * d.1 + d.2 * d.2).sqrt()
}

/// Distance of `p` from the segment from `a` to `b`, mm.
fn off_chord(a: P3, b: P3, p: P3) -> f64 {
    let (ab, ap) = (minus(b, a), minus(p, a));
    let length_sq = ab.0 * ab.0 + ab.1 * ab.1 + ab.2 * ab.2;
    let t = if length_sq > 0.0 { ((ap.0 * ab.0 + ap.1 * ab.1 + ap.2 * ab.2) / length_sq).clamp(0.0, 1.0) } else { 0.0 };
    distance(p, P3::new(a.x + t * ab.0, a.y + t * ab.1, a.z + t * ab.2))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A feed move of `motion` from `start` to `end`.
    fn feed(motion: Motion, start: P3, end: P3) -> Move {
        Move { motion, start, end, feed_mm_min: Some(100.0), spindle_rpm: None, tool: None, line: 1 }
    }

    /// A counter-clockwise arc in XY about `center`.
    fn ccw(center: P3) -> Motion {
        Motion::Arc { center, clockwise: false, plane: Plane::Xy, turns: 0 }
    }

    #[test]
    fn a_ramp_split_along_itself_continues_and_one_that_bends_or_turns_back_does_not() {
        let (a, m, b) = (P3::new(0.0, 0.0, 0.0), P3::new(5.0, 0.0, -1.0), P3::new(10.0, 0.0, -2.0));
        assert!(continues(&feed(Motion::Linear, a, m), &feed(Motion::Linear, m, b)));
        // Rounded to a micrometre in the program, still one ramp.
        let rounded = P3::new(5.0004, 0.0, -1.0003);
        assert!(continues(&feed(Motion::Linear, a, rounded), &feed(Motion::Linear, rounded, b)));
        assert!(!continues(&feed(Motion::Linear, a, m), &feed(Motion::Linear, m, P3::new(10.0, 0.0, -1.0))));
        assert!(!continues(&feed(Motion::Linear, a, m), &feed(Motion::Linear, m, a)));
    }

    #[test]
    fn a_helix_split_about_its_centre_continues_and_one_that_changes_its_rise_does_not() {
        let c = P3::new(0.0, 0.0, 0.0);
        let (a, m, b) = (P3::new(5.0, 0.0, 0.0), P3::new(0.0, 5.0, -0.5), P3::new(-5.0, 0.0, -1.0));
        let first = feed(ccw(c), a, m);
        assert!(continues(&first, &feed(ccw(P3::new(0.0, 0.0, -0.5)), m, b)));
        assert!(!continues(&first, &feed(ccw(P3::new(0.0, 0.0, -0.5)), m, P3::new(-5.0, 0.0, -0.5))));
        let clockwise = Motion::Arc { center: c, clockwise: true, plane: Plane::Xy, turns: 0 };
        assert!(!continues(&first, &feed(clockwise, m, b)));
        assert!(!continues(&first, &feed(Motion::Linear, m, b)));
    }
}
