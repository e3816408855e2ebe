//! The feeds, wear and time of a plan from the geometry its verification kept, against the
//! way they were found before: the optimised program simulated again.

use super::evaluate::{evaluate, feed_spec};
use super::feeds::{for_each_sample_in_plan, force_at_feed, optimise};
use super::layer::{plan_layers, Step};
use super::tests::{options, ten_mm};
use super::CavityInput;
use crate::core::analysis::analyze_with;
use crate::core::feed::plan::optimize_side_milling;
use crate::core::fixtures::rounded_box;
use crate::core::progress::NoProgress;
use crate::core::tool_life::WearCut;
use crate::core::toolpath::move_length;
use crate::core::toolpath::Motion;

/// Side-cutting wear (the approach holes left out: the simulation of a helix split into the
/// optimiser's pieces sees material at every piece, the helix as written clears its slice in
/// the first turn) and feed time of a layer, from the kept geometry and from a new
/// simulation of the optimised program.
#[test]
fn the_wear_and_time_from_the_kept_geometry_are_those_of_the_optimised_program_simulated_again() {
    let input = CavityInput::Depth { pocket: rounded_box(40.0, 30.0, 6.0), z_top_mm: 0.0, z_bottom_mm: -12.0 };
    let c = ten_mm(10.0);
    let o = options();
    let cavity = input.layers_for(c.roughing.ad_mm, c.intermediate.ad_mm).unwrap();
    let layers = plan_layers(&cavity, &c, &o, &NoProgress).unwrap();
    let flutes = f64::from(c.tool.flutes);
    for factor in [1.0, 2.0] {
        evaluate(&layers, &c, &o, factor, &NoProgress).unwrap();
        let spec = feed_spec(&c, &o, factor);
        for l in layers.iter().filter(|l| l.copy_of.is_none()) {
            let g = l.geometry.as_deref().unwrap();
            let side =
                |line: u32| l.steps[(line as usize).saturating_sub(1).min(l.steps.len() - 1)] != Step::HelicalBoring;
            let simulated = optimize_side_milling(&l.toolpath, &l.analysis, &spec, &NoProgress).unwrap();
            let arithmetic = optimise(&l.toolpath, g, &spec).unwrap();
            assert_eq!(arithmetic.path.moves.len(), simulated.path.moves.len());
            let time = |p: &crate::core::toolpath::Toolpath| -> f64 {
                let feed = p.moves.iter().filter(|m| !matches!(m.motion, Motion::Rapid));
                feed.map(|m| move_length(m) / m.feed_mm_min.unwrap_or(1.0)).sum()
            };
            assert!((time(&arithmetic.path) - time(&simulated.path)).abs() < 1e-6 * time(&simulated.path));
            let (mut again, mut kept) = (0.0, 0.0);
            analyze_with(&simulated.path, &l.analysis, &NoProgress, |s| {
                let alpha_deg = s.contact.alpha_rad.to_degrees();
                if alpha_deg <= 0.0 || s.sample.rapid || !side(s.sample.line) {
                    return;
                }
                let fz_p =
                    s.sample.feed_mm_min / (flutes * s.sample.spindle_rpm.unwrap_or(1.0)) * s.cutting_point_ratio;
                let cut = WearCut { alpha_deg, arc_length_mm: s.arc_length_mm, fz_p_mm: fz_p, force_n: s.force_n };
                again += c.life.wear_mm(s.sample.step_mm, &cut);
            })
            .unwrap();
            for_each_sample_in_plan(&l.toolpath, g, &arithmetic, |s, i| {
                let m = &arithmetic.path.moves[i];
                let alpha_deg = f64::from(s.alpha_rad).to_degrees();
                if alpha_deg <= 0.0 || s.rapid() || !side(m.line) {
                    return;
                }
                let feed = m.feed_mm_min.unwrap_or(0.0);
                let fz_p = feed / (flutes * f64::from(s.spindle_rpm)) * f64::from(s.cutting_point_ratio);
                let force_n = force_at_feed(c.force_model, s, c.tool.flutes, feed);
                let cut = WearCut { alpha_deg, arc_length_mm: s.arc_length_mm(), fz_p_mm: fz_p, force_n };
                kept += c.life.wear_mm(f64::from(s.step_mm), &cut);
            });
            assert!((kept - again).abs() <= 0.02 * again, "layer {} at {factor} × F*: {kept} vs {again}", l.index);
        }
    }
}
