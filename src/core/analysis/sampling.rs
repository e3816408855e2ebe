//! Samples along a tool path at a fixed spacing, with position, direction, curvature,
//! programmed feed and source line (MODEL.md §6: "per sample").

use crate::core::curvature::{polyline_curvature, PointCurvature, DEFAULT_FIT_HALF_WIDTH_MM};
use crate::core::toolpath::{arc_sweep, in_plane, move_length, Motion, Move, Plane, Toolpath, P3};

/// Below this (mm) a move has no length in XY.
const MIN_XY_MM: f64 = 1e-9;

/// One point of the path to analyse.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sample {
    pub p: P3,
    /// Unit tangent in XY; (0, 0) for a plunge (no XY motion).
    pub heading: (f64, f64),
    /// Path length from the previous sample, mm.
    pub step_mm: f64,
    pub move_index: usize,
    pub line: u32,
    /// Programmed feed, mm/min (0 when none is programmed).
    pub feed_mm_min: f64,
    pub spindle_rpm: Option<f64>,
    pub rapid: bool,
    /// Curvature of the tool-centre path in XY.
    pub curvature: PointCurvature,
}

/// Position on `m` at parameter `t` ∈ [0, 1] (a fraction of its length), and its XY
/// tangent (not normalised).
pub fn point_on(m: &Move, t: f64) -> (P3, (f64, f64)) {
    MovePoints::of(m).at(t)
}

/// Places points along one move as [`point_on`] does, with what all its points share found
/// once (an arc's angles and radius need three arc tangents and a root): for loops over
/// the points of a move.
#[derive(Debug, Clone, Copy)]
pub struct MovePoints<'a> {
    m: &'a Move,
    arc: Option<ArcPoints>,
}

impl<'a> MovePoints<'a> {
    /// The points of `m`.
    pub fn of(m: &'a Move) -> MovePoints<'a> {
        MovePoints { m, arc: ArcPoints::of(m) }
    }

    /// The point at parameter `t` ∈ [0, 1] and its XY tangent, exactly as [`point_on`].
    pub fn at(&self, t: f64) -> (P3, (f64, f64)) {
        if let Some(arc) = &self.arc {
            return arc.at(t);
        }
        let m = self.m;
        let p = P3::new(
            m.start.x + (m.end.x - m.start.x) * t,
            m.start.y + (m.end.y - m.start.y) * t,
            m.start.z + (m.end.z - m.start.z) * t,
        );
        (p, (m.end.x - m.start.x, m.end.y - m.start.y))
    }
}

/// What places the points of an arc move, found once for all its points (the angles and
/// the radius need an arc tangent and a root each, which samples would find again).
#[derive(Debug, Clone, Copy)]
struct ArcPoints {
    /// Start, end and centre in the arc's plane.
    s: (f64, f64, f64),
    e: (f64, f64, f64),
    c: (f64, f64, f64),
    plane: Plane,
    /// Angle of the start about the centre, the angle swept (signed) and the radius.
    a0: f64,
    sweep: f64,
    r: f64,
}

impl ArcPoints {
    /// The arc of `m`, unless it is a line or a rapid.
    fn of(m: &Move) -> Option<ArcPoints> {
        let Motion::Arc { center, clockwise, plane, turns } = m.motion else {
            return None;
        };
        let (s, e, c) = in_plane(m.start, m.end, center, plane);
        let a0 = (s.1 - c.1).atan2(s.0 - c.0);
        let sweep = arc_sweep(s, e, c, clockwise, turns);
        let r = (s.0 - c.0).hypot(s.1 - c.1);
        Some(ArcPoints { s, e, c, plane, a0, sweep, r })
    }

