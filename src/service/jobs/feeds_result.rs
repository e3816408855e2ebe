//! The answer of a `feeds` job: the core's feed plan, costs and analysis with the database
//! rows and limits they were computed with.

use super::analysis_result::PathSummary;
use super::costing_result::CostReport;
use super::feeds::{CutMode, FeedsPrepared};
use super::setup::CostSetup;
use super::setup::{NamedRef, ToolRef};
use crate::core::analysis::outside::{ForceOverload, OutsideModel};
use crate::core::analysis::report::{CriticalRegion, Stats};
use crate::core::analysis::Analysis;
use crate::core::costing::estimate::Estimate;
use crate::core::feed::collect::{ReasonLengths, Shortfall};
use crate::core::feed::costed::Costed;
use crate::core::feed::edit::Edited;
use crate::core::feed::objective::Objective;
use crate::core::feed::plan::{FeedPlan, Figures};
use crate::core::feed::rule::FeedStrategy;
use crate::core::kinematics::MachiningTime;
use crate::core::CoreError;
use serde::Serialize;
use utoipa::ToSchema;

/// Figures of a program: the optimiser's, and the costing's for the same tool, machine
/// and cost rates (the costing job gives the same numbers for the same program).
#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct FeedFigures {
    /// Predicted XY force over the cutting samples, N (null without a force model).
    pub force_n: Option<Stats>,
    /// Feed over the feed moves, mm/min (length-weighted).
    pub feed_mm_min: Stats,
    /// Feed moves at their feeds plus rapids at the machine's rapid rate, min.
    pub time_min: f64,
    /// The costing's nominal time (feeds, rapids, tool changes, dwells), min.
    pub nominal_time_min: Option<f64>,
    /// The costing's kinematic time (the machine's feed, acceleration and jerk limits),
    /// min: the time of the cost.
    pub kinematic_time_min: Option<f64>,
    /// Share of one tool's life the program uses, L_t/L_f (MODEL.md §9; null where the
    /// costing cannot run: surface finishing, no tool-life data).
    pub consumption: Option<f64>,
    /// The costing's cost, `C = c_m·T_m + c_t·L_t/L_f` (seed 002 Eq. 4).
    pub cost: Option<CostReport>,
    /// Where this program's forces leave the force model's experiments (null when not
    /// simulated or without a force model).
    pub outside_model: Option<OutsideModel>,
    /// Where this program's predicted force exceeds 3 × the standard force, by line.
    pub force_overload: Option<ForceOverload>,
    /// `true` when force, consumption or cost rest on forces outside the force model's
    /// experiments: extrapolations.
    pub extrapolated: bool,
}

impl FeedFigures {
    fn new(
        f: Figures,
        time: Option<&MachiningTime>,
        estimate: Option<(&CostSetup, &Estimate)>,
        analysis: Option<&Analysis>,
    ) -> Result<Self, CoreError> {
        let s = analysis.map(|a| &a.summary);
        let outside = s.and_then(|s| s.outside_model.clone());
        let force_extrapolated = outside.as_ref().is_some_and(|o| o.length_mm > 0.0);
        let wear_extrapolated = estimate.is_some_and(|(_, e)| e.wear.extrapolated_share > 0.0);
        // The simulation's forces where the program was simulated (the optimiser's
        // prediction otherwise).
        let force_n = s.map_or(f.force_n, |s| s.force_n);
        Ok(FeedFigures {
            force_n,
            feed_mm_min: f.feed_mm_min,
            time_min: f.time_min,
            nominal_time_min: time.map(|t| t.nominal_min),
            kinematic_time_min: time.map(|t| t.kinematic_min),
            consumption: estimate.map(|(_, e)| e.wear.consumption.ratio),
            cost: estimate.map(|(setup, e)| CostReport::new(setup, e)).transpose()?,
            outside_model: outside,
            force_overload: s.and_then(|s| s.force_overload.clone()),
            extrapolated: force_extrapolated || wear_extrapolated,
        })
    }
}

/// The limits the feeds were held to.
#[derive(Debug, Clone, Copy, Serialize, ToSchema)]
pub struct FeedLimits {
    pub min_feed_mm_min: f64,
    pub max_feed_mm_min: f64,
    pub air_feed_mm_min: f64,
    /// mm/min per mm of path (null: no limit).
    pub max_feed_change_per_mm: Option<f64>,
}

/// Path length by what set the feed, mm.
#[derive(Debug, Clone, Copy, Serialize, ToSchema)]
pub struct FeedLengths {
    #[serde(flatten)]
    pub reasons: ReasonLengths,
    /// Lowered further by the change-rate limit.
    pub rate_limited_mm: f64,
}

/// One entry per block of the written program (rapids have no feed).
#[derive(Debug, Clone, Default, Serialize, ToSchema)]
pub struct Blocks {
    /// Source line of the move the block comes from.
    pub line: Vec<u32>,
    pub length_mm: Vec<f64>,
    pub programmed_mm_min: Vec<Option<f64>>,
    pub feed_mm_min: Vec<Option<f64>>,
}

/// The written program in numbers (the text is at the job's `program` link).
#[derive(Debug, Clone, Copy, Serialize, ToSchema)]
pub struct ProgramInfo {
    /// Moves of the path the job started from.
    pub moves_in: usize,
    pub moves_out: usize,
    pub lines: usize,
    pub bytes: usize,
}

