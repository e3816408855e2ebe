//! Per-sample bookkeeping of the feed optimiser: the feed every sample needs (kept
//! compactly, since the rate limit and the blocks need them all), the path length per
//! reason, and the regions where the target force cannot be held.

use super::objective::ObjectiveSpec;
use super::rule::{FeedReason, FeedRule, SampleCut};
use crate::core::analysis::report::PathPoint;
use serde::Serialize;

/// What the optimiser keeps of one sample (48 bytes: f32 values, so the 2.9 M samples of
/// tiger.nc take about 140 MB).
#[derive(Debug, Clone, Copy)]
pub struct Kept {
    pub move_index: u32,
    pub step_mm: f32,
    /// The feed the sample needs, mm/min (NaN on rapids).
    pub feed_mm_min: f32,
    pub reason: Option<FeedReason>,
    pub alpha_rad: f32,
    pub arc_length_mm: f32,
    pub ad_mm: f32,
    pub ratio: f32,
    /// The centre-path radius of the ratio, mm (infinite: straight).
    pub centre_radius_mm: f32,
    pub spindle_rpm: f32,
    /// Predicted force at the programmed feed, N (NaN when none).
    pub force_before_n: f32,
    pub programmed_mm_min: f32,
}

impl Kept {
    /// The cut of this sample, as the rules read it (`tool_radius_mm`: the tool's). The
    /// engagement was measured at the radius its arc length gives (the tool's, but in the
    /// corner of a radius or ball end mill).
    pub fn cut(&self, tool_radius_mm: f64) -> SampleCut {
        let tool_radius_mm = match self.alpha_rad > 0.0 {
            true => f64::from(self.arc_length_mm) / f64::from(self.alpha_rad),
            false => tool_radius_mm,
        };
        SampleCut {
            alpha_rad: f64::from(self.alpha_rad),
            arc_length_mm: f64::from(self.arc_length_mm),
            ad_mm: f64::from(self.ad_mm),
            cutting_point_ratio: f64::from(self.ratio),
            centre_radius_mm: f64::from(self.centre_radius_mm),
            tool_radius_mm,
            programmed_feed_mm_min: f64::from(self.programmed_mm_min),
            spindle_rpm: (self.spindle_rpm > 0.0).then_some(f64::from(self.spindle_rpm)),
            plunge: self.reason == Some(FeedReason::Kept),
            in_material: self.alpha_rad > 0.0,
        }
    }
}

/// Why a region could not be cut at the target force.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum ShortfallKind {
    /// No feed reaches the target: a trochoid or a z-cut division is needed.
    Infeasible,
    /// The target needs a feed below the minimum: the force stays above the target.
    BelowMinimumFeed,
}

/// A run of the path where the target force cannot be held.
#[derive(Debug, Clone, PartialEq, Serialize, utoipa::ToSchema)]
pub struct Shortfall {
    pub kind: ShortfallKind,
    pub start: PathPoint,
    pub end: PathPoint,
    pub length_mm: f64,
    pub max_alpha_deg: f64,
}

/// Path length by what set the feed, mm.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, utoipa::ToSchema)]
pub struct ReasonLengths {
    /// The strategy's feed, within the limits.
    pub target_mm: f64,
    /// Capped at the maximum feed.
    pub clamped_max_mm: f64,
    /// Raised to the minimum feed: the force stays above the target.
    pub clamped_min_mm: f64,
    /// No feed reaches the target (constant_force: needs a trochoid or a z-cut
    /// division), or none keeps the force under the limit (min_cost, min_time).
    pub infeasible_mm: f64,
    /// Feed moves in the air, at the air-cut feed.
    pub air_mm: f64,
    /// Kept at the programmed feed (plunges, no spindle speed).
    pub kept_mm: f64,
}

impl ReasonLengths {
    fn add(&mut self, reason: FeedReason, length_mm: f64) {
        let slot = match reason {
            FeedReason::Target => &mut self.target_mm,
            FeedReason::ClampedMax => &mut self.clamped_max_mm,
            FeedReason::ClampedMin => &mut self.clamped_min_mm,
            FeedReason::Infeasible => &mut self.infeasible_mm,
            FeedReason::Air => &mut self.air_mm,
            FeedReason::Kept => &mut self.kept_mm,
        };
        *slot += length_mm;
    }
}

