//! The full reader of one line, for lines the fast scanner (`lexer.rs`) cannot read:
//! parameters and expressions, O-words (LinuxCNC subroutines and control flow), Fanuc
//! Custom Macro B statements (`IF [..] GOTO n`, `IF [..] THEN #1 = ..`, `WHILE [..] DO m`,
//! `END m`, `GOTO n`), polar words (`@`, `^`) and blanks inside numbers.
//!
//! As LinuxCNC does, the line is first *compacted*: comments and blanks removed, letters
//! upper-cased. Every item keeps the byte span it came from in the original line, so
//! errors point at the word as written and the editor can replace a word in place.
//!
//! Each fault is one error on the whole word it spoils (a run of unknown characters is one
//! error), and reading goes on after it, so a line reports every bad word at once.

use super::expr::{Cursor, Expr, ExprError, ParamRef};
use super::lexer::read_number;

/// A line compacted for reading: upper case, no blanks or comments.
pub(crate) struct Compact {
    pub bytes: Vec<u8>,
    /// For each compacted byte, its offset in the original line.
    pub origin: Vec<u32>,
    /// The original offset just past the last compacted byte.
    pub end: u32,
}

impl Compact {
    /// The original span of compacted bytes `start..end`.
    pub fn span(&self, start: usize, end: usize) -> (u32, u32) {
        let s = self.origin.get(start).copied().unwrap_or(self.end);
        let e = if end == 0 { s } else { self.origin.get(end - 1).map_or(self.end, |&o| o + 1).max(s) };
        (s, e)
    }
}

/// A fault found while reading, with its original span.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Fault {
    pub start: u32,
    pub end: u32,
    pub reason: String,
    /// Characters that start no word: a warning when unknown words are.
    pub unknown: bool,
}

/// The name of an O-word.
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
pub(crate) enum OName {
    Number(u32),
    /// `o<name>` (upper case).
    Name(String),
}

impl std::fmt::Display for OName {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            OName::Number(n) => write!(f, "o{n}"),
            OName::Name(name) => write!(f, "o<{}>", name.to_ascii_lowercase()),
        }
    }
}

/// The keyword of a LinuxCNC O-word.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum OKeyword {
    Sub,
    Endsub,
    Call,
    Return,
    Do,
    While,
    Endwhile,
    If,
    Elseif,
    Else,
    Endif,
    Break,
    Continue,
    Repeat,
    Endrepeat,
}

const O_KEYWORDS: [(&[u8], OKeyword); 15] = [
    (b"ENDSUB", OKeyword::Endsub),
    (b"ENDWHILE", OKeyword::Endwhile),
    (b"ENDIF", OKeyword::Endif),
    (b"ENDREPEAT", OKeyword::Endrepeat),
    (b"ELSEIF", OKeyword::Elseif),
    (b"ELSE", OKeyword::Else),
    (b"SUB", OKeyword::Sub),
    (b"CALL", OKeyword::Call),
    (b"RETURN", OKeyword::Return),
    (b"DO", OKeyword::Do),
    (b"WHILE", OKeyword::While),
    (b"IF", OKeyword::If),
    (b"BREAK", OKeyword::Break),
    (b"CONTINUE", OKeyword::Continue),
    (b"REPEAT", OKeyword::Repeat),
];

impl OKeyword {
    pub fn as_str(self) -> &'static str {
        match self {
            OKeyword::Sub => "sub",
            OKeyword::Endsub => "endsub",
            OKeyword::Call => "call",
            OKeyword::Return => "return",
            OKeyword::Do => "do",
            OKeyword::While => "while",
            OKeyword::Endwhile => "endwhile",
            OKeyword::If => "if",
            OKeyword::Elseif => "elseif",
            OKeyword::Else => "else",
            OKeyword::Endif => "endif",
            OKeyword::Break => "break",
            OKeyword::Continue => "continue",
            OKeyword::Repeat => "repeat",
            OKeyword::Endrepeat => "endrepeat",
        }
    }
}

/// What `IF [..]` does when its condition holds (Fanuc).
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum Then {
    Goto(Expr),
    Assign(Vec<(ParamRef, Expr)>),
}

