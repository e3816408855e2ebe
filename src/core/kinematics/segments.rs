//! The path as the planner sees it: one segment per move with its length, its unit tangent
//! at both ends, its speed limits and its acceleration and jerk limits along the path.
//!
//! Arcs stay whole (no chords): their centripetal acceleration `v²/R` and its steady-state
//! jerk `v³/R²` (uniform circular motion) are bounded by the weaker of the two axes of the
//! arc's plane, which caps the speed on the arc. The acceleration is shared between the
//! two directions as LinuxCNC's trajectory planner shares it (`tp.h`,
//! `TP_ACC_RATIO_TANGENTIAL` 0.5 and `TP_ACC_RATIO_NORMAL` √(1 − 0.5²); `tp.c`: "limit
//! acceleration for circular arcs to allow for normal acceleration"): the centripetal part
//! gets [`ARC_NORMAL_ACCEL_SHARE`] of the limit, speeding up and slowing down along the arc
//! [`ARC_TANGENTIAL_ACCEL_SHARE`], so their sum never exceeds the axes' limit.

use super::limits::MachineLimits;
use crate::core::error::CoreError;
use crate::core::toolpath::{arc_sweep, move_length};
use crate::core::toolpath::{Motion, Move, Plane, Toolpath, P3};

/// Seconds in a minute (feeds are per minute, the planner works per second).
pub(super) const SECONDS_PER_MINUTE: f64 = 60.0;

/// Moves shorter than this (mm) take no time and do not break the path.
const MIN_SEGMENT_MM: f64 = 1e-9;

/// Arcs of a smaller radius (mm) are timed as the straight move between their ends.
const MIN_ARC_RADIUS_MM: f64 = 1e-9;

/// A move starting farther than this (mm) from the previous move's end is a discontinuity:
/// the machine is assumed to stop there.
const CONTINUITY_TOLERANCE_MM: f64 = 1e-6;

/// Share of the acceleration limit left to speed changes along an arc (LinuxCNC's
/// `TP_ACC_RATIO_TANGENTIAL`).
pub const ARC_TANGENTIAL_ACCEL_SHARE: f64 = 0.5;

/// Share of the acceleration limit the centripetal acceleration of an arc may use, so that
/// with [`ARC_TANGENTIAL_ACCEL_SHARE`] the vector sum stays within the limit:
/// `√(1 − 0.5²)` (LinuxCNC's `TP_ACC_RATIO_NORMAL`).
pub const ARC_NORMAL_ACCEL_SHARE: f64 = 0.866_025_403_784_438_6;

/// Below this, a direction cosine is zero (the axis does not move).
const AXIS_COSINE_EPS: f64 = 1e-12;

/// What a segment comes from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum SegmentKind {
    Rapid,
    Line,
    Arc,
}

/// One move, ready for the planner. Speeds mm/s, accelerations mm/s², jerks mm/s³.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Segment {
    pub move_index: usize,
    pub kind: SegmentKind,
    pub length_mm: f64,
    /// Unit tangent at the start and at the end.
    pub u_start: [f64; 3],
    pub u_end: [f64; 3],
    /// Programmed speed (feed, or the rapid rate): the nominal time is `length / nominal`.
    pub nominal_mm_s: f64,
    /// Programmed speed clamped to the machine's maximum feed.
    pub clamped_mm_s: f64,
    /// Highest speed on the segment: `clamped` and, on arcs, the centripetal limits.
    pub cap_mm_s: f64,
    /// Acceleration and jerk limits along the path (the weakest axis' limit over its share
    /// of the direction).
    pub accel_mm_s2: f64,
    pub jerk_mm_s3: f64,
    /// The machine is at rest at the segment's start (event, discontinuity, exact stop).
    pub stop_before: bool,
}

/// The segments and what was noticed while building them.
#[derive(Debug, Clone, Default)]
pub(super) struct Segments {
    pub list: Vec<Segment>,
    /// Feed moves programmed above the maximum feed, and the first one's line.
    pub clamped_feeds: (usize, Option<u32>),
    /// Moves not starting where the previous one ended, and the first one's line.
    pub discontinuities: (usize, Option<u32>),
}

