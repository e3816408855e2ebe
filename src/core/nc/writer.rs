//! NC programs out: a [`Toolpath`] written as G-code for a Fanuc (ISO) or a LinuxCNC
//! control, the inverse of [`parse_gcode`](super::parse_gcode): reading the output back
//! gives the same moves and events, to the written resolution.
//!
//! The program (Fanuc; LinuxCNC has no `%` lines and no O number, puts the title in a
//! comment line of its own and ends with `M2`):
//!
//! ```text
//! %
//! O0001 (TITLE)
//! (TIMESTAMP, only if given)
//! G21 G17 G90 G94 G40 G80 [G49 if the program changes tools]
//! [T1 M6 if the path has no tool change and a tool is known]
//! [S8000 M3 if the path does not start the spindle before its first feed move]
//! [M8 after the first spindle start, if `coolant` and the path has no coolant events]
//! …moves and events…
//! [M9 if the coolant is on]
//! M30
//! %
//! ```
//!
//! - Always mm: a [`Toolpath`] is in mm whatever its source, so the writer writes `G21`.
//! - Modal: G0/G1/G2/G3 only when the motion changes, an axis only when its written value
//!   changes (values equal after rounding to `decimals`, i.e. within half a unit of the last
//!   digit, are not repeated), F when the written feed changes (never on a G0), S when the written speed
//!   changes, G17/G18/G19 before an arc in another plane. The first move, and the first
//!   after a tool change, writes all three axes.
//! - Tool changes: `T.. M6`, then `G43 H..` (the tool's length offset) on the next move,
//!   which restates all three axes (a Fanuc applies the offset with a Z move); on a line
//!   of its own if that move is an arc. `G49` in the safety line cancels an earlier offset
//!   only in programs that change tools, so a program without tool changes keeps the
//!   offset the machine has.
//! - Arcs: centres as incremental I/J/K (the in-plane two, the default arc-centre mode of
//!   both controls), chosen on the written grid so that the start and end radii agree; a
//!   full circle (end = start in the plane) and a helix (axial motion) are one block.
//!   Extra turns are LinuxCNC's `P(turns + 1)`; Fanuc has no turn count, so the arc is
//!   written as full circles and the final arc, keeping the helix pitch. An arc too small
//!   for the resolution (ends rounding together on less than a half turn, or a radius the
//!   controls' check would refuse) is a G1 to its end.
//! - Comments: `(` `)` become `[` `]`, `%` and control characters spaces; Fanuc comments
//!   are upper-case ASCII; a LinuxCNC comment that would be a command (`MSG,`…) gets a
//!   leading `-`.
//! - Numbers: rounded half away from zero to `decimals` (feeds to `feed_decimals`),
//!   trailing zeros trimmed, never `-0`; Fanuc writes a decimal point on every length and
//!   feed (`X10.`: without it a Fanuc reads ten least increments). S, T, H, P and N are
//!   whole numbers. Dwells: `G4 P<s>` (LinuxCNC) or `G4 X<s>.` (Fanuc, seconds).
//! - Events go before the move they precede, in order; a stop is `M0`. The path's `End`
//!   event is the footer (moves after it are not written). The spindle is not stopped with
//!   `M5` at the end: `M30`/`M2` stop it.
//! - N numbers (optional) on every line but `%` and the O line, restarting at `start`
//!   after [`MAX_SEQUENCE_NUMBER`] (the largest both controls read).
//! - Deterministic: the same path and options give the same bytes; a timestamp appears
//!   only when given.
//! - Moves are taken as continuous (each starts where the one before ended), as the G-code
//!   and JSON readers make them: only end points are written.

mod arc;
pub(crate) mod format;
mod options;
mod turns;

#[cfg(test)]
mod round_trip_tests;
#[cfg(test)]
mod tests;

use self::format::{comment_text, Fixed};
use self::turns::split_turns;
use crate::core::toolpath::{Event, EventKind, Motion, Move, Plane, Toolpath, P3};

pub use self::format::MAX_DECIMALS;
pub use self::options::{Dialect, LineNumbers, WriterOptions, DEFAULT_DECIMALS, DEFAULT_FEED_DECIMALS};

/// Largest N number: LinuxCNC refuses larger ones and many Fanuc controls read 5 digits.
pub const MAX_SEQUENCE_NUMBER: u32 = 99_999;

