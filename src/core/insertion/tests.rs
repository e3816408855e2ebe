//! The planner on real contours: border.dxf and a box cavity with a narrow slot.

use super::*;
use crate::core::conditions::CuttingConditions;
use crate::core::geometry::{Loop, Vertex};
use crate::core::progress::NoProgress;
use crate::core::tool::{EndMill, ToolType};

fn tool() -> EndMill {
    EndMill { tool_type: ToolType::Square, diameter_mm: 10.0, flutes: 6, corner_radius_mm: 0.0 }
}

fn spec(z_bottom: f64) -> InsertionSpec {
    let roughing = CuttingConditions { spindle_rpm: 4800.0, fz_mm: 0.1, rd_mm: 0.5, ad_mm: 10.0 };
    let grooving = CuttingConditions { spindle_rpm: 4800.0, fz_mm: 0.1, rd_mm: 0.5, ad_mm: 10.0 };
    InsertionSpec::new(tool(), roughing, grooving, 0.0, z_bottom)
}

pub fn border_dxf() -> Pocket {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../shared/data/border.dxf");
    let text = std::fs::read_to_string(path).unwrap();
    crate::core::geometry::pocket_from_loops(crate::core::geometry::loops_from_dxf(&text).unwrap()).unwrap()
}

/// An 80 × 60 mm box with a 12 mm wide, 40 mm long slot leaving its right wall.
pub fn box_with_slot(slot_width_mm: f64) -> Pocket {
    let h = slot_width_mm / 2.0;
    let outer = Loop::new(vec![
        Vertex::new(0.0, 0.0, 0.0),
        Vertex::new(80.0, 0.0, 0.0),
        Vertex::new(80.0, 30.0 - h, 0.0),
        Vertex::new(120.0, 30.0 - h, 0.0),
        Vertex::new(120.0, 30.0 + h, 0.0),
        Vertex::new(80.0, 30.0 + h, 0.0),
        Vertex::new(80.0, 60.0, 0.0),
        Vertex::new(0.0, 60.0, 0.0),
    ]);
    Pocket::new(outer, vec![]).unwrap()
}

fn show(name: &str, plan: &InsertionPlan) {
    println!(
        "{name}: base max α {:.1}° ({} overloaded), rounds {}",
        plan.base_max_alpha_deg, plan.base_overloaded_samples, plan.rounds
    );
    for t in &plan.treatments {
        println!("  {t:?}");
    }
    println!("  verification {:?}", plan.verification);
    println!("  trim {:?}, moves {}", plan.trim, plan.toolpath.moves.len());
    if let Some(o) = plan.verification.first_overload {
        let i = o.line as usize - 1;
        for m in &plan.toolpath.moves[i.saturating_sub(3)..(i + 2).min(plan.toolpath.moves.len())] {
            println!("    {m:?}");
        }
    }
}

#[test]
fn border_dxf_gets_a_complete_gouge_free_program_within_the_engagement_limit() {
    let pocket = border_dxf();
    let plan = plan_insertion(&pocket, &spec(-10.0), None, &NoProgress).unwrap();
    show("border", &plan);
    assert!(plan.verification.passed, "{:?}", plan.verification);
}

#[test]
fn a_box_cavity_with_a_12_mm_slot_gets_a_complete_gouge_free_program_within_the_engagement_limit() {
    let pocket = box_with_slot(12.0);
    let plan = plan_insertion(&pocket, &spec(-10.0), None, &NoProgress).unwrap();
    show("box", &plan);
    assert!(plan.verification.passed, "{:?}", plan.verification);
}
