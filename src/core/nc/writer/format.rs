//! How the writer spells numbers and comments.
//!
//! A number is first rounded to a fixed count of decimals ([`Fixed`], an exact integer
//! count of 10⁻ᵈ), so that "did this value change?" is an integer comparison of what is
//! written, and the text is built from that integer: no float formatting, no `-0`, trailing
//! zeros trimmed, and on request a decimal point on whole numbers (Fanuc reads `X10` as ten
//! least increments, 0.010 mm, and `X10.` as 10 mm).

use std::fmt::Write as _;

use crate::core::toolpath::Section;

/// Most decimals written (0.1 µm for mm): more would be noise, and keeps [`Fixed`] exact.
pub const MAX_DECIMALS: u32 = 6;

/// Powers of ten up to 10^[`MAX_DECIMALS`].
const POWERS_OF_TEN: [i64; MAX_DECIMALS as usize + 1] = [1, 10, 100, 1_000, 10_000, 100_000, 1_000_000];

/// A value rounded to `decimals` places: `units` × 10^−`decimals`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Fixed {
    pub units: i64,
    pub decimals: u32,
}

impl Fixed {
    /// `value` rounded half away from zero to `decimals` places (at most
    /// [`MAX_DECIMALS`]). The rounding is of `value × 10^decimals` as an `f64`; values out of
    /// the `i64` range saturate, NaN is 0.
    pub fn round(value: f64, decimals: u32) -> Fixed {
        let decimals = decimals.min(MAX_DECIMALS);
        let scaled = value * POWERS_OF_TEN[decimals as usize] as f64;
        // `f64::round` rounds half away from zero; `as` saturates and maps NaN to 0.
        Fixed { units: scaled.round() as i64, decimals }
    }

    /// The rounded value as an `f64`.
    pub fn value(self) -> f64 {
        self.units as f64 / POWERS_OF_TEN[self.decimals as usize] as f64
    }

    /// Appends the value to `out`: `-` only when non-zero, trailing zeros trimmed, a point
    /// after a whole number only if `point`. `0` (or `0.`) for zero.
    pub fn push_to(self, out: &mut String, point: bool) {
        if self.units < 0 {
            out.push('-');
        }
        let magnitude = self.units.unsigned_abs();
        let scale = POWERS_OF_TEN[self.decimals as usize].unsigned_abs();
        let (whole, mut fraction) = (magnitude / scale, magnitude % scale);
        let mut digits = self.decimals as usize;
        while digits > 0 && fraction % 10 == 0 {
            fraction /= 10;
            digits -= 1;
        }
        // Writing to a `String` cannot fail.
        let _ = write!(out, "{whole}");
        if digits > 0 {
            let _ = write!(out, ".{fraction:0digits$}");
        } else if point {
            out.push('.');
        }
    }
}

/// Characters a comment cannot hold, and what replaces them: a `)` would end the comment,
/// a `(` inside one is an error on some controls and `%` ends a Fanuc tape.
const COMMENT_REPLACEMENTS: [(char, char); 3] = [('(', '['), (')', ']'), ('%', ' ')];

/// LinuxCNC comments starting with one of these words (then a comma, or for the file words
/// anything) are commands, not comments.
const LINUXCNC_ACTIVE_COMMENTS: [&str; 10] =
    ["MSG", "DEBUG", "PRINT", "LOG", "LOGOPEN", "LOGAPPEND", "LOGCLOSE", "PROBEOPEN", "PROBECLOSE", "PY"];

/// `text` made safe inside `( )`: brackets for parentheses, spaces for `%` and control
/// characters (line ends included), trimmed. `upper_ascii` (Fanuc) also upper-cases it and
/// replaces non-ASCII characters with `?`. A text that LinuxCNC would take for a command
/// (`MSG,…`, `PROBEOPEN …`) gets a leading `-`.
pub(crate) fn comment_text(text: &str, upper_ascii: bool) -> String {
    let mut safe: String = text
        .chars()
        .map(|c| {
            let c = COMMENT_REPLACEMENTS.iter().find(|(from, _)| *from == c).map_or(c, |&(_, to)| to);
            match c {
                _ if c.is_control() => ' ',
                _ if upper_ascii && !c.is_ascii() => '?',
                _ if upper_ascii => c.to_ascii_uppercase(),
                _ => c,
            }
        })
        .collect();
    safe = safe.trim().to_string();
    let first_word: String = safe.chars().take_while(char::is_ascii_alphabetic).collect();
    if LINUXCNC_ACTIVE_COMMENTS.iter().any(|w| w.eq_ignore_ascii_case(&first_word)) {
        safe.insert(0, '-');
    }
    safe
}

