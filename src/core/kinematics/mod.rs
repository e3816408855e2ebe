//! Machining time, nominal and kinematic (MODEL.md §10; seed 002 §2.6, the `T_m` of Eq. 4).
//!
//! The papers time a program at its programmed feeds and came out 35 % short of the real
//! time (25'27" predicted, 33'51" measured) "because the commanded feed rate cannot be
//! achieved at corners because of servo delay". [`machining_time`] reports both that nominal
//! time and a kinematic one that follows the machine's limits:
//!
//! 1. **Segments** (`segments.rs`): one per move. The speed is capped by the programmed feed
//!    (clamped to the machine's maximum feed) or the rapid rate; on arcs, also by the
//!    centripetal limit `v ≤ sqrt(a_n·R)` and its jerk counterpart `v ≤ cbrt(j_n·R²)`, `a_n`,
//!    `j_n` the weaker of the arc plane's two axes (arcs are treated analytically, not as
//!    chords). The acceleration and jerk along a line are the per-axis limits over the
//!    direction's shares, `min_i a_i/|u_i|`.
//! 2. **Junctions** (`junction.rs`): the speed where two segments meet is limited by their
//!    change of direction (GRBL's junction deviation, per-axis acceleration) and, on dense
//!    polylines, by the curvature their chords describe (Marlin's small-segment rule).
//! 3. **Look-ahead** (`planner.rs`): backward and forward passes with constant acceleration
//!    over the whole program, plus the stop-within-window rule of a control that reads
//!    [`TimeOptions::look_ahead_blocks`] ahead; a trapezoid on each segment.
//! 4. **Jerk** (`jerk.rs`, `scurve.rs`): every speed-up and slow-down, merged across blocks,
//!    re-timed as an exact S-curve with the jerk limit.
//!
//! By construction the kinematic time of every move is at least its length over its
//! programmed speed: every profile stays at or below the cap, which is at most the programmed
//! speed, and the jerk step only adds time. It tends to the nominal time on long straight
//! moves (a constant overhead per speed change). Linear in the number of moves.
//!
//! Assumptions (state them with the figures):
//! - Rapids move along the straight line at the rapid rate with the axes' acceleration and
//!   jerk limits (a real G0 may move each axis at its own rate, a "dog-leg").
//! - Every event (tool change, dwell, M codes for spindle, coolant, stop; not the section
//!   labels of generated programs, which are comments) and every rapid
//!   ([`TimeOptions::exact_stop_at_rapids`]) brings the machine to rest; a gap between moves
//!   too. M0/M1 stops wait no time (the operator's is not counted).
//! - Acceleration is zero at both ends of every speed change (symmetric S-curves); a change of
//!   direction between blocks does not cost jerk beyond the junction speed; on arcs the
//!   acceleration limit is shared as LinuxCNC's planner shares it: √3/2 of it for the
//!   centripetal part, 1/2 for speeding up and slowing down along the arc
//!   ([`ARC_NORMAL_ACCEL_SHARE`], [`ARC_TANGENTIAL_ACCEL_SHARE`]); the jerk is not shared.
//! - No block-processing-time limit (very short blocks at high feed could be slower still),
//!   no servo lag (following error): only the planner's acceleration and jerk limits.
//! - Defaults **assumed**, not from the papers: a 200-block look-ahead
//!   ([`DEFAULT_LOOK_AHEAD_BLOCKS`]) and a 0.01 mm junction deviation
//!   ([`DEFAULT_JUNCTION_DEVIATION_MM`]).

mod jerk;
mod junction;
mod limits;
mod nominal;
mod planner;
mod report;
mod scurve;
mod segments;

#[cfg(test)]
mod data_tests;
#[cfg(test)]
mod proptests;
#[cfg(test)]
mod tests;

pub use junction::ARC_LIKE_MAX_TURN_DEG;
pub use limits::{MachineLimits, TimeOptions, DEFAULT_JUNCTION_DEVIATION_MM, DEFAULT_LOOK_AHEAD_BLOCKS};
pub use report::{KinematicBreakdown, MachiningTime};
pub use scurve::{hill_time_s, ramp_distance_mm, ramp_time_s};
pub use segments::{ARC_NORMAL_ACCEL_SHARE, ARC_TANGENTIAL_ACCEL_SHARE};

use crate::core::error::CoreError;
use crate::core::toolpath::Toolpath;
use segments::{SegmentKind, SECONDS_PER_MINUTE};

/// Relative rounding allowed when checking that a move is never faster than programmed.
const ROUNDING_RELATIVE: f64 = 1e-12;

