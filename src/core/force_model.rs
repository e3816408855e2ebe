//! The response-surface cutting-force model (seed 002 Eq. 1; coefficients in seed 001
//! Table 4; MODEL.md §3):
//!
//! `F_xy = β0 + β1·X1 + β2·X2 + β11·X1² + β22·X2² + β12·X1·X2`,
//! `X1 = (t_m − t0)/δt`, `X2 = (L − L0)/δL`, scaled linearly with `Ad / Ad_ref`.

use crate::core::error::require_positive;
use crate::core::CoreError;
use serde::{Deserialize, Serialize};

/// Central-composite designs put their axial points at ±√2 (MODEL.md §3): inside this
/// coded radius the model interpolates, beyond it it extrapolates.
pub const DESIGN_REGION_CODED_RADIUS: f64 = std::f64::consts::SQRT_2;

/// The design region's squared radius, with a rounding allowance.
const DESIGN_REGION_SQUARED: f64 = (DESIGN_REGION_CODED_RADIUS + 1e-9) * (DESIGN_REGION_CODED_RADIUS + 1e-9);

/// Coefficients of one response surface, in coded variables.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Coefficients {
    pub b0: f64,
    pub b1: f64,
    pub b2: f64,
    pub b11: f64,
    pub b22: f64,
    pub b12: f64,
}

/// A response-surface force model for one tool in one material.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct ForceModel {
    /// Centre of the chip-thickness variable, µm.
    pub t0_um: f64,
    /// Step of the chip-thickness variable, µm.
    pub dt_um: f64,
    /// Centre of the arc-length variable, mm.
    pub l0_mm: f64,
    /// Step of the arc-length variable, mm.
    pub dl_mm: f64,
    pub coefficients: Coefficients,
    /// The axial depth of cut the model was measured at, mm.
    pub ad_ref_mm: f64,
}

/// Coded variables of one (t_m, L) point.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Coded {
    pub x1: f64,
    pub x2: f64,
}

impl Coded {
    /// The coded radius `|X| = √(X1² + X2²)`: how far the point lies from the design
    /// centre, in steps of the experiments (MODEL.md §3).
    pub fn radius(&self) -> f64 {
        self.radius_squared().sqrt()
    }

    /// `X1² + X2²` (cheaper to compare than the radius).
    pub fn radius_squared(&self) -> f64 {
        self.x1 * self.x1 + self.x2 * self.x2
    }

    /// `true` when the point lies inside the experiments' design region (|X| ≤ √2).
    pub fn within_design_region(&self) -> bool {
        self.radius_squared() <= DESIGN_REGION_SQUARED
    }
}

impl Coefficients {
    /// The polynomial of seed 002 Eq. 1 at coded point `(x1, x2)`, N.
    pub fn evaluate(&self, x1: f64, x2: f64) -> f64 {
        self.b0 + self.b1 * x1 + self.b2 * x2 + self.b11 * x1 * x1 + self.b22 * x2 * x2 + self.b12 * x1 * x2
    }
}

impl ForceModel {
    /// Checks that every parameter is finite and the steps and reference depth positive.
    pub fn validate(&self) -> Result<(), CoreError> {
        require_positive("t0_um", self.t0_um)?;
        require_positive("dt_um", self.dt_um)?;
        require_positive("l0_mm", self.l0_mm)?;
        require_positive("dl_mm", self.dl_mm)?;
        require_positive("ad_ref_mm", self.ad_ref_mm)?;
        let c = self.coefficients;
        for (name, v) in [("b0", c.b0), ("b1", c.b1), ("b2", c.b2), ("b11", c.b11), ("b22", c.b22), ("b12", c.b12)] {
            crate::core::error::require_finite(name, v)?;
        }
        Ok(())
    }

    /// F* of MODEL.md §3: the force at the design centre (`X = 0`) and the reference
    /// depth, `β0`, N. The experiments are centred on the tool's standard straight cut.
    pub fn design_centre_force_n(&self) -> f64 {
        self.coefficients.evaluate(0.0, 0.0)
    }

    /// The coded variables `X1 = (t_m − t0)/δt`, `X2 = (L − L0)/δL` (MODEL.md §3).
    pub fn coded(&self, chip_thickness_um: f64, arc_length_mm: f64) -> Coded {
        Coded { x1: (chip_thickness_um - self.t0_um) / self.dt_um, x2: (arc_length_mm - self.l0_mm) / self.dl_mm }
    }

