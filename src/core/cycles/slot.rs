//! Trochoidal grooving of a straight slot (seed 004 Table 1 steps 3 and 7: 20 × 60 mm and
//! 12 × 800 mm slots with a 10 mm straight end mill; seed 002 Fig. 3(b)): a trochoid along
//! the slot's centre line whose loops sweep its full width, `ρ = w/2 − r − allowance`,
//! repeated at z levels no more than the operation's Ad apart (z-cut division, MODEL.md §7).
//!
//! The slot is the stadium of width `w` around the segment from `start` to `end` (the
//! centre line, length `L`): the loops' ends are half circles of radius `w/2`, so the cleared
//! area is `w·L + π·w²/4`. Each level starts at `start`, which must be open to the bottom
//! (the approach hole of Table 1 steps 1–2) unless the entry is helical.

use super::arcs::{at_z, PathBuilder};
use super::guide::Guide;
use super::levels::z_levels;
use super::report::{Cycle, CycleReport};
use super::setup::{CutDirection, CycleSetup};
use super::trochoid::{validate_entry, Entry, LoopPlan, LoopRadius, MIN_LOOP_RADIUS_MM};
use crate::core::error::{require_finite, require_positive};
use crate::core::geometry::Point;
use crate::core::tolerance::LENGTH_EPS_MM;
use crate::core::CoreError;

/// A straight slot to groove.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SlotParams {
    /// Centre of the slot's first end (where each level starts), mm.
    pub start: Point,
    /// Centre of its other end, mm.
    pub end: Point,
    /// Slot width w, mm.
    pub width_mm: f64,
    /// Tool radius r, mm.
    pub tool_radius_mm: f64,
    /// Stock left on the walls, mm (≥ 0).
    pub allowance_mm: f64,
    /// Advance per loop, mm; default the conditions' Rd.
    pub pitch_mm: Option<f64>,
    /// Top of the material and bottom of the slot, mm.
    pub z_top_mm: f64,
    pub z_bottom_mm: f64,
    /// Largest axial depth per level, mm; default the conditions' Ad.
    pub max_ad_mm: Option<f64>,
    pub direction: CutDirection,
    pub entry: Entry,
}

/// Loop radius that sweeps a slot of width `w`: `w/2 − r − allowance`, mm.
pub fn slot_loop_radius_mm(width_mm: f64, tool_radius_mm: f64, allowance_mm: f64) -> f64 {
    width_mm / 2.0 - tool_radius_mm - allowance_mm
}

/// Grooves the slot by trochoids, level by level (seed 004 Table 1). Between levels the tool
/// rapids up to the retract height and back over the start.
pub fn trochoidal_slot(params: &SlotParams, setup: &CycleSetup) -> Result<Cycle, CoreError> {
    setup.validate()?;
    validate_entry(params.entry)?;
    let w = require_positive("width_mm", params.width_mm)?;
    let r = require_positive("tool_radius_mm", params.tool_radius_mm)?;
    let allowance = require_finite("allowance_mm", params.allowance_mm)?;
    if allowance < 0.0 {
        return Err(CoreError::invalid("allowance_mm", "must not be negative"));
    }
    for (field, v) in
        [("start.x", params.start.x), ("start.y", params.start.y), ("end.x", params.end.x), ("end.y", params.end.y)]
    {
        require_finite(field, v)?;
    }
    if params.start.distance_mm(params.end) <= LENGTH_EPS_MM {
        return Err(CoreError::invalid("end", "the slot has no length: use spiral_hole_expansion for a hole"));
    }
    let rho = slot_loop_radius_mm(w, r, allowance);
    if rho < MIN_LOOP_RADIUS_MM {
        return Err(CoreError::invalid(
            "width_mm",
            format!(
                "a {w} mm slot leaves a loop radius of {rho:.4} mm with a {r} mm tool radius and {allowance} mm allowance: it is too narrow for trochoids (cut it by z-cut division slotting, seed 004 §2.3)"
            ),
        ));
    }
    setup.require_below_retract("z_top_mm", params.z_top_mm)?;
    let max_ad = params.max_ad_mm.unwrap_or(setup.conditions.ad_mm);
    let levels = z_levels(params.z_top_mm, params.z_bottom_mm, max_ad)?;
    let guide = Guide::polyline(&[params.start, params.end])?;
    let pitch = params.pitch_mm.unwrap_or(setup.conditions.rd_mm);
    let plan = LoopPlan::new(&guide, &LoopRadius::Fixed { rho_mm: rho }, r, pitch, params.direction)?;

    let mut b = PathBuilder::starting_at(at_z(plan.start(), setup.clearance_z_mm), setup);
    let mut turns = 0.0;
    for &z in &levels {
        turns += f64::from(plan.append_pass(&mut b, z, params.entry, setup)?);
    }
    b.rapid_z(setup.clearance_z_mm);
    let moves = b.finish();
    let report = CycleReport {
        levels: levels.len(),
        loops: plan.loops() * levels.len(),
        turns,
        warnings: plan.warnings.clone(),
        ..CycleReport::of_moves(&moves, setup.rapid_mm_min)
    };
    Ok(Cycle { moves, report })
}

#[cfg(test)]
#[path = "slot_tests.rs"]
mod tests;