/// Dwells are written to the millisecond.
const DWELL_DECIMALS: u32 = 3;

/// Spindle speeds are written in whole min⁻¹ (a Fanuc refuses a point in S).
const SPINDLE_DECIMALS: u32 = 0;

/// Fanuc program numbers are written with at least this many digits (`O0001`).
const PROGRAM_NUMBER_DIGITS: usize = 4;

/// The letters of the axes and of the arc-centre offsets, X, Y, Z order.
const AXIS_LETTERS: [char; 3] = ['X', 'Y', 'Z'];
const CENTRE_LETTERS: [char; 3] = ['I', 'J', 'K'];

/// G codes the writer uses.
const G_RAPID: u32 = 0;
const G_LINEAR: u32 = 1;
const G_CLOCKWISE: u32 = 2;
const G_COUNTER_CLOCKWISE: u32 = 3;
const G_DWELL: u32 = 4;
const G_LENGTH_OFFSET: u32 = 43;

/// M codes the writer uses.
const M_STOP: u32 = 0;
const M_SPINDLE_CLOCKWISE: u32 = 3;
const M_SPINDLE_COUNTER_CLOCKWISE: u32 = 4;
const M_SPINDLE_OFF: u32 = 5;
const M_TOOL_CHANGE: u32 = 6;
const M_COOLANT_ON: u32 = 8;
const M_COOLANT_OFF: u32 = 9;
const M_END_LINUXCNC: u32 = 2;
const M_END_FANUC: u32 = 30;

/// The safety line: mm, XY plane, absolute, feed per minute, no cutter compensation, no
/// canned cycle. `G49` is added in programs that change tools.
const SAFETY_LINE: &str = "G21 G17 G90 G94 G40 G80";
const CANCEL_LENGTH_OFFSET: &str = " G49";

/// Writes `path` as an NC program (see the module documentation for its layout).
pub fn write_program(path: &Toolpath, options: &WriterOptions) -> String {
    let mut writer = Writer::new(path, options);
    writer.header();
    writer.body();
    writer.footer();
    writer.out
}

/// The writer's state: what the control knows from the lines written so far.
struct Writer<'a> {
    path: &'a Toolpath,
    options: &'a WriterOptions,
    fanuc: bool,
    decimals: u32,
    out: String,
    /// The line being built.
    line: String,
    /// The next N number, if lines are numbered.
    sequence: Option<u32>,
    /// Written axis values (units of 10^−decimals); `None` before the first move and after
    /// a tool change.
    position: [Option<i64>; 3],
    motion: Option<u32>,
    plane: Plane,
    feed: Option<i64>,
    spindle: Option<i64>,
    coolant_on: bool,
    /// `M8` is still to be written after the next spindle start.
    coolant_pending: bool,
    /// `G43 H..` is still to be written for this tool.
    length_offset_pending: Option<u32>,
    /// `options.spindle_rpm` if no move has a speed.
    fallback_rpm: Option<f64>,
}

impl<'a> Writer<'a> {
    fn new(path: &'a Toolpath, options: &'a WriterOptions) -> Self {
        let has_speed = path.moves.iter().any(|m| m.spindle_rpm.is_some());
        let has_coolant = path.events.iter().any(|e| matches!(e.kind, EventKind::Coolant { .. }));
        Writer {
            path,
            options,
            fanuc: options.dialect == Dialect::Fanuc,
            decimals: options.decimals.min(MAX_DECIMALS),
            out: String::with_capacity(path.moves.len() * 32 + 256),
            line: String::new(),
            sequence: options.line_numbers.map(|n| n.start.min(MAX_SEQUENCE_NUMBER)),
            position: [None; 3],
            motion: None,
            plane: Plane::Xy,
            feed: None,
            spindle: None,
            coolant_on: false,
            coolant_pending: options.coolant && !has_coolant,
            length_offset_pending: None,
            fallback_rpm: if has_speed { None } else { options.spindle_rpm },
        }
    }

    // --- lines and words ---

    /// Writes a line that never gets an N number (`%`, the O line).
    fn raw_line(&mut self, text: &str) {
        self.out.push_str(text);
        self.out.push('\n');
    }

