//! NC programs out: a [`Toolpath`] written as G-code for a Fanuc (ISO) or a LinuxCNC
//! control, the inverse of [`parse_gcode`](super::parse_gcode): reading the output back
//! gives the same cutting moves and events, to the written resolution, and rapids to the
//! same points (see "Safety" for the rapids the writer adds or splits).
//!
//! The program (Fanuc; LinuxCNC has no `%` lines and no O number, puts the title in a
//! comment line of its own and ends with `M2`):
//!
//! ```text
//! %
//! O0001 (TITLE)
//! (TIMESTAMP, only if given)
//! G21 G17 G90 G94 G40 G80 G49
//! T1 M6                    the tool (unless the path changes tools before its first move)
//! G0 G43 H1 Z5.            its length offset, with Z alone to the safe height
//! S8000 M3                 if the path does not start the spindle before its first feed move
//! M7                       the options' coolant (M7 mist, M8 flood), if the path has none
//! (LAYER 1 Z-10 HELICAL BORING REGION 1)   the path's section labels
//! X50.606 Y25.             XY at the safe height
//! Z1.                      then down
//! …moves and events…
//! G0 Z5.                   Z alone back to the safe height
//! M5                       if the spindle runs
//! M9                       if the coolant is on
//! M30
//! %
//! ```
//!
//! - Always mm: a [`Toolpath`] is in mm whatever its source, so the writer writes `G21`.
//! - Modal: G0/G1/G2/G3 only when the motion changes, an axis only when its written value
//!   changes (values equal after rounding to `decimals`, i.e. within half a unit of the last
//!   digit, are not repeated), F when the written feed changes (never on a G0), S when the written speed
//!   changes, G17/G18/G19 before an arc in another plane.
//! - Safety (any path, generated or sent as JSON moves; see `writer/safety.rs`): the safe
//!   height is the options' `safe_z_mm` or the path's highest point, whichever is higher. The
//!   tool is called with `T.. M6` and its length offset applied with `G43 H..` on a move of
//!   Z alone to the safe height, at the start and at every tool change of the path (which
//!   retracts Z alone to the safe height first). The first move after that goes to its XY
//!   at the safe height, then down. A rapid that moves in Z and in XY is written as two: Z
//!   first when it rises, XY first when it descends. The footer retracts Z alone to the safe
//!   height, stops the spindle (`M5`) and the coolant (`M9`) if they run, and ends.
//! - Sections: each [`EventKind::Section`] label of the path is a comment line before the
//!   part it starts, `(LAYER 2 Z-20 TROCHOIDAL GROOVING REGION 1)`: layer and region counted
//!   from 1, the height at the written resolution, upper-case words.
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
//!   event is the footer (moves after it are not written).
//! - N numbers (optional) on every line but `%` and the O line, comments included,
//!   restarting at `start` after [`MAX_SEQUENCE_NUMBER`] (the largest both controls read).
//! - Deterministic: the same path and options give the same bytes; a timestamp appears
//!   only when given.
//! - Moves are taken as continuous (each starts where the one before ended), as the G-code
//!   and JSON readers make them: only end points are written (and the start of the first
//!   move, or of the first after a tool change, when it is a feed move).

mod arc;
pub(crate) mod format;
mod options;
mod safety;
mod turns;

#[cfg(test)]
mod round_trip_tests;
#[cfg(test)]
mod safety_tests;
#[cfg(test)]
mod tests;

use self::format::{comment_text, section_text, Fixed};
use self::turns::split_turns;
use crate::core::toolpath::{Event, EventKind, Motion, Move, Plane, Toolpath, P3};

pub use self::format::MAX_DECIMALS;
pub use self::options::{
    Coolant, Dialect, LineNumbers, WriterOptions, DEFAULT_DECIMALS, DEFAULT_FEED_DECIMALS, DEFAULT_TOOL_NUMBER,
};
pub use self::safety::highest_point_mm;

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
const M_COOLANT_MIST: u32 = 7;
const M_COOLANT_FLOOD: u32 = 8;
const M_COOLANT_OFF: u32 = 9;
const M_END_LINUXCNC: u32 = 2;
const M_END_FANUC: u32 = 30;

/// The safety line: mm, XY plane, absolute, feed per minute, no cutter compensation, no
/// canned cycle, no length offset (the tool call applies its own).
const SAFETY_LINE: &str = "G21 G17 G90 G94 G40 G80 G49";

