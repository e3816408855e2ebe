//! The answer of a `costing` job: the core's machining time, wear and cost with the
//! database rows and rates they were computed with.

use super::analysis_result::PathSummary;
use super::costing::CostingPrepared;
use super::setup::CostSetup;
use super::setup::{NamedRef, ToolRef};
use crate::core::analysis::Analysis;
use crate::core::costing::cost::{cost, Cost};
use crate::core::costing::estimate::Estimate;
use crate::core::costing::wear::{AlphaWear, LineWear};
use crate::core::kinematics::MachiningTime;
use crate::core::tool_life::CutLength;
use crate::core::toolpath::Toolpath;
use crate::core::CoreError;
use serde::Serialize;
use utoipa::ToSchema;

/// mm³ per cm³.
const MM3_PER_CM3: f64 = 1000.0;

/// How much of a tool the program uses (MODEL.md §9) and where.
#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct ToolLifeUse {
    pub tool_life_id: i64,
    /// L_t / L_f: 1 is one whole tool.
    pub consumption: f64,
    /// Edge arc worn, mm (L_t).
    pub worn_edge_arc_mm: f64,
    /// The tool's life as edge arc, mm (L_f).
    pub life_edge_arc_mm: f64,
    /// The tool's life at standard straight cutting, m (both ways alike on a straight cut).
    pub standard_life_m: f64,
    /// The program's cutting length, both ways.
    pub cutting_length: CutLength,
    /// The length one tool lasts at this program's mix of cuts, both ways: the cutting
    /// length over the consumption.
    pub equivalent_life: CutLength,
    /// Share of the wear on samples whose force rests on the force model outside its
    /// experiments (see the analysis' `outside_model`), 0–1.
    pub extrapolated_share: f64,
    /// `true` when some of the consumption rests on extrapolated forces.
    pub extrapolated: bool,
    /// The lines that wear the tool most (at most 20), largest share first.
    pub by_line: Vec<LineWear>,
    pub by_alpha: Vec<AlphaWear>,
}

impl ToolLifeUse {
    fn new(setup: &CostSetup, estimate: &Estimate) -> Self {
        let wear = &estimate.wear;
        let c = wear.consumption;
        ToolLifeUse {
            tool_life_id: setup.tool_life_id,
            consumption: c.ratio,
            worn_edge_arc_mm: c.worn_edge_arc_mm,
            life_edge_arc_mm: c.life_edge_arc_mm,
            standard_life_m: setup.life.life_m,
            cutting_length: CutLength::from_mm(c.cutting_length_mm, c.machined_surface_mm),
            equivalent_life: c.equivalent_life,
            extrapolated_share: wear.extrapolated_share,
            extrapolated: wear.extrapolated_share > 0.0,
            by_line: wear.by_line.clone(),
            by_alpha: wear.by_alpha.clone(),
        }
    }
}

/// Cost (seed 002, Eq. 4): `C = c_m · T_m + c_t · L_t / L_f`, with `T_m` the kinematic
/// time: `machine` is c_m · T_m, `tool` c_t · L_t / L_f.
#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct CostReport {
    #[serde(flatten)]
    pub cost: Cost,
    /// c_m · T_m with the nominal time, as the papers estimated.
    pub machine_at_nominal_time: f64,
    pub machine_rate_per_hour: f64,
    pub tool_price: f64,
    /// `true` when the tool part rests on wear computed from forces outside the force
    /// model's experiments: an extrapolation.
    pub extrapolated: bool,
}

impl CostReport {
    /// The cost of `estimate` with the rates of `setup`.
    pub fn new(setup: &CostSetup, estimate: &Estimate) -> Result<CostReport, CoreError> {
        Ok(CostReport {
            cost: estimate.cost.clone(),
            machine_at_nominal_time: cost(estimate.time.nominal_min, 0.0, &setup.rates)?.machine,
            machine_rate_per_hour: setup.rates.machine_rate_per_hour,
            tool_price: setup.rates.tool_price,
            extrapolated: estimate.wear.extrapolated_share > 0.0,
        })
    }
}

/// The answer of a `costing` job.
#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct CostingResult {
    pub material: NamedRef,
    pub tool: ToolRef,
    pub machine: NamedRef,
    pub cost_rates: NamedRef,
    pub force_model_id: Option<i64>,
    /// Machining time, min (MODEL.md §10).
    pub time: MachiningTime,
    pub tool_life: ToolLifeUse,
    pub cost: CostReport,
    pub removed_volume_mm3: f64,
    /// Removed volume over the kinematic time, cm³/min.
    pub removal_rate_cm3_min: f64,
    /// The analysis of the program (engagement, force, critical regions).
    pub analysis: PathSummary,
    pub warnings: Vec<String>,
}

impl CostingResult {
    pub fn new(
        prepared: CostingPrepared,
        path: &Toolpath,
        analysis: Analysis,
        estimate: Estimate,
    ) -> Result<CostingResult, CoreError> {
        let setup = &prepared.cost;
        let mut warnings = analysis.summary.warnings.clone();
        warnings.extend(estimate.time.warnings.iter().cloned());
        if setup.life.standard_force_n.is_none() {
            warnings.push("no force model: tool wear is not increased for forces above the standard".to_string());
        }
        let removed = analysis.summary.removed_volume_mm3;
        let kinematic_min = estimate.time.kinematic_min;
        let regions = analysis.critical_regions.len();
        let base = prepared.base.clone();
        Ok(CostingResult {
            material: base.material,
            tool: base.tool,
            machine: base.machine,
            cost_rates: setup.cost_rates.clone(),
            force_model_id: base.force_model.map(|f| f.id),
            tool_life: ToolLifeUse::new(setup, &estimate),
            cost: CostReport::new(setup, &estimate)?,
            time: estimate.time,
            removed_volume_mm3: removed,
            removal_rate_cm3_min: if kinematic_min > 0.0 { removed / MM3_PER_CM3 / kinematic_min } else { 0.0 },
            analysis: PathSummary::new(path.moves.len(), analysis.summary, regions),
            warnings,
        })
    }
}
