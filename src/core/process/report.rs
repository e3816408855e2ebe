//! What the process planner returns: the table of candidates, the chosen tool's plan per
//! layer and step, its tuning, the program, and the comparison with the baseline.

use super::baseline::Baseline;
use super::cavity::{Cavity, LayerRole};
use super::evaluate::{Evaluation, Figures, LayerFigures};
use super::layer::LayerPlan;
use super::spec::ToolCandidate;
use super::stair_step::StairStep;
use super::tune::Tuning;
use crate::core::costing::cost::Cost;
use crate::core::insertion::{Overload, TreatmentKind, Verification};
use serde::Serialize;

/// Uncleared area below this counts as cleared, mm² per layer (the coverage raster's noise).
pub const UNCLEARED_TOLERANCE_MM2: f64 = 1.0;

/// What became of a candidate.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, utoipa::ToSchema)]
#[serde(rename_all = "snake_case")]
pub enum CandidateStatus {
    /// Planned and the cheapest: the job's tool.
    Chosen,
    /// Planned completely, but dearer.
    Planned,
    /// Too large for some of the cavity (not planned).
    CannotReach,
    /// Planned, but the plan gouges a wall or leaves material.
    Incomplete,
    /// The planner could not plan it (see the reason).
    Unplannable,
    /// Planned at a coarse sample spacing only: its estimate could not beat the chosen plan
    /// (see `estimated_cost` and the reason).
    ScreenedOut,
}

/// One row of the table of candidates: a candidate tool and what became of it.
#[derive(Debug, Clone, PartialEq, Serialize, utoipa::ToSchema)]
pub struct CandidateReport {
    pub name: String,
    pub diameter_mm: f64,
    /// The end mill's type (plans rough with square and radius end mills).
    pub tool_type: crate::core::tool::ToolType,
    /// Its corner radius, mm (0 for a square end mill).
    pub corner_radius_mm: f64,
    pub status: CandidateStatus,
    pub reason: Option<String>,
    /// Area of the cavity the tool cannot reach, mm² (over the layers).
    pub unreachable_area_mm2: f64,
    /// At the standard force, before tuning.
    pub figures: Option<Figures>,
    /// C = c_m·T_m + c_t·L_t/L_f (seed 002 Eq. 4) with the kinematic time, and its parts.
    pub cost: Option<f64>,
    pub machine_cost: Option<f64>,
    pub tool_cost: Option<f64>,
    /// Trochoids, z-cut stretches and openings over all layers.
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

impl CandidateReport {
    pub(super) fn new(c: &ToolCandidate, unreachable_area_mm2: f64) -> Self {
        CandidateReport {
            name: c.name.clone(),
            diameter_mm: c.tool.diameter_mm,
            tool_type: c.tool.tool_type,
            corner_radius_mm: c.tool.corner_radius_mm,
            status: CandidateStatus::Planned,
            reason: None,
            unreachable_area_mm2,
            figures: None,
            cost: None,
            machine_cost: None,
            tool_cost: None,
            trochoids: 0,
            z_cuts: 0,
            openings: 0,
            max_alpha_deg: None,
            estimated_cost: None,
            screening_spacing_mm: None,
        }
    }

    /// Counts the treatments and marks the candidate incomplete when a layer's plan gouges
    /// or leaves material.
    pub(super) fn check_layers(&mut self, layers: &[LayerPlan]) {
        let mut max_alpha: f64 = 0.0;
        for l in layers {
            let plan = &l.insertion;
            let count = |k: TreatmentKind| plan.treatments.iter().filter(|t| t.kind == k).count();
            self.trochoids += count(TreatmentKind::Trochoid);
            self.z_cuts += count(TreatmentKind::ZCut);
            self.openings += count(TreatmentKind::Opening);
            let v: &Verification = &plan.verification;
            max_alpha = max_alpha.max(v.outside_zcut.max_alpha_deg);
            if self.status == CandidateStatus::Incomplete {
                continue;
            }
            if v.gouges > 0 {
                self.status = CandidateStatus::Incomplete;
                self.reason = Some(format!("layer {}: the path comes closer to a wall than allowed", l.index));
            } else if v.uncleared_area_mm2 > UNCLEARED_TOLERANCE_MM2 {
                self.status = CandidateStatus::Incomplete;
                self.reason = Some(format!(
                    "layer {}: leaves {:.1} mm² the tool could reach uncut, near {:?}",
                    l.index, v.uncleared_area_mm2, v.uncleared_at
                ));
            }
        }
        self.max_alpha_deg = Some(max_alpha);
    }

