//! The analysis as a whole: how its progress moves while the stock is painted, and what it
//! warns of where a ball or radius end mill's corner cuts.

use super::*;
use crate::core::progress::NoProgress;
use crate::core::toolpath::{Move, Units, P3};
use std::sync::Mutex;

/// Keeps every fraction reported.
#[derive(Default)]
struct Recorded(Mutex<Vec<f64>>);

impl Progress for Recorded {
    fn report(&self, fraction: f64) {
        self.0.lock().expect("not poisoned").push(fraction);
    }
    fn cancelled(&self) -> bool {
        false
    }
}

/// `tool` in `block`, 5 mm deep, without a force model or a spindle speed.
fn block_spec(tool: EndMill, block: Rect) -> AnalysisSpec {
    AnalysisSpec::new(tool, vec![StockRegion::Rect(block)], 0.0, -5.0)
}

/// One feed move from `start` to `end` at F1000, S9600.
fn straight(start: P3, end: P3) -> Toolpath {
    let line = Move {
        motion: Motion::Linear,
        start,
        end,
        feed_mm_min: Some(1000.0),
        spindle_rpm: Some(9600.0),
        tool: None,
        line: 1,
    };
    Toolpath { moves: vec![line], events: vec![], source_units: Units::Mm, warnings: vec![] }
}

#[test]
fn painting_a_large_stock_moves_the_progress_before_the_simulation_does() {
    // A 200 mm square block (4 M cells of 0.1 mm) and 10 mm of path (200 samples):
    // painting is nearly all of the work.
    let block = Rect { x_min: 0.0, y_min: 0.0, x_max: 200.0, y_max: 200.0 };
    let tool = EndMill { tool_type: ToolType::Square, diameter_mm: 10.0, flutes: 6, corner_radius_mm: 0.0 };
    let path = straight(P3::new(0.0, 100.0, -1.0), P3::new(10.0, 100.0, -1.0));
    let spec = block_spec(tool, block);
    let recorded = Recorded::default();
    analyze(&path, &spec, &recorded).expect("analyses");
    let reports = recorded.0.into_inner().expect("not poisoned");
    assert!(reports.windows(2).all(|w| w[0] <= w[1]), "the progress went back");
    let while_painting = reports.iter().filter(|&&f| f < 0.99).count();
    assert!(while_painting > 1000, "{while_painting} reports while painting");
    assert!(reports.last().is_some_and(|&f| (f - 1.0).abs() < 1e-12));
}

#[test]
fn ball_and_radius_end_mills_are_told_that_the_force_where_their_corner_cuts_is_extrapolated() {
    let block = Rect { x_min: 0.0, y_min: 0.0, x_max: 30.0, y_max: 30.0 };
    let path = straight(P3::new(-10.0, 15.0, -1.0), P3::new(40.0, 15.0, -1.0));
    let warned = |tool_type: ToolType, corner_radius_mm: f64| {
        let spec = AnalysisSpec {
            force_model: Some(crate::core::fixtures::seed_001_ten_mm()),
            ..block_spec(EndMill { tool_type, diameter_mm: 10.0, flutes: 2, corner_radius_mm }, block)
        };
        let mut extrapolated = false;
        let a = analyze_with(&path, &spec, &NoProgress, |r| extrapolated |= r.force_extrapolated).expect("analyses");
        (a.summary.warnings.into_iter().find(|w| w.contains("extrapolated from the flat end mill")), extrapolated)
    };
    assert!(warned(ToolType::Square, 0.0).0.is_none());
    let (ball, ball_samples) = warned(ToolType::Ball, 5.0);
    assert!(ball.is_some_and(|w| w.starts_with("ball end mill")) && ball_samples);
    let (bull, bull_samples) = warned(ToolType::Radius, 1.0);
    assert!(bull.is_some_and(|w| w.contains("corner radius 1 mm")) && bull_samples);
}
