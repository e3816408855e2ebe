//! Writes the moves of a pocketing path: positioning, plunges, loops of lines and XY arcs,
//! links and retracts, each move starting exactly where the one before ended.

use super::PocketingSpec;
use crate::core::geometry::{Loop, Point};
use crate::core::toolpath::{Event, EventKind, Motion, Move, Plane, Toolpath, Units, P3};

/// A link or a segment shorter than this is not written (mm).
pub(super) const MIN_MOVE_MM: f64 = 1e-9;

/// Builds a [`Toolpath`] move by move.
pub(super) struct PathWriter {
    spec: PocketingSpec,
    moves: Vec<Move>,
    /// Where the tool is; `None` before the first move.
    position: Option<P3>,
    /// The last programmed feed (mm/min), carried by rapids as the modal F word.
    modal_feed_mm_min: Option<f64>,
    /// XY of every plunge.
    entries: Vec<(f64, f64)>,
}

impl PathWriter {
    pub fn new(spec: &PocketingSpec) -> PathWriter {
        PathWriter { spec: *spec, moves: Vec::new(), position: None, modal_feed_mm_min: None, entries: Vec::new() }
    }

    /// XY of the tool, `None` before the first move.
    pub fn position(&self) -> Option<Point> {
        self.position.map(|p| Point::new(p.x, p.y))
    }

    /// The tool radius r (mm).
    pub fn tool_radius_mm(&self) -> f64 {
        self.spec.tool_radius_mm
    }

    /// `true` when the tool is at the cutting level.
    pub fn at_cutting_depth(&self) -> bool {
        self.position.is_some_and(|p| p.z < self.spec.safe_z_mm)
    }

    /// Goes to `p` at cutting depth from above: retracts to `safe_z_mm`, moves over at the
    /// rapid rate and plunges at the plunge feed. The first move of the path is the
    /// positioning above `p` (its start is the same point: where the tool comes from is the
    /// caller's business).
    pub fn enter_at(&mut self, p: Point) {
        let safe_z = self.spec.safe_z_mm;
        let above = P3::new(p.x, p.y, safe_z);
        match self.position {
            None => self.push(Motion::Rapid, above, above, None),
            Some(here) => {
                self.push(Motion::Rapid, here, P3::new(here.x, here.y, safe_z), None);
                self.push(Motion::Rapid, P3::new(here.x, here.y, safe_z), above, None);
            }
        }
        let plunge = self.spec.plunge_feed_mm_min;
        self.push(Motion::Linear, above, P3::new(p.x, p.y, self.spec.z_mm), Some(plunge));
        self.entries.push((p.x, p.y));
    }

    /// A straight feed move at cutting depth to `p`.
    pub fn feed_to(&mut self, p: Point) {
        let Some(here) = self.position else {
            return self.enter_at(p);
        };
        let end = P3::new(p.x, p.y, self.spec.z_mm);
        if Point::new(here.x, here.y).distance_mm(p) > MIN_MOVE_MM {
            self.push(Motion::Linear, here, end, Some(self.spec.feed_mm_min));
        }
    }

    /// Cuts the closed loop `lp`, which must start where the tool is: straight segments as
    /// linear moves, arcs as XY arcs about their centres (clockwise for a negative bulge).
    pub fn cut_loop(&mut self, lp: &Loop) {
        let z = self.spec.z_mm;
        let feed = Some(self.spec.feed_mm_min);
        for seg in lp.segments() {
            if seg.chord_mm() <= MIN_MOVE_MM {
                continue;
            }
            let Some(start) = self.position else {
                return;
            };
            let end = P3::new(seg.end.x, seg.end.y, z);
            let motion = match seg.circle() {
                Some((c, _)) => Motion::Arc {
                    center: P3::new(c.x, c.y, start.z),
                    clockwise: seg.bulge < 0.0,
                    plane: Plane::Xy,
                    turns: 0,
                },
                None => Motion::Linear,
            };
            self.push(motion, start, end, feed);
        }
    }

    /// Retracts to `safe_z_mm` and returns the tool path (spindle on, clockwise, before the
    /// first move; off after the last) and the entry points.
    pub fn finish(mut self) -> (Toolpath, Vec<(f64, f64)>) {
        if let Some(here) = self.position {
            self.push(Motion::Rapid, here, P3::new(here.x, here.y, self.spec.safe_z_mm), None);
        }
        // Events carry the line of the move they precede (the last move's for the final one).
        let last_line = u32::try_from(self.moves.len()).unwrap_or(u32::MAX);
        let events = vec![
            Event { kind: EventKind::SpindleOn { clockwise: true }, before_move: 0, line: 1 },
            Event { kind: EventKind::SpindleOff, before_move: self.moves.len(), line: last_line },
        ];
        let toolpath = Toolpath { moves: self.moves, events, source_units: Units::Mm, warnings: Vec::new() };
        (toolpath, self.entries)
    }

    /// Appends a move from `start` (the current position) to `end`; `feed` programs a new F.
    fn push(&mut self, motion: Motion, start: P3, end: P3, feed: Option<f64>) {
        if feed.is_some() {
            self.modal_feed_mm_min = feed;
        }
        let line = u32::try_from(self.moves.len() + 1).unwrap_or(u32::MAX);
        self.moves.push(Move {
            motion,
            start,
            end,
            feed_mm_min: self.modal_feed_mm_min,
            spindle_rpm: Some(self.spec.spindle_rpm),
            tool: None,
            line,
        });
        self.position = Some(end);
    }
}