/// Writes `path` as an NC program (see the module documentation for its layout).
pub fn write_program(path: &Toolpath, options: &WriterOptions) -> String {
    write_program_mapped(path, options).text
}

/// A written program and where each move of the path went.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct WrittenProgram {
    pub text: String,
    /// Per move of the path: the (1-based) line of the text that ends it (its own block;
    /// a Fanuc arc of several turns ends on its last piece). Moves after the path's end
    /// event are not written and have none.
    pub move_lines: Vec<u32>,
}

/// [`write_program`], with the line of each move.
pub fn write_program_mapped(path: &Toolpath, options: &WriterOptions) -> WrittenProgram {
    let mut writer = Writer::new(path, options);
    writer.header();
    writer.body();
    writer.footer();
    WrittenProgram { text: writer.out, move_lines: writer.move_lines }
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
    /// Written axis values (units of 10^−decimals); `None` where unknown: X and Y before
    /// the first move and after a tool change.
    position: [Option<i64>; 3],
    motion: Option<u32>,
    plane: Plane,
    feed: Option<i64>,
    spindle: Option<i64>,
    spindle_running: bool,
    coolant_on: bool,
    /// Coolant still to switch on after the next spindle start.
    coolant_pending: Option<Coolant>,
    /// The header's spindle start, still to write before the first section or move.
    start_pending: bool,
    /// `options.spindle_rpm` if no move has a speed.
    fallback_rpm: Option<f64>,
    /// The safe height (units of 10^−decimals); `None` only for a path without moves and
    /// options without a safe height.
    safe_z: Option<i64>,
    /// Lines written so far, and the line ending each move written.
    lines_written: u32,
    move_lines: Vec<u32>,
}

impl<'a> Writer<'a> {
    fn new(path: &'a Toolpath, options: &'a WriterOptions) -> Self {
        let has_speed = path.moves.iter().any(|m| m.spindle_rpm.is_some());
        let has_coolant = path.events.iter().any(|e| matches!(e.kind, EventKind::Coolant { .. }));
        let decimals = options.decimals.min(MAX_DECIMALS);
        let safe_z = [options.safe_z_mm, highest_point_mm(path)]
            .into_iter()
            .flatten()
            .map(|z| Fixed::round(z, decimals).units)
            .max();
        Writer {
            path,
            options,
            fanuc: options.dialect == Dialect::Fanuc,
            decimals,
            out: String::with_capacity(path.moves.len() * 32 + 256),
            line: String::new(),
            sequence: options.line_numbers.map(|n| n.start.min(MAX_SEQUENCE_NUMBER)),
            position: [None; 3],
            motion: None,
            plane: Plane::Xy,
            feed: None,
            spindle: None,
            spindle_running: false,
            coolant_on: false,
            coolant_pending: (options.coolant != Coolant::Off && !has_coolant).then_some(options.coolant),
            start_pending: false,
            fallback_rpm: if has_speed { None } else { options.spindle_rpm },
            safe_z,
            lines_written: 0,
            move_lines: Vec::with_capacity(path.moves.len()),
        }
    }

    // --- lines and words ---

    /// Writes a line that never gets an N number (`%`, the O line).
    fn raw_line(&mut self, text: &str) {
        self.out.push_str(text);
        self.out.push('\n');
        self.lines_written += 1;
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
        self.lines_written += 1;
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

    // --- header and events ---

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
        self.line.push_str(SAFETY_LINE);
        self.end_line();
        let calls_tool_first =
            path.events.iter().any(|e| matches!(e.kind, EventKind::ToolChange { .. }) && e.before_move == 0);
        if !calls_tool_first {
            let tool = options.tool_number.or_else(|| path.moves.first().and_then(|m| m.tool));
            let tool = tool.unwrap_or(DEFAULT_TOOL_NUMBER);
            self.call_tool(tool, options.length_offset.unwrap_or(tool));
        }
        let first_feed = path.moves.iter().position(|m| !matches!(m.motion, Motion::Rapid)).unwrap_or(path.moves.len());
        self.start_pending =
            !path.events.iter().any(|e| matches!(e.kind, EventKind::SpindleOn { .. }) && e.before_move <= first_feed);
    }

