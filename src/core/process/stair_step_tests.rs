use super::tests::{options, ten_mm};
use super::*;
use crate::core::conditions::CuttingConditions;
use crate::core::fixtures::ten_mm_life;
use crate::core::geometry::{Loop, Pocket};
use crate::core::nc::{parse_gcode, write_program, ParseOptions, WriterOptions};
use crate::core::progress::NoProgress;
use crate::core::tool::{EndMill, ToolType};
use crate::core::toolpath::{EventKind, Step};

/// A 60 × 40 mm cavity whose floor slopes 1 in 3 along x, from z −5 at x 60 down to −20 at
/// x 15 and flat beyond, as a CAM system slices it at Ad 5: each layer's contour is the
/// cavity's section at its bottom.
fn slanted_floor() -> CavityInput {
    let layer = |x_max: f64, top: f64, bottom: f64| CavityLayer {
        pocket: Pocket::new(Loop::rectangle(0.0, 0.0, x_max, 40.0), Vec::new()).unwrap(),
        z_top_mm: top,
        z_bottom_mm: bottom,
    };
    CavityInput::Layers(Cavity {
        layers: vec![
            layer(60.0, 0.0, -5.0),
            layer(45.0, -5.0, -10.0),
            layer(30.0, -10.0, -15.0),
            layer(15.0, -15.0, -20.0),
        ],
    })
}

/// The steps the layers leave over the slope: three wedges 15 mm wide and 5 mm high across
/// the 40 mm, mm³.
const SLANTED_FLOOR_STEPS_MM3: f64 = 3.0 * 15.0 * 5.0 / 2.0 * 40.0;

/// The R5 ball at its standard side cut (seed 004 Table 7: S 10000, fz 0.3, Rd 4, Ad 0.6)
/// with its carried-over force model and F* as the database holds them.
fn r5_ball() -> StairStepSpec {
    let conditions = CuttingConditions { spindle_rpm: 10000.0, fz_mm: 0.3, rd_mm: 4.0, ad_mm: 0.6 };
    let tool = EndMill { tool_type: ToolType::Ball, diameter_mm: 10.0, flutes: 2, corner_radius_mm: 5.0 };
    let model =
        crate::core::fixtures::seed_001_ten_mm().carried_over(6, tool.flutes, tool.corner_radius_mm, conditions.ad_mm);
    let cut = crate::core::standard_cut::contour_parallel_cut(&tool, conditions, Some(&model)).unwrap();
    StairStepSpec {
        candidate: ToolCandidate {
            name: "ball D10 R5".into(),
            tool,
            roughing: conditions,
            intermediate: conditions,
            grooving: conditions,
            force_model: model,
            standard_force_n: cut.force_n.unwrap(),
            // The ball's life row: 320 m at its own cut, γ 1 up to its engagement there.
            life: crate::core::tool_life::ToolLifeModel {
                gamma_table: vec![(0.0, 1.0), (65.0, 1.0), (90.0, 2.0), (180.0, 4.0)],
                standard_arc_length_mm: cut.arc_length_mm,
                standard_fz_mm: conditions.fz_mm,
                standard_force_n: cut.force_n,
                ..ten_mm_life()
            },
            min_feed_mm_min: 300.0,
            max_feed_mm_min: 12000.0,
            tool_price: 85.0,
        },
        tool_number: 2,
    }
}

