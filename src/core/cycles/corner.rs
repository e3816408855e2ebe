//! Corner milling (seed 002 §2.2.3 and Fig. 2, the fourth fixed cycle; MODEL.md §8): an
//! inner corner left by a larger tool (or by the contour-parallel path) with a corner
//! radius `R_prev` is cut down to the finished corner radius `R_f` in steps, each step a
//! fillet arc tangent to both walls, so that the engagement stays under a limit (40° by
//! default, seed 002 §2.4 and seed 004 §2.1).
//!
//! A fillet of radius `R` in a corner of interior angle `θ` has its centre on the bisector
//! at `R / sin(θ/2)` from the vertex, so going from `R_k−1` to `R_k` cuts at most
//! `Δ = (R_k−1 − R_k)·(1/sin(θ/2) − 1)` deep, on the bisector. Each step takes the smallest
//! `R_k` whose `Δ` is no more than the largest radial depth of a concave cut of surface radius
//! `R_k` with `α ≤ α_limit` — the inverse of MODEL.md §2's concave formula. The previous
//! fillet is flatter than the concentric surface that formula assumes and touches it on the
//! bisector from outside, so the formula bounds the engagement there.
//!
//! Each step: the tool rapids over a point on the wall's offset line beyond the material,
//! plunges, feeds along that wall into the corner, round the fillet arc (radius `R_k − r`)
//! and out along the other wall, then rapids up to the retract height. A climb cut (M3)
//! has the corner on the right: counter-clockwise about the fillet centre (G3).

use super::arcs::{at_z, on_circle, PathBuilder};
use super::levels::z_levels;
use super::report::{Cycle, CycleReport};
use super::setup::{CutDirection, CycleSetup};
use super::trochoid::MIN_LOOP_RADIUS_MM;
use crate::core::error::{require_finite, require_positive};
use crate::core::geometry::Point;
use crate::core::tolerance::LENGTH_EPS_MM;
use crate::core::CoreError;

/// Default engagement limit, deg (seed 002 §2.4: tool temperature rises sharply above 40°).
pub const DEFAULT_CORNER_ALPHA_LIMIT_DEG: f64 = 40.0;

/// The lead-in starts this far beyond where the material can reach the tool, mm.
pub const LEAD_CLEARANCE_MM: f64 = 0.5;

/// Interior angles accepted, deg: outside them the corner is a slot or no corner.
pub const MIN_CORNER_ANGLE_DEG: f64 = 1.0;
pub const MAX_CORNER_ANGLE_DEG: f64 = 179.0;

/// Most steps one corner may take.
pub const MAX_CORNER_STEPS: usize = 1000;

/// Bisection iterations when solving for a step's radius.
const BISECTION_STEPS: usize = 100;

/// An inner corner to clear.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CornerParams {
    /// Where the two walls' lines meet, mm.
    pub vertex: Point,
    /// Directions from the vertex along each wall, away from the corner (need not be unit).
    pub wall_a: (f64, f64),
    pub wall_b: (f64, f64),
    /// Corner radius of the finished contour, mm (> r).
    pub final_radius_mm: f64,
    /// Corner radius left by the previous tool or path, mm (> `final_radius_mm`).
    pub previous_radius_mm: f64,
    /// Tool radius r, mm.
    pub tool_radius_mm: f64,
    /// Largest engagement, deg; default [`DEFAULT_CORNER_ALPHA_LIMIT_DEG`].
    pub alpha_limit_deg: Option<f64>,
    /// Top of the material and bottom of the corner, mm.
    pub z_top_mm: f64,
    pub z_bottom_mm: f64,
    /// Largest axial depth per level, mm; default the conditions' Ad.
    pub max_ad_mm: Option<f64>,
    pub direction: CutDirection,
}

/// Largest radial depth of a concave cut of machined radius `R` with engagement at most
/// `α` (MODEL.md §2 solved for Rd): `Rd = R − sqrt(Rc² + r² + 2·Rc·r·cos α)`, `Rc = R − r`.
pub fn max_concave_rd_mm(surface_radius_mm: f64, tool_radius_mm: f64, alpha_rad: f64) -> f64 {
    let rc = surface_radius_mm - tool_radius_mm;
    let r = tool_radius_mm;
    surface_radius_mm - (rc * rc + r * r + 2.0 * rc * r * alpha_rad.cos()).max(0.0).sqrt()
}

