//! Arcs with extra turns for controls that have no turn count on G2/G3 (Fanuc): the same
//! motion as full circles followed by the plain arc.

use std::f64::consts::TAU;

use crate::core::nc::arcs::{coord, plane_axes, with_coord};
use crate::core::toolpath::arc_sweep;
use crate::core::toolpath::{Motion, Move};

/// The pieces of `m`: for an arc with `turns` = k > 0, k full circles from its start, then
/// the plain arc to its end, each with `turns` = 0. A helix keeps its pitch: the axial
/// advance of each piece is proportional to its sweep, so the pieces trace the same helix.
/// Any other move is returned as it is.
pub(crate) fn split_turns(m: &Move) -> Vec<Move> {
    let Motion::Arc { center, clockwise, plane, turns } = m.motion else {
        return vec![*m];
    };
    if turns == 0 {
        return vec![*m];
    }
    let [a, b, n] = plane_axes(plane);
    let in_plane = |p| (coord(p, a), coord(p, b), coord(p, n));
    let total_sweep = arc_sweep(in_plane(m.start), in_plane(m.end), in_plane(center), clockwise, turns).abs();
    let start_axial = coord(m.start, n);
    let axial_per_turn = (coord(m.end, n) - start_axial) * TAU / total_sweep;
    let at_turn = |k: u32| with_coord(m.start, n, start_axial + axial_per_turn * f64::from(k));
    let piece = |start, end| {
        let center = with_coord(center, n, coord(start, n));
        Move { motion: Motion::Arc { center, clockwise, plane, turns: 0 }, start, end, ..*m }
    };
    let mut pieces: Vec<Move> = (0..turns).map(|k| piece(at_turn(k), at_turn(k + 1))).collect();
    pieces.push(piece(at_turn(turns), m.end));
    pieces
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::core::tolerance::approx_eq;
    use crate::core::toolpath::move_length;
    use crate::core::toolpath::{Plane, P3};

    /// The pieces are computed from the same numbers: equal to rounding.
    const TOL: f64 = 1e-9;

    fn helix(turns: u32, plane: Plane) -> Move {
        // Quarter arc about the origin from +a to +b, descending 10 mm along the normal.
        let [a, b, n] = plane_axes(plane);
        let start = with_coord(with_coord(P3::default(), a, 5.0), n, 2.0);
        let end = with_coord(with_coord(P3::default(), b, 5.0), n, -8.0);
        let center = with_coord(P3::default(), n, 2.0);
        Move {
            motion: Motion::Arc { center, clockwise: false, plane, turns },
            start,
            end,
            feed_mm_min: Some(500.0),
            spindle_rpm: Some(9000.0),
            tool: Some(4),
            line: 12,
        }
    }

    #[test]
    fn a_helix_with_two_turns_becomes_two_full_circles_and_the_plain_arc_with_the_same_pitch() {
        for plane in [Plane::Xy, Plane::Zx, Plane::Yz] {
            let m = helix(2, plane);
            let pieces = split_turns(&m);
            assert_eq!(pieces.len(), 3);
            let [_, _, n] = plane_axes(plane);
            // 2.25 turns over 10 mm: 40/9 mm per turn.
            let per_turn = -10.0 / 2.25;
            for (k, piece) in pieces.iter().enumerate() {
                assert!(approx_eq(coord(piece.start, n), 2.0 + per_turn * k as f64, TOL), "{plane:?} {k}");
                let Motion::Arc { center, turns, .. } = piece.motion else { panic!("not an arc") };
                assert_eq!(turns, 0);
                assert!(approx_eq(coord(center, n), coord(piece.start, n), TOL));
                assert_eq!((piece.feed_mm_min, piece.tool, piece.line), (m.feed_mm_min, m.tool, m.line));
            }
            assert_eq!(pieces[0].start, m.start);
            assert_eq!(pieces[2].end, m.end);
            let length: f64 = pieces.iter().map(move_length).sum();
            assert!(approx_eq(length, move_length(&m), 1e-6), "{length} vs {}", move_length(&m));
        }
    }

    #[test]
    fn a_plain_arc_and_a_line_are_returned_unchanged() {
        let m = helix(0, Plane::Xy);
        assert_eq!(split_turns(&m), vec![m]);
        let line = Move { motion: Motion::Linear, ..m };
        assert_eq!(split_turns(&line), vec![line]);
    }
}
