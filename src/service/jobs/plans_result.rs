//! The answer of a `plan` job, as the API documents it: the table of candidate tools, the
//! chosen tool's layers and steps, its tuning, the totals, and the baseline comparison (the
//! G-code is at the job's `program` link).

use super::costing_result::CutLengthDto;
use super::feeds_result::ProgramInfoDto;
use super::plans::{BaselinePrepared, PlanPrepared, RowRef};
use super::setup::NamedRef;
use super::trochoids_result::OverloadDto;
use crate::core::nc::WrittenProgram;
use crate::core::process::{
    overload_program_lines, Baseline, CandidateReport, CandidateStatus, Comparison, Figures, LayerReport, LayerRole,
    ProcessPlan, Step, Tuning, TuningOutcome,
};
use serde::Serialize;
use utoipa::ToSchema;

/// Lengths, times and tool consumption of a part of the job.
#[derive(Debug, Clone, Copy, Serialize, ToSchema)]
#[schema(as = PlanFigures)]
pub struct FiguresDto {
    pub feed_length_mm: f64,
    /// Feed moves that cut material, mm.
    pub cutting_length_mm: f64,
    pub rapid_length_mm: f64,
    /// Feed moves at their feeds and rapids at the rapid rate, min.
    pub nominal_time_min: f64,
    /// With the machine's acceleration and jerk limits, min.
    pub kinematic_time_min: f64,
    /// Share of one tool's life (L_t / L_f).
    pub consumption: f64,
}

impl From<Figures> for FiguresDto {
    fn from(f: Figures) -> Self {
        FiguresDto {
            feed_length_mm: f.feed_length_mm,
            cutting_length_mm: f.cutting_length_mm,
            rapid_length_mm: f.rapid_length_mm,
            nominal_time_min: f.nominal_time_min,
            kinematic_time_min: f.kinematic_time_min,
            consumption: f.consumption,
        }
    }
}

/// A candidate tool and what became of it.
#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct CandidateDto {
    pub tool_id: i64,
    pub name: String,
    pub diameter_mm: f64,
    /// `chosen`, `planned`, `cannot_reach`, `incomplete`, `unplannable` or `screened_out`
    /// (planned at the screening's coarse spacing only: its estimate could not win).
    #[schema(value_type = String)]
    pub status: CandidateStatus,
    pub reason: Option<String>,
    /// Area of the cavity out of the tool's reach, mm² (over the layers).
    pub unreachable_area_mm2: f64,
    /// At the standard force (before tuning).
    pub figures: Option<FiguresDto>,
    /// C = c_m·T_m + c_t·L_t/L_f (seed 002 Eq. 4) with the kinematic time, and its parts.
    pub cost: Option<f64>,
    pub machine_cost: Option<f64>,
    pub tool_cost: Option<f64>,
    pub trochoids: usize,
    pub z_cuts: usize,
    pub openings: usize,
    /// Largest engagement left outside the z-cut regions, deg.
    pub max_alpha_deg: Option<f64>,
    /// The cost estimated at the screening's coarse sample spacing, at the standard force
    /// (every candidate screened when more than one can reach the cavity).
    pub estimated_cost: Option<f64>,
    /// The screening's sample spacing, mm.
    pub screening_spacing_mm: Option<f64>,
}

/// A step of a layer.
#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct StepDto {
    /// `helical_boring`, `spiral_hole_expansion`, `trochoidal_grooving`, `z_cut_division`,
    /// `rough_side_cutting` or `intermediate_rough_side_cutting`.
    #[schema(value_type = String)]
    pub step: Step,
    #[serde(flatten)]
    pub figures: FiguresDto,
}