/// The corner's frame: unit walls ordered so that `first × second > 0`, and `sin(θ/2)`.
struct Frame {
    vertex: Point,
    first: (f64, f64),
    second: (f64, f64),
    bisector: (f64, f64),
    half_sin: f64,
    half_tan: f64,
}

impl Frame {
    fn new(p: &CornerParams) -> Result<Frame, CoreError> {
        let unit = |field: &str, d: (f64, f64)| -> Result<(f64, f64), CoreError> {
            require_finite(field, d.0)?;
            require_finite(field, d.1)?;
            let l = d.0.hypot(d.1);
            if l <= LENGTH_EPS_MM {
                return Err(CoreError::invalid(field, "must be a direction (non-zero)"));
            }
            Ok((d.0 / l, d.1 / l))
        };
        let (a, b) = (unit("wall_a", p.wall_a)?, unit("wall_b", p.wall_b)?);
        let cross = a.0 * b.1 - a.1 * b.0;
        let theta = cross.abs().atan2(a.0 * b.0 + a.1 * b.1);
        let deg = theta.to_degrees();
        if !(MIN_CORNER_ANGLE_DEG..=MAX_CORNER_ANGLE_DEG).contains(&deg) {
            return Err(CoreError::invalid(
                "wall_b",
                format!(
                    "the walls meet at {deg:.2}°; a corner needs {MIN_CORNER_ANGLE_DEG}° to {MAX_CORNER_ANGLE_DEG}°"
                ),
            ));
        }
        let (first, second) = if cross > 0.0 { (a, b) } else { (b, a) };
        let (bx, by) = (first.0 + second.0, first.1 + second.1);
        let bl = bx.hypot(by);
        Ok(Frame {
            vertex: p.vertex,
            first,
            second,
            bisector: (bx / bl, by / bl),
            half_sin: (theta / 2.0).sin(),
            half_tan: (theta / 2.0).tan(),
        })
    }

    /// Depth cut on the bisector per unit of radius reduction, `1/sin(θ/2) − 1`.
    fn depth_per_radius(&self) -> f64 {
        1.0 / self.half_sin - 1.0
    }

    /// Centre of the fillet of radius `R`.
    fn centre(&self, radius_mm: f64) -> Point {
        on_circle(self.vertex, radius_mm / self.half_sin, self.bisector)
    }

    /// The tool centre at `along` mm from the vertex along `wall`, `r` off it.
    fn on_wall(&self, wall: (f64, f64), along_mm: f64, r: f64) -> Point {
        // The inward normal of a wall points to the bisector's side.
        let n = if (wall.0 * self.bisector.1 - wall.1 * self.bisector.0) > 0.0 {
            (-wall.1, wall.0)
        } else {
            (wall.1, -wall.0)
        };
        self.vertex.offset(wall.0 * along_mm + n.0 * r, wall.1 * along_mm + n.1 * r)
    }
}

/// The surface radii of the steps, from the first cut to `R_f` (MODEL.md §2, concave).
pub fn corner_step_radii(params: &CornerParams) -> Result<Vec<f64>, CoreError> {
    let frame = Frame::new(params)?;
    step_radii(params, &frame)
}

