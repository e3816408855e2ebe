//! The nominal time (MODEL.md §10: "feed moves at their feeds, rapids at the machine's rapid
//! rate"), plus tool changes and dwells, which both estimates share.

use super::segments::{Segment, SegmentKind, SECONDS_PER_MINUTE};
use super::MachineLimits;
use crate::core::error::CoreError;
use crate::core::toolpath::{Event, EventKind};

/// Nominal figures, minutes and mm.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub(super) struct Nominal {
    pub feed_min: f64,
    pub rapid_min: f64,
    pub feed_length_mm: f64,
    pub rapid_length_mm: f64,
    pub tool_changes: usize,
    pub tool_change_min: f64,
    pub dwell_min: f64,
    pub program_stops: usize,
}

/// Sums the nominal time of `segments` and the time of `events`. Fails on a dwell that is
/// not a finite number of seconds ≥ 0.
pub(super) fn nominal(segments: &[Segment], events: &[Event], machine: &MachineLimits) -> Result<Nominal, CoreError> {
    let mut out = Nominal::default();
    for s in segments {
        let minutes = s.length_mm / s.nominal_mm_s / SECONDS_PER_MINUTE;
        if s.kind == SegmentKind::Rapid {
            out.rapid_min += minutes;
            out.rapid_length_mm += s.length_mm;
        } else {
            out.feed_min += minutes;
            out.feed_length_mm += s.length_mm;
        }
    }
    for (i, e) in events.iter().enumerate() {
        match e.kind {
            EventKind::ToolChange { .. } => out.tool_changes += 1,
            EventKind::Dwell { seconds } if seconds.is_finite() && seconds >= 0.0 => {
                out.dwell_min += seconds / SECONDS_PER_MINUTE;
            }
            EventKind::Dwell { seconds } => {
                return Err(CoreError::invalid(
                    format!("events[{i}].seconds"),
                    format!("line {}: a dwell must be a finite number of seconds >= 0, got {seconds}", e.line),
                ))
            }
            EventKind::Stop => out.program_stops += 1,
            _ => {}
        }
    }
    out.tool_change_min = out.tool_changes as f64 * machine.tool_change_s / SECONDS_PER_MINUTE;
    Ok(out)
}
