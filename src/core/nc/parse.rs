//! The interpreter's driver: runs a program line after line from a program counter (so
//! that loops, jumps and calls work), reading plain lines with the fast scanner and the
//! others in full, evaluating their expressions, and handing the words to the modal
//! machine. A line with an error changes nothing: its effects are rolled back.

use std::collections::HashMap;
use std::rc::Rc;

use super::block::{Block, INTEGER_TOLERANCE};
use super::codes::{GCode, MCode};
use super::error::{Diagnostics, NcErrors};
use super::eval::{evaluate, index_of};
use super::expr::ParamRef;
use super::flow::Flow;
use super::lexer::{self, Issue, Word};
use super::line::{parse_line, Item, ParsedLine};
use super::machine::{Machine, Settings};
use super::map::ProgramMap;
use super::options::Control;
use super::params::ParamStore;
use super::report::Line;
use super::system::{self, Env, Written};
use super::tools::ToolTable;
use super::ParseOptions;
use crate::core::toolpath::{EventKind, Toolpath};

/// Words a line usually has; the word buffer starts with room for this many.
const WORDS_PER_LINE: usize = 16;

/// A program read by the interpreter: the tool path, and how each line ran.
#[derive(Debug, Clone, PartialEq)]
pub struct Interpreted {
    pub path: Toolpath,
    pub map: ProgramMap,
}

/// Reads a G-code program into a [`Toolpath`], or all the errors in it (at most
/// [`super::MAX_NC_ERRORS`]).
pub fn parse_gcode(text: &str, options: &ParseOptions) -> Result<Toolpath, NcErrors> {
    run_program(text, options, false).map(|i| i.path)
}

/// Runs a G-code program: its tool path and how each of its lines ran.
pub fn interpret(text: &str, options: &ParseOptions) -> Result<Interpreted, NcErrors> {
    run_program(text, options, true)
}

fn run_program(text: &str, options: &ParseOptions, with_map: bool) -> Result<Interpreted, NcErrors> {
    let bytes = text.as_bytes();
    let mut lines: Vec<(u32, u32)> = Vec::with_capacity(bytes.len() / 24 + 1);
    let mut start = 0usize;
    for (i, &b) in bytes.iter().enumerate() {
        if b == b'\n' {
            lines.push((start as u32, i as u32));
            start = i + 1;
        }
    }
    lines.push((start as u32, bytes.len() as u32));
    let settings = Settings {
        canned: options.canned_cycles,
        fanuc: options.control == Control::Fanuc,
        arc_tolerance: options.arc_tolerance,
        retract_z_mm: options.retract_z_mm,
        tool_radius_mm: options.tool_radius_mm,
    };
    let machine = Machine::new(options.initial_position, settings, ToolTable::new(&options.tool_table), lines.len());
    let mut run = Run {
        text: bytes,
        map: ProgramMap::new(if with_map { lines.len() } else { 0 }, Control::Auto),
        with_map,
        control: (options.control != Control::Auto).then_some(options.control),
        flow: Flow::new(options.max_loop_iterations, options.max_call_depth),
        lines,
        machine,
        params: ParamStore::new(options.control == Control::Fanuc),
        diagnostics: Diagnostics::default(),
        options,
        parsed: HashMap::new(),
        order: Vec::new(),
        started: false,
    };
    run.go();
    run.finish()
}

/// Whether `value` is a whole number (within [`INTEGER_TOLERANCE`]).
pub(crate) fn is_integer(value: f64) -> bool {
    (value - value.round()).abs() <= INTEGER_TOLERANCE
}

/// What the control flow asks of the driver after a line.
pub(crate) enum Next {
    /// Go on with the line after it.
    Continue,
    /// Go on at this 0-based line.
    Jump(usize),
    /// The program ends here.
    End,
}

