//! Opening a round region from its centre (seed 004 Table 1 steps 1–2; MODEL.md §8): where the
//! medial axis is a single point (a circular pocket, or a round end of a region the base path
//! starts in), the tool enters by a helix on a small circle (the approach hole) and spirals out
//! to the walls. Each turn grows by the largest step that keeps the concave cut under the
//! engagement limit (MODEL.md §2 solved for Rd, see [`max_concave_rd_mm`]), at most the
//! grooving Rd: small near the centre, where the machined radius is close to `r`, larger
//! further out.
//!
//! Each turn is the two-centre spiral of [`crate::core::cycles::spiral_hole_expansion`]: a half
//! circle about the centre `A` of radius `ρ_k`, then a half circle about `A + (s_k/2, 0)` of
//! radius `ρ_k + s_k/2`, arriving at `ρ_k+1 = ρ_k + s_k`; then a full circle at the last radius.

use super::spec::{InsertionSpec, PITCH_DESIGN_MARGIN_DEG};
use crate::core::cycles::arcs::{on_circle, PathBuilder};
use crate::core::cycles::max_concave_rd_mm;
use crate::core::cycles::trochoid::default_loop_radius_mm;
use crate::core::geometry::Point;
use crate::core::tolerance::LENGTH_EPS_MM;

/// Smallest growth per turn, mm: below it the spiral would take thousands of turns (the
/// region is then left to the base path and the check reports it).
pub const MIN_SPIRAL_STEP_MM: f64 = 0.01;

/// Most turns of one opening.
pub const MAX_OPENING_TURNS: usize = 100_000;

/// A round region opened from its centre.
#[derive(Debug, Clone)]
pub struct OpeningStretch {
    pub centre: Point,
    /// Tool-centre radius at the start of each turn, then the last (one more entry), mm.
    pub radii_mm: Vec<f64>,
}

impl OpeningStretch {
    /// The tool-centre radius of the last circle, mm.
    pub fn final_radius_mm(&self) -> f64 {
        self.radii_mm[self.radii_mm.len() - 1]
    }

    /// Where the helix starts and the spiral begins: `+x` of the centre at the first radius.
    pub fn start(&self) -> Point {
        on_circle(self.centre, self.radii_mm[0], (1.0, 0.0))
    }

    /// Appends the spiral turns and the closing circle at the builder's height.
    pub fn append_spiral(&self, b: &mut PathBuilder, clockwise: bool, feed_mm_min: f64) {
        let a = self.centre;
        for w in self.radii_mm.windows(2) {
            let (rho, next) = (w[0], w[1]);
            let s = next - rho;
            b.arc_xy(on_circle(a, -rho, (1.0, 0.0)), a, clockwise, feed_mm_min);
            b.arc_xy(on_circle(a, next, (1.0, 0.0)), a.offset(s / 2.0, 0.0), clockwise, feed_mm_min);
        }
        b.full_circle(a, clockwise, feed_mm_min);
    }
}

/// Plans the opening of the round region about `centre` of clearance `clearance_mm`, from a
/// helix of the default trochoid radius ((1.2 − 1)·r); `None` when the tool does not fit or a
/// step would be below [`MIN_SPIRAL_STEP_MM`].
pub fn plan_opening(centre: Point, clearance_mm: f64, spec: &InsertionSpec) -> Option<OpeningStretch> {
    let r = spec.r_mm();
    let last = clearance_mm - r - spec.allowance_mm - spec.wall_gap_mm;
    let first = default_loop_radius_mm(r);
    if last <= first + LENGTH_EPS_MM {
        return None;
    }
    let limit = (spec.alpha_limit_deg - PITCH_DESIGN_MARGIN_DEG).to_radians();
    let mut radii = vec![first];
    while radii[radii.len() - 1] < last - LENGTH_EPS_MM {
        let rho = radii[radii.len() - 1];
        let step = max_concave_rd_mm(rho + r, r, limit).min(spec.max_pitch_mm());
        if step < MIN_SPIRAL_STEP_MM || radii.len() > MAX_OPENING_TURNS {
            return None;
        }
        radii.push((rho + step).min(last));
    }
    Some(OpeningStretch { centre, radii_mm: radii })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::core::conditions::CuttingConditions;
    use crate::core::tool::{EndMill, ToolType};

    #[test]
    fn a_30_mm_hole_opens_in_steps_that_grow_outwards_and_never_exceed_a_straight_cut_at_the_limit() {
        let tool = EndMill { tool_type: ToolType::Square, diameter_mm: 10.0, flutes: 6, corner_radius_mm: 0.0 };
        let c = CuttingConditions { spindle_rpm: 4800.0, fz_mm: 0.1, rd_mm: 0.5, ad_mm: 10.0 };
        let spec = InsertionSpec::new(tool, c, c, 0.0, -10.0);
        let o = plan_opening(Point::new(0.0, 0.0), 30.0, &spec).unwrap();
        let steps: Vec<f64> = o.radii_mm.windows(2).map(|w| w[1] - w[0]).collect();
        // r·(1 − cos 40°) = 1.17 mm: no turn's step engages more than a straight cut at the limit.
        assert!((spec.max_pitch_mm() - 5.0 * (1.0 - 40f64.to_radians().cos())).abs() < 1e-12);
        assert!(steps[0] < 0.3 && steps.iter().all(|s| *s <= spec.max_pitch_mm() + 1e-12), "{steps:?}");
        assert!(steps.windows(2).take(steps.len() - 2).all(|w| w[1] >= w[0] - 1e-12));
        assert!((o.final_radius_mm() - (30.0 - 5.0 - spec.wall_gap_mm)).abs() < 1e-9);
    }
}
