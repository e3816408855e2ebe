//! Where a program's tool tip turns in z: the levels its non-flat feed moves (ramps,
//! helices, 3-D surface moves, arcs in the XZ and YZ planes) give the slices (see
//! [`super::slices::slice_levels`]).
//!
//! Consecutive connected non-flat moves form one course of the tip. Its levels are where
//! it starts and ends and where it turns from going down to going up or back (a local
//! extreme of z along it, at a joint or inside an arc in a vertical plane). A move split
//! in two adds a joint the course passes straight through, so the levels do not depend on
//! how the program's moves are split (issue 32: the same path gave α 130.5° or 178.5°
//! when a ramp's pieces each added a level).

use crate::core::toolpath::{arc_sweep, in_plane, move_length, Motion, Move, Plane, Toolpath};
use std::f64::consts::{FRAC_PI_2, PI};

/// Moves whose ends lie this close in every coordinate are connected, mm.
const CONNECTED_MM: f64 = 1e-9;
/// A move whose ends are this close in z cuts at one level, mm (see [`cuts_flat`]).
pub const FLAT_Z_MM: f64 = 1e-6;
/// An extreme of an arc this close to one of its ends is that end, rad.
const EXTREME_AT_END_RAD: f64 = 1e-12;

/// `true` when the move cuts at one z level: a line or an arc in the XY plane whose ends
/// lie at the same height.
pub fn cuts_flat(m: &Move) -> bool {
    let in_xy = match m.motion {
        Motion::Linear => true,
        Motion::Arc { plane, .. } => plane == Plane::Xy,
        Motion::Rapid => false,
    };
    in_xy && (m.end.z - m.start.z).abs() <= FLAT_Z_MM
}

/// How a non-flat move's tip goes in z: which way at its start and at its end (−1 down,
/// +1 up, 0 level), and the z of the extremes it passes inside.
struct Course {
    start_dir: f64,
    end_dir: f64,
    extremes: Vec<f64>,
}

/// The course of the non-flat feed move `m`.
fn course(m: &Move) -> Course {
    let Motion::Arc { center, clockwise, plane, turns } = m.motion else {
        let dir = (m.end.z - m.start.z).signum();
        return Course { start_dir: dir, end_dir: dir, extremes: Vec::new() };
    };
    // In the plane's coordinates (u, v, normal) of `in_plane`: z is the normal in XY
    // (a helix: monotone), u in ZX (z = c + r·cos a) and v in YZ (z = c + r·sin a).
    let (s, e, c) = in_plane(m.start, m.end, center, plane);
    let (phase, cz) = match plane {
        Plane::Xy => {
            let dir = (m.end.z - m.start.z).signum();
            return Course { start_dir: dir, end_dir: dir, extremes: Vec::new() };
        }
        Plane::Zx => (0.0, c.0),
        Plane::Yz => (FRAC_PI_2, c.1),
    };
    let r = (s.0 - c.0).hypot(s.1 - c.1);
    let a0 = (s.1 - c.1).atan2(s.0 - c.0);
    let sweep = arc_sweep(s, e, c, clockwise, turns);
    // z = cz + r·cos(a − phase): dz/da = −r·sin(a − phase); its extremes lie at
    // a = phase + kπ.
    let dir = |a: f64| (-(a - phase).sin() * sweep.signum()).signum();
    let (lo, hi) = if sweep > 0.0 { (a0, a0 + sweep) } else { (a0 + sweep, a0) };
    // The angles the tip passes, in the order it travels: its start, the extremes inside,
    // its end. Between two of them z goes one way, so the way at an end is the way midway
    // to the next of them (an end may be an extreme itself).
    let mut angles = vec![a0];
    let mut k = ((lo - phase) / PI).floor();
    let mut inside = Vec::new();
    loop {
        let a = phase + k * PI;
        if a >= hi - EXTREME_AT_END_RAD {
            break;
        }
        if a > lo + EXTREME_AT_END_RAD {
            inside.push(a);
        }
        k += 1.0;
    }
    if sweep < 0.0 {
        inside.reverse();
    }
    angles.extend(&inside);
    angles.push(a0 + sweep);
    let n = angles.len();
    Course {
        start_dir: dir((angles[0] + angles[1]) / 2.0),
        end_dir: dir((angles[n - 2] + angles[n - 1]) / 2.0),
        extremes: inside.iter().map(|a| cz + r * (a - phase).cos()).collect(),
    }
}

