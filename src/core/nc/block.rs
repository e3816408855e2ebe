//! One block (line) of G-code as the interpreter sees it: its words sorted by letter and
//! its G and M codes classified into modal groups.

use super::canned::CycleKind;
use super::lexer::Word;
use super::report::Line;
use crate::core::toolpath::{Plane, Units};

/// A number closer than this to an integer (or, for G codes, to a tenth) is that integer.
pub(crate) const INTEGER_TOLERANCE: f64 = 1e-6;

/// G and M codes are stored as ten times their number (`G90.1` → 901).
const CODE_SCALE: f64 = 10.0;

/// Largest code number read (ten times the code); larger ones are unknown.
const MAX_CODE_TIMES_TEN: f64 = 100_000.0;

/// The bit of a letter in a letter mask.
pub(crate) const fn bit(letter: u8) -> u32 {
    1 << (letter - b'A')
}

/// The axis letters X, Y and Z.
pub(crate) const AXES: u32 = bit(b'X') | bit(b'Y') | bit(b'Z');

/// Which way a G2/G3-group code moves the tool.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum MotionCode {
    Rapid,
    Linear,
    Arc { clockwise: bool },
    Cycle(CycleKind),
}

/// A G code this parser knows.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum GCode {
    Motion(MotionCode),
    /// G80.
    CancelCycle,
    /// G4.
    Dwell,
    Plane(Plane),
    Units(Units),
    /// G90 / G91.
    Distance {
        absolute: bool,
    },
    /// G90.1 / G91.1.
    ArcDistance {
        absolute: bool,
    },
    /// G98 (false) / G99 (true).
    RetractToR(bool),
    /// G43: reads H.
    ToolLength,
    /// G64: reads P and Q (ignored, with a warning).
    Blending,
    /// Read, no effect on the path.
    NoOp,
}

/// An M code this parser knows.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum MCode {
    /// M0, M1.
    Stop,
    /// M2, M30.
    End,
    /// M3 (`Some(true)`), M4 (`Some(false)`), M5 (`None`).
    Spindle(Option<bool>),
    /// M6.
    ToolChange,
    /// M7, M8 (on) or M9 (off).
    Coolant { on: bool },
}

/// Modal groups: two codes of one group cannot share a line.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Group {
    /// G4 (and the refused G10, G28, G30, G53, G92).
    NonModal,
    Motion,
    Plane,
    Distance,
    ArcDistance,
    FeedMode,
    Units,
    CutterCompensation,
    ToolLength,
    Retract,
    Coordinates,
    PathControl,
    /// G80 (its own group, so that `G80 G0 …` is accepted as Fanuc posts write it).
    CancelCycle,
    /// G15 (polar coordinates off).
    Polar,
    /// G69 (rotation off).
    Rotation,
    Stop,
    ToolChange,
    Spindle,
    Coolant,
}

