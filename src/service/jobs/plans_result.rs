//! The answer of a `plan` job: the core's table of candidate tools, the chosen tool's
//! layers and steps, its tuning and the comparison with the baseline, with the database
//! rows they were planned with, the totals and the written programs in numbers (the G-code
//! is at the job's `program` link).

use super::feeds_result::ProgramInfo;
use super::plans::{BaselinePrepared, PlanPrepared, RowRef};
use super::setup::NamedRef;
use super::trochoids_result::OverloadReport;
use crate::core::analysis::rest::RestMaterial;
use crate::core::nc::WrittenProgram;
use crate::core::process::{
    overload_program_lines, Baseline, CandidateReport, Comparison, Figures, LayerReport, ProcessPlan, StairStep, Tuning,
};
use crate::core::tool_life::CutLength;
use serde::Serialize;
use utoipa::ToSchema;

/// A candidate tool and what became of it.
#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct Candidate {
    pub tool_id: i64,
    #[serde(flatten)]
    pub report: CandidateReport,
}

/// A layer of the chosen plan, its overloads with the lines of the job's program.
#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct PlanLayer {
    #[serde(flatten)]
    pub report: LayerReport,
    /// The stretches of samples of the full-depth moves above the engagement limit (outside
    /// the z-cut regions, or short spikes where the wall pass crosses them), each with its
    /// lines (at most 64 listed; all counted in `overload_stretches`).
    pub overloads: Vec<OverloadReport>,
}

/// The chosen plan's totals: its roughing and its stair-step roughing (lengths, times, cost
/// and removed volume); the consumption and the equivalent life are the roughing tool's (the
/// stair step's tool has its own, in `stair_step`).
#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct PlanTotals {
    #[serde(flatten)]
    pub figures: Figures,
    pub cost: f64,
    pub machine_cost: f64,
    pub tool_cost: f64,
    pub currency: String,
    pub removed_volume_mm3: f64,
    /// Over the kinematic time, cm³/min.
    pub removal_rate_cm3_min: f64,
    /// The length one tool lasts at this job's mix of cuts, along the tool-centre path and
    /// along the machined surface.
    pub equivalent_life: CutLength,
}

/// The conventional baseline (seed 004 §3.3): its NC program is at
/// `GET /v1/jobs/{id}/program?part=baseline`.
#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct PlanBaseline {
    pub tool: String,
    pub diameter_mm: f64,
    pub levels: usize,
    /// Circles cut before the sharp corners of its rings, over all levels, so that each
    /// corner is cut in two steps (seed 004 §3.3, Fig. 11).
    pub corner_loops: usize,
    pub axial_depth_mm: f64,
    pub radial_depth_mm: f64,
    pub spindle_rpm: f64,
    pub fz_mm: f64,
    pub feed_mm_min: f64,
    /// The `conventional_ball_roughing` row of `/v1/conditions/standard` the baseline is cut
    /// at (null in jobs stored before it was kept): the seeded R5 row's fz is `inferred` from
    /// seed 004 Table 4 (MODEL.md §5), since Table 3's fz 0.05 contradicts it.
    pub conditions: Option<RowRef>,
    #[serde(flatten)]
    pub figures: Figures,
    /// The length one ball lasts at this baseline's mix of cuts, both ways.
    pub equivalent_life: CutLength,
    pub cost: f64,
    pub removed_volume_mm3: f64,
    /// Its NC program, at `GET /v1/jobs/{id}/program?part=baseline`.
    pub program: ProgramInfo,
}

impl PlanBaseline {
    fn new(b: &Baseline, prepared: &BaselinePrepared, program: &str) -> Self {
        PlanBaseline {
            tool: b.tool.clone(),
            diameter_mm: b.diameter_mm,
            levels: b.levels,
            corner_loops: b.corner_loops,
            axial_depth_mm: b.axial_depth_mm,
            radial_depth_mm: b.radial_depth_mm,
            spindle_rpm: prepared.conditions.spindle_rpm,
            fz_mm: prepared.conditions.fz_mm,
            feed_mm_min: b.feed_mm_min,
            conditions: prepared.conditions_row.clone(),
            figures: b.figures,
            equivalent_life: b.consumption.equivalent_life,
            cost: b.cost.total,
            removed_volume_mm3: b.removed_volume_mm3,
            program: ProgramInfo::new(b.program.moves.len(), b.program.moves.len(), program),
        }
    }
}

