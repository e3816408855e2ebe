//! The response-surface cutting-force model (seed 002 Eq. 1; coefficients in seed 001
//! Table 4; MODEL.md §3):
//!
//! `F_xy = β0 + β1·X1 + β2·X2 + β11·X1² + β22·X2² + β12·X1·X2`,
//! `X1 = (t_m − t0)/δt`, `X2 = (L − L0)/δL`, scaled with the engaged cutting-edge length
//! at the axial depth: linearly with `Ad / Ad_ref` for a square end mill (MODEL.md §3), by
//! [`engaged_edge_length_mm`] for radius and ball end mills.

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
    /// Corner radius of the tool's cutting edge, mm: the force scales with the engaged edge
    /// length at the axial depth ([`engaged_edge_length_mm`]). 0 (the default) is a square
    /// end mill, whose force scales linearly with `Ad` as in seed 001's tests.
    #[serde(default)]
    pub corner_radius_mm: f64,
}

/// Length of one flute's cutting edge engaged at axial depth `Ad` below the uncut surface,
/// measured from the tool's tip, mm: the edge is a corner arc of radius `rc` and then the
/// straight flank, so `rc·acos(1 − Ad/rc)` while `Ad ≤ rc` and `rc·π/2 + (Ad − rc)` above.
/// A square end mill (`rc` = 0) engages `Ad`; a ball (`rc` = R = D/2) engages
/// `R·acos(1 − Ad/R)` up to its equator. Plane geometry of the tool's profile; our rule
/// (`extrapolated`) for the force of radius and ball end mills, whose forces the papers did
/// not measure (seed 001 Table 1 tests square end mills at Ad = D; MODEL.md §3).
pub fn engaged_edge_length_mm(corner_radius_mm: f64, axial_depth_mm: f64) -> f64 {
    if corner_radius_mm <= 0.0 {
        return axial_depth_mm;
    }
    let depth_mm = axial_depth_mm.max(0.0);
    if depth_mm <= corner_radius_mm {
        corner_radius_mm * (1.0 - depth_mm / corner_radius_mm).acos()
    } else {
        corner_radius_mm * std::f64::consts::FRAC_PI_2 + (depth_mm - corner_radius_mm)
    }
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
        if !(self.corner_radius_mm.is_finite() && self.corner_radius_mm >= 0.0) {
            return Err(CoreError::invalid(
                "corner_radius_mm",
                format!("must be a finite number >= 0, got {}", self.corner_radius_mm),
            ));
        }
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
    /// depth `Ad` (mm, from the tool's tip): seed 002 Eq. 1, scaled by the engaged edge
    /// length at `Ad` over that at `Ad_ref` ([`engaged_edge_length_mm`]; `Ad / Ad_ref` for
    /// a square end mill, MODEL.md §3).
    pub fn force_n(&self, chip_thickness_um: f64, arc_length_mm: f64, axial_depth_mm: f64) -> f64 {
        let c = self.coded(chip_thickness_um, arc_length_mm);
        self.coefficients.evaluate(c.x1, c.x2) * self.edge_length_mm(axial_depth_mm)
            / self.edge_length_mm(self.ad_ref_mm)
    }

    /// The force of the edge between `h_bottom_mm` and `h_bottom_mm + thickness_mm` above the
    /// tool's tip (one z slice of the stock, MODEL.md §3 on the engaged edge): the model's
    /// force scaled by that stretch of edge over the edge engaged at `Ad_ref`. For a square
    /// end mill's model, [`ForceModel::force_n`] at the slice's thickness.
    pub fn slice_force_n(
        &self,
        chip_thickness_um: f64,
        arc_length_mm: f64,
        h_bottom_mm: f64,
        thickness_mm: f64,
    ) -> f64 {
        if self.corner_radius_mm <= 0.0 {
            return self.force_n(chip_thickness_um, arc_length_mm, thickness_mm);
        }
        let c = self.coded(chip_thickness_um, arc_length_mm);
        let edge = self.edge_length_mm(h_bottom_mm + thickness_mm) - self.edge_length_mm(h_bottom_mm);
        self.coefficients.evaluate(c.x1, c.x2) * edge / self.edge_length_mm(self.ad_ref_mm)
    }

    /// The engaged edge length of this model's tool at axial depth `Ad`, mm.
    fn edge_length_mm(&self, axial_depth_mm: f64) -> f64 {
        engaged_edge_length_mm(self.corner_radius_mm, axial_depth_mm)
    }

    /// This model carried over to an end mill of another edge profile and number of flutes:
    /// at equal chip thickness and engagement arc the mean force grows with the cutting edge
    /// in the cut, the flutes in the cut (`z·α/2π`, so `z`) times the edge each engages at
    /// the depth ([`engaged_edge_length_mm`]). Every β is multiplied by
    /// `(z / z_self) · e(rc, Ad_ref) / e(rc_self, Ad_ref_self)`; the centres and steps stay,
    /// so the design region stays that of the experiments. Our rule (`extrapolated`): the
    /// papers measured square end mills only (seed 001 Table 4; MODEL.md §3).
    pub fn carried_over(&self, self_flutes: u32, flutes: u32, corner_radius_mm: f64, ad_ref_mm: f64) -> ForceModel {
        let factor = f64::from(flutes) / f64::from(self_flutes) * engaged_edge_length_mm(corner_radius_mm, ad_ref_mm)
            / self.edge_length_mm(self.ad_ref_mm);
        let c = self.coefficients;
        ForceModel {
            coefficients: Coefficients {
                b0: c.b0 * factor,
                b1: c.b1 * factor,
                b2: c.b2 * factor,
                b11: c.b11 * factor,
                b22: c.b22 * factor,
                b12: c.b12 * factor,
            },
            ad_ref_mm,
            corner_radius_mm,
            ..*self
        }
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
        let target_at_ref = target_force_n * self.edge_length_mm(self.ad_ref_mm) / self.edge_length_mm(axial_depth_mm);
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
    fn the_engaged_edge_is_the_depth_for_a_square_end_mill_and_the_profile_arc_for_ball_and_radius() {
        assert!(approx_eq(engaged_edge_length_mm(0.0, 7.0), 7.0, 1e-12));
        // Ball R5: 5·acos(1 − 0.6/5) = 2.4747 mm at Ad 0.6, a quarter circle at its equator,
        // then the flank.
        assert!(approx_eq(engaged_edge_length_mm(5.0, 0.6), 2.474_670_6, 1e-7));
        assert!(approx_eq(engaged_edge_length_mm(5.0, 5.0), 5.0 * std::f64::consts::FRAC_PI_2, 1e-12));
        assert!(approx_eq(engaged_edge_length_mm(5.0, 7.0), 5.0 * std::f64::consts::FRAC_PI_2 + 2.0, 1e-12));
        // Radius end mill, corner R1: π/3 at Ad 0.5 (on the arc), π/2 + 9 at Ad 10.
        assert!(approx_eq(engaged_edge_length_mm(1.0, 0.5), std::f64::consts::FRAC_PI_3, 1e-12));
        assert!(approx_eq(engaged_edge_length_mm(1.0, 10.0), 10.570_796_3, 1e-7));
        assert!(approx_eq(engaged_edge_length_mm(1.0, 1.0 - 1e-12), engaged_edge_length_mm(1.0, 1.0 + 1e-12), 1e-9));
        assert!(approx_eq(engaged_edge_length_mm(5.0, -1.0), 0.0, 1e-12));
    }

    proptest::proptest! {
        #[test]
        fn the_engaged_edge_grows_with_depth_and_is_longer_than_the_depth_by_at_most_the_corners_bulge(
            rc in 0.0f64..10.0,
            ad in 0.0f64..30.0,
            more in 0.0f64..5.0,
        ) {
            let e = engaged_edge_length_mm(rc, ad);
            proptest::prop_assert!(e >= ad - 1e-12);
            proptest::prop_assert!(e <= ad + rc * (std::f64::consts::FRAC_PI_2 - 1.0) + 1e-12);
            proptest::prop_assert!(engaged_edge_length_mm(rc, ad + more) >= e - 1e-12);
        }
    }

    #[test]
    fn the_r5_balls_model_is_the_square_ones_carried_over_by_flutes_and_engaged_edge() {
        let ball = seed_001_ten_mm().carried_over(6, 2, 5.0, 0.6);
        // Every β × (2/6) × 2.4747/10 = × 0.082489: β0 269.1 → 22.198 N, centres unchanged.
        assert!(approx_eq(ball.coefficients.b0, 22.197_796, 1e-6));
        assert!(approx_eq(ball.coefficients.b12, 15.45 * 0.082_489_021, 1e-6));
        assert!(approx_eq(ball.t0_um, seed_001_ten_mm().t0_um, 1e-12));
        // At its standard side cut (seed 004 Table 7: fz 0.3, Rd 4, Ad 0.6; the 2.5-D
        // engagement α 78.46°, t_m 293.94 µm, L 6.847 mm) the model gives 417.9 N.
        let e = engagement(Contour::Straight, 5.0, 4.0).unwrap();
        let t_um = 1000.0 * 0.3 * e.angle_rad.sin();
        assert!(approx_eq(e.arc_length_mm, 6.847_192, 1e-6) && approx_eq(t_um, 293.938_77, 1e-5));
        assert!(approx_eq(ball.force_n(t_um, e.arc_length_mm, 0.6), 417.922_25, 1e-4));
        // Far outside the square tests' design region: X1 ≈ 17, X2 ≈ 10.5.
        let coded = ball.coded(t_um, e.arc_length_mm);
        assert!(approx_eq(coded.x1, 16.69, 0.01) && approx_eq(coded.x2, 10.53, 0.01), "{coded:?}");
        // Half the depth engages 70.3 % of the edge, not 50 % as a straight flank would.
        let half = ball.force_n(t_um, e.arc_length_mm, 0.3) / ball.force_n(t_um, e.arc_length_mm, 0.6);
        assert!(approx_eq(half, 0.703_459_3, 1e-7));
        let t = ball.chip_thickness_for_force_um(100.0, 6.0, 0.3).unwrap();
        assert!(approx_eq(ball.force_n(t, 6.0, 0.3), 100.0, 1e-9));
    }

    #[test]
    fn a_radius_end_mill_engages_its_corner_arc_and_flank_so_its_model_is_5_7_percent_above_the_square_at_full_depth() {
        let square = seed_001_ten_mm();
        let radius = square.carried_over(6, 6, 1.0, 10.0);
        assert!(approx_eq(radius.coefficients.b0, 284.460_129, 1e-6));
        let (t, l) = (square.t0_um, square.l0_mm);
        assert!(approx_eq(radius.force_n(t, l, 5.0) / radius.force_n(t, l, 10.0), 5.570_796 / 10.570_796, 1e-6));
        // A square end mill carried over to itself is itself.
        assert_eq!(square.carried_over(6, 6, 0.0, 10.0), square);
    }

    #[test]
    fn the_design_region_is_the_circle_of_the_axial_points() {
        assert!(Coded { x1: 1.0, x2: 1.0 }.within_design_region());
        assert!(!Coded { x1: 1.5, x2: 0.0 }.within_design_region());
    }
}
