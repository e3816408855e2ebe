//! min_cost's guarantee, move by move: a move keeps its programmed feed where its new
//! feeds would cost more (seed 002 Eq. 4 per millimetre, [`cost_per_mm`]): the rate limit
//! and the blocks lower feeds below what each sample would choose, and a sample whose
//! programmed feed was faster than the limits allow may be cheaper as it was.

use super::blocks::Piece;
use super::collect::Kept;
use super::objective::{cost_per_mm, ForceCurve, Objective, ObjectiveSpec};
use super::rule::FeedRule;

/// `true` unless `objective` is min_cost and running the move's `samples` at `pieces`
/// costs more than at their programmed feed. Sample `k` of `n` lies at fraction
/// `(k + 1)/n` of the move, as the pieces are cut.
pub fn pieces_pay(
    samples: &[Kept],
    pieces: &[Piece],
    rule: &FeedRule,
    objective: &ObjectiveSpec,
    tool_radius_mm: f64,
) -> bool {
    let (Objective::MinCost, Some(model)) = (objective.objective, &objective.cost) else {
        return true;
    };
    let n = samples.len() as f64;
    let (mut before, mut after) = (0.0, 0.0);
    let mut p = 0;
    for (k, s) in samples.iter().enumerate() {
        let t = (k + 1) as f64 / n;
        while p + 1 < pieces.len() && t > pieces[p].t1 + f64::EPSILON {
            p += 1;
        }
        let programmed = f64::from(s.programmed_mm_min);
        let (rpm, ds) = (f64::from(s.spindle_rpm), f64::from(s.step_mm));
        if programmed <= 0.0 || rpm <= 0.0 {
            continue;
        }
        let cut = s.cut(tool_radius_mm);
        let force_before = s.force_before_n.is_finite().then_some(f64::from(s.force_before_n));
        let curve = rule.force_model.map(|m| ForceCurve::new(m, &cut, rule.flutes, rpm, force_before));
        let at = |feed: f64| ds * cost_per_mm(model, &cut, rule.flutes, rpm, feed, curve.map(|c| c.force_n(feed)));
        before += at(programmed);
        after += at(pieces[p].feed_mm_min);
    }
    after <= before
}
