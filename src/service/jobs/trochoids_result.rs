//! The answer of a `trochoids` job: the core's treatments and checks with the database rows
//! and conditions they were planned with, the medial axis with its classes as plain
//! arrays, the overloads with the lines of the written program, and the new path as JSON
//! moves (the G-code is at the job's `program` link).

use super::costing_result::CostReport;
use super::feeds_result::ProgramInfo;
use super::setup::CostSetup;
use super::setup::{NamedRef, ToolRef};
use super::trochoids::TrochoidsPrepared;
use crate::core::analysis::engine::SampleResult;
use crate::core::conditions::CuttingConditions;
use crate::core::costing::estimate::estimate_with_wear;
use crate::core::costing::wear::{WearCounter, WearReport};
use crate::core::insertion::{InsertionPlan, Overload, SampleObserver, Treatment, Verification};
use crate::core::kinematics::{machining_time, MachineLimits, TimeOptions};
use crate::core::medial::{ClassInterval, CriticalInterval, NodeKind};
use crate::core::nc::{toolpath_to_json, JsonProgram, WrittenProgram};
use crate::core::tool_life::ToolLifeModel;
use crate::core::toolpath::Toolpath;
use crate::core::CoreError;
use serde::Serialize;
use utoipa::ToSchema;

/// Cutting conditions used.
#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct UsedConditions {
    #[serde(flatten)]
    pub conditions: CuttingConditions,
    /// Where they come from.
    pub source: String,
}

/// A node of the medial axis.
#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct AxisNodeReport {
    pub x: f64,
    pub y: f64,
    /// Clearance radius R, mm.
    pub clearance_mm: f64,
    pub kind: NodeKind,
}

/// A branch of the medial axis.
#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct AxisBranchReport {
    pub start_node: usize,
    pub end_node: usize,
    pub closed: bool,
    pub length_mm: f64,
    /// `[x, y, R]` of every point, mm.
    pub points: Vec<[f64; 3]>,
    /// Its stretches by radius-ratio class (seed 004 §2.3), in order.
    pub classes: Vec<ClassInterval>,
}

/// The medial axis graph (seed 004 §2.1).
#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct AxisReport {
    /// Boundary sampling step, mm.
    pub step_mm: f64,
    pub nodes: Vec<AxisNodeReport>,
    pub branches: Vec<AxisBranchReport>,
}

impl AxisReport {
    fn new(plan: &InsertionPlan) -> Self {
        let branches = plan
            .axis
            .branches
            .iter()
            .enumerate()
            .map(|(i, b)| AxisBranchReport {
                start_node: b.start_node,
                end_node: b.end_node,
                closed: b.closed,
                length_mm: b.length_mm,
                points: b.points.iter().map(|p| [p.point.x, p.point.y, p.clearance_mm]).collect(),
                classes: plan
                    .classes
                    .iter()
                    .filter(|c| c.branch == i)
                    .flat_map(|c| c.intervals.iter().copied())
                    .collect(),
            })
            .collect();
        let nodes = plan
            .axis
            .nodes
            .iter()
            .map(|n| AxisNodeReport {
                x: n.point.point.x,
                y: n.point.point.y,
                clearance_mm: n.point.clearance_mm,
                kind: n.kind,
            })
            .collect();
        AxisReport { step_mm: plan.axis.step_mm, nodes, branches }
    }
}

/// A stretch of consecutive samples above the engagement limit (a short spike at a corner
/// of a wall pass is a few samples long).
#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct OverloadReport {
    /// First and last line of the job's program (`GET /v1/jobs/{id}/program`) it spans.
    pub program_lines: Option<[u32; 2]>,
    /// First and last move (1-based) of the planned path (of the layer's own plan, in a
    /// plan; the line of the given program, for a given path).
    pub layer_moves: [u32; 2],
    pub samples: usize,
    pub length_mm: f64,
    /// The largest engagement, deg, and where it is (mm; z of the layer's plan, before a
    /// copy of the layer moves down).
    pub max_alpha_deg: f64,
    pub x: f64,
    pub y: f64,
    pub z: f64,
    /// In a region the z-cut division cleared, but on a move at the full depth.
    pub in_zcut_region: bool,
}

impl OverloadReport {
    pub fn new(o: &Overload, program_lines: Option<(u32, u32)>) -> Self {
        OverloadReport {
            program_lines: program_lines.map(|(a, b)| [a, b]),
            layer_moves: [o.line_from, o.line_to],
            samples: o.samples,
            length_mm: o.length_mm,
            max_alpha_deg: o.peak.value,
            x: o.peak.x_mm,
            y: o.peak.y_mm,
            z: o.peak.z_mm,
            in_zcut_region: o.in_zcut_region,
        }
    }
}

