//! The feed one sample needs under a strategy: constant feed at the cutting point
//! (seed 000, Eq. 1), constant cutting force (MODEL.md §3), or the lower of both; air
//! cuts at the air-cut feed; everything clamped to the limits.

use super::constant_force::{constant_force_feed, Cut, FeedLimits};
use crate::core::engagement::ToothCut;
use crate::core::force_model::ForceModel;
use serde::{Deserialize, Serialize};

/// How the feeds are chosen.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum FeedStrategy {
    /// The programmed feed held at the cutting point (seed 000).
    CuttingPoint,
    /// The feed that holds the cutting force at the target (seeds 001–003).
    ConstantForce,
    /// Constant force, capped by the cutting-point rule.
    Both,
}

impl FeedStrategy {
    pub fn needs_force_model(self) -> bool {
        !matches!(self, FeedStrategy::CuttingPoint)
    }
}

/// Why a sample got its feed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum FeedReason {
    /// The strategy's feed, within the limits.
    Target,
    /// The strategy wanted more than the maximum feed.
    ClampedMax,
    /// The strategy wanted less than the minimum feed: the force is above the target.
    ClampedMin,
    /// No positive chip thickness reaches the target force: minimum feed (the region
    /// needs a trochoid or a z-cut division).
    Infeasible,
    /// The tool is in the air: the air-cut feed.
    Air,
    /// Nothing to compute with (no spindle speed, or a plunge): the programmed feed.
    Kept,
}

/// What is known about the cut at one sample.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SampleCut {
    pub alpha_rad: f64,
    pub arc_length_mm: f64,
    pub ad_mm: f64,
    /// Feed at the cutting point over feed at the tool centre (pivot-bounded).
    pub cutting_point_ratio: f64,
    /// The centre-path radius the ratio was computed at, mm (infinite: straight).
    pub centre_radius_mm: f64,
    pub tool_radius_mm: f64,
    pub programmed_feed_mm_min: f64,
    pub spindle_rpm: Option<f64>,
    /// A plunge (no XY motion) into material.
    pub plunge: bool,
    /// The tool touches material (α > 0 in side milling; always in surface finishing).
    pub in_material: bool,
}

impl SampleCut {
    /// What bounds the chip of one tooth here (MODEL.md §2).
    pub fn tooth(&self) -> ToothCut {
        ToothCut {
            alpha_rad: self.alpha_rad,
            cutting_point_ratio: self.cutting_point_ratio,
            centre_radius_mm: self.centre_radius_mm,
            tool_radius_mm: self.tool_radius_mm,
        }
    }
}

/// The strategy with its model, target and limits.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FeedRule {
    pub strategy: FeedStrategy,
    pub force_model: Option<ForceModel>,
    pub target_force_n: f64,
    pub flutes: u32,
    pub min_feed_mm_min: f64,
    pub max_feed_mm_min: f64,
    pub air_feed_mm_min: f64,
}

impl FeedRule {
    fn clamp(&self, feed: f64) -> (f64, FeedReason) {
        if feed > self.max_feed_mm_min {
            (self.max_feed_mm_min, FeedReason::ClampedMax)
        } else if feed < self.min_feed_mm_min {
            (self.min_feed_mm_min, FeedReason::ClampedMin)
        } else {
            (feed, FeedReason::Target)
        }
    }

    /// The programmed feed, capped by the maximum. A programmed feed below the minimum
    /// (a slow plunge) is kept: raising it could break the tool.
    fn kept(&self, cut: &SampleCut) -> (f64, FeedReason) {
        (cut.programmed_feed_mm_min.min(self.max_feed_mm_min), FeedReason::Kept)
    }

    /// The feed at the tool centre that holds the programmed feed at the cutting point
    /// (seed 000, Eq. 1: `F_c = F_p · R / |PO|`, `|PO| / R` being the ratio).
    fn cutting_point(&self, cut: &SampleCut) -> (f64, FeedReason) {
        self.clamp(cut.programmed_feed_mm_min / cut.cutting_point_ratio)
    }

    fn constant_force(&self, cut: &SampleCut, spindle_rpm: f64) -> (f64, FeedReason) {
        let Some(model) = self.force_model else {
            return self.kept(cut);
        };
        let limits = FeedLimits {
            flutes: self.flutes,
            spindle_rpm,
            min_feed_mm_min: self.min_feed_mm_min,
            max_feed_mm_min: self.max_feed_mm_min,
        };
        let c = Cut { tooth: cut.tooth(), arc_length_mm: cut.arc_length_mm, ad_mm: cut.ad_mm };
        let f = constant_force_feed(&model, self.target_force_n, c, limits);
        match f.unclamped_mm_min {
            None => (f.feed_mm_min, FeedReason::Infeasible),
            Some(unclamped) => self.clamp(unclamped),
        }
    }

