//! One block (line) of G-code as the interpreter sees it: its words by letter (the 26
//! letters and LinuxCNC's polar `@` and `^`) and its G and M codes classified into modal
//! groups. The codes are those LinuxCNC and Fanuc read in 3-axis milling; see `codes.rs`.

use super::codes::{classify_g, classify_m, Class, GCode, Group, MCode};
use super::lexer::Word;
use super::report::Line;

/// A number closer than this to an integer (or, for G codes, to a tenth) is that integer.
pub(crate) const INTEGER_TOLERANCE: f64 = 1e-6;

/// G and M codes are stored as ten times their number (`G90.1` → 901).
const CODE_SCALE: f64 = 10.0;

/// Largest code number read (ten times the code); larger ones are unknown.
const MAX_CODE_TIMES_TEN: f64 = 100_000.0;

/// Slots of the word letters: A–Z, then `@` (polar distance) and `^` (polar angle).
const LETTER_SLOTS: usize = 28;

/// The slot of a word letter.
pub(crate) const fn slot(letter: u8) -> usize {
    match letter {
        b'@' => 26,
        b'^' => 27,
        _ => (letter - b'A') as usize,
    }
}

/// The bit of a letter in a letter mask.
pub(crate) const fn bit(letter: u8) -> u32 {
    1 << slot(letter)
}

/// The axis letters X, Y and Z.
pub(crate) const AXES: u32 = bit(b'X') | bit(b'Y') | bit(b'Z');

/// LinuxCNC's polar words.
pub(crate) const POLAR: u32 = bit(b'@') | bit(b'^');

/// The letters of a mask, for messages.
pub(crate) fn letter_of(slot: usize) -> char {
    match slot {
        26 => '@',
        27 => '^',
        s => char::from(b'A' + s as u8),
    }
}

const ROTARY_AXES: &str = "rotary and secondary axes (A/B/C/U/V/W) are not supported: dieplan plans 3-axis milling";

/// The code number ×10 of a G or M value, if it is a non-negative multiple of a tenth.
pub(crate) fn code_times_ten(value: f64) -> Option<u32> {
    let scaled = value * CODE_SCALE;
    if !(0.0..MAX_CODE_TIMES_TEN).contains(&scaled) {
        return None;
    }
    // Nearest integer (`scaled` ≥ 0, so truncation after adding a half rounds).
    let nearest = (scaled + 0.5) as u32;
    let exact = (scaled - f64::from(nearest)).abs() <= INTEGER_TOLERANCE * CODE_SCALE;
    exact.then_some(nearest)
}

/// The words of one line, by letter.
#[derive(Debug, Default)]
pub(crate) struct Block {
    present: u32,
    values: [f64; LETTER_SLOTS],
    index: [u32; LETTER_SLOTS],
    /// Known G codes: code, modal group, word index.
    pub g: Vec<(GCode, Group, usize)>,
    /// Known M codes: code, modal group, word index.
    pub m: Vec<(MCode, Group, usize)>,
}

impl Block {
    /// Letters with a value on this line (not G, M, N).
    pub fn present(&self) -> u32 {
        self.present
    }

    /// The value of `letter`'s word, as written.
    pub fn value(&self, letter: u8) -> Option<f64> {
        (self.present & bit(letter) != 0).then(|| self.values[slot(letter)])
    }

    /// Whether `letter` has a word on this line.
    pub fn has(&self, letter: u8) -> bool {
        self.present & bit(letter) != 0
    }

    /// The index (in the line's words) of `letter`'s word; meaningful only if present.
    pub fn word(&self, letter: u8) -> usize {
        self.index[slot(letter)] as usize
    }