/// One run of a program.
pub(crate) struct Run<'a> {
    pub text: &'a [u8],
    pub lines: Vec<(u32, u32)>,
    pub machine: Machine,
    pub params: ParamStore,
    pub flow: Flow,
    pub diagnostics: Diagnostics,
    pub options: &'a ParseOptions,
    pub map: ProgramMap,
    /// Whether the map of the lines is kept.
    with_map: bool,
    /// Whose rules apply, once a line needed to know.
    control: Option<Control>,
    /// Lines read in full, kept for loops.
    parsed: HashMap<usize, Rc<ParsedLine>>,
    /// The lines in the order they ran.
    order: Vec<u32>,
    /// A line with words was read (a program number is no longer the first line).
    pub started: bool,
}

impl<'a> Run<'a> {
    /// Settles whose rules apply (the first time a line's meaning depends on it).
    pub fn ensure_control(&mut self) {
        if self.control.is_some() {
            return;
        }
        let control = super::control::resolve_control(self.text);
        let fanuc = control == Control::Fanuc;
        self.control = Some(control);
        self.machine.settings.fanuc = fanuc;
        self.params.set_fanuc(fanuc);
    }

    /// Records how 0-based line `index` ran, when the map is kept.
    pub fn record(&mut self, index: usize, motion: super::map::LineMotion) {
        if self.with_map {
            self.map.record(index, motion);
        }
    }

    /// The text of 0-based line `index`.
    pub fn line_text(&self, index: usize) -> &[u8] {
        let (s, e) = self.lines[index];
        &self.text[s as usize..e as usize]
    }

    fn go(&mut self) {
        let mut words: Vec<Word> = Vec::with_capacity(WORDS_PER_LINE);
        let mut issues: Vec<Issue> = Vec::new();
        let mut block = Block::default();
        let mut pc = 0usize;
        let mut percents = 0;
        loop {
            if self.machine.ended || self.diagnostics.full() {
                break;
            }
            if pc >= self.lines.len() {
                self.unreturned_call();
                break;
            }
            let index = pc;
            pc += 1;
            let (s, e) = self.lines[index];
            let all: &'a [u8] = self.text;
            let text = &all[s as usize..e as usize];
            words.clear();
            issues.clear();
            let shape = lexer::scan_line(text, &mut words, &mut issues);
            if shape.percent {
                percents += 1;
                // The closing tape mark ends the program text.
                if percents > 1 || self.started {
                    break;
                }
                continue;
            }
            if words.is_empty() && issues.is_empty() && !shape.block_delete {
                continue;
            }
            let number = u32::try_from(index + 1).unwrap_or(u32::MAX);
            if self.with_map {
                self.order.push(number);
            }
            let next = if issues.is_empty() {
                self.run_words(index, number, text, &words, &mut block, shape.block_delete)
            } else {
                self.run_parsed(index, number, &mut block)
            };
            self.started = true;
            match next {
                Next::Continue => {}
                Next::Jump(to) => {
                    pc = to;
                }
                Next::End => break,
            }
            if self.machine.moves.len() > self.options.max_moves {
                let mut line = Line::new(number, text, &[], &mut self.diagnostics, self.options.unknown_words);
                let reason = format!(
                    "the program makes more than {} moves (canned cycles expanded, loops run)",
                    self.options.max_moves
                );
                line.error_near(None, reason).ignore();
                break;
            }
        }
    }

