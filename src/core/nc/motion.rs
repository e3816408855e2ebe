//! The motion of a line: rapid, linear and arc moves and canned cycles, in the modal
//! motion mode or the one the line sets.
//!
//! Rapid and linear moves whose end is their start (within
//! [`crate::core::tolerance::LENGTH_EPS_MM`] on every axis) are dropped: they take no time
//! and cut nothing, and CAM output has many (`G1 Z5` right after `G0 Z5`). The position,
//! feed and everything modal they set still apply. Arcs are never dropped: an arc whose end
//! is its start is a full circle.

use super::arcs::{self, coord, plane_axes};
use super::block::{bit, Block, MotionCode, AXES};
use super::canned::{self, CycleKind, Hole, Step};
use super::parse::{is_integer, CycleMemory, Machine};
use super::report::{Failed, Line};
use super::CannedCycles;
use crate::core::tolerance::{approx_eq, LENGTH_EPS_MM};
use crate::core::toolpath::{EventKind, Motion, Move, Plane, P3};

/// What [`CannedCycles::Refuse`] says about a canned cycle.
const CYCLES_NOT_EXPANDED: &str = "canned cycles are not expanded: send the moves, or let the service expand them";

/// The arc-centre letters I, J, K by axis (X, Y, Z).
const CENTRE_LETTERS: [u8; 3] = [b'I', b'J', b'K'];

fn same_point(p: P3, q: P3) -> bool {
    approx_eq(p.x, q.x, LENGTH_EPS_MM) && approx_eq(p.y, q.y, LENGTH_EPS_MM) && approx_eq(p.z, q.z, LENGTH_EPS_MM)
}

fn plane_code(plane: Plane) -> &'static str {
    match plane {
        Plane::Xy => "XY plane (G17)",
        Plane::Zx => "ZX plane (G18)",
        Plane::Yz => "YZ plane (G19)",
    }
}

impl Machine {
    /// Appends a move from the current position to `end` (dropping a rapid or linear move
    /// of zero length) and makes `end` the current position.
    pub fn push_move(&mut self, motion: Motion, end: P3, line: u32) {
        let start = self.modal.position;
        self.modal.position = end;
        if !matches!(motion, Motion::Arc { .. }) && same_point(start, end) {
            return;
        }
        self.moves.push(Move {
            motion,
            start,
            end,
            feed_mm_min: self.modal.feed_mm_min,
            spindle_rpm: self.modal.spindle_rpm,
            tool: self.modal.tool,
            line,
        });
    }

    /// Runs the motion of a line; returns the letters it read.
    pub fn motion(
        &mut self,
        b: &Block,
        line: &mut Line,
        explicit: Option<(MotionCode, usize)>,
        cancel: Option<usize>,
    ) -> Result<u32, Failed> {
        let previous = self.modal.motion;
        if cancel.is_some() {
            self.modal.motion = None;
        }
        if let Some((code, i)) = explicit {
            if matches!(code, MotionCode::Cycle(_)) && self.canned == CannedCycles::Refuse {
                return Err(line.error_at(i, CYCLES_NOT_EXPANDED));
            }
            if matches!(code, MotionCode::Cycle(_)) && previous != Some(code) {
                self.modal.cycle = CycleMemory::default();
            }
            self.modal.motion = Some(code);
        }
        let axes = b.present() & AXES;
        let anchor = explicit.map(|(_, i)| i).or_else(|| first_word(b, AXES));
        let Some(mode) = self.modal.motion else {
            if axes != 0 {
                let reason = if cancel.is_some() {
                    "G80 ends the motion mode: add G0 or G1 for these axis words"
                } else {
                    "axis words with no motion mode in effect: add G0 or G1"
                };
                return Err(line.error_near(anchor, reason));
            }
            return Ok(0);
        };
        match mode {
            MotionCode::Rapid | MotionCode::Linear if axes != 0 => {
                let end = self.target(b, line)?;
                let motion = if mode == MotionCode::Rapid {
                    Motion::Rapid
                } else {
                    self.require_feed(line, anchor)?;
                    Motion::Linear
                };
                self.push_move(motion, end, line.number);
                Ok(AXES)
            }
            MotionCode::Arc { clockwise } => self.arc(b, line, clockwise, anchor),
            MotionCode::Cycle(kind) if axes != 0 => self.cycle(b, line, kind, anchor),
            _ => Ok(0),
        }
    }

