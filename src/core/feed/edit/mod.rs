//! The user's program, edited: only its F words change, and a block whose feed must
//! change inside it is split into consecutive blocks of the same kind. Everything else of
//! the text stays byte for byte: units, N numbers, comments, offsets, coolant and spindle
//! words, `%` and `O` lines, line ends.
//!
//! - F words are written in the program's units and feed mode (mm or inch per minute,
//!   per revolution under G95, the inverse of the block's minutes under G93), rounded
//!   down (never faster than planned) and spelled as the program spells numbers.
//! - A block run once, whose one move was spelled by its own words, is split where its
//!   feed changes: lines into lines, arcs into arcs in the program's own format (`R` or
//!   `I/J/K`, absolute or incremental), in the program's units. The first piece keeps the
//!   line (its N number, comments and other words); the others follow on lines of their
//!   own.
//! - A block run several times (in a loop or a subprogram), a canned cycle, a block under
//!   cutter compensation or a retract gets one feed: the lowest any of its moves needs.
//! - F is modal: a block that needs a feed the control would not have in effect there
//!   (after edits before it, in the order the program runs) gets its own F word.
//!
//! The result lists every changed line (`line`, `before`, `after`).

mod modal;
mod split;

#[cfg(test)]
mod tests;

use std::collections::HashMap;

use serde::Serialize;

use super::blocks::Piece;
use crate::core::nc::words::{feed_down, Fixed, LineWords, Style, MIN_DECIMALS_INCH, MIN_DECIMALS_MM};
use crate::core::nc::{FeedMode, LineMotion, MotionContext, ProgramMap};
use crate::core::toolpath::move_length;
use crate::core::toolpath::{Motion, Toolpath, Units};

/// The program as the interpreter read it.
#[derive(Clone, Copy)]
pub(crate) struct Program<'a> {
    pub path: &'a Toolpath,
    pub map: &'a ProgramMap,
}

/// One changed line of the program.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, utoipa::ToSchema)]
pub struct LineChange {
    /// 1-based line of the input program.
    pub line: u32,
    /// The line as it was.
    pub before: String,
    /// The line as it is now (several lines where it was split).
    pub after: String,
}

/// The edited program: only its F words changed, blocks split where the feed changes
/// inside them.
#[derive(Debug, Clone, PartialEq, Default, Serialize, utoipa::ToSchema)]
pub struct Edited {
    /// The program itself (served as the job's program, not in its report).
    #[serde(skip)]
    pub text: String,
    /// Every changed line, in order: its 1-based number in the input, the line as it was
    /// and as it is now (several lines where the block was split).
    #[serde(rename = "changed_lines")]
    pub changes: Vec<LineChange>,
    /// Blocks split into several.
    pub split_blocks: u32,
    /// Reported with the warnings of the job.
    #[serde(skip)]
    pub warnings: Vec<String>,
}

/// M codes that act after a block's motion (M0, M1, M2, M30, M60): a block with one is
/// not split, or the stop would come after its first piece.
const STOP_CODES: [u32; 5] = [0, 10, 20, 300, 600];

/// Decimals of F words: per minute (mm, inch), per revolution (mm, inch), inverse time.
const FEED_DECIMALS_MM_MIN: u32 = 1;
const FEED_DECIMALS_INCH_MIN: u32 = 2;
const FEED_DECIMALS_MM_REV: u32 = 4;
const FEED_DECIMALS_INCH_REV: u32 = 5;
const FEED_DECIMALS_INVERSE: u32 = 4;

/// A feed word's value: its mode, the units it is in, and the value as written.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct FeedValue {
    pub mode: FeedMode,
    pub units: Units,
    pub value: Fixed,
}

/// What a line's feed becomes.
#[derive(Debug, Clone)]
pub(crate) enum Plan {
    /// One feed for the whole line.
    One(FeedValue),
    /// The line's one move, split into pieces, each with its feed.
    Split { move_index: usize, pieces: Vec<Piece>, feeds: Vec<FeedValue>, ctx: MotionContext },
}

impl Plan {
    /// The F in effect when the line's first move starts.
    pub fn first(&self) -> FeedValue {
        match self {
            Plan::One(f) => *f,
            Plan::Split { feeds, .. } => feeds[0],
        }
    }

