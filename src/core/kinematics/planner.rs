//! Look-ahead over the blocks with the acceleration limits (the constant-acceleration
//! planner of GRBL 1.1 `planner.c` and Marlin, after S. Jeon): each junction gets the highest
//! speed that its direction change, both segments' caps and a look-ahead window allow; a
//! backward pass makes every speed one the machine can slow down from in time for the next
//! limits (`v_k² ≤ v_{k+1}² + 2·a_k·L_k`), a forward pass one it can reach
//! (`v_{k+1}² ≤ v_k² + 2·a_k·L_k`). Each segment then runs a trapezoid: speed up at its
//! acceleration limit, cruise at its cap, slow down.
//!
//! A control that reads only `N` blocks ahead must always be able to stop at the end of what
//! it has read: `v_k² ≤ Σ_{i=k}^{k+N−1} 2·a_i·L_i`. With the full backward pass this gives
//! exactly what a windowed planner gives (a limit beyond the window, carried back, is never
//! below the stop at the window's end), in O(1) per junction from prefix sums.

use super::junction::junction_limit_mm_s;
use super::segments::Segment;
use super::MachineLimits;

/// A piece shorter than this share of its segment is rounding (e.g. the cruise left between
/// a speed-up that fills the segment and its end): its time counts, but it does not split
/// the phases that the jerk step merges across blocks.
const NEGLIGIBLE_PIECE_RELATIVE: f64 = 1e-9;

/// What a piece of a segment's trapezoid does.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum PieceKind {
    Accelerate,
    Cruise,
    Decelerate,
}

/// One phase of a segment's trapezoid: from `v0` to `v1` (mm/s) over `length_mm` in `time_s`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Piece {
    pub segment: usize,
    pub kind: PieceKind,
    pub v0_mm_s: f64,
    pub v1_mm_s: f64,
    pub length_mm: f64,
    pub time_s: f64,
}

/// The plan: speeds at the `n + 1` junctions (at rest at both ends) and the number of
/// junctions slowed by their direction change.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Plan {
    pub junction_mm_s: Vec<f64>,
    pub slowed_corners: usize,
    pub exact_stops: usize,
}

/// Plans the junction speeds of `segments`.
pub(super) fn plan(
    segments: &[Segment],
    machine: &MachineLimits,
    deviation_mm: f64,
    look_ahead_blocks: Option<usize>,
) -> Plan {
    let n = segments.len();
    let mut v = vec![0.0; n + 1];
    let (mut slowed_corners, mut exact_stops) = (0, 0);
    for k in 1..n {
        let (prev, next) = (&segments[k - 1], &segments[k]);
        if next.stop_before {
            exact_stops += 1;
            continue;
        }
        let caps = prev.cap_mm_s.min(next.cap_mm_s);
        v[k] = junction_limit_mm_s(prev, next, machine, deviation_mm, caps);
        if v[k] < caps {
            slowed_corners += 1;
        }
    }
    if let Some(window) = look_ahead_blocks {
        // prefix[k] = Σ_{i<k} 2·a_i·L_i: the squared speed the window lets the machine shed.
        let mut prefix = Vec::with_capacity(n + 1);
        prefix.push(0.0);
        for s in segments {
            prefix.push(prefix.last().copied().unwrap_or(0.0) + 2.0 * s.accel_mm_s2 * s.length_mm);
        }
        for k in 1..n {
            let stop_sq = prefix[(k + window).min(n)] - prefix[k];
            v[k] = v[k].min(stop_sq.max(0.0).sqrt());
        }
    }
    for k in (1..n).rev() {
        let s = &segments[k];
        v[k] = v[k].min((v[k + 1] * v[k + 1] + 2.0 * s.accel_mm_s2 * s.length_mm).sqrt());
    }
    for k in 0..n {
        let s = &segments[k];
        v[k + 1] = v[k + 1].min((v[k] * v[k] + 2.0 * s.accel_mm_s2 * s.length_mm).sqrt());
    }
    Plan { junction_mm_s: v, slowed_corners, exact_stops }
}

/// Appends the trapezoid of segment `index` (entry `v0`, exit `v1`, mm/s) to `pieces`;
/// returns its time (s). Every piece moves at most at the cap, so the time is at least
/// `length / cap`.
pub(super) fn push_trapezoid(index: usize, s: &Segment, v0: f64, v1: f64, pieces: &mut Vec<Piece>) -> f64 {
    let a = s.accel_mm_s2;
    let two_a = 2.0 * a;
    let top = ((two_a * s.length_mm + v0 * v0 + v1 * v1) / 2.0).sqrt();
    let peak = top.min(s.cap_mm_s).max(v0).max(v1);
    let up_mm = ((peak * peak - v0 * v0) / two_a).max(0.0);
    let down_mm = ((peak * peak - v1 * v1) / two_a).max(0.0);
    let cruise_mm = (s.length_mm - up_mm - down_mm).max(0.0);
    let phases = [
        (PieceKind::Accelerate, v0, peak, up_mm, (peak - v0) / a),
        (PieceKind::Cruise, peak, peak, cruise_mm, cruise_mm / peak),
        (PieceKind::Decelerate, peak, v1, down_mm, (peak - v1) / a),
    ];
    let mut time_s = 0.0;
    for (kind, v0_mm_s, v1_mm_s, length_mm, t) in phases {
        if length_mm > NEGLIGIBLE_PIECE_RELATIVE * s.length_mm && t > 0.0 {
            pieces.push(Piece { segment: index, kind, v0_mm_s, v1_mm_s, length_mm, time_s: t });
        }
        time_s += t;
    }
    time_s
}
