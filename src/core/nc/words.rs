//! The words of a line as written, with their byte spans, and how the editor spells the
//! numbers it writes: in the program's own style (a decimal point on whole numbers if the
//! program writes one, as a Fanuc needs), rounded to the program's resolution.

pub(crate) use super::block::code_times_ten as code_of;
use super::lexer::{self, Word};
use super::line::{parse_line, Item};
pub(crate) use super::writer::format::Fixed;
use super::writer::format::MAX_DECIMALS;

/// The words of one line.
#[derive(Debug, Clone, Default)]
pub(crate) struct LineWords {
    /// Letter, value (NaN for an expression), span.
    pub words: Vec<Word>,
    /// The line starts with `/`.
    pub block_delete: bool,
}

impl LineWords {
    /// Reads the words of `text` (the fast scanner, or the full reader for lines with
    /// expressions and control statements).
    pub fn read(text: &[u8]) -> LineWords {
        let (mut words, mut issues) = (Vec::new(), Vec::new());
        let shape = lexer::scan_line(text, &mut words, &mut issues);
        if issues.is_empty() {
            return LineWords { words, block_delete: shape.block_delete };
        }
        let parsed = parse_line(text);
        let words = parsed
            .items
            .iter()
            .filter_map(|s| match &s.item {
                Item::Word { letter, value } => {
                    let v = match value {
                        super::expr::Expr::Number(v) => *v,
                        _ => f64::NAN,
                    };
                    Some(Word { letter: *letter, value: v, start: s.start, end: s.end })
                }
                _ => None,
            })
            .collect();
        LineWords { words, block_delete: parsed.block_delete }
    }

    /// The word of `letter`, if the line has one.
    pub fn get(&self, letter: u8) -> Option<&Word> {
        self.words.iter().find(|w| w.letter == letter)
    }

    /// Whether the line has G code `code` (ten times its number, `G93` → 930).
    pub fn has_g(&self, code: u32) -> bool {
        self.words.iter().any(|w| w.letter == b'G' && super::block::code_times_ten(w.value) == Some(code))
    }

    /// Whether the line has an M code among `codes` (ten times their numbers).
    pub fn has_m(&self, codes: &[u32]) -> bool {
        self.words
            .iter()
            .any(|w| w.letter == b'M' && super::block::code_times_ten(w.value).is_some_and(|c| codes.contains(&c)))
    }

    /// Where a new word goes: just after the last word (before trailing comments).
    pub fn insert_at(&self) -> u32 {
        self.words.iter().map(|w| w.end).max().unwrap_or(0)
    }
}

/// How a program spells numbers.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Style {
    /// Whole numbers get a decimal point (`X10.`).
    pub point: bool,
    /// Decimals of lengths.
    pub decimals: u32,
    /// Words are separated by spaces.
    pub spaced: bool,
}

/// Decimals the editor writes lengths with, at least: a micron in mm, a ten-thousandth
/// of an inch.
pub(crate) const MIN_DECIMALS_MM: u32 = 3;
pub(crate) const MIN_DECIMALS_INCH: u32 = 4;

impl Style {
    /// The style of `text`: a decimal point on whole numbers if any axis or feed word is
    /// written `X10.`; as many decimals as its longest axis word has (at least
    /// `min_decimals`); spaces if its words are spaced.
    pub fn of(text: &str, min_decimals: u32) -> Style {
        let bytes = text.as_bytes();
        let (mut point, mut decimals, mut spaced, mut unspaced) = (false, 0u32, 0usize, 0usize);
        let mut i = 0;
        while i < bytes.len() {
            let c = bytes[i].to_ascii_uppercase();
            if matches!(c, b'X' | b'Y' | b'Z' | b'F' | b'I' | b'J' | b'K' | b'R') {
                let digits = &bytes[i + 1..];
                let run = digits.iter().take_while(|b| b.is_ascii_digit() || matches!(b, b'.' | b'-' | b'+')).count();
                let number = &digits[..run];
                if let Some(dot) = number.iter().position(|&b| b == b'.') {
                    let after = number.len() - dot - 1;
                    point |= after == 0;
                    if c != b'F' {
                        decimals = decimals.max(after as u32);
                    }
                }
                if i > 0 {
                    match bytes[i - 1] {
                        b' ' | b'\t' => spaced += 1,
                        b'0'..=b'9' | b'.' => unspaced += 1,
                        _ => {}
                    }
                }
                i += 1 + run;
            } else {
                i += 1;
            }
        }
        Style { point, decimals: decimals.clamp(min_decimals, MAX_DECIMALS), spaced: spaced >= unspaced }
    }

    /// The separator between words.
    pub fn separator(&self) -> &'static str {
        if self.spaced {
            " "
        } else {
            ""
        }
    }

    /// `value` rounded to the program's decimals.
    pub fn length(&self, value: f64) -> Fixed {
        Fixed::round(value, self.decimals)
    }

    /// Writes `letter` and a rounded value.
    pub fn word(&self, out: &mut String, letter: char, value: Fixed) {
        out.push(letter);
        value.push_to(out, self.point);
    }
}

/// A feed rounded down (never faster) to `decimals` places.
pub(crate) fn feed_down(value: f64, decimals: u32) -> Fixed {
    let exact = Fixed::round(value, decimals);
    if exact.value() > value {
        Fixed { units: exact.units - 1, decimals: exact.decimals }
    } else {
        exact
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_style_follows_the_programs_own_numbers() {
        let fanuc = Style::of("N10 G1 X10. Y-2.5 F500.\nN20 X12.345", 3);
        assert_eq!(fanuc, Style { point: true, decimals: 3, spaced: true });
        let inch = Style::of("G20\nG1X1.23456Y2F10\n", 4);
        assert_eq!(inch, Style { point: false, decimals: 5, spaced: false });
        let mut out = String::new();
        fanuc.word(&mut out, 'X', fanuc.length(10.0));
        assert_eq!(out, "X10.");
    }

    #[test]
    fn feeds_are_rounded_down_and_words_are_found_in_any_line() {
        assert_eq!(feed_down(1160.99, 1).value(), 1160.9);
        assert_eq!(feed_down(1160.0, 1).value(), 1160.0);
        let w = LineWords::read(b"N10 G1 X[#1+2] F#5 (cut)");
        assert_eq!(w.get(b'F').map(|w| (w.start, w.end)), Some((15, 18)));
        assert!(w.get(b'X').unwrap().value.is_nan());
        assert_eq!(w.insert_at(), 18);
        assert!(LineWords::read(b"G93 G1 X1 F2").has_g(930));
        assert!(LineWords::read(b"X1 M30").has_m(&[300, 20]));
    }
}
