//! Splitting one block where its feed changes: the pieces of its move written as blocks
//! of the same kind, in the program's own terms. Lines stay lines; arcs stay arcs with
//! their centre written as the block wrote it (`R`, or `I/J/K` incremental or, under
//! G90.1, absolute); coordinates absolute or incremental (G91) as the block's; units and
//! number style the program's. The last piece ends exactly where the block did: its axis
//! words are the block's own when they were plain numbers, and under G91 the pieces'
//! increments add up to the block's to the last digit.

use super::super::blocks::Piece;
use super::super::split::sub_move;
use super::{feed_word, mm_per, FeedValue};
use crate::core::nc::words::{Fixed, LineWords, Style};
use crate::core::nc::{ArcFormat, MotionContext};
use crate::core::toolpath::arc_sweep;
use crate::core::toolpath::{Motion, Move, Plane, P3};

/// Letters of the motion words a split rewrites (axes, polar words, centre, radius).
const MOTION_LETTERS: [u8; 9] = [b'X', b'Y', b'Z', b'@', b'^', b'I', b'J', b'K', b'R'];
/// Axis letters by axis index.
const AXES: [u8; 3] = [b'X', b'Y', b'Z'];
/// Centre letters by axis index.
const CENTRES: [u8; 3] = [b'I', b'J', b'K'];
/// A coordinate that changes by less than this along a move is not written, program units.
const UNCHANGED: f64 = 1e-9;

fn coord(p: P3, axis: usize) -> f64 {
    [p.x, p.y, p.z][axis]
}

/// The plane's axes (a, b, normal).
fn plane_axes(plane: Plane) -> [usize; 3] {
    match plane {
        Plane::Xy => [0, 1, 2],
        Plane::Zx => [2, 0, 1],
        Plane::Yz => [1, 2, 0],
    }
}

/// The block written as its pieces: the first on the block's own line (every other word
/// kept), the others on lines of their own, joined by `newline`.
#[allow(clippy::too_many_arguments)]
pub(super) fn split_line(
    original: &str,
    words: &LineWords,
    m: &Move,
    ctx: &MotionContext,
    pieces: &[Piece],
    feeds: &[FeedValue],
    style: Style,
    newline: &str,
) -> String {
    let unit = mm_per(ctx.units);
    let prog = |p: P3| {
        let q = ctx.frame.to_program(p);
        P3::new(q.x / unit, q.y / unit, q.z / unit)
    };
    let arc = match m.motion {
        Motion::Arc { center, clockwise, plane, .. } => Some((prog(center), clockwise, plane)),
        _ => None,
    };
    let start = prog(m.start);
    let end = prog(m.end);
    let axes: Vec<usize> = match arc {
        Some((_, _, plane)) => {
            let [a, b, n] = plane_axes(plane);
            let mut axes = vec![a, b];
            if (coord(end, n) - coord(start, n)).abs() > UNCHANGED {
                axes.push(n);
            }
            axes.sort_unstable();
            axes
        }
        None => (0..3).filter(|&a| (coord(end, a) - coord(start, a)).abs() > UNCHANGED).collect(),
    };
    let sep = style.separator();
    let mut lines: Vec<String> = Vec::with_capacity(pieces.len());
    // Written positions so far (absolute, program units), per axis.
    let mut written = [style.length(start.x), style.length(start.y), style.length(start.z)];
    let mut piece_start = start;
    for (k, (piece, feed)) in pieces.iter().zip(feeds).enumerate() {
        let last = k + 1 == pieces.len();
        let sub = sub_move(m, piece.t0, piece.t1);
        let target = prog(sub.end);
        let mut parts: Vec<String> = Vec::new();
        let mut next = written;
        for &axis in &axes {
            let letter = AXES[axis];
            let own = words.get(letter).filter(|w| last && w.value.is_finite());
            let absolute_value = match own {
                Some(w) if ctx.absolute => Fixed::round(w.value, style.decimals),
                Some(w) => {
                    let total = Fixed::round(w.value, style.decimals);
                    let before = style.length(coord(start, axis));
                    Fixed { units: before.units + total.units, decimals: total.decimals }
                }
                None => style.length(coord(target, axis)),
            };
            next[axis] = absolute_value;
            let value = if ctx.absolute {
                absolute_value
            } else {
                Fixed { units: absolute_value.units - written[axis].units, decimals: absolute_value.decimals }
            };
            let mut s = String::new();
            match own {
                Some(w) if ctx.absolute => s.push_str(&original[w.start as usize..w.end as usize]),
                _ => style.word(&mut s, char::from(letter), value),
            }
            parts.push(s);
        }
        if let Some((centre, clockwise, plane)) = arc {
            parts.extend(centre_words(ctx, centre, clockwise, plane, piece_start, &sub, style));
        }
        parts.push(feed_word(b'F', *feed, style));
        written = next;
        piece_start = P3::new(written[0].value(), written[1].value(), written[2].value());
        lines.push(parts.join(sep));
    }
    let first = first_piece(original, words, ctx, &lines[0], style);
    let motion = motion_word(original, words, m);
    let prefix = if words.block_delete { "/" } else { "" };
    let mut out = first;
    for rest in &lines[1..] {
        out.push_str(newline);
        out.push_str(prefix);
        out.push_str(&motion);
        out.push_str(sep);
        out.push_str(rest);
    }
    out
}

