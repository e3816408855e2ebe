//! The motion of a line: rapid, linear and arc moves and canned cycles, in the modal
//! motion mode or the one the line sets, placed by the coordinate frame, fed in the feed
//! mode, and passed through cutter compensation when it is on.
//!
//! Rapid and linear moves whose end is their start (within
//! [`crate::core::tolerance::LENGTH_EPS_MM`] on every axis) are dropped: they take no time
//! and cut nothing, and CAM output has many (`G1 Z5` right after `G0 Z5`). The position,
//! feed and everything modal they set still apply. Arcs are never dropped: an arc whose end
//! is its start is a full circle.

use super::arcs::{self, coord, plane_axes, with_coord};
use super::block::{bit, Block, AXES, POLAR};
use super::canned::{self, CycleKind, Hole, Step};
use super::codes::MotionCode;
use super::machine::{CycleMemory, Machine};
use super::map::{ArcFormat, FeedMode, LineMotion, MotionContext};
use super::parse::is_integer;
use super::report::{Failed, Line};
use super::CannedCycles;
use crate::core::tolerance::{approx_eq, LENGTH_EPS_MM};
use crate::core::toolpath::move_length;
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
    /// of zero length) and makes `end` the current position. The move's feed comes from
    /// the feed mode.
    pub fn push_move(&mut self, motion: Motion, end: P3, line: u32) {
        let start = self.modal.position;
        self.modal.position = end;
        self.frame.start_moving();
        if !matches!(motion, Motion::Arc { .. }) && same_point(start, end) {
            return;
        }
        self.highest_z = self.highest_z.max(end.z).max(start.z);
        let mut m = Move {
            motion,
            start,
            end,
            feed_mm_min: None,
            spindle_rpm: self.modal.spindle_rpm,
            tool: self.modal.tool,
            line,
        };
        m.feed_mm_min = match self.modal.feed_mode {
            FeedMode::PerMinute => self.modal.feed_mm_min,
            FeedMode::PerRevolution => self.modal.feed_mm_rev.zip(self.modal.spindle_rpm).map(|(f, s)| f * s),
            FeedMode::InverseTime => self.inverse_feed.map(|f| f * move_length(&m)),
        };
        match self.comp.as_mut() {
            Some(comp) => {
                let mut out = Vec::new();
                match comp.push(m, &mut out) {
                    Ok(()) => self.moves.extend(out),
                    Err(reason) => self.comp_error = Some(reason),
                }
            }
            None => self.moves.push(m),
        }
    }

    /// Runs the motion of a line; returns the letters it read.
    pub fn motion(
        &mut self,
        b: &Block,
        line: &mut Line,
        explicit: Option<(MotionCode, usize)>,
        cancel: Option<usize>,
        machine_coords: Option<usize>,
    ) -> Result<u32, Failed> {
        let previous = self.modal.motion;
        if cancel.is_some() {
            self.modal.motion = None;
        }
        if let Some((code, i)) = explicit {
            if matches!(code, MotionCode::Cycle(_)) && self.settings.canned == CannedCycles::Refuse {
                return Err(line.error_at(i, CYCLES_NOT_EXPANDED));
            }
            if matches!(code, MotionCode::Cycle(_)) && previous != Some(code) {
                self.modal.cycle = CycleMemory::default();
            }
            self.modal.motion = Some(code);
        }
        let axes = b.present() & (AXES | POLAR);
        let anchor = explicit.map(|(_, i)| i).or_else(|| first_word(b, AXES | POLAR));
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
        if let Some(i) = machine_coords {
            if !matches!(mode, MotionCode::Rapid | MotionCode::Linear) {
                return Err(line.error_at(i, "G53 needs G0 or G1"));
            }
            if axes != 0 {
                self.retract(line, i, "G53")?;
            }
            return Ok(AXES);
        }
        let dz = self.tip_dz(line);
        self.frame.set_tip_dz(dz);
        if let Some(w) = self.frame.assumption_warning() {
            line.warn(w);
        }
        match mode {
            MotionCode::Rapid | MotionCode::Linear if axes != 0 => {
                let end = self.target(b, line)?;
                let motion = if mode == MotionCode::Rapid {
                    Motion::Rapid
                } else {
                    self.require_feed(line, anchor)?;
                    self.warn_g49(line);
                    Motion::Linear
                };
                self.direct(None, false);
                self.push_move(motion, end, line.number);
                self.comp_result(line, anchor)?;
                Ok(AXES | POLAR)
            }
            MotionCode::Arc { clockwise } => self.arc(b, line, clockwise, anchor),
            MotionCode::Cycle(kind) if axes != 0 => self.cycle(b, line, kind, anchor),
            _ => Ok(0),
        }
    }

    /// The state the line's motion is read in.
    pub fn context(&self, arc: Option<ArcFormat>, turns_word: bool) -> MotionContext {
        MotionContext {
            units: self.modal.units,
            absolute: self.modal.absolute,
            absolute_centres: self.modal.absolute_centres,
            plane: self.modal.plane,
            feed_mode: self.modal.feed_mode,
            spindle_rpm: self.modal.spindle_rpm,
            arc,
            turns_word,
            frame: self.frame.affine(),
        }
    }

    /// Records that the line's move is its own words' (unless compensation changes it).
    fn direct(&mut self, arc: Option<ArcFormat>, turns_word: bool) {
        let context = self.context(arc, turns_word);
        self.line_motion = if self.comp.is_some() { LineMotion::Derived(context) } else { LineMotion::Direct(context) };
    }

    /// A fault cutter compensation found in the line's move.
    fn comp_result(&mut self, line: &mut Line, anchor: Option<usize>) -> Result<(), Failed> {
        match self.comp_error.take() {
            Some(reason) => Err(line.error_near(anchor, reason)),
            None => Ok(()),
        }
    }

    /// One warning when feed moves run under G49 after the program used G43.
    fn warn_g49(&mut self, line: &mut Line) {
        if self.length_offset_used && self.modal.length_offset.is_none() {
            self.warn_once(
                line,
                "g49",
                "feed moves with the tool length offset cancelled (G49): Z is read as the tool tip",
            );
        }
    }

    fn require_feed(&self, line: &mut Line, anchor: Option<usize>) -> Result<(), Failed> {
        let missing = match self.modal.feed_mode {
            FeedMode::PerMinute => {
                self.modal.feed_mm_min.is_none().then_some("a feed move with no feed rate: add an F word")
            }
            FeedMode::PerRevolution if self.modal.feed_mm_rev.is_none() => {
                Some("a feed move with no feed per revolution (G95): add an F word")
            }
            FeedMode::PerRevolution => self
                .modal
                .spindle_rpm
                .is_none()
                .then_some("a feed per revolution (G95) needs the spindle speed: add an S word"),
            FeedMode::InverseTime => {
                self.inverse_feed.is_none().then_some("in inverse-time mode (G93) every feed move needs its own F word")
            }
        };
        match missing {
            Some(reason) => Err(line.error_near(anchor, reason)),
            None => Ok(()),
        }
    }

    /// The end point of a G0/G1/G2/G3 line, output coordinates.
    fn target(&self, b: &Block, line: &mut Line) -> Result<P3, Failed> {
        Ok(self.frame.to_out(self.program_target(b, line)?))
    }

    /// The end point of a motion line, program coordinates (mm).
    fn program_target(&self, b: &Block, line: &mut Line) -> Result<P3, Failed> {
        let scale = self.scale();
        let mut p = self.frame.to_program(self.modal.position);
        for (axis, letter) in [b'X', b'Y', b'Z'].into_iter().enumerate() {
            if let Some(v) = b.value(letter) {
                let v = v * scale;
                let value = if self.modal.absolute { v } else { coord(p, axis) + v };
                if !value.is_finite() {
                    return Err(line.error_at(b.word(letter), "the coordinate is out of range"));
                }
                p = with_coord(p, axis, value);
            }
        }
        if b.present() & POLAR != 0 {
            p = self.polar(b, line, p)?;
        }
        Ok(p)
    }

    /// LinuxCNC's polar words: `@` the distance from the origin, `^` the angle (degrees),
    /// absolute (G90) or added to the current polar coordinates (G91), in the XY plane.
    fn polar(&self, b: &Block, line: &mut Line, p: P3) -> Result<P3, Failed> {
        let i = first_word(b, POLAR).unwrap_or(0);
        if self.modal.plane != Plane::Xy {
            return Err(line.error_at(i, "polar coordinates (@, ^) work in the XY plane (G17) only"));
        }
        if b.has(b'X') || b.has(b'Y') {
            return Err(line.error_at(i, "give either X and Y or polar coordinates (@, ^), not both"));
        }
        let here = self.frame.to_program(self.modal.position);
        let (radius, angle) = (here.x.hypot(here.y), here.y.atan2(here.x));
        let at_origin = radius < LENGTH_EPS_MM;
        let distance = b.value(b'@').map(|d| d * self.scale());
        let theta = b.value(b'^').map(f64::to_radians);
        let (r, a) = if self.modal.absolute {
            if at_origin && theta.is_none() {
                return Err(line.error_at(i, "at the origin a polar move needs its angle (^)"));
            }
            (distance.unwrap_or(radius), theta.unwrap_or(angle))
        } else {
            if at_origin {
                return Err(line.error_at(i, "an incremental (G91) polar move from the origin has no direction"));
            }
            (radius + distance.unwrap_or(0.0), angle + theta.unwrap_or(0.0))
        };
        Ok(P3::new(r * a.cos(), r * a.sin(), p.z))
    }

    fn arc(&mut self, b: &Block, line: &mut Line, clockwise: bool, anchor: Option<usize>) -> Result<u32, Failed> {
        let plane = self.modal.plane;
        let [a, bb, n] = plane_axes(plane);
        let (la, lb) = (CENTRE_LETTERS[a], CENTRE_LETTERS[bb]);
        let centre_words = bit(la) | bit(lb);
        let read = AXES | POLAR | centre_words | bit(b'R') | bit(b'P');
        if b.present() & (AXES | POLAR | centre_words | bit(b'R')) == 0 {
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
        if plane != Plane::Xy && self.frame.affine().rotation_deg.abs() > f64::EPSILON {
            return Err(line.error_near(anchor, "arcs in G18/G19 in a rotated coordinate system are not supported"));
        }
        self.require_feed(line, anchor)?;
        self.warn_g49(line);
        let scale = self.scale();
        let start = self.frame.to_program(self.modal.position);
        let end = self.program_target(b, line)?;
        let anchor = anchor.or_else(|| first_word(b, centre_words | bit(b'R')));
        let tolerance = self.settings.arc_tolerance;
        let units = self.modal.units;
        let (centre, format) = match (b.value(b'R'), b.present() & centre_words != 0) {
            (Some(_), true) => {
                let reason = "give either R or I/J/K for an arc, not both";
                return Err(line.error_at(b.word(b'R'), reason));
            }
            (Some(r), false) => {
                let centre = arcs::centre_from_radius(start, end, plane, clockwise, r * scale, units, &tolerance)
                    .map_err(|reason| line.error_at(b.word(b'R'), reason))?;
                (centre, ArcFormat::Radius)
            }
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
                arcs::check_centre(start, centre, end, plane, units, &tolerance)
                    .map_err(|reason| line.error_near(anchor, reason))?;
                (centre, ArcFormat::Centre)
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
        let end_out = self.frame.to_out(end);
        let centre_out = with_coord(self.frame.to_out(centre), n, coord(self.modal.position, n));
        let motion = Motion::Arc { center: centre_out, clockwise, plane, turns };
        self.direct(Some(format), b.has(b'P'));
        self.push_move(motion, end_out, line.number);
        self.comp_result(line, anchor)?;
        Ok(read)
    }

    fn cycle(&mut self, b: &Block, line: &mut Line, kind: CycleKind, anchor: Option<usize>) -> Result<u32, Failed> {
        let code = kind.code();
        let mut read = AXES | bit(b'R') | bit(b'L') | bit(b'K');
        if kind == CycleKind::FineBore && !self.settings.fanuc {
            return Err(line.error_near(anchor, "G76 is LinuxCNC's lathe threading cycle, not a milling move"));
        }
        if self.comp.is_some() {
            return Err(
                line.error_near(anchor, "canned cycles while cutter compensation is on: turn it off (G40) first")
            );
        }
        if self.modal.feed_mode == FeedMode::InverseTime {
            return Err(line.error_near(anchor, "canned cycles cannot run in inverse-time feed mode (G93)"));
        }
        self.require_feed(line, anchor)?;
        if self.modal.plane != Plane::Xy {
            let reason = "canned cycles are supported in the XY plane (G17) only";
            return Err(line.error_near(anchor, reason));
        }
        if b.has(b'K') && !self.settings.fanuc {
            return Err(line.error_at(b.word(b'K'), "K is not a canned-cycle word in LinuxCNC: repeats are L"));
        }
        let scale = self.scale();
        let here = self.frame.to_program(self.modal.position);
        let mut memory = self.modal.cycle;
        // In G91, R is measured from the starting height and Z from R.
        let (z_word, r_word) = (b.value(b'Z').map(|z| z * scale), b.value(b'R').map(|r| r * scale));
        if self.modal.absolute {
            memory.bottom_z_mm = z_word.or(memory.bottom_z_mm);
            memory.r_plane_mm = r_word.or(memory.r_plane_mm);
        } else {
            if let Some(r) = r_word {
                memory.r_plane_mm = Some(here.z + r);
            }
            if let Some(z) = z_word {
                memory.bottom_z_mm = Some(memory.r_plane_mm.unwrap_or(here.z) + z);
            }
        }
        if kind.dwells() {
            read |= bit(b'P');
            if let Some(p) = b.value(b'P') {
                self.claim(b, line, b'P', code)?;
                if p < 0.0 {
                    return Err(line.error_at(b.word(b'P'), "a dwell cannot be negative"));
                }
                memory.dwell_s = Some(p);
            }
        }
        if kind.pecks() {
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
        if kind.needs_dwell() && memory.dwell_s.is_none() {
            return Err(line.error_near(anchor, missing("P (the dwell in seconds)")));
        }
        if kind.pecks() && memory.peck_mm.is_none() {
            return Err(line.error_near(anchor, missing("Q (the peck depth)")));
        }
        let repeats = match b.value(b'L').or(b.value(b'K')) {
            None => 1,
            Some(l) => {
                let letter = if b.has(b'L') { b'L' } else { b'K' };
                if !(is_integer(l) && (0.0..=f64::from(u16::MAX)).contains(&l)) {
                    let reason = "the repeat count must be a whole number from 0 to 65535";
                    return Err(line.error_at(b.word(letter), reason));
                }
                l.round() as u32
            }
        };
        self.modal.cycle = memory;
        let step = if self.modal.absolute { (0.0, 0.0) } else { incremental_xy(b, scale) };
        let mut hole_xy = if self.modal.absolute {
            (b.value(b'X').map_or(here.x, |x| x * scale), b.value(b'Y').map_or(here.y, |y| y * scale))
        } else {
            (here.x, here.y)
        };
        self.line_motion = LineMotion::Derived(self.context(None, false));
        for _ in 0..repeats {
            if !self.modal.absolute {
                hole_xy = (hole_xy.0 + step.0, hole_xy.1 + step.1);
            }
            let hole = Hole {
                kind,
                x_mm: hole_xy.0,
                y_mm: hole_xy.1,
                bottom_z_mm,
                r_plane_mm,
                dwell_s: if kind.dwells() { memory.dwell_s.unwrap_or(0.0) } else { 0.0 },
                peck_mm: memory.peck_mm.unwrap_or(0.0),
                retract_to_r: self.modal.retract_to_r,
            };
            self.drill(line, &hole, anchor)?;
        }
        Ok(read)
    }

    /// Expands one hole (program coordinates) into moves.
    fn drill(&mut self, line: &mut Line, hole: &Hole, anchor: Option<usize>) -> Result<(), Failed> {
        let mut steps = std::mem::take(&mut self.steps);
        let position = self.frame.to_program(self.modal.position);
        if let Err(reason) = canned::expand_hole(position, hole, &mut steps) {
            self.steps = steps;
            return Err(line.error_near(anchor, reason));
        }
        for step in &steps {
            match *step {
                Step::Rapid(p) => self.push_move(Motion::Rapid, self.frame.to_out(p), line.number),
                Step::Feed(p) => self.push_move(Motion::Linear, self.frame.to_out(p), line.number),
                Step::Dwell { seconds } => self.event(EventKind::Dwell { seconds }, line.number),
            }
        }
        self.steps = steps;
        Ok(())
    }
}

/// The X and Y steps of an incremental (G91) cycle, mm.
fn incremental_xy(b: &Block, scale: f64) -> (f64, f64) {
    (b.value(b'X').unwrap_or(0.0) * scale, b.value(b'Y').unwrap_or(0.0) * scale)
}

/// The index of the first word of the line whose letter is in `letters`.
pub(crate) fn first_word(b: &Block, letters: u32) -> Option<usize> {
    (0..28).filter(|&s| letters & b.present() & (1 << s) != 0).map(|s| b.word(super::block::letter_of(s) as u8)).min()
}
