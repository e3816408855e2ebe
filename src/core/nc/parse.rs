//! The modal interpreter: reads a program line by line, keeps the modal state (position,
//! units, plane, distance modes, motion mode, feed, spindle, tool) and turns each line into
//! moves and events. A line with an error changes nothing: its effects are rolled back.

use super::block::{bit, Block, GCode, MCode, MotionCode, INTEGER_TOLERANCE};
use super::canned::Step;
use super::error::{Diagnostics, NcErrors};
use super::lexer::{self, Issue, Word};
use super::report::{Failed, Line};
use super::{CannedCycles, ParseOptions, MM_PER_INCH};
use crate::core::toolpath::{Event, EventKind, Move, Plane, Toolpath, Units, P3};

/// Words a line usually has; the word buffer starts with room for this many.
const WORDS_PER_LINE: usize = 16;

/// The sticky values of a canned-cycle series (absolute, mm and s).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub(crate) struct CycleMemory {
    pub bottom_z_mm: Option<f64>,
    pub r_plane_mm: Option<f64>,
    pub dwell_s: Option<f64>,
    pub peck_mm: Option<f64>,
}

/// Everything a line can change besides the output lists.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Modal {
    pub position: P3,
    pub units: Units,
    pub plane: Plane,
    /// G90 (true) / G91.
    pub absolute: bool,
    /// G90.1 (true) / G91.1 (the default).
    pub absolute_centres: bool,
    pub motion: Option<MotionCode>,
    /// G99 (true) / G98 (the default).
    pub retract_to_r: bool,
    pub cycle: CycleMemory,
    pub feed_mm_min: Option<f64>,
    pub spindle_rpm: Option<f64>,
    /// The last T word (takes effect at M6).
    pub selected_tool: Option<u32>,
    pub tool: Option<u32>,
}

/// The interpreter's state and output.
pub(crate) struct Machine {
    pub modal: Modal,
    pub moves: Vec<Move>,
    pub events: Vec<Event>,
    /// M2/M30 was read: later lines are not.
    pub ended: bool,
    pub canned: CannedCycles,
    /// Buffer for expanded canned cycles.
    pub steps: Vec<Step>,
    /// Who reads this line's P and Q words (a word read twice is an error).
    pub p_reader: Option<&'static str>,
    pub q_reader: Option<&'static str>,
}

/// Reads a G-code program into a [`Toolpath`], or all the errors in it (at most
/// [`super::MAX_NC_ERRORS`]).
///
/// A Fanuc program number (`O1234`, alone on its line but for comments) before the first
/// line with words is read and ignored; every other O word, a second program number
/// included, is refused (subprograms).
pub fn parse_gcode(text: &str, options: &ParseOptions) -> Result<Toolpath, NcErrors> {
    let bytes = text.as_bytes();
    let lines = bytes.iter().filter(|&&b| b == b'\n').count() + 1;
    let mut machine = Machine::new(options, lines);
    let mut diagnostics = Diagnostics::default();
    let mut words: Vec<Word> = Vec::with_capacity(WORDS_PER_LINE);
    let mut issues: Vec<Issue> = Vec::new();
    let mut block = Block::default();
    // A line with words (or the program number) was read: an `O1234` line is no longer
    // a program number.
    let mut started = false;
    for (index, text) in bytes.split(|&b| b == b'\n').enumerate() {
        if machine.ended || diagnostics.full() {
            break;
        }
        words.clear();
        issues.clear();
        let shape = lexer::scan_line(text, &mut words, &mut issues);
        if shape.percent || (words.is_empty() && issues.is_empty() && !shape.block_delete) {
            continue;
        }
        let program_number = shape.program_number && !started;
        started = true;
        if program_number {
            continue;
        }
        let number = u32::try_from(index + 1).unwrap_or(u32::MAX);
        let mut line = Line::new(number, text, &words, &mut diagnostics, options.unknown_words);
        if shape.block_delete {
            line.warn("block delete (/) is not honoured: the line is read");
        }
        for issue in &issues {
            line.issue(issue);
        }
        block.fill(&words, &mut line);
        if !line.failed {
            machine.run_line(&block, &mut line);
        }
        if machine.moves.len() > options.max_moves {
            let reason = format!("the program makes more than {} moves (canned cycles expanded)", options.max_moves);
            line.error_near(None, reason).ignore();
            break;
        }
    }
    let warnings = diagnostics.finish()?;
    Ok(Toolpath { moves: machine.moves, events: machine.events, source_units: machine.modal.units, warnings })
}

