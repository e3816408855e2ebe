//! Expressions of a G-code line, as LinuxCNC (RS274/NGC) and Fanuc Custom Macro B read
//! them: numbers, parameters (`#12`, `##2`, `#[#1+1]`, `#<name>`), `[ ]` groups, the
//! binary operators `** * / MOD + - EQ NE GT GE LT LE AND OR XOR`, unary minus, and the
//! functions `ABS ACOS ASIN ATAN COS EXP FIX FUP LN ROUND SIN SQRT TAN EXISTS` (and Fanuc's
//! `POW[a, b]` and `ATAN[y, x]`). Angles are in degrees.
//!
//! The parser reads a *compacted* line (blanks and comments removed, letters upper case,
//! see `line.rs`); positions in errors are positions in that compacted text.
//!
//! Precedence, highest first (LinuxCNC's, left to right within a level): `**`; `* / MOD`;
//! `+ -`; comparisons; `AND OR XOR`.

use super::lexer::read_number;

/// Two numbers closer than this compare as equal (`EQ`, `NE`, `GE`, `LE`).
pub(crate) const COMPARE_TOLERANCE: f64 = 1e-6;

/// Deepest nesting of `[ ]` groups and function calls an expression may have.
pub(crate) const MAX_EXPRESSION_DEPTH: u32 = 64;

/// A unary function.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Func {
    Abs,
    Acos,
    Asin,
    Atan,
    Cos,
    Exp,
    Fix,
    Fup,
    Ln,
    Round,
    Sin,
    Sqrt,
    Tan,
}

/// A binary operator.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum BinOp {
    Pow,
    Mul,
    Div,
    Mod,
    Add,
    Sub,
    Eq,
    Ne,
    Gt,
    Ge,
    Lt,
    Le,
    And,
    Or,
    Xor,
}

impl BinOp {
    /// Binding strength: higher binds tighter.
    fn level(self) -> u8 {
        match self {
            BinOp::Pow => 5,
            BinOp::Mul | BinOp::Div | BinOp::Mod => 4,
            BinOp::Add | BinOp::Sub => 3,
            BinOp::Eq | BinOp::Ne | BinOp::Gt | BinOp::Ge | BinOp::Lt | BinOp::Le => 2,
            BinOp::And | BinOp::Or | BinOp::Xor => 1,
        }
    }
}

/// Which parameter an expression names.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum ParamRef {
    /// `#n`, `##n`, `#[expr]`: the number is computed when the line runs.
    Index(Box<Expr>),
    /// `#<name>` (upper case, blanks removed).
    Name(String),
}

/// An expression.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum Expr {
    Number(f64),
    Param(ParamRef),
    Neg(Box<Expr>),
    Func(Func, Box<Expr>),
    /// `ATAN[y]/[x]` or `ATAN[y, x]`: the angle of (x, y), degrees.
    Atan2(Box<Expr>, Box<Expr>),
    Binary(BinOp, Box<Expr>, Box<Expr>),
    /// `EXISTS[#<name>]`: 1 if the named parameter is defined.
    Exists(String),
}

/// A fault in an expression, at positions of the compacted line.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct ExprError {
    pub start: usize,
    pub end: usize,
    pub reason: String,
}

/// Reads expressions from a compacted line.
pub(crate) struct Cursor<'a> {
    pub bytes: &'a [u8],
    pub i: usize,
    depth: u32,
}

impl<'a> Cursor<'a> {
    pub fn new(bytes: &'a [u8], i: usize) -> Self {
        Cursor { bytes, i, depth: 0 }
    }

    pub fn peek(&self) -> Option<u8> {
        self.bytes.get(self.i).copied()
    }

    fn error<T>(&self, start: usize, reason: impl Into<String>) -> Result<T, ExprError> {
        let end = self.i.max(start + 1).min(self.bytes.len().max(start + 1));
        Err(ExprError { start, end, reason: reason.into() })
    }

    /// A name followed by `[` is at the cursor (a function call).
    pub fn function_follows(&self) -> bool {
        let letters = self.letters().len();
        letters >= 2 && self.bytes.get(self.i + letters) == Some(&b'[')
    }