/// The comment of a section label: `LAYER 2 Z-20 TROCHOIDAL GROOVING REGION 1`, the layer
/// and the region counted from 1, the height at `decimals` (no point on whole numbers), the
/// words upper case in both dialects.
pub(crate) fn section_text(section: &Section, decimals: u32) -> String {
    let mut text = format!("LAYER {} Z", u64::from(section.layer) + 1);
    Fixed::round(section.z_mm, decimals).push_to(&mut text, false);
    text.push(' ');
    text.push_str(&section.step.name().to_ascii_uppercase());
    if let Some(region) = section.region {
        let _ = write!(text, " REGION {}", u64::from(region) + 1);
    }
    text
}

#[cfg(test)]
mod tests {
    use super::*;

    fn text(value: f64, decimals: u32, point: bool) -> String {
        let mut out = String::new();
        Fixed::round(value, decimals).push_to(&mut out, point);
        out
    }

    #[test]
    fn numbers_are_rounded_half_away_from_zero_and_trailing_zeros_are_trimmed() {
        assert_eq!(text(10.0, 3, false), "10");
        assert_eq!(text(10.0, 3, true), "10.");
        assert_eq!(text(10.25, 1, false), "10.3");
        assert_eq!(text(-10.25, 1, false), "-10.3");
        assert_eq!(text(0.5, 0, false), "1");
        assert_eq!(text(-0.5, 0, true), "-1.");
        assert_eq!(text(1.2304, 3, true), "1.23");
        assert_eq!(text(-0.001, 3, true), "-0.001");
        assert_eq!(text(123_456.789_012_4, 6, false), "123456.789012");
    }

    #[test]
    fn minus_zero_and_values_that_round_to_zero_are_written_as_zero() {
        assert_eq!(text(-0.0, 3, false), "0");
        assert_eq!(text(-0.0004, 3, true), "0.");
        assert_eq!(text(0.0004, 3, false), "0");
    }

    #[test]
    fn decimals_beyond_the_maximum_are_capped() {
        let f = Fixed::round(1.234_567_89, 9);
        assert_eq!(f.decimals, MAX_DECIMALS);
        assert_eq!(f.units, 1_234_568);
        assert!((f.value() - 1.234_568).abs() < 1e-12);
    }

    #[test]
    fn a_section_is_its_layer_height_step_and_region_counted_from_one() {
        use crate::core::toolpath::Step;
        let s = Section { layer: 1, z_mm: -20.0, step: Step::TrochoidalGrooving, region: Some(0) };
        assert_eq!(section_text(&s, 3), "LAYER 2 Z-20 TROCHOIDAL GROOVING REGION 1");
        let s = Section { layer: 0, z_mm: -8.333_333, step: Step::ZCutDivision, region: Some(11) };
        assert_eq!(section_text(&s, 3), "LAYER 1 Z-8.333 Z-CUT DIVISION REGION 12");
        let s = Section { layer: 3, z_mm: -35.0, step: Step::IntermediateRoughSideCutting, region: None };
        assert_eq!(section_text(&s, 3), "LAYER 4 Z-35 INTERMEDIATE-ROUGH SIDE CUTTING");
    }

    #[test]
    fn comments_lose_their_parentheses_and_line_ends_and_fanuc_ones_are_upper_case_ascii() {
        assert_eq!(comment_text(" Die (left) 50%\nv2 ", false), "Die [left] 50  v2");
        assert_eq!(comment_text("côté (A)", true), "C?T? [A]");
        assert_eq!(comment_text("msg, hello", false), "-msg, hello");
        assert_eq!(comment_text("Message board", false), "Message board");
    }
}
