//! Whose rules a program follows where LinuxCNC and Fanuc differ, recognised from its
//! text the first time a line's meaning depends on it.

use super::options::Control;

/// Fanuc's rules for a program that looks like a Fanuc program, LinuxCNC's otherwise:
/// one pass over the bytes, looking at line starts (`%`, `O1234`, `o100 sub`) and for
/// `#<`, `M98`, `M99`, `G65`, `GOTO`, `WHILE[` and `IF[` anywhere.
pub(crate) fn resolve_control(text: &[u8]) -> Control {
    let mut fanuc = false;
    let mut line_start = true;
    let n = text.len();
    let upper = |i: usize| text.get(i).map_or(0, u8::to_ascii_uppercase);
    let word = |i: usize, w: &[u8]| w.iter().enumerate().all(|(k, &c)| upper(i + k) == c);
    let mut i = 0;
    while i < n {
        let c = text[i];
        if line_start && !matches!(c, b' ' | b'\t' | b'\r') {
            line_start = false;
            match c.to_ascii_uppercase() {
                b'%' => fanuc = true,
                b'O' => {
                    let digits = text[i + 1..].iter().take_while(|b| b.is_ascii_digit()).count();
                    match text.get(i + 1 + digits) {
                        _ if upper(i + 1) == b'<' => return Control::LinuxCnc,
                        Some(b) if digits > 0 && (b.is_ascii_alphabetic() || *b == b' ') => {
                            let after = text[i + 1 + digits..].iter().position(|b| !matches!(b, b' ' | b'\t'));
                            let next = after.map_or(0, |k| upper(i + 1 + digits + k));
                            if next.is_ascii_alphabetic() {
                                return Control::LinuxCnc;
                            }
                            fanuc = true;
                        }
                        _ if digits > 0 => fanuc = true,
                        _ => {}
                    }
                }
                _ => {}
            }
        }
        match c {
            b'\n' => line_start = true,
            b'#' if text.get(i + 1) == Some(&b'<') => return Control::LinuxCnc,
            b'M' | b'm' if word(i + 1, b"98") || word(i + 1, b"99") => fanuc = true,
            b'G' | b'g' if word(i + 1, b"65") || word(i + 1, b"OTO") => fanuc = true,
            b'W' | b'w' if word(i + 1, b"HILE[") || word(i + 1, b"HILE [") => fanuc = true,
            b'I' | b'i' if word(i + 1, b"F[") || word(i + 1, b"F [") => fanuc = true,
            _ => {}
        }
        i += 1;
    }
    if fanuc {
        Control::Fanuc
    } else {
        Control::LinuxCnc
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fanuc_programs_are_recognised_by_their_marks_and_linuxcnc_ones_by_theirs() {
        for text in ["%\nO0001\nG0 X1\nM30\n%", "G0 X1\nM98 P100\n", "#1=1\nIF [#1 EQ 1] GOTO 10\n", "O1000 (SUB)\n"] {
            assert_eq!(resolve_control(text.as_bytes()), Control::Fanuc, "{text}");
        }
        for text in ["o100 sub\no100 endsub\nM98 P1", "G0 X#<depth>", "G0 X1\nM2", "o<p> call"] {
            assert_eq!(resolve_control(text.as_bytes()), Control::LinuxCnc, "{text}");
        }
    }
}