impl ProgramInfo {
    /// `text`, written from `moves_out` moves of a path of `moves_in`, in numbers.
    pub fn new(moves_in: usize, moves_out: usize, text: &str) -> Self {
        ProgramInfo { moves_in, moves_out, lines: text.lines().count(), bytes: text.len() }
    }
}

/// The answer of a `feeds` job.
#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct FeedsResult {
    pub material: NamedRef,
    pub tool: ToolRef,
    pub machine: NamedRef,
    pub force_model_id: Option<i64>,
    pub standard_conditions_id: Option<i64>,
    pub mode: CutMode,
    pub strategy: FeedStrategy,
    /// What the feeds were chosen for.
    pub objective: Objective,
    /// The force held, N (null for cutting_point).
    pub target_force_n: Option<f64>,
    /// The most force min_cost and min_time may ask of the tool, N.
    pub max_force_n: Option<f64>,
    pub limits: FeedLimits,
    /// The cost rates of the costs (null where there are no costs).
    pub cost_rates: Option<NamedRef>,
    /// The input program at its programmed feeds.
    pub before: FeedFigures,
    /// The optimised program.
    pub after: FeedFigures,
    /// min_cost found every new feed dearer than the program's own and returned it
    /// unchanged.
    pub kept_input: bool,
    /// Moves that keep their programmed feed because the new feeds would cost more
    /// (min_cost).
    pub kept_moves: usize,
    pub lengths: FeedLengths,
    /// Runs of the path where the target force cannot be held.
    pub shortfalls: Vec<Shortfall>,
    /// The analysis of the input path (side milling).
    pub analysis: Option<PathSummary>,
    pub critical_regions: Vec<CriticalRegion>,
    pub program: ProgramInfo,
    /// How the G-code sent was edited (null for JSON moves, whose program is written
    /// anew).
    pub edit: Option<Edited>,
    pub blocks: Blocks,
    pub warnings: Vec<String>,
    /// The job whose stock the layer started from (`stock.from_job`), if any.
    pub stock_from_job: Option<String>,
}

impl FeedsResult {
    pub fn new(
        prepared: FeedsPrepared,
        mode: CutMode,
        moves_in: usize,
        program: &str,
        plan: FeedPlan,
        costed: Option<Costed>,
        times: Option<(MachiningTime, MachiningTime)>,
    ) -> Result<Self, CoreError> {
        let setup = prepared.cost.as_ref();
        let before = FeedFigures::new(
            plan.before,
            times.as_ref().map(|t| &t.0),
            setup.zip(costed.as_ref().map(|c| &c.before)),
            plan.analysis.as_ref(),
        )?;
        let after = FeedFigures::new(
            plan.after,
            times.as_ref().map(|t| &t.1),
            setup.zip(costed.as_ref().map(|c| &c.after)),
            costed.as_ref().and_then(|c| c.after_analysis.as_ref()),
        )?;
        let kept_input = costed.as_ref().is_some_and(|c| c.kept_input);
        let mut warnings = prepared.notes.clone();
        warnings.extend(plan.warnings.iter().cloned());
        if let Some(a) = costed.as_ref().and_then(|c| c.after_analysis.as_ref()).filter(|_| !kept_input) {
            let overload = a.summary.force_overload.as_ref().and_then(|o| o.warning());
            warnings.extend(overload.map(|w| format!("after: {w}")));
        }
        let mut blocks = Blocks::default();
        for b in &plan.blocks {
            blocks.line.push(b.line);
            blocks.length_mm.push(b.length_mm);
            blocks.programmed_mm_min.push(b.programmed_mm_min);
            blocks.feed_mm_min.push(b.feed_mm_min);
        }
        let (analysis, critical_regions) = match plan.analysis {
            Some(a) => {
                let n = a.critical_regions.len();
                (Some(PathSummary::new(moves_in, a.summary, n)), a.critical_regions)
            }
            None => (None, vec![]),
        };
        let base = prepared.base;
        let stock_from_job = base.carried_stock.as_ref().map(|c| c.from_job.clone());
        Ok(FeedsResult {
            material: base.material,
            tool: base.tool,
            machine: base.machine,
            force_model_id: base.force_model.map(|f| f.id),
            standard_conditions_id: prepared.standard_conditions_id,
            mode,
            strategy: prepared.strategy,
            objective: prepared.objective,
            target_force_n: prepared.target_force_n,
            max_force_n: prepared.max_force_n.filter(|_| prepared.strategy.needs_force_model()),
            cost_rates: prepared.cost.map(|c| c.cost_rates),
            limits: FeedLimits {
                min_feed_mm_min: prepared.min_feed_mm_min,
                max_feed_mm_min: prepared.max_feed_mm_min,
                air_feed_mm_min: prepared.air_feed_mm_min,
                max_feed_change_per_mm: prepared.max_feed_change_per_mm,
            },
            before,
            after,
            kept_input,
            kept_moves: plan.kept_moves,
            lengths: FeedLengths { reasons: plan.lengths, rate_limited_mm: plan.rate_limited_mm },
            shortfalls: plan.shortfalls,
            analysis,
            critical_regions,
            program: ProgramInfo::new(moves_in, plan.path.moves.len(), program),
            edit: None,
            blocks,
            warnings,
            stock_from_job,
        })
    }
}
