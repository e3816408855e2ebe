//! The words of one line: a byte scanner that splits a line into letter–number pairs,
//! skipping comments, without allocating (the caller's buffers are reused line after line).

/// One word of a line: a letter and its number, with where it was written.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Word {
    /// The letter, upper case (`b'A'..=b'Z'`).
    pub letter: u8,
    /// The number as written (in the program's units, not converted).
    pub value: f64,
    /// Byte offset of the letter in the line.
    pub start: u32,
    /// Byte offset just past the number.
    pub end: u32,
}

/// Something on a line that is not a word.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum IssueKind {
    /// A letter with no number after it.
    NoNumber,
    /// A character that starts no word, comment or anything else G-code knows.
    UnknownCharacter,
    /// A `(` comment with no `)` on the line.
    UnclosedComment,
    /// A `#` parameter (the rest of the line is not read).
    Parameter,
    /// A `[` expression (the rest of the line is not read).
    Expression,
    /// An `O` word: subprograms and control flow (the rest of the line is not read).
    Subprogram,
}

/// A non-word found on a line, with its byte span.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Issue {
    pub kind: IssueKind,
    pub start: u32,
    pub end: u32,
}

/// What the scanner learnt about a line besides its words.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub(crate) struct LineShape {
    /// The line starts with `/` (block delete).
    pub block_delete: bool,
    /// The line starts with `%` (tape start/end marker) and is not read.
    pub percent: bool,
    /// The line is a Fanuc program number: an `O` word with digits, then nothing but
    /// comments (`O1234 (TITLE)`). It is still reported as an [`IssueKind::Subprogram`]
    /// issue: the interpreter decides whether it is where a program number may be.
    pub program_number: bool,
}

/// Largest mantissa the fast decimal path accepts: 2⁵³, below which every integer is an
/// exact `f64`.
const FAST_MANTISSA_LIMIT: u64 = 1 << 53;

/// Powers of ten that are exact `f64` values (10⁰..10²²): dividing an exact mantissa by
/// one of them is a single correctly rounded operation (Clinger's fast path).
const EXACT_POWERS_OF_TEN: [f64; 23] = [
    1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15, 1e16, 1e17, 1e18, 1e19, 1e20,
    1e21, 1e22,
];

/// Digits accumulated in a `u64` before the fast path gives up (10¹⁹ < 2⁶⁴).
const MAX_FAST_DIGITS: u32 = 19;

/// Reads a decimal number at `bytes[i..]`: optional sign, digits with at most one point,
/// at least one digit. Returns the value and the index just past it.
///
/// The result is the correctly rounded value, the same as `str::parse::<f64>`: numbers
/// with at most 15 or so significant digits take an exact fast path, others fall back to
/// the standard library.
pub(crate) fn read_number(bytes: &[u8], mut i: usize) -> Option<(f64, usize)> {
    let start = i;
    let negative = match bytes.get(i) {
        Some(b'-') => {
            i += 1;
            true
        }
        Some(b'+') => {
            i += 1;
            false
        }
        _ => false,
    };
    let mut mantissa: u64 = 0;
    let mut digits: u32 = 0;
    let mut fraction_digits: u32 = 0;
    let mut seen_point = false;
    while let Some(&c) = bytes.get(i) {
        if c.is_ascii_digit() {
            if digits < MAX_FAST_DIGITS {
                mantissa = mantissa * 10 + u64::from(c - b'0');
            }
            digits += 1;
            if seen_point {
                fraction_digits += 1;
            }
        } else if c == b'.' && !seen_point {
            seen_point = true;
        } else {
            break;
        }
        i += 1;
    }
    if digits == 0 {
        return None;
    }
    let fast = digits <= MAX_FAST_DIGITS
        && mantissa <= FAST_MANTISSA_LIMIT
        && (fraction_digits as usize) < EXACT_POWERS_OF_TEN.len();
    let magnitude = if fast {
        mantissa as f64 / EXACT_POWERS_OF_TEN[fraction_digits as usize]
    } else {
        let unsigned = if negative || bytes[start] == b'+' { start + 1 } else { start };
        // Only ASCII digits and one point are in this slice, so both steps succeed.
        std::str::from_utf8(&bytes[unsigned..i]).ok()?.parse::<f64>().ok()?
    };
    Some((if negative { -magnitude } else { magnitude }, i))
}