    /// Predicted XY force (N) at chip thickness `t_m` (µm), arc length `L` (mm) and axial
    /// depth `Ad` (mm): seed 002 Eq. 1, scaled linearly with `Ad / Ad_ref` (MODEL.md §3).
    pub fn force_n(&self, chip_thickness_um: f64, arc_length_mm: f64, axial_depth_mm: f64) -> f64 {
        let c = self.coded(chip_thickness_um, arc_length_mm);
        self.coefficients.evaluate(c.x1, c.x2) * axial_depth_mm / self.ad_ref_mm
    }

    /// The chip thickness (µm) at which the model gives `target_force_n` for arc length
    /// `L` and axial depth `Ad` (MODEL.md §3, "constant cutting force"): the model is
    /// quadratic in X1 when β11 ≠ 0 and linear otherwise; the root on the rising branch
    /// (force grows with chip thickness) is taken. `None` when no positive chip thickness
    /// reaches the target.
    pub fn chip_thickness_for_force_um(
        &self,
        target_force_n: f64,
        arc_length_mm: f64,
        axial_depth_mm: f64,
    ) -> Option<f64> {
        let target_at_ref = target_force_n * self.ad_ref_mm / axial_depth_mm;
        let x2 = (arc_length_mm - self.l0_mm) / self.dl_mm;
        let c = self.coefficients;
        let a = c.b11;
        let b = c.b1 + c.b12 * x2;
        let k = c.b0 + c.b2 * x2 + c.b22 * x2 * x2 - target_at_ref;
        let x1 = solve_rising_root(a, b, k)?;
        let t_m = self.t0_um + self.dt_um * x1;
        (t_m.is_finite() && t_m > 0.0).then_some(t_m)
    }
}

/// Coefficient magnitudes below this are treated as zero when solving for X1.
const COEFFICIENT_EPS: f64 = 1e-12;

/// Root of `a·x² + b·x + k = 0` where the polynomial rises (`2a·x + b > 0`).
fn solve_rising_root(a: f64, b: f64, k: f64) -> Option<f64> {
    if a.abs() < COEFFICIENT_EPS {
        if b <= COEFFICIENT_EPS {
            return None;
        }
        return Some(-k / b);
    }
    let disc = b * b - 4.0 * a * k;
    if disc < 0.0 {
        return None;
    }
    // The rising root is the one with 2a·x + b = +sqrt(disc).
    Some((-b + disc.sqrt()) / (2.0 * a))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::core::engagement::{engagement, Contour};
    use crate::core::fixtures::seed_001_ten_mm;
    use crate::core::tolerance::approx_eq;

    #[test]
    fn at_the_design_centre_the_force_is_beta0() {
        assert!(approx_eq(
            {
                let m = seed_001_ten_mm();
                m.force_n(m.t0_um, m.l0_mm, 10.0)
            },
            269.1,
            1e-9
        ));
    }

    #[test]
    fn force_scales_linearly_with_axial_depth() {
        assert!(approx_eq(
            {
                let m = seed_001_ten_mm();
                m.force_n(m.t0_um, m.l0_mm, 5.0)
            },
            269.1 / 2.0,
            1e-9
        ));
    }

    #[test]
    fn solving_for_chip_thickness_inverts_the_model() {
        let m = seed_001_ten_mm();
        let t = m.chip_thickness_for_force_um(300.0, 3.0, 10.0).unwrap();
        assert!(approx_eq(m.force_n(t, 3.0, 10.0), 300.0, 1e-9));
        let quad = ForceModel { coefficients: Coefficients { b11: 2.0, ..m.coefficients }, ..m };
        let t = quad.chip_thickness_for_force_um(300.0, 3.0, 10.0).unwrap();
        assert!(approx_eq(quad.force_n(t, 3.0, 10.0), 300.0, 1e-9));
    }

    #[test]
    fn a_very_long_engagement_arc_cannot_reach_the_target_force() {
        let e = engagement(Contour::Concave { surface_radius_mm: 6.0 }, 5.0, 0.5).unwrap();
        assert!(seed_001_ten_mm().chip_thickness_for_force_um(269.1, e.arc_length_mm, 10.0).is_none());
    }

    #[test]
    fn the_design_region_is_the_circle_of_the_axial_points() {
        assert!(Coded { x1: 1.0, x2: 1.0 }.within_design_region());
        assert!(!Coded { x1: 1.5, x2: 0.0 }.within_design_region());
    }
}
