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
//! 6. **Stair steps** ([`stair_step`]): where the layers' sections slope, a ball or radius end
//!    mill takes the steps the roughing leaves off in thin levels, from the stock the roughing
//!    left; its time and cost join the plan's, its program follows the roughing's after a
//!    tool change.
//! 7. **Baseline** ([`baseline`]): the conventional ball-end roughing, for the comparison.

pub mod baseline;
pub mod cavity;
pub mod evaluate;
pub mod feeds;
pub mod kept_layers;
pub mod layer;
mod overload_lines;
pub(crate) mod parallel;
mod report;
pub mod screen;
pub mod spec;
pub mod stair_step;
pub mod stairs;
pub mod tune;

#[cfg(test)]
mod feeds_tests;
#[cfg(test)]
mod program_tests;
#[cfg(test)]
mod stair_step_tests;
#[cfg(test)]
mod tests;

pub use baseline::{plan_baseline, Baseline, BaselineSpec};
pub use cavity::{
    layer_count_by_depth, layers_by_depth, min_concave_radius_mm, Cavity, CavityInput, CavityLayer, LayerRole,
    MAX_CAVITY_LAYERS,
};
pub use evaluate::{Evaluation, Figures, LayerFigures, StepFigures};
pub use layer::{LayerPlan, Step};
pub use overload_lines::overload_program_lines;
pub use report::{CandidateReport, CandidateStatus, Comparison, LayerReport, ProcessPlan, Whole};
pub use screen::{Estimate, SCREEN_MARGIN, SCREEN_SPACING_FACTOR};
pub use spec::{ProcessOptions, ToolCandidate, DEFAULT_MAX_FORCE_FACTOR, DEFAULT_TARGET_CONSUMPTION};
pub use stair_step::{joined_program, plan_stair_step, stair_conditions, StairStep, StairStepSpec, STAIR_STEP_FIELD};
pub use tune::{Tuning, TuningOutcome};

use crate::core::pocketing::unreachable_area_mm2;
use crate::core::progress::{Beside, Progress, Stage};
use crate::core::CoreError;
use std::sync::atomic::{AtomicBool, Ordering};

/// A candidate that leaves more than this much more of the cavity unreachable than the
/// smallest candidate cannot cut it, mm² per layer (**assumed**: a square millimetre, well
/// above the offsets' rounding).
pub const UNREACHABLE_TOLERANCE_MM2: f64 = 1.0;

/// Share of the progress spent on the candidates (screening included); the rest goes to
/// tuning and the baseline (which runs beside them and is waited for at the end).
const CANDIDATES_SHARE: f64 = 0.75;
/// Share of the progress spent on the screening, when there is one.
const SCREENING_SHARE: f64 = 0.35;
const TUNING_SHARE: f64 = 0.15;
/// Share of the progress spent on the stair-step roughing (the baseline is waited for in the
/// rest).
const STAIR_STEP_SHARE: f64 = 0.05;

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

/// Plans `cavity` with each of `candidates`, chooses the cheapest complete one, tunes it,
/// (with `stair_step`) plans the stair-step roughing after it, and (with `baseline`) plans
/// the conventional baseline. The baseline depends on nothing else:
/// it is planned beside the candidates, on a thread of its own, and reports no progress of
/// its own (the last tenth of the progress waits for it); it stops when the job is cancelled
/// or the candidates' planning fails.
pub fn plan_process(
    input: &CavityInput,
    candidates: &[ToolCandidate],
    options: &ProcessOptions,
    baseline: Option<&BaselineSpec>,
    stair_step: Option<&StairStepSpec>,
    progress: &dyn Progress,
) -> Result<ProcessPlan, CoreError> {
    check_process(input, candidates, options)?;
    let cavity = &input.whole();
    let abandoned = AtomicBool::new(false);
    let (chosen, baseline) = std::thread::scope(|scope| {
        let side = baseline.map(|spec| {
            let beside = Beside { inner: progress, abandoned: &abandoned };
            scope.spawn(move || plan_baseline(cavity, spec, options, &beside))
        });
        let chosen = choose_and_tune(input, cavity, candidates, options, progress)
            .and_then(|chosen| with_stair_step(chosen, cavity, stair_step, options, progress));
        if chosen.is_err() {
            abandoned.store(true, Ordering::Relaxed);
        }
        let baseline = side.map(|h| h.join().unwrap_or_else(|panic| std::panic::resume_unwind(panic)));
        (chosen, baseline)
    });
    let Chosen { reports, chosen, layers, evaluation, tuning, warnings, stock, stair_step } = chosen?;
    let baseline = baseline.transpose()?;
    progress.report(1.0);
    let parts = report::Parts { candidates: reports, chosen, evaluation, tuning, baseline, stair_step, warnings };
    let mut plan = report::assemble(cavity, &layers, parts);
    plan.stock = stock;
    Ok(plan)
}