/// The checks of the new path by the full simulation, its overloads with the lines of the
/// job's program.
#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct VerificationReport {
    #[serde(flatten)]
    pub verification: Verification,
    /// The stretches of samples of the full-depth moves above the limit (outside the z-cut
    /// regions, or crossing them), each with its lines (at most 64 listed; all counted in
    /// `overload_stretches`).
    pub overloads: Vec<OverloadReport>,
}

/// Lengths, times, tool use and cost of one program, as the costing gives them (MODEL.md
/// §9 and §10).
#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct ProgramFigures {
    /// Length of the feed moves, mm.
    pub feed_length_mm: f64,
    /// Length of the rapid moves, mm.
    pub rapid_length_mm: f64,
    /// Feed moves at their programmed feeds, rapids at the rapid rate, tool changes and
    /// dwells, min.
    pub nominal_time_min: f64,
    /// With the machine's feed, acceleration and jerk limits, min.
    pub kinematic_time_min: f64,
    /// Length of the feed moves that cut nothing (the stock simulation's), mm; null
    /// without tool-life data for the tool in the material (the simulation runs with the
    /// costing).
    pub air_cut_length_mm: Option<f64>,
    /// Share of one tool's life the program uses (seed 002 Eq. 2–3 with MODEL.md §9);
    /// null without tool-life data.
    pub consumption: Option<f64>,
    /// The costing's cost, `C = c_m·T_m + c_t·L_t/L_f` with the kinematic time (seed 002
    /// Eq. 4), at the first cost rates and the tool's price; null without tool-life data.
    pub cost: Option<CostReport>,
}

impl ProgramFigures {
    /// The figures of `path` on a machine of `limits`, with its wear and cost when
    /// `costed` is given (its wear and air cut, counted on its simulation, costed by
    /// `setup`).
    pub fn of(
        path: &Toolpath,
        limits: &MachineLimits,
        costed: Option<(&CostSetup, Counted)>,
    ) -> Result<Self, CoreError> {
        let t = machining_time(path, limits, &TimeOptions::default())?;
        let mut figures = ProgramFigures {
            feed_length_mm: t.feed_length_mm,
            rapid_length_mm: t.rapid_length_mm,
            nominal_time_min: t.nominal_min,
            kinematic_time_min: t.kinematic_min,
            air_cut_length_mm: None,
            consumption: None,
            cost: None,
        };
        if let Some((setup, counted)) = costed {
            let estimate = estimate_with_wear(path, counted.wear, &setup.cost_model())?;
            figures.air_cut_length_mm = Some(counted.air_cut_mm);
            figures.consumption = Some(estimate.wear.consumption.ratio);
            figures.cost = Some(CostReport::new(setup, &estimate)?);
        }
        Ok(figures)
    }
}

/// What one program's simulation gave for its cost: its wear and its air cut, mm.
pub struct Counted {
    pub wear: WearReport,
    pub air_cut_mm: f64,
}

/// Counts the wear of the base path and of the finished program from the insertion's own
/// simulations of them (the base check and the last verification), so that
/// costing them simulates nothing again.
pub struct WearObserver<'a> {
    model: &'a ToolLifeModel,
    flutes: u32,
    default_rpm: Option<f64>,
    base: WearCounter<'a>,
    planned: WearCounter<'a>,
}

impl<'a> WearObserver<'a> {
    /// Counts with the tool life `model` for a tool of `flutes` turning at `default_rpm`
    /// where the program has no S word (the insertion's analysis spec).
    pub fn new(model: &'a ToolLifeModel, flutes: u32, default_rpm: Option<f64>) -> Self {
        let counter = || WearCounter::new(model, flutes, default_rpm);
        WearObserver { model, flutes, default_rpm, base: counter(), planned: counter() }
    }

    /// The base path's and the finished program's counts, with their air cuts from `plan`.
    pub fn finish(self, plan: &InsertionPlan) -> (Counted, Counted) {
        (
            Counted { wear: self.base.finish(), air_cut_mm: plan.base_air_cut_length_mm },
            Counted { wear: self.planned.finish(), air_cut_mm: plan.air_cut_length_mm },
        )
    }
}

impl SampleObserver for WearObserver<'_> {
    fn base(&mut self, sample: &SampleResult) {
        self.base.add(sample);
    }

    fn restart(&mut self) {
        self.planned = WearCounter::new(self.model, self.flutes, self.default_rpm);
    }

    fn verified(&mut self, sample: &SampleResult) {
        self.planned.add(sample);
    }
}

