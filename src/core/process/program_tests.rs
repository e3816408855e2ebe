//! The program a process plan writes: golden files in both dialects of a small cavity cut
//! in a rough and an intermediate-rough layer, a comment before each operation of each
//! layer, links that go up first, and labels that cost no machine time.

use super::tests::{options, ten_mm};
use super::*;
use crate::core::fixtures::rounded_box;
use crate::core::golden::check_program_goldens;
use crate::core::insertion::program_tests::assert_links_go_up_over_and_down;
use crate::core::kinematics::{machining_time, TimeOptions};
use crate::core::nc::{write_program, WriterOptions};
use crate::core::progress::NoProgress;
use crate::core::toolpath::{labels_of, Motion};
use std::collections::BTreeSet;

/// A 30 × 20 mm box with corners of radius 6, 8 mm deep, planned with the 10 mm end mill
/// alone, untuned: a 3 mm rough layer and a 5 mm intermediate-rough one.
fn small_plan() -> ProcessPlan {
    let input = CavityInput::Depth { pocket: rounded_box(30.0, 20.0, 6.0), z_top_mm: 0.0, z_bottom_mm: -8.0 };
    let untuned = ProcessOptions { tune: false, ..options() };
    plan_process(&input, &[ten_mm(10.0)], &untuned, None, None, &NoProgress).unwrap()
}

#[test]
fn a_small_cavity_in_two_layers_matches_its_golden_programs_in_both_dialects() {
    let plan = small_plan();
    assert_eq!(plan.layers.len(), 2);
    assert_eq!(plan.layers[1].role, LayerRole::IntermediateRough);
    check_program_goldens(&plan.evaluation.program, "square D10", "plan_fanuc.nc", "plan_linuxcnc_numbered.ngc");
}

#[test]
fn every_layer_of_the_plan_comments_each_of_its_steps_and_its_labels_agree_with_its_figures() {
    let plan = small_plan();
    let program = &plan.evaluation.program;
    let labels = labels_of(&program.events, program.moves.len());
    assert!(labels.iter().all(Option::is_some), "every move belongs to a part");
    let text = write_program(program, &WriterOptions::default());
    for layer in &plan.layers {
        let labelled: BTreeSet<Step> = labels
            .iter()
            .flatten()
            .zip(&program.moves)
            .filter(|(l, m)| l.layer as usize == layer.index && !matches!(m.motion, Motion::Rapid))
            .map(|(l, _)| l.step)
            .collect();
        let figured: BTreeSet<Step> =
            layer.figures.steps.iter().filter(|s| s.figures.feed_length_mm > 0.0).map(|s| s.step).collect();
        assert_eq!(labelled, figured, "layer {}", layer.index);
        for step in figured {
            let comment = format!("(LAYER {} Z{} {}", layer.index + 1, layer.z_bottom_mm, step.name().to_uppercase());
            assert!(text.contains(&comment), "{comment} in\n{text}");
        }
    }
    assert!(text.contains("(LAYER 2 Z-8 INTERMEDIATE-ROUGH SIDE CUTTING)\n"), "{text}");
}

#[test]
fn the_plans_links_go_up_in_z_first_and_its_labels_cost_no_machine_time() {
    let plan = small_plan();
    let program = &plan.evaluation.program;
    assert_links_go_up_over_and_down(&program.moves, options().safe_z_mm);
    let mut unlabelled = program.clone();
    unlabelled.events.retain(|e| !e.kind.is_label());
    assert!(unlabelled.events.len() < program.events.len());
    let time = |p| machining_time(p, &options().machine, &TimeOptions::default()).unwrap().kinematic_min;
    assert_eq!(time(program).to_bits(), time(&unlabelled).to_bits());
}