/// What a code is: known (with its modal group), refused (with the reason) or unknown.
enum Class<T> {
    Known(T, Group),
    Refused(&'static str),
    Unknown,
}

const CUTTER_COMPENSATION: &str = "cutter radius compensation (G41/G42) is not supported: send the tool-centre path";
const INVERSE_TIME: &str = "inverse-time feed (G93) is not supported: send feeds per minute (G94)";
const FEED_PER_REVOLUTION: &str = "feed per revolution (G95) is not supported: send feeds per minute (G94)";
const POSITION_CHANGE: &str = "G10/G28/G30/G53/G92 change positions or offsets the planner \
     cannot know: send the moves in one work coordinate system";
const OTHER_CYCLES: &str = "only the G81, G82 and G83 canned cycles are supported";
const ROTARY_AXES: &str = "rotary and secondary axes (A/B/C/U/V/W) are not supported";
pub(crate) const SUBPROGRAMS: &str = "O words and subprograms (O, M98, M99) are not supported: send the \
     program with its subprograms and loops expanded";
pub(crate) const PARAMETERS: &str = "# parameters are not supported: send the program with numbers";
pub(crate) const EXPRESSIONS: &str = "[ ] expressions are not supported: send the program with numbers";

fn classify_g(code: u32) -> Class<GCode> {
    use Class::{Known, Refused};
    use GCode as G;
    use Group as K;
    match code {
        0 => Known(G::Motion(MotionCode::Rapid), K::Motion),
        10 => Known(G::Motion(MotionCode::Linear), K::Motion),
        20 => Known(G::Motion(MotionCode::Arc { clockwise: true }), K::Motion),
        30 => Known(G::Motion(MotionCode::Arc { clockwise: false }), K::Motion),
        810 => Known(G::Motion(MotionCode::Cycle(CycleKind::Drill)), K::Motion),
        820 => Known(G::Motion(MotionCode::Cycle(CycleKind::DwellAtBottom)), K::Motion),
        830 => Known(G::Motion(MotionCode::Cycle(CycleKind::Peck)), K::Motion),
        730 | 740 | 760 | 840 | 850 | 860 | 870 | 880 | 890 => Refused(OTHER_CYCLES),
        40 => Known(G::Dwell, K::NonModal),
        170 => Known(G::Plane(Plane::Xy), K::Plane),
        180 => Known(G::Plane(Plane::Zx), K::Plane),
        190 => Known(G::Plane(Plane::Yz), K::Plane),
        200 => Known(G::Units(Units::Inch), K::Units),
        210 => Known(G::Units(Units::Mm), K::Units),
        400 => Known(G::NoOp, K::CutterCompensation),
        410 | 411 | 420 | 421 => Refused(CUTTER_COMPENSATION),
        430 => Known(G::ToolLength, K::ToolLength),
        490 => Known(G::NoOp, K::ToolLength),
        540 | 550 | 560 | 570 | 580 | 590 | 591 | 592 | 593 => Known(G::NoOp, K::Coordinates),
        610 | 611 => Known(G::NoOp, K::PathControl),
        640 => Known(G::Blending, K::PathControl),
        800 => Known(G::CancelCycle, K::CancelCycle),
        900 => Known(G::Distance { absolute: true }, K::Distance),
        910 => Known(G::Distance { absolute: false }, K::Distance),
        901 => Known(G::ArcDistance { absolute: true }, K::ArcDistance),
        911 => Known(G::ArcDistance { absolute: false }, K::ArcDistance),
        930 => Refused(INVERSE_TIME),
        940 => Known(G::NoOp, K::FeedMode),
        950 => Refused(FEED_PER_REVOLUTION),
        980 => Known(G::RetractToR(false), K::Retract),
        990 => Known(G::RetractToR(true), K::Retract),
        150 => Known(G::NoOp, K::Polar),
        690 => Known(G::NoOp, K::Rotation),
        100 | 280 | 281 | 300 | 301 | 530 | 920..=923 => Refused(POSITION_CHANGE),
        _ => Class::Unknown,
    }
}

fn classify_m(code: u32) -> Class<MCode> {
    use Class::Known;
    match code {
        0 | 10 => Known(MCode::Stop, Group::Stop),
        20 | 300 => Known(MCode::End, Group::Stop),
        30 => Known(MCode::Spindle(Some(true)), Group::Spindle),
        40 => Known(MCode::Spindle(Some(false)), Group::Spindle),
        50 => Known(MCode::Spindle(None), Group::Spindle),
        60 => Known(MCode::ToolChange, Group::ToolChange),
        70 | 80 => Known(MCode::Coolant { on: true }, Group::Coolant),
        90 => Known(MCode::Coolant { on: false }, Group::Coolant),
        980 | 990 => Class::Refused(SUBPROGRAMS),
        _ => Class::Unknown,
    }
}

/// The code number ×10 of a G or M value, if it is a non-negative multiple of a tenth.
fn code_times_ten(value: f64) -> Option<u32> {
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
    values: [f64; 26],
    index: [u32; 26],
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
        (self.present & bit(letter) != 0).then(|| self.values[usize::from(letter - b'A')])
    }

    /// Whether `letter` has a word on this line.
    pub fn has(&self, letter: u8) -> bool {
        self.present & bit(letter) != 0
    }

    /// The index (in the line's words) of `letter`'s word; meaningful only if present.
    pub fn word(&self, letter: u8) -> usize {
        self.index[usize::from(letter - b'A')] as usize
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
                        let clash = self.m_clash(group, code);
                        if let Some(j) = clash {
                            let other = line.word_text(j);
                            line.error_at(i, format!("{other} on the same line is of the same group"));
                        }
                        self.m.push((code, group, i));
                    }
                    Class::Refused(reason) => line.error_at(i, reason).ignore(),
                    Class::Unknown => line.unknown_at(i, "unknown M code"),
                },
                b'N' => {}
                b'A' | b'B' | b'C' | b'U' | b'V' | b'W' => line.error_at(i, ROTARY_AXES).ignore(),
                b'X' | b'Y' | b'Z' | b'I' | b'J' | b'K' | b'R' | b'F' | b'S' | b'T' | b'P' | b'Q' | b'H' | b'L' => {
                    let slot = usize::from(w.letter - b'A');
                    if self.present & bit(w.letter) != 0 {
                        let letter = char::from(w.letter);
                        line.error_at(i, format!("two {letter} words on one line"));
                    } else {
                        self.present |= bit(w.letter);
                        self.values[slot] = w.value;
                        self.index[slot] = i as u32;
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
            let (x, p) = (usize::from(b'X' - b'A'), usize::from(b'P' - b'A'));
            self.present = (self.present & !bit(b'X')) | bit(b'P');
            self.values[p] = self.values[x];
            self.index[p] = self.index[x];
        }
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
    fn g80_has_its_own_group_so_fanuc_style_g80_g0_lines_are_accepted() {
        let group = |code| match classify_g(code) {
            Class::Known(_, group) => group,
            _ => panic!("G{code} is not known"),
        };
        assert_ne!(group(800), group(0));
        assert_eq!(group(810), group(0));
        assert_eq!(group(901), Group::ArcDistance);
        assert!(matches!(classify_g(410), Class::Refused(_)));
        assert!(matches!(classify_g(50), Class::Unknown));
    }
}
