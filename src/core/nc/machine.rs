//! The modal machine: the state a program's lines change (position, units, plane,
//! distance and feed modes, spindle, tools, offsets, cutter compensation) and the part of
//! a line that is not motion, in the order LinuxCNC runs a line's words.

use super::block::{bit, Block};
use super::canned::Step;
use super::codes::{GCode, MCode, MotionCode};
use super::compensation::Compensation;
use super::frame::{Frame, SystemId};
use super::map::{FeedMode, LineMotion};
use super::options::ArcTolerance;
use super::report::{Failed, Line};
use super::tools::ToolTable;
use super::{CannedCycles, MM_PER_INCH};
use crate::core::toolpath::{Event, EventKind, Move, Plane, Units, P3};

/// The sticky values of a canned-cycle series (absolute, mm and s).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub(crate) struct CycleMemory {
    pub bottom_z_mm: Option<f64>,
    pub r_plane_mm: Option<f64>,
    pub dwell_s: Option<f64>,
    pub peck_mm: Option<f64>,
}

/// The active tool length offset.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum LengthOffset {
    /// G43 H (or the tool in the spindle).
    Table(u32),
    /// G43.1: the length itself, mm.
    Dynamic(f64),
}

/// Everything a line can change besides the output lists.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Modal {
    /// The programmed position, output coordinates (the contour point under cutter
    /// compensation).
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
    pub feed_mode: FeedMode,
    /// The G94 feed, mm/min.
    pub feed_mm_min: Option<f64>,
    /// The G95 feed, mm per revolution.
    pub feed_mm_rev: Option<f64>,
    pub spindle_rpm: Option<f64>,
    /// The last T word (takes effect at M6).
    pub selected_tool: Option<u32>,
    pub tool: Option<u32>,
    pub length_offset: Option<LengthOffset>,
}

/// How the machine reads (from the options, with the control resolved).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Settings {
    pub canned: CannedCycles,
    pub fanuc: bool,
    pub arc_tolerance: ArcTolerance,
    pub retract_z_mm: Option<f64>,
    pub tool_radius_mm: Option<f64>,
}

/// The interpreter's machine state and output.
pub(crate) struct Machine {
    pub modal: Modal,
    pub frame: Frame,
    pub tools: ToolTable,
    pub comp: Option<Compensation>,
    pub moves: Vec<Move>,
    pub events: Vec<Event>,
    /// M2/M30 was read: later lines are not.
    pub ended: bool,
    pub settings: Settings,
    /// Buffer for expanded canned cycles.
    pub steps: Vec<Step>,
    /// Who reads this line's P and Q words (a word read twice is an error).
    pub p_reader: Option<&'static str>,
    pub q_reader: Option<&'static str>,
    /// The highest Z the tool has been at (the default retract height), mm.
    pub highest_z: f64,
    /// The state M70/M73 saved.
    pub saved: Option<(Modal, SystemId)>,
    /// M73 on this line: the caller's flow restores the state when the subroutine ends.
    pub auto_restore: bool,
    /// G43 was used: feed moves under G49 get one warning.
    pub length_offset_used: bool,
    /// Warnings given once per program.
    pub warned: Vec<String>,
    /// F on this line, in G93 (1/min).
    pub inverse_feed: Option<f64>,
    /// A fault cutter compensation found in the line's move.
    pub comp_error: Option<String>,
    /// What the line being run moved, for the program map.
    pub line_motion: LineMotion,
}