/// Nominal and kinematic machining time of `path` on `machine` (see the module doc).
///
/// Fails on invalid limits or options, non-finite coordinates, a feed move without a
/// positive feed, or a negative dwell.
pub fn machining_time(
    path: &Toolpath,
    machine: &MachineLimits,
    options: &TimeOptions,
) -> Result<MachiningTime, CoreError> {
    machine.validate()?;
    options.validate()?;
    let built = segments::build_segments(path, machine, options.exact_stop_at_rapids)?;
    let segs = &built.list;
    let nominal = nominal::nominal(segs, &path.events, machine)?;
    let plan = planner::plan(segs, machine, options.junction_deviation_mm, options.look_ahead_blocks);

    let mut pieces = Vec::with_capacity(segs.len() * 2);
    let mut segment_time_s: Vec<f64> = segs
        .iter()
        .enumerate()
        .map(|(k, s)| planner::push_trapezoid(k, s, plan.junction_mm_s[k], plan.junction_mm_s[k + 1], &mut pieces))
        .collect();
    let mut breakdown = KinematicBreakdown {
        slowed_corners: plan.slowed_corners,
        exact_stops: plan.exact_stops,
        ..KinematicBreakdown::default()
    };
    for (s, &t) in segs.iter().zip(&segment_time_s) {
        let (nominal_s, clamped_s, capped_s) =
            (s.length_mm / s.nominal_mm_s, s.length_mm / s.clamped_mm_s, s.length_mm / s.cap_mm_s);
        breakdown.feed_clamp_min += (clamped_s - nominal_s) / SECONDS_PER_MINUTE;
        breakdown.arc_limit_min += (capped_s - clamped_s) / SECONDS_PER_MINUTE;
        breakdown.acceleration_min += (t - capped_s) / SECONDS_PER_MINUTE;
    }
    breakdown.jerk_min = jerk::add_jerk_time(segs, &pieces, &mut segment_time_s) / SECONDS_PER_MINUTE;

    let (mut feed_kinematic_min, mut rapid_kinematic_min) = (0.0, 0.0);
    for (s, &t) in segs.iter().zip(&segment_time_s) {
        debug_assert!(t >= s.length_mm / s.nominal_mm_s * (1.0 - ROUNDING_RELATIVE), "segment faster than programmed");
        match s.kind {
            SegmentKind::Rapid => rapid_kinematic_min += t / SECONDS_PER_MINUTE,
            SegmentKind::Line | SegmentKind::Arc => feed_kinematic_min += t / SECONDS_PER_MINUTE,
        }
    }
    let events_min = nominal.tool_change_min + nominal.dwell_min;
    let nominal_min = nominal.feed_min + nominal.rapid_min + events_min;
    let kinematic_min = feed_kinematic_min + rapid_kinematic_min + events_min;
    let per_move_s = options.per_move.then(|| {
        let mut out = vec![0.0f32; path.moves.len()];
        for (s, &t) in segs.iter().zip(&segment_time_s) {
            out[s.move_index] = t as f32;
        }
        out
    });
    Ok(MachiningTime {
        nominal_min,
        kinematic_min,
        kinematic_ratio: if nominal_min > 0.0 { kinematic_min / nominal_min } else { 1.0 },
        feed_nominal_min: nominal.feed_min,
        rapid_nominal_min: nominal.rapid_min,
        feed_kinematic_min,
        rapid_kinematic_min,
        feed_length_mm: nominal.feed_length_mm,
        rapid_length_mm: nominal.rapid_length_mm,
        tool_changes: nominal.tool_changes,
        tool_change_min: nominal.tool_change_min,
        dwell_min: nominal.dwell_min,
        breakdown,
        per_move_s,
        warnings: warnings(&built, &nominal, machine),
    })
}

fn warnings(built: &segments::Segments, nominal: &nominal::Nominal, machine: &MachineLimits) -> Vec<String> {
    let mut out = Vec::new();
    if let (n, Some(line)) = built.clamped_feeds {
        out.push(format!(
            "{n} feed move(s) program more than the machine's maximum feed of {} mm/min (first on line {line}): \
             timed at the maximum",
            machine.max_feed_mm_min
        ));
    }
    if let (n, Some(line)) = built.discontinuities {
        out.push(format!(
            "{n} move(s) do not start where the previous one ended (first on line {line}): the machine is assumed \
             to stop there"
        ));
    }
    if nominal.program_stops > 0 {
        out.push(format!("{} program stop(s) (M0/M1): the operator's time is not counted", nominal.program_stops));
    }
    out
}
