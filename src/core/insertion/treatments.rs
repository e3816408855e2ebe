//! What each critical stretch of the medial axis gets (seed 004 §2.2–2.3, MODEL.md §7):
//! trochoid cycles where a loop fits, z-cut division where it does not.
//!
//! Along a critical interval of a branch the loop radius is `ρ(s) = R(s) − r − allowance −
//! gap` (or the fixed radius, whichever is smaller), at most `(a − 1)·r`. Where `ρ` is at
//! least `(1.1 − 1)·r` (R/r ≥ 1.1 once the allowance is taken off: classes A and B) the
//! stretch gets a trochoid whose pitch keeps every loop under the engagement limit
//! ([`super::pitch`]); where it is smaller (class C) the stretch is cut by z-cut division: a
//! slot along the axis, repeated at the reduced axial depth. Where the tool does not fit at
//! all (R < r + allowance) nothing is cut.

use super::pitch::{pitch_for_limit_remembering, PeakMemo};
use super::spec::{InsertionSpec, LoopSize, PITCH_DESIGN_MARGIN_DEG};
use crate::core::cycles::guide::Guide;
use crate::core::cycles::trochoid::LoopPlan;
use crate::core::geometry::{Pocket, Point};
use crate::core::medial::{class_of, AxisBranch, Boundary, CriticalInterval, RadiusClass, CLASS_C_RATIO};
use crate::core::tolerance::LENGTH_EPS_MM;
use crate::core::CoreError;

/// Spacing of the scan for class C stretches along an interval, mm.
pub const CLASS_SCAN_STEP_MM: f64 = 0.05;

/// Consecutive loop radii differ by at most this fraction of the distance between their
/// centres, so that the tangent link between them exists (MODEL.md §7, variable radius).
const LINK_SLOPE: f64 = 0.95;

/// A trochoid planned along a stretch of a branch.
#[derive(Debug, Clone)]
pub struct TrochoidStretch {
    pub branch: usize,
    /// Arc lengths along the branch where the guide starts and ends (the guide may run
    /// either way), mm.
    pub s_from_mm: f64,
    pub s_to_mm: f64,
    pub plan: LoopPlan,
    pub pitch_min_mm: f64,
    pub pitch_max_mm: f64,
}

/// A stretch cut by z-cut division: the tool centre runs along `path` (the axis).
#[derive(Debug, Clone)]
pub struct ZCutStretch {
    pub branch: usize,
    pub s_from_mm: f64,
    pub s_to_mm: f64,
    pub path: Vec<Point>,
    /// The clearance at each point of `path`, mm.
    pub clearance_mm: Vec<f64>,
}

/// The treatment of one stretch.
#[derive(Debug, Clone)]
pub enum Stretch {
    Trochoid(TrochoidStretch),
    ZCut(ZCutStretch),
    Opening(super::opening::OpeningStretch),
}

/// The part of a branch between two arc lengths, walked from `from` to `to` (either order).
pub struct BranchPiece {
    pub points: Vec<Point>,
}

/// The polyline of `branch` from arc length `from` to `to` (reversed when `to < from`).
pub fn branch_piece(branch: &AxisBranch, from: f64, to: f64) -> BranchPiece {
    let (lo, hi) = (from.min(to), from.max(to));
    let mut points = Vec::new();
    let mut s = 0.0;
    for w in branch.points.windows(2) {
        let (a, b) = (w[0].point, w[1].point);
        let len = a.distance_mm(b);
        let (s0, s1) = (s, s + len);
        let at = |t: f64| Point::new(a.x + (b.x - a.x) * t, a.y + (b.y - a.y) * t);
        if s1 >= lo && s0 <= hi && len > LENGTH_EPS_MM {
            if points.is_empty() {
                points.push(at(((lo - s0) / len).clamp(0.0, 1.0)));
            }
            if s1 < hi {
                points.push(b);
            } else {
                points.push(at(((hi - s0) / len).clamp(0.0, 1.0)));
                break;
            }
        }
        s = s1;
    }
    points.dedup_by(|a, b| a.near(*b, LENGTH_EPS_MM));
    if to < from {
        points.reverse();
    }
    BranchPiece { points }
}

