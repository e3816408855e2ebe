//! Tuning the chosen tool's conditions so that the job uses about 90 % of one tool (seed 002
//! §2.6): the constant-force target is raised above the standard force F* (the feeds rise
//! and the time falls) until the predicted consumption reaches the target.
//!
//! In the wear model (MODEL.md §9) a lower force never saves the tool: at or below F* each
//! millimetre wears `L / fz_p · γ(α)`, which a lower feed only raises. So a job that needs
//! more than the target at F* keeps F* and is reported as needing more than one tool.

use super::evaluate::{evaluate, Evaluation};
use super::layer::LayerPlan;
use super::spec::{ProcessOptions, ToolCandidate, CONSUMPTION_TOLERANCE};
use crate::core::progress::{Progress, Stage};
use crate::core::CoreError;
use serde::Serialize;

/// Most evaluations of the search (besides the one at F*).
pub const MAX_TUNING_EVALUATIONS: usize = 6;

/// How the tuning ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, utoipa::ToSchema)]
#[serde(rename_all = "snake_case")]
pub enum TuningOutcome {
    /// The consumption is within the tolerance of the target.
    Reached,
    /// Even the highest force factor uses less than the target: the job is as fast as the
    /// limits allow.
    LimitedByMaxForce,
    /// At the standard force the job already uses more than the target (see the module doc).
    AboveTargetAtStandardForce,
    /// The search stopped after its evaluations; the best one found is kept.
    Closest,
    /// Tuning was not asked for.
    Off,
}

/// The tuning of the chosen tool (seed 002 §2.6).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, utoipa::ToSchema)]
pub struct Tuning {
    pub outcome: TuningOutcome,
    pub target_consumption: f64,
    /// The chosen target force over F*.
    pub force_factor: f64,
    pub standard_force_n: f64,
    pub target_force_n: f64,
    /// Consumption at F* and at the chosen force.
    pub consumption_at_standard: f64,
    pub consumption: f64,
    /// Tools the job needs at the chosen conditions (1 when one tool lasts).
    pub tools_needed: usize,
    /// Kinematic time at F* and at the chosen force, min.
    pub time_at_standard_min: f64,
    pub time_min: f64,
    pub evaluations: usize,
}

/// Tunes `standard` (the evaluation at F*) of `candidate`.
pub fn tune(
    layers: &[LayerPlan],
    candidate: &ToolCandidate,
    options: &ProcessOptions,
    standard: Evaluation,
    progress: &dyn Progress,
) -> Result<(Evaluation, Tuning), CoreError> {
    let target = options.target_consumption;
    let at_standard = standard.consumption.ratio;
    let time_at_standard_min = standard.time.kinematic_min;
    let summary = |e: &Evaluation, outcome: TuningOutcome, evaluations: usize| Tuning {
        outcome,
        target_consumption: target,
        force_factor: e.force_factor,
        standard_force_n: candidate.standard_force_n,
        target_force_n: e.target_force_n,
        consumption_at_standard: at_standard,
        consumption: e.consumption.ratio,
        tools_needed: e.consumption.ratio.ceil().max(1.0) as usize,
        time_at_standard_min,
        time_min: e.time.kinematic_min,
        evaluations,
    };
    if !options.tune {
        let t = summary(&standard, TuningOutcome::Off, 0);
        return Ok((standard, t));
    }
    if at_standard >= target - CONSUMPTION_TOLERANCE {
        let outcome = if at_standard <= target + CONSUMPTION_TOLERANCE {
            TuningOutcome::Reached
        } else {
            TuningOutcome::AboveTargetAtStandardForce
        };
        let t = summary(&standard, outcome, 0);
        return Ok((standard, t));
    }
    let stage = |k: usize| Stage::nth(progress, 0.0, 1.0, k, MAX_TUNING_EVALUATIONS);
    let high = evaluate(layers, candidate, options, options.max_force_factor, &stage(0))?;
    if high.consumption.ratio <= target + CONSUMPTION_TOLERANCE {
        let outcome = if high.consumption.ratio >= target - CONSUMPTION_TOLERANCE {
            TuningOutcome::Reached
        } else {
            TuningOutcome::LimitedByMaxForce
        };
        let t = summary(&high, outcome, 1);
        return Ok((high, t));
    }
    // Bisection on log κ between F* (below the target) and the maximum (above it).
    let (mut lo, mut hi) = (standard, high);
    let mut evaluations = 1;
    while evaluations < MAX_TUNING_EVALUATIONS {
        progress.checkpoint()?;
        let kappa = (lo.force_factor.ln() + 0.5 * (hi.force_factor.ln() - lo.force_factor.ln())).exp();
        let e = evaluate(layers, candidate, options, kappa, &stage(evaluations))?;
        evaluations += 1;
        let ratio = e.consumption.ratio;
        if (ratio - target).abs() <= CONSUMPTION_TOLERANCE {
            let t = summary(&e, TuningOutcome::Reached, evaluations);
            return Ok((e, t));
        }
        if ratio < target {
            lo = e;
        } else {
            hi = e;
        }
    }
    // The closest below the target: one tool still lasts.
    let t = summary(&lo, TuningOutcome::Closest, evaluations);
    Ok((lo, t))
}