/// Splits `line` into words (appended to `words`) and non-words (appended to `issues`).
/// Comments `( … )` and `;` to the end of the line are skipped, spaces and tabs are allowed
/// anywhere between words and between a letter and its number, letters may be lower case.
pub(crate) fn scan_line(line: &[u8], words: &mut Vec<Word>, issues: &mut Vec<Issue>) -> LineShape {
    let n = line.len();
    let (words_before, issues_before) = (words.len(), issues.len());
    let mut shape = LineShape::default();
    let mut i = 0;
    while i < n && is_blank(line[i]) {
        i += 1;
    }
    match line.get(i) {
        Some(b'%') => {
            shape.percent = true;
            return shape;
        }
        Some(b'/') => {
            shape.block_delete = true;
            i += 1;
        }
        _ => {}
    }
    while i < n {
        let c = line[i];
        match c {
            b' ' | b'\t' | b'\r' => i += 1,
            b'(' => match line[i + 1..].iter().position(|&b| b == b')') {
                Some(k) => i += k + 2,
                None => {
                    issues.push(issue(IssueKind::UnclosedComment, i, n));
                    break;
                }
            },
            b';' => break,
            b'#' | b'[' | b'O' | b'o' => {
                let (kind, end) = match c {
                    b'#' => (IssueKind::Parameter, i + 1),
                    b'[' => (IssueKind::Expression, i + 1),
                    _ => {
                        let digits = line[i + 1..].iter().take_while(|b| b.is_ascii_digit()).count();
                        let alone = words.len() == words_before && issues.len() == issues_before;
                        let end = i + 1 + digits;
                        shape.program_number =
                            alone && digits > 0 && !shape.block_delete && only_comments(&line[end..]);
                        (IssueKind::Subprogram, end)
                    }
                };
                issues.push(issue(kind, i, end));
                break;
            }
            _ if c.is_ascii_alphabetic() => {
                let mut j = i + 1;
                while j < n && is_blank(line[j]) {
                    j += 1;
                }
                match read_number(line, j) {
                    Some((value, end)) => {
                        words.push(Word { letter: c.to_ascii_uppercase(), value, start: i as u32, end: end as u32 });
                        i = end;
                    }
                    None => {
                        issues.push(issue(IssueKind::NoNumber, i, i + 1));
                        i += 1;
                    }
                }
            }
            _ => {
                let width = utf8_width(c).min(n - i);
                issues.push(issue(IssueKind::UnknownCharacter, i, i + width));
                i += width;
            }
        }
    }
    shape
}

/// Whether `rest` holds nothing but blanks, closed `( )` comments and a `;` comment.
fn only_comments(rest: &[u8]) -> bool {
    let mut i = 0;
    while i < rest.len() {
        match rest[i] {
            c if is_blank(c) => i += 1,
            b'(' => match rest[i + 1..].iter().position(|&b| b == b')') {
                Some(k) => i += k + 2,
                None => return false,
            },
            b';' => return true,
            _ => return false,
        }
    }
    true
}

fn issue(kind: IssueKind, start: usize, end: usize) -> Issue {
    Issue { kind, start: start as u32, end: end as u32 }
}

fn is_blank(c: u8) -> bool {
    c == b' ' || c == b'\t' || c == b'\r'
}