/// The loop radius the spec allows at a point of clearance `clearance_mm`, mm (may be
/// negative where the tool does not fit).
pub fn loop_radius_at(spec: &InsertionSpec, clearance_mm: f64) -> f64 {
    let room = clearance_mm - spec.r_mm() - spec.allowance_mm - spec.wall_gap_mm;
    let cap = match spec.loop_size {
        LoopSize::Variable => spec.max_loop_radius_mm(),
        LoopSize::Fixed { rho_mm } => rho_mm.min(spec.max_loop_radius_mm()),
    };
    room.min(cap)
}

/// The smallest loop radius of a trochoid, mm: `(1.1 − 1)·r` (seed 004 §2.3).
pub fn min_loop_radius_mm(spec: &InsertionSpec) -> f64 {
    (CLASS_C_RATIO - 1.0) * spec.r_mm()
}

/// The stretches of one critical interval: class C runs become z-cut stretches, the rest
/// trochoids; each run starts at its end of larger clearance.
pub fn treat_interval(
    branch: &AxisBranch,
    interval: &CriticalInterval,
    pocket_boundary: &Boundary,
    pocket: &Pocket,
    spec: &InsertionSpec,
) -> Result<Vec<Stretch>, CoreError> {
    let clearance = |p: Point| {
        if pocket.contains(p.x, p.y) {
            pocket_boundary.clearance_mm(p)
        } else {
            0.0
        }
    };
    let (s0, s1) = (interval.s_start_mm, interval.s_end_mm);
    let n = ((s1 - s0) / CLASS_SCAN_STEP_MM).ceil().max(1.0) as usize;
    let whole = branch_piece(branch, s0, s1);
    let Ok(guide) = Guide::polyline(&whole.points) else { return Ok(Vec::new()) };
    let rho_min = min_loop_radius_mm(spec);
    let fits = |c: f64| c >= spec.r_mm() + spec.allowance_mm;
    // Runs of (kind, from, to) along the interval: 0 = none, 1 = z-cut, 2 = trochoid.
    let mut runs: Vec<(u8, f64, f64)> = Vec::new();
    for i in 0..=n {
        let s = (i as f64 * CLASS_SCAN_STEP_MM).min(guide.length_mm());
        let c = clearance(guide.point_at(s));
        let kind = if !fits(c) {
            0
        } else if loop_radius_at(spec, c) >= rho_min {
            2
        } else {
            1
        };
        match runs.last_mut() {
            Some(last) if last.0 == kind => last.2 = s,
            _ => runs.push((kind, s, s)),
        }
    }
    // Runs meet: each ends where the next starts, except that nothing runs on into a stretch
    // where the tool does not fit.
    for k in 1..runs.len() {
        if runs[k - 1].0 != 0 && runs[k].0 != 0 {
            runs[k - 1].2 = runs[k].1;
        }
    }
    let mut out = Vec::new();
    for (kind, a, b) in runs {
        if b - a <= LENGTH_EPS_MM {
            continue;
        }
        let (ca, cb) = (clearance(guide.point_at(a)), clearance(guide.point_at(b)));
        let (from, to) = if cb > ca { (b, a) } else { (a, b) };
        let piece = branch_piece_of_guide(&guide, from, to);
        let (bf, bt) = (s0 + from, s0 + to);
        match kind {
            2 => {
                if let Some(t) = plan_trochoid(&piece, &clearance, spec)? {
                    out.push(Stretch::Trochoid(TrochoidStretch {
                        branch: interval.branch,
                        s_from_mm: bf,
                        s_to_mm: bt,
                        ..t
                    }));
                }
            }
            1 => {
                let clearance_mm = piece.iter().map(|&p| clearance(p)).collect();
                out.push(Stretch::ZCut(ZCutStretch {
                    branch: interval.branch,
                    s_from_mm: bf,
                    s_to_mm: bt,
                    path: piece,
                    clearance_mm,
                }));
            }
            _ => {}
        }
    }
    Ok(out)
}