    /// Reads the words of a line, reporting unknown, refused, repeated and conflicting ones.
    pub fn fill(&mut self, words: &[Word], line: &mut Line) {
        self.present = 0;
        self.g.clear();
        self.m.clear();
        for (i, w) in words.iter().enumerate() {
            if !w.value.is_finite() {
                line.error_at(i, "the number is out of range");
                continue;
            }
            match w.letter {
                b'G' => match code_times_ten(w.value).map_or(Class::Unknown, classify_g) {
                    Class::Known(code, group) => {
                        if let Some(&(_, _, j)) = self.g.iter().find(|g| g.1 == group) {
                            let other = line.word_text(j);
                            let reason = if group == Group::Motion {
                                format!("two motion codes on one line ({other} and this one)")
                            } else {
                                format!("{other} on the same line is of the same modal group")
                            };
                            line.error_at(i, reason);
                        }
                        self.g.push((code, group, i));
                    }
                    Class::Refused(reason) => line.error_at(i, reason).ignore(),
                    Class::Unknown => line.unknown_at(i, "unknown G code"),
                },
                b'M' => match code_times_ten(w.value).map_or(Class::Unknown, classify_m) {
                    Class::Known(code, group) => {
                        if let Some(j) = self.m_clash(group, code) {
                            let other = line.word_text(j);
                            line.error_at(i, format!("{other} on the same line is of the same group"));
                        }
                        self.m.push((code, group, i));
                    }
                    Class::Refused(reason) => line.error_at(i, reason).ignore(),
                    // An M code moves no axis: an unknown one (a machine builder's own) is
                    // read as an auxiliary function, with a warning.
                    Class::Unknown => {
                        let text = line.word_text(i);
                        line.warn(format!(
                            "{text} is not a standard M code: read as an auxiliary function that moves nothing"
                        ));
                    }
                },
                b'N' => {}
                b'A' | b'B' | b'C' | b'U' | b'V' | b'W' => line.error_at(i, ROTARY_AXES).ignore(),
                b'D' | b'F' | b'H' | b'I' | b'J' | b'K' | b'L' | b'P' | b'Q' | b'R' | b'S' | b'T' | b'X' | b'Y'
                | b'Z' | b'@' | b'^' => {
                    let s = slot(w.letter);
                    if self.present & bit(w.letter) != 0 {
                        let letter = char::from(w.letter);
                        line.error_at(i, format!("two {letter} words on one line"));
                    } else {
                        self.present |= bit(w.letter);
                        self.values[s] = w.value;
                        self.index[s] = i as u32;
                    }
                }
                _ => line.unknown_at(i, "unknown letter"),
            }
        }
        self.fanuc_dwell();
    }

    /// Fanuc's dwell `G4 X<seconds>` (no P on the line) is read as `G4 P<seconds>`.
    fn fanuc_dwell(&mut self) {
        let dwell = self.g.iter().any(|g| g.0 == GCode::Dwell);
        if dwell && self.has(b'X') && !self.has(b'P') {
            let (x, p) = (slot(b'X'), slot(b'P'));
            self.present = (self.present & !bit(b'X')) | bit(b'P');
            self.values[p] = self.values[x];
            self.index[p] = self.index[x];
        }
    }

    /// Removes a word (read by the interpreter's control flow, not by the block).
    pub fn take(&mut self, letter: u8) -> Option<(f64, usize)> {
        let v = self.value(letter)?;
        self.present &= !bit(letter);
        Some((v, self.word(letter)))
    }

    /// The earlier M word of `group` that `code` cannot share a line with (M7 and M8 can).
    fn m_clash(&self, group: Group, code: MCode) -> Option<usize> {
        let both_on =
            |other: MCode| matches!((other, code), (MCode::Coolant { on: true }, MCode::Coolant { on: true }));
        self.m.iter().find(|m| m.1 == group && !both_on(m.0)).map(|m| m.2)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_code_is_read_to_a_tenth_and_other_fractions_are_not_codes() {
        assert_eq!(code_times_ten(1.0), Some(10));
        assert_eq!(code_times_ten(90.1), Some(901));
        assert_eq!(code_times_ten(59.3), Some(593));
        assert_eq!(code_times_ten(0.0), Some(0));
        assert_eq!(code_times_ten(1.25), None);
        assert_eq!(code_times_ten(-1.0), None);
        assert_eq!(code_times_ten(1e9), None);
    }

    #[test]
    fn polar_words_have_their_own_slots_beside_the_letters() {
        assert_eq!((slot(b'A'), slot(b'Z'), slot(b'@'), slot(b'^')), (0, 25, 26, 27));
        assert_eq!((letter_of(26), letter_of(27), letter_of(3)), ('@', '^', 'D'));
        assert_eq!(POLAR & AXES, 0);
    }
}
