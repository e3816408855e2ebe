//! What the feeds are chosen for (the `objective`), and the feed of one sample under it.
//!
//! - `constant_force`: the papers' rule as written (MODEL.md §3): the feed that holds the
//!   target force, the minimum feed where no feed reaches it.
//! - `min_time`: the fastest feed whose predicted force stays under the force limit.
//! - `min_cost`: the feed of least cost per millimetre, `c_m/F + c_t·w(F)/L_f` (seed 002
//!   Eq. 4 per millimetre of path), under the force limit, with the tool wear per
//!   millimetre `w(F) = L / fz_p · γ(α) · φ(F_xy/F*)` of MODEL.md §9. Below F* the wear
//!   per millimetre falls as the feed rises (a tooth passes `1/fz_p` times per millimetre
//!   and φ = 1), so a slower feed wears the tool more per millimetre, not less.
//!
//! The force limit is by default the target force: min_cost and min_time then hold the
//! constant force wherever it can be held (below F* the cost per millimetre only falls
//! as the feed rises), and a higher `max_force_n` lets them trade force for cost or time.
//! Where no feed keeps the force under the limit (full slotting, helical entries: the
//! extrapolated model predicts more than the limit even at the minimum feed), they never
//! go faster than the programmed feed, nor past the overload threshold (3 × F*) where a
//! feed stays under it; min_cost takes the cheapest feed up to there instead of dropping
//! to the minimum feed, min_time the fastest.

use super::rule::{FeedReason, FeedRule, FeedStrategy, SampleCut};
use crate::core::analysis::outside::OVERLOAD_FORCE_FACTOR;
use crate::core::costing::estimate::CostModel;
use crate::core::engagement::{tooth_chip_thickness_mm, ToothCut};
use crate::core::force_model::ForceModel;
use crate::core::tool_life::WearCut;
use serde::{Deserialize, Serialize};

/// Micrometres per millimetre.
const UM_PER_MM: f64 = 1000.0;
/// Minutes per hour.
const MIN_PER_HOUR: f64 = 60.0;
/// Steps of the bisections and of the golden-section search on ln F (a feed range of
/// 1:10⁴ is then resolved to 10⁻⁵ in ln F).
const SEARCH_STEPS: usize = 40;
/// The golden ratio's conjugate, (√5 − 1)/2.
const GOLDEN: f64 = 0.618_033_988_749_895;

/// What the feeds are chosen for.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Objective {
    /// The cheapest feed per millimetre under the force limit; the program never costs
    /// more than the input by the costing's own figures.
    #[default]
    MinCost,
    /// The papers' rule as written: hold the target force (MODEL.md §3).
    ConstantForce,
    /// The fastest feed under the force limit.
    MinTime,
}

/// The objective and what it needs.
#[derive(Debug, Clone, PartialEq)]
pub struct ObjectiveSpec {
    pub objective: Objective,
    /// The largest force a min_time or min_cost feed may cause, N (the service's
    /// default: the target force).
    pub max_force_n: f64,
    /// The costing's model: needed for min_cost, and for the figures before and after.
    pub cost: Option<CostModel>,
}

/// The predicted force of one sample as a function of its centre feed: the force model
/// at the chip thickness the feed gives (the bounds of
/// [`tooth_chip_thickness_mm`] included), scaled so that it equals the simulation's force
/// at the programmed feed (exact for a single slice; the slices' shares kept otherwise).
#[derive(Debug, Clone, Copy)]
pub struct ForceCurve {
    model: ForceModel,
    tooth: ToothCut,
    arc_length_mm: f64,
    ad_mm: f64,
    /// mm/min per mm of feed per tooth: z·S.
    teeth_per_min: f64,
    scale: f64,
}

impl ForceCurve {
    /// The curve of a sample cut as `cut` at `spindle_rpm` by `flutes` teeth, whose force
    /// at its programmed feed was `force_before_n` (if known).
    pub fn new(
        model: ForceModel,
        cut: &SampleCut,
        flutes: u32,
        spindle_rpm: f64,
        force_before_n: Option<f64>,
    ) -> ForceCurve {
        let tooth = cut.tooth();
        let mut curve = ForceCurve {
            model,
            tooth,
            arc_length_mm: cut.arc_length_mm,
            ad_mm: cut.ad_mm,
            teeth_per_min: f64::from(flutes) * spindle_rpm,
            scale: 1.0,
        };
        let at_programmed = curve.force_n(cut.programmed_feed_mm_min);
        if let Some(before) = force_before_n.filter(|f| *f > 0.0 && at_programmed > 0.0) {
            curve.scale = before / at_programmed;
        }
        curve
    }

    /// Predicted force at centre feed `feed_mm_min`, N.
    pub fn force_n(&self, feed_mm_min: f64) -> f64 {
        let t_m_um = tooth_chip_thickness_mm(feed_mm_min / self.teeth_per_min, &self.tooth) * UM_PER_MM;
        self.scale * self.model.force_n(t_m_um, self.arc_length_mm, self.ad_mm)
    }

    /// The fastest feed in `[lo, hi]` whose force is at most `limit_n` (the force rises
    /// with the feed); `None` when even `lo` is above it.
    pub fn fastest_under(&self, limit_n: f64, lo: f64, hi: f64) -> Option<f64> {
        if self.force_n(lo) > limit_n {
            return None;
        }
        if self.force_n(hi) <= limit_n {
            return Some(hi);
        }
        let (mut a, mut b) = (lo.ln(), hi.ln());
        for _ in 0..SEARCH_STEPS {
            let m = 0.5 * (a + b);
            if self.force_n(m.exp()) <= limit_n {
                a = m;
            } else {
                b = m;
            }
        }
        Some(a.exp())
    }
}