/// What the insertion changes: the base path's figures and the planned path's.
#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct ChangeFigures {
    /// The base path (generated or given), before the insertion.
    pub before: ProgramFigures,
    /// The planned path, with its trochoids and z-cut passes.
    pub after: ProgramFigures,
    /// The cost rates of the costs (null without tool-life data: no wear or cost).
    pub cost_rates: Option<NamedRef>,
}

impl ChangeFigures {
    /// The figures of `plan`'s base path and planned path on a machine of `limits`, with
    /// their wear and cost when `costed` is given (costed by the setup, from the counts of
    /// the base path and the planned path).
    pub fn of(
        plan: &InsertionPlan,
        limits: &MachineLimits,
        costed: Option<(&CostSetup, (Counted, Counted))>,
    ) -> Result<Self, CoreError> {
        let (setup, before, after) = match costed {
            Some((setup, (before, after))) => (Some(setup), Some(before), Some(after)),
            None => (None, None, None),
        };
        Ok(ChangeFigures {
            before: ProgramFigures::of(&plan.drawing.base_path, limits, setup.zip(before))?,
            after: ProgramFigures::of(&plan.toolpath, limits, setup.zip(after))?,
            cost_rates: setup.map(|s| s.cost_rates.clone()),
        })
    }
}

/// The answer of a `trochoids` job.
#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct TrochoidsResult {
    pub material: NamedRef,
    pub tool: ToolRef,
    pub machine: NamedRef,
    pub roughing: UsedConditions,
    pub grooving: UsedConditions,
    /// `generated` (contour-parallel) or `given` (the request's program).
    pub base_path: String,
    /// The base path's largest engagement and its samples above the limit.
    pub base_max_alpha_deg: f64,
    pub base_overloaded_samples: usize,
    pub axis: AxisReport,
    /// Where the base path overloads the tool, on the axis.
    pub critical: Vec<CriticalInterval>,
    /// Overloaded samples not near the axis (links, entries).
    pub off_axis_samples: usize,
    pub treatments: Vec<Treatment>,
    /// Cutting levels, top first, mm.
    pub levels_mm: Vec<f64>,
    /// Length of the base path left out where the trochoids had cleared, mm; the straight
    /// links and hops written instead.
    pub trimmed_mm: f64,
    pub relinks: usize,
    pub hops: usize,
    pub verification: VerificationReport,
    pub rounds: usize,
    pub pocket_area_mm2: f64,
    pub program: ProgramInfo,
    /// Lengths and times before and after the insertion, on the job's machine (null in
    /// jobs queued before it was kept).
    pub figures: Option<ChangeFigures>,
    /// The new path as JSON moves (the form `program.moves` of other jobs accepts).
    #[schema(value_type = Object)]
    pub path: JsonProgram,
    pub warnings: Vec<String>,
}

impl TrochoidsResult {
    pub fn new(
        prepared: TrochoidsPrepared,
        given: bool,
        program: &WrittenProgram,
        plan: InsertionPlan,
        figures: Option<ChangeFigures>,
    ) -> Self {
        let overloads = plan
            .verification
            .overloads
            .iter()
            .map(|o| {
                let moves = plan.toolpath.moves.iter().zip(program.move_lines.iter().copied());
                OverloadReport::new(o, o.written_lines(moves))
            })
            .collect();
        let used = |conditions, source| UsedConditions { conditions, source };
        TrochoidsResult {
            roughing: used(prepared.roughing, prepared.roughing_source),
            grooving: used(prepared.grooving, prepared.grooving_source),
            material: prepared.base.material,
            tool: prepared.base.tool,
            machine: prepared.base.machine,
            base_path: if given { "given" } else { "generated" }.to_string(),
            base_max_alpha_deg: plan.base_max_alpha_deg,
            base_overloaded_samples: plan.base_overloaded_samples,
            axis: AxisReport::new(&plan),
            critical: plan.critical.intervals.clone(),
            off_axis_samples: plan.critical.off_axis_samples,
            treatments: plan.treatments.clone(),
            levels_mm: plan.levels_mm.clone(),
            trimmed_mm: plan.trim.removed_mm,
            relinks: plan.trim.links,
            hops: plan.trim.hops,
            verification: VerificationReport { verification: plan.verification.clone(), overloads },
            rounds: plan.rounds,
            pocket_area_mm2: plan.pocket_area_mm2,
            program: ProgramInfo::new(plan.base_moves, plan.toolpath.moves.len(), &program.text),
            figures,
            path: toolpath_to_json(&plan.toolpath),
            warnings: plan.warnings,
        }
    }
}
