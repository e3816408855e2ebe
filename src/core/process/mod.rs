//! Process planning of a cavity (seed 002 Fig. 1 and Fig. 7, §2.6; seed 004 Table 1;
//! MODEL.md §8–11): from the cavity's layers to the cheapest complete roughing program.
//!
//! 1. **Reach**: each candidate end mill is checked against the cavity: a tool that leaves
//!    more of it unreachable than the smallest candidate does (a concave radius or a neck
//!    tighter than the tool) is not planned.
//! 2. **Layers**: every layer gets its sequence from the trochoid-insertion planner
//!    ([`crate::core::insertion`]): approach holes by helical entries, spiral hole expansion
//!    of round regions, trochoidal grooving of the critical stretches, z-cut division of the
//!    class C ones, and the contour-parallel rough side cutting; the last layer is cut at the
//!    intermediate-rough conditions.
//! 3. **Feeds, wear, time, cost**: the feeds are optimised for a constant cutting force at the
//!    standard force F* ([`evaluate`]); the wear, the nominal and kinematic times and the cost
//!    `C = c_m·T_m + c_t·L_t/L_f` (seed 002 Eq. 4, with the kinematic time) follow.
//! 4. **Choice**: the complete candidate of the lowest cost.
//! 5. **Tuning** ([`tune`]): the chosen tool's force target is raised until the job uses about
//!    90 % of one tool.
//! 6. **Baseline** ([`baseline`]): the conventional ball-end roughing, for the comparison.

pub mod baseline;
pub mod cavity;
pub mod evaluate;
pub mod layer;
mod report;
pub mod spec;
pub mod tune;

#[cfg(test)]
mod program_tests;
#[cfg(test)]
mod tests;

pub use baseline::{plan_baseline, Baseline, BaselineSpec};
pub use cavity::{
    layer_count_by_depth, layers_by_depth, min_concave_radius_mm, Cavity, CavityInput, CavityLayer, LayerRole,
    MAX_CAVITY_LAYERS,
};
pub use evaluate::{Evaluation, Figures, LayerFigures, StepFigures};
pub use layer::{LayerPlan, Step};
pub use report::{CandidateReport, CandidateStatus, Comparison, LayerReport, ProcessPlan};
pub use spec::{ProcessOptions, ToolCandidate, DEFAULT_MAX_FORCE_FACTOR, DEFAULT_TARGET_CONSUMPTION};
pub use tune::{Tuning, TuningOutcome};

use crate::core::pocketing::unreachable_area_mm2;
use crate::core::progress::{Progress, Stage};
use crate::core::CoreError;

/// A candidate that leaves more than this much more of the cavity unreachable than the
/// smallest candidate cannot cut it, mm² per layer (**assumed**: a square millimetre, well
/// above the offsets' rounding).
pub const UNREACHABLE_TOLERANCE_MM2: f64 = 1.0;

/// Share of the progress spent on the candidates; the rest goes to tuning and the baseline.
const CANDIDATES_SHARE: f64 = 0.75;
const TUNING_SHARE: f64 = 0.15;

/// Checks what can be checked before planning.
pub fn check_process(
    input: &CavityInput,
    candidates: &[ToolCandidate],
    options: &ProcessOptions,
) -> Result<(), CoreError> {
    let cavity = input.whole();
    cavity.validate()?;
    for (i, layer) in cavity.layers.iter().enumerate() {
        let field = match input {
            CavityInput::Layers(_) => format!("layers[{i}].contour"),
            CavityInput::Depth { .. } => "contour".to_string(),
        };
        crate::core::insertion::check_pocket_size(&layer.pocket, &field)?;
    }
    options.validate()?;
    if candidates.is_empty() {
        return Err(CoreError::invalid("diameters_mm", "no candidate tool to plan with"));
    }
    for c in candidates {
        c.validate()?;
        input.layers_for(c.roughing.ad_mm, c.intermediate.ad_mm)?.validate()?;
    }
    if options.safe_z_mm <= cavity.top_mm() {
        return Err(CoreError::invalid(
            "safe_z",
            format!("must be above the top of the cavity ({} mm), got {} mm", cavity.top_mm(), options.safe_z_mm),
        ));
    }
    Ok(())
}

/// The area of `cavity` (summed over its layers) a tool of `radius_mm` cannot reach, mm².
fn unreachable_mm2(cavity: &Cavity, radius_mm: f64, allowance_mm: f64) -> f64 {
    cavity.layers.iter().map(|l| unreachable_area_mm2(&l.pocket, radius_mm + allowance_mm)).sum()
}

/// A candidate's planning step: cancelling stops the whole job (`Err`); any other failure
/// makes the candidate unplannable, for the reason given (`Ok(Err(reason))`).
fn unplannable_unless_cancelled<T>(step: Result<T, CoreError>) -> Result<Result<T, String>, CoreError> {
    match step {
        Ok(value) => Ok(Ok(value)),
        Err(CoreError::Cancelled) => Err(CoreError::Cancelled),
        Err(e) => Ok(Err(e.to_string())),
    }
}