    fn require_feed(&self, line: &mut Line, anchor: Option<usize>) -> Result<(), Failed> {
        if self.modal.feed_mm_min.is_none() {
            return Err(line.error_near(anchor, "a feed move with no feed rate: add an F word"));
        }
        Ok(())
    }

    /// The end point of a G0/G1/G2/G3 line, absolute, mm.
    fn target(&self, b: &Block, line: &mut Line) -> Result<P3, Failed> {
        let scale = self.scale();
        let mut p = self.modal.position;
        for (axis, letter) in [b'X', b'Y', b'Z'].into_iter().enumerate() {
            if let Some(v) = b.value(letter) {
                let v = v * scale;
                let value = if self.modal.absolute { v } else { coord(p, axis) + v };
                if !value.is_finite() {
                    return Err(line.error_at(b.word(letter), "the coordinate is out of range"));
                }
                p = arcs::with_coord(p, axis, value);
            }
        }
        Ok(p)
    }

    fn arc(&mut self, b: &Block, line: &mut Line, clockwise: bool, anchor: Option<usize>) -> Result<u32, Failed> {
        let plane = self.modal.plane;
        let [a, bb, n] = plane_axes(plane);
        let (la, lb) = (CENTRE_LETTERS[a], CENTRE_LETTERS[bb]);
        let centre_words = bit(la) | bit(lb);
        let read = AXES | centre_words | bit(b'R') | bit(b'P');
        if b.present() & (AXES | centre_words | bit(b'R')) == 0 {
            return Ok(0);
        }
        if b.has(CENTRE_LETTERS[n]) {
            let reason = format!(
                "{} is not an arc centre word in the {}: use {} and {}",
                char::from(CENTRE_LETTERS[n]),
                plane_code(plane),
                char::from(la),
                char::from(lb)
            );
            return Err(line.error_at(b.word(CENTRE_LETTERS[n]), reason));
        }
        self.require_feed(line, anchor)?;
        let start = self.modal.position;
        let end = self.target(b, line)?;
        let scale = self.scale();
        let anchor = anchor.or_else(|| first_word(b, centre_words | bit(b'R')));
        let centre = match (b.value(b'R'), b.present() & centre_words != 0) {
            (Some(_), true) => {
                let reason = "give either R or I/J/K for an arc, not both";
                return Err(line.error_at(b.word(b'R'), reason));
            }
            (Some(r), false) => arcs::centre_from_radius(start, end, plane, clockwise, r * scale)
                .map_err(|reason| line.error_at(b.word(b'R'), reason))?,
            (None, true) => {
                let absolute = self.modal.absolute_centres;
                if absolute && b.present() & centre_words != centre_words {
                    let (ca, cb) = (char::from(la), char::from(lb));
                    let reason = format!("with G90.1 (absolute centres) give both {ca} and {cb}");
                    return Err(line.error_near(first_word(b, centre_words), reason));
                }
                let oa = b.value(la).unwrap_or(0.0) * scale;
                let ob = b.value(lb).unwrap_or(0.0) * scale;
                let centre = arcs::centre_from_offsets(start, plane, oa, ob, absolute);
                arcs::check_arc(start, centre, end, plane).map_err(|reason| line.error_near(anchor, reason))?;
                centre
            }
            (None, false) => {
                let reason = "an arc needs its centre (I/J/K) or its radius (R)";
                return Err(line.error_near(anchor, reason));
            }
        };
        let turns = match b.value(b'P') {
            None => 0,
            Some(p) => {
                self.claim(b, line, b'P', "G2/G3")?;
                if !(is_integer(p) && p >= 1.0 && p <= f64::from(u32::MAX)) {
                    let reason = "P (number of turns) must be a positive integer";
                    return Err(line.error_at(b.word(b'P'), reason));
                }
                p.round() as u32 - 1
            }
        };
        let motion = Motion::Arc { center: centre, clockwise, plane, turns };
        self.push_move(motion, end, line.number);
        Ok(read)
    }