/// The centre words of one piece of an arc, in the block's format.
fn centre_words(
    ctx: &MotionContext,
    centre: P3,
    clockwise: bool,
    plane: Plane,
    start: P3,
    sub: &Move,
    style: Style,
) -> Vec<String> {
    let [a, b, _] = plane_axes(plane);
    let mut out = Vec::new();
    let Motion::Arc { turns, .. } = sub.motion else { return out };
    match ctx.arc {
        Some(ArcFormat::Radius) => {
            let r = (coord(start, a) - coord(centre, a)).hypot(coord(start, b) - coord(centre, b));
            let in_plane = |p: P3| (coord(p, a), coord(p, b), 0.0);
            let c = match sub.motion {
                Motion::Arc { center, .. } => center,
                _ => sub.start,
            };
            let sweep = arc_sweep(in_plane(sub.start), in_plane(sub.end), in_plane(c), clockwise, 0);
            let signed = if sweep.abs() > std::f64::consts::PI { -r } else { r };
            let mut s = String::new();
            style.word(&mut s, 'R', style.length(signed));
            out.push(s);
        }
        _ => {
            for axis in [a, b] {
                let v =
                    if ctx.absolute_centres { coord(centre, axis) } else { coord(centre, axis) - coord(start, axis) };
                let mut s = String::new();
                style.word(&mut s, char::from(CENTRES[axis]), style.length(v));
                out.push(s);
            }
        }
    }
    if turns > 0 {
        out.push(format!("P{}", turns + 1));
    }
    out
}

/// The block's own line with its motion words and F replaced by the first piece's.
fn first_piece(original: &str, words: &LineWords, ctx: &MotionContext, new_words: &str, style: Style) -> String {
    let removable =
        |letter: u8| MOTION_LETTERS.contains(&letter) || letter == b'F' || (letter == b'P' && ctx.turns_word);
    let mut spans: Vec<(usize, usize)> =
        words.words.iter().filter(|w| removable(w.letter)).map(|w| (w.start as usize, w.end as usize)).collect();
    spans.sort_unstable();
    let bytes = original.as_bytes();
    let mut out = String::with_capacity(original.len() + new_words.len());
    let mut at = 0;
    let mut inserted = false;
    for (s, e) in spans {
        out.push_str(&original[at..s]);
        if !inserted {
            out.push_str(new_words);
            inserted = true;
            at = e;
        } else {
            // Drop the word and the blanks after it.
            let mut e = e;
            while e < bytes.len() && matches!(bytes[e], b' ' | b'\t') {
                e += 1;
            }
            at = e;
            if out.ends_with([' ', '\t']) && e >= bytes.len() {
                while out.ends_with([' ', '\t']) {
                    out.pop();
                }
            }
        }
    }
    if !inserted {
        let at_end = words.insert_at() as usize;
        out.push_str(&original[..at_end]);
        out.push_str(style.separator());
        out.push_str(new_words);
        out.push_str(&original[at_end..]);
        return out;
    }
    out.push_str(&original[at..]);
    out
}

/// The motion word of the pieces after the first: the block's own G word, or G1/G2/G3.
fn motion_word(original: &str, words: &LineWords, m: &Move) -> String {
    const MOTION_CODES: [u32; 3] = [10, 20, 30];
    let own = words.words.iter().find(|w| {
        w.letter == b'G' && crate::core::nc::words::code_of(w.value).is_some_and(|c| MOTION_CODES.contains(&c))
    });
    match own {
        Some(w) => original[w.start as usize..w.end as usize].to_string(),
        None => match m.motion {
            Motion::Arc { clockwise: true, .. } => "G2".to_string(),
            Motion::Arc { clockwise: false, .. } => "G3".to_string(),
            _ => "G1".to_string(),
        },
    }
}
