//! Fanuc subprograms in the same program text: `M98 P… L…` calls program O…, `M99`
//! returns (to line N… of the caller with P), `G65 P… L…` calls a macro with arguments
//! as local variables (argument specification I).

use super::flow::{CallFrame, FrameKind, Span};
use super::parse::{is_integer, Next, Run};

/// Fanuc's argument specification I: the local variable each letter of a G65 call sets.
const G65_ARGUMENTS: [(u8, u32); 21] = [
    (b'A', 1),
    (b'B', 2),
    (b'C', 3),
    (b'I', 4),
    (b'J', 5),
    (b'K', 6),
    (b'D', 7),
    (b'E', 8),
    (b'F', 9),
    (b'H', 11),
    (b'M', 13),
    (b'Q', 17),
    (b'R', 18),
    (b'S', 19),
    (b'T', 20),
    (b'U', 21),
    (b'V', 22),
    (b'W', 23),
    (b'X', 24),
    (b'Y', 25),
    (b'Z', 26),
];

/// A Fanuc `M98 P` with more than four digits holds the repeat count before the program
/// number (`P30010`: three times O0010).
const FANUC_PROGRAM_DIGITS: u32 = 10_000;

/// An M98 line's P and L words (value, word index).
pub(crate) type CallWords = (Option<(f64, usize)>, Option<(f64, usize)>);

impl Run<'_> {
    /// `M98 P… L…`: calls subprogram O… of the same text.
    pub(crate) fn m98(
        &mut self,
        number: u32,
        words: &[super::lexer::Word],
        i: usize,
        (p, l): CallWords,
        index: usize,
    ) -> Next {
        let span: Span = (words[i].start, words[i].end);
        let Some((p, _)) = p else {
            return self.fail(number, index, span, "M98 needs P, the subprogram's number");
        };
        if !(is_integer(p) && p >= 0.0) {
            return self.fail(number, index, span, "M98 P must be a program number");
        }
        let p = p.round() as u32;
        let (program, count) = match l {
            Some((l, _)) if is_integer(l) && l >= 0.0 => (p, l.round() as u32),
            Some(_) => return self.fail(number, index, span, "M98 L must be a whole number of repeats"),
            None if p >= FANUC_PROGRAM_DIGITS => (p % FANUC_PROGRAM_DIGITS, p / FANUC_PROGRAM_DIGITS),
            None => (p, 1),
        };
        self.call_program(index, number, span, program, count, None)
    }

    fn call_program(
        &mut self,
        index: usize,
        number: u32,
        span: Span,
        program: u32,
        count: u32,
        args: Option<Vec<(u32, Option<f64>)>>,
    ) -> Next {
        if count == 0 {
            return Next::Continue;
        }
        let Some(&label) = self.labels().programs.get(&program) else {
            return self.fail(
                number,
                index,
                span,
                format!("subprogram O{program} is not in the program text: send it with the program"),
            );
        };
        if !self.call_depth_ok(number, index, span) {
            return Next::End;
        }
        let macro_call = args.is_some();
        if let Some(args) = args {
            self.params.push_level(&args);
        }
        self.flow.frames.push(CallFrame {
            kind: FrameKind::Program { remaining: count, start: label + 1, macro_call },
            return_to: index + 1,
            call_line: number,
            repeats: Vec::new(),
            restore: None,
        });
        self.jump(label + 1)
    }

    /// `M99 [P…]`: returns from a subprogram (to line N… of the caller with P).
    pub(crate) fn m99(
        &mut self,
        number: u32,
        words: &[super::lexer::Word],
        i: usize,
        p: Option<(f64, usize)>,
        index: usize,
    ) -> Next {
        let span: Span = (words[i].start, words[i].end);
        let Some(frame) = self.flow.frames.last_mut() else {
            self.line_warning(number, "M99 in the main program would run it again from its start: it is read once");
            return Next::End;
        };
        let FrameKind::Program { remaining, start, macro_call } = &mut frame.kind else {
            return self.fail(number, index, span, "M99 inside an O-word subroutine: end it with endsub");
        };
        if *remaining > 1 {
            *remaining -= 1;
            let start = *start;
            return self.jump_back(start, number, index, span);
        }
        let macro_call = *macro_call;
        let frame = self.flow.frames.pop().expect("checked");
        if macro_call {
            self.params.pop_level();
        }
        if let Some(state) = frame.restore {
            self.machine.restore(state);
        }
        match p {
            None => self.jump(frame.return_to),
            Some((n, _)) => {
                let n = n.round() as u32;
                match self.sequence_in_program(n, frame.return_to.saturating_sub(1), frame.return_to.saturating_sub(1))
                {
                    Some(to) => self.jump(to),
                    None => self.fail(number, index, span, format!("M99 P{n}: no line N{n} in the calling program")),
                }
            }
        }
    }

    /// `G65 P… L… <arguments>`: a macro call with its own local variables.
    pub(crate) fn g65(&mut self, number: u32, words: &[super::lexer::Word], g65: usize, index: usize) -> Next {
        let span: Span = (words[g65].start, words[g65].end);
        self.record(index, super::map::LineMotion::None);
        let (mut program, mut count, mut args) = (None, 1u32, Vec::new());
        for (k, w) in words.iter().enumerate() {
            let here: Span = (w.start, w.end);
            match w.letter {
                _ if k == g65 => {}
                b'N' | b'O' => {}
                b'P' if is_integer(w.value) && w.value >= 0.0 => program = Some(w.value.round() as u32),
                b'L' if is_integer(w.value) && w.value >= 0.0 => count = w.value.round() as u32,
                b'P' | b'L' => return self.fail(number, index, here, "G65 P and L must be whole numbers"),
                letter => match G65_ARGUMENTS.iter().find(|(l, _)| *l == letter) {
                    Some(&(_, n)) => args.push((n, Some(w.value))),
                    None => {
                        return self.fail(
                            number,
                            index,
                            here,
                            "this letter is not a G65 argument (argument specification I)",
                        )
                    }
                },
            }
        }
        let Some(program) = program else {
            return self.fail(number, index, span, "G65 needs P, the macro's program number");
        };
        self.call_program(index, number, span, program, count, Some(args))
    }

    /// The program ended inside a call that never returned.
    pub(crate) fn unreturned_call(&mut self) {
        let Some(frame) = self.flow.frames.last() else { return };
        let (line, kind) = (frame.call_line, frame.kind.clone());
        let what = match kind {
            FrameKind::Sub(name) => format!("{name} has no endsub"),
            FrameKind::Program { .. } => "the subprogram has no M99".to_string(),
        };
        let index = line as usize - 1;
        let end = self.lines[index].1 - self.lines[index].0;
        self.line_error(line, index, 0, end, format!("the call never returns: {what}"));
    }
}
