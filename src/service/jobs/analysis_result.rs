//! The answer of an `analysis` job: the core's [`Analysis`] with the database rows it was
//! run with and what the service counts around it.

use super::setup::PathSetup;
use super::setup::{NamedRef, ToolRef};
use crate::core::analysis::report::{CriticalRegion, Series};
use crate::core::analysis::{Analysis, Summary};
use serde::Serialize;
use utoipa::ToSchema;

/// The figures of the whole path.
#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct PathSummary {
    /// Moves of the path.
    pub moves: usize,
    #[serde(flatten)]
    pub summary: Summary,
    /// `true` when some of the forces rest on the force model outside its experiments
    /// (see `outside_model`): they are extrapolations.
    pub force_extrapolated: bool,
    /// Runs of samples with α above the limit.
    pub critical_regions: usize,
}

impl PathSummary {
    /// The summary of a path of `moves` moves with `critical_regions` critical regions.
    pub fn new(moves: usize, summary: Summary, critical_regions: usize) -> Self {
        let force_extrapolated = summary.outside_model.as_ref().is_some_and(|o| o.length_mm > 0.0);
        PathSummary { moves, summary, force_extrapolated, critical_regions }
    }
}

/// The answer of an `analysis` job.
#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct AnalysisResult {
    pub material: NamedRef,
    pub tool: ToolRef,
    pub machine: NamedRef,
    /// The force model used (null: none, forces are not predicted).
    pub force_model_id: Option<i64>,
    pub summary: PathSummary,
    pub critical_regions: Vec<CriticalRegion>,
    pub series: Option<Series>,
    /// The job whose stock the layer started from (`stock.from_job`), if any.
    pub stock_from_job: Option<String>,
}

impl AnalysisResult {
    pub fn new(prepared: PathSetup, moves: usize, a: Analysis) -> AnalysisResult {
        let regions = a.critical_regions.len();
        let stock_from_job = prepared.carried_stock.as_ref().map(|c| c.from_job.clone());
        AnalysisResult {
            material: prepared.material,
            tool: prepared.tool,
            machine: prepared.machine,
            force_model_id: prepared.force_model.map(|f| f.id),
            summary: PathSummary::new(moves, a.summary, regions),
            critical_regions: a.critical_regions,
            series: a.series,
            stock_from_job,
        }
    }
}
