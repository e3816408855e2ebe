//! Straight runs of a path in XY: consecutive linear moves that continue one another
//! along the same line (a raster-scan relief program is mostly made of them). The probe
//! remembers what it found along a run (see [`super::scan_memory`]).

use crate::core::toolpath::{Motion, Move, Toolpath};

/// Two headings closer than this (1 − cos of the angle between them) are the same.
const SAME_HEADING: f64 = 1e-12;
/// A move starting this close to the line of the previous one continues it, mm.
const ON_LINE_MM: f64 = 1e-9;
/// Moves shorter than this in XY have no heading, mm.
const MIN_XY_MM: f64 = 1e-9;

/// The straight run a move belongs to: its number and where it ends in XY.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Run {
    pub id: usize,
    pub end: (f64, f64),
}

/// An XY point or vector, mm.
type Point = (f64, f64);

/// The run of every move (None for arcs and moves without XY motion).
pub fn straight_runs(path: &Toolpath) -> Vec<Option<Run>> {
    let mut runs: Vec<Option<Run>> = Vec::with_capacity(path.moves.len());
    // The run being extended: its number, where its last move ends, its heading.
    let mut current: Option<(usize, Point, Point)> = None;
    let mut next_id = 0;
    for m in &path.moves {
        let Some(dir) = heading(m) else {
            runs.push(None);
            current = None;
            continue;
        };
        let continues = current.is_some_and(|(_, last_end, last_dir)| {
            let aligned = 1.0 - (dir.0 * last_dir.0 + dir.1 * last_dir.1) < SAME_HEADING;
            let (dx, dy) = (m.start.x - last_end.0, m.start.y - last_end.1);
            aligned && (dx * dir.1 - dy * dir.0).abs() < ON_LINE_MM
        });
        let id = match (continues, current) {
            (true, Some((id, _, _))) => id,
            _ => {
                next_id += 1;
                next_id - 1
            }
        };
        current = Some((id, (m.end.x, m.end.y), dir));
        runs.push(Some(Run { id, end: (m.end.x, m.end.y) }));
    }
    // Every move of a run ends where the run ends.
    let mut end_of_run: Option<Run> = None;
    for run in runs.iter_mut().rev().flatten() {
        match end_of_run {
            Some(last) if last.id == run.id => run.end = last.end,
            _ => end_of_run = Some(*run),
        }
    }
    runs
}

/// The unit XY heading of a linear move, if it moves in XY.
fn heading(m: &Move) -> Option<(f64, f64)> {
    if !matches!(m.motion, Motion::Linear | Motion::Rapid) {
        return None;
    }
    let (dx, dy) = (m.end.x - m.start.x, m.end.y - m.start.y);
    let len = dx.hypot(dy);
    (len > MIN_XY_MM).then(|| (dx / len, dy / len))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::core::toolpath::{Units, P3};

    fn line(points: &[(f64, f64, f64)]) -> Toolpath {
        let moves = points
            .windows(2)
            .map(|w| Move {
                motion: Motion::Linear,
                start: P3::new(w[0].0, w[0].1, w[0].2),
                end: P3::new(w[1].0, w[1].1, w[1].2),
                feed_mm_min: Some(100.0),
                spindle_rpm: None,
                tool: None,
                line: 1,
            })
            .collect();
        Toolpath { moves, events: vec![], source_units: Units::Mm, warnings: vec![] }
    }

    #[test]
    fn collinear_moves_at_any_depth_form_one_run_until_the_path_turns() {
        let path = line(&[(0.0, 0.0, 0.0), (1.0, 0.0, -1.0), (2.0, 0.0, -3.0), (2.0, 1.0, -3.0), (2.0, 2.0, -3.0)]);
        let runs = straight_runs(&path);
        let ids: Vec<usize> = runs.iter().map(|r| r.expect("straight").id).collect();
        assert_eq!(ids, vec![0, 0, 1, 1]);
        let ends: Vec<(f64, f64)> = runs.iter().map(|r| r.expect("straight").end).collect();
        assert!((ends[0].0 - 2.0).abs() < 1e-12 && (ends[3].1 - 2.0).abs() < 1e-12);
    }

    #[test]
    fn a_parallel_move_on_another_line_starts_a_new_run() {
        let path = line(&[(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (1.0, 0.5, 0.0), (2.0, 0.5, 0.0)]);
        let runs = straight_runs(&path);
        assert_ne!(runs[0].expect("straight").id, runs[2].expect("straight").id);
    }
}
