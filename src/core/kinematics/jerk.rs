//! The jerk limits: every speed-up and slow-down of the constant-acceleration plan re-timed
//! as an S-curve (`scurve.rs`).
//!
//! The plan's pieces (see `planner.rs`) are merged along the path into runs: consecutive
//! accelerations form one phase even across many blocks (look-ahead: a control keeps
//! accelerating through short collinear blocks), and so do decelerations and cruises at one
//! speed. Acceleration is taken to be zero at both ends of every phase. Each "hill" is then
//! re-timed as a whole with the exact S-curve profile of [`hill_time_s`]:
//!
//! - a speed-up followed by a slow-down (a peak): from the speed-up's entry speed to the
//!   slow-down's exit speed, over their joint length, at most at the peak;
//! - a cruise with the speed-up before it and the slow-down after it (either may be
//!   missing): the S-curves take the extra length they need from the cruise, at most at the
//!   cruise speed.
//!
//! A hill's S-curve profile, with the lowest acceleration and jerk of the segments where it
//! speeds up or slows down (not of those it cruises through: a cruise on an arc, whose
//! speed changes get only part of the limit, does not slow the ramps on the lines beside
//! it), never goes faster than the plan at any point of the path (its acceleration is no
//! higher, it starts from the same speed and never exceeds the plan's peak), so the extra
//! time is never negative; it is clamped at 0 against rounding and shared among the hill's
//! pieces in proportion to their time.

use super::planner::{Piece, PieceKind};
use super::scurve::hill_time_s;
use super::segments::Segment;

/// Two cruise speeds within this relative difference are one cruise.
const SAME_SPEED_RELATIVE: f64 = 1e-9;

/// Consecutive pieces doing the same thing.
#[derive(Debug, Clone, Copy)]
struct Run {
    kind: PieceKind,
    v0_mm_s: f64,
    v1_mm_s: f64,
    /// Pieces `first..end`.
    first: usize,
    end: usize,
}

fn runs(pieces: &[Piece]) -> Vec<Run> {
    let mut out: Vec<Run> = Vec::new();
    for (i, p) in pieces.iter().enumerate() {
        if let Some(last) = out.last_mut() {
            let same_speed = (p.v0_mm_s - last.v1_mm_s).abs() <= SAME_SPEED_RELATIVE * p.v0_mm_s.max(last.v1_mm_s);
            let joins = match p.kind {
                PieceKind::Cruise => last.kind == PieceKind::Cruise && same_speed,
                kind => last.kind == kind,
            };
            if joins {
                last.v1_mm_s = p.v1_mm_s;
                last.end = i + 1;
                continue;
            }
        }
        out.push(Run { kind: p.kind, v0_mm_s: p.v0_mm_s, v1_mm_s: p.v1_mm_s, first: i, end: i + 1 });
    }
    out
}

/// A hill to re-time: runs `first..end`, entered at `v_in`, left at `v_out`, at most `cap`.
struct Hill {
    first: usize,
    end: usize,
    v_in: f64,
    v_out: f64,
    cap: f64,
}

/// Groups the runs into hills (see the module doc); runs left out keep their plan time.
fn hills(runs: &[Run]) -> Vec<Hill> {
    let kind = |i: usize| runs.get(i).map(|r| r.kind);
    let mut out = Vec::new();
    let mut i = 0;
    while i < runs.len() {
        let r = &runs[i];
        let (cruise, first) = match (r.kind, kind(i + 1)) {
            (PieceKind::Accelerate, Some(PieceKind::Decelerate)) => {
                let down = &runs[i + 1];
                out.push(Hill { first: i, end: i + 2, v_in: r.v0_mm_s, v_out: down.v1_mm_s, cap: r.v1_mm_s });
                i += 2;
                continue;
            }
            (PieceKind::Accelerate, Some(PieceKind::Cruise)) => (i + 1, i),
            (PieceKind::Cruise, _) => (i, i),
            _ => {
                i += 1;
                continue;
            }
        };
        let c = &runs[cruise];
        let (end, v_out) = match kind(cruise + 1) {
            Some(PieceKind::Decelerate) => (cruise + 2, runs[cruise + 1].v1_mm_s),
            _ => (cruise + 1, c.v1_mm_s),
        };
        if end - first > 1 {
            out.push(Hill { first, end, v_in: runs[first].v0_mm_s, v_out, cap: c.v0_mm_s });
        }
        i = end;
    }
    out
}

/// Adds the jerk limits' extra time to `segment_time_s` (per segment); returns the total (s).
pub(super) fn add_jerk_time(segments: &[Segment], pieces: &[Piece], segment_time_s: &mut [f64]) -> f64 {
    let runs = runs(pieces);
    let mut total_s = 0.0;
    for hill in hills(&runs) {
        let span = &pieces[runs[hill.first].first..runs[hill.end - 1].end];
        let (mut length_mm, mut plan_s) = (0.0, 0.0);
        let (mut accel, mut jerk) = (f64::INFINITY, f64::INFINITY);
        for p in span {
            length_mm += p.length_mm;
            plan_s += p.time_s;
            if p.kind != PieceKind::Cruise {
                accel = accel.min(segments[p.segment].accel_mm_s2);
                jerk = jerk.min(segments[p.segment].jerk_mm_s3);
            }
        }
        if !accel.is_finite() || !jerk.is_finite() {
            continue; // a cruise alone: nothing to re-time
        }
        let s_curve_s = hill_time_s(hill.v_in, hill.v_out, hill.cap, length_mm, accel, jerk);
        let extra_s = (s_curve_s - plan_s).max(0.0);
        if extra_s > 0.0 && plan_s > 0.0 {
            for p in span {
                segment_time_s[p.segment] += extra_s * p.time_s / plan_s;
            }
            total_s += extra_s;
        }
    }
    total_s
}