    fn cycle(&mut self, b: &Block, line: &mut Line, kind: CycleKind, anchor: Option<usize>) -> Result<u32, Failed> {
        let code = kind.code();
        let mut read = AXES | bit(b'R') | bit(b'L');
        self.require_feed(line, anchor)?;
        if !self.modal.absolute {
            let reason = "canned cycles with G91 (incremental) are not supported: use G90";
            return Err(line.error_near(anchor, reason));
        }
        if self.modal.plane != Plane::Xy {
            let reason = "canned cycles are supported in the XY plane (G17) only";
            return Err(line.error_near(anchor, reason));
        }
        let scale = self.scale();
        let mut memory = self.modal.cycle;
        if let Some(z) = b.value(b'Z') {
            memory.bottom_z_mm = Some(z * scale);
        }
        if let Some(r) = b.value(b'R') {
            memory.r_plane_mm = Some(r * scale);
        }
        if kind == CycleKind::DwellAtBottom {
            read |= bit(b'P');
            if let Some(p) = b.value(b'P') {
                self.claim(b, line, b'P', code)?;
                if p < 0.0 {
                    return Err(line.error_at(b.word(b'P'), "a dwell cannot be negative"));
                }
                memory.dwell_s = Some(p);
            }
        }
        if kind == CycleKind::Peck {
            read |= bit(b'Q');
            if let Some(q) = b.value(b'Q') {
                self.claim(b, line, b'Q', code)?;
                memory.peck_mm = Some(q * scale);
            }
        }
        let missing = |what: &str| format!("{code} needs {what} on the first line of the cycle");
        let Some(bottom_z_mm) = memory.bottom_z_mm else {
            return Err(line.error_near(anchor, missing("Z (the bottom of the hole)")));
        };
        let Some(r_plane_mm) = memory.r_plane_mm else {
            return Err(line.error_near(anchor, missing("R (the retract plane)")));
        };
        let dwell_s = match (kind, memory.dwell_s) {
            (CycleKind::DwellAtBottom, None) => {
                return Err(line.error_near(anchor, missing("P (the dwell in seconds)")))
            }
            (_, dwell) => dwell.unwrap_or(0.0),
        };
        let peck_mm = match (kind, memory.peck_mm) {
            (CycleKind::Peck, None) => return Err(line.error_near(anchor, missing("Q (the peck depth)"))),
            (_, peck) => peck.unwrap_or(0.0),
        };
        if let Some(l) = b.value(b'L') {
            if !(is_integer(l) && l >= 1.0) {
                let reason = "L (repeats) must be a positive integer";
                return Err(line.error_at(b.word(b'L'), reason));
            }
            if l.round() > 1.0 {
                line.warn(format!("L{l} ignored: each position is drilled once"));
            }
        }
        self.modal.cycle = memory;
        let position = self.modal.position;
        let hole = Hole {
            kind,
            x_mm: b.value(b'X').map_or(position.x, |x| x * scale),
            y_mm: b.value(b'Y').map_or(position.y, |y| y * scale),
            bottom_z_mm,
            r_plane_mm,
            dwell_s,
            peck_mm,
            retract_to_r: self.modal.retract_to_r,
        };
        let mut steps = std::mem::take(&mut self.steps);
        let expanded = canned::expand_hole(position, &hole, &mut steps);
        if let Err(reason) = expanded {
            self.steps = steps;
            return Err(line.error_near(anchor, reason));
        }
        for step in &steps {
            match *step {
                Step::Rapid(p) => self.push_move(Motion::Rapid, p, line.number),
                Step::Feed(p) => self.push_move(Motion::Linear, p, line.number),
                Step::Dwell { seconds } => self.event(EventKind::Dwell { seconds }, line.number),
            }
        }
        self.steps = steps;
        Ok(read)
    }
}

/// The index of the first word of the line whose letter is in `letters`.
fn first_word(b: &Block, letters: u32) -> Option<usize> {
    (b'A'..=b'Z').filter(|&l| letters & b.present() & bit(l) != 0).map(|l| b.word(l)).min()
}
