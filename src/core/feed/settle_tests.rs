//! The change-rate limit around moves min_cost keeps at their programmed feed.

use super::blocks::BlockOptions;
use super::collect::Kept;
use super::objective::{Objective, ObjectiveSpec};
use super::objective_tests::{model, rule};
use super::plan::FeedSpec;
use super::rule::FeedReason;
use super::settle::{move_ranges, settle};
use crate::core::toolpath::{Motion, Move, P3};

/// Sample spacing of the path below, mm.
const STEP_MM: f64 = 0.5;
/// mm/min per mm of path.
const RATE: f64 = 1000.0;

/// A straight feed move along X from `x0` to `x1` at `feed`, mm/min.
fn line(x0: f64, x1: f64, feed: f64) -> Move {
    let at = |x: f64| P3 { x, y: 0.0, z: -1.0 };
    Move {
        motion: Motion::Linear,
        start: at(x0),
        end: at(x1),
        feed_mm_min: Some(feed),
        spindle_rpm: Some(9600.0),
        tool: None,
        line: 1,
    }
}

/// Samples through air (their cost is the machine time alone) along move `index` of
/// `length_mm`, each needing `needed` mm/min, programmed at `programmed`.
fn samples(index: u32, length_mm: f64, needed: f32, programmed: f32) -> Vec<Kept> {
    let n = (length_mm / STEP_MM).round() as usize;
    (0..n)
        .map(|_| Kept {
            move_index: index,
            step_mm: STEP_MM as f32,
            feed_mm_min: needed,
            reason: Some(FeedReason::Target),
            alpha_rad: 0.0,
            arc_length_mm: 0.0,
            ad_mm: 0.0,
            ratio: 1.0,
            centre_radius_mm: f32::INFINITY,
            spindle_rpm: 9600.0,
            force_before_n: f32::NAN,
            programmed_mm_min: programmed,
        })
        .collect()
}

#[test]
fn a_move_kept_at_its_programmed_feed_is_ramped_to_at_that_feed_not_at_the_new_one() {
    // Two moves programmed at F1500 that may run at F3000, around a short one that would
    // be slowed to F1000, which costs more than its programmed F2000: min_cost keeps it,
    // so the move before it only needs to come down to F2000, not to the F1000 the move
    // never gets.
    let moves = [line(0.0, 20.0, 1500.0), line(20.0, 22.0, 2000.0), line(22.0, 42.0, 1500.0)];
    let kept: Vec<Kept> =
        [samples(0, 20.0, 3000.0, 1500.0), samples(1, 2.0, 1000.0, 2000.0), samples(2, 20.0, 3000.0, 1500.0)].concat();
    let spec = FeedSpec {
        rule: rule(),
        max_change_per_mm: Some(RATE),
        blocks: BlockOptions::default(),
        rapid_mm_min: 20000.0,
    };
    let objective = ObjectiveSpec { objective: Objective::MinCost, max_force_n: 269.1, cost: Some(model()) };
    let ranges = move_ranges(&moves, &kept);
    let settled = settle(&moves, &kept, &ranges, &spec, Some(&objective), 5.0);
    assert_eq!(settled.keeps_programmed, [false, true, false]);
    assert!(settled.all_checked, "the second run keeps no other move");
    let end_of_first = settled.limited[ranges[0].end - 1];
    assert!((end_of_first - 2000.0 - RATE * STEP_MM).abs() < 1e-6, "F{end_of_first}");
    let start_of_last = settled.limited[ranges[2].start];
    assert!((start_of_last - 2000.0 - RATE * STEP_MM).abs() < 1e-6, "F{start_of_last}");
    // The limit lowered 1 mm either side of the kept move (the kept move itself is not counted).
    assert!((settled.rate_limited_mm - 2.0 * (1000.0 / RATE - STEP_MM)).abs() < 1e-6, "{}", settled.rate_limited_mm);

    // Without an objective that keeps moves, the neighbours ramp to the new feed.
    let plain = settle(&moves, &kept, &ranges, &spec, None, 5.0);
    assert_eq!(plain.keeps_programmed, [false, false, false]);
    assert!(!plain.all_checked);
    assert!((plain.limited[ranges[0].end - 1] - 1000.0 - RATE * STEP_MM).abs() < 1e-6);
}
