//! How a fixed cycle runs (seed 002 §2.2.3, MODEL.md §1 and §8): the feeds from the cutting
//! conditions, the heights it moves at between cuts and the cutting direction.

use crate::core::conditions::{feed_mm_min, CuttingConditions};
use crate::core::error::{require_finite, require_positive};
use crate::core::CoreError;
use serde::{Deserialize, Serialize};

/// Plunge feed as a fraction of the cutting feed when none is given (**assumed**: the
/// papers give no plunge feed; a third of the cutting feed is a common shop default).
pub const DEFAULT_PLUNGE_FEED_RATIO: f64 = 1.0 / 3.0;

pub use crate::core::analysis::DEFAULT_RAPID_MM_MIN;

/// Milling direction (MODEL.md §1: down (climb) cut unless the request says otherwise).
///
/// Every cycle assumes an M3 spindle (clockwise seen from above). A tooth of such a tool
/// moves with the feed on the tool's left and against it on its right, so the chip is
/// thickest where the tooth enters (a down cut) when the material is on the **right** of
/// the direction of travel. Around a circle with the material outside, that is a
/// counter-clockwise circle (G3); with the material inside, a clockwise one (G2).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum CutDirection {
    /// Down cut: material on the right of travel (M3 spindle).
    #[default]
    Climb,
    /// Up cut: material on the left of travel.
    Conventional,
}

impl CutDirection {
    /// Whether a circle that cuts the material *outside* it (a hole, a slot, a trochoid
    /// loop, an inner corner) runs clockwise (G2): `false` (G3) for a climb cut.
    pub fn outside_material_clockwise(self) -> bool {
        matches!(self, CutDirection::Conventional)
    }

    /// +1 for counter-clockwise travel about material outside the circle, −1 for clockwise.
    pub fn turn_sign(self) -> f64 {
        if self.outside_material_clockwise() {
            -1.0
        } else {
            1.0
        }
    }
}

/// Feeds, heights and tool of a cycle.
///
/// Heights follow the G98/G99 convention of canned cycles: the tool arrives and leaves at
/// `clearance_z_mm` (the initial plane), rapids down to `retract_z_mm` (the R plane, just
/// above the material) and feeds from there; inside a cycle it moves between passes at the
/// retract height.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct CycleSetup {
    /// The operation's cutting conditions (MODEL.md §5): S, fz, Rd and Ad.
    pub conditions: CuttingConditions,
    /// Flutes of the tool, z in `F = fz·z·S`.
    pub flutes: u32,
    /// Safe height the cycle starts and ends at, mm.
    pub clearance_z_mm: f64,
    /// Height the tool rapids down to and feeds from, mm; default the clearance height.
    pub retract_z_mm: Option<f64>,
    /// Feed of plunges, mm/min; default [`DEFAULT_PLUNGE_FEED_RATIO`] × the cutting feed.
    pub plunge_feed_mm_min: Option<f64>,
    /// Feed of the moves that cut nothing (the return half of a trochoid loop), mm/min;
    /// default the cutting feed.
    pub air_feed_mm_min: Option<f64>,
    /// Rapid rate for the time estimate, mm/min.
    pub rapid_mm_min: f64,
    /// Tool number written on every move, if known.
    pub tool: Option<u32>,
}

impl CycleSetup {
    /// A setup with the default plunge feed and rapid rate, retracting to the clearance height.
    pub fn new(conditions: CuttingConditions, flutes: u32, clearance_z_mm: f64) -> CycleSetup {
        CycleSetup {
            conditions,
            flutes,
            clearance_z_mm,
            retract_z_mm: None,
            plunge_feed_mm_min: None,
            air_feed_mm_min: None,
            rapid_mm_min: DEFAULT_RAPID_MM_MIN,
            tool: None,
        }
    }

    /// Checks the conditions, the heights and the feeds.
    pub fn validate(&self) -> Result<(), CoreError> {
        self.conditions.validate()?;
        if self.flutes == 0 {
            return Err(CoreError::invalid("flutes", "must be at least 1"));
        }
        require_finite("clearance_z_mm", self.clearance_z_mm)?;
        if let Some(r) = self.retract_z_mm {
            require_finite("retract_z_mm", r)?;
            if r > self.clearance_z_mm {
                return Err(CoreError::invalid("retract_z_mm", "must not be above clearance_z_mm"));
            }
        }
        if let Some(f) = self.plunge_feed_mm_min {
            require_positive("plunge_feed_mm_min", f)?;
        }
        if let Some(f) = self.air_feed_mm_min {
            require_positive("air_feed_mm_min", f)?;
        }
        require_positive("rapid_mm_min", self.rapid_mm_min)?;
        Ok(())
    }

    /// Cutting feed `F = fz·z·S` (MODEL.md §1), mm/min.
    pub fn feed_mm_min(&self) -> f64 {
        feed_mm_min(self.conditions.fz_mm, self.flutes, self.conditions.spindle_rpm)
    }

    /// Plunge feed, mm/min.
    pub fn plunge_feed_mm_min(&self) -> f64 {
        self.plunge_feed_mm_min.unwrap_or(DEFAULT_PLUNGE_FEED_RATIO * self.feed_mm_min())
    }

    /// Feed of the moves in the air, mm/min: the given one, else the cutting feed.
    pub fn air_feed_mm_min(&self) -> f64 {
        self.air_feed_mm_min.unwrap_or_else(|| self.feed_mm_min())
    }

    /// The R plane, mm.
    pub fn retract_z_mm(&self) -> f64 {
        self.retract_z_mm.unwrap_or(self.clearance_z_mm)
    }

    /// Checks that the cut at `z_mm` lies below the retract height.
    pub fn require_below_retract(&self, field: &str, z_mm: f64) -> Result<(), CoreError> {
        require_finite(field, z_mm)?;
        if z_mm >= self.retract_z_mm() {
            return Err(CoreError::invalid(
                field,
                format!("{z_mm} mm is not below the retract height {} mm", self.retract_z_mm()),
            ));
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::core::tolerance::approx_eq;

    fn grooving() -> CuttingConditions {
        CuttingConditions { spindle_rpm: 4800.0, fz_mm: 0.1, rd_mm: 0.5, ad_mm: 10.0 }
    }

    #[test]
    fn the_feed_is_fz_times_flutes_times_speed_and_the_plunge_a_third_of_it() {
        let s = CycleSetup::new(grooving(), 6, 50.0);
        assert!(approx_eq(s.feed_mm_min(), 2880.0, 1e-9));
        assert!(approx_eq(s.plunge_feed_mm_min(), 960.0, 1e-9));
        assert!(approx_eq(s.retract_z_mm(), 50.0, 0.0));
    }

    #[test]
    fn a_retract_height_above_the_clearance_is_refused() {
        let s = CycleSetup { retract_z_mm: Some(60.0), ..CycleSetup::new(grooving(), 6, 50.0) };
        assert!(s.validate().unwrap_err().to_string().starts_with("retract_z_mm"));
    }

    #[test]
    fn a_climb_cut_runs_counter_clockwise_about_material_outside_the_circle() {
        assert!(!CutDirection::Climb.outside_material_clockwise());
        assert!(CutDirection::Conventional.outside_material_clockwise());
        assert!(approx_eq(CutDirection::Climb.turn_sign(), 1.0, 0.0));
    }
}
