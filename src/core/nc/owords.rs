//! LinuxCNC O-words: subroutines (`sub`, `endsub`, `call`, `return`) and control flow
//! (`if`/`elseif`/`else`/`endif`, `while`/`endwhile`, `do`/`while`, `repeat`/`endrepeat`,
//! `break`, `continue`). Each part of a block names the same O-word, which is how they
//! find each other.

use super::expr::Expr;
use super::flow::{CallFrame, FrameKind, Repeat};
use super::line::{OKeyword, OName, Spanned};
use super::parse::{Next, Run};

impl Run<'_> {
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn o_word(
        &mut self,
        index: usize,
        number: u32,
        s: &Spanned,
        name: &OName,
        keyword: OKeyword,
        args: &[Expr],
        from_if: bool,
    ) -> Next {
        use OKeyword as K;
        let missing = |what: &str| format!("{name} {} has no {what}", keyword.as_str());
        match keyword {
            K::Sub => match self.o_after(name, index, &[K::Endsub]) {
                Some(end) => self.jump(end + 1),
                None => self.fail(number, index, (s.start, s.end), missing("endsub")),
            },
            K::Endsub | K::Return => self.o_return(index, number, s, name, args),
            K::Call => self.o_call(index, number, s, name, args),
            K::If => self.o_condition(index, number, s, name, keyword, args),
            K::Elseif if from_if => self.o_condition(index, number, s, name, keyword, args),
            K::Else if from_if => Next::Continue,
            K::Elseif | K::Else => match self.o_after(name, index, &[K::Endif]) {
                // The branch before was taken: skip to the end of the chain.
                Some(end) => self.jump(end + 1),
                None => self.fail(number, index, (s.start, s.end), missing("endif")),
            },
            K::Endif | K::Do => Next::Continue,
            K::While => self.o_while(index, number, s, name, args),
            K::Endwhile => match self.o_before(name, index, &[K::While]) {
                Some(start) => self.jump_back(start, number, index, (s.start, s.end)),
                None => self.fail(number, index, (s.start, s.end), format!("{name} endwhile has no while before it")),
            },
            K::Repeat => {
                let count = match args.first().map(|a| self.eval(a)) {
                    Some(Ok(v)) => v.unwrap_or(0.0).round(),
                    Some(Err(reason)) => return self.fail(number, index, (s.start, s.end), reason),
                    None => {
                        return self.fail(
                            number,
                            index,
                            (s.start, s.end),
                            format!("{name} repeat needs a count in [ ]"),
                        )
                    }
                };
                if count < 1.0 {
                    return match self.o_after(name, index, &[K::Endrepeat]) {
                        Some(end) => self.jump(end + 1),
                        None => self.fail(number, index, (s.start, s.end), missing("endrepeat")),
                    };
                }
                let repeats = self.flow.repeats();
                repeats.retain(|r| r.line != index);
                repeats.push(Repeat { name: name.clone(), line: index, remaining: count as u64 });
                Next::Continue
            }
            K::Endrepeat => {
                let repeats = self.flow.repeats();
                let Some(k) = repeats.iter().rposition(|r| &r.name == name) else {
                    return self.fail(
                        number,
                        index,
                        (s.start, s.end),
                        format!("{name} endrepeat has no repeat before it"),
                    );
                };
                repeats[k].remaining -= 1;
                if repeats[k].remaining > 0 {
                    let line = repeats[k].line;
                    return self.jump_back(line + 1, number, index, (s.start, s.end));
                }
                repeats.remove(k);
                Next::Continue
            }
            K::Break | K::Continue => self.o_break(index, number, s, name, keyword == K::Break),
        }
    }

    /// `if` (or an `elseif` a failed condition jumped to): its branch, or the next one.
    fn o_condition(
        &mut self,
        index: usize,
        number: u32,
        s: &Spanned,
        name: &OName,
        keyword: OKeyword,
        args: &[Expr],
    ) -> Next {
        use OKeyword as K;
        match args.first().map(|a| self.truth(a)) {
            None => self.fail(
                number,
                index,
                (s.start, s.end),
                format!("{name} {} needs a condition in [ ]", keyword.as_str()),
            ),
            Some(Err(reason)) => self.fail(number, index, (s.start, s.end), reason),
            Some(Ok(true)) => Next::Continue,
            Some(Ok(false)) => match self.o_after(name, index, &[K::Elseif, K::Else, K::Endif]) {
                Some(next) => {
                    self.flow.if_target = Some(next);
                    self.jump(next)
                }
                None => self.fail(number, index, (s.start, s.end), format!("{name} {} has no endif", keyword.as_str())),
            },
        }
    }

    fn o_while(&mut self, index: usize, number: u32, s: &Spanned, name: &OName, args: &[Expr]) -> Next {
        use OKeyword as K;
        let closes_do = self.previous_keyword(name, index) == Some(K::Do);
        let holds = match args.first().map(|a| self.truth(a)) {
            Some(Ok(v)) => v,
            Some(Err(reason)) => return self.fail(number, index, (s.start, s.end), reason),
            None => {
                return self.fail(number, index, (s.start, s.end), format!("{name} while needs a condition in [ ]"))
            }
        };
        match (closes_do, holds) {
            (true, true) => match self.o_before(name, index, &[K::Do]) {
                Some(start) => self.jump_back(start + 1, number, index, (s.start, s.end)),
                None => Next::Continue,
            },
            (true, false) | (false, true) => Next::Continue,
            (false, false) => match self.o_after(name, index, &[K::Endwhile]) {
                Some(end) => self.jump(end + 1),
                None => self.fail(number, index, (s.start, s.end), format!("{name} while has no endwhile")),
            },
        }
    }

    fn o_break(&mut self, index: usize, number: u32, s: &Spanned, name: &OName, leave: bool) -> Next {
        use OKeyword as K;
        let Some(start) = self.o_before(name, index, &[K::While, K::Do, K::Repeat]) else {
            return self.fail(
                number,
                index,
                (s.start, s.end),
                format!("{name} break/continue is not inside a loop of that name"),
            );
        };
        let opener = self.labels().owords[name].iter().find(|(l, _)| *l == start).map(|(_, k)| *k);
        let end = match opener {
            Some(K::Repeat) => self.o_after(name, index, &[K::Endrepeat]),
            Some(K::Do) => self.o_after(name, index, &[K::While]),
            _ => self.o_after(name, index, &[K::Endwhile]),
        };
        let Some(end) = end else {
            return self.fail(number, index, (s.start, s.end), format!("{name}'s loop has no end"));
        };
        if leave {
            if opener == Some(K::Repeat) {
                self.flow.repeats().retain(|r| r.line != start);
            }
            return self.jump(end + 1);
        }
        match opener {
            Some(K::While) => self.jump_back(start, number, index, (s.start, s.end)),
            _ => self.jump(end),
        }
    }

    fn o_call(&mut self, index: usize, number: u32, s: &Spanned, name: &OName, args: &[Expr]) -> Next {
        let mut values = Vec::with_capacity(args.len());
        for (k, a) in args.iter().enumerate() {
            match self.eval(a) {
                Ok(v) => values.push((k as u32 + 1, v)),
                Err(reason) => return self.fail(number, index, (s.start, s.end), reason),
            }
        }
        let sub = self.labels().owords.get(name).and_then(|l| l.iter().find(|(_, k)| *k == OKeyword::Sub));
        let Some(&(start, _)) = sub else {
            return self.fail(
                number,
                index,
                (s.start, s.end),
                format!("{name} is not defined in the program: send its subroutine (o… sub … endsub) with the program"),
            );
        };
        if !self.call_depth_ok(number, index, (s.start, s.end)) {
            return Next::End;
        }
        self.params.push_level(&values);
        self.params.set_named("_VALUE_RETURNED", 0.0);
        self.flow.frames.push(CallFrame {
            kind: FrameKind::Sub(name.clone()),
            return_to: index + 1,
            call_line: number,
            repeats: Vec::new(),
            restore: None,
        });
        self.jump(start + 1)
    }

    fn o_return(&mut self, index: usize, number: u32, s: &Spanned, name: &OName, args: &[Expr]) -> Next {
        let value = match args.first().map(|a| self.eval(a)) {
            Some(Ok(v)) => v,
            Some(Err(reason)) => return self.fail(number, index, (s.start, s.end), reason),
            None => None,
        };
        let top_matches =
            matches!(self.flow.frames.last(), Some(CallFrame { kind: FrameKind::Sub(n), .. }) if n == name);
        if !top_matches {
            return self.fail(number, index, (s.start, s.end), format!("{name} returns, but it was not called"));
        }
        let frame = self.flow.frames.pop().expect("checked");
        self.params.pop_level();
        if let Some(v) = value {
            self.params.set_named("_VALUE", v);
            self.params.set_named("_VALUE_RETURNED", 1.0);
        }
        if let Some(state) = frame.restore {
            self.machine.restore(state);
        }
        self.jump(frame.return_to)
    }
}