/// One sample as the optimiser sees it.
pub struct SampleIn {
    pub at: PathPoint,
    pub step_mm: f64,
    pub move_index: usize,
    pub rapid: bool,
    pub cut: SampleCut,
    pub force_before_n: Option<f64>,
}

/// Collects samples in path order.
pub struct Collector {
    pub rule: FeedRule,
    /// How the feeds are chosen beyond the papers' rule (`None`: the rule as written).
    pub objective: Option<ObjectiveSpec>,
    /// The tool's radius, mm.
    pub tool_radius_mm: f64,
    pub kept: Vec<Kept>,
    pub lengths: ReasonLengths,
    pub shortfalls: Vec<Shortfall>,
    open: Option<Shortfall>,
}

impl Collector {
    /// A collector that sets the papers' feeds (the strategy of `rule`).
    pub fn new(rule: FeedRule) -> Self {
        Collector::with_objective(rule, None, 0.0)
    }

    /// A collector that sets the feeds of `objective` (`None`: the papers' rule), for a
    /// tool of radius `tool_radius_mm`.
    pub fn with_objective(rule: FeedRule, objective: Option<ObjectiveSpec>, tool_radius_mm: f64) -> Self {
        Collector {
            rule,
            objective,
            tool_radius_mm,
            kept: Vec::new(),
            lengths: ReasonLengths::default(),
            shortfalls: Vec::new(),
            open: None,
        }
    }

    pub fn add(&mut self, s: &SampleIn) {
        // The papers' rule says where the target force cannot be held (the shortfalls);
        // the objective sets the feed.
        let (feed, reason, constant) = if s.rapid {
            (f64::NAN, None, None)
        } else {
            let constant = self.rule.feed(&s.cut);
            let (feed, reason) = match &self.objective {
                Some(objective) => objective.feed(&self.rule, &s.cut, s.force_before_n, constant),
                None => constant,
            };
            (feed, Some(reason), Some(constant.1))
        };
        if let Some(reason) = reason {
            self.lengths.add(reason, s.step_mm);
        }
        let kind = match constant {
            Some(FeedReason::Infeasible) => Some(ShortfallKind::Infeasible),
            Some(FeedReason::ClampedMin) => Some(ShortfallKind::BelowMinimumFeed),
            _ => None,
        };
        match (&mut self.open, kind) {
            (Some(open), Some(k)) if open.kind == k => {
                open.end = s.at;
                open.length_mm += s.step_mm;
                open.max_alpha_deg = open.max_alpha_deg.max(s.cut.alpha_rad.to_degrees());
            }
            (_, k) => {
                if let Some(done) = self.open.take() {
                    self.shortfalls.push(done);
                }
                self.open = k.map(|kind| Shortfall {
                    kind,
                    start: s.at,
                    end: s.at,
                    length_mm: s.step_mm,
                    max_alpha_deg: s.cut.alpha_rad.to_degrees(),
                });
            }
        }
        self.kept.push(Kept {
            move_index: s.move_index as u32,
            step_mm: s.step_mm as f32,
            feed_mm_min: feed as f32,
            reason,
            alpha_rad: s.cut.alpha_rad as f32,
            arc_length_mm: s.cut.arc_length_mm as f32,
            ad_mm: s.cut.ad_mm as f32,
            ratio: s.cut.cutting_point_ratio as f32,
            centre_radius_mm: s.cut.centre_radius_mm as f32,
            spindle_rpm: s.cut.spindle_rpm.unwrap_or(0.0) as f32,
            force_before_n: s.force_before_n.map_or(f32::NAN, |f| f as f32),
            programmed_mm_min: s.cut.programmed_feed_mm_min as f32,
        });
    }

    /// Closes the last open region.
    pub fn finish(&mut self) {
        if let Some(done) = self.open.take() {
            self.shortfalls.push(done);
        }
    }
}
