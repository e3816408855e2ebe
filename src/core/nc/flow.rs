//! Control flow: where a program goes after a line. LinuxCNC O-words (`sub`/`endsub`/
//! `call`/`return`, `if`/`elseif`/`else`/`endif`, `while`/`endwhile`, `do`/`while`,
//! `repeat`/`endrepeat`, `break`, `continue`) and Fanuc Custom Macro B (`IF [..] GOTO n`,
//! `IF [..] THEN`, `GOTO n`, `WHILE [..] DO m` … `END m`, `M98 P L`, `M99 [P]`, `G65 P L`
//! with arguments), in the same program text.
//!
//! Labels (O-words, program numbers, N numbers, loop numbers) are found once, the first
//! time the program jumps or calls. Every backward jump counts as a loop iteration, and
//! calls nest at most so deep: a program that exceeds either stops with an error naming
//! the line, so a loop that never ends cannot hang the service.

use std::collections::HashMap;

use super::eval::evaluate;
use super::expr::Expr;
use super::frame::SystemId;
use super::line::{parse_line, Item, OKeyword, OName, Spanned, Then};
use super::machine::Modal;
use super::parse::{assign, is_integer, Next, Run, Target};
use super::system::Env;

/// A byte span of a line: where a fault is reported.
pub(crate) type Span = (u32, u32);

/// Where the labels of a program are.
#[derive(Debug, Default)]
pub(crate) struct Labels {
    pub(crate) owords: HashMap<OName, Vec<(usize, OKeyword)>>,
    pub(crate) programs: HashMap<u32, usize>,
    pub(crate) program_starts: Vec<usize>,
    pub(crate) loops: HashMap<u32, Vec<(usize, bool)>>,
    pub(crate) sequence: HashMap<u32, Vec<usize>>,
}

#[derive(Debug, Clone)]
pub(crate) enum FrameKind {
    Sub(OName),
    /// M98 (`macro_call` false) or G65: the repeats left, and where the subprogram starts.
    Program {
        remaining: u32,
        start: usize,
        macro_call: bool,
    },
}

#[derive(Debug, Clone)]
pub(crate) struct Repeat {
    pub(crate) name: OName,
    pub(crate) line: usize,
    pub(crate) remaining: u64,
}

#[derive(Debug, Clone)]
pub(crate) struct CallFrame {
    pub(crate) kind: FrameKind,
    pub(crate) return_to: usize,
    pub(crate) call_line: u32,
    pub(crate) repeats: Vec<Repeat>,
    pub(crate) restore: Option<(Modal, SystemId)>,
}

/// The control flow's state.
#[derive(Debug, Default)]
pub(crate) struct Flow {
    pub(crate) labels: Option<Labels>,
    pub(crate) frames: Vec<CallFrame>,
    pub(crate) main_repeats: Vec<Repeat>,
    pub(crate) iterations: u64,
    pub(crate) max_iterations: u64,
    pub(crate) max_depth: u32,
    /// The line a failed `if`/`elseif` jumped to (it may take its branch).
    pub(crate) if_target: Option<usize>,
    pub(crate) jumped: bool,
}

impl Flow {
    pub fn new(max_iterations: u64, max_depth: u32) -> Self {
        Flow { max_iterations, max_depth, ..Flow::default() }
    }

    /// Whether the program jumped or called (its lines did not run in text order).
    pub fn jumped(&self) -> bool {
        self.jumped
    }

    /// M73: the state is restored when the current subroutine returns.
    pub fn auto_restore(&mut self, saved: Option<(Modal, SystemId)>) {
        if let Some(frame) = self.frames.last_mut() {
            frame.restore = saved;
        }
    }

    pub(crate) fn repeats(&mut self) -> &mut Vec<Repeat> {
        match self.frames.last_mut() {
            Some(f) => &mut f.repeats,
            None => &mut self.main_repeats,
        }
    }
}

