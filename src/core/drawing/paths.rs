//! A tool path into the scene: its values per sample (from an analysis) and per move
//! (programmed or optimised feed, wear), traced and simplified for drawing.

use super::scene::{LayerInfo, Quantity, ScenePath};
use super::trace::{trace_path, TraceOptions, TraceValues};
use crate::core::analysis::samples::PathSamples;
use crate::core::toolpath::move_length;
use crate::core::toolpath::{Motion, Toolpath};

/// Millimetres per metre.
const MM_PER_M: f64 = 1000.0;

/// The programmed feed of every move (`None` for rapids).
pub fn move_feeds(path: &Toolpath) -> Vec<Option<f64>> {
    path.moves.iter().map(|m| if matches!(m.motion, Motion::Rapid) { None } else { m.feed_mm_min }).collect()
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