/// A layer of the chosen plan.
#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct LayerDto {
    pub index: usize,
    /// `rough` or `intermediate_rough`.
    #[schema(value_type = String)]
    pub role: LayerRole,
    pub z_top: f64,
    pub z_bottom: f64,
    /// The layer whose plan this one repeats lower down.
    pub copy_of: Option<usize>,
    pub trochoids: usize,
    pub z_cuts: usize,
    pub openings: usize,
    /// Engagement of the plain contour-parallel path, and of the plan, deg.
    pub base_max_alpha_deg: f64,
    pub max_alpha_deg: f64,
    /// No overload outside the z-cut regions, no gouge, nothing reachable left.
    pub verification_passed: bool,
    /// The stretches of samples of the full-depth moves above the engagement limit (outside
    /// the z-cut regions, or short spikes where the wall pass crosses them), each with its
    /// lines (at most 64 listed; all counted in `overload_stretches`).
    pub overloads: Vec<OverloadDto>,
    pub overload_stretches: usize,
    pub gouges: usize,
    pub uncleared_area_mm2: f64,
    pub removed_volume_mm3: f64,
    #[serde(flatten)]
    pub figures: FiguresDto,
    pub steps: Vec<StepDto>,
}

/// The tuning of the chosen tool (seed 002 §2.6).
#[derive(Debug, Clone, Copy, Serialize, ToSchema)]
pub struct TuningDto {
    /// `reached`, `limited_by_max_force`, `above_target_at_standard_force`, `closest` or `off`.
    #[schema(value_type = String)]
    pub outcome: TuningOutcome,
    pub target_consumption: f64,
    /// Target force over the standard force F*.
    pub force_factor: f64,
    pub standard_force_n: f64,
    pub target_force_n: f64,
    pub consumption_at_standard: f64,
    pub consumption: f64,
    pub tools_needed: usize,
    pub time_at_standard_min: f64,
    pub time_min: f64,
    pub evaluations: usize,
}

impl From<Tuning> for TuningDto {
    fn from(t: Tuning) -> Self {
        TuningDto {
            outcome: t.outcome,
            target_consumption: t.target_consumption,
            force_factor: t.force_factor,
            standard_force_n: t.standard_force_n,
            target_force_n: t.target_force_n,
            consumption_at_standard: t.consumption_at_standard,
            consumption: t.consumption,
            tools_needed: t.tools_needed,
            time_at_standard_min: t.time_at_standard_min,
            time_min: t.time_min,
            evaluations: t.evaluations,
        }
    }
}

/// The chosen plan's totals.
#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct TotalsDto {
    #[serde(flatten)]
    pub figures: FiguresDto,
    pub cost: f64,
    pub machine_cost: f64,
    pub tool_cost: f64,
    pub currency: String,
    pub removed_volume_mm3: f64,
    /// Over the kinematic time, cm³/min.
    pub removal_rate_cm3_min: f64,
    /// The length one tool lasts at this job's mix of cuts, along the tool-centre path and
    /// along the machined surface.
    pub equivalent_life: CutLengthDto,
}

/// The conventional baseline (seed 004 §3.3): its NC program is at
/// `GET /v1/jobs/{id}/program?part=baseline`.
#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct BaselineDto {
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
    pub figures: FiguresDto,
    /// The length one ball lasts at this baseline's mix of cuts, both ways.
    pub equivalent_life: CutLengthDto,
    pub cost: f64,
    pub removed_volume_mm3: f64,
    /// Its NC program, at `GET /v1/jobs/{id}/program?part=baseline`.
    pub program: ProgramInfoDto,
}

impl BaselineDto {
    fn new(b: &Baseline, prepared: &BaselinePrepared, program: &str) -> Self {
        BaselineDto {
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
            figures: b.figures.into(),
            equivalent_life: b.consumption.equivalent_life.into(),
            cost: b.cost.total,
            removed_volume_mm3: b.removed_volume_mm3,
            program: program_info(b.program.moves.len(), program),
        }
    }
}

/// The proposed plan over the baseline.
#[derive(Debug, Clone, Copy, Serialize, ToSchema)]
pub struct ComparisonDto {
    pub kinematic_time_ratio: f64,
    pub cutting_length_ratio: f64,
    pub cost_ratio: f64,
    pub time_saved_min: f64,
}