    /// Runs a line read in full: control statements go to the flow, words and
    /// assignments to the machine.
    fn run_parsed(&mut self, index: usize, number: u32, block: &mut Block) -> Next {
        self.ensure_control();
        let parsed = match self.parsed.get(&index) {
            Some(p) => Rc::clone(p),
            None => {
                let p = Rc::new(parse_line(self.line_text(index)));
                self.parsed.insert(index, Rc::clone(&p));
                p
            }
        };
        let all: &'a [u8] = self.text;
        let (s, e) = self.lines[index];
        let text = &all[s as usize..e as usize];
        let mut failed = false;
        if !parsed.faults.is_empty() {
            let mut line = Line::new(number, text, &[], &mut self.diagnostics, self.options.unknown_words);
            for f in &parsed.faults {
                line.fault(f);
            }
            failed = line.failed;
        }
        if let Some(control) = parsed.items.iter().find(|s| s.item.is_control()) {
            if failed {
                return Next::Continue;
            }
            return self.flow_item(index, number, control);
        }
        // Evaluate every value before any assignment takes effect (LinuxCNC's rule).
        let mut words = Vec::with_capacity(parsed.items.len());
        let mut assigns = Vec::new();
        let mut faults = Vec::new();
        {
            let env = Env { store: &self.params, machine: &self.machine };
            for s in &parsed.items {
                match &s.item {
                    Item::Word { letter, value } => match evaluate(value, &env) {
                        Ok(Some(v)) => words.push(Word { letter: *letter, value: v, start: s.start, end: s.end }),
                        // A vacant value drops the word in Fanuc (LinuxCNC reads 0, never vacant).
                        Ok(None) => {}
                        Err(reason) => faults.push((s.start, s.end, reason)),
                    },
                    Item::Assign { target, value } => {
                        let target = match target {
                            ParamRef::Index(i) => index_of(i, &env).map(Target::Numbered),
                            ParamRef::Name(n) => Ok(Target::Named(n.clone())),
                        };
                        match (target, evaluate(value, &env)) {
                            (Ok(t), Ok(v)) => assigns.push((t, v, s.start, s.end)),
                            (Err(reason), _) | (_, Err(reason)) => faults.push((s.start, s.end, reason)),
                        }
                    }
                    _ => {}
                }
            }
        }
        if !faults.is_empty() || failed {
            let mut line = Line::new(number, text, &[], &mut self.diagnostics, self.options.unknown_words);
            for (s, e, reason) in faults {
                line.error_on(s, e, reason).ignore();
            }
            return Next::Continue;
        }
        let next = if words.is_empty() && !parsed.block_delete {
            self.record(index, super::map::LineMotion::None);
            Next::Continue
        } else {
            self.run_words(index, number, text, &words, block, parsed.block_delete)
        };
        let mut line = Line::new(number, text, &words, &mut self.diagnostics, self.options.unknown_words);
        for (target, value, s, e) in assigns {
            if let Err(reason) = assign(&mut self.params, &mut self.machine, &target, value) {
                line.error_on(s, e, reason).ignore();
            } else if matches!(target, Target::Numbered(3006)) && self.machine.settings.fanuc {
                self.machine.event(EventKind::Stop, number);
            }
        }
        next
    }

    /// Runs the words of one line on the machine (and M98/M99/G65 through the flow).
    fn run_words(
        &mut self,
        index: usize,
        number: u32,
        text: &[u8],
        words: &[Word],
        block: &mut Block,
        block_delete: bool,
    ) -> Next {
        if let Some(next) = self.macro_call(index, number, words) {
            return next;
        }
        let mut line = Line::new(number, text, words, &mut self.diagnostics, self.options.unknown_words);
        if block_delete {
            line.warn("block delete (/) is not honoured: the line is read");
        }
        block.fill(words, &mut line);
        let call = block.m.iter().find(|m| matches!(m.0, MCode::SubCall | MCode::SubReturn)).map(|m| (m.0, m.2));
        let call_words = match call {
            Some((MCode::SubCall, _)) => (block.take(b'P'), block.take(b'L')),
            Some(_) => (block.take(b'P'), None),
            None => (None, None),
        };
        if line.failed {
            return Next::Continue;
        }
        let mut line = if self.control.is_none() && (call.is_some() || depends_on_control(block)) {
            self.ensure_control();
            Line::new(number, text, words, &mut self.diagnostics, self.options.unknown_words)
        } else {
            line
        };
        let saved_modal = self.machine.modal;
        let saved_counts = (self.machine.moves.len(), self.machine.events.len());
        let heavy = block.g.iter().any(|g| {
            matches!(
                g.0,
                GCode::SetOffsets
                    | GCode::AxisOffset(_)
                    | GCode::CoordinateSystem(_)
                    | GCode::ExtendedCoordinates
                    | GCode::CutterComp(_)
            )
        }) || self.machine.comp.is_some();
        let saved_state =
            heavy.then(|| (self.machine.frame.clone(), self.machine.tools.clone(), self.machine.comp.clone()));
        let result = self.machine.execute(block, &mut line);
        if result.is_err() || line.failed {
            self.machine.modal = saved_modal;
            self.machine.moves.truncate(saved_counts.0);
            self.machine.events.truncate(saved_counts.1);
            self.machine.ended = false;
            if let Some((frame, tools, comp)) = saved_state {
                self.machine.frame = frame;
                self.machine.tools = tools;
                self.machine.comp = comp;
            }
            return Next::Continue;
        }
        self.record(index, self.machine.line_motion);
        if self.machine.auto_restore {
            self.flow.auto_restore(self.machine.saved);
        }
        match call {
            Some((MCode::SubCall, i)) => self.m98(number, words, i, call_words, index),
            Some((_, i)) => self.m99(number, words, i, call_words.0, index),
            None => Next::Continue,
        }
    }

