//! `cargo bench --bench trochoids`: the trochoid-insertion planner on `border.dxf` and on an
//! 80 × 60 mm box with a 12 mm slot (10 mm end mill, 10 mm deep, seed 004's rough and
//! grooving conditions). Prints the time of each stage and the figures of the plan.
//! `cargo bench --bench trochoids -- border` runs the cases whose label contains a word.

use dieplan::core::conditions::CuttingConditions;
use dieplan::core::geometry::{loops_from_dxf, pocket_from_loops, Loop, Pocket, Vertex};
use dieplan::core::insertion::{base_path, plan_insertion, InsertionSpec, TreatmentKind};
use dieplan::core::medial::{medial_axis, MedialOptions};
use dieplan::core::progress::NoProgress;
use dieplan::core::tool::{EndMill, ToolType};
use dieplan::core::toolpath::move_length;
use std::time::Instant;

fn border() -> Pocket {
    let path = format!("{}/../shared/data/border.dxf", env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{path}: {e}"));
    pocket_from_loops(loops_from_dxf(&text).expect("dxf")).expect("pocket")
}

fn box_with_slot() -> Pocket {
    let v = |x: f64, y: f64| Vertex::new(x, y, 0.0);
    let outer = Loop::new(vec![
        v(0.0, 0.0),
        v(80.0, 0.0),
        v(80.0, 24.0),
        v(120.0, 24.0),
        v(120.0, 36.0),
        v(80.0, 36.0),
        v(80.0, 60.0),
        v(0.0, 60.0),
    ]);
    Pocket::new(outer, vec![]).expect("pocket")
}

fn spec() -> InsertionSpec {
    let tool = EndMill { tool_type: ToolType::Square, diameter_mm: 10.0, flutes: 6, corner_radius_mm: 0.0 };
    // Seed 004 Table 2 (10 mm straight end mill): rough side cutting and trochoidal grooving.
    let roughing = CuttingConditions { spindle_rpm: 4800.0, fz_mm: 0.1, rd_mm: 0.5, ad_mm: 10.0 };
    let grooving = CuttingConditions { spindle_rpm: 4800.0, fz_mm: 0.1, rd_mm: 0.5, ad_mm: 10.0 };
    InsertionSpec::new(tool, roughing, grooving, 0.0, -10.0)
}

fn run(label: &str, pocket: &Pocket) {
    let spec = spec();
    let start = Instant::now();
    let axis = medial_axis(pocket, &MedialOptions::default()).expect("axis");
    let t_axis = start.elapsed().as_secs_f64();
    let start = Instant::now();
    let base = base_path(pocket, &spec).expect("base");
    let t_base = start.elapsed().as_secs_f64();
    let start = Instant::now();
    let plan = plan_insertion(pocket, &spec, None, &NoProgress).expect("plan");
    let t_plan = start.elapsed().as_secs_f64();
    let length: f64 = plan.toolpath.moves.iter().map(move_length).sum();
    let base_length: f64 = base.moves.iter().map(move_length).sum();
    let count = |k: TreatmentKind| plan.treatments.iter().filter(|t| t.kind == k).count();
    let v = &plan.verification;
    println!(
        "{label}: axis {} branches in {:.1} ms; base path {} moves, {:.0} mm in {:.1} ms; plan in {:.2} s ({} rounds: 2 simulations + raster checks): {} trochoids, {} z-cut stretches, {} moves, {:.0} mm; max α outside z-cut {:.1}° (base {:.1}°), gouges {}, uncleared {:.2} mm², passed {}",
        axis.branches.len(),
        t_axis * 1e3,
        base.moves.len(),
        base_length,
        t_base * 1e3,
        t_plan,
        plan.rounds,
        count(TreatmentKind::Trochoid),
        count(TreatmentKind::ZCut),
        plan.toolpath.moves.len(),
        length,
        v.outside_zcut.max_alpha_deg,
        plan.base_max_alpha_deg,
        v.gouges,
        v.uncleared_area_mm2,
        v.passed
    );
}

/// A labelled pocket.
type Case = (&'static str, fn() -> Pocket);

fn main() {
    let filters: Vec<String> = std::env::args().skip(1).filter(|a| !a.starts_with('-')).collect();
    let cases: [Case; 2] = [("border.dxf", border), ("box with a 12 mm slot", box_with_slot)];
    for (label, pocket) in cases {
        if filters.is_empty() || filters.iter().any(|f| label.contains(f.as_str())) {
            run(label, &pocket());
        }
    }
}