/// Finds the labels of the program text.
fn find_labels(run: &Run) -> Labels {
    let mut labels = Labels::default();
    let mut percents = 0;
    for index in 0..run.lines.len() {
        let text = run.line_text(index);
        let mut i = 0;
        let skip_blanks = |i: &mut usize| {
            while *i < text.len() && matches!(text[*i], b' ' | b'\t' | b'\r') {
                *i += 1;
            }
        };
        skip_blanks(&mut i);
        if text.get(i) == Some(&b'%') {
            percents += 1;
            if percents > 1 {
                break;
            }
            continue;
        }
        if text.get(i) == Some(&b'/') {
            i += 1;
            skip_blanks(&mut i);
        }
        if matches!(text.get(i), Some(b'N' | b'n')) {
            let digits: String =
                text[i + 1..].iter().take_while(|b| b.is_ascii_digit()).map(|&b| char::from(b)).collect();
            if let Ok(n) = digits.parse::<u32>() {
                labels.sequence.entry(n).or_default().push(index);
            }
            i += 1 + digits.len();
            skip_blanks(&mut i);
        }
        if !matches!(text.get(i).map(u8::to_ascii_uppercase), Some(b'O' | b'W' | b'D' | b'E')) {
            continue;
        }
        for s in parse_line(text).items {
            match s.item {
                Item::OWord { name, keyword, .. } => labels.owords.entry(name).or_default().push((index, keyword)),
                Item::ProgramLabel { number } => {
                    labels.programs.entry(number).or_insert(index);
                    labels.program_starts.push(index);
                }
                Item::While { id, .. } | Item::Do { id } => labels.loops.entry(id).or_default().push((index, false)),
                Item::End { id } => labels.loops.entry(id).or_default().push((index, true)),
                _ => {}
            }
        }
    }
    labels
}