/// Number of bytes of the UTF-8 character whose first byte is `c` (1 for stray bytes).
fn utf8_width(c: u8) -> usize {
    match c {
        0xF0..=0xF7 => 4,
        0xE0..=0xEF => 3,
        0xC0..=0xDF => 2,
        _ => 1,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scan(text: &str) -> (Vec<(u8, f64)>, Vec<IssueKind>, LineShape) {
        let mut words = Vec::new();
        let mut issues = Vec::new();
        let shape = scan_line(text.as_bytes(), &mut words, &mut issues);
        (words.iter().map(|w| (w.letter, w.value)).collect(), issues.iter().map(|i| i.kind).collect(), shape)
    }

    #[test]
    fn the_fast_decimal_reader_agrees_with_the_standard_library() {
        for text in [
            "1",
            "-1.",
            ".5",
            "+2.5",
            "0.00000000",
            "-32.77817459",
            "123456789012345678901.5",
            "0.1234567890123456789012345",
            "92.430",
            "-0.0",
            "9007199254740993",
        ] {
            let (value, end) = read_number(text.as_bytes(), 0).unwrap();
            assert_eq!(end, text.len(), "{text}");
            let expected: f64 = text.parse().unwrap();
            assert_eq!(value.to_bits(), expected.to_bits(), "{text}");
        }
    }

    #[test]
    fn a_sign_or_point_without_digits_is_not_a_number() {
        for text in ["", "-", "+", ".", "-.", "x"] {
            assert_eq!(read_number(text.as_bytes(), 0), None, "{text}");
        }
    }

    #[test]
    fn letters_are_case_insensitive_and_spaces_may_separate_letter_and_number() {
        let (words, issues, _) = scan("g1x2 Y -3.5\tz .5");
        assert!(issues.is_empty());
        assert_eq!(words, vec![(b'G', 1.0), (b'X', 2.0), (b'Y', -3.5), (b'Z', 0.5)]);
    }

    #[test]
    fn comments_of_both_kinds_are_skipped_wherever_they_are() {
        let (words, issues, _) = scan("G0 (move up; X9 Y9) X1 (again) Y2 ; Z3 (ignored");
        assert!(issues.is_empty());
        assert_eq!(words, vec![(b'G', 0.0), (b'X', 1.0), (b'Y', 2.0)]);
    }

    #[test]
    fn percent_lines_block_delete_and_unclosed_comments_are_reported() {
        assert!(scan("  %").2.percent);
        let (words, _, shape) = scan("/G1 X1");
        assert!(shape.block_delete);
        assert_eq!(words.len(), 2);
        assert_eq!(scan("G1 (oops").1, vec![IssueKind::UnclosedComment]);
    }

    #[test]
    fn parameters_expressions_and_o_words_stop_the_line() {
        assert_eq!(scan("#1=5 G1").1, vec![IssueKind::Parameter]);
        assert_eq!(scan("G1 X[1+2] Y3").1, vec![IssueKind::NoNumber, IssueKind::Expression]);
        assert_eq!(scan("o100 sub").1, vec![IssueKind::Subprogram]);
    }

    #[test]
    fn an_o_word_alone_or_with_comments_is_marked_as_a_program_number() {
        for text in ["O1234", "  o0001 (DIE 12) ; rough", "O12(A)(B)\r"] {
            let (words, issues, shape) = scan(text);
            assert!(shape.program_number, "{text}");
            assert!(words.is_empty(), "{text}");
            assert_eq!(issues, vec![IssueKind::Subprogram], "{text}");
        }
        for text in ["o100 sub", "O", "G0 O1", "O1 (open", "/O1", "O1 G0 X1", "N10 O1"] {
            assert!(!scan(text).2.program_number, "{text}");
        }
    }

    #[test]
    fn a_letter_without_a_number_and_a_stray_character_are_issues_with_their_spans() {
        let mut words = Vec::new();
        let mut issues = Vec::new();
        scan_line("G1 X Y2 é*".as_bytes(), &mut words, &mut issues);
        assert_eq!(issues.len(), 3);
        assert_eq!((issues[0].kind, issues[0].start, issues[0].end), (IssueKind::NoNumber, 3, 4));
        assert_eq!((issues[1].start, issues[1].end), (8, 10));
        assert_eq!((issues[2].start, issues[2].end), (10, 11));
        assert_eq!(words[1].start, 5);
        assert_eq!(words[1].end, 7);
    }
}