fn step_radii(p: &CornerParams, frame: &Frame) -> Result<Vec<f64>, CoreError> {
    let r = require_positive("tool_radius_mm", p.tool_radius_mm)?;
    let r_final = require_positive("final_radius_mm", p.final_radius_mm)?;
    let r_prev = require_positive("previous_radius_mm", p.previous_radius_mm)?;
    if r_final < r + MIN_LOOP_RADIUS_MM {
        return Err(CoreError::invalid(
            "final_radius_mm",
            format!("a {r_final} mm corner radius is not larger than the tool radius {r} mm: no step can keep the engagement limited"),
        ));
    }
    if r_prev <= r_final + LENGTH_EPS_MM {
        return Err(CoreError::invalid("previous_radius_mm", "must be larger than final_radius_mm"));
    }
    let limit_deg = p.alpha_limit_deg.unwrap_or(DEFAULT_CORNER_ALPHA_LIMIT_DEG);
    if !(limit_deg > 0.0 && limit_deg < 180.0) {
        return Err(CoreError::invalid("alpha_limit_deg", "must be between 0 and 180"));
    }
    let alpha = limit_deg.to_radians();
    let k = frame.depth_per_radius();
    let mut radii = Vec::new();
    let mut current = r_prev;
    while current > r_final + LENGTH_EPS_MM {
        // g(R) = (current − R)·k − Rd_max(R) falls as R grows; the step is the smallest
        // R ≥ R_f with g(R) ≤ 0.
        let g = |radius: f64| (current - radius) * k - max_concave_rd_mm(radius, r, alpha);
        let next = if g(r_final) <= 0.0 {
            r_final
        } else {
            let (mut lo, mut hi) = (r_final, current);
            for _ in 0..BISECTION_STEPS {
                let mid = 0.5 * (lo + hi);
                if g(mid) <= 0.0 {
                    hi = mid;
                } else {
                    lo = mid;
                }
            }
            hi
        };
        radii.push(next);
        current = next;
        if radii.len() > MAX_CORNER_STEPS {
            return Err(CoreError::invalid(
                "final_radius_mm",
                format!(
                    "clearing the corner from {r_prev} to {r_final} mm at α ≤ {limit_deg}° takes more than {MAX_CORNER_STEPS} steps: use a smaller tool"
                ),
            ));
        }
    }
    Ok(radii)
}

/// Clears the corner level by level, each level in the steps of [`corner_step_radii`].
pub fn corner_milling(params: &CornerParams, setup: &CycleSetup) -> Result<Cycle, CoreError> {
    setup.validate()?;
    require_finite("vertex.x", params.vertex.x)?;
    require_finite("vertex.y", params.vertex.y)?;
    let frame = Frame::new(params)?;
    let radii = step_radii(params, &frame)?;
    setup.require_below_retract("z_top_mm", params.z_top_mm)?;
    let levels = z_levels(params.z_top_mm, params.z_bottom_mm, params.max_ad_mm.unwrap_or(setup.conditions.ad_mm))?;
    let r = params.tool_radius_mm;
    let clockwise = params.direction.outside_material_clockwise();
    // Climb (counter-clockwise about the fillet centre): in along the second wall, out
    // along the first; conventional the other way round.
    let (wall_in, wall_out) = if clockwise { (frame.first, frame.second) } else { (frame.second, frame.first) };
    // The material reaches along each wall no further than the previous fillet's tangent point.
    let lead_mm = params.previous_radius_mm / frame.half_tan + r + LEAD_CLEARANCE_MM;
    let (feed, plunge, retract) = (setup.feed_mm_min(), setup.plunge_feed_mm_min(), setup.retract_z_mm());

    let lead_in = frame.on_wall(wall_in, lead_mm, r);
    let mut b = PathBuilder::starting_at(at_z(lead_in, setup.clearance_z_mm), setup);
    for &z in &levels {
        for &radius in &radii {
            let centre = frame.centre(radius);
            let tangent = radius / frame.half_tan;
            b.rapid(at_z(lead_in, b.position().z));
            b.rapid_z(retract);
            b.line(at_z(lead_in, z), plunge);
            b.line(at_z(frame.on_wall(wall_in, tangent, r), z), feed);
            b.arc_xy(frame.on_wall(wall_out, tangent, r), centre, clockwise, feed);
            b.line(at_z(frame.on_wall(wall_out, lead_mm, r), z), feed);
            b.rapid_z(retract);
        }
    }
    b.rapid_z(setup.clearance_z_mm);
    let moves = b.finish();
    let report =
        CycleReport { levels: levels.len(), steps: radii.len(), ..CycleReport::of_moves(&moves, setup.rapid_mm_min) };
    Ok(Cycle { moves, report })
}

#[cfg(test)]
#[path = "corner_tests.rs"]
mod tests;