    /// A G65 line is a macro call: its words are the arguments.
    fn macro_call(&mut self, index: usize, number: u32, words: &[Word]) -> Option<Next> {
        let g65 = words.iter().position(|w| w.letter == b'G' && (w.value - 65.0).abs() < INTEGER_TOLERANCE)?;
        self.ensure_control();
        Some(self.g65(number, words, g65, index))
    }

    /// Runs a control statement.
    fn flow_item(&mut self, index: usize, number: u32, item: &super::line::Spanned) -> Next {
        self.record(index, super::map::LineMotion::None);
        self.control(index, number, item)
    }

    /// Reports an error on a line (with no words to point at).
    pub fn line_error(&mut self, number: u32, index: usize, start: u32, end: u32, reason: impl Into<String>) {
        let (s, e) = self.lines[index];
        let all: &'a [u8] = self.text;
        let text = &all[s as usize..e as usize];
        let mut line = Line::new(number, text, &[], &mut self.diagnostics, self.options.unknown_words);
        line.error_on(start, end, reason).ignore();
    }

    /// Adds a warning about a line.
    pub fn line_warning(&mut self, number: u32, message: impl std::fmt::Display) {
        self.diagnostics.warn(format!("line {number}: {message}"));
    }

    fn finish(mut self) -> Result<Interpreted, NcErrors> {
        if self.machine.comp.is_some() && !self.diagnostics.full() {
            let number = self.order.last().copied().unwrap_or(1);
            let index = number as usize - 1;
            let (s, e) = self.lines[index.min(self.lines.len() - 1)];
            let all: &'a [u8] = self.text;
            let text = &all[s as usize..e as usize];
            let mut line = Line::new(number, text, &[], &mut self.diagnostics, self.options.unknown_words);
            line.warn("cutter compensation is still on at the end of the program");
            // An error is reported on the line.
            let _ = self.machine.end_compensation(&mut line, None);
        }
        let warnings = self.diagnostics.finish()?;
        if self.flow.jumped() && self.with_map {
            self.map.order = Some(self.order);
        }
        self.map.control = self.control.unwrap_or(Control::Auto);
        let path = Toolpath {
            moves: self.machine.moves,
            events: self.machine.events,
            source_units: self.machine.modal.units,
            warnings,
        };
        Ok(Interpreted { path, map: self.map })
    }
}

/// Whether a line's meaning depends on whose rules apply (LinuxCNC's or Fanuc's).
fn depends_on_control(block: &Block) -> bool {
    use super::canned::CycleKind;
    use super::codes::{CompCode, MotionCode};
    block.g.iter().any(|g| {
        matches!(
            g.0,
            GCode::HighSpeed { .. }
                | GCode::SetOffsets
                | GCode::CutterComp(CompCode::Table { .. } | CompCode::Diameter { .. })
                | GCode::Motion(MotionCode::Cycle(CycleKind::FineBore))
        )
    }) || block.has(b'K')
}

/// What an assignment sets.
pub(crate) enum Target {
    Numbered(u32),
    Named(String),
}

/// Sets a parameter (a system parameter through the machine).
pub(crate) fn assign(
    params: &mut ParamStore,
    machine: &mut Machine,
    target: &Target,
    value: Option<f64>,
) -> Result<(), String> {
    match target {
        Target::Named(name) => {
            params.set_named(name, value.unwrap_or(0.0));
            Ok(())
        }
        Target::Numbered(n) => match system::write(machine, *n, value)? {
            Written::Store => params.set(*n, value),
            Written::Done | Written::Stop => Ok(()),
        },
    }
}
