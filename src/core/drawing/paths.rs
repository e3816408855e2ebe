//! A tool path into the scene: its values per sample (from an analysis) and per move
//! (programmed or optimised feed, wear), traced and simplified for drawing.

use super::scene::{LayerInfo, Quantity, ScenePath};
use super::trace::{trace_path, TraceOptions, TraceValues};
use crate::core::analysis::samples::PathSamples;
use crate::core::feed::edit::LineChange;
use crate::core::toolpath::move_length;
use crate::core::toolpath::{Motion, Toolpath};

/// Millimetres per metre.
const MM_PER_M: f64 = 1000.0;

/// The programmed feed of every move (`None` for rapids).
pub fn move_feeds(path: &Toolpath) -> Vec<Option<f64>> {
    path.moves.iter().map(|m| if matches!(m.motion, Motion::Rapid) { None } else { m.feed_mm_min }).collect()
}

/// `path` with each move's line replaced by the line of the written program that ends it
/// (`move_lines`, one per move, 1-based; a move without one keeps its line), so that a
/// drawing of it names the lines of the program that is served.
pub fn with_lines(path: &Toolpath, move_lines: &[u32]) -> Toolpath {
    let mut path = path.clone();
    for (m, &line) in path.moves.iter_mut().zip(move_lines) {
        m.line = line;
    }
    path
}

/// Per move of `path` (the moves of a program whose text was edited, each carrying its
/// line of the text sent), the line of the edited text that ends it: a block split into
/// several (a changed line whose `after` holds several lines) pushes the lines after it
/// down, and its k-th piece is on its k-th line.
pub fn edited_move_lines(path: &Toolpath, changes: &[LineChange]) -> Vec<u32> {
    // Each split line with the lines added up to and including it.
    let mut added = 0u32;
    let grown: Vec<(u32, u32, u32)> = changes
        .iter()
        .filter_map(|c| {
            let lines = u32::try_from(c.after.split('\n').count()).unwrap_or(u32::MAX);
            (lines > 1).then(|| {
                added = added.saturating_add(lines - 1);
                (c.line, lines, added)
            })
        })
        .collect();
    let mut previous = (0u32, 0u32);
    path.moves
        .iter()
        .map(|m| {
            let before = grown.partition_point(|g| g.0 < m.line);
            let shift = before.checked_sub(1).map_or(0, |i| grown[i].2);
            let piece = if previous.0 == m.line { previous.1 + 1 } else { 0 };
            previous = (m.line, piece);
            let pieces = grown.get(before).filter(|g| g.0 == m.line).map_or(1, |g| g.1);
            m.line.saturating_add(shift).saturating_add(piece.min(pieces - 1))
        })
        .collect()
}

/// Tool-life consumption per metre of every move, % of one tool per m, from each
/// move's share of one tool's life.
pub fn wear_rates(path: &Toolpath, consumption: &[f64]) -> Vec<Option<f64>> {
    path.moves
        .iter()
        .enumerate()
        .map(|(i, m)| {
            let length_m = move_length(m) / MM_PER_M;
            let share = consumption.get(i).copied()?;
            (length_m > 0.0 && !matches!(m.motion, Motion::Rapid)).then(|| 100.0 * share / length_m)
        })
        .collect()
}

/// `path` traced under `name`, coloured by the quantities `samples` carry (α, force,
/// feed) and by `per_move` ones (which replace sampled ones of the same quantity).
pub fn traced(
    name: &str,
    path: &Toolpath,
    samples: Option<&PathSamples>,
    per_move: Vec<(Quantity, Vec<Option<f64>>)>,
    layers: &[LayerInfo],
) -> ScenePath {
    let mut values = TraceValues::new();
    if let Some(s) = samples {
        for (q, v) in [(Quantity::Alpha, &s.alpha_deg), (Quantity::Force, &s.force_n), (Quantity::Feed, &s.feed_mm_min)]
        {
            if v.iter().any(Option::is_some) {
                values = values.per_sample(q, &s.s_mm, v);
            }
        }
    }
    for (q, v) in &per_move {
        if v.iter().any(Option::is_some) {
            values = values.per_move(*q, v);
        }
    }
    trace_path(name, path, &values, layers, &TraceOptions::default())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::core::toolpath::{Move, Units, P3};

    fn line(x0: f64, x1: f64, motion: Motion) -> Move {
        Move {
            motion,
            start: P3::new(x0, 0.0, -1.0),
            end: P3::new(x1, 0.0, -1.0),
            feed_mm_min: Some(1000.0),
            spindle_rpm: Some(9600.0),
            tool: None,
            line: 1,
        }
    }

    #[test]
    fn moves_of_an_edited_program_name_its_lines_after_the_blocks_split_before_them() {
        let mut moves = vec![line(0.0, 1.0, Motion::Linear); 5];
        for (m, l) in moves.iter_mut().zip([2, 3, 3, 3, 5]) {
            m.line = l;
        }
        let path = Toolpath { moves, events: Vec::new(), source_units: Units::Mm, warnings: Vec::new() };
        let change = |line: u32, after: &str| LineChange { line, before: String::new(), after: after.into() };
        // Line 3 split in three pieces (two lines added), line 2 only got an F word.
        let changes = [change(2, "G1 X1 F900"), change(3, "G1 X1 F800\nG1 X2 F700\nG1 X3 F600")];
        assert_eq!(edited_move_lines(&path, &changes), [2, 3, 4, 5, 7]);
    }

    #[test]
    fn wear_per_metre_is_the_moves_share_over_its_length_and_rapids_have_none() {
        let path = Toolpath {
            moves: vec![line(0.0, 500.0, Motion::Linear), line(500.0, 600.0, Motion::Rapid)],
            events: Vec::new(),
            source_units: Units::Mm,
            warnings: Vec::new(),
        };
        let rates = wear_rates(&path, &[0.01, 0.0]);
        assert!((rates[0].unwrap() - 2.0).abs() < 1e-12, "1 % over half a metre is 2 %/m");
        assert_eq!(rates[1], None);
        assert_eq!(move_feeds(&path), vec![Some(1000.0), None]);
    }
}