impl Run<'_> {
    pub(crate) fn labels(&mut self) -> &Labels {
        if self.flow.labels.is_none() {
            let labels = find_labels(self);
            self.flow.labels = Some(labels);
        }
        self.flow.labels.as_ref().expect("just found")
    }

    pub(crate) fn eval(&self, e: &Expr) -> Result<Option<f64>, String> {
        evaluate(e, &Env { store: &self.params, machine: &self.machine })
    }

    pub(crate) fn truth(&self, e: &Expr) -> Result<bool, String> {
        Ok(self.eval(e)?.is_some_and(|v| v != 0.0))
    }

    pub(crate) fn fail(&mut self, number: u32, index: usize, s: Span, reason: impl Into<String>) -> Next {
        self.line_error(number, index, s.0, s.1, reason);
        Next::End
    }

    pub(crate) fn jump(&mut self, to: usize) -> Next {
        self.flow.jumped = true;
        Next::Jump(to)
    }

    /// A jump back: one more loop iteration.
    pub(crate) fn jump_back(&mut self, to: usize, number: u32, index: usize, s: Span) -> Next {
        self.flow.iterations += 1;
        if self.flow.iterations > self.flow.max_iterations {
            let max = self.flow.max_iterations;
            return self.fail(
                number,
                index,
                s,
                format!("the program's loops repeat more than {max} times: does a loop never end? (max_loop_iterations raises the limit)"),
            );
        }
        self.jump(to)
    }

    /// Checks the call depth before a call.
    pub(crate) fn call_depth_ok(&mut self, number: u32, index: usize, s: Span) -> bool {
        if self.flow.frames.len() as u32 >= self.flow.max_depth {
            let max = self.flow.max_depth;
            self.fail(
                number,
                index,
                s,
                format!("calls nest deeper than {max}: does a subroutine call itself without end?"),
            );
            return false;
        }
        true
    }

    /// The first line after `index` where O-word `name` has one of `keywords`.
    pub(crate) fn o_after(&mut self, name: &OName, index: usize, keywords: &[OKeyword]) -> Option<usize> {
        let list = self.labels().owords.get(name)?;
        list.iter().find(|(l, k)| *l > index && keywords.contains(k)).map(|(l, _)| *l)
    }

    /// The last line before `index` where O-word `name` has one of `keywords`.
    pub(crate) fn o_before(&mut self, name: &OName, index: usize, keywords: &[OKeyword]) -> Option<usize> {
        let list = self.labels().owords.get(name)?;
        list.iter().rev().find(|(l, k)| *l < index && keywords.contains(k)).map(|(l, _)| *l)
    }

    /// The keyword of O-word `name` on the line before `index`'s entry.
    pub(crate) fn previous_keyword(&mut self, name: &OName, index: usize) -> Option<OKeyword> {
        let list = self.labels().owords.get(name)?;
        list.iter().rev().find(|(l, _)| *l < index).map(|(_, k)| *k)
    }

    /// Runs a control statement of line `index`.
    pub(crate) fn control(&mut self, index: usize, number: u32, s: &Spanned) -> Next {
        let from_if = self.flow.if_target.take() == Some(index);
        match &s.item {
            Item::OWord { name, keyword, args } => self.o_word(index, number, s, name, *keyword, args, from_if),
            Item::ProgramLabel { number: p } => {
                if !self.started {
                    return Next::Continue;
                }
                if self.flow.frames.is_empty() {
                    self.line_warning(number, format!("the main program has no M30: it ends where O{p} starts"));
                    return Next::End;
                }
                self.fail(number, index, (s.start, s.end), format!("the subprogram runs into O{p} without M99"))
            }
            Item::If { cond, then } => match self.truth(cond) {
                Err(reason) => self.fail(number, index, (s.start, s.end), reason),
                Ok(false) => Next::Continue,
                Ok(true) => match then {
                    Then::Goto(target) => self.goto(index, number, s, target),
                    Then::Assign(assigns) => {
                        for (target, value) in assigns {
                            let result = self.assign_now(target, value);
                            if let Err(reason) = result {
                                return self.fail(number, index, (s.start, s.end), reason);
                            }
                        }
                        Next::Continue
                    }
                },
            },
            Item::Goto { target } => self.goto(index, number, s, target),
            Item::While { cond, id } => match self.truth(cond) {
                Err(reason) => self.fail(number, index, (s.start, s.end), reason),
                Ok(true) => Next::Continue,
                Ok(false) => match self.loop_end(*id, index) {
                    Some(end) => self.jump(end + 1),
                    None => self.fail(number, index, (s.start, s.end), format!("WHILE … DO {id} has no END {id}")),
                },
            },
            Item::Do { .. } => Next::Continue,
            Item::End { id } => {
                let start = self
                    .labels()
                    .loops
                    .get(id)
                    .and_then(|l| l.iter().rev().find(|(line, end)| *line < index && !*end).map(|(line, _)| *line));
                match start {
                    Some(start) => self.jump_back(start, number, index, (s.start, s.end)),
                    None => self.fail(number, index, (s.start, s.end), format!("END {id} has no DO {id} before it")),
                }
            }
            Item::Word { .. } | Item::Assign { .. } => Next::Continue,
        }
    }

    fn loop_end(&mut self, id: u32, index: usize) -> Option<usize> {
        let list = self.labels().loops.get(&id)?;
        list.iter().find(|(line, end)| *line > index && *end).map(|(line, _)| *line)
    }

    fn assign_now(&mut self, target: &super::expr::ParamRef, value: &Expr) -> Result<(), String> {
        let v = self.eval(value)?;
        let target = match target {
            super::expr::ParamRef::Index(i) => {
                Target::Numbered(super::eval::index_of(i, &Env { store: &self.params, machine: &self.machine })?)
            }
            super::expr::ParamRef::Name(n) => Target::Named(n.clone()),
        };
        assign(&mut self.params, &mut self.machine, &target, v)
    }

    /// Fanuc `GOTO n`: the line numbered N n in the current program, after this line or
    /// else from the program's start.
    fn goto(&mut self, index: usize, number: u32, s: &Spanned, target: &Expr) -> Next {
        let n = match self.eval(target) {
            Ok(Some(v)) if is_integer(v) && v >= 0.0 => v.round() as u32,
            Ok(_) => return self.fail(number, index, (s.start, s.end), "GOTO needs a sequence number ≥ 0"),
            Err(reason) => return self.fail(number, index, (s.start, s.end), reason),
        };
        match self.sequence_in_program(n, index, index) {
            Some(to) if to <= index => self.jump_back(to, number, index, (s.start, s.end)),
            Some(to) => self.jump(to),
            None => self.fail(number, index, (s.start, s.end), format!("GOTO {n}: no line N{n} in this program")),
        }
    }

    /// The line numbered `n` in the program that holds line `within`, searching after
    /// `from` first.
    pub(crate) fn sequence_in_program(&mut self, n: u32, within: usize, from: usize) -> Option<usize> {
        let lines = self.lines.len();
        let labels = self.labels();
        let start = labels.program_starts.iter().rev().find(|&&l| l <= within).copied().unwrap_or(0);
        let end = labels.program_starts.iter().find(|&&l| l > within).copied().unwrap_or(lines);
        let candidates = labels.sequence.get(&n)?;
        let inside = |l: &&usize| (start..end).contains(*l);
        candidates.iter().filter(inside).find(|&&l| l > from).or_else(|| candidates.iter().find(inside)).copied()
    }
}
