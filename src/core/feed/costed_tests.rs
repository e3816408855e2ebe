//! min_cost's promise on whole programs: the costing's cost after is never above the cost
//! before, whatever the cut and the programmed feed.

use super::blocks::BlockOptions;
use super::costed::optimize_costed;
use super::objective::{Objective, ObjectiveSpec};
use super::plan::{FeedSpec, DEFAULT_MAX_FEED_CHANGE_PER_MM};
use super::rule::{FeedRule, FeedStrategy};
use crate::core::analysis::{AnalysisSpec, StockRegion, DEFAULT_ALPHA_LIMIT_DEG};
use crate::core::costing::cost::Rates;
use crate::core::costing::estimate::CostModel;
use crate::core::fixtures::{seed_001_ten_mm, ten_mm_life};
use crate::core::kinematics::MachineLimits;
use crate::core::progress::NoProgress;
use crate::core::stock::Rect;
use crate::core::tool::{EndMill, ToolType};
use crate::core::toolpath::{Motion, Move, Plane, Toolpath, Units, P3};
use proptest::prelude::*;

fn analysis() -> AnalysisSpec {
    AnalysisSpec {
        tool: EndMill { tool_type: ToolType::Square, diameter_mm: 10.0, flutes: 6, corner_radius_mm: 0.0 },
        stock: vec![StockRegion::Rect(Rect { x_min: 0.0, y_min: 0.0, x_max: 60.0, y_max: 40.0 })],
        open: vec![],
        z_top: 0.0,
        z_bottom: -10.0,
        force_model: Some(seed_001_ten_mm()),
        default_spindle_rpm: Some(9600.0),
        rapid_mm_min: 20000.0,
        sample_spacing_mm: Some(0.1),
        cell_mm: None,
        alpha_limit_deg: DEFAULT_ALPHA_LIMIT_DEG,
        series_points: 0,
        stock_memory_bytes: crate::core::analysis::DEFAULT_STOCK_MEMORY_BYTES,
    }
}

fn spec() -> FeedSpec {
    FeedSpec {
        rule: FeedRule {
            strategy: FeedStrategy::ConstantForce,
            force_model: Some(seed_001_ten_mm()),
            target_force_n: 269.1,
            flutes: 6,
            min_feed_mm_min: 288.0,
            max_feed_mm_min: 11520.0,
            air_feed_mm_min: 11520.0,
        },
        max_change_per_mm: Some(DEFAULT_MAX_FEED_CHANGE_PER_MM),
        blocks: BlockOptions::default(),
        rapid_mm_min: 20000.0,
    }
}

fn min_cost() -> ObjectiveSpec {
    let machine = MachineLimits {
        rapid_mm_min: 20000.0,
        max_feed_mm_min: 15000.0,
        accel_mm_s2: [2000.0, 2000.0, 1500.0],
        jerk_mm_s3: [50000.0, 50000.0, 40000.0],
        tool_change_s: 8.0,
    };
    let rates = Rates { machine_rate_per_hour: 60.0, tool_price: 90.0, currency: "USD".into() };
    ObjectiveSpec {
        objective: Objective::MinCost,
        max_force_n: 269.1,
        cost: Some(CostModel { life: ten_mm_life(), machine, rates }),
    }
}

/// Along the block's lower edge at radial depth `rd` (a full slot from 10 mm) and depth
/// `ad`, at `feed`, then a quarter circle of radius `turn` into the block.
fn program(rd: f64, ad: f64, feed: f64, turn: f64) -> Toolpath {
    let y = 5.0 - rd;
    let mv = |motion, start, end, line| Move {
        motion,
        start,
        end,
        feed_mm_min: Some(feed),
        spindle_rpm: Some(9600.0),
        tool: None,
        line,
    };
    let (a, b) = (P3::new(-10.0, y, -ad), P3::new(40.0, y, -ad));
    let arc = Motion::Arc { center: P3::new(40.0, y + turn, -ad), clockwise: false, plane: Plane::Xy, turns: 0 };
    let moves = vec![mv(Motion::Linear, a, b, 1), mv(arc, b, P3::new(40.0 + turn, y + turn, -ad), 2)];
    Toolpath { moves, events: vec![], source_units: Units::Mm, warnings: vec![] }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(12))]

    #[test]
    fn min_cost_never_returns_a_program_that_costs_more_than_the_input(
        rd in 0.2f64..12.0,
        ad in 1.0f64..10.0,
        feed in 300.0f64..12_000.0,
        turn in 0.3f64..20.0,
    ) {
        let optimised =
            optimize_costed(&program(rd, ad, feed, turn), &analysis(), None, &spec(), min_cost(), &NoProgress)
                .expect("optimises");
        let c = optimised.costed.expect("costed");
        prop_assert!(c.after.cost.total <= c.before.cost.total, "{} → {}", c.before.cost.total, c.after.cost.total);
    }
}