    /// The F in effect after the line.
    pub fn last(&self) -> FeedValue {
        match self {
            Plan::One(f) => *f,
            Plan::Split { feeds, .. } => *feeds.last().expect("a split has pieces"),
        }
    }
}

/// mm per unit.
fn mm_per(units: Units) -> f64 {
    match units {
        Units::Mm => 1.0,
        Units::Inch => crate::core::nc::MM_PER_INCH,
    }
}

/// The F word that runs a move of `length_mm` at `feed_mm_min` in the line's feed mode
/// (`None` under G95 without a spindle speed).
pub(crate) fn feed_value(feed_mm_min: f64, length_mm: f64, ctx: &MotionContext) -> Option<FeedValue> {
    let unit = mm_per(ctx.units);
    let inch = ctx.units == Units::Inch;
    let (value, decimals) = match ctx.feed_mode {
        FeedMode::PerMinute => (feed_mm_min / unit, if inch { FEED_DECIMALS_INCH_MIN } else { FEED_DECIMALS_MM_MIN }),
        FeedMode::PerRevolution => {
            let rpm = ctx.spindle_rpm.filter(|s| *s > 0.0)?;
            (feed_mm_min / rpm / unit, if inch { FEED_DECIMALS_INCH_REV } else { FEED_DECIMALS_MM_REV })
        }
        FeedMode::InverseTime => {
            if length_mm <= 0.0 {
                return None;
            }
            (feed_mm_min / length_mm, FEED_DECIMALS_INVERSE)
        }
    };
    let mut fixed = feed_down(value, decimals);
    if fixed.units <= 0 {
        // The slowest feed the decimals can write.
        fixed = Fixed { units: 1, decimals };
    }
    Some(FeedValue { mode: ctx.feed_mode, units: ctx.units, value: fixed })
}

/// What the plan knows of one line's moves.
struct LineMoves {
    first: usize,
    count: usize,
    length_mm: f64,
    lowest_mm_min: f64,
    pieces_differ: bool,
}

/// Edits `text` (the program the interpreter read into `path`, running as `map` says) so
/// that each move `i` runs at the feeds of `pieces[i]` (pieces of its length, as the feed
/// optimiser cut it; empty for rapids and for moves that keep their feed).
pub fn edit_feeds(text: &str, path: &Toolpath, map: &ProgramMap, pieces: &[Vec<Piece>]) -> Edited {
    let program = Program { path, map };
    let mut warnings = Vec::new();
    let mut by_line: HashMap<u32, LineMoves> = HashMap::new();
    for (i, m) in program.path.moves.iter().enumerate() {
        let Some(ps) = pieces.get(i).filter(|p| !p.is_empty()) else { continue };
        if matches!(m.motion, Motion::Rapid) {
            continue;
        }
        let lowest = ps.iter().map(|p| p.feed_mm_min).fold(f64::INFINITY, f64::min);
        let differ = ps.windows(2).any(|w| (w[0].feed_mm_min - w[1].feed_mm_min).abs() > f64::EPSILON);
        let entry = by_line.entry(m.line).or_insert(LineMoves {
            first: i,
            count: 0,
            length_mm: 0.0,
            lowest_mm_min: f64::INFINITY,
            pieces_differ: false,
        });
        entry.count += 1;
        entry.length_mm += move_length(m);
        entry.lowest_mm_min = entry.lowest_mm_min.min(lowest);
        entry.pieces_differ |= differ;
    }
    let lines = split_lines(text);
    let mut plans: HashMap<u32, Plan> = HashMap::new();
    for (&line, moves) in &by_line {
        let Some(record) = program.map.line(line) else { continue };
        let (ctx, direct) = match record.motion {
            LineMotion::Direct(c) => (c, true),
            LineMotion::Derived(c) => (c, false),
            LineMotion::None => continue,
        };
        let Some(&(start, end, _)) = lines.get(line as usize - 1) else { continue };
        let words = LineWords::read(&text.as_bytes()[start..end]);
        let splittable = direct
            && record.executions == 1
            && moves.count == 1
            && moves.pieces_differ
            && !words.has_m(&STOP_CODES)
            && ctx.frame.rotation_deg.abs() < f64::EPSILON;
        let plan = if splittable {
            let m = &program.path.moves[moves.first];
            let ps = pieces[moves.first].clone();
            let feeds: Option<Vec<FeedValue>> =
                ps.iter().map(|p| feed_value(p.feed_mm_min, move_length(m) * (p.t1 - p.t0), &ctx)).collect();
            feeds.map(|feeds| Plan::Split { move_index: moves.first, pieces: ps, feeds, ctx })
        } else {
            let length = if ctx.feed_mode == FeedMode::InverseTime { moves.length_mm } else { 0.0 };
            feed_value(moves.lowest_mm_min, length, &ctx).map(Plan::One)
        };
        match plan {
            Some(plan) => {
                plans.insert(line, plan);
            }
            None => warnings.push(format!(
                "line {line}: the feed stays as programmed (its feed mode needs what the program does not give)"
            )),
        }
    }
    let inserted = modal::missing_feeds(text, &lines, program, &plans);
    let min_decimals = if program.path.source_units == Units::Inch { MIN_DECIMALS_INCH } else { MIN_DECIMALS_MM };
    let style = Style::of(text, min_decimals);
    write(text, &lines, program, &plans, &inserted, style, warnings)
}

