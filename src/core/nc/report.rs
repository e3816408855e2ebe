//! Where the problems of a line go: the reporter that turns them into errors (with line,
//! column and word) or, for unknown words under [`UnknownWords::Warn`], warnings.

use super::error::{Diagnostics, NcError};
use super::lexer::Word;
use super::line::Fault;
use super::UnknownWords;

/// Whether `b` continues a multi-byte UTF-8 character (bits 10xxxxxx).
fn is_utf8_continuation(b: u8) -> bool {
    const TOP_TWO_BITS: u8 = 0b1100_0000;
    const CONTINUATION: u8 = 0b1000_0000;
    b & TOP_TWO_BITS == CONTINUATION
}

/// A word longer than this many characters is quoted in errors and warnings by its first
/// ones and an ellipsis: a 10 000-digit number or a comment left open over a whole file
/// is named, not echoed.
pub const MAX_QUOTED_WORD_CHARS: usize = 32;

/// Marks that a line has an error: the line's effects are dropped.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Failed;

impl Failed {
    /// For errors recorded without stopping the line's reading.
    pub fn ignore(self) {}
}

/// A line being read: where its errors and warnings go.
pub(crate) struct Line<'a> {
    /// 1-based line number.
    pub number: u32,
    text: &'a [u8],
    words: &'a [Word],
    diagnostics: &'a mut Diagnostics,
    unknown: UnknownWords,
    /// An error was reported on this line.
    pub failed: bool,
    /// The last byte offset whose column was found, and the characters before it.
    counted: (u32, usize),
}

impl<'a> Line<'a> {
    /// A reporter for line `number` (1-based) of text `text` with words `words`.
    pub fn new(
        number: u32,
        text: &'a [u8],
        words: &'a [Word],
        diagnostics: &'a mut Diagnostics,
        unknown: UnknownWords,
    ) -> Self {
        Line { number, text, words, diagnostics, unknown, failed: false, counted: (0, 0) }
    }

    /// The text of word `i` as written.
    pub fn word_text(&self, i: usize) -> String {
        let w = &self.words[i];
        self.span_text(w.start, w.end)
    }

    /// The text from byte `start` to `end` as written, shortened past
    /// [`MAX_QUOTED_WORD_CHARS`].
    fn span_text(&self, start: u32, end: u32) -> String {
        let text = String::from_utf8_lossy(&self.text[start as usize..end as usize]);
        match text.char_indices().nth(MAX_QUOTED_WORD_CHARS) {
            Some((cut, _)) => format!("{}…", &text[..cut]),
            None => text.into_owned(),
        }
    }

    /// 1-based column (in characters) of byte offset `start`. Counting resumes from the
    /// last column asked for when `start` lies after it, so a line's errors (found in
    /// order) cost one walk over the line.
    fn column(&mut self, start: u32) -> u32 {
        let (from, mut chars) = if start >= self.counted.0 { self.counted } else { (0, 0) };
        let between = &self.text[from as usize..start as usize];
        chars += between.iter().filter(|&&b| !is_utf8_continuation(b)).count();
        self.counted = (start, chars);
        u32::try_from(chars + 1).unwrap_or(u32::MAX)
    }

    fn error_span(&mut self, start: u32, end: u32, reason: String) -> Failed {
        self.failed = true;
        if self.diagnostics.full() {
            // No more errors are kept: none is worth locating.
            return Failed;
        }
        let error = NcError { line: self.number, column: self.column(start), word: self.span_text(start, end), reason };
        self.diagnostics.error(error);
        Failed
    }

    /// Reports an error on word `i`.
    pub fn error_at(&mut self, i: usize, reason: impl Into<String>) -> Failed {
        let w = self.words[i];
        self.error_span(w.start, w.end, reason.into())
    }

    /// Reports an error on word `i` if there is one, else on the whole line (column 1).
    pub fn error_near(&mut self, i: Option<usize>, reason: impl Into<String>) -> Failed {
        match i {
            Some(i) => self.error_at(i, reason),
            None => self.error_span(0, 0, reason.into()),
        }
    }

    fn unknown_span(&mut self, start: u32, end: u32, what: &str) {
        match self.unknown {
            UnknownWords::Reject => {
                let reason = format!("{what} (only the words of the supported dialect are read)");
                self.error_span(start, end, reason).ignore();
            }
            UnknownWords::Warn => {
                let message = format!("unknown word {} ignored", self.span_text(start, end));
                self.warn(message);
            }
        }
    }

    /// Reports an unknown word: an error, or a warning under [`UnknownWords::Warn`].
    pub fn unknown_at(&mut self, i: usize, what: &str) {
        let w = self.words[i];
        self.unknown_span(w.start, w.end, what);
    }

    /// Reports a fault the full reader found: an unknown character is an unknown word
    /// (a warning under [`UnknownWords::Warn`]), anything else an error.
    pub fn fault(&mut self, fault: &Fault) {
        if fault.unknown {
            self.unknown_span(fault.start, fault.end, "unknown character");
        } else {
            self.error_span(fault.start, fault.end, fault.reason.clone()).ignore();
        }
    }

    /// Reports an error on the byte span `start..end` of the line.
    pub fn error_on(&mut self, start: u32, end: u32, reason: impl Into<String>) -> Failed {
        self.error_span(start, end, reason.into())
    }

    /// Adds a warning about this line.
    pub fn warn(&mut self, message: impl std::fmt::Display) {
        let line = self.number;
        self.diagnostics.warn(format!("line {line}: {message}"));
    }
}
