//! Spiral hole expansion (seed 002 §2.2.3 "spiral milling" and Fig. 2; seed 004 Table 1
//! steps 2 and 6, Table 2: 10 mm straight, S 4800, fz 0.1, Rd 0.5, Ad 10 (5 on the last
//! layer); MODEL.md §8 step 2): a hole of radius `R0` opened to `R1` by a spiral that grows
//! by at most `Rd` per turn, then a full circle at `R1`.
//!
//! The spiral is the classic two-centre arc spiral: half circles alternately about the hole
//! centre `A` and about `B = A + (s/2, 0)`, where `s = (ρ1 − ρ0)/n ≤ Rd` is the growth per
//! turn and `ρ = R − r` the tool-centre radii. Turn `k` is a half circle about `A` of radius
//! `ρ0 + k·s` from `+x` to `−x`, then one about `B` of radius `ρ0 + k·s + s/2` back to `+x`
//! at `ρ0 + (k + 1)·s`. Every half is concentric with the same half of the turn before, one
//! step `s` further out — a concave cut at radial depth `s` (MODEL.md §2) — and the halves
//! meet on the x axis with a common tangent. A climb cut (M3) runs counter-clockwise (G3).

use super::arcs::{at_z, on_circle, PathBuilder};
use super::levels::z_levels;
use super::report::{Cycle, CycleReport};
use super::setup::{CutDirection, CycleSetup};
use super::trochoid::MIN_LOOP_RADIUS_MM;
use crate::core::error::{require_finite, require_positive};
use crate::core::geometry::Point;
use crate::core::tolerance::LENGTH_EPS_MM;
use crate::core::CoreError;

/// Most spiral turns per level.
pub const MAX_SPIRAL_TURNS: f64 = 100_000.0;

/// A hole to expand.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SpiralParams {
    /// Hole centre, mm.
    pub center: Point,
    /// Radius of the hole already open (the bored approach hole), mm (≥ r).
    pub start_radius_mm: f64,
    /// Radius to open it to, mm (> `start_radius_mm`).
    pub final_radius_mm: f64,
    /// Tool radius r, mm.
    pub tool_radius_mm: f64,
    /// Largest growth per turn, mm; default the conditions' Rd.
    pub rd_mm: Option<f64>,
    /// Top of the material and bottom of the hole, mm.
    pub z_top_mm: f64,
    pub z_bottom_mm: f64,
    /// Largest axial depth per level, mm; default the conditions' Ad.
    pub max_ad_mm: Option<f64>,
    pub direction: CutDirection,
}

/// The spiral's geometry at one level.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Spiral {
    center: Point,
    rho0: f64,
    rho1: f64,
    turns: usize,
    clockwise: bool,
}

impl Spiral {
    /// Growth per turn, mm.
    fn step(&self) -> f64 {
        (self.rho1 - self.rho0) / self.turns as f64
    }

    /// Where each level starts: `+x` of the centre at `ρ0`.
    fn start(&self) -> Point {
        on_circle(self.center, self.rho0, (1.0, 0.0))
    }

    fn append(&self, b: &mut PathBuilder, feed_mm_min: f64) {
        let (a, s) = (self.center, self.step());
        let b_centre = a.offset(s / 2.0, 0.0);
        for k in 0..self.turns {
            let rho = self.rho0 + k as f64 * s;
            if rho >= MIN_LOOP_RADIUS_MM {
                b.arc_xy(on_circle(a, -rho, (1.0, 0.0)), a, self.clockwise, feed_mm_min);
            }
            // The last turn ends exactly on ρ1.
            let next = if k + 1 == self.turns { self.rho1 } else { rho + s };
            b.arc_xy(on_circle(a, next, (1.0, 0.0)), b_centre, self.clockwise, feed_mm_min);
        }
        b.full_circle(a, self.clockwise, feed_mm_min);
    }
}

/// Expands the hole level by level: at each level, rapid over the spiral's start inside the
/// open hole, plunge, spiral out to `R1 − r`, a full circle there, and rapid up to the
/// retract height; at the end, up to the clearance height.
pub fn spiral_hole_expansion(params: &SpiralParams, setup: &CycleSetup) -> Result<Cycle, CoreError> {
    setup.validate()?;
    let r = require_positive("tool_radius_mm", params.tool_radius_mm)?;
    let r0 = require_positive("start_radius_mm", params.start_radius_mm)?;
    let r1 = require_positive("final_radius_mm", params.final_radius_mm)?;
    require_finite("center.x", params.center.x)?;
    require_finite("center.y", params.center.y)?;
    if r0 < r - LENGTH_EPS_MM {
        return Err(CoreError::invalid(
            "start_radius_mm",
            format!("the open hole ({r0} mm radius) is narrower than the tool ({r} mm): bore it first"),
        ));
    }
    if r1 <= r0 + LENGTH_EPS_MM {
        return Err(CoreError::invalid("final_radius_mm", "must be larger than start_radius_mm"));
    }
    let rd = require_positive("rd_mm", params.rd_mm.unwrap_or(setup.conditions.rd_mm))?;
    setup.require_below_retract("z_top_mm", params.z_top_mm)?;
    let levels = z_levels(params.z_top_mm, params.z_bottom_mm, params.max_ad_mm.unwrap_or(setup.conditions.ad_mm))?;
    let (rho0, rho1) = ((r0 - r).max(0.0), r1 - r);
    let turns = ((rho1 - rho0 - LENGTH_EPS_MM) / rd).ceil().max(1.0);
    if turns > MAX_SPIRAL_TURNS {
        return Err(CoreError::invalid("rd_mm", format!("gives more than {MAX_SPIRAL_TURNS} turns")));
    }
    let spiral = Spiral {
        center: params.center,
        rho0,
        rho1,
        turns: turns as usize,
        clockwise: params.direction.outside_material_clockwise(),
    };

    let feed = setup.feed_mm_min();
    let retract = setup.retract_z_mm();
    let mut b = PathBuilder::starting_at(at_z(spiral.start(), setup.clearance_z_mm), setup);
    for &z in &levels {
        b.rapid(at_z(spiral.start(), b.position().z));
        b.rapid_z(retract);
        b.line(at_z(spiral.start(), z), setup.plunge_feed_mm_min());
        spiral.append(&mut b, feed);
        b.rapid_z(retract);
    }
    b.rapid_z(setup.clearance_z_mm);
    let moves = b.finish();
    let report = CycleReport {
        levels: levels.len(),
        turns: (turns + 1.0) * levels.len() as f64,
        steps: spiral.turns,
        ..CycleReport::of_moves(&moves, setup.rapid_mm_min)
    };
    Ok(Cycle { moves, report })
}

#[cfg(test)]
#[path = "spiral_tests.rs"]
mod tests;