/// The lines of `text`: (start, end without the line end, end with it).
pub(crate) fn split_lines(text: &str) -> Vec<(usize, usize, usize)> {
    let bytes = text.as_bytes();
    let mut out = Vec::with_capacity(bytes.len() / 24 + 1);
    let mut start = 0;
    for (i, &b) in bytes.iter().enumerate() {
        if b == b'\n' {
            let end = if i > start && bytes[i - 1] == b'\r' { i - 1 } else { i };
            out.push((start, end, i + 1));
            start = i + 1;
        }
    }
    out.push((start, bytes.len(), bytes.len()));
    out
}

/// Puts the edited text together.
fn write(
    text: &str,
    lines: &[(usize, usize, usize)],
    program: Program,
    plans: &HashMap<u32, Plan>,
    inserted: &std::collections::HashSet<u32>,
    style: Style,
    warnings: Vec<String>,
) -> Edited {
    let mut out = String::with_capacity(text.len() + text.len() / 16);
    let mut changes = Vec::new();
    let mut split_blocks = 0;
    for (k, &(start, end, full_end)) in lines.iter().enumerate() {
        let number = k as u32 + 1;
        let original = &text[start..end];
        let line_end = &text[end..full_end];
        let Some(plan) = plans.get(&number) else {
            out.push_str(&text[start..full_end]);
            continue;
        };
        let words = LineWords::read(original.as_bytes());
        let newline = if line_end.is_empty() { "\n" } else { line_end };
        let after = match plan {
            Plan::One(f) => set_feed(original, &words, *f, inserted.contains(&number), style),
            Plan::Split { move_index, pieces, feeds, ctx } => {
                split_blocks += 1;
                let m = &program.path.moves[*move_index];
                split::split_line(original, &words, m, ctx, pieces, feeds, style, newline)
            }
        };
        if after != original {
            changes.push(LineChange { line: number, before: original.to_string(), after: after.replace("\r\n", "\n") });
        }
        out.push_str(&after);
        out.push_str(line_end);
    }
    Edited { text: out, changes, split_blocks, warnings }
}

/// Writes an F word's text (keeping the letter's case).
pub(crate) fn feed_word(letter: u8, f: FeedValue, style: Style) -> String {
    let mut s = String::with_capacity(10);
    s.push(char::from(letter));
    f.value.push_to(&mut s, style.point);
    s
}

/// The line with its F word set to `f`: the word replaced, or added after the last word
/// when the line needs its own (`insert`). A word that already says `f` stays as written.
fn set_feed(original: &str, words: &LineWords, f: FeedValue, insert: bool, style: Style) -> String {
    match words.get(b'F') {
        Some(w) => {
            let same = w.value.is_finite() && Fixed::round(w.value, f.value.decimals) == f.value;
            if same {
                return original.to_string();
            }
            let letter = original.as_bytes()[w.start as usize];
            let mut s = String::with_capacity(original.len() + 4);
            s.push_str(&original[..w.start as usize]);
            s.push_str(&feed_word(letter, f, style));
            s.push_str(&original[w.end as usize..]);
            s
        }
        None if insert => {
            let at = words.insert_at() as usize;
            let mut s = String::with_capacity(original.len() + 10);
            s.push_str(&original[..at]);
            s.push_str(style.separator());
            s.push_str(&feed_word(b'F', f, style));
            s.push_str(&original[at..]);
            s
        }
        None => original.to_string(),
    }
}
