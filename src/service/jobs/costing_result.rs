//! The answer of a `costing` job, as the API documents it.

use super::analysis_result::{summary, SummaryDto};
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

/// Machining time, min (MODEL.md §10).
#[derive(Debug, Clone, Copy, Serialize, ToSchema)]
pub struct TimeDto {
    /// Feed moves at their feeds, rapids at the rapid rate, tool changes and dwells (the
    /// papers' prediction).
    pub nominal_min: f64,
    /// With the machine's feed, acceleration and jerk limits, look-ahead and the
    /// centripetal limit on arcs: never below the nominal time.
    pub kinematic_min: f64,
    pub kinematic_ratio: f64,
    pub feed_nominal_min: f64,
    pub feed_kinematic_min: f64,
    pub rapid_nominal_min: f64,
    pub rapid_kinematic_min: f64,
    pub tool_changes: usize,
    pub tool_change_min: f64,
    pub dwell_min: f64,
    /// Kinematic minus nominal time by cause, min.
    pub lost_to_feed_clamp_min: f64,
    pub lost_to_arc_limits_min: f64,
    pub lost_to_acceleration_min: f64,
    pub lost_to_jerk_min: f64,
    /// Junctions where a change of direction forces a lower speed.
    pub slowed_corners: usize,
    /// Junctions where the machine stops.
    pub exact_stops: usize,
}

impl From<&MachiningTime> for TimeDto {
    fn from(t: &MachiningTime) -> Self {
        TimeDto {
            nominal_min: t.nominal_min,
            kinematic_min: t.kinematic_min,
            kinematic_ratio: t.kinematic_ratio,
            feed_nominal_min: t.feed_nominal_min,
            feed_kinematic_min: t.feed_kinematic_min,
            rapid_nominal_min: t.rapid_nominal_min,
            rapid_kinematic_min: t.rapid_kinematic_min,
            tool_changes: t.tool_changes,
            tool_change_min: t.tool_change_min,
            dwell_min: t.dwell_min,
            lost_to_feed_clamp_min: t.breakdown.feed_clamp_min,
            lost_to_arc_limits_min: t.breakdown.arc_limit_min,
            lost_to_acceleration_min: t.breakdown.acceleration_min,
            lost_to_jerk_min: t.breakdown.jerk_min,
            slowed_corners: t.breakdown.slowed_corners,
            exact_stops: t.breakdown.exact_stops,
        }
    }
}

/// Wear on one NC line.
#[derive(Debug, Clone, Copy, Serialize, ToSchema)]
pub struct LineWearDto {
    pub line: u32,
    /// Share of the program's tool wear, 0–1.
    pub share: f64,
    pub cutting_length_mm: f64,
    pub max_alpha_deg: f64,
}

/// Wear at engagement angles in [from_deg, to_deg).
#[derive(Debug, Clone, Copy, Serialize, ToSchema)]
pub struct AlphaWearDto {
    pub from_deg: f64,
    pub to_deg: f64,
    /// Share of the program's tool wear, 0–1.
    pub share: f64,
    pub cutting_length_mm: f64,
}

/// A length of cut measured two ways, m: along the tool-centre path (what the program and
/// the simulation step along) and along the machined surface, which seed 003 measures tool
/// life by ("the total length of the machined workpiece surface"). On a concave arc the
/// surface is `R/(R − r)` times the centre path (twice at R/r = 2), on a straight cut
/// equal, on a convex arc shorter (MODEL.md §9).
#[derive(Debug, Clone, Copy, Serialize, ToSchema)]
pub struct CutLengthDto {
    pub centre_path_m: f64,
    pub machined_surface_m: f64,
}

impl From<CutLength> for CutLengthDto {
    fn from(c: CutLength) -> Self {
        CutLengthDto { centre_path_m: c.centre_path_m, machined_surface_m: c.machined_surface_m }
    }
}

/// How much of a tool the program uses (MODEL.md §9) and where.
#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct ToolLifeDto {
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
    pub cutting_length: CutLengthDto,
    /// The length one tool lasts at this program's mix of cuts, both ways: the cutting
    /// length over the consumption.
    pub equivalent_life: CutLengthDto,
    /// Share of the wear on samples whose force rests on the force model outside its
    /// experiments (see the analysis' `outside_model`), 0–1.
    pub extrapolated_share: f64,
    /// `true` when some of the consumption rests on extrapolated forces.
    pub extrapolated: bool,
    /// The lines that wear the tool most (at most 20), largest share first.
    pub by_line: Vec<LineWearDto>,
    pub by_alpha: Vec<AlphaWearDto>,
}

