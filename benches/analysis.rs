//! `cargo bench --bench analysis`: parsing throughput and analysis speed on the real
//! files of ../shared/data and on a long synthetic pocket path. Prints its figures.

use dieplan::core::analysis::{analyze, AnalysisSpec, StockRegion, DEFAULT_ALPHA_LIMIT_DEG};
use dieplan::core::force_model::{Coefficients, ForceModel};
use dieplan::core::nc::{parse_gcode, ParseOptions};
use dieplan::core::progress::NoProgress;
use dieplan::core::stock::Rect;
use dieplan::core::tool::{EndMill, ToolType};
use dieplan::core::toolpath::{Motion, Move, Toolpath, Units, P3};
use std::time::Instant;

mod fixtures;
use fixtures::{data, wanted};

fn parse_throughput(name: &str) -> Toolpath {
    let text = data(name);
    let runs = 20;
    let start = Instant::now();
    let mut path = None;
    for _ in 0..runs {
        path = Some(parse_gcode(&text, &ParseOptions::default()).expect("parses"));
    }
    let secs = start.elapsed().as_secs_f64() / runs as f64;
    let path = path.expect("parsed");
    println!(
        "parse {name}: {:.2} MB in {:.2} ms = {:.0} MB/s ({} moves)",
        text.len() as f64 / 1e6,
        secs * 1e3,
        text.len() as f64 / 1e6 / secs,
        path.moves.len()
    );
    path
}

fn report(label: &str, path: &Toolpath, spec: &AnalysisSpec) {
    if !wanted(label) {
        return;
    }
    let start = Instant::now();
    let a = analyze(path, spec, &NoProgress).expect("analyses");
    let secs = start.elapsed().as_secs_f64();
    let s = &a.summary;
    println!(
        "analysis {label}: {} samples at {:.3} mm, cell {:.4} mm, {} slices, raster {:.1} MB: {:.2} s = {:.2} M samples/s; cut {:.0} mm, air {:.0} mm, α max {:.1}°, {} critical regions",
        s.samples,
        s.sample_spacing_mm,
        s.cell_mm,
        s.slices.len(),
        s.raster_memory_bytes as f64 / 1e6,
        secs,
        s.samples as f64 / secs / 1e6,
        s.cutting_length_mm,
        s.air_cut_length_mm,
        s.alpha_deg.max,
        a.critical_regions.len()
    );
}

fn spec(
    tool: EndMill,
    stock: Rect,
    z_top: f64,
    z_bottom: f64,
    model: Option<ForceModel>,
    spacing: Option<f64>,
) -> AnalysisSpec {
    AnalysisSpec {
        tool,
        stock: vec![StockRegion::Rect(stock)],
        open: vec![],
        z_top,
        z_bottom,
        force_model: model,
        default_spindle_rpm: Some(9600.0),
        rapid_mm_min: 20000.0,
        sample_spacing_mm: spacing,
        cell_mm: None,
        alpha_limit_deg: DEFAULT_ALPHA_LIMIT_DEG,
        series_points: 0,
        stock_memory_bytes: dieplan::core::analysis::DEFAULT_STOCK_MEMORY_BYTES,
    }
}

/// A contour-parallel path for a `w` × `h` rectangular pocket: rectangles offset inward
/// by `step`, linked by short feed moves, at depth `z`.
fn synthetic_pocket(w: f64, h: f64, r: f64, step: f64, z: f64) -> Toolpath {
    let mut moves = Vec::new();
    let mut at = P3::new(w / 2.0, h / 2.0, 5.0);
    let mut push = |motion: Motion, to: P3, moves: &mut Vec<Move>| {
        moves.push(Move {
            motion,
            start: at,
            end: to,
            feed_mm_min: Some(5760.0),
            spindle_rpm: Some(9600.0),
            tool: Some(1),
            line: moves.len() as u32 + 1,
        });
        at = to;
    };
    push(Motion::Linear, P3::new(w / 2.0, h / 2.0, z), &mut moves);
    let mut offsets = Vec::new();
    let mut o = r;
    while o < h / 2.0 {
        offsets.push(o);
        o += step;
    }
    for &o in offsets.iter().rev() {
        let (x0, y0, x1, y1) = (o, o, w - o, h - o);
        for p in [(x0, y0), (x1, y0), (x1, y1), (x0, y1), (x0, y0)] {
            push(Motion::Linear, P3::new(p.0, p.1, z), &mut moves);
        }
    }
    Toolpath { moves, events: vec![], source_units: Units::Mm, warnings: vec![] }
}

/// `cargo bench --bench analysis -- NAME…` runs only the cases whose label contains
/// one of the names.
fn main() {
    let tiger = parse_throughput("tiger.nc");
    let trochoidal = parse_throughput("trochoidal.ngc");

    // tiger.camotics: 2.5 mm flat end mill, stock (-2,-1,-32)..(92,89,0).
    let small = EndMill { tool_type: ToolType::Square, diameter_mm: 2.5, flutes: 2, corner_radius_mm: 0.0 };
    let tiger_stock = Rect { x_min: -2.0, y_min: -1.0, x_max: 92.0, y_max: 89.0 };
    // seed 001 Table 4, 10 mm end mill.
    let model = ForceModel {
        t0_um: 43.589,
        dt_um: 15.0,
        l0_mm: 2.2551,
        dl_mm: 0.436,
        coefficients: Coefficients { b0: 269.1, b1: 65.84, b2: 53.66, b11: 0.0, b22: 3.763, b12: 15.45 },
        ad_ref_mm: 10.0,
        corner_radius_mm: 0.0,
    };
    report("tiger.nc (default spacing D/100)", &tiger, &spec(small, tiger_stock, 0.0, -32.0, None, None));
    report("tiger.nc at 0.05 mm", &tiger, &spec(small, tiger_stock, 0.0, -32.0, None, Some(0.05)));
    // With a force model every slice cut is measured (its force needs its α); without
    // one only the deepest is, and the others only for Ad. The 10 mm tool's model stands
    // in here: its forces mean nothing for the 2.5 mm tool, the time is what counts.
    report(
        "tiger.nc with the forces of every slice, at 0.05 mm",
        &tiger,
        &spec(small, tiger_stock, 0.0, -32.0, Some(model), Some(0.05)),
    );

    let ten = EndMill { tool_type: ToolType::Square, diameter_mm: 10.0, flutes: 6, corner_radius_mm: 0.0 };
    let troch_stock = Rect { x_min: -60.0, y_min: -10.0, x_max: 40.0, y_max: 90.0 };
    report("trochoidal.ngc (10 mm tool)", &trochoidal, &spec(ten, troch_stock, 0.0, -10.0, Some(model), None));

    let pocket = synthetic_pocket(200.0, 150.0, 5.0, 0.5, -5.0);
    let pocket_stock = Rect { x_min: 0.0, y_min: 0.0, x_max: 200.0, y_max: 150.0 };
    report(
        "synthetic 200 x 150 pocket, Rd 0.5, 10 mm tool",
        &pocket,
        &spec(ten, pocket_stock, 0.0, -10.0, Some(model), None),
    );
}