/// One statement or word of a line.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum Item {
    /// A letter (or `@`, `^`) and its value.
    Word { letter: u8, value: Expr },
    /// `#n = value`, `#<name> = value`.
    Assign { target: ParamRef, value: Expr },
    /// A LinuxCNC O-word: `o100 sub`, `o<loop> while [#1 LT 3]`, `o100 call [1] [2]`.
    OWord { name: OName, keyword: OKeyword, args: Vec<Expr> },
    /// A Fanuc program number (`O1000`): the start of a (sub)program.
    ProgramLabel { number: u32 },
    /// Fanuc `IF [cond] GOTO n` / `IF [cond] THEN #1 = ..`.
    If { cond: Expr, then: Then },
    /// Fanuc `GOTO n`.
    Goto { target: Expr },
    /// Fanuc `WHILE [cond] DO m`.
    While { cond: Expr, id: u32 },
    /// Fanuc `DO m` (an endless loop until a GOTO leaves it).
    Do { id: u32 },
    /// Fanuc `END m`.
    End { id: u32 },
}

impl Item {
    /// Whether the item steers the program (it must be alone on its line, but for N).
    pub fn is_control(&self) -> bool {
        !matches!(self, Item::Word { .. } | Item::Assign { .. })
    }
}

/// An item with its original span.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Spanned {
    pub item: Item,
    pub start: u32,
    pub end: u32,
}

/// A line read in full.
#[derive(Debug, Clone, PartialEq, Default)]
pub(crate) struct ParsedLine {
    pub items: Vec<Spanned>,
    pub faults: Vec<Fault>,
    /// The line starts with `/` (block delete).
    pub block_delete: bool,
}

/// Largest Fanuc `DO`/`END` loop number read.
const MAX_LOOP_ID: f64 = 99.0;

/// Compacts `line`; an unclosed comment is a fault.
pub(crate) fn compact(line: &[u8]) -> (Compact, Option<Fault>) {
    let mut bytes = Vec::with_capacity(line.len());
    let mut origin = Vec::with_capacity(line.len());
    let mut fault = None;
    let mut i = 0;
    while i < line.len() {
        match line[i] {
            b' ' | b'\t' | b'\r' => i += 1,
            b'(' => match line[i + 1..].iter().position(|&b| b == b')') {
                Some(k) => i += k + 2,
                None => {
                    let reason = "the comment is not closed: add ')'".to_string();
                    fault = Some(Fault { start: i as u32, end: line.len() as u32, reason, unknown: false });
                    break;
                }
            },
            b';' => break,
            c => {
                bytes.push(c.to_ascii_uppercase());
                origin.push(i as u32);
                i += 1;
            }
        }
    }
    let end = origin.last().map_or(0, |&o| o + 1);
    (Compact { bytes, origin, end }, fault)
}

/// Reads a whole line.
pub(crate) fn parse_line(line: &[u8]) -> ParsedLine {
    let (c, unclosed) = compact(line);
    let mut out = ParsedLine::default();
    let mut r = Reader { c: &c, i: 0, out: &mut out };
    if r.c.bytes.first() == Some(&b'/') {
        r.out.block_delete = true;
        r.i = 1;
    }
    r.items();
    if let Some(f) = unclosed {
        out.faults.push(f);
    }
    check_alone(&mut out);
    out
}

/// Control statements must be alone on their line (but for an N word).
fn check_alone(out: &mut ParsedLine) {
    let control = out.items.iter().filter(|s| s.item.is_control()).count();
    let others =
        out.items.iter().filter(|s| !s.item.is_control() && !matches!(s.item, Item::Word { letter: b'N', .. })).count();
    if control > 0 && (control > 1 || others > 0) {
        let first = out.items.iter().find(|s| s.item.is_control()).expect("a control item");
        let reason = "an O-word or a macro statement (IF, GOTO, WHILE, DO, END) must be alone on its line";
        out.faults.push(Fault { start: first.start, end: first.end, reason: reason.to_string(), unknown: false });
    }
}

struct Reader<'a> {
    c: &'a Compact,
    i: usize,
    out: &'a mut ParsedLine,
}