/// Cost (seed 002, Eq. 4): `C = c_m · T_m + c_t · L_t / L_f`, with `T_m` the kinematic
/// time.
#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct CostDto {
    /// c_m · T_m.
    pub machine: f64,
    /// c_m · T_m with the nominal time, as the papers estimated.
    pub machine_at_nominal_time: f64,
    /// c_t · L_t / L_f.
    pub tool: f64,
    pub total: f64,
    pub currency: String,
    pub machine_rate_per_hour: f64,
    pub tool_price: f64,
    /// `true` when the tool part rests on wear computed from forces outside the force
    /// model's experiments: an extrapolation.
    pub extrapolated: bool,
}

impl CostDto {
    /// The cost of `estimate` with the rates of `setup`.
    pub fn new(setup: &CostSetup, estimate: &Estimate) -> Result<CostDto, CoreError> {
        let Cost { machine, tool, total, currency } = estimate.cost.clone();
        Ok(CostDto {
            machine,
            machine_at_nominal_time: cost(estimate.time.nominal_min, 0.0, &setup.rates())?.machine,
            tool,
            total,
            currency,
            machine_rate_per_hour: setup.machine_rate_per_hour,
            tool_price: setup.tool_price,
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
    pub time: TimeDto,
    pub tool_life: ToolLifeDto,
    pub cost: CostDto,
    pub removed_volume_mm3: f64,
    /// Removed volume over the kinematic time, cm³/min.
    pub removal_rate_cm3_min: f64,
    /// The analysis of the program (engagement, force, critical regions).
    pub analysis: SummaryDto,
    pub warnings: Vec<String>,
}

impl CostingResult {
    pub fn new(
        prepared: CostingPrepared,
        path: &Toolpath,
        analysis: Analysis,
        estimate: Estimate,
    ) -> Result<CostingResult, CoreError> {
        let (wear, time) = (&estimate.wear, &estimate.time);
        let c = wear.consumption;
        let setup = &prepared.cost;
        let mut warnings = analysis.summary.warnings.clone();
        warnings.extend(time.warnings.iter().cloned());
        if setup.standard_force_n.is_none() {
            warnings.push("no force model: tool wear is not increased for forces above the standard".to_string());
        }
        let removed = analysis.summary.removed_volume_mm3;
        let regions = analysis.critical_regions.len();
        let base = prepared.base.clone();
        Ok(CostingResult {
            material: base.material,
            tool: base.tool,
            machine: base.machine,
            cost_rates: setup.cost_rates.clone(),
            force_model_id: base.force_model.map(|f| f.id),
            time: TimeDto::from(time),
            tool_life: ToolLifeDto {
                tool_life_id: setup.tool_life_id,
                consumption: c.ratio,
                worn_edge_arc_mm: c.worn_edge_arc_mm,
                life_edge_arc_mm: c.life_edge_arc_mm,
                standard_life_m: setup.life_m,
                cutting_length: CutLength::from_mm(c.cutting_length_mm, c.machined_surface_mm).into(),
                equivalent_life: c.equivalent_life.into(),
                extrapolated_share: wear.extrapolated_share,
                extrapolated: wear.extrapolated_share > 0.0,
                by_line: wear
                    .by_line
                    .iter()
                    .map(|&LineWear { line, share, cutting_length_mm, max_alpha_deg }| LineWearDto {
                        line,
                        share,
                        cutting_length_mm,
                        max_alpha_deg,
                    })
                    .collect(),
                by_alpha: wear
                    .by_alpha
                    .iter()
                    .map(|&AlphaWear { from_deg, to_deg, share, cutting_length_mm }| AlphaWearDto {
                        from_deg,
                        to_deg,
                        share,
                        cutting_length_mm,
                    })
                    .collect(),
            },
            cost: CostDto::new(setup, &estimate)?,
            removed_volume_mm3: removed,
            removal_rate_cm3_min: if time.kinematic_min > 0.0 {
                removed / MM3_PER_CM3 / time.kinematic_min
            } else {
                0.0
            },
            analysis: summary(path.moves.len(), analysis.summary, regions),
            warnings,
        })
    }
}
