//! What a cycle generator returns: its moves and a small report (lengths, loops or turns,
//! z levels and the time at its feeds, MODEL.md §10 without the machine's acceleration).

use crate::core::toolpath::move_length;
use crate::core::toolpath::{Motion, Move, Toolpath, Units};
use serde::Serialize;

/// The figures of one generated cycle.
#[derive(Debug, Clone, PartialEq, Default, Serialize)]
pub struct CycleReport {
    /// Length of the feed moves (cutting and air), mm.
    pub feed_length_mm: f64,
    /// Length of the rapid moves, mm.
    pub rapid_length_mm: f64,
    /// Feed moves at their feeds plus rapids at the setup's rapid rate, min.
    pub time_min: f64,
    /// z levels cut.
    pub levels: usize,
    /// Trochoid loops over all levels (0 for the other cycles).
    pub loops: usize,
    /// Full turns of the helices and spirals over all levels, fractional (0 for the others).
    pub turns: f64,
    /// Radial steps per level: spiral turns or corner passes (0 for the others).
    pub steps: usize,
    /// Things the caller should know (e.g. a trochoid in the z-cut division class).
    pub warnings: Vec<String>,
}

impl CycleReport {
    /// The lengths and time of `moves`, rapids at `rapid_mm_min`; the counts are zero.
    pub fn of_moves(moves: &[Move], rapid_mm_min: f64) -> CycleReport {
        let mut report = CycleReport::default();
        for m in moves {
            let len = move_length(m);
            match (m.motion, m.feed_mm_min) {
                (Motion::Rapid, _) => {
                    report.rapid_length_mm += len;
                    report.time_min += len / rapid_mm_min;
                }
                (_, Some(f)) => {
                    report.feed_length_mm += len;
                    report.time_min += len / f;
                }
                (_, None) => report.feed_length_mm += len,
            }
        }
        report
    }
}

/// A generated cycle.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Cycle {
    /// The moves, continuous, `line` = 1-based index.
    pub moves: Vec<Move>,
    pub report: CycleReport,
}

impl Cycle {
    /// The moves as a tool path (mm, no events: the caller starts the spindle and changes tools).
    pub fn toolpath(&self) -> Toolpath {
        Toolpath { moves: self.moves.clone(), events: Vec::new(), source_units: Units::Mm, warnings: Vec::new() }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::core::tolerance::approx_eq;
    use crate::core::toolpath::P3;

    #[test]
    fn feed_moves_take_their_feed_and_rapids_the_rapid_rate() {
        let mv = |motion, end: P3, feed| Move {
            motion,
            start: P3::default(),
            end,
            feed_mm_min: feed,
            spindle_rpm: None,
            tool: None,
            line: 1,
        };
        let moves = [
            mv(Motion::Rapid, P3::new(0.0, 0.0, 100.0), None),
            mv(Motion::Linear, P3::new(50.0, 0.0, 0.0), Some(500.0)),
        ];
        let r = CycleReport::of_moves(&moves, 20_000.0);
        assert!(approx_eq(r.rapid_length_mm, 100.0, 1e-12));
        assert!(approx_eq(r.feed_length_mm, 50.0, 1e-12));
        assert!(approx_eq(r.time_min, 100.0 / 20_000.0 + 0.1, 1e-12));
    }
}
