//! Feed optimisation with the costing's figures (MODEL.md §9 and §10, seed 002 Eq. 4)
//! before and after: the input's wear is counted on the optimiser's own simulation, the
//! optimised program is simulated and costed as the costing job costs a program, and
//! min_cost returns the input unchanged when the whole new program would cost more.

use super::objective::{Objective, ObjectiveSpec};
use super::plan::{figures, optimize_side_milling_with, written, BlockFeed, FeedPlan, FeedSpec};
use crate::core::analysis::kept::KeptStock;
use crate::core::analysis::{Analysis, AnalysisSpec, Stack};
use crate::core::costing::cost::Rates;
use crate::core::costing::estimate::{estimate_from, estimate_with_wear, Estimate};
use crate::core::costing::wear::WearCounter;
use crate::core::feed::blocks::Piece;
use crate::core::progress::{Progress, Stage};
use crate::core::toolpath::move_length;
use crate::core::toolpath::{Motion, Toolpath};
use crate::core::CoreError;
use std::collections::HashSet;

/// Share of the progress the optimisation's simulation takes …
const OPTIMISATION_SHARE: f64 = 0.5;
/// … and each costing of the new program (a second one only where min_cost puts moves
/// back).
const COSTING_SHARE: f64 = 0.25;
/// Minutes per hour.
const MIN_PER_HOUR: f64 = 60.0;
/// Seconds per minute.
const S_PER_MIN: f64 = 60.0;

/// The costing's figures of the input and of the optimised program.
#[derive(Debug, Clone, PartialEq)]
pub struct Costed {
    pub before: Estimate,
    pub after: Estimate,
    /// The simulation of the program returned (its forces at the new feeds).
    pub after_analysis: Option<Analysis>,
    /// min_cost found the new program dearer than the input and returned the input.
    pub kept_input: bool,
}

/// A feed optimisation with its costs, and the stock the path leaves.
pub struct Optimised {
    pub plan: FeedPlan,
    /// Null when the objective carries no costing model.
    pub costed: Option<Costed>,
    /// The stock the path leaves (the optimised program cuts the same path).
    pub stock: Stack,
}

/// Optimises the feeds of a side-milling path for `objective`, and costs the input and
/// the result when the objective carries the costing's model. Every simulation starts
/// from the stock `start` another simulation left when given (see
/// [`crate::core::analysis::analyze_from`]).
pub fn optimize_costed(
    path: &Toolpath,
    analysis: &AnalysisSpec,
    start: Option<&KeptStock>,
    spec: &FeedSpec,
    objective: ObjectiveSpec,
    progress: &dyn Progress,
) -> Result<Optimised, CoreError> {
    let model = objective.cost.clone();
    let min_cost = objective.objective == Objective::MinCost;
    let first = Stage { inner: progress, from: 0.0, span: OPTIMISATION_SHARE };
    let Some(model) = model else {
        let (plan, stock) = optimize_side_milling_with(path, analysis, start, spec, Some(objective), &first, |_| {})?;
        progress.report(1.0);
        return Ok(Optimised { plan, costed: None, stock });
    };
    model.life.validate()?;
    let mut counter = WearCounter::new(&model.life, analysis.tool.flutes, analysis.default_spindle_rpm);
    let (mut plan, stock) =
        optimize_side_milling_with(path, analysis, start, spec, Some(objective), &first, |r| counter.add(r))?;
    let before = estimate_with_wear(path, counter.finish(), &model)?;
    let second = Stage { inner: progress, from: OPTIMISATION_SHARE, span: COSTING_SHARE };
    let estimate = |path: &Toolpath, stage: &dyn Progress| {
        estimate_from(path, analysis, start, &model, stage).map(|(analysis, estimate, _)| (analysis, estimate))
    };
    let (mut after_analysis, mut after) = estimate(&plan.path, &second)?;
    if min_cost && after.cost.total > before.cost.total {
        // The costing simulates the new program afresh (its pieces add z levels and
        // samples): put back the moves it finds dearer than before, and cost once more.
        let dearer = dearer_moves(&plan, &before, &after, &model.rates);
        if dearer.iter().any(|&d| d) {
            plan.keep_moves(path, &dearer);
            let third = Stage { inner: progress, from: OPTIMISATION_SHARE + COSTING_SHARE, span: COSTING_SHARE };
            (after_analysis, after) = estimate(&plan.path, &third)?;
        }
    }
    progress.report(1.0);
    if min_cost && after.cost.total > before.cost.total {
        plan.keep_input(path);
        plan.warnings.push(format!(
            "the optimised feeds would cost {:.2} {} against {:.2} as programmed (min_cost): the program keeps its feeds",
            after.cost.total, after.cost.currency, before.cost.total
        ));
        let analysis = plan.analysis.clone();
        let costed = Costed { after: before.clone(), before, after_analysis: analysis, kept_input: true };
        return Ok(Optimised { plan, costed: Some(costed), stock });
    }
    let costed = Costed { before, after, after_analysis: Some(after_analysis), kept_input: false };
    Ok(Optimised { plan, costed: Some(costed), stock })
}