    /// The point at parameter `t` and its XY tangent, as [`point_on`].
    fn at(&self, t: f64) -> (P3, (f64, f64)) {
        let ArcPoints { s, e, c, plane, a0, sweep, r } = *self;
        let a = a0 + sweep * t;
        let (u, v) = (c.0 + r * a.cos(), c.1 + r * a.sin());
        let axial = s.2 + (e.2 - s.2) * t;
        let du = (-r * a.sin() * sweep, r * a.cos() * sweep);
        let d_axial = e.2 - s.2;
        let (p, d) = from_plane((u, v, axial), (du.0, du.1, d_axial), plane);
        (p, (d.0, d.1))
    }
}

fn from_plane(p: (f64, f64, f64), d: (f64, f64, f64), plane: Plane) -> (P3, (f64, f64, f64)) {
    match plane {
        Plane::Xy => (P3::new(p.0, p.1, p.2), (d.0, d.1, d.2)),
        Plane::Zx => (P3::new(p.1, p.2, p.0), (d.1, d.2, d.0)),
        Plane::Yz => (P3::new(p.2, p.0, p.1), (d.2, d.0, d.1)),
    }
}

/// Curvature at the start and end of every move: exact on XY arcs, from the polynomial
/// fit (seed 000 §2) over runs of consecutive linear feed moves.
pub fn move_curvatures(path: &Toolpath) -> Vec<(PointCurvature, PointCurvature)> {
    let moves = &path.moves;
    let mut out = vec![(PointCurvature::STRAIGHT, PointCurvature::STRAIGHT); moves.len()];
    let mut i = 0;
    while i < moves.len() {
        let is_run_move = |m: &Move| {
            matches!(m.motion, Motion::Linear) && (m.end.x - m.start.x).hypot(m.end.y - m.start.y) > MIN_XY_MM
        };
        if let Motion::Arc { center, clockwise, plane: Plane::Xy, .. } = moves[i].motion {
            let r = (moves[i].start.x - center.x).hypot(moves[i].start.y - center.y);
            let k = PointCurvature { kappa: if clockwise { -1.0 / r } else { 1.0 / r }, corner: false };
            out[i] = (k, k);
            i += 1;
            continue;
        }
        if !is_run_move(&moves[i]) {
            i += 1;
            continue;
        }
        let start = i;
        while i < moves.len() && is_run_move(&moves[i]) && (i == start || connected(&moves[i - 1], &moves[i])) {
            i += 1;
        }
        let mut pts: Vec<(f64, f64)> = Vec::with_capacity(i - start + 1);
        pts.push((moves[start].start.x, moves[start].start.y));
        pts.extend(moves[start..i].iter().map(|m| (m.end.x, m.end.y)));
        let k = polyline_curvature(&pts, DEFAULT_FIT_HALF_WIDTH_MM);
        for (n, slot) in out[start..i].iter_mut().enumerate() {
            *slot = (k[n], k[n + 1]);
        }
    }
    out
}

fn connected(a: &Move, b: &Move) -> bool {
    (a.end.x - b.start.x).hypot(a.end.y - b.start.y) < MIN_XY_MM
}

/// Interpolates the curvature along a move from its end values; a sharp corner at one
/// end does not spread into the move.
fn curvature_at(ends: (PointCurvature, PointCurvature), t: f64) -> PointCurvature {
    match (ends.0.corner, ends.1.corner) {
        (true, true) => PointCurvature::STRAIGHT,
        (true, false) => ends.1,
        (false, true) => ends.0,
        (false, false) => PointCurvature { kappa: ends.0.kappa + (ends.1.kappa - ends.0.kappa) * t, corner: false },
    }
}

/// A unit heading has |x| + |y| ≥ 1, the (0, 0) of a move along z only has 0: anything
/// shorter than this is no heading.
const HEADING_PRESENT: f64 = 0.5;

/// `true` for a sample's unit heading, `false` for the (0, 0) of a move along z only (a
/// plunge or a retract).
pub fn has_heading(h: (f64, f64)) -> bool {
    h.0.abs() + h.1.abs() >= HEADING_PRESENT
}

/// The unit vector along `d`, or (0, 0) when it has no length.
fn unit_heading(d: (f64, f64)) -> (f64, f64) {
    let dl = d.0.hypot(d.1);
    if dl > MIN_XY_MM {
        (d.0 / dl, d.1 / dl)
    } else {
        (0.0, 0.0)
    }
}

/// Calls `visit` for every sample of the moves, in order: each move is divided into equal
/// steps no longer than `spacing_mm`; a sample sits at the end of each step.
pub fn for_each_sample(
    path: &Toolpath,
    curvatures: &[(PointCurvature, PointCurvature)],
    spacing_mm: f64,
    mut visit: impl FnMut(&Sample) -> bool,
) {
    for (index, m) in path.moves.iter().enumerate() {
        let len = move_length(m);
        let steps = ((len / spacing_mm).ceil() as usize).max(1);
        let step_mm = len / steps as f64;
        // A straight move has one heading.
        let straight = matches!(m.motion, Motion::Rapid | Motion::Linear).then(|| unit_heading(point_on(m, 1.0).1));
        let points = MovePoints::of(m);
        for k in 1..=steps {
            let t = k as f64 / steps as f64;
            let (p, d) = points.at(t);
            let heading = straight.unwrap_or_else(|| unit_heading(d));
            let sample = Sample {
                p,
                heading,
                step_mm,
                move_index: index,
                line: m.line,
                feed_mm_min: m.feed_mm_min.unwrap_or(0.0),
                spindle_rpm: m.spindle_rpm,
                rapid: matches!(m.motion, Motion::Rapid),
                curvature: curvature_at(curvatures[index], t),
            };
            if !visit(&sample) {
                return;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    fn mv(motion: Motion, start: P3, end: P3) -> Move {
        Move { motion, start, end, feed_mm_min: Some(1000.0), spindle_rpm: Some(9600.0), tool: None, line: 1 }
    }

    #[test]
    fn a_quarter_arc_has_the_length_and_curvature_of_its_circle() {
        let m = mv(
            Motion::Arc { center: P3::new(0.0, 0.0, 0.0), clockwise: false, plane: Plane::Xy, turns: 0 },
            P3::new(10.0, 0.0, 0.0),
            P3::new(0.0, 10.0, 0.0),
        );
        assert!((move_length(&m) - 5.0 * PI).abs() < 1e-9);
        let path = Toolpath {
            moves: vec![m],
            events: vec![],
            source_units: crate::core::toolpath::Units::Mm,
            warnings: vec![],
        };
        let k = move_curvatures(&path);
        assert!((k[0].0.kappa - 0.1).abs() < 1e-12);
        let mut n = 0;
        for_each_sample(&path, &k, 0.05, |s| {
            n += 1;
            assert!((s.p.x.hypot(s.p.y) - 10.0).abs() < 1e-9);
            true
        });
        assert_eq!(n, (5.0 * PI / 0.05).ceil() as usize);
    }

    #[test]
    fn a_full_circle_sweeps_two_pi_and_extra_turns_add_more() {
        let s = (10.0, 0.0, 0.0);
        let c = (0.0, 0.0, 0.0);
        assert!((arc_sweep(s, s, c, false, 0) - 2.0 * PI).abs() < 1e-12);
        assert!((arc_sweep(s, s, c, true, 1) + 4.0 * PI).abs() < 1e-12);
    }
}