/// What a plan of layers of different contours says when no stair-step roughing was asked for.
pub const STEPS_NOT_PLANNED: &str = "the layers' contours differ: where they are sections of a sloped wall or floor, the roughing leaves steps over it; ask for the stair-step roughing (\"stair_step\": {}) to have a ball take them off";

/// The chosen plan with its stair-step roughing (`spec`), planned from the stock the
/// roughing leaves; unchanged when there is no spec or the layers leave no steps. A plan
/// that keeps no stock cannot have the step simulated: a warning says so.
fn with_stair_step(
    mut chosen: Chosen,
    cavity: &Cavity,
    spec: Option<&StairStepSpec>,
    options: &ProcessOptions,
    progress: &dyn Progress,
) -> Result<Chosen, CoreError> {
    let Some(spec) = spec else {
        if cavity.layers.windows(2).any(|w| w[0].pocket != w[1].pocket) {
            chosen.warnings.push(STEPS_NOT_PLANNED.to_string());
        }
        return Ok(chosen);
    };
    let Some(stock) = chosen.stock.as_ref() else {
        chosen.warnings.push("no stair-step roughing: the roughing keeps no stock to plan it on".to_string());
        return Ok(chosen);
    };
    let stage = Stage { inner: progress, from: CANDIDATES_SHARE + TUNING_SHARE, span: STAIR_STEP_SHARE };
    let Some((step, kept)) = plan_stair_step(cavity, &stock.stock, spec, options, &stage)? else {
        return Ok(chosen);
    };
    match crate::core::analysis::rest::RestMaterial::of_kept(&kept) {
        Ok(rest) => chosen.stock = Some(kept_layers::PlanStock { stock: kept, rest }),
        Err(reason) => {
            chosen.warnings.push(format!("the plan keeps no stock for another job to start from: {reason}"));
            chosen.stock = None;
        }
    }
    chosen.warnings.extend(step.warnings.iter().map(|w| format!("stair-step roughing: {w}")));
    chosen.stair_step = Some(step);
    Ok(chosen)
}

/// The candidates' plans, the one chosen, and its tuning.
struct Chosen {
    reports: Vec<CandidateReport>,
    chosen: usize,
    layers: Vec<LayerPlan>,
    evaluation: Evaluation,
    tuning: Tuning,
    warnings: Vec<String>,
    /// The stock the chosen plan leaves (`None`: a warning says why).
    stock: Option<kept_layers::PlanStock>,
    /// The stair-step roughing after the chosen tool's, if planned.
    stair_step: Option<StairStep>,
}

