//! `cargo bench --bench feeds`: feed optimisation of the real files of ../shared/data,
//! against the simulation it needs, and the NC writer's speed. Prints its figures.

use dieplan::core::analysis::{analyze, AnalysisSpec, StockRegion, DEFAULT_ALPHA_LIMIT_DEG};
use dieplan::core::feed::blocks::BlockOptions;
use dieplan::core::feed::edit::edit_feeds;
use dieplan::core::feed::plan::{optimize_side_milling, FeedSpec, DEFAULT_MAX_FEED_CHANGE_PER_MM};
use dieplan::core::feed::rule::{FeedRule, FeedStrategy};
use dieplan::core::force_model::{Coefficients, ForceModel};
use dieplan::core::nc::{interpret, parse_gcode, write_program, Interpreted, ParseOptions, WriterOptions};
use dieplan::core::progress::NoProgress;
use dieplan::core::stock::Rect;
use dieplan::core::tool::{EndMill, ToolType};
use std::time::Instant;

mod fixtures;
use fixtures::data;

fn analysis_spec(tool: EndMill, stock: Rect, z_bottom: f64, model: Option<ForceModel>) -> AnalysisSpec {
    AnalysisSpec {
        tool,
        stock: vec![StockRegion::Rect(stock)],
        open: vec![],
        z_top: 0.0,
        z_bottom,
        force_model: model,
        default_spindle_rpm: Some(9600.0),
        rapid_mm_min: 20000.0,
        sample_spacing_mm: Some(0.05),
        cell_mm: None,
        alpha_limit_deg: DEFAULT_ALPHA_LIMIT_DEG,
        series_points: 0,
        stock_memory_bytes: dieplan::core::analysis::DEFAULT_STOCK_MEMORY_BYTES,
    }
}

fn feed_spec(strategy: FeedStrategy, model: Option<ForceModel>, flutes: u32, standard: f64) -> FeedSpec {
    FeedSpec {
        rule: FeedRule {
            strategy,
            force_model: model,
            target_force_n: 269.1,
            flutes,
            min_feed_mm_min: 0.05 * standard,
            max_feed_mm_min: 2.0 * standard,
            air_feed_mm_min: 2.0 * standard,
        },
        max_change_per_mm: Some(DEFAULT_MAX_FEED_CHANGE_PER_MM),
        blocks: BlockOptions::default(),
        rapid_mm_min: 20000.0,
    }
}

fn run(label: &str, text: &str, analysis: &AnalysisSpec, spec: &FeedSpec) {
    let start = Instant::now();
    let path = &parse_gcode(text, &ParseOptions::default()).expect("parses");
    let parsing = start.elapsed().as_secs_f64();
    let start = Instant::now();
    let Interpreted { path: mapped, map } = interpret(text, &ParseOptions::default()).expect("parses");
    let interpreting = start.elapsed().as_secs_f64();
    assert_eq!(mapped.moves.len(), path.moves.len());
    let start = Instant::now();
    let a = analyze(path, analysis, &NoProgress).expect("analyses");
    let simulation = start.elapsed().as_secs_f64();
    let start = Instant::now();
    let plan = optimize_side_milling(path, analysis, spec, &NoProgress).expect("optimises");
    let optimisation = start.elapsed().as_secs_f64();
    let start = Instant::now();
    let program = write_program(&plan.path, &WriterOptions::default());
    let writing = start.elapsed().as_secs_f64();
    let start = Instant::now();
    let edited = edit_feeds(text, path, &map, &plan.pieces);
    let editing = start.elapsed().as_secs_f64();
    let mb = text.len() as f64 / 1e6;
    println!(
        "feeds {label}: input {mb:.2} MB read in {:.1} ms ({:.0} MB/s), with the line map in {:.1} ms ({:.0} MB/s); edited in place in {:.1} ms ({:.0} MB/s of input): {} lines changed, {} split",
        parsing * 1e3,
        mb / parsing,
        interpreting * 1e3,
        mb / interpreting,
        editing * 1e3,
        mb / editing,
        edited.changes.len(),
        edited.split_blocks,
    );
    println!(
        "feeds {label}: {} samples; simulation alone {:.2} s, simulation + optimisation {:.2} s (optimiser {:+.2} s = {:.0} %); {} moves → {} blocks; program {:.2} MB written in {:.1} ms ({:.0} MB/s); time {:.2} → {:.2} min",
        a.summary.samples,
        simulation,
        optimisation,
        optimisation - simulation,
        100.0 * (optimisation - simulation) / simulation,
        path.moves.len(),
        plan.path.moves.len(),
        program.len() as f64 / 1e6,
        writing * 1e3,
        program.len() as f64 / 1e6 / writing,
        plan.before.time_min,
        plan.after.time_min,
    );
}

fn main() {
    let filters: Vec<String> = std::env::args().skip(1).filter(|a| !a.starts_with("--")).collect();
    let wanted = |label: &str| filters.is_empty() || filters.iter().any(|f| label.contains(f.as_str()));
    let model = ForceModel {
        t0_um: 43.589,
        dt_um: 15.0,
        l0_mm: 2.2551,
        dl_mm: 0.436,
        coefficients: Coefficients { b0: 269.1, b1: 65.84, b2: 53.66, b11: 0.0, b22: 3.763, b12: 15.45 },
        ad_ref_mm: 10.0,
        corner_radius_mm: 0.0,
    };
    if wanted("trochoidal") {
        let ten = EndMill { tool_type: ToolType::Square, diameter_mm: 10.0, flutes: 6, corner_radius_mm: 0.0 };
        let stock = Rect { x_min: -60.0, y_min: -10.0, x_max: 40.0, y_max: 90.0 };
        run(
            "trochoidal.ngc, constant force, 10 mm tool",
            &data("trochoidal.ngc"),
            &analysis_spec(ten, stock, -10.0, Some(model)),
            &feed_spec(FeedStrategy::ConstantForce, Some(model), 6, 5760.0),
        );
    }
    if wanted("tiger") {
        // tiger.camotics: 2.5 mm flat end mill, stock (-2,-1,-32)..(92,89,0); no force
        // model for that tool: the cutting-point rule.
        let small = EndMill { tool_type: ToolType::Square, diameter_mm: 2.5, flutes: 2, corner_radius_mm: 0.0 };
        let stock = Rect { x_min: -2.0, y_min: -1.0, x_max: 92.0, y_max: 89.0 };
        run(
            "tiger.nc, cutting point, 2.5 mm tool",
            &data("tiger.nc"),
            &analysis_spec(small, stock, -32.0, None),
            &feed_spec(FeedStrategy::CuttingPoint, None, 2, 1000.0),
        );
    }
}