/// Builds the segments of `path`. Fails on non-finite coordinates or on a feed move with no
/// positive feed (the parser refuses both; a hand-made tool path may not).
pub(super) fn build_segments(
    path: &Toolpath,
    machine: &MachineLimits,
    exact_stop_at_rapids: bool,
) -> Result<Segments, CoreError> {
    let mut stop_before_move = vec![false; path.moves.len() + 1];
    for e in path.events.iter().filter(|e| !e.kind.is_label()) {
        if let Some(slot) = stop_before_move.get_mut(e.before_move) {
            *slot = true;
        }
    }
    let mut out = Segments { list: Vec::with_capacity(path.moves.len()), ..Segments::default() };
    let mut pending_stop = false;
    let mut previous_end: Option<P3> = None;
    for (index, m) in path.moves.iter().enumerate() {
        check_finite(index, m)?;
        pending_stop |= stop_before_move[index];
        if let Some(end) = previous_end {
            if distance(end, m.start) > CONTINUITY_TOLERANCE_MM {
                pending_stop = true;
                count(&mut out.discontinuities, m.line);
            }
        }
        previous_end = Some(m.end);
        let rapid = matches!(m.motion, Motion::Rapid);
        let nominal_mm_s = if rapid {
            machine.rapid_mm_min / SECONDS_PER_MINUTE
        } else {
            match m.feed_mm_min {
                Some(f) if f.is_finite() && f > 0.0 => f / SECONDS_PER_MINUTE,
                other => {
                    return Err(CoreError::invalid(
                        format!("moves[{index}].feed_mm_min"),
                        format!("a feed move (line {}) needs a finite feed > 0, got {other:?}", m.line),
                    ))
                }
            }
        };
        let Some(shape) = shape(m, machine) else { continue };
        let max_mm_s = if rapid { nominal_mm_s } else { machine.max_feed_mm_min / SECONDS_PER_MINUTE };
        if nominal_mm_s > max_mm_s {
            count(&mut out.clamped_feeds, m.line);
        }
        let clamped_mm_s = nominal_mm_s.min(max_mm_s);
        let previous_rapid = out.list.last().is_some_and(|s: &Segment| s.kind == SegmentKind::Rapid);
        let stop_before = pending_stop || out.list.is_empty() || (exact_stop_at_rapids && (rapid || previous_rapid));
        pending_stop = false;
        out.list.push(Segment {
            move_index: index,
            kind: if rapid { SegmentKind::Rapid } else { shape.kind },
            length_mm: shape.length_mm,
            u_start: shape.u_start,
            u_end: shape.u_end,
            nominal_mm_s,
            clamped_mm_s,
            cap_mm_s: clamped_mm_s.min(shape.speed_limit_mm_s),
            accel_mm_s2: shape.accel_mm_s2,
            jerk_mm_s3: shape.jerk_mm_s3,
            stop_before,
        });
    }
    Ok(out)
}

fn count(counter: &mut (usize, Option<u32>), line: u32) {
    counter.0 += 1;
    counter.1.get_or_insert(line);
}

fn check_finite(index: usize, m: &Move) -> Result<(), CoreError> {
    let center = match m.motion {
        Motion::Arc { center, .. } => center,
        Motion::Rapid | Motion::Linear => m.start,
    };
    if [m.start, m.end, center].iter().all(|p| p.x.is_finite() && p.y.is_finite() && p.z.is_finite()) {
        Ok(())
    } else {
        Err(CoreError::invalid(format!("moves[{index}]"), format!("line {}: coordinates must be finite", m.line)))
    }
}

fn distance(a: P3, b: P3) -> f64 {
    ((a.x - b.x).powi(2) + (a.y - b.y).powi(2) + (a.z - b.z).powi(2)).sqrt()
}

/// The geometry-dependent part of a segment.
struct Shape {
    kind: SegmentKind,
    length_mm: f64,
    u_start: [f64; 3],
    u_end: [f64; 3],
    /// Speed limit from the geometry (centripetal on arcs; infinite on lines).
    speed_limit_mm_s: f64,
    accel_mm_s2: f64,
    jerk_mm_s3: f64,
}

/// `limits[i] / |u_i|` minimised over the axes that move: the path limit along `u` such that
/// no axis exceeds its own (GRBL's `limit_value_by_axis_maximum`).
pub(super) fn along(limits: [f64; 3], u: [f64; 3]) -> f64 {
    (0..3).filter(|&i| u[i].abs() > AXIS_COSINE_EPS).map(|i| limits[i] / u[i].abs()).fold(f64::INFINITY, f64::min)
}