/// Screens and plans the candidates, chooses the cheapest complete plan and tunes it.
fn choose_and_tune(
    input: &CavityInput,
    cavity: &Cavity,
    candidates: &[ToolCandidate],
    options: &ProcessOptions,
    progress: &dyn Progress,
) -> Result<Chosen, CoreError> {
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
    let mut reports: Vec<CandidateReport> =
        candidates.iter().zip(&unreachable).map(|(c, u)| CandidateReport::new(c, *u)).collect();
    let mut reachable = Vec::new();
    for (k, c) in candidates.iter().enumerate() {
        if unreachable[k] > allowed {
            reports[k].status = CandidateStatus::CannotReach;
            reports[k].reason = Some(format!(
                "leaves {:.0} mm² of the cavity out of its reach (a concave radius or a neck tighter than its radius {} mm); the smallest candidate leaves {least:.0} mm²",
                unreachable[k],
                c.tool.radius_mm()
            ));
        } else {
            reachable.push(k);
        }
    }
    // Screening: every reachable candidate planned and costed coarsely, side by side (one
    // alone needs no screening).
    let screening = reachable.len() > 1;
    let (screen_share, full_from) = if screening { (SCREENING_SHARE, SCREENING_SHARE) } else { (0.0, 0.0) };
    let shares = parallel::Shares::new(progress, 0.0, screen_share, reachable.len());
    let estimates: Vec<Option<screen::Estimate>> = if screening {
        let found = parallel::map(progress, &reachable, |i, &k| {
            let layered = input.layers_for(candidates[k].roughing.ad_mm, candidates[k].intermediate.ad_mm)?;
            screen::estimate(&layered, &candidates[k], options, &shares.part(i))
        });
        let mut estimates = Vec::with_capacity(found.len());
        for e in found {
            estimates.push(e?.ok());
        }
        estimates
    } else {
        vec![None; reachable.len()]
    };
    for (i, &k) in reachable.iter().enumerate() {
        if let Some(e) = &estimates[i] {
            reports[k].estimated_cost = Some(e.cost);
            reports[k].screening_spacing_mm = Some(e.spacing_mm);
        }
    }
    // Full plans, the most promising first (passing the verification, then cheaper), while a
    // candidate can still win.
    let mut order: Vec<usize> = (0..reachable.len()).collect();
    let key = |i: &usize| estimates[*i].as_ref().map_or((true, f64::INFINITY), |e| (!e.passes, e.cost));
    order.sort_by(|a, b| key(a).partial_cmp(&key(b)).unwrap_or(std::cmp::Ordering::Equal));
    let mut best: Option<(usize, Vec<LayerPlan>, Evaluation, bool)> = None;
    for (n, &i) in order.iter().enumerate() {
        progress.checkpoint()?;
        let k = reachable[i];
        let c = &candidates[k];
        if let (Some(e), Some((b, _, evaluation, passes))) = (&estimates[i], &best) {
            if !screen::can_still_win(e, Some((evaluation.cost.total, *passes))) {
                reports[k].status = CandidateStatus::ScreenedOut;
                reports[k].reason = Some(format!(
                    "estimated at {:.2} {} at a sample spacing of {} mm, more than {:.0} % above {} ({:.2})",
                    e.cost,
                    options.currency,
                    e.spacing_mm,
                    100.0 * screen::SCREEN_MARGIN / (1.0 - screen::SCREEN_MARGIN),
                    candidates[*b].name,
                    evaluation.cost.total
                ));
                continue;
            }
        }
        let stage = Stage::nth(progress, full_from, CANDIDATES_SHARE - full_from, n, order.len());
        let plan_stage = Stage { inner: &stage, from: 0.0, span: 0.9 };
        let layered = input.layers_for(c.roughing.ad_mm, c.intermediate.ad_mm)?;
        let mut layers = match unplannable_unless_cancelled(layer::plan_layers(&layered, c, options, &plan_stage))? {
            Ok(l) => l,
            Err(reason) => {
                reports[k].status = CandidateStatus::Unplannable;
                reports[k].reason = Some(reason);
                continue;
            }
        };
        reports[k].check_layers(&layers);
        if reports[k].status == CandidateStatus::Incomplete {
            continue;
        }
        let eval_stage = Stage { inner: &stage, from: 0.9, span: 0.1 };
        let evaluation = match unplannable_unless_cancelled(evaluate::evaluate(&layers, c, options, 1.0, &eval_stage))?
        {
            Ok(e) => e,
            Err(reason) => {
                reports[k].status = CandidateStatus::Unplannable;
                reports[k].reason = Some(reason);
                continue;
            }
        };
        reports[k].set_figures(&evaluation);
        let passes = layers.iter().all(|l| l.insertion.verification.passed);
        // A plan that fails its verification never beats one that passes.
        let better = best.as_ref().is_none_or(|(_, _, e, p)| (passes, -evaluation.cost.total) > (*p, -e.cost.total));
        if better {
            best = Some((k, layers, evaluation, passes));
        } else {
            // Only the best plan keeps its samples (for the tuning) and its stock.
            layers.iter_mut().for_each(|l| (l.geometry, l.stock) = (None, None));
        }
    }
    let Some((chosen, layers, standard, passes)) = best else {
        let why: Vec<String> =
            reports.iter().map(|r| format!("{}: {}", r.name, r.reason.as_deref().unwrap_or("not planned"))).collect();
        return Err(CoreError::unsolvable(
            "diameters_mm",
            format!("no candidate tool can rough the cavity ({})", why.join("; ")),
        ));
    };
    reports[chosen].status = CandidateStatus::Chosen;
    if !passes {
        warnings.push(format!(
            "no candidate's plan passes its verification: {} is the cheapest of those that do not (see its layers)",
            candidates[chosen].name
        ));
    }
    let tune_stage = Stage { inner: progress, from: CANDIDATES_SHARE, span: TUNING_SHARE };
    let (evaluation, tuning) = tune::tune(&layers, &candidates[chosen], options, standard, &tune_stage)?;
    // The samples have served (the tuning was the last to read them): let them go before
    // the layers' stocks are stacked into the one the plan keeps, and those after.
    let mut layers = layers;
    layers.iter_mut().for_each(|l| l.geometry = None);
    let stock = kept_layers::plan_stock(&layers)
        .map_err(|reason| warnings.push(format!("the plan keeps no stock for another job to start from: {reason}")))
        .ok();
    layers.iter_mut().for_each(|l| l.stock = None);
    if tuning.outcome == TuningOutcome::AboveTargetAtStandardForce {
        warnings.push(format!(
            "the job uses {:.0} % of a tool at the standard force: it needs {} tools (a lower force does not save the tool in the wear model)",
            100.0 * tuning.consumption,
            tuning.tools_needed
        ));
    }
    Ok(Chosen { reports, chosen, layers, evaluation, tuning, warnings, stock, stair_step: None })
}