/// Whether `value` is a whole number (within [`INTEGER_TOLERANCE`]).
pub(crate) fn is_integer(value: f64) -> bool {
    (value - value.round()).abs() <= INTEGER_TOLERANCE
}

impl Machine {
    fn new(options: &ParseOptions, lines: usize) -> Self {
        Machine {
            modal: Modal {
                position: options.initial_position,
                units: Units::Mm,
                plane: Plane::Xy,
                absolute: true,
                absolute_centres: false,
                motion: None,
                retract_to_r: false,
                cycle: CycleMemory::default(),
                feed_mm_min: None,
                spindle_rpm: None,
                selected_tool: None,
                tool: None,
            },
            moves: Vec::with_capacity(lines),
            events: Vec::new(),
            ended: false,
            canned: options.canned_cycles,
            steps: Vec::new(),
            p_reader: None,
            q_reader: None,
        }
    }

    /// Runs one line; on error, undoes everything it did.
    fn run_line(&mut self, b: &Block, line: &mut Line) {
        let saved = (self.modal, self.moves.len(), self.events.len());
        self.p_reader = None;
        self.q_reader = None;
        if self.execute(b, line).is_err() || line.failed {
            self.modal = saved.0;
            self.moves.truncate(saved.1);
            self.events.truncate(saved.2);
            self.ended = false;
        }
    }

    /// mm per program unit.
    pub fn scale(&self) -> f64 {
        match self.modal.units {
            Units::Mm => 1.0,
            Units::Inch => MM_PER_INCH,
        }
    }

    /// Records an event before the next move.
    pub fn event(&mut self, kind: EventKind, line: u32) {
        self.events.push(Event { kind, before_move: self.moves.len(), line });
    }

    /// Notes that word `letter` is read by `reader`; a second reader is an error.
    pub fn claim(&mut self, b: &Block, line: &mut Line, letter: u8, reader: &'static str) -> Result<(), Failed> {
        let slot = if letter == b'P' { &mut self.p_reader } else { &mut self.q_reader };
        match slot.replace(reader) {
            Some(first) if first != reader => Err(line.error_at(
                b.word(letter),
                format!("{first} and {reader} would both read this word: put them on separate lines"),
            )),
            _ => Ok(()),
        }
    }

    fn execute(&mut self, b: &Block, line: &mut Line) -> Result<(), Failed> {
        let mut used = bit(b'F') | bit(b'S') | bit(b'T');
        let mut explicit: Option<(MotionCode, usize)> = None;
        let (mut cancel, mut dwell, mut blending) = (None, None, None);
        for &(code, _, i) in &b.g {
            match code {
                GCode::Motion(m) => explicit = Some((m, i)),
                GCode::CancelCycle => cancel = Some(i),
                GCode::Dwell => dwell = Some(i),
                GCode::Plane(p) => self.modal.plane = p,
                GCode::Units(u) => self.modal.units = u,
                GCode::Distance { absolute } => self.modal.absolute = absolute,
                GCode::ArcDistance { absolute } => self.modal.absolute_centres = absolute,
                GCode::RetractToR(to_r) => self.modal.retract_to_r = to_r,
                GCode::ToolLength => used |= bit(b'H'),
                GCode::Blending => blending = Some(i),
                GCode::NoOp => {}
            }
        }
        self.feed_speed_tool(b, line)?;
        self.m_codes_before_motion(b, line)?;
        if let Some(i) = dwell {
            used |= bit(b'P');
            self.claim(b, line, b'P', "G4")?;
            let Some(seconds) = b.value(b'P') else {
                return Err(line.error_at(i, "G4 needs P, the dwell in seconds"));
            };
            if seconds < 0.0 {
                return Err(line.error_at(b.word(b'P'), "a dwell cannot be negative"));
            }
            self.event(EventKind::Dwell { seconds }, line.number);
        }
        if blending.is_some() && b.present() & (bit(b'P') | bit(b'Q')) != 0 {
            used |= bit(b'P') | bit(b'Q');
            for letter in [b'P', b'Q'] {
                if b.has(letter) {
                    self.claim(b, line, letter, "G64")?;
                }
            }
            line.warn("the G64 blending tolerance (P/Q) is ignored");
        }
        used |= self.motion(b, line, explicit, cancel)?;
        for &(code, _, _) in &b.m {
            match code {
                MCode::Stop => self.event(EventKind::Stop, line.number),
                MCode::End => {
                    self.event(EventKind::End, line.number);
                    self.ended = true;
                }
                _ => {}
            }
        }
        report_unused(b, line, used)
    }

