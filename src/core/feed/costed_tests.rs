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
        let (_, costed) = optimize_costed(&program(rd, ad, feed, turn), &analysis(), &spec(), min_cost(), &NoProgress)
            .expect("optimises");
        let c = costed.expect("costed");
        prop_assert!(c.after.cost.total <= c.before.cost.total, "{} → {}", c.before.cost.total, c.after.cost.total);
    }
}