impl Machine {
    pub fn new(initial_position: P3, settings: Settings, tools: ToolTable, lines: usize) -> Self {
        Machine {
            modal: Modal {
                position: initial_position,
                units: Units::Mm,
                plane: Plane::Xy,
                absolute: true,
                absolute_centres: false,
                motion: None,
                retract_to_r: false,
                cycle: CycleMemory::default(),
                feed_mode: FeedMode::PerMinute,
                feed_mm_min: None,
                feed_mm_rev: None,
                spindle_rpm: None,
                selected_tool: None,
                tool: None,
                length_offset: None,
            },
            frame: Frame::default(),
            tools,
            comp: None,
            moves: Vec::with_capacity(lines),
            events: Vec::new(),
            ended: false,
            settings,
            steps: Vec::new(),
            p_reader: None,
            q_reader: None,
            highest_z: initial_position.z,
            saved: None,
            auto_restore: false,
            length_offset_used: false,
            warned: Vec::new(),
            inverse_feed: None,
            comp_error: None,
            line_motion: LineMotion::None,
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

    /// A warning given once per program (`key` tells repeats apart).
    pub fn warn_once(&mut self, line: &mut Line, key: &str, message: impl std::fmt::Display) {
        if !self.warned.iter().any(|k| k == key) {
            self.warned.push(key.to_string());
            line.warn(message);
        }
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

    /// Runs one line (the words the control flow left); on error the caller undoes it.
    pub fn execute(&mut self, b: &Block, line: &mut Line) -> Result<(), Failed> {
        self.p_reader = None;
        self.q_reader = None;
        self.inverse_feed = None;
        self.auto_restore = false;
        self.line_motion = LineMotion::None;
        let mut used = bit(b'F') | bit(b'S') | bit(b'T');
        let mut explicit: Option<(MotionCode, usize)> = None;
        let (mut cancel, mut dwell, mut blending, mut axes_owner, mut machine_coords) = (None, None, None, None, None);
        let (mut comp, mut length, mut system) = (None, None, None);
        for &(code, _, i) in &b.g {
            match code {
                GCode::CutterComp(c) => comp = Some((c, i)),
                GCode::ToolLength(l) => length = Some((l, i)),
                GCode::CoordinateSystem(_) | GCode::ExtendedCoordinates => system = Some((code, i)),
                GCode::Motion(m) => explicit = Some((m, i)),
                GCode::CancelCycle => cancel = Some(i),
                GCode::Dwell => dwell = Some(i),
                GCode::Plane(p) => self.modal.plane = p,
                GCode::Units(u) => self.modal.units = u,
                GCode::Distance { absolute } => self.modal.absolute = absolute,
                GCode::ArcDistance { absolute } => self.modal.absolute_centres = absolute,
                GCode::RetractToR(to_r) => self.modal.retract_to_r = to_r,
                GCode::FeedMode(mode) => self.modal.feed_mode = mode,
                GCode::Blending => blending = Some(i),
                GCode::MachineCoordinates => machine_coords = Some(i),
                GCode::Home { .. } | GCode::SetHome | GCode::SetOffsets | GCode::AxisOffset(_) => {
                    axes_owner = Some((code, i));
                }
                GCode::HighSpeed { code } => used |= self.high_speed(b, line, code, i)?,
                GCode::SpindleMode { surface_speed } if surface_speed => {
                    line.warn("G96 (constant surface speed): the spindle speed varies with the diameter and is not known; S is not read as min⁻¹");
                }
                _ => {}
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
        if let Some((code, i)) = comp {
            used |= self.cutter_compensation(b, line, code, i)?;
        }
        if let Some((code, i)) = length {
            used |= self.tool_length(b, line, code, i)?;
        }
        if let Some((code, i)) = system {
            used |= self.coordinate_system(b, line, code, i)?;
        }
        if let Some((code, i)) = axes_owner {
            if let Some((_, j)) = explicit {
                let reason = "a motion code and G10/G28/G30/G52/G92 on one line would both use the axis words";
                return Err(line.error_at(j.max(i), reason));
            }
            used |= self.non_modal(b, line, code, i)?;
        } else {
            used |= self.motion(b, line, explicit, cancel, machine_coords)?;
        }
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

    /// Fanuc's G5/G5.1/G8 look-ahead modes read P and Q; in LinuxCNC G5 and G5.1 are
    /// splines.
    fn high_speed(&mut self, b: &Block, line: &mut Line, code: u32, i: usize) -> Result<u32, Failed> {
        const SPLINE_CODES: [u32; 2] = [50, 51];
        if !self.settings.fanuc && SPLINE_CODES.contains(&code) {
            return Err(line.error_at(i, super::codes::SPLINES));
        }
        let mut read = 0;
        for letter in [b'P', b'Q', b'R'] {
            if b.has(letter) {
                if letter != b'R' {
                    self.claim(b, line, letter, "G5.1/G8")?;
                }
                read |= bit(letter);
            }
        }
        Ok(read)
    }

    /// F, S and T words.
    fn feed_speed_tool(&mut self, b: &Block, line: &mut Line) -> Result<(), Failed> {
        if let Some(f) = b.value(b'F') {
            if !(f > 0.0 && f.is_finite()) {
                return Err(line.error_at(b.word(b'F'), "the feed F must be > 0"));
            }
            match self.modal.feed_mode {
                FeedMode::PerMinute => self.modal.feed_mm_min = Some(f * self.scale()),
                FeedMode::PerRevolution => self.modal.feed_mm_rev = Some(f * self.scale()),
                FeedMode::InverseTime => self.inverse_feed = Some(f),
            }
        }
        if let Some(s) = b.value(b'S') {
            if s < 0.0 {
                return Err(line.error_at(b.word(b'S'), "the spindle speed S must be ≥ 0"));
            }
            let surface_speed = b.g.iter().any(|g| g.0 == GCode::SpindleMode { surface_speed: true });
            self.modal.spindle_rpm = if surface_speed { None } else { Some(s) };
        }
        if b.has(b'T') {
            self.modal.selected_tool = Some(whole_number(b, line, b'T', "the tool number T")?);
        }
        Ok(())
    }

    /// M6, then M3/M4/M5, M70–M73, then M7/M8/M9 (the order LinuxCNC runs them in).
    fn m_codes_before_motion(&mut self, b: &Block, line: &mut Line) -> Result<(), Failed> {
        for &(code, _, i) in &b.m {
            if code == MCode::ToolChange {
                let Some(tool) = self.modal.selected_tool else {
                    return Err(line.error_at(i, "M6 with no tool selected: add a T word"));
                };
                if self.comp.is_some() {
                    return Err(
                        line.error_at(i, "a tool change while cutter compensation is on: turn it off (G40) first")
                    );
                }
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
        for &(code, _, i) in &b.m {
            if let MCode::ModalState(k) = code {
                self.modal_state(line, k, i)?;
            }
        }
        for &(code, _, _) in &b.m {
            if let MCode::Coolant { on } = code {
                self.event(EventKind::Coolant { on }, line.number);
            }
        }
        Ok(())
    }

    /// M70 saves the modal state, M71 forgets it, M72 restores it, M73 saves it for the
    /// end of the subroutine.
    fn modal_state(&mut self, line: &mut Line, k: u8, i: usize) -> Result<(), Failed> {
        match k {
            0 | 3 => {
                self.saved = Some((self.modal, self.frame.active));
                self.auto_restore = k == 3;
            }
            1 => self.saved = None,
            _ => {
                let Some(state) = self.saved else {
                    return Err(line.error_at(i, "M72 restores a state no M70 saved"));
                };
                self.restore(state);
            }
        }
        Ok(())
    }

    /// Restores a saved modal state (not the position or the tool in the spindle).
    pub fn restore(&mut self, (saved, system): (Modal, SystemId)) {
        let keep = self.modal;
        self.modal = Modal {
            position: keep.position,
            tool: keep.tool,
            selected_tool: keep.selected_tool,
            motion: keep.motion,
            cycle: keep.cycle,
            ..saved
        };
        self.frame.select(system);
    }
}

/// A word's value as a whole number ≥ 0.
pub(crate) fn whole_number(b: &Block, line: &mut Line, letter: u8, what: &str) -> Result<u32, Failed> {
    let v = b.value(letter).unwrap_or(0.0);
    if !(super::parse::is_integer(v) && (0.0..=f64::from(u32::MAX)).contains(&v)) {
        return Err(line.error_at(b.word(letter), format!("{what} must be a non-negative integer")));
    }
    Ok(v.round() as u32)
}

/// Reports every word of the line that nothing read.
fn report_unused(b: &Block, line: &mut Line, used: u32) -> Result<(), Failed> {
    let unused = b.present() & !used;
    if unused == 0 {
        return Ok(());
    }
    for slot in 0..28 {
        if unused & (1 << slot) == 0 {
            continue;
        }
        let letter = super::block::letter_of(slot) as u8;
        let reason = match letter {
            b'X' | b'Y' | b'Z' => "axis words need a motion mode: add G0 or G1",
            b'@' | b'^' => "polar words need a motion mode: add G0 or G1",
            b'I' | b'J' | b'K' => "I/J/K (arc centre) need G2 or G3 and the matching plane",
            b'R' => "R needs G2/G3 (radius), a canned cycle (retract plane) or G10",
            b'P' => "P needs G4 (dwell), G2/G3 (turns), G10, G54.1, G64 or a canned cycle",
            b'Q' => "Q needs a pecking cycle (G73, G83) or G64",
            b'L' => "L needs a canned cycle or G10",
            b'H' => "H needs G43",
            b'D' => "D needs G41 or G42",
            _ => "nothing on this line reads this word",
        };
        line.error_at(b.word(letter), reason).ignore();
    }
    Err(Failed)
}