impl Reader<'_> {
    fn bytes(&self) -> &[u8] {
        &self.c.bytes
    }

    fn at(&self, word: &[u8]) -> bool {
        self.bytes()[self.i..].starts_with(word)
    }

    fn push(&mut self, item: Item, start: usize) {
        let (s, e) = self.c.span(start, self.i);
        self.out.items.push(Spanned { item, start: s, end: e });
    }

    fn fault(&mut self, start: usize, end: usize, reason: impl Into<String>) {
        let (s, e) = self.c.span(start, end.max(start + 1).min(self.bytes().len().max(start + 1)));
        self.out.faults.push(Fault { start: s, end: e, reason: reason.into(), unknown: false });
    }

    fn expr_fault(&mut self, e: ExprError, word_start: usize) {
        // The fault spoils the word: report it on the whole word, with the reason.
        self.fault(word_start, e.end.max(self.i), e.reason);
    }

    /// Whether `b` can start a word or a statement.
    fn starts_item(&self, b: u8) -> bool {
        b.is_ascii_uppercase() || matches!(b, b'#' | b'@' | b'^')
    }

    /// Skips to the next character that can start a word (after a fault).
    fn resync(&mut self) {
        while self.i < self.bytes().len() && !self.starts_item(self.bytes()[self.i]) {
            self.i += 1;
        }
    }

    fn items(&mut self) {
        while self.i < self.bytes().len() {
            let start = self.i;
            let c = self.bytes()[self.i];
            let result = match c {
                b'O' => self.o_word(),
                b'#' => self.assignment(),
                b'I' if self.at(b"IF[") => self.fanuc_if(),
                b'G' if self.at(b"GOTO") => {
                    self.i += 4;
                    self.value_of().map(|target| Item::Goto { target })
                }
                b'W' if self.at(b"WHILE[") => self.fanuc_while(),
                b'D' if self.at(b"DO") && self.digit_after(2) => {
                    self.i += 2;
                    self.loop_id(start).map(|id| Item::Do { id })
                }
                b'E' if self.at(b"END") && self.digit_after(3) => {
                    self.i += 3;
                    self.loop_id(start).map(|id| Item::End { id })
                }
                b'A'..=b'Z' | b'@' | b'^' => {
                    self.i += 1;
                    if self.i < self.bytes().len() && self.starts_value() {
                        self.value_of().map(|value| Item::Word { letter: c, value })
                    } else {
                        // The letter and whatever spoils it are one bad word.
                        while self.i < self.bytes().len() && !self.starts_item(self.bytes()[self.i]) {
                            self.i += 1;
                        }
                        self.fault(start, self.i, "a letter must be followed by a number");
                        continue;
                    }
                }
                _ => {
                    // A run of characters that start nothing is one fault.
                    while self.i < self.bytes().len() && !self.starts_item(self.bytes()[self.i]) {
                        self.i += 1;
                    }
                    let shown = String::from_utf8_lossy(&self.bytes()[start..self.i]).into_owned();
                    self.fault(start, self.i, format!("'{shown}' is not a G-code word"));
                    if let Some(f) = self.out.faults.last_mut() {
                        f.unknown = true;
                    }
                    continue;
                }
            };
            match result {
                Ok(item) => self.push(item, start),
                Err(e) => {
                    self.expr_fault(e, start);
                    self.resync();
                }
            }
        }
    }

    fn digit_after(&self, k: usize) -> bool {
        self.bytes().get(self.i + k).is_some_and(|b| b.is_ascii_digit())
    }

    /// Whether a value can start at the cursor.
    fn starts_value(&self) -> bool {
        matches!(self.bytes()[self.i], b'0'..=b'9' | b'.' | b'-' | b'+' | b'#' | b'[')
            || self.cursor().function_follows()
    }

    fn cursor(&self) -> Cursor<'_> {
        Cursor::new(&self.c.bytes, self.i)
    }

    /// A real value at the cursor (consumed).
    fn value_of(&mut self) -> Result<Expr, ExprError> {
        let mut cur = self.cursor();
        let result = cur.real_value();
        self.i = cur.i;
        result
    }

    fn loop_id(&mut self, start: usize) -> Result<u32, ExprError> {
        match read_number(self.bytes(), self.i) {
            Some((v, end)) if v.fract().abs() <= 0.0 && (1.0..=MAX_LOOP_ID).contains(&v) => {
                self.i = end;
                Ok(v as u32)
            }
            _ => {
                self.i += 1;
                Err(ExprError { start, end: self.i, reason: "DO and END take a loop number from 1 to 99".into() })
            }
        }
    }

    fn assignment_at_cursor(&mut self) -> Result<(ParamRef, Expr), ExprError> {
        let start = self.i;
        let mut cur = self.cursor();
        let target = cur.param()?;
        self.i = cur.i;
        if !self.at(b"=") {
            return Err(ExprError {
                start,
                end: self.i,
                reason: "a parameter alone is not a word: set it with '=' or use it in a word (X#1)".into(),
            });
        }
        self.i += 1;
        let mut cur = self.cursor();
        let value = cur.expression();
        self.i = cur.i;
        Ok((target, value?))
    }

    fn assignment(&mut self) -> Result<Item, ExprError> {
        self.assignment_at_cursor().map(|(target, value)| Item::Assign { target, value })
    }

    fn fanuc_if(&mut self) -> Result<Item, ExprError> {
        let start = self.i;
        self.i += 2;
        let mut cur = self.cursor();
        let cond = cur.group();
        self.i = cur.i;
        let cond = cond?;
        if self.at(b"GOTO") {
            self.i += 4;
            let target = self.value_of()?;
            return Ok(Item::If { cond, then: Then::Goto(target) });
        }
        if self.at(b"THEN") {
            self.i += 4;
            let mut assigns = Vec::new();
            while self.at(b"#") {
                assigns.push(self.assignment_at_cursor()?);
            }
            if assigns.is_empty() {
                return Err(ExprError { start, end: self.i, reason: "THEN must be followed by #n = value".into() });
            }
            return Ok(Item::If { cond, then: Then::Assign(assigns) });
        }
        Err(ExprError {
            start,
            end: self.i,
            reason: "IF [condition] must be followed by GOTO n or THEN #n = value".into(),
        })
    }

    fn fanuc_while(&mut self) -> Result<Item, ExprError> {
        let start = self.i;
        self.i += 5;
        let mut cur = self.cursor();
        let cond = cur.group();
        self.i = cur.i;
        let cond = cond?;
        if !(self.at(b"DO") && self.digit_after(2)) {
            return Err(ExprError { start, end: self.i, reason: "WHILE [condition] must be followed by DO m".into() });
        }
        self.i += 2;
        let id = self.loop_id(start)?;
        Ok(Item::While { cond, id })
    }

    fn o_word(&mut self) -> Result<Item, ExprError> {
        let start = self.i;
        self.i += 1;
        let name = match self.bytes().get(self.i) {
            Some(b'<') => match self.bytes()[self.i..].iter().position(|&b| b == b'>') {
                Some(k) if k > 1 => {
                    let name = String::from_utf8_lossy(&self.bytes()[self.i + 1..self.i + k]).into_owned();
                    self.i += k + 1;
                    OName::Name(name)
                }
                _ => {
                    self.i = self.bytes().len();
                    return Err(ExprError { start, end: self.i, reason: "an O-word name is written o<name>".into() });
                }
            },
            Some(b'0'..=b'9') => {
                let digits = self.bytes()[self.i..].iter().take_while(|b| b.is_ascii_digit()).count();
                let number =
                    std::str::from_utf8(&self.bytes()[self.i..self.i + digits]).ok().and_then(|t| t.parse().ok());
                self.i += digits;
                match number {
                    Some(n) => OName::Number(n),
                    None => return Err(ExprError { start, end: self.i, reason: "the O number is too large".into() }),
                }
            }
            _ => {
                return Err(ExprError { start, end: self.i, reason: "O must be followed by a number or <name>".into() })
            }
        };
        let Some(&(word, keyword)) = O_KEYWORDS.iter().find(|(w, _)| self.at(w)) else {
            return match (name, self.i == self.bytes().len()) {
                (OName::Number(number), true) => Ok(Item::ProgramLabel { number }),
                _ => Err(ExprError {
                    start,
                    end: self.bytes().len(),
                    reason: "an O-word needs a keyword: sub, endsub, call, return, if, elseif, else, endif, while, endwhile, do, repeat, endrepeat, break or continue".into(),
                }),
            };
        };
        self.i += word.len();
        let mut args = Vec::new();
        while self.at(b"[") {
            let mut cur = self.cursor();
            let arg = cur.group();
            self.i = cur.i;
            args.push(arg?);
        }
        Ok(Item::OWord { name, keyword, args })
    }
}
