//! The costing of one program (seed 002 Eq. 4 with MODEL.md §9 and §10): the tool wear of
//! the stock simulation, the nominal and kinematic machining time, and
//! `C = c_m · T_m + c_t · L_t / L_f` with the kinematic time. The costing job and the
//! feeds job's before-and-after figures both come from here.

use super::cost::{cost, Cost, Rates};
use super::wear::{path_wear_from, WearReport};
use crate::core::analysis::kept::KeptStock;
use crate::core::analysis::{Analysis, AnalysisSpec, Stack};
use crate::core::kinematics::{machining_time, MachineLimits, MachiningTime, TimeOptions};
use crate::core::progress::Progress;
use crate::core::tool_life::ToolLifeModel;
use crate::core::toolpath::Toolpath;
use crate::core::CoreError;

/// What a program's cost depends on besides the program: the tool's life, the machine
/// and the shop's rates.
#[derive(Debug, Clone, PartialEq)]
pub struct CostModel {
    pub life: ToolLifeModel,
    pub machine: MachineLimits,
    pub rates: Rates,
}

/// A program's wear, time and cost.
#[derive(Debug, Clone, PartialEq)]
pub struct Estimate {
    pub wear: WearReport,
    pub time: MachiningTime,
    /// With the kinematic time.
    pub cost: Cost,
}

/// The time and cost of `path` whose wear is `wear` (counted on its simulation); the
/// time of every move is kept too.
pub fn estimate_with_wear(path: &Toolpath, wear: WearReport, model: &CostModel) -> Result<Estimate, CoreError> {
    let time = machining_time(path, &model.machine, &TimeOptions { per_move: true, ..TimeOptions::default() })?;
    let cost = cost(time.kinematic_min, wear.consumption.ratio, &model.rates)?;
    Ok(Estimate { wear, time, cost })
}

/// Simulates `path` in the stock of `spec` and costs it.
pub fn estimate(
    path: &Toolpath,
    spec: &AnalysisSpec,
    model: &CostModel,
    progress: &dyn Progress,
) -> Result<(Analysis, Estimate), CoreError> {
    estimate_from(path, spec, None, model, progress).map(|(analysis, estimate, _)| (analysis, estimate))
}

/// As [`estimate`], on the stock `start` another simulation left when given (see
/// [`crate::core::analysis::analyze_from`]), handing back the stock this one leaves.
pub fn estimate_from(
    path: &Toolpath,
    spec: &AnalysisSpec,
    start: Option<&KeptStock>,
    model: &CostModel,
    progress: &dyn Progress,
) -> Result<(Analysis, Estimate, Stack), CoreError> {
    let (analysis, wear, stack) = path_wear_from(path, spec, start, &model.life, progress)?;
    let estimate = estimate_with_wear(path, wear, model)?;
    Ok((analysis, estimate, stack))
}