fn line_shape(start: P3, end: P3, machine: &MachineLimits) -> Option<Shape> {
    let length_mm = distance(start, end);
    if length_mm < MIN_SEGMENT_MM {
        return None;
    }
    let u = [(end.x - start.x) / length_mm, (end.y - start.y) / length_mm, (end.z - start.z) / length_mm];
    Some(Shape {
        kind: SegmentKind::Line,
        length_mm,
        u_start: u,
        u_end: u,
        speed_limit_mm_s: f64::INFINITY,
        accel_mm_s2: along(machine.accel_mm_s2, u),
        jerk_mm_s3: along(machine.jerk_mm_s3, u),
    })
}

fn shape(m: &Move, machine: &MachineLimits) -> Option<Shape> {
    let Motion::Arc { center, clockwise, plane, turns } = m.motion else {
        return line_shape(m.start, m.end, machine);
    };
    // Indices of the plane's two axes and of its normal (the helix axis), as in sampling.rs.
    let (pa, axial) = match plane {
        Plane::Xy => ([0, 1], 2),
        Plane::Zx => ([2, 0], 1),
        Plane::Yz => ([1, 2], 0),
    };
    let xyz = |p: P3| [p.x, p.y, p.z];
    let (s, e, c) = (xyz(m.start), xyz(m.end), xyz(center));
    let to_plane = |p: [f64; 3]| (p[pa[0]], p[pa[1]], p[axial]);
    let (sp, ep, cp) = (to_plane(s), to_plane(e), to_plane(c));
    let radius_mm = (sp.0 - cp.0).hypot(sp.1 - cp.1);
    if radius_mm < MIN_ARC_RADIUS_MM {
        return line_shape(m.start, m.end, machine);
    }
    let length_mm = move_length(m);
    if length_mm < MIN_SEGMENT_MM {
        return None;
    }
    let sweep = arc_sweep(sp, ep, cp, clockwise, turns);
    let rise_mm = ep.2 - sp.2;
    // Share of the speed in the plane (cos) and along the helix axis (sin).
    let cos_helix = radius_mm * sweep.abs() / length_mm;
    let sin_helix = rise_mm.abs() / length_mm;
    let start_angle = (sp.1 - cp.1).atan2(sp.0 - cp.0);
    let tangent = |angle: f64| {
        let mut u = [0.0; 3];
        u[pa[0]] = -angle.sin() * sweep.signum() * cos_helix;
        u[pa[1]] = angle.cos() * sweep.signum() * cos_helix;
        u[axial] = rise_mm / length_mm;
        u
    };
    let in_plane = |limits: [f64; 3]| limits[pa[0]].min(limits[pa[1]]);
    // The tangent turns through the plane: bound each part by the weaker plane axis.
    let path_limit = |limits: [f64; 3]| {
        let planar = if cos_helix > AXIS_COSINE_EPS { in_plane(limits) / cos_helix } else { f64::INFINITY };
        let normal = if sin_helix > AXIS_COSINE_EPS { limits[axial] / sin_helix } else { f64::INFINITY };
        planar.min(normal)
    };
    // Planar speed v·cos: centripetal (v cos)²/R ≤ share · a_n and circular jerk (v cos)³/R² ≤ j_n.
    let centripetal_mm_s = (ARC_NORMAL_ACCEL_SHARE * in_plane(machine.accel_mm_s2) * radius_mm).sqrt();
    let circular_jerk_mm_s = (in_plane(machine.jerk_mm_s3) * radius_mm * radius_mm).cbrt();
    Some(Shape {
        kind: SegmentKind::Arc,
        length_mm,
        u_start: tangent(start_angle),
        u_end: tangent(start_angle + sweep),
        speed_limit_mm_s: centripetal_mm_s.min(circular_jerk_mm_s) / cos_helix.max(AXIS_COSINE_EPS),
        accel_mm_s2: ARC_TANGENTIAL_ACCEL_SHARE * path_limit(machine.accel_mm_s2),
        jerk_mm_s3: path_limit(machine.jerk_mm_s3),
    })
}