/// The z levels of the courses of `path`'s non-flat feed moves: each course's start and
/// end, and every z where it turns (see the module's doc).
pub fn course_levels(path: &Toolpath) -> Vec<f64> {
    let mut levels = Vec::new();
    // The last move of the course being followed, and which way it ends.
    let mut open: Option<(&Move, f64)> = None;
    for m in &path.moves {
        let non_flat = !matches!(m.motion, Motion::Rapid) && !cuts_flat(m) && move_length(m) > 0.0;
        if !non_flat {
            if let Some((last, _)) = open.take() {
                levels.push(last.end.z);
            }
            continue;
        }
        let c = course(m);
        match open {
            Some((last, end_dir)) if connected(last, m) => {
                if end_dir * c.start_dir < 0.0 {
                    levels.push(m.start.z);
                }
            }
            Some((last, _)) => {
                levels.push(last.end.z);
                levels.push(m.start.z);
            }
            None => levels.push(m.start.z),
        }
        levels.extend(c.extremes);
        open = Some((m, c.end_dir));
    }
    if let Some((last, _)) = open {
        levels.push(last.end.z);
    }
    levels
}

/// `true` when `b` starts where `a` ends.
fn connected(a: &Move, b: &Move) -> bool {
    (a.end.x - b.start.x).abs() <= CONNECTED_MM
        && (a.end.y - b.start.y).abs() <= CONNECTED_MM
        && (a.end.z - b.start.z).abs() <= CONNECTED_MM
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::core::toolpath::{Units, P3};
    use proptest::prelude::*;

    fn feed(motion: Motion, start: P3, end: P3) -> Move {
        Move { motion, start, end, feed_mm_min: Some(500.0), spindle_rpm: None, tool: None, line: 1 }
    }

    fn program(moves: Vec<Move>) -> Toolpath {
        Toolpath { moves, events: vec![], source_units: Units::Mm, warnings: vec![] }
    }

    /// The polyline through `points`, one linear feed move per pair.
    fn polyline(points: &[P3]) -> Vec<Move> {
        points.windows(2).map(|w| feed(Motion::Linear, w[0], w[1])).collect()
    }

    fn sorted(mut levels: Vec<f64>) -> Vec<f64> {
        levels.sort_by(f64::total_cmp);
        levels
    }

    #[test]
    fn a_ramp_gives_its_two_ends_however_many_moves_write_it() {
        let whole = polyline(&[P3::new(0.0, 0.0, 0.0), P3::new(30.0, 0.0, -6.0)]);
        let pieces: Vec<P3> =
            (0..=7).map(|i| P3::new(30.0 * f64::from(i) / 7.0, 0.0, -6.0 * f64::from(i) / 7.0)).collect();
        assert_eq!(sorted(course_levels(&program(whole))), vec![-6.0, 0.0]);
        assert_eq!(sorted(course_levels(&program(polyline(&pieces)))), vec![-6.0, 0.0]);
    }

    #[test]
    fn a_surface_pass_gives_every_level_it_turns_at() {
        let points =
            [(0.0, 0.0), (5.0, -2.0), (10.0, -1.0), (15.0, -3.0), (20.0, -3.5)].map(|(x, z)| P3::new(x, 0.0, z));
        assert_eq!(sorted(course_levels(&program(polyline(&points)))), vec![-3.5, -2.0, -1.0, 0.0]);
    }

    #[test]
    fn a_helix_of_several_turns_gives_its_two_ends() {
        let helix = |z0: f64, z1: f64| {
            feed(
                Motion::Arc { center: P3::new(0.0, 0.0, z0), clockwise: false, plane: Plane::Xy, turns: 0 },
                P3::new(4.0, 0.0, z0),
                P3::new(4.0, 0.0, z1),
            )
        };
        let moves = vec![helix(0.0, -1.0), helix(-1.0, -2.0), helix(-2.0, -3.0)];
        assert_eq!(sorted(course_levels(&program(moves))), vec![-3.0, 0.0]);
    }

    #[test]
    fn an_arc_in_a_vertical_plane_gives_the_bottom_it_passes() {
        // G18 from (−5, 0, 0) to (5, 0, 0) about (0, 0, 0): down through z = −5 and up (G2 in
        // the ZX plane's turning sense, where G3 passes over the top).
        let g18 = |clockwise: bool, start: P3, end: P3| {
            feed(Motion::Arc { center: P3::new(0.0, 0.0, 0.0), clockwise, plane: Plane::Zx, turns: 0 }, start, end)
        };
        let (left, right) = (P3::new(-5.0, 0.0, 0.0), P3::new(5.0, 0.0, 0.0));
        let bottom = P3::new(0.0, 0.0, -5.0);
        let whole = sorted(course_levels(&program(vec![g18(true, left, right)])));
        let other_way = sorted(course_levels(&program(vec![g18(false, left, right)])));
        // Split at its bottom: the bottom is then where the two halves meet.
        let halves = sorted(course_levels(&program(vec![g18(true, left, bottom), g18(true, bottom, right)])));
        assert!(whole.len() == 3 && (whole[0] + 5.0).abs() < 1e-9, "{whole:?}");
        assert!(
            other_way.len() == 3 && (other_way[2] - 5.0).abs() < 1e-9,
            "the other way passes the top: {other_way:?}"
        );
        assert_eq!(whole.len(), halves.len());
        assert!(whole.iter().zip(&halves).all(|(a, b)| (a - b).abs() < 1e-9), "{whole:?} against {halves:?}");
    }

    #[test]
    fn flat_moves_rapids_and_gaps_end_a_course() {
        let mut moves = polyline(&[P3::new(0.0, 0.0, 0.0), P3::new(5.0, 0.0, -1.0)]);
        moves.extend(polyline(&[P3::new(5.0, 0.0, -1.0), P3::new(9.0, 0.0, -1.0)]));
        moves.extend(polyline(&[P3::new(9.0, 0.0, -1.0), P3::new(12.0, 0.0, -2.0)]));
        // A gap: the next ramp starts elsewhere, a little lower.
        moves.extend(polyline(&[P3::new(20.0, 0.0, -2.5), P3::new(25.0, 0.0, -4.0)]));
        assert_eq!(sorted(course_levels(&program(moves))), vec![-4.0, -2.5, -2.0, -1.0, -1.0, 0.0]);
    }

    proptest! {
        #[test]
        fn splitting_moves_anywhere_changes_no_level(
            zs in proptest::collection::vec(-10.0f64..0.0, 2..12),
            splits in proptest::collection::vec((0usize..12, 0.05f64..0.95), 0..12),
        ) {
            let points: Vec<P3> = zs.iter().enumerate().map(|(i, &z)| P3::new(3.0 * i as f64, 0.0, z)).collect();
            let mut split_points = points.clone();
            for (at, t) in splits {
                let i = at % (split_points.len() - 1);
                let (a, b) = (split_points[i], split_points[i + 1]);
                split_points.insert(i + 1, P3::new(a.x + t * (b.x - a.x), a.y, a.z + t * (b.z - a.z)));
            }
            let (whole, split) = (course_levels(&program(polyline(&points))), course_levels(&program(polyline(&split_points))));
            let mut whole = sorted(whole);
            let mut split = sorted(split);
            whole.dedup_by(|a, b| (*a - *b).abs() < 1e-9);
            split.dedup_by(|a, b| (*a - *b).abs() < 1e-9);
            prop_assert_eq!(whole.len(), split.len(), "{:?} against {:?}", whole, split);
            prop_assert!(whole.iter().zip(&split).all(|(a, b)| (a - b).abs() < 1e-9), "{:?} against {:?}", whole, split);
        }
    }
}