    pub(super) fn set_figures(&mut self, e: &Evaluation) {
        self.figures = Some(e.total);
        self.cost = Some(e.cost.total);
        self.machine_cost = Some(e.cost.machine);
        self.tool_cost = Some(e.cost.tool);
    }
}

/// One layer of the chosen plan.
#[derive(Debug, Clone, PartialEq, Serialize, utoipa::ToSchema)]
pub struct LayerReport {
    pub index: usize,
    pub role: LayerRole,
    #[serde(rename = "z_top")]
    pub z_top_mm: f64,
    #[serde(rename = "z_bottom")]
    pub z_bottom_mm: f64,
    /// The layer above whose plan this one repeats lower down, if any.
    pub copy_of: Option<usize>,
    /// Trochoids, z-cut stretches and openings.
    pub trochoids: usize,
    pub z_cuts: usize,
    pub openings: usize,
    /// Engagement of the contour-parallel path before and after the treatments, deg.
    pub base_max_alpha_deg: f64,
    pub max_alpha_deg: f64,
    /// No overload outside the z-cut regions, no gouge, nothing reachable left.
    pub verification_passed: bool,
    /// The stretches of samples of the full-depth moves above the limit (outside the z-cut
    /// regions, or short spikes where the wall pass crosses them), with the layer program's
    /// moves, and how many (reported with the lines of the written program).
    #[serde(skip)]
    pub overloads: Vec<Overload>,
    pub overload_stretches: usize,
    pub gouges: usize,
    pub uncleared_area_mm2: f64,
    #[serde(flatten)]
    pub figures: LayerFigures,
}

/// The proposed plan against the baseline.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, utoipa::ToSchema)]
pub struct Comparison {
    /// Proposed over baseline.
    pub kinematic_time_ratio: f64,
    pub cutting_length_ratio: f64,
    pub cost_ratio: f64,
    /// Baseline time less the proposed time, min.
    pub time_saved_min: f64,
}

/// The whole result.
#[derive(Debug, Clone)]
pub struct ProcessPlan {
    pub candidates: Vec<CandidateReport>,
    /// Index of the chosen candidate.
    pub chosen: usize,
    pub layers: Vec<LayerReport>,
    /// The chosen tool's job at the tuned conditions (its program included).
    pub evaluation: Evaluation,
    pub tuning: Tuning,
    pub baseline: Option<Baseline>,
    pub comparison: Option<Comparison>,
    pub cavity_volume_mm3: f64,
    pub min_concave_radius_mm: Option<f64>,
    pub warnings: Vec<String>,
    /// The stock the chosen plan leaves in the cavity, and its rest material (`None`, with
    /// a warning, where it cannot be kept).
    pub stock: Option<super::kept_layers::PlanStock>,
    /// The stair-step roughing after the chosen tool's (`None`: not asked for, or no steps).
    pub stair_step: Option<StairStep>,
    /// The whole job, the stair step included.
    pub whole: Whole,
}

/// What a plan is assembled from, besides its cavity and layers.
pub(super) struct Parts {
    pub candidates: Vec<CandidateReport>,
    pub chosen: usize,
    pub evaluation: Evaluation,
    pub tuning: Tuning,
    pub baseline: Option<Baseline>,
    pub stair_step: Option<StairStep>,
    pub warnings: Vec<String>,
}

pub(super) fn assemble(cavity: &Cavity, layers: &[LayerPlan], parts: Parts) -> ProcessPlan {
    let Parts { candidates, chosen, evaluation, tuning, baseline, stair_step, mut warnings } = parts;
    let layer_reports = layers
        .iter()
        .zip(&evaluation.layers)
        .map(|(l, figures)| {
            let plan = &l.insertion;
            let count = |k: TreatmentKind| plan.treatments.iter().filter(|t| t.kind == k).count();
            let v = &plan.verification;
            LayerReport {
                index: l.index,
                role: l.role,
                z_top_mm: l.z_top_mm,
                z_bottom_mm: l.z_bottom_mm,
                copy_of: l.copy_of,
                trochoids: count(TreatmentKind::Trochoid),
                z_cuts: count(TreatmentKind::ZCut),
                openings: count(TreatmentKind::Opening),
                base_max_alpha_deg: plan.base_max_alpha_deg,
                max_alpha_deg: v.outside_zcut.max_alpha_deg,
                verification_passed: v.passed,
                overloads: v.overloads.clone(),
                overload_stretches: v.overload_stretches,
                gouges: v.gouges,
                uncleared_area_mm2: v.uncleared_area_mm2,
                figures: figures.clone(),
            }
        })
        .collect();
    for l in layers.iter().filter(|l| l.copy_of.is_none()) {
        warnings.extend(l.insertion.warnings.iter().map(|w| format!("layer {}: {w}", l.index)));
    }
    warnings.extend(evaluation.warnings.iter().cloned());
    let whole = Whole::of(&evaluation, stair_step.as_ref());
    let comparison = baseline.as_ref().map(|b| {
        let ratio = |a: f64, b: f64| if b > 0.0 { a / b } else { 0.0 };
        Comparison {
            kinematic_time_ratio: ratio(whole.figures.kinematic_time_min, b.figures.kinematic_time_min),
            cutting_length_ratio: ratio(whole.figures.cutting_length_mm, b.figures.cutting_length_mm),
            cost_ratio: ratio(whole.cost.total, b.cost.total),
            time_saved_min: b.figures.kinematic_time_min - whole.figures.kinematic_time_min,
        }
    });
    ProcessPlan {
        candidates,
        chosen,
        layers: layer_reports,
        evaluation,
        tuning,
        baseline,
        comparison,
        cavity_volume_mm3: cavity.volume_mm3(),
        min_concave_radius_mm: cavity.min_concave_radius_mm(),
        warnings,
        stock: None,
        stair_step,
        whole,
    }
}

/// The whole job: the chosen tool's roughing and, after it, the stair-step roughing.
#[derive(Debug, Clone, PartialEq)]
pub struct Whole {
    /// Lengths and times of both; the consumption is the roughing tool's (the stair step's
    /// own tool has its own, in [`StairStep`]).
    pub figures: Figures,
    pub cost: Cost,
    pub removed_volume_mm3: f64,
    /// Over the kinematic time, cm³/min.
    pub removal_rate_cm3_min: f64,
}

impl Whole {
    /// The whole of `evaluation` and, if planned, `stair_step`.
    pub fn of(evaluation: &Evaluation, stair_step: Option<&StairStep>) -> Whole {
        let mut figures = evaluation.total;
        let mut cost = evaluation.cost.clone();
        let mut removed_volume_mm3 = evaluation.removed_volume_mm3;
        if let Some(s) = stair_step {
            let consumption = figures.consumption;
            figures.add(&s.figures);
            figures.consumption = consumption;
            cost.machine += s.cost.machine;
            cost.tool += s.cost.tool;
            cost.total += s.cost.total;
            removed_volume_mm3 += s.removed_volume_mm3;
        }
        let removal_rate_cm3_min = if figures.kinematic_time_min > 0.0 {
            removed_volume_mm3 / 1000.0 / figures.kinematic_time_min
        } else {
            0.0
        };
        Whole { figures, cost, removed_volume_mm3, removal_rate_cm3_min }
    }
}