/// Passes across a 100 × 40 block 20 mm deep along y = `y`, one at each of `levels`, at
/// the standard feed (5760 mm/min).
fn passes(y: f64, levels: &[f64]) -> Toolpath {
    let feed = |start, end, line| Move {
        motion: Motion::Linear,
        start,
        end,
        feed_mm_min: Some(5760.0),
        spindle_rpm: Some(9600.0),
        tool: None,
        line,
    };
    let mut moves = Vec::new();
    for (k, &z) in levels.iter().enumerate() {
        let line = 3 * k as u32 + 1;
        moves.push(feed(P3::new(-10.0, y, 5.0), P3::new(-10.0, y, z), line));
        moves.push(feed(P3::new(-10.0, y, z), P3::new(110.0, y, z), line + 1));
        moves.push(Move { motion: Motion::Rapid, ..feed(P3::new(110.0, y, z), P3::new(-10.0, y, 5.0), line + 2) });
    }
    Toolpath { moves, events: vec![], source_units: Units::Mm, warnings: vec![] }
}

#[test]
fn an_intermediate_pass_optimised_on_what_the_roughing_left_engages_less_and_runs_faster_than_on_the_block() {
    let block = Rect { x_min: 0.0, y_min: 0.0, x_max: 100.0, y_max: 40.0 };
    let layer = AnalysisSpec { stock: vec![StockRegion::Rect(block)], z_bottom: -20.0, ..analysis() };
    let constant_force = ObjectiveSpec { objective: Objective::ConstantForce, ..min_cost() };
    // Roughing at Ad 10: a slot from y = 15 to 25, then 1 mm into its wall at Ad 2.5.
    let roughing = passes(20.0, &[-10.0, -20.0]);
    let (_, roughed) =
        crate::core::analysis::analyze_from(&roughing, &layer, None, &NoProgress, |_| {}).expect("roughs");
    let kept = roughed.keep(false);
    let levels: Vec<f64> = (1..=8).map(|i| -2.5 * f64::from(i)).collect();
    let pass = passes(21.0, &levels);
    let optimise = |start| optimize_costed(&pass, &layer, start, &spec(), constant_force.clone(), &NoProgress);
    let carried = optimise(Some(&kept)).expect("optimises on the kept stock");
    let fresh = optimise(None).expect("optimises on the block");
    let alpha = |o: &super::costed::Optimised| o.plan.analysis.as_ref().expect("side milling").summary.alpha_deg.max;
    // 1 mm of a 10 mm tool: acos(0.8) = 36.87°; on the block, a full slot.
    assert!((alpha(&carried) - 36.87).abs() < 2.0 && alpha(&fresh) > 170.0, "{} {}", alpha(&carried), alpha(&fresh));
    let feed = |o: &super::costed::Optimised| o.plan.after.feed_mm_min.mean;
    assert!(feed(&carried) > 1.5 * feed(&fresh), "{} against {}", feed(&carried), feed(&fresh));
    let time = |o: &super::costed::Optimised| o.costed.as_ref().expect("costed").after.time.kinematic_min;
    assert!(time(&carried) < time(&fresh), "{} against {}", time(&carried), time(&fresh));
    // The stock it hands back is the one the pass leaves: 40 × 100 × 20 less 11 × 100 × 20.
    let left = crate::core::analysis::rest::remaining_volume_mm3(&carried.stock);
    assert!((left - 58_000.0).abs() < 300.0, "{left}");
}
