//! The feeds a program's blocks are cut from: the change-rate limit (MODEL.md §4) over the
//! feeds the samples need, with the moves min_cost keeps at their programmed feed
//! ([`super::guarantee`]) taken at that feed. A neighbour then ramps towards the feed the
//! program will really have there, not towards a new feed the kept move never gets. A kept
//! move is written whole at its programmed feed, so where the move after it is slower, the
//! feed still steps down at the block boundary (the limit's ramp inside the kept move is
//! not written), as a programmed feed change does.

use super::blocks::{split_feeds, Piece};
use super::collect::Kept;
use super::guarantee::pieces_pay;
use super::objective::ObjectiveSpec;
use super::plan::FeedSpec;
use super::rate_limit::limit_feed_change;
use super::rule::FeedReason;
use crate::core::toolpath::{move_length, Motion, Move};
use std::ops::Range;

/// A limited feed this far below the required one counts as lowered by the rate limit.
const RATE_LIMITED_SLACK_MM_MIN: f64 = 1e-6;
/// Most times the rate limit is run again for moves newly kept at their programmed feed.
/// Each run can only add kept moves; a move a last run finds not to pay still keeps its
/// programmed feed (the guarantee holds), its neighbours ramping as that run left them.
const MAX_SETTLE_RUNS: usize = 4;

/// The settled feeds of a path's samples.
#[derive(Debug, Clone, PartialEq)]
pub struct Settled {
    /// Per sample, the feed after the change-rate limit, mm/min.
    pub limited: Vec<f64>,
    /// Length where the limit lowered the feed of a move that takes new feeds, mm.
    pub rate_limited_mm: f64,
    /// Per move: it keeps its programmed feed (its new feeds would cost more, min_cost).
    pub keeps_programmed: Vec<bool>,
    /// Every other move was found to pay at the `limited` feeds (min_cost), so its pieces
    /// need no second look; `false` when the runs ran out first, or with no objective.
    pub all_checked: bool,
}

/// Per move of `moves`, the range of `kept` samples that lie on it (samples are in path
/// order, each naming its move).
pub fn move_ranges(moves: &[Move], kept: &[Kept]) -> Vec<Range<usize>> {
    let mut i = 0;
    (0..moves.len())
        .map(|index| {
            let start = i;
            while i < kept.len() && kept[i].move_index as usize == index {
                i += 1;
            }
            start..i
        })
        .collect()
}

/// Samples whose feed takes part in the change-rate limit: feed moves whose feed the
/// optimiser sets (a kept plunge feed neither drags its neighbours down nor is raised).
pub fn is_limited(k: &Kept) -> bool {
    k.reason.is_some_and(|r| r != FeedReason::Kept)
}

/// The pieces of move `m` whose samples are `kept[range]`, at the `limited` feeds: the
/// feed at its start is the previous sample's when that one takes part in the limit.
pub fn move_pieces(m: &Move, kept: &[Kept], limited: &[f64], range: Range<usize>, spec: &FeedSpec) -> Vec<Piece> {
    let start = range.start;
    let before_start = if start > 0 && is_limited(&kept[start - 1]) { limited[start - 1] } else { limited[start] };
    let mut feeds = Vec::with_capacity(range.len() + 1);
    feeds.push(before_start);
    feeds.extend_from_slice(&limited[range]);
    let lowest = feeds.iter().copied().fold(f64::INFINITY, f64::min);
    split_feeds(move_length(m), &feeds, spec.rule.min_feed_mm_min.min(lowest), &spec.blocks)
}

/// The samples' feeds after the change-rate limit, and the moves that keep their
/// programmed feed under `objective` (min_cost). A move is kept when its pieces would cost
/// more than its programmed feed; the limit then runs again with the kept moves' samples at
/// their programmed feed, up to [`MAX_SETTLE_RUNS`] times.
pub fn settle(
    moves: &[Move],
    kept: &[Kept],
    ranges: &[Range<usize>],
    spec: &FeedSpec,
    objective: Option<&ObjectiveSpec>,
    tool_radius_mm: f64,
) -> Settled {
    let needed: Vec<f64> = kept.iter().map(|k| f64::from(k.feed_mm_min)).collect();
    let mut required = needed.clone();
    let mut keeps_programmed = vec![false; moves.len()];
    let mut limited = rate_limited(kept, &required, spec.max_change_per_mm);
    // The feeds the moves were last found to pay at (none yet): a move whose feeds have not
    // changed since still pays.
    let mut checked_at: Option<Vec<f64>> = None;
    let mut all_checked = false;
    for _ in 0..MAX_SETTLE_RUNS {
        let Some(objective) = objective else { break };
        let mut newly_kept = false;
        for (index, m) in moves.iter().enumerate() {
            let range = ranges[index].clone();
            let Some(programmed) = m.feed_mm_min else { continue };
            if keeps_programmed[index] || matches!(m.motion, Motion::Rapid) || range.is_empty() {
                continue;
            }
            // Its pieces read its samples' feeds and the one before them: the very same
            // values give the very same pieces.
            let read = range.start.saturating_sub(1)..range.end;
            let same = |before: &Vec<f64>| {
                before[read.clone()].iter().zip(&limited[read.clone()]).all(|(a, b)| a.to_bits() == b.to_bits())
            };
            let unchanged = checked_at.as_ref().is_some_and(same);
            if unchanged {
                continue;
            }
            let pieces = move_pieces(m, kept, &limited, range.clone(), spec);
            if !pieces_pay(&kept[range.clone()], &pieces, &spec.rule, objective, tool_radius_mm) {
                keeps_programmed[index] = true;
                required[range].fill(programmed);
                newly_kept = true;
            }
        }
        if !newly_kept {
            all_checked = true;
            break;
        }
        let next = rate_limited(kept, &required, spec.max_change_per_mm);
        checked_at = Some(std::mem::replace(&mut limited, next));
    }
    let in_kept_move = |s: usize| keeps_programmed.get(kept[s].move_index as usize).copied().unwrap_or(false);
    let rate_limited_mm = (0..kept.len())
        .filter(|&s| !in_kept_move(s) && limited[s] < needed[s] - RATE_LIMITED_SLACK_MM_MIN)
        .map(|s| f64::from(kept[s].step_mm))
        .sum();
    Settled { limited, rate_limited_mm, keeps_programmed, all_checked }
}

/// The `required` feeds after the change-rate limit, over each run of samples that take
/// part in it.
fn rate_limited(kept: &[Kept], required: &[f64], max_change_per_mm: Option<f64>) -> Vec<f64> {
    let mut out = required.to_vec();
    let Some(rate) = max_change_per_mm else {
        return out;
    };
    let mut i = 0;
    while i < kept.len() {
        if !is_limited(&kept[i]) {
            i += 1;
            continue;
        }
        let start = i;
        while i < kept.len() && is_limited(&kept[i]) {
            i += 1;
        }
        let steps: Vec<f64> = kept[start..i].iter().map(|k| f64::from(k.step_mm)).collect();
        out[start..i].copy_from_slice(&limit_feed_change(&required[start..i], &steps, rate));
    }
    out
}