    /// The feed `cut` needs, and why.
    pub fn feed(&self, cut: &SampleCut) -> (f64, FeedReason) {
        if cut.plunge {
            return self.kept(cut);
        }
        if !cut.in_material {
            return (self.air_feed_mm_min, FeedReason::Air);
        }
        match self.strategy {
            FeedStrategy::CuttingPoint => self.cutting_point(cut),
            FeedStrategy::ConstantForce | FeedStrategy::Both => {
                let Some(rpm) = cut.spindle_rpm.filter(|s| *s > 0.0) else {
                    return self.kept(cut);
                };
                let force = self.constant_force(cut, rpm);
                if self.strategy == FeedStrategy::Both {
                    let point = self.cutting_point(cut);
                    if point.0 < force.0 {
                        return point;
                    }
                }
                force
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::core::engagement::{engagement, Contour};
    use crate::core::fixtures::seed_001_ten_mm;

    fn rule(strategy: FeedStrategy) -> FeedRule {
        FeedRule {
            strategy,
            force_model: Some(seed_001_ten_mm()),
            target_force_n: 269.1,
            flutes: 6,
            min_feed_mm_min: 288.0,
            max_feed_mm_min: 11520.0,
            air_feed_mm_min: 11520.0,
        }
    }

    fn concave(ratio: f64) -> SampleCut {
        let e = engagement(Contour::Concave { surface_radius_mm: 5.0 * ratio }, 5.0, 0.5).unwrap();
        SampleCut {
            alpha_rad: e.angle_rad,
            arc_length_mm: e.arc_length_mm,
            ad_mm: 10.0,
            cutting_point_ratio: e.cutting_point_feed_ratio,
            centre_radius_mm: 5.0 * ratio - 5.0,
            tool_radius_mm: 5.0,
            programmed_feed_mm_min: 5760.0,
            spindle_rpm: Some(9600.0),
            plunge: false,
            in_material: true,
        }
    }

    #[test]
    fn constant_force_at_r_over_r_2_gives_the_model_section_3_feed() {
        let (f, why) = rule(FeedStrategy::ConstantForce).feed(&concave(2.0));
        assert_eq!(why, FeedReason::Target);
        assert!((f - 1160.0).abs() / 1160.0 < 0.02, "{f}");
    }

    #[test]
    fn the_cutting_point_rule_raises_the_centre_feed_in_a_concave_arc_by_its_ratio() {
        let cut = concave(2.0);
        let (f, _) = rule(FeedStrategy::CuttingPoint).feed(&cut);
        assert!((f - 5760.0 / cut.cutting_point_ratio).abs() < 1e-9);
    }

    #[test]
    fn both_takes_the_lower_of_the_two() {
        let cut = concave(3.0);
        let (both, _) = rule(FeedStrategy::Both).feed(&cut);
        let (force, _) = rule(FeedStrategy::ConstantForce).feed(&cut);
        let (point, _) = rule(FeedStrategy::CuttingPoint).feed(&cut);
        assert!((both - force.min(point)).abs() < 1e-9);
    }

    #[test]
    fn air_plunges_and_unknown_spindles_are_told_apart() {
        let r = rule(FeedStrategy::ConstantForce);
        let air = SampleCut { alpha_rad: 0.0, in_material: false, ..concave(2.0) };
        assert_eq!(r.feed(&air), (11520.0, FeedReason::Air));
        let plunge = SampleCut { plunge: true, programmed_feed_mm_min: 300.0, ..concave(2.0) };
        assert_eq!(r.feed(&plunge), (300.0, FeedReason::Kept));
        let no_spindle = SampleCut { spindle_rpm: None, ..concave(2.0) };
        assert_eq!(r.feed(&no_spindle), (5760.0, FeedReason::Kept));
    }

    #[test]
    fn r_over_r_1_2_is_infeasible_and_1_3_is_below_the_minimum() {
        let r = rule(FeedStrategy::ConstantForce);
        assert_eq!(r.feed(&concave(1.2)), (288.0, FeedReason::Infeasible));
        assert_eq!(r.feed(&concave(1.3)), (288.0, FeedReason::ClampedMin));
    }
}
