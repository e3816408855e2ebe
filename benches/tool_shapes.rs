//! `cargo bench --bench tool_shapes`: how well the stock simulation removes the material of
//! square, radius and ball end mills (issue 32 items 1 and 6), against volumes computed
//! from the tools' real profiles, and its speed and memory on tiger.nc.
//!
//! The cases:
//! - one pass 0.6 mm deep straight across a 50 mm block, with each tool shape (the exact
//!   volume is the block's length times the area of the tool's profile below the surface);
//! - a z-level roughing with the ball end mill: passes 3 mm apart across a block, five
//!   levels 0.6 mm apart;
//! - a raster pass of the ball end mill over a slanted surface: passes 1 mm apart, each
//!   0.2 mm deeper than the last;
//! - a z-level roughing of a 35 mm deep cavity at Ad 0.6, square and ball (issue 32 item 2):
//!   58 levels of passes 3 mm apart, each level under 2 % of the program's feed length,
//!   with the slices, the stock's memory and the time.
//!
//! Every pass runs beyond the block at both ends, so the material each removes depends
//! only on y: the exact volume is the block's length times the integral across y of the
//! depth the deepest pass reaches there (the tools' profiles, integrated numerically).
//! And tiger.nc at 0.05 mm with the 6 mm square end mill: samples per second and the
//! stock's memory per mm² of its area.
//!
//! Arguments: words that pick the cases whose label contains one.

use dieplan::core::analysis::{analyze, AnalysisSpec, StockRegion};
use dieplan::core::nc::{parse_gcode, ParseOptions};
use dieplan::core::progress::NoProgress;
use dieplan::core::stock::Rect;
use dieplan::core::tool::{EndMill, ToolType};
use dieplan::core::toolpath::{Motion, Move, Toolpath, Units, P3};
use std::time::Instant;

mod fixtures;
use fixtures::wanted;

/// The block the passes cross: 50 mm long in x, 40 mm wide in y, 10 mm deep (35 mm for the
/// deep roughing).
const BLOCK: Rect = Rect { x_min: 0.0, y_min: 0.0, x_max: 50.0, y_max: 40.0 };
const BLOCK_DEPTH_MM: f64 = 10.0;
const DEEP_BLOCK_DEPTH_MM: f64 = 35.0;
/// Levels of the deep roughing: Ad 35/58 ≈ 0.6 mm.
const DEEP_LEVELS: u32 = 58;
/// Steps across y of the numerical integration of the exact volume.
const INTEGRATION_STEPS: usize = 400_000;
const D_MM: f64 = 10.0;
const CORNER_MM: f64 = 1.0;

fn tool(tool_type: ToolType) -> EndMill {
    let corner_radius_mm = match tool_type {
        ToolType::Square => 0.0,
        ToolType::Radius => CORNER_MM,
        ToolType::Ball => D_MM / 2.0,
    };
    EndMill { tool_type, diameter_mm: D_MM, flutes: 2, corner_radius_mm }
}

/// The height of the tool's cutting edge above its tip at distance `d` from its axis, mm
/// (infinite beyond its radius).
fn profile_height_mm(tool: &EndMill, d: f64) -> f64 {
    let r = tool.radius_mm();
    let rc = tool.corner_radius_mm;
    if d > r {
        return f64::INFINITY;
    }
    let flat = r - rc;
    if d <= flat {
        0.0
    } else {
        rc - (rc * rc - (d - flat).powi(2)).max(0.0).sqrt()
    }
}

/// A pass along x at `y` with the tip at `z`, from before the block to beyond it.
struct Pass {
    y: f64,
    z: f64,
}

fn program(passes: &[Pass]) -> Toolpath {
    let mut moves = Vec::new();
    let safe = 5.0;
    let (x0, x1) = (BLOCK.x_min - D_MM, BLOCK.x_max + D_MM);
    let mut at = P3::new(x0, passes[0].y, safe);
    let mut go = |motion: Motion, end: P3, moves: &mut Vec<Move>| {
        let feed_mm_min = (!matches!(motion, Motion::Rapid)).then_some(1000.0);
        moves.push(Move { motion, start: at, end, feed_mm_min, spindle_rpm: Some(10000.0), tool: None, line: 1 });
        at = end;
    };
    for p in passes {
        go(Motion::Rapid, P3::new(x0, p.y, safe), &mut moves);
        go(Motion::Linear, P3::new(x0, p.y, p.z), &mut moves);
        go(Motion::Linear, P3::new(x1, p.y, p.z), &mut moves);
        go(Motion::Rapid, P3::new(x1, p.y, safe), &mut moves);
    }
    Toolpath { moves, events: vec![], source_units: Units::Mm, warnings: vec![] }
}

/// The volume `passes` of `tool` remove from the block `depth_mm` deep, from the tool's
/// profile, mm³.
fn exact_volume_mm3(tool: &EndMill, passes: &[Pass], depth_mm: f64) -> f64 {
    let dy = (BLOCK.y_max - BLOCK.y_min) / INTEGRATION_STEPS as f64;
    let area: f64 = (0..INTEGRATION_STEPS)
        .map(|i| {
            let y = BLOCK.y_min + (i as f64 + 0.5) * dy;
            let lowest =
                passes.iter().map(|p| p.z + profile_height_mm(tool, (y - p.y).abs())).fold(f64::INFINITY, f64::min);
            (0.0 - lowest.max(-depth_mm)).max(0.0) * dy
        })
        .sum();
    area * (BLOCK.x_max - BLOCK.x_min)
}

