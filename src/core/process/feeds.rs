//! A layer's constant-force feeds from the geometry its verification kept (MODEL.md §3): the
//! material a path removes does not depend on its feeds, so the feed optimisation at any
//! force target, and the wear of every sample at the new feeds, are arithmetic over the
//! samples of [`PathGeometry`], without simulating the path again.

use crate::core::analysis::geometry::{PathGeometry, SampleGeometry};
use crate::core::feed::collect::{Collector, SampleIn};
use crate::core::feed::objective::ForceCurve;
use crate::core::feed::plan::{assemble, check_spec, FeedPlan, FeedSpec};
use crate::core::feed::rule::SampleCut;
use crate::core::force_model::ForceModel;
use crate::core::toolpath::{Motion, Toolpath};
use crate::core::CoreError;

/// The cut of a sample as the feed rules read it.
pub fn sample_cut(g: &SampleGeometry) -> SampleCut {
    SampleCut {
        alpha_rad: f64::from(g.alpha_rad),
        arc_length_mm: g.arc_length_mm(),
        ad_mm: f64::from(g.ad_mm),
        cutting_point_ratio: f64::from(g.cutting_point_ratio),
        centre_radius_mm: f64::from(g.centre_radius_mm),
        tool_radius_mm: f64::from(g.contact_radius_mm),
        programmed_feed_mm_min: f64::from(g.programmed_mm_min),
        spindle_rpm: g.spindle(),
        // A move straight down keeps its feed, in material or not.
        plunge: g.plunge() || g.vertical(),
        in_material: g.in_material(),
    }
}

/// The feeds of `path` (whose simulated samples are `geometry`) optimised by `spec`, as
/// [`crate::core::feed::plan::optimize_side_milling`] optimises them from a simulation.
pub fn optimise(path: &Toolpath, geometry: &PathGeometry, spec: &FeedSpec) -> Result<FeedPlan, CoreError> {
    check_spec(spec)?;
    let r = geometry.tool_radius_mm;
    let mut collector = Collector::with_objective(spec.rule, None, r);
    for g in &geometry.samples {
        collector.add(&SampleIn {
            at: g.at(),
            step_mm: f64::from(g.step_mm),
            move_index: g.move_index as usize,
            rapid: g.rapid(),
            cut: sample_cut(g),
            force_before_n: g.force(),
        });
    }
    collector.finish();
    Ok(assemble(path, collector, spec, None, Vec::new()))
}

/// Hands every sample of `geometry` (the samples of `path`) to `visit` with the index of the
/// move of `plan.path` it falls in: the optimiser cuts each move into pieces, and sample `k`
/// of `n` of a move falls in the piece that holds the fraction `(k + 1) / n` of it.
pub fn for_each_sample_in_plan(
    path: &Toolpath,
    geometry: &PathGeometry,
    plan: &FeedPlan,
    mut visit: impl FnMut(&SampleGeometry, usize),
) {
    let samples = &geometry.samples;
    let mut i = 0;
    let mut first = 0;
    for (index, m) in path.moves.iter().enumerate() {
        let start = i;
        while i < samples.len() && samples[i].move_index as usize == index {
            i += 1;
        }
        let here = &samples[start..i];
        // As the optimiser writes them: a rapid or a move without samples stays whole.
        if matches!(m.motion, Motion::Rapid) || here.is_empty() {
            here.iter().for_each(|s| visit(s, first));
            first += 1;
            continue;
        }
        let pieces = plan.pieces.get(index).map_or(&[][..], Vec::as_slice);
        let n = here.len() as f64;
        let mut p = 0;
        for (k, s) in here.iter().enumerate() {
            let t = (k + 1) as f64 / n;
            while p + 1 < pieces.len() && t > pieces[p].t1 + f64::EPSILON {
                p += 1;
            }
            visit(s, (first + p).min(plan.path.moves.len().saturating_sub(1)));
        }
        first += pieces.len();
    }
}

/// The force at a sample run at centre feed `feed_mm_min`, N: the model's curve through the
/// simulated force at the programmed feed (exact for a single slice, the slices' shares
/// kept otherwise; see [`ForceCurve`]).
pub fn force_at_feed(model: ForceModel, g: &SampleGeometry, flutes: u32, feed_mm_min: f64) -> Option<f64> {
    let rpm = g.spindle()?;
    Some(ForceCurve::new(model, &sample_cut(g), flutes, rpm, g.force()).force_n(feed_mm_min))
}
