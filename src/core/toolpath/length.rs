//! Lengths and sweeps of moves: the geometry of the path's own motions, which the analysis,
//! the NC writer, the feed editor and the planners all measure with.

use super::{Motion, Move, Plane, P3};
use std::f64::consts::PI;

/// Signed sweep of an arc (radians): negative for clockwise.
pub fn arc_sweep(s: (f64, f64, f64), e: (f64, f64, f64), c: (f64, f64, f64), clockwise: bool, turns: u32) -> f64 {
    let a0 = (s.1 - c.1).atan2(s.0 - c.0);
    let a1 = (e.1 - c.1).atan2(e.0 - c.0);
    let mut sweep = a1 - a0;
    if clockwise {
        while sweep >= -1e-12 {
            sweep -= 2.0 * PI;
        }
        sweep -= 2.0 * PI * f64::from(turns);
    } else {
        while sweep <= 1e-12 {
            sweep += 2.0 * PI;
        }
        sweep += 2.0 * PI * f64::from(turns);
    }
    sweep
}

/// A point as (u, v, axial) coordinates of an arc's plane.
pub type PlanePoint = (f64, f64, f64);

/// Start, end and centre as (u, v, axial) in the arc's plane.
pub fn in_plane(s: P3, e: P3, c: P3, plane: Plane) -> (PlanePoint, PlanePoint, PlanePoint) {
    let f = |p: P3| match plane {
        Plane::Xy => (p.x, p.y, p.z),
        Plane::Zx => (p.z, p.x, p.y),
        Plane::Yz => (p.y, p.z, p.x),
    };
    (f(s), f(e), f(c))
}

/// Length of a move, mm.
pub fn move_length(m: &Move) -> f64 {
    match m.motion {
        Motion::Rapid | Motion::Linear => {
            ((m.end.x - m.start.x).powi(2) + (m.end.y - m.start.y).powi(2) + (m.end.z - m.start.z).powi(2)).sqrt()
        }
        Motion::Arc { center, clockwise, plane, turns } => {
            let (s, e, c) = in_plane(m.start, m.end, center, plane);
            let r = (s.0 - c.0).hypot(s.1 - c.1);
            let planar = r * arc_sweep(s, e, c, clockwise, turns).abs();
            planar.hypot(e.2 - s.2)
        }
    }
}