/// The stair-step roughing after the chosen tool's: its program is the plan's program's
/// last part, after the tool change to it.
#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct PlanStairStep {
    /// The tool's id in the database.
    pub tool_id: i64,
    #[serde(flatten)]
    pub step: StairStep,
}

/// The result of a plan job.
#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct PlanResult {
    pub material: NamedRef,
    pub machine: NamedRef,
    pub cost_rates: NamedRef,
    pub cavity_volume_mm3: f64,
    /// Smallest concave radius of the walls, mm (0: sharp corners).
    pub min_concave_radius_mm: Option<f64>,
    pub candidates: Vec<Candidate>,
    /// Tools of the type in 6–16 mm the database cannot plan with, and why.
    pub skipped: Vec<String>,
    /// The chosen candidate's tool id.
    pub chosen_tool_id: i64,
    pub layers: Vec<PlanLayer>,
    pub tuning: Tuning,
    pub totals: PlanTotals,
    /// The stair-step roughing (null: the layers leave no steps, or it was turned off; a
    /// warning says when its tool cannot be planned with).
    pub stair_step: Option<PlanStairStep>,
    pub baseline: Option<PlanBaseline>,
    /// The proposed plan over the baseline.
    pub comparison: Option<Comparison>,
    pub program: ProgramInfo,
    /// The material the chosen plan leaves in the cavity, per slice (the corners and necks
    /// its tool cannot reach), as its layers' verifications simulated it: the stock the job
    /// keeps for another job to start from (`"stock": {"from_job": …}`). Null, with a
    /// warning, when no stock could be kept.
    pub rest_material: Option<RestMaterial>,
    pub warnings: Vec<String>,
}

fn layer(l: &LayerReport, program_lines: &[Option<(u32, u32)>]) -> PlanLayer {
    let overloads = l
        .overloads
        .iter()
        .enumerate()
        .map(|(i, o)| OverloadReport::new(o, program_lines.get(i).copied().flatten()))
        .collect();
    PlanLayer { report: l.clone(), overloads }
}

impl PlanResult {
    /// The result of `plan`, whose program is `program` (with the line of each of its
    /// moves) and its baseline's `baseline_program` (empty without a baseline).
    pub fn new(prepared: &PlanPrepared, plan: &ProcessPlan, program: &WrittenProgram, baseline_program: &str) -> Self {
        let (e, w) = (&plan.evaluation, &plan.whole);
        let overload_lines = overload_program_lines(plan, &program.move_lines);
        PlanResult {
            material: prepared.material.clone(),
            machine: prepared.machine.clone(),
            cost_rates: prepared.cost_rates.clone(),
            cavity_volume_mm3: plan.cavity_volume_mm3,
            min_concave_radius_mm: plan.min_concave_radius_mm,
            candidates: plan
                .candidates
                .iter()
                .zip(&prepared.candidates)
                .map(|(r, c)| Candidate { tool_id: c.tool_id, report: r.clone() })
                .collect(),
            skipped: prepared.skipped.clone(),
            chosen_tool_id: prepared.candidates[plan.chosen].tool_id,
            layers: plan.layers.iter().zip(&overload_lines).map(|(l, lines)| layer(l, lines)).collect(),
            tuning: plan.tuning,
            totals: PlanTotals {
                figures: w.figures,
                cost: w.cost.total,
                machine_cost: w.cost.machine,
                tool_cost: w.cost.tool,
                currency: w.cost.currency.clone(),
                removed_volume_mm3: w.removed_volume_mm3,
                removal_rate_cm3_min: w.removal_rate_cm3_min,
                equivalent_life: e.consumption.equivalent_life,
            },
            stair_step: plan
                .stair_step
                .as_ref()
                .zip(prepared.stair_step.as_ref())
                .map(|(step, p)| PlanStairStep { tool_id: p.tool_id, step: step.clone() }),
            baseline: plan
                .baseline
                .as_ref()
                .zip(prepared.baseline.as_ref())
                .map(|(b, p)| PlanBaseline::new(b, p, baseline_program)),
            comparison: plan.comparison,
            program: ProgramInfo::new(program.move_lines.len(), program.move_lines.len(), &program.text),
            rest_material: plan.stock.as_ref().map(|s| s.rest.clone()),
            warnings: plan.warnings.clone(),
        }
    }
}
