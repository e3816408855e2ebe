//! A piece of a move: the part of a line, arc or helix between two fractions of its
//! length, as a move of the same kind (arcs stay arcs, about the same centre).

use crate::core::analysis::sampling::point_on;
use crate::core::toolpath::arc_sweep;
use crate::core::toolpath::{Motion, Move, Plane, P3};
use std::f64::consts::TAU;

/// Sweeps within this of a whole number of turns are whole turns, rad.
const WHOLE_TURN_TOLERANCE_RAD: f64 = 1e-9;

/// The part of `m` from `t0` to `t1` (fractions of its length, `0 ≤ t0 < t1 ≤ 1`).
/// The whole move (`0, 1`) is returned unchanged, so unsplit moves keep their exact
/// coordinates.
pub fn sub_move(m: &Move, t0: f64, t1: f64) -> Move {
    let whole = t0 <= 0.0 && t1 >= 1.0;
    if whole {
        return *m;
    }
    let start = if t0 <= 0.0 { m.start } else { point_on(m, t0).0 };
    let end = if t1 >= 1.0 { m.end } else { point_on(m, t1).0 };
    let motion = match m.motion {
        Motion::Rapid | Motion::Linear => m.motion,
        Motion::Arc { center, clockwise, plane, turns } => {
            let sweep = full_sweep(m, center, clockwise, plane, turns) * (t1 - t0);
            let whole_turns = (sweep.abs() / TAU + WHOLE_TURN_TOLERANCE_RAD).floor();
            let remainder = sweep.abs() - whole_turns * TAU;
            // A piece of whole turns ends where it starts (a full circle and more turns);
            // otherwise the remainder is a plain arc after the whole turns.
            let (end, turns) = if remainder.abs() < WHOLE_TURN_TOLERANCE_RAD && whole_turns >= 1.0 {
                (with_plane_coords_of(end, start, plane), whole_turns as u32 - 1)
            } else {
                (end, whole_turns as u32)
            };
            let center = with_axial_of(center, start, plane);
            return Move { motion: Motion::Arc { center, clockwise, plane, turns }, start, end, ..*m };
        }
    };
    Move { motion, start, end, ..*m }
}

/// The signed sweep of an arc move, rad.
fn full_sweep(m: &Move, center: P3, clockwise: bool, plane: Plane, turns: u32) -> f64 {
    let f = |p: P3| match plane {
        Plane::Xy => (p.x, p.y, p.z),
        Plane::Zx => (p.z, p.x, p.y),
        Plane::Yz => (p.y, p.z, p.x),
    };
    arc_sweep(f(m.start), f(m.end), f(center), clockwise, turns)
}

/// `p` with the in-plane coordinates of `q` (its axial coordinate kept).
fn with_plane_coords_of(p: P3, q: P3, plane: Plane) -> P3 {
    match plane {
        Plane::Xy => P3::new(q.x, q.y, p.z),
        Plane::Zx => P3::new(q.x, p.y, q.z),
        Plane::Yz => P3::new(p.x, q.y, q.z),
    }
}

/// `c` with the axial coordinate of `p` (an arc's centre lies in its start's plane).
fn with_axial_of(c: P3, p: P3, plane: Plane) -> P3 {
    match plane {
        Plane::Xy => P3::new(c.x, c.y, p.z),
        Plane::Zx => P3::new(c.x, p.y, c.z),
        Plane::Yz => P3::new(p.x, c.y, c.z),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::core::tolerance::approx_eq;
    use crate::core::toolpath::move_length;

    fn mv(motion: Motion, start: P3, end: P3) -> Move {
        Move { motion, start, end, feed_mm_min: Some(1000.0), spindle_rpm: Some(9600.0), tool: None, line: 7 }
    }

    fn close(a: P3, b: P3) -> bool {
        (a.x - b.x).abs() < 1e-9 && (a.y - b.y).abs() < 1e-9 && (a.z - b.z).abs() < 1e-9
    }

    #[test]
    fn pieces_of_a_line_join_up_and_keep_its_length() {
        let m = mv(Motion::Linear, P3::new(0.0, 0.0, 0.0), P3::new(10.0, 5.0, -2.0));
        let (a, b) = (sub_move(&m, 0.0, 0.3), sub_move(&m, 0.3, 1.0));
        assert!(close(a.end, b.start) && close(a.start, m.start) && close(b.end, m.end));
        assert!(approx_eq(move_length(&a) + move_length(&b), move_length(&m), 1e-9));
        assert_eq!(a.line, 7);
    }

    #[test]
    fn pieces_of_a_helix_stay_arcs_about_the_same_axis() {
        let arc = Motion::Arc { center: P3::new(0.0, 0.0, 0.0), clockwise: true, plane: Plane::Xy, turns: 0 };
        let m = mv(arc, P3::new(10.0, 0.0, 0.0), P3::new(0.0, -10.0, -3.0));
        let b = sub_move(&m, 0.5, 1.0);
        let Motion::Arc { center, clockwise, turns, .. } = b.motion else { panic!("not an arc") };
        assert!(clockwise && turns == 0);
        assert!(close(center, P3::new(0.0, 0.0, -1.5)), "{center:?}");
        assert!(approx_eq(b.start.x.hypot(b.start.y), 10.0, 1e-9));
        assert!(approx_eq(move_length(&b) * 2.0, move_length(&m), 1e-9));
    }

    #[test]
    fn a_piece_of_a_multi_turn_helix_keeps_its_whole_turns() {
        // Three turns down 6 mm, split after one and a half turns.
        let arc = Motion::Arc { center: P3::new(0.0, 0.0, 0.0), clockwise: false, plane: Plane::Xy, turns: 2 };
        let m = mv(arc, P3::new(5.0, 0.0, 0.0), P3::new(5.0, 0.0, -6.0));
        let (a, b) = (sub_move(&m, 0.0, 0.5), sub_move(&m, 0.5, 1.0));
        for piece in [a, b] {
            let Motion::Arc { turns, .. } = piece.motion else { panic!("not an arc") };
            assert_eq!(turns, 1);
            assert!(approx_eq(move_length(&piece) * 2.0, move_length(&m), 1e-9));
        }
        assert!(close(a.end, P3::new(-5.0, 0.0, -3.0)), "{:?}", a.end);
    }

    #[test]
    fn a_piece_of_whole_turns_is_a_full_circle() {
        let arc = Motion::Arc { center: P3::new(0.0, 0.0, 0.0), clockwise: true, plane: Plane::Xy, turns: 1 };
        let m = mv(arc, P3::new(5.0, 0.0, 0.0), P3::new(5.0, 0.0, -2.0));
        let a = sub_move(&m, 0.0, 0.5);
        let Motion::Arc { turns, .. } = a.motion else { panic!("not an arc") };
        assert_eq!(turns, 0);
        assert!(close(a.end, P3::new(5.0, 0.0, -1.0)), "{:?}", a.end);
        assert!(approx_eq(move_length(&a) * 2.0, move_length(&m), 1e-9));
    }
}