    /// F, S and T words.
    fn feed_speed_tool(&mut self, b: &Block, line: &mut Line) -> Result<(), Failed> {
        if let Some(f) = b.value(b'F') {
            let feed = f * self.scale();
            if !(feed > 0.0 && feed.is_finite()) {
                return Err(line.error_at(b.word(b'F'), "the feed F must be > 0"));
            }
            self.modal.feed_mm_min = Some(feed);
        }
        if let Some(s) = b.value(b'S') {
            if s < 0.0 {
                return Err(line.error_at(b.word(b'S'), "the spindle speed S must be ≥ 0"));
            }
            self.modal.spindle_rpm = Some(s);
        }
        if let Some(t) = b.value(b'T') {
            if !(is_integer(t) && (0.0..=f64::from(u32::MAX)).contains(&t)) {
                let reason = "the tool number T must be a non-negative integer";
                return Err(line.error_at(b.word(b'T'), reason));
            }
            self.modal.selected_tool = Some(t.round() as u32);
        }
        Ok(())
    }

    /// M6, then M3/M4/M5, then M7/M8/M9 (the order LinuxCNC runs them in).
    fn m_codes_before_motion(&mut self, b: &Block, line: &mut Line) -> Result<(), Failed> {
        for &(code, _, i) in &b.m {
            if code == MCode::ToolChange {
                let Some(tool) = self.modal.selected_tool else {
                    return Err(line.error_at(i, "M6 with no tool selected: add a T word"));
                };
                self.modal.tool = Some(tool);
                self.event(EventKind::ToolChange { tool }, line.number);
            }
        }
        for &(code, _, _) in &b.m {
            if let MCode::Spindle(direction) = code {
                let kind = match direction {
                    Some(clockwise) => EventKind::SpindleOn { clockwise },
                    None => EventKind::SpindleOff,
                };
                self.event(kind, line.number);
            }
        }
        for &(code, _, _) in &b.m {
            if let MCode::Coolant { on } = code {
                self.event(EventKind::Coolant { on }, line.number);
            }
        }
        Ok(())
    }
}

/// Reports every word of the line that nothing read.
fn report_unused(b: &Block, line: &mut Line, used: u32) -> Result<(), Failed> {
    let unused = b.present() & !used;
    if unused == 0 {
        return Ok(());
    }
    for letter in b'A'..=b'Z' {
        if unused & bit(letter) != 0 {
            let reason = match letter {
                b'X' | b'Y' | b'Z' => "axis words need a motion mode: add G0 or G1",
                b'I' | b'J' | b'K' => "I/J/K (arc centre) need G2 or G3 and the matching plane",
                b'R' => "R needs G2/G3 (radius) or a canned cycle (retract plane)",
                b'P' => "P needs G4 (dwell), G2/G3 (turns), G64 or G82 (dwell)",
                b'Q' => "Q needs G83 (peck) or G64",
                b'L' => "L needs a canned cycle",
                b'H' => "H needs G43",
                _ => "nothing on this line reads this word",
            };
            line.error_at(b.word(letter), reason).ignore();
        }
    }
    Err(Failed)
}