/// The points of `guide` from arc length `from` to `to` (reversed when `to < from`), at its
/// vertices in between.
fn branch_piece_of_guide(guide: &Guide, from: f64, to: f64) -> Vec<Point> {
    let (lo, hi) = (from.min(to), from.max(to));
    let mut points = vec![guide.point_at(lo)];
    points.extend(guide.vertex_s_mm().iter().filter(|&&s| s > lo && s < hi).map(|&s| guide.point_at(s)));
    points.push(guide.point_at(hi));
    points.dedup_by(|a, b| a.near(*b, LENGTH_EPS_MM));
    if to < from {
        points.reverse();
    }
    points
}

/// Loops along the polyline `points` with the variable pitch of the engagement limit.
fn plan_trochoid(
    points: &[Point],
    clearance: &dyn Fn(Point) -> f64,
    spec: &InsertionSpec,
) -> Result<Option<TrochoidStretch>, CoreError> {
    let Ok(guide) = Guide::polyline(points) else { return Ok(None) };
    let r = spec.r_mm();
    let rho_min = min_loop_radius_mm(spec);
    let rho_at = |s: f64| loop_radius_at(spec, clearance(guide.point_at(s))).max(rho_min);
    let design_limit = spec.alpha_limit_deg - PITCH_DESIGN_MARGIN_DEG;
    let length = guide.length_mm();
    let mut s_mm = vec![0.0];
    let mut rho_mm = vec![rho_at(0.0)];
    let (mut p_min, mut p_max) = (f64::INFINITY, 0.0_f64);
    let mut peaks = PeakMemo::default();
    while s_mm[s_mm.len() - 1] < length - LENGTH_EPS_MM {
        let s = s_mm[s_mm.len() - 1];
        let rho = rho_mm[rho_mm.len() - 1];
        let mut max_p = spec.max_pitch_for_loop_mm(rho).min(length - s);
        max_p = max_p.min(spec.max_pitch_for_loop_mm(rho_at(s + max_p)));
        let p = pitch_for_limit_remembering(rho, |p| rho_at(s + p), r, design_limit, max_p, &mut peaks).ok_or_else(
            || {
                CoreError::unsolvable(
                    "alpha_limit_deg",
                    format!(
                        "no trochoid pitch keeps the engagement under {}° with loops of ρ = {rho:.3} mm (r = {r} mm)",
                        spec.alpha_limit_deg
                    ),
                )
            },
        )?;
        if s + p < length - LENGTH_EPS_MM || s_mm.len() == 1 {
            p_min = p_min.min(p);
        }
        p_max = p_max.max(p);
        s_mm.push((s + p).min(length));
        rho_mm.push(rho_at(s + p));
    }
    if s_mm.len() < 2 {
        return Ok(None);
    }
    // Tangent links need |ρ_k − ρ_k+1| below the distance between the centres.
    let centres: Vec<Point> = s_mm.iter().map(|&s| guide.point_at(s)).collect();
    for k in (0..rho_mm.len() - 1).rev() {
        let chord = centres[k].distance_mm(centres[k + 1]);
        rho_mm[k] = rho_mm[k].min(rho_mm[k + 1] + LINK_SLOPE * chord);
    }
    for k in 1..rho_mm.len() {
        let chord = centres[k - 1].distance_mm(centres[k]);
        rho_mm[k] = rho_mm[k].min(rho_mm[k - 1] + LINK_SLOPE * chord);
    }
    let plan = LoopPlan::from_stations(&guide, s_mm, rho_mm, r, spec.direction)?;
    Ok(Some(TrochoidStretch {
        branch: 0,
        s_from_mm: 0.0,
        s_to_mm: 0.0,
        plan,
        pitch_min_mm: p_min.min(p_max),
        pitch_max_mm: p_max,
    }))
}

/// The class of the smallest clearance of an interval (for the report).
pub fn interval_class(interval: &CriticalInterval, spec: &InsertionSpec) -> RadiusClass {
    class_of(interval.min_clearance_mm / spec.r_mm(), spec.class_a_ratio)
}