/// Cost of one millimetre of path at centre feed `feed_mm_min`: `c_m · (1/F)` for the
/// machine time plus `c_t · w(F) / L_f` for the tool (seed 002 Eq. 4 per millimetre;
/// the wear per millimetre `w` of MODEL.md §9 through [`ToolLifeModel::wear_mm`], as the
/// costing counts it), in the rates' currency.
///
/// [`ToolLifeModel::wear_mm`]: crate::core::tool_life::ToolLifeModel::wear_mm
pub fn cost_per_mm(
    model: &CostModel,
    cut: &SampleCut,
    flutes: u32,
    spindle_rpm: f64,
    feed_mm_min: f64,
    force_n: Option<f64>,
) -> f64 {
    let machine = model.rates.machine_rate_per_hour / MIN_PER_HOUR / feed_mm_min;
    if !cut.in_material {
        return machine;
    }
    let wear = WearCut::at_centre_feed(
        cut.alpha_rad.to_degrees(),
        cut.arc_length_mm,
        feed_mm_min,
        f64::from(flutes),
        spindle_rpm,
        cut.cutting_point_ratio,
        force_n,
    );
    machine + model.rates.tool_price * model.life.wear_mm(1.0, &wear) / model.life.life_edge_arc_mm()
}

/// The feed in `[lo, hi]` that minimises `cost` (a golden-section search on ln F; the
/// cost per millimetre of [`cost_per_mm`] has one minimum there: the machine part falls
/// as 1/F, and the wear part falls as 1/F below F* and rises above it as (F/F*)^k / F).
pub fn cheapest_feed(lo: f64, hi: f64, cost: impl Fn(f64) -> f64) -> f64 {
    if hi <= lo {
        return hi;
    }
    let (mut a, mut b) = (lo.ln(), hi.ln());
    let mut c = b - GOLDEN * (b - a);
    let mut d = a + GOLDEN * (b - a);
    let (mut fc, mut fd) = (cost(c.exp()), cost(d.exp()));
    for _ in 0..SEARCH_STEPS {
        if fc <= fd {
            b = d;
            (d, fd) = (c, fc);
            c = b - GOLDEN * (b - a);
            fc = cost(c.exp());
        } else {
            a = c;
            (c, fc) = (d, fd);
            d = a + GOLDEN * (b - a);
            fd = cost(d.exp());
        }
    }
    let inner = if fc <= fd { c.exp() } else { d.exp() };
    // The search keeps the bracket's inside: an end may still be cheaper.
    [lo, hi, inner].into_iter().min_by(|x, y| cost(*x).total_cmp(&cost(*y))).unwrap_or(hi)
}

impl ObjectiveSpec {
    /// The feed of `cut` under min_time or min_cost, and why; `constant` is what the
    /// papers' rule gives there (taken as it is for constant_force, for a strategy without
    /// a force model, and where the rule keeps the feed or cuts air).
    pub fn feed(
        &self,
        rule: &FeedRule,
        cut: &SampleCut,
        force_before_n: Option<f64>,
        constant: (f64, FeedReason),
    ) -> (f64, FeedReason) {
        let (Some(model), Some(rpm)) = (rule.force_model, cut.spindle_rpm.filter(|s| *s > 0.0)) else {
            return constant;
        };
        let decided = matches!(constant.1, FeedReason::Air | FeedReason::Kept);
        if self.objective == Objective::ConstantForce || rule.strategy == FeedStrategy::CuttingPoint || decided {
            return constant;
        }
        let curve = ForceCurve::new(model, cut, rule.flutes, rpm, force_before_n);
        let (lo, mut hi) = (rule.min_feed_mm_min, rule.max_feed_mm_min);
        if rule.strategy == FeedStrategy::Both {
            // The cutting-point rule caps the feed too.
            hi = hi.min(cut.programmed_feed_mm_min / cut.cutting_point_ratio).max(lo);
        }
        let (up, reason) = match curve.fastest_under(self.max_force_n, lo, hi) {
            Some(f) if f >= hi => (hi, FeedReason::ClampedMax),
            Some(f) => (f, FeedReason::Target),
            // No feed keeps the force under the limit: never faster than programmed, nor
            // past the overload threshold where a feed stays under it.
            None => {
                let overload = OVERLOAD_FORCE_FACTOR * model.design_centre_force_n();
                let safe = curve.fastest_under(overload, lo, hi).unwrap_or(hi);
                (cut.programmed_feed_mm_min.min(safe).clamp(lo, hi), FeedReason::Infeasible)
            }
        };
        match (&self.objective, &self.cost) {
            (Objective::MinCost, Some(cost)) => {
                let per_mm = |f: f64| cost_per_mm(cost, cut, rule.flutes, rpm, f, Some(curve.force_n(f)));
                // Below F* the cost only falls with the feed: search from where F* is met.
                let from =
                    cost.life.standard_force_n.and_then(|f_star| curve.fastest_under(f_star, lo, up)).unwrap_or(lo);
                let feed = cheapest_feed(from, up, per_mm);
                let reason = if feed < up && reason != FeedReason::Infeasible { FeedReason::Target } else { reason };
                (feed, reason)
            }
            _ => (up, reason),
        }
    }
}