/// Per move of the input: `true` where the costing finds its pieces in the new program
/// dearer than the move was (machine time of its kinematic time plus the tool share of
/// its wear, seed 002 Eq. 4 move by move).
fn dearer_moves(plan: &FeedPlan, before: &Estimate, after: &Estimate, rates: &Rates) -> Vec<bool> {
    let cost = |e: &Estimate, i: usize| {
        let seconds = e.time.per_move_s.as_ref().and_then(|t| t.get(i)).map_or(0.0, |&t| f64::from(t));
        let worn = e.wear.move_consumption.get(i).copied().unwrap_or(0.0);
        rates.machine_rate_per_hour / MIN_PER_HOUR * seconds / S_PER_MIN + rates.tool_price * worn
    };
    let mut out = 0;
    plan.pieces
        .iter()
        .enumerate()
        .map(|(i, pieces)| {
            let n = pieces.len().max(1);
            let new: f64 = (out..out + n).map(|k| cost(after, k)).sum();
            out += n;
            new > cost(before, i)
        })
        .collect()
}

impl FeedPlan {
    /// Puts the moves of `input` flagged in `keep` back at their programmed feed, and
    /// writes the path and the blocks again from the pieces.
    pub fn keep_moves(&mut self, input: &Toolpath, keep: &[bool]) {
        let mut lines = HashSet::new();
        for ((m, pieces), _) in input.moves.iter().zip(&mut self.pieces).zip(keep).filter(|(_, &k)| k) {
            if let (Some(f), false) = (m.feed_mm_min, pieces.is_empty()) {
                *pieces = vec![Piece { t0: 0.0, t1: 1.0, feed_mm_min: f }];
                self.kept_moves += 1;
                lines.insert(m.line);
            }
        }
        let (path, blocks) = written(input, &self.pieces);
        self.after = figures(&path.moves, self.after.force_n, self.rapid_mm_min);
        (self.path, self.blocks) = (path, blocks);
        if let Some(drawing) = &mut self.drawing {
            for k in 0..drawing.after.len() {
                if lines.contains(&drawing.after.line[k]) {
                    drawing.after.feed_mm_min[k] = drawing.before.feed_mm_min[k];
                    drawing.after.force_n[k] = drawing.before.force_n[k];
                }
            }
        }
    }

    /// Makes this plan the input program as it is: every move at its programmed feed.
    pub fn keep_input(&mut self, path: &Toolpath) {
        self.path = path.clone();
        self.blocks = path
            .moves
            .iter()
            .map(|m| {
                let feed = m.feed_mm_min.filter(|_| !matches!(m.motion, Motion::Rapid));
                BlockFeed { line: m.line, length_mm: move_length(m), programmed_mm_min: feed, feed_mm_min: feed }
            })
            .collect();
        self.pieces = self
            .blocks
            .iter()
            .map(|b| b.feed_mm_min.map(|f| Piece { t0: 0.0, t1: 1.0, feed_mm_min: f }).into_iter().collect())
            .collect();
        self.kept_moves = self.pieces.iter().filter(|p| !p.is_empty()).count();
        self.after = self.before;
        self.rate_limited_mm = 0.0;
        if let Some(drawing) = &mut self.drawing {
            drawing.after = drawing.before.clone();
        }
    }
}