#[test]
fn a_slanted_floor_gets_its_steps_taken_off_by_a_ball_after_the_roughing() {
    let without = plan_process(&slanted_floor(), &[ten_mm(10.0)], &options(), None, None, &NoProgress).unwrap();
    let plan =
        plan_process(&slanted_floor(), &[ten_mm(10.0)], &options(), None, Some(&r5_ball()), &NoProgress).unwrap();
    let step = plan.stair_step.as_ref().unwrap_or_else(|| panic!("no stair step: {:?}", plan.warnings));
    println!(
        "steps {:.0} mm³ (exact {SLANTED_FLOOR_STEPS_MM3}), removed {:.0} mm³, {} levels, {:?}",
        step.step_volume_mm3,
        step.removed_volume_mm3,
        step.levels.len(),
        step.figures
    );
    // The surface between the sections is the slope: its steps as the layers leave them.
    assert!((step.step_volume_mm3 / SLANTED_FLOOR_STEPS_MM3 - 1.0).abs() < 0.03, "{}", step.step_volume_mm3);
    // The ball takes most of them off (it leaves its scallops between rings and the corners
    // its radius cannot reach), on the stock the roughing really left.
    let share = step.removed_volume_mm3 / SLANTED_FLOOR_STEPS_MM3;
    assert!((0.75..=1.05).contains(&share), "removed {share:.2} of the steps");
    // The plan keeps the stock after the step: what the roughing left in its layers' contours
    // and what the ball left of the steps (a plan without the step keeps no steps: each
    // layer's simulation held its own contour only).
    let rest = |p: &ProcessPlan| p.stock.as_ref().expect("a kept stock").rest.volume_mm3;
    let left = step.step_volume_mm3 - step.removed_volume_mm3;
    assert!(
        (rest(&plan) - rest(&without) - left).abs() < 0.1 * SLANTED_FLOOR_STEPS_MM3,
        "{} against {} + {left}",
        rest(&plan),
        rest(&without)
    );
    println!("warnings {:?}; consumption {:?}", plan.warnings, step.consumption);
    // The step's time and cost are the plan's too; the roughing itself is the same.
    assert_eq!(plan.evaluation.program, without.evaluation.program);
    let (w, e) = (&plan.whole, &plan.evaluation);
    assert!((w.figures.kinematic_time_min - e.total.kinematic_time_min - step.figures.kinematic_time_min).abs() < 1e-9);
    assert!((w.cost.total - e.cost.total - step.cost.total).abs() < 1e-9);
    assert!(step.figures.kinematic_time_min > 0.0 && step.cost.tool > 0.0);
    // Its feeds hold the ball's F* where they can: the force of its standard cut as
    // contour-parallel roughing takes it (about 250 N), within the tool's feed limits.
    assert!(step.target_force_n > 200.0 && step.target_force_n < 300.0, "{}", step.target_force_n);
    let p = &step.program;
    assert!(matches!(p.events[0].kind, EventKind::ToolChange { tool: 2 }));
    assert!(p.events.iter().any(|e| matches!(e.kind, EventKind::Section(s) if s.step == Step::StairStepRoughing)));
    assert!(p.moves.iter().filter_map(|m| m.feed_mm_min).all(|f| (100.0..=12000.0 + 1e-9).contains(&f)));
    // The whole program: the roughing, the tool change, the step; written and read back, it
    // has the same motion.
    let whole = joined_program(&plan.evaluation.program, p, options().safe_z_mm);
    let written = write_program(&whole, &WriterOptions::default());
    assert!(written.contains("T1 M6") && written.contains("T2 M6") && written.contains("G43 H2"), "{written:.400}");
    assert!(written.contains("STAIR-STEP INTERMEDIATE ROUGHING"));
    let back = parse_gcode(&written, &ParseOptions::default()).unwrap();
    // The step's feed moves come back as they were, with the ball in the spindle.
    let step_feeds = |t: &crate::core::toolpath::Toolpath| -> Vec<(f64, f64, f64)> {
        t.moves
            .iter()
            .filter(|m| m.tool == Some(2) && !matches!(m.motion, crate::core::toolpath::Motion::Rapid))
            .map(|m| (m.end.x, m.end.y, m.end.z))
            .collect()
    };
    let (sent, read) = (step_feeds(p), step_feeds(&back));
    assert_eq!(sent.len(), read.len());
    assert!(sent
        .iter()
        .zip(&read)
        .all(|(a, b)| (a.0 - b.0).abs() < 1e-3 && (a.1 - b.1).abs() < 1e-3 && (a.2 - b.2).abs() < 1e-3));
}

#[test]
fn a_cavity_of_one_contour_gets_no_stair_step() {
    let input = CavityInput::Depth {
        pocket: Pocket::new(Loop::rectangle(0.0, 0.0, 60.0, 40.0), Vec::new()).unwrap(),
        z_top_mm: 0.0,
        z_bottom_mm: -15.0,
    };
    let plan = plan_process(&input, &[ten_mm(10.0)], &options(), None, Some(&r5_ball()), &NoProgress).unwrap();
    assert!(plan.stair_step.is_none());
    assert!((plan.whole.cost.total - plan.evaluation.cost.total).abs() < 1e-12);
}
