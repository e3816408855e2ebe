//! `cargo bench --bench feeds_cost`: the feeds job's objectives on the real programs of
//! ../shared/data and on a program with full-slot helical entries, with the costing's
//! figures before and after (BENCHMARKS.md, "Feeds: cost before → after"). Prints one
//! line per program and objective.
//!
//! The tools, models, machine and rates are the seeded rows (migrations/0002_seed.sql:
//! seed 001 Table 4's force models, 320 m of life, the γ table and k = 2.4, the OKK VM-4
//! limits, 60 per hour, the tools' prices). tiger.nc's 2.5 mm end mill (tiger.camotics,
//! 2 flutes as benches/analysis.rs takes it) has no rows: its standard cut is assumed by
//! MODEL.md §5's rule for other diameters (Rd 0.05·D, fz 0.01·D at the program's S 2000),
//! 320 m of life, no force model (so the cutting-point rule), and a price of 30.

use dieplan::core::analysis::{AnalysisSpec, StockRegion, DEFAULT_ALPHA_LIMIT_DEG};
use dieplan::core::costing::cost::Rates;
use dieplan::core::costing::estimate::CostModel;
use dieplan::core::engagement::{engagement, Contour};
use dieplan::core::feed::blocks::BlockOptions;
use dieplan::core::feed::costed::optimize_costed;
use dieplan::core::feed::objective::{Objective, ObjectiveSpec};
use dieplan::core::feed::plan::{FeedSpec, DEFAULT_MAX_FEED_CHANGE_PER_MM};
use dieplan::core::feed::rule::{FeedRule, FeedStrategy};
use dieplan::core::force_model::{Coefficients, ForceModel};
use dieplan::core::kinematics::MachineLimits;
use dieplan::core::nc::{parse_gcode, ParseOptions};
use dieplan::core::progress::NoProgress;
use dieplan::core::stock::Rect;
use dieplan::core::tool::{EndMill, ToolType};
use dieplan::core::tool_life::ToolLifeModel;
use dieplan::core::toolpath::Toolpath;
use std::time::Instant;

mod fixtures;
use fixtures::data;

/// Two helical entries of the 10 mm tool (a 14 mm hole, 10 turns down 10 mm: a full slot
/// all round), each followed by a full slot: tests/api/feeds.rs's program.
const HELICAL_ENTRIES: &str = "G21 G90 G17\nS9600 M3\nG0 X17 Y20 Z2\nG1 Z0 F1000\nG2 X17 Y20 Z-10 I-2 J0 P10 F1500\nG1 X45 F2000\nG0 Z2\nG0 X17 Y60\nG1 Z0 F1000\nG2 X17 Y60 Z-10 I-2 J0 P10 F1500\nG1 X45 F2000\nG0 Z5\nM30\n";

/// One tool as the seeded database has it.
struct Tool {
    diameter_mm: f64,
    flutes: u32,
    spindle_rpm: f64,
    fz_mm: f64,
    fz_min_mm: f64,
    rd_mm: f64,
    price: f64,
    model: Option<ForceModel>,
}

/// A seeded tool of `diameter_mm` with 6 flutes: its standard conditions (S, fz, fz_min,
/// Rd), its price and its force model's row (t0, δt, L0, δL, β0, β1, β2, β22, β12).
fn seeded(diameter_mm: f64, standard: [f64; 4], price: f64, row: [f64; 9]) -> Tool {
    let [t0_um, dt_um, l0_mm, dl_mm, b0, b1, b2, b22, b12] = row;
    let coefficients = Coefficients { b0, b1, b2, b11: 0.0, b22, b12 };
    let model = ForceModel { t0_um, dt_um, l0_mm, dl_mm, coefficients, ad_ref_mm: diameter_mm, corner_radius_mm: 0.0 };
    let [spindle_rpm, fz_mm, fz_min_mm, rd_mm] = standard;
    Tool { diameter_mm, flutes: 6, spindle_rpm, fz_mm, fz_min_mm, rd_mm, price, model: Some(model) }
}

fn six() -> Tool {
    seeded(6.0, [15000.0, 0.04, 0.002, 0.3], 55.0, [17.435596, 7.0, 1.35308, 0.262, 83.84, 23.6, 18.01, 1.505, 5.821])
}

fn ten() -> Tool {
    seeded(10.0, [9600.0, 0.1, 0.005, 0.5], 90.0, [43.588989, 15.0, 2.255134, 0.436, 269.1, 65.84, 53.66, 3.763, 15.45])
}

fn tiger_tool() -> Tool {
    Tool {
        diameter_mm: 2.5,
        flutes: 2,
        spindle_rpm: 2000.0,
        fz_mm: 0.025,
        fz_min_mm: 0.00125,
        rd_mm: 0.125,
        price: 30.0,
        model: None,
    }
}

const MACHINE: MachineLimits = MachineLimits {
    rapid_mm_min: 20000.0,
    max_feed_mm_min: 15000.0,
    accel_mm_s2: [2000.0, 2000.0, 1500.0],
    jerk_mm_s3: [50000.0, 50000.0, 40000.0],
    tool_change_s: 8.0,
};