    /// Ends the line being built (nothing if it is empty), with its N number.
    fn end_line(&mut self) {
        if self.line.is_empty() {
            return;
        }
        if let (Some(n), Some(numbers)) = (self.sequence, self.options.line_numbers) {
            self.out.push('N');
            self.out.push_str(&n.to_string());
            self.out.push(' ');
            let next = n.saturating_add(numbers.step);
            self.sequence =
                Some(if next > MAX_SEQUENCE_NUMBER { numbers.start.min(MAX_SEQUENCE_NUMBER) } else { next });
        }
        self.out.push_str(&self.line);
        self.out.push('\n');
        self.line.clear();
    }

    fn separate(&mut self) {
        if !self.line.is_empty() {
            self.line.push(' ');
        }
    }

    /// A word with a whole number (G, M, S, T, H, P).
    fn code(&mut self, letter: char, value: u32) {
        self.separate();
        self.line.push(letter);
        self.line.push_str(&value.to_string());
    }

    /// A word with a rounded number; a Fanuc writes the point of whole numbers.
    fn number(&mut self, letter: char, value: Fixed) {
        self.separate();
        self.line.push(letter);
        value.push_to(&mut self.line, self.fanuc);
    }

    fn comment_line(&mut self, text: &str) {
        self.separate();
        self.line.push('(');
        self.line.push_str(&comment_text(text, self.fanuc));
        self.line.push(')');
        self.end_line();
    }

    fn code_line(&mut self, letter: char, value: u32) {
        self.code(letter, value);
        self.end_line();
    }

    fn fixed(&self, value_mm: f64) -> Fixed {
        Fixed::round(value_mm, self.decimals)
    }

    fn units_of(&self, p: P3) -> [i64; 3] {
        [self.fixed(p.x).units, self.fixed(p.y).units, self.fixed(p.z).units]
    }

    fn mm(&self, units: i64) -> f64 {
        Fixed { units, decimals: self.decimals }.value()
    }

    // --- header, events, footer ---

    fn header(&mut self) {
        let path = self.path;
        let options = self.options;
        if self.fanuc {
            self.raw_line("%");
            let mut o_line = format!("O{:0width$}", options.program_number, width = PROGRAM_NUMBER_DIGITS);
            if let Some(title) = &options.title {
                o_line.push_str(&format!(" ({})", comment_text(title, true)));
            }
            self.raw_line(&o_line);
        } else if let Some(title) = &options.title {
            self.comment_line(title);
        }
        if let Some(timestamp) = &options.timestamp {
            self.comment_line(timestamp);
        }
        let changes_tool = path.events.iter().any(|e| matches!(e.kind, EventKind::ToolChange { .. }));
        let header_tool =
            if changes_tool { None } else { options.tool_number.or_else(|| path.moves.first().and_then(|m| m.tool)) };
        self.line.push_str(SAFETY_LINE);
        if changes_tool || header_tool.is_some() {
            self.line.push_str(CANCEL_LENGTH_OFFSET);
        }
        self.end_line();
        if let Some(tool) = header_tool {
            self.tool_change(tool);
        }
        let first_feed = path.moves.iter().position(|m| !matches!(m.motion, Motion::Rapid)).unwrap_or(path.moves.len());
        let started =
            path.events.iter().any(|e| matches!(e.kind, EventKind::SpindleOn { .. }) && e.before_move <= first_feed);
        if !started {
            let rpm = path.moves.first().and_then(|m| m.spindle_rpm).or(self.fallback_rpm);
            self.spindle_on(true, rpm);
        }
    }

    /// Writes the moves and the events between them, up to the path's `End` event.
    fn body(&mut self) {
        let path = self.path;
        let mut events: Vec<&Event> = path.events.iter().collect();
        events.sort_by_key(|e| e.before_move);
        let mut next = 0;
        for (i, m) in path.moves.iter().enumerate() {
            while let Some(e) = events.get(next).filter(|e| e.before_move <= i) {
                if !self.event(e) {
                    return;
                }
                next += 1;
            }
            self.write_move(m);
        }
        for e in &events[next..] {
            if !self.event(e) {
                return;
            }
        }
    }