/// The analysis of `tool` through the block `depth_mm` deep.
fn spec(tool: EndMill, depth_mm: f64) -> AnalysisSpec {
    let block = AnalysisSpec::new(tool, vec![StockRegion::Rect(BLOCK)], 0.0, -depth_mm);
    AnalysisSpec { default_spindle_rpm: Some(10000.0), ..block }
}

/// Analyses `passes` of `tool` through the block `depth_mm` deep and prints the volume
/// removed against the exact one, the slices, the stock's memory and the time.
fn case(label: &str, tool: EndMill, passes: &[Pass], depth_mm: f64) {
    if !wanted(label) {
        return;
    }
    let path = program(passes);
    let exact = exact_volume_mm3(&tool, passes, depth_mm);
    let start = Instant::now();
    let a = analyze(&path, &spec(tool, depth_mm), &NoProgress).expect("analyses");
    let secs = start.elapsed().as_secs_f64();
    let s = &a.summary;
    println!(
        "{label}: removed {:.1} mm³ against {:.1} mm³ from the tool's profile ({:+.1} %); {} slices, stock {:.1} MB, {} samples in {:.3} s",
        s.removed_volume_mm3,
        exact,
        100.0 * (s.removed_volume_mm3 / exact - 1.0),
        s.slices.len(),
        s.raster_memory_bytes as f64 / 1e6,
        s.samples,
        secs
    );
}

fn tiger() {
    if !wanted("tiger") {
        return;
    }
    let file = format!("{}/../shared/data/tiger.nc", env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(&file).unwrap_or_else(|e| panic!("{file}: {e}"));
    let path = parse_gcode(&text, &ParseOptions::default()).expect("tiger.nc parses");
    // tiger.camotics's workpiece: x −2…92, y −1…89, z −32…0.
    let stock = Rect { x_min: -2.0, y_min: -1.0, x_max: 92.0, y_max: 89.0 };
    let mut spec = spec(tool(ToolType::Square), BLOCK_DEPTH_MM);
    spec.tool.diameter_mm = 6.0;
    spec.stock = vec![StockRegion::Rect(stock)];
    spec.z_bottom = -32.0;
    spec.sample_spacing_mm = Some(0.05);
    let start = Instant::now();
    let a = analyze(&path, &spec, &NoProgress).expect("tiger.nc analyses");
    let secs = start.elapsed().as_secs_f64();
    let s = &a.summary;
    let area = (stock.x_max - stock.x_min) * (stock.y_max - stock.y_min);
    println!(
        "tiger.nc, square D6 at 0.05 mm: {} samples in {:.2} s = {:.2} M samples/s; {} slices, cell {:.3} mm, stock {:.1} MB = {:.0} bytes per mm² of stock ({:.0} per slice)",
        s.samples,
        secs,
        s.samples as f64 / secs / 1e6,
        s.slices.len(),
        s.cell_mm,
        s.raster_memory_bytes as f64 / 1e6,
        s.raster_memory_bytes as f64 / area,
        s.raster_memory_bytes as f64 / area / s.slices.len() as f64
    );
}

fn main() {
    let straight = [Pass { y: 20.0, z: -0.6 }];
    for t in ToolType::ALL {
        case(&format!("one pass 0.6 mm deep, {} D10", t.as_str()), tool(t), &straight, BLOCK_DEPTH_MM);
    }
    let levels: Vec<Pass> = (1..=5)
        .flat_map(|level| (0..=13).map(move |i| Pass { y: 1.0 + 3.0 * f64::from(i), z: -0.6 * f64::from(level) }))
        .collect();
    case("z-level roughing, ball D10, 5 levels at Ad 0.6", tool(ToolType::Ball), &levels, BLOCK_DEPTH_MM);
    let raster: Vec<Pass> = (0..=38).map(|i| Pass { y: 1.0 + f64::from(i), z: -0.2 * f64::from(i) - 0.2 }).collect();
    case("raster over a slanted surface, ball D10, 1 mm stepover", tool(ToolType::Ball), &raster, BLOCK_DEPTH_MM);
    let ad = DEEP_BLOCK_DEPTH_MM / f64::from(DEEP_LEVELS);
    let deep: Vec<Pass> = (1..=DEEP_LEVELS)
        .flat_map(|level| (0..=13).map(move |i| Pass { y: 1.0 + 3.0 * f64::from(i), z: -ad * f64::from(level) }))
        .collect();
    for t in [ToolType::Square, ToolType::Ball] {
        let label = format!("deep z-level roughing, {} D10, 58 levels at Ad 0.6 in 35 mm", t.as_str());
        case(&label, tool(t), &deep, DEEP_BLOCK_DEPTH_MM);
    }
    tiger();
}