/// Plans `cavity` with each of `candidates`, chooses the cheapest complete one, tunes it, and
/// (with `baseline`) plans the conventional baseline.
pub fn plan_process(
    input: &CavityInput,
    candidates: &[ToolCandidate],
    options: &ProcessOptions,
    baseline: Option<&BaselineSpec>,
    progress: &dyn Progress,
) -> Result<ProcessPlan, CoreError> {
    check_process(input, candidates, options)?;
    let cavity = &input.whole();
    let mut warnings = Vec::new();
    let concave = cavity.min_concave_radius_mm();
    if concave.is_some_and(|r| r <= crate::core::tolerance::LENGTH_EPS_MM) {
        warnings.push(
            "the walls have sharp concave corners: every tool leaves material in them for a smaller tool or finishing"
                .to_string(),
        );
    }
    let unreachable: Vec<f64> =
        candidates.iter().map(|c| unreachable_mm2(cavity, c.tool.radius_mm(), options.allowance_mm)).collect();
    let least = unreachable.iter().copied().fold(f64::INFINITY, f64::min);
    let allowed = least + UNREACHABLE_TOLERANCE_MM2 * cavity.layers.len() as f64;
    let mut reports = Vec::with_capacity(candidates.len());
    let mut planned = Vec::new();
    for (k, c) in candidates.iter().enumerate() {
        progress.checkpoint()?;
        let stage = Stage::nth(progress, 0.0, CANDIDATES_SHARE, k, candidates.len());
        let mut report = CandidateReport::new(c, unreachable[k]);
        if unreachable[k] > allowed {
            report.status = CandidateStatus::CannotReach;
            report.reason = Some(format!(
                "leaves {:.0} mm² of the cavity out of its reach (a concave radius or a neck tighter than its radius {} mm); the smallest candidate leaves {least:.0} mm²",
                unreachable[k],
                c.tool.radius_mm()
            ));
            reports.push(report);
            continue;
        }
        let plan_stage = Stage { inner: &stage, from: 0.0, span: 0.7 };
        let layered = input.layers_for(c.roughing.ad_mm, c.intermediate.ad_mm)?;
        let layers = match unplannable_unless_cancelled(layer::plan_layers(&layered, c, options, &plan_stage))? {
            Ok(l) => l,
            Err(reason) => {
                report.status = CandidateStatus::Unplannable;
                report.reason = Some(reason);
                reports.push(report);
                continue;
            }
        };
        report.check_layers(&layers);
        if report.status == CandidateStatus::Incomplete {
            reports.push(report);
            continue;
        }
        let eval_stage = Stage { inner: &stage, from: 0.7, span: 0.3 };
        let evaluation = match unplannable_unless_cancelled(evaluate::evaluate(&layers, c, options, 1.0, &eval_stage))?
        {
            Ok(e) => e,
            Err(reason) => {
                report.status = CandidateStatus::Unplannable;
                report.reason = Some(reason);
                reports.push(report);
                continue;
            }
        };
        report.set_figures(&evaluation);
        reports.push(report);
        planned.push((k, layers, evaluation));
    }
    let best = planned
        .iter()
        .enumerate()
        .min_by(|a, b| a.1 .2.cost.total.total_cmp(&b.1 .2.cost.total))
        .map(|(i, _)| i)
        .ok_or_else(|| {
            let why: Vec<String> = reports
                .iter()
                .map(|r| format!("{}: {}", r.name, r.reason.as_deref().unwrap_or("not planned")))
                .collect();
            CoreError::unsolvable(
                "diameters_mm",
                format!("no candidate tool can rough the cavity ({})", why.join("; ")),
            )
        })?;
    let (chosen, layers, standard) = planned.swap_remove(best);
    reports[chosen].status = CandidateStatus::Chosen;
    let tune_stage = Stage { inner: progress, from: CANDIDATES_SHARE, span: TUNING_SHARE };
    let (evaluation, tuning) = tune::tune(&layers, &candidates[chosen], options, standard, &tune_stage)?;
    if tuning.outcome == TuningOutcome::AboveTargetAtStandardForce {
        warnings.push(format!(
            "the job uses {:.0} % of a tool at the standard force: it needs {} tools (a lower force does not save the tool in the wear model)",
            100.0 * tuning.consumption,
            tuning.tools_needed
        ));
    }
    let baseline = match baseline {
        Some(spec) => {
            let stage = Stage { inner: progress, from: CANDIDATES_SHARE + TUNING_SHARE, span: 0.1 };
            Some(plan_baseline(cavity, spec, options, &stage)?)
        }
        None => None,
    };
    progress.report(1.0);
    Ok(report::assemble(cavity, reports, chosen, &layers, evaluation, tuning, baseline, warnings))
}