    /// The run of letters at the cursor (not consumed).
    pub fn letters(&self) -> &'a [u8] {
        let n = self.bytes[self.i..].iter().take_while(|b| b.is_ascii_uppercase()).count();
        &self.bytes[self.i..self.i + n]
    }

    /// Consumes `word` if the cursor is at it.
    pub fn eat(&mut self, word: &[u8]) -> bool {
        if self.bytes[self.i..].starts_with(word) {
            self.i += word.len();
            true
        } else {
            false
        }
    }

    /// A real value as a word takes it: a number, a parameter, a `[ ]` group, a function
    /// call, each with an optional sign.
    pub fn real_value(&mut self) -> Result<Expr, ExprError> {
        self.unary()
    }

    /// A `[ ]` group at the cursor.
    pub fn group(&mut self) -> Result<Expr, ExprError> {
        let start = self.i;
        if !self.eat(b"[") {
            return self.error(start, "expected '['");
        }
        self.nest(start)?;
        let e = self.expression()?;
        self.depth -= 1;
        if !self.eat(b"]") {
            return self.error(start, "the expression is not closed: add ']'");
        }
        Ok(e)
    }

    fn nest(&mut self, start: usize) -> Result<(), ExprError> {
        self.depth += 1;
        if self.depth > MAX_EXPRESSION_DEPTH {
            return self.error(start, format!("expressions nest at most {MAX_EXPRESSION_DEPTH} deep"));
        }
        Ok(())
    }

    /// A whole expression inside a group (binary operators by precedence).
    pub fn expression(&mut self) -> Result<Expr, ExprError> {
        self.binary(1)
    }

    fn binary(&mut self, min_level: u8) -> Result<Expr, ExprError> {
        let mut left = self.unary()?;
        loop {
            let save = self.i;
            let Some(op) = self.operator() else { break };
            if op.level() < min_level {
                self.i = save;
                break;
            }
            let right = self.binary(op.level() + 1)?;
            left = Expr::Binary(op, Box::new(left), Box::new(right));
        }
        Ok(left)
    }

    /// Consumes a binary operator, if there is one at the cursor.
    fn operator(&mut self) -> Option<BinOp> {
        let op = match self.peek()? {
            b'*' if self.bytes.get(self.i + 1) == Some(&b'*') => {
                self.i += 1;
                BinOp::Pow
            }
            b'*' => BinOp::Mul,
            b'/' => BinOp::Div,
            b'+' => BinOp::Add,
            b'-' => BinOp::Sub,
            b'A'..=b'Z' => {
                const WORDS: [(&[u8], BinOp); 10] = [
                    (b"MOD", BinOp::Mod),
                    (b"EQ", BinOp::Eq),
                    (b"NE", BinOp::Ne),
                    (b"GT", BinOp::Gt),
                    (b"GE", BinOp::Ge),
                    (b"LT", BinOp::Lt),
                    (b"LE", BinOp::Le),
                    (b"AND", BinOp::And),
                    (b"OR", BinOp::Or),
                    (b"XOR", BinOp::Xor),
                ];
                let (word, op) = WORDS.iter().find(|(w, _)| self.bytes[self.i..].starts_with(w))?;
                self.i += word.len();
                return Some(*op);
            }
            _ => return None,
        };
        self.i += 1;
        Some(op)
    }

    fn unary(&mut self) -> Result<Expr, ExprError> {
        let start = self.i;
        match self.peek() {
            Some(b'-') => {
                self.i += 1;
                Ok(Expr::Neg(Box::new(self.unary()?)))
            }
            Some(b'+') => {
                self.i += 1;
                self.unary()
            }
            Some(b'0'..=b'9' | b'.') => match read_number(self.bytes, self.i) {
                Some((v, end)) => {
                    self.i = end;
                    Ok(Expr::Number(v))
                }
                None => {
                    self.i += 1;
                    self.error(start, "a number needs at least one digit")
                }
            },
            Some(b'#') => Ok(Expr::Param(self.param()?)),
            Some(b'[') => self.group(),
            Some(b'A'..=b'Z') if self.function_follows() => self.function(),
            // A letter that starts no function ends the expression here (it may be the next
            // word of the line): the fault is before it.
            Some(b'A'..=b'Z') => Err(ExprError {
                start,
                end: start,
                reason: "expected a number, a parameter, '[' or a function".to_string(),
            }),
            Some(_) => {
                self.i += 1;
                self.error(start, "expected a number, a parameter, '[' or a function")
            }
            None => self.error(start, "the expression ends too early"),
        }
    }

    /// A parameter reference at `#`.
    pub fn param(&mut self) -> Result<ParamRef, ExprError> {
        let start = self.i;
        self.i += 1; // '#'
        match self.peek() {
            Some(b'<') => {
                let close = self.bytes[self.i..].iter().position(|&b| b == b'>');
                let Some(k) = close else {
                    self.i = self.bytes.len();
                    return self.error(start, "the parameter name is not closed: add '>'");
                };
                let name = &self.bytes[self.i + 1..self.i + k];
                self.i += k + 1;
                if name.is_empty() {
                    return self.error(start, "a parameter name cannot be empty");
                }
                Ok(ParamRef::Name(String::from_utf8_lossy(name).into_owned()))
            }
            Some(b'0'..=b'9' | b'.' | b'#' | b'[') => {
                let index = match self.peek() {
                    Some(b'#') => Expr::Param(self.param()?),
                    Some(b'[') => self.group()?,
                    _ => match read_number(self.bytes, self.i) {
                        Some((v, end)) => {
                            self.i = end;
                            Expr::Number(v)
                        }
                        None => return self.error(start, "a parameter number needs a digit"),
                    },
                };
                Ok(ParamRef::Index(Box::new(index)))
            }
            _ => self.error(start, "'#' must be followed by a number, '#', '[' or '<name>'"),
        }
    }

    fn function(&mut self) -> Result<Expr, ExprError> {
        let start = self.i;
        let name = self.letters();
        const FUNCS: [(&[u8], Func); 13] = [
            (b"ABS", Func::Abs),
            (b"ACOS", Func::Acos),
            (b"ASIN", Func::Asin),
            (b"ATAN", Func::Atan),
            (b"COS", Func::Cos),
            (b"EXP", Func::Exp),
            (b"FIX", Func::Fix),
            (b"FUP", Func::Fup),
            (b"LN", Func::Ln),
            (b"ROUND", Func::Round),
            (b"SIN", Func::Sin),
            (b"SQRT", Func::Sqrt),
            (b"TAN", Func::Tan),
        ];
        if name == b"EXISTS" {
            self.i += name.len();
            let open = self.i;
            if !(self.eat(b"[") && self.peek() == Some(b'#')) {
                return self.error(open, "EXISTS needs a named parameter: EXISTS[#<name>]");
            }
            let ParamRef::Name(param) = self.param()? else {
                return self.error(open, "EXISTS needs a named parameter: EXISTS[#<name>]");
            };
            if !self.eat(b"]") {
                return self.error(open, "the expression is not closed: add ']'");
            }
            return Ok(Expr::Exists(param));
        }
        if name == b"POW" {
            self.i += name.len();
            let (a, b) = self.two_arguments(start, "POW[base, exponent]")?;
            return Ok(Expr::Binary(BinOp::Pow, Box::new(a), Box::new(b)));
        }
        let Some(&(word, func)) = FUNCS.iter().find(|(w, _)| *w == name) else {
            self.i += name.len().max(1);
            let shown = String::from_utf8_lossy(name);
            return self.error(start, format!("{shown} is not a function"));
        };
        self.i += word.len();
        if self.peek() != Some(b'[') {
            return self.error(start, format!("{} needs its argument in [ ]", String::from_utf8_lossy(word)));
        }
        if func == Func::Atan {
            let open = self.i;
            self.i += 1;
            self.nest(open)?;
            let y = self.expression()?;
            self.depth -= 1;
            if self.eat(b",") {
                self.nest(open)?;
                let x = self.expression()?;
                self.depth -= 1;
                if !self.eat(b"]") {
                    return self.error(open, "the expression is not closed: add ']'");
                }
                return Ok(Expr::Atan2(Box::new(y), Box::new(x)));
            }
            if !self.eat(b"]") {
                return self.error(open, "the expression is not closed: add ']'");
            }
            // LinuxCNC's two-argument form `ATAN[y]/[x]`; a Fanuc `ATAN[t]` alone is the
            // arc tangent of t.
            if self.bytes[self.i..].starts_with(b"/[") {
                self.i += 1;
                let x = self.group()?;
                return Ok(Expr::Atan2(Box::new(y), Box::new(x)));
            }
            return Ok(Expr::Func(Func::Atan, Box::new(y)));
        }
        let argument = self.group()?;
        Ok(Expr::Func(func, Box::new(argument)))
    }

    fn two_arguments(&mut self, start: usize, form: &str) -> Result<(Expr, Expr), ExprError> {
        if !self.eat(b"[") {
            return self.error(start, format!("expected {form}"));
        }
        self.nest(start)?;
        let a = self.expression()?;
        if !self.eat(b",") {
            return self.error(start, format!("expected {form}"));
        }
        let b = self.expression()?;
        self.depth -= 1;
        if !self.eat(b"]") {
            return self.error(start, "the expression is not closed: add ']'");
        }
        Ok((a, b))
    }
}