fn run(label: &str, gcode: &str, tool: &Tool, stock: Rect, z_bottom: f64, objective: Objective) {
    let path: Toolpath = parse_gcode(gcode, &ParseOptions::default()).expect("parses");
    let standard = engagement(Contour::Straight, tool.diameter_mm / 2.0, tool.rd_mm).expect("a standard cut");
    let f_star = tool.model.map(|m| m.design_centre_force_n());
    let standard_feed = tool.fz_mm * f64::from(tool.flutes) * tool.spindle_rpm;
    let max_feed = (2.0 * standard_feed).min(MACHINE.max_feed_mm_min);
    let strategy = if tool.model.is_some() { FeedStrategy::ConstantForce } else { FeedStrategy::CuttingPoint };
    let spec = FeedSpec {
        rule: FeedRule {
            strategy,
            force_model: tool.model,
            target_force_n: f_star.unwrap_or(0.0),
            flutes: tool.flutes,
            min_feed_mm_min: tool.fz_min_mm * f64::from(tool.flutes) * tool.spindle_rpm,
            max_feed_mm_min: max_feed,
            air_feed_mm_min: max_feed,
        },
        max_change_per_mm: Some(DEFAULT_MAX_FEED_CHANGE_PER_MM),
        blocks: BlockOptions::default(),
        rapid_mm_min: MACHINE.rapid_mm_min,
    };
    let analysis = AnalysisSpec {
        tool: EndMill {
            tool_type: ToolType::Square,
            diameter_mm: tool.diameter_mm,
            flutes: tool.flutes,
            corner_radius_mm: 0.0,
        },
        stock: vec![StockRegion::Rect(stock)],
        open: vec![],
        z_top: 0.0,
        z_bottom,
        force_model: tool.model,
        default_spindle_rpm: Some(tool.spindle_rpm),
        rapid_mm_min: MACHINE.rapid_mm_min,
        sample_spacing_mm: None,
        cell_mm: None,
        alpha_limit_deg: DEFAULT_ALPHA_LIMIT_DEG,
        series_points: 0,
        stock_memory_bytes: dieplan::core::analysis::DEFAULT_STOCK_MEMORY_BYTES,
    };
    let life = ToolLifeModel {
        life_m: 320.0,
        gamma_table: vec![(0.0, 1.0), (40.0, 1.0), (50.0, 2.0), (60.0, 4.0), (90.0, 8.0), (180.0, 12.0)],
        force_exponent: 2.4,
        standard_arc_length_mm: standard.arc_length_mm,
        standard_fz_mm: tool.fz_mm,
        standard_force_n: f_star,
    };
    let rates = Rates { machine_rate_per_hour: 60.0, tool_price: tool.price, currency: "USD".into() };
    let objective = ObjectiveSpec {
        objective,
        max_force_n: f_star.unwrap_or(f64::INFINITY),
        cost: Some(CostModel { life, machine: MACHINE, rates }),
    };
    let start = Instant::now();
    let optimised = optimize_costed(&path, &analysis, None, &spec, objective.clone(), &NoProgress).expect("optimises");
    let secs = start.elapsed().as_secs_f64();
    let (plan, c) = (optimised.plan, optimised.costed.expect("costed"));
    println!(
        "{label}, {:?}: cost {:.2} → {:.2} USD, tools {:.3} → {:.3}, kinematic time {:.2} → {:.2} min; {} moves kept{}; {:.1} s",
        objective.objective,
        c.before.cost.total,
        c.after.cost.total,
        c.before.wear.consumption.ratio,
        c.after.wear.consumption.ratio,
        c.before.time.kinematic_min,
        c.after.time.kinematic_min,
        plan.kept_moves,
        if c.kept_input { ", input returned" } else { "" },
        secs,
    );
}

fn main() {
    let filters: Vec<String> = std::env::args().skip(1).filter(|a| !a.starts_with("--")).collect();
    let wanted = |label: &str| filters.is_empty() || filters.iter().any(|f| label.contains(f.as_str()));
    let objectives = [Objective::MinCost, Objective::ConstantForce, Objective::MinTime];
    // benches/analysis.rs's 100 × 100 × 10 block around trochoidal.ngc.
    let troch_stock = Rect { x_min: -60.0, y_min: -10.0, x_max: 40.0, y_max: 90.0 };
    for (name, tool) in [("trochoidal.ngc, 6 mm", six()), ("trochoidal.ngc, 10 mm", ten())] {
        if wanted(name) {
            for o in objectives {
                run(name, &data("trochoidal.ngc"), &tool, troch_stock, -10.0, o);
            }
        }
    }
    if wanted("helical") {
        let stock = Rect { x_min: 0.0, y_min: 0.0, x_max: 60.0, y_max: 80.0 };
        for o in objectives {
            run("helical entries, 10 mm", HELICAL_ENTRIES, &ten(), stock, -10.0, o);
        }
    }
    if wanted("tiger") {
        // tiger.camotics: stock (-2,-1,-32)..(92,89,0).
        let stock = Rect { x_min: -2.0, y_min: -1.0, x_max: 92.0, y_max: 89.0 };
        for o in [Objective::MinCost, Objective::ConstantForce] {
            run("tiger.nc, 2.5 mm", &data("tiger.nc"), &tiger_tool(), stock, -32.0, o);
        }
    }
}