    /// Writes the moves and the events between them, up to the path's `End` event; after
    /// the last move, Z alone back to the safe height before the events that follow it.
    fn body(&mut self) {
        let path = self.path;
        let mut events: Vec<&Event> = path.events.iter().collect();
        events.sort_by_key(|e| e.before_move);
        let end = events.iter().find(|e| e.kind == EventKind::End).map_or(usize::MAX, |e| e.before_move);
        let mut next = 0;
        for (i, m) in path.moves.iter().enumerate().take(end) {
            while let Some(e) = events.get(next).filter(|e| e.before_move <= i) {
                self.event(e);
                next += 1;
            }
            self.start_if_pending();
            self.write_move(m);
            self.move_lines.push(self.lines_written);
        }
        self.retract();
        for e in &events[next..] {
            if !self.event(e) {
                return;
            }
        }
    }

    /// Writes an event; `false` at the end of the program.
    fn event(&mut self, e: &Event) -> bool {
        match e.kind {
            EventKind::ToolChange { tool } => self.call_tool(tool, tool),
            EventKind::SpindleOn { clockwise } => {
                let rpm = self.path.moves.get(e.before_move).and_then(|m| m.spindle_rpm).or(self.fallback_rpm);
                self.spindle_on(clockwise, rpm);
            }
            EventKind::SpindleOff => {
                self.spindle_running = false;
                self.code_line('M', M_SPINDLE_OFF);
            }
            EventKind::Dwell { seconds } => {
                self.code('G', G_DWELL);
                let letter = if self.fanuc { 'X' } else { 'P' };
                self.number(letter, Fixed::round(seconds, DWELL_DECIMALS));
                self.end_line();
            }
            EventKind::Coolant { on } => {
                self.coolant_on = on;
                let code = match (on, self.options.coolant) {
                    (false, _) => M_COOLANT_OFF,
                    (true, Coolant::Mist) => M_COOLANT_MIST,
                    (true, _) => M_COOLANT_FLOOD,
                };
                self.code_line('M', code);
            }
            EventKind::Stop => self.code_line('M', M_STOP),
            EventKind::End => return false,
            EventKind::Section(section) => {
                self.start_if_pending();
                let text = section_text(&section, self.decimals);
                self.comment_line(&text);
            }
        }
        true
    }

    /// The header's spindle start, if it is still to be written.
    fn start_if_pending(&mut self) {
        if std::mem::take(&mut self.start_pending) {
            let rpm = self.path.moves.first().and_then(|m| m.spindle_rpm).or(self.fallback_rpm);
            self.spindle_on(true, rpm);
        }
    }

    /// `S.. M3` (S if it changes), then the coolant if it is still to come.
    fn spindle_on(&mut self, clockwise: bool, rpm: Option<f64>) {
        if let Some(rpm) = rpm {
            self.speed(rpm);
        }
        self.code_line('M', if clockwise { M_SPINDLE_CLOCKWISE } else { M_SPINDLE_COUNTER_CLOCKWISE });
        self.spindle_running = true;
        if let Some(coolant) = self.coolant_pending.take() {
            self.coolant_on = true;
            self.code_line('M', if coolant == Coolant::Mist { M_COOLANT_MIST } else { M_COOLANT_FLOOD });
        }
    }

    // --- moves ---

    fn write_move(&mut self, m: &Move) {
        let rapid = matches!(m.motion, Motion::Rapid);
        if self.position[0].is_none() || self.position[1].is_none() {
            // Where the tool is in XY is unknown: go to the move's start (a rapid's end) over
            // the safe height.
            let target = self.units_of(if rapid { m.end } else { m.start });
            self.rapid_to(target, Some(m));
            if rapid {
                return;
            }
        }
        match m.motion {
            Motion::Rapid => self.rapid_to(self.units_of(m.end), Some(m)),
            Motion::Linear => self.straight(m),
            Motion::Arc { turns, .. } if self.fanuc && turns > 0 => {
                for piece in split_turns(m) {
                    self.arc(&piece);
                }
            }
            Motion::Arc { .. } => self.arc(m),
        }
    }

    /// The G code if it changes.
    fn motion_code(&mut self, code: u32) {
        if self.motion != Some(code) {
            self.code('G', code);
            self.motion = Some(code);
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

    /// A G1 move; nothing if no written axis changes.
    fn straight(&mut self, m: &Move) {
        let end = self.units_of(m.end);
        if (0..3).all(|axis| self.position[axis] == Some(end[axis])) {
            return;
        }
        self.motion_code(G_LINEAR);
        self.axes(end);
        self.feed_and_speed(m);
        self.end_line();
    }
}