    /// Writes an event; `false` at the end of the program.
    fn event(&mut self, e: &Event) -> bool {
        match e.kind {
            EventKind::ToolChange { tool } => self.tool_change(tool),
            EventKind::SpindleOn { clockwise } => {
                let rpm = self.path.moves.get(e.before_move).and_then(|m| m.spindle_rpm).or(self.fallback_rpm);
                self.spindle_on(clockwise, rpm);
            }
            EventKind::SpindleOff => self.code_line('M', M_SPINDLE_OFF),
            EventKind::Dwell { seconds } => {
                self.code('G', G_DWELL);
                let letter = if self.fanuc { 'X' } else { 'P' };
                self.number(letter, Fixed::round(seconds, DWELL_DECIMALS));
                self.end_line();
            }
            EventKind::Coolant { on } => {
                self.coolant_on = on;
                self.code_line('M', if on { M_COOLANT_ON } else { M_COOLANT_OFF });
            }
            EventKind::Stop => self.code_line('M', M_STOP),
            EventKind::End => return false,
        }
        true
    }

    /// `T.. M6`; the next move restates every axis and applies the length offset.
    fn tool_change(&mut self, tool: u32) {
        self.code('T', tool);
        self.code_line('M', M_TOOL_CHANGE);
        self.length_offset_pending = Some(tool);
        self.position = [None; 3];
        self.motion = None;
    }

    /// `S.. M3` (S if it changes), then `M8` if it is still to come.
    fn spindle_on(&mut self, clockwise: bool, rpm: Option<f64>) {
        if let Some(rpm) = rpm {
            self.speed(rpm);
        }
        self.code_line('M', if clockwise { M_SPINDLE_CLOCKWISE } else { M_SPINDLE_COUNTER_CLOCKWISE });
        if self.coolant_pending {
            self.coolant_pending = false;
            self.coolant_on = true;
            self.code_line('M', M_COOLANT_ON);
        }
    }

    fn footer(&mut self) {
        if self.coolant_on {
            self.code_line('M', M_COOLANT_OFF);
        }
        self.code_line('M', if self.fanuc { M_END_FANUC } else { M_END_LINUXCNC });
        if self.fanuc {
            self.raw_line("%");
        }
    }

    // --- moves ---

    fn write_move(&mut self, m: &Move) {
        match m.motion {
            Motion::Rapid => self.straight(m, G_RAPID),
            Motion::Linear => self.straight(m, G_LINEAR),
            Motion::Arc { turns, .. } if self.fanuc && turns > 0 => {
                for piece in split_turns(m) {
                    self.arc(&piece);
                }
            }
            Motion::Arc { .. } => self.arc(m),
        }
    }

    /// The G code if it changes, and a pending length offset.
    fn motion_code(&mut self, code: u32) {
        if self.motion != Some(code) {
            self.code('G', code);
            self.motion = Some(code);
        }
        if let Some(tool) = self.length_offset_pending.take() {
            self.code('G', G_LENGTH_OFFSET);
            self.code('H', tool);
        }
    }

    /// The axis words of `end` that differ from the written position.
    fn axes(&mut self, end: [i64; 3]) {
        for (axis, letter) in AXIS_LETTERS.into_iter().enumerate() {
            if self.position[axis] != Some(end[axis]) {
                self.number(letter, Fixed { units: end[axis], decimals: self.decimals });
            }
        }
        self.position = end.map(Some);
    }

    /// F (on feed moves: a rapid's modal feed waits for the next feed move) and S if they
    /// change.
    fn feed_and_speed(&mut self, m: &Move) {
        if let (Some(feed), false) = (m.feed_mm_min, matches!(m.motion, Motion::Rapid)) {
            let feed = Fixed::round(feed, self.options.feed_decimals);
            if self.feed != Some(feed.units) {
                self.number('F', feed);
                self.feed = Some(feed.units);
            }
        }
        if let Some(rpm) = m.spindle_rpm {
            self.speed(rpm);
        }
    }

    /// An S word if the written speed changes.
    fn speed(&mut self, rpm: f64) {
        let rpm = Fixed::round(rpm, SPINDLE_DECIMALS);
        if self.spindle != Some(rpm.units) {
            self.separate();
            self.line.push('S');
            rpm.push_to(&mut self.line, false);
            self.spindle = Some(rpm.units);
        }
    }

    /// A G0 or G1 move; nothing if no written axis changes.
    fn straight(&mut self, m: &Move, code: u32) {
        let end = self.units_of(m.end);
        if (0..3).all(|axis| self.position[axis] == Some(end[axis])) {
            return;
        }
        self.motion_code(code);
        self.axes(end);
        self.feed_and_speed(m);
        self.end_line();
    }
}
