//! A synthetic path to draw, shared by the drawing benchmark and the tests that check a
//! large scene stays small: about 53 m of contour-parallel loops with corner arcs, and an
//! engagement per sample that waves slowly and peaks above the 40° limit like corners do.

use crate::core::toolpath::{Motion, Move, Plane, Toolpath, Units, P3};

/// Distance between the loops, mm.
const STEP_MM: f64 = 0.5;
/// Radius of the loops' corner arcs, mm.
const CORNER_MM: f64 = 3.0;
/// Half the height of the outermost loop, mm; loops stop below [`INNERMOST_MM`].
const OUTERMOST_MM: f64 = 70.0;
const INNERMOST_MM: f64 = 2.0;
/// The loops are this much longer than high on each side, mm.
const LONGER_MM: f64 = 25.0;
/// Centre of the loops and the cutting level, mm.
const CENTRE: (f64, f64) = (100.0, 75.0);
const Z_MM: f64 = -2.0;
const SAFE_Z_MM: f64 = 5.0;
const FEED_MM_MIN: f64 = 2000.0;

/// Rectangular loops, outermost first, joined by short feed moves; one rapid down first.
pub fn long_loops() -> Toolpath {
    let mut moves = Vec::new();
    let mut at = P3::new(CENTRE.0, CENTRE.1, SAFE_Z_MM);
    let mut push = |motion: Motion, to: P3, moves: &mut Vec<Move>| {
        let line = u32::try_from(moves.len() + 1).unwrap_or(u32::MAX);
        moves.push(Move {
            motion,
            start: at,
            end: to,
            feed_mm_min: Some(FEED_MM_MIN),
            spindle_rpm: None,
            tool: None,
            line,
        });
        at = to;
    };
    let mut o = OUTERMOST_MM;
    while o > INNERMOST_MM {
        let (x0, y0, x1, y1) = (CENTRE.0 - o - LONGER_MM, CENTRE.1 - o, CENTRE.0 + o + LONGER_MM, CENTRE.1 + o);
        let c = CORNER_MM.min(o / 2.0);
        let start = P3::new(x0 + c, y0, Z_MM);
        if moves.is_empty() {
            push(Motion::Rapid, P3::new(start.x, start.y, SAFE_Z_MM), &mut moves);
        }
        push(Motion::Linear, start, &mut moves);
        let corners = [(x1, y0, -1.0, 1.0), (x1, y1, -1.0, -1.0), (x0, y1, 1.0, -1.0), (x0, y0, 1.0, 1.0)];
        let mut dir = (1.0, 0.0);
        for (cx, cy, sx, sy) in corners {
            push(Motion::Linear, P3::new(cx - dir.0 * c, cy - dir.1 * c, Z_MM), &mut moves);
            let center = P3::new(cx + sx * c, cy + sy * c, Z_MM);
            let next = (-dir.1, dir.0);
            let after = P3::new(cx + next.0 * c, cy + next.1 * c, Z_MM);
            push(Motion::Arc { center, clockwise: false, plane: Plane::Xy, turns: 0 }, after, &mut moves);
            dir = next;
        }
        o -= STEP_MM;
    }
    Toolpath { moves, events: vec![], source_units: Units::Mm, warnings: vec![] }
}

/// Engagement at path distance `s_mm`, deg: a slow wave about 18° plus sharp peaks to
/// about 96° every 46 mm.
pub fn alpha_at(s_mm: f64) -> f64 {
    let corner = ((s_mm / 7.3).sin() * 0.5 + 0.5).powi(40);
    18.0 + 8.0 * (s_mm / 95.0).sin() + 70.0 * corner
}

/// Samples every `spacing_mm` over `total_mm` of path, with [`alpha_at`].
pub fn alpha_samples(total_mm: f64, spacing_mm: f64) -> (Vec<f64>, Vec<Option<f64>>) {
    let n = (total_mm / spacing_mm) as usize;
    let s: Vec<f64> = (1..=n).map(|i| i as f64 * spacing_mm).collect();
    let alpha = s.iter().map(|&s| Some(alpha_at(s))).collect();
    (s, alpha)
}