impl From<Comparison> for ComparisonDto {
    fn from(c: Comparison) -> Self {
        ComparisonDto {
            kinematic_time_ratio: c.kinematic_time_ratio,
            cutting_length_ratio: c.cutting_length_ratio,
            cost_ratio: c.cost_ratio,
            time_saved_min: c.time_saved_min,
        }
    }
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
    pub candidates: Vec<CandidateDto>,
    /// Tools of the type in 6–16 mm the database cannot plan with, and why.
    pub skipped: Vec<String>,
    /// The chosen candidate's tool id.
    pub chosen_tool_id: i64,
    pub layers: Vec<LayerDto>,
    pub tuning: TuningDto,
    pub totals: TotalsDto,
    pub baseline: Option<BaselineDto>,
    pub comparison: Option<ComparisonDto>,
    pub program: ProgramInfoDto,
    pub warnings: Vec<String>,
}

fn candidate(r: &CandidateReport, tool_id: i64) -> CandidateDto {
    CandidateDto {
        tool_id,
        name: r.name.clone(),
        diameter_mm: r.diameter_mm,
        status: r.status,
        reason: r.reason.clone(),
        unreachable_area_mm2: r.unreachable_area_mm2,
        figures: r.figures.map(Into::into),
        cost: r.cost,
        machine_cost: r.machine_cost,
        tool_cost: r.tool_cost,
        trochoids: r.trochoids,
        z_cuts: r.z_cuts,
        openings: r.openings,
        max_alpha_deg: r.max_alpha_deg,
        estimated_cost: r.estimated_cost,
        screening_spacing_mm: r.screening_spacing_mm,
    }
}

/// A written program of `moves` moves (a plan's paths are written as planned) in numbers.
fn program_info(moves: usize, text: &str) -> ProgramInfoDto {
    ProgramInfoDto { moves_in: moves, moves_out: moves, lines: text.lines().count(), bytes: text.len() }
}

fn layer(l: &LayerReport, program_lines: &[Option<(u32, u32)>]) -> LayerDto {
    LayerDto {
        index: l.index,
        role: l.role,
        z_top: l.z_top_mm,
        z_bottom: l.z_bottom_mm,
        copy_of: l.copy_of,
        trochoids: l.trochoids,
        z_cuts: l.z_cuts,
        openings: l.openings,
        base_max_alpha_deg: l.base_max_alpha_deg,
        max_alpha_deg: l.max_alpha_deg,
        verification_passed: l.verification_passed,
        overloads: l
            .overloads
            .iter()
            .enumerate()
            .map(|(i, o)| OverloadDto::new(o, program_lines.get(i).copied().flatten()))
            .collect(),
        overload_stretches: l.overload_stretches,
        gouges: l.gouges,
        uncleared_area_mm2: l.uncleared_area_mm2,
        removed_volume_mm3: l.figures.removed_volume_mm3,
        figures: l.figures.figures.into(),
        steps: l.figures.steps.iter().map(|s| StepDto { step: s.step, figures: s.figures.into() }).collect(),
    }
}

impl PlanResult {
    /// The result of `plan`, whose program is `program` (with the line of each of its
    /// moves) and its baseline's `baseline_program` (empty without a baseline).
    pub fn new(prepared: &PlanPrepared, plan: &ProcessPlan, program: &WrittenProgram, baseline_program: &str) -> Self {
        let e = &plan.evaluation;
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
                .map(|(r, c)| candidate(r, c.tool_id))
                .collect(),
            skipped: prepared.skipped.clone(),
            chosen_tool_id: prepared.candidates[plan.chosen].tool_id,
            layers: plan.layers.iter().zip(&overload_lines).map(|(l, lines)| layer(l, lines)).collect(),
            tuning: plan.tuning.into(),
            totals: TotalsDto {
                figures: e.total.into(),
                cost: e.cost.total,
                machine_cost: e.cost.machine,
                tool_cost: e.cost.tool,
                currency: e.cost.currency.clone(),
                removed_volume_mm3: e.removed_volume_mm3,
                removal_rate_cm3_min: e.removal_rate_cm3_min,
                equivalent_life: e.consumption.equivalent_life.into(),
            },
            baseline: plan
                .baseline
                .as_ref()
                .zip(prepared.baseline.as_ref())
                .map(|(b, p)| BaselineDto::new(b, p, baseline_program)),
            comparison: plan.comparison.map(Into::into),
            program: program_info(e.program.moves.len(), &program.text),
            warnings: plan.warnings.clone(),
        }
    }
}
