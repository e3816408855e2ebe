//! The answer of a `feeds` job, as the API documents it.

use super::analysis_result::{summary, CriticalRegionDto, PathPointDto, StatsDto, SummaryDto};
use super::conditions::{NamedRef, ToolRef};
use super::feeds::{CutMode, FeedsPrepared};
use crate::core::feed::collect::{ReasonLengths, Shortfall, ShortfallKind};
use crate::core::feed::plan::{FeedPlan, Figures};
use crate::core::feed::rule::FeedStrategy;
use serde::Serialize;
use utoipa::ToSchema;

/// Figures of a program.
#[derive(Debug, Clone, Copy, Serialize, ToSchema)]
pub struct FiguresDto {
    /// Predicted XY force over the cutting samples, N (null without a force model).
    pub force_n: Option<StatsDto>,
    /// Feed over the feed moves, mm/min (length-weighted).
    pub feed_mm_min: StatsDto,
    /// Feed moves at their feeds plus rapids at the machine's rapid rate, min.
    pub time_min: f64,
}

impl From<Figures> for FiguresDto {
    fn from(f: Figures) -> Self {
        FiguresDto { force_n: f.force_n.map(Into::into), feed_mm_min: f.feed_mm_min.into(), time_min: f.time_min }
    }
}

/// The limits the feeds were held to.
#[derive(Debug, Clone, Copy, Serialize, ToSchema)]
pub struct LimitsDto {
    pub min_feed_mm_min: f64,
    pub max_feed_mm_min: f64,
    pub air_feed_mm_min: f64,
    /// mm/min per mm of path (null: no limit).
    pub max_feed_change_per_mm: Option<f64>,
}

/// Path length by what set the feed, mm.
#[derive(Debug, Clone, Copy, Serialize, ToSchema)]
pub struct ReasonLengthsDto {
    /// The strategy's feed, within the limits.
    pub target_mm: f64,
    /// Capped at the maximum feed.
    pub clamped_max_mm: f64,
    /// Raised to the minimum feed: the force stays above the target.
    pub clamped_min_mm: f64,
    /// No feed reaches the target (needs a trochoid or a z-cut division).
    pub infeasible_mm: f64,
    /// Feed moves in the air, at the air-cut feed.
    pub air_mm: f64,
    /// Kept at the programmed feed (plunges, no spindle speed).
    pub kept_mm: f64,
    /// Lowered further by the change-rate limit.
    pub rate_limited_mm: f64,
}

/// A run of the path where the target force cannot be held.
#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct ShortfallDto {
    pub kind: ShortfallKind,
    pub start: PathPointDto,
    pub end: PathPointDto,
    pub length_mm: f64,
    pub max_alpha_deg: f64,
}

impl From<Shortfall> for ShortfallDto {
    fn from(s: Shortfall) -> Self {
        ShortfallDto {
            kind: s.kind,
            start: s.start.into(),
            end: s.end.into(),
            length_mm: s.length_mm,
            max_alpha_deg: s.max_alpha_deg,
        }
    }
}

/// One entry per block of the written program (rapids have no feed).
#[derive(Debug, Clone, Default, Serialize, ToSchema)]
pub struct BlocksDto {
    /// Source line of the move the block comes from.
    pub line: Vec<u32>,
    pub length_mm: Vec<f64>,
    pub programmed_mm_min: Vec<Option<f64>>,
    pub feed_mm_min: Vec<Option<f64>>,
}

/// The written program in numbers (the text is at the job's `program` link).
#[derive(Debug, Clone, Copy, Serialize, ToSchema)]
pub struct ProgramInfoDto {
    /// Moves of the path the job started from.
    pub moves_in: usize,
    pub moves_out: usize,
    pub lines: usize,
    pub bytes: usize,
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
    /// The force held, N (null for cutting_point).
    pub target_force_n: Option<f64>,
    pub limits: LimitsDto,
    /// The input program at its programmed feeds.
    pub before: FiguresDto,
    /// The optimised program.
    pub after: FiguresDto,
    pub lengths: ReasonLengthsDto,
    pub shortfalls: Vec<ShortfallDto>,
    /// The analysis of the input path (side milling).
    pub analysis: Option<SummaryDto>,
    pub critical_regions: Vec<CriticalRegionDto>,
    pub program: ProgramInfoDto,
    pub blocks: BlocksDto,
    pub warnings: Vec<String>,
}

impl FeedsResult {
    pub fn new(prepared: FeedsPrepared, mode: CutMode, moves_in: usize, program: &str, plan: FeedPlan) -> Self {
        let ReasonLengths { target_mm, clamped_max_mm, clamped_min_mm, infeasible_mm, air_mm, kept_mm } = plan.lengths;
        let mut blocks = BlocksDto::default();
        for b in &plan.blocks {
            blocks.line.push(b.line);
            blocks.length_mm.push(b.length_mm);
            blocks.programmed_mm_min.push(b.programmed_mm_min);
            blocks.feed_mm_min.push(b.feed_mm_min);
        }
        let (analysis, critical_regions) = match plan.analysis {
            Some(a) => {
                let n = a.critical_regions.len();
                (Some(summary(moves_in, a.summary, n)), a.critical_regions.into_iter().map(Into::into).collect())
            }
            None => (None, vec![]),
        };
        let base = prepared.base;
        FeedsResult {
            material: base.material,
            tool: base.tool,
            machine: base.machine,
            force_model_id: base.force_model.map(|f| f.id),
            standard_conditions_id: prepared.standard_conditions_id,
            mode,
            strategy: prepared.strategy,
            target_force_n: prepared.target_force_n,
            limits: LimitsDto {
                min_feed_mm_min: prepared.min_feed_mm_min,
                max_feed_mm_min: prepared.max_feed_mm_min,
                air_feed_mm_min: prepared.air_feed_mm_min,
                max_feed_change_per_mm: prepared.max_feed_change_per_mm,
            },
            before: plan.before.into(),
            after: plan.after.into(),
            lengths: ReasonLengthsDto {
                target_mm,
                clamped_max_mm,
                clamped_min_mm,
                infeasible_mm,
                air_mm,
                kept_mm,
                rate_limited_mm: plan.rate_limited_mm,
            },
            shortfalls: plan.shortfalls.into_iter().map(Into::into).collect(),
            analysis,
            critical_regions,
            program: ProgramInfoDto {
                moves_in,
                moves_out: plan.path.moves.len(),
                lines: program.lines().count(),
                bytes: program.len(),
            },
            blocks,
            warnings: plan.warnings,
        }
    }
}
