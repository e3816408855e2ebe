//! Intermediate roughing of the stair steps (issue 32 item 4; seed 004 §3.2, case II: "the
//! bottom surface of the cavity is slightly slanted … it leaves a large leftover volume to
//! intermediate-rough cutting processes"). A cavity roughed layer by layer with a flat end
//! mill is left in steps where its surface slopes: each layer is cut straight down to its
//! bottom section, so between two sections the material over the sloped surface stays. A
//! ball or radius end mill then follows the surface in thin z levels and takes the steps off.
//!
//! 1. **Surface** ([`surface`]): the die's surface as a height field interpolated between the
//!    layers' sections, and how deep the roughing cut at every point.
//! 2. **Where the tip may go** ([`tip`]): for every cell, the lowest tip height at which the
//!    tool's real end (ball, radius or square) keeps the allowance off the surface.
//! 3. **Levels**: from the highest step down to the lowest point of the steps, at most the
//!    axial depth Ad apart (the steps `z_levels` gives, equal and ending on the lowest).
//! 4. **Rings** ([`levels`]): at each level the edge of the region the tip may reach (the
//!    wall of the level, cut at the allowance) and its offsets inward at the radial depth Rd,
//!    each kept where it comes within the tool's radius of material the roughing left above
//!    the level: over a steep wall one ring, over a gently sloped floor a ring every Rd.
//! 5. **Program** ([`writer`]): per level the rings from the innermost out (each with the
//!    material outside it, climb milling), linked by a straight feed move where the tip may
//!    stand all along it, otherwise over the safe height and plunged from a clearance over
//!    the stock the roughing may have left there. The program calls its own tool (`T.. M6`, `G43 H..`) and labels every
//!    level (`(LAYER 3 Z-24.6 STAIR-STEP INTERMEDIATE ROUGHING)`).
//!
//! The rings follow the height field to its cell (a sixteenth of the tool's radius, see
//! [`CELLS_PER_TOOL_RADIUS`]): they keep the allowance, on a flat floor exactly and on a
//! steep wall with up to half a cell's diagonal more (see [`tip`]).

pub mod distance;
pub mod levels;
pub mod rings;
pub mod stock;
pub mod surface;
pub mod tip;
pub mod writer;

#[cfg(test)]
mod tests;

use self::levels::Level;
use self::surface::Surface;
use self::tip::tip_heights_mm;
use self::writer::{Feeds, Writer};
use crate::core::analysis::profile::Profile;
use crate::core::conditions::{feed_mm_min, CuttingConditions};
use crate::core::cycles::setup::DEFAULT_PLUNGE_FEED_RATIO;
use crate::core::cycles::z_levels;
use crate::core::insertion::labelled_program;
use crate::core::process::cavity::Cavity;
use crate::core::progress::Progress;
use crate::core::tolerance::LENGTH_EPS_MM;
use crate::core::tool::EndMill;
use crate::core::toolpath::{move_length, Event, EventKind, Motion, Section, Step, Toolpath};
use crate::core::CoreError;
use serde::Serialize;

/// The height field's cell is the tool's radius over this (**assumed**: a sixteenth of the
/// radius, 0.31 mm for a R5 ball, places the rings within a sixth of a millimetre).
pub const CELLS_PER_TOOL_RADIUS: f64 = 16.0;

/// The finest cell of the height field, mm (a small tool is still planned on a grid the
/// stock simulation's own cell resolves).
pub const MIN_CELL_MM: f64 = 0.1;

/// Most cells of the height field; a larger cavity is planned on a coarser cell.
pub const MAX_SURFACE_CELLS: usize = 4_000_000;

/// Steps lower than this are none, mm (**assumed**: below any allowance).
pub const MIN_STEP_MM: f64 = 0.01;

/// Most levels one stair-step roughing may cut (a guard against an axial depth far below
/// the steps' height: 0.6 mm over 1.2 m of depth).
pub const MAX_STAIR_LEVELS: usize = 2000;

/// The request fields the step's depths come from, for its errors.
const AXIAL_FIELD: &str = "stair_step.axial_depth_mm";
const RADIAL_FIELD: &str = "stair_step.radial_depth_mm";

/// The stair-step roughing's tool, conditions and heights.
#[derive(Debug, Clone, PartialEq)]
pub struct StairSpec {
    /// A ball or radius end mill (a square one is accepted too, but leaves steps of its own).
    pub tool: EndMill,
    /// S and fz for the programmed feed, Rd between rings, Ad between levels.
    pub conditions: CuttingConditions,
    /// Stock left on the surface, mm (along its normal).
    pub allowance_mm: f64,
    pub safe_z_mm: f64,
    /// The tool's number in the program (`T.. M6`, `G43 H..`).
    pub tool_number: u32,
}

/// One level of the stair-step roughing.
#[derive(Debug, Clone, PartialEq, Serialize, utoipa::ToSchema)]
pub struct StairLevel {
    /// The level's height, mm.
    pub z_mm: f64,
    /// Rings cut at it.
    pub rings: usize,
    /// Length of its feed moves at the level (the rings and the straight links between
    /// them), mm.
    pub ring_length_mm: f64,
}

/// The stair-step roughing's path.
#[derive(Debug, Clone)]
pub struct StairPath {
    /// The program: the tool change, then every level, labelled.
    pub toolpath: Toolpath,
    pub levels: Vec<StairLevel>,
    /// The height field's cell, mm.
    pub cell_mm: f64,
    /// The steps' volume over the surface as the layers leave them, mm³ (the surface's own
    /// figure, before the allowance).
    pub step_volume_mm3: f64,
    /// The die's surface the rings follow.
    pub surface: Surface,
}

/// Plans the stair-step roughing of `cavity`; `None` when its layers leave no steps (every
/// layer of one contour, or the sections one above the other).
pub fn plan_stairs(cavity: &Cavity, spec: &StairSpec, progress: &dyn Progress) -> Result<Option<StairPath>, CoreError> {
    cavity.validate()?;
    spec.conditions.validate()?;
    if !(spec.allowance_mm.is_finite() && spec.allowance_mm >= 0.0) {
        return Err(CoreError::invalid("allowance_mm", format!("must be 0 or more, got {}", spec.allowance_mm)));
    }
    let profile = Profile::of(&spec.tool);
    let radius = profile.radius_mm;
    let cell_mm = surface_cell_mm(cavity, radius, spec.allowance_mm);
    // Rings farther apart than the tool is wide leave ridges between them.
    if spec.conditions.rd_mm > spec.tool.diameter_mm {
        return Err(CoreError::invalid(
            RADIAL_FIELD,
            format!("at most the tool's diameter, {} mm, got {} mm", spec.tool.diameter_mm, spec.conditions.rd_mm),
        ));
    }
    // Rings closer than the surface's cell would follow the same cells.
    if spec.conditions.rd_mm < cell_mm {
        return Err(CoreError::invalid(
            RADIAL_FIELD,
            format!("must be at least the surface's cell, {cell_mm:.3} mm, got {} mm", spec.conditions.rd_mm),
        ));
    }
    let surface = Surface::of(cavity, cell_mm, radius + spec.allowance_mm + 2.0 * cell_mm);
    let cell_area = cell_mm * cell_mm;
    let steps: Vec<usize> = (0..surface.grid.cells()).filter(|&c| surface.stair_mm(c) > MIN_STEP_MM).collect();
    if steps.is_empty() {
        return Ok(None);
    }
    let step_volume_mm3 = steps.iter().map(|&c| surface.stair_mm(c) * cell_area).sum();
    let highest = steps.iter().map(|&c| surface.roughed_mm[c]).fold(f64::NEG_INFINITY, f64::max);
    let lowest = steps.iter().map(|&c| surface.height_mm[c]).fold(f64::INFINITY, f64::min) + spec.allowance_mm;
    if lowest >= highest - MIN_STEP_MM {
        return Ok(None);
    }
    progress.checkpoint()?;
    let tip = tip_heights_mm(&surface, &profile, spec.allowance_mm);
    let c = spec.conditions;
    let feed = feed_mm_min(c.fz_mm, spec.tool.flutes, c.spindle_rpm);
    let mut writer = Writer::new(Feeds {
        feed_mm_min: feed,
        plunge_feed_mm_min: DEFAULT_PLUNGE_FEED_RATIO * feed,
        spindle_rpm: c.spindle_rpm,
        safe_z_mm: spec.safe_z_mm,
        tool: spec.tool_number,
    });
    let zs = z_levels(highest, lowest, c.ad_mm)?;
    if zs.len() > MAX_STAIR_LEVELS {
        return Err(CoreError::invalid(
            AXIAL_FIELD,
            format!(
                "the steps from z {highest:.3} to {lowest:.3} would take {} levels at {} mm, more than {MAX_STAIR_LEVELS}",
                zs.len(),
                c.ad_mm
            ),
        ));
    }
    let mut levels = Vec::with_capacity(zs.len());
    for (k, &z) in zs.iter().enumerate() {
        progress.checkpoint()?;
        progress.report(k as f64 / zs.len() as f64);
        let level = Level::new(&surface, &tip, z);
        let mut rings = level.rings(z, radius, c.rd_mm);
        if rings.is_empty() {
            continue;
        }
        // The innermost first, so that every ring has the material outside it.
        rings.sort_by_key(|r| std::cmp::Reverse(r.offset));
        writer.label(Section { layer: layer_at(cavity, z), z_mm: z, step: Step::StairStepRoughing, region: None });
        let before = writer.moves.len();
        for r in &rings {
            writer.cut_ring(&r.ring, z, &level, radius);
        }
        let ring_length_mm = writer.moves[before..]
            .iter()
            .filter(|m| !matches!(m.motion, Motion::Rapid) && (m.start.z - z).abs() <= LENGTH_EPS_MM)
            .map(move_length)
            .sum();
        levels.push(StairLevel { z_mm: z, rings: rings.len(), ring_length_mm });
    }
    if levels.is_empty() {
        return Ok(None);
    }
    writer.retract();
    let mut toolpath = labelled_program(writer.moves, writer.labels);
    toolpath
        .events
        .insert(0, Event { kind: EventKind::ToolChange { tool: spec.tool_number }, before_move: 0, line: 1 });
    progress.report(1.0);
    Ok(Some(StairPath { toolpath, levels, cell_mm, step_volume_mm3, surface }))
}

/// The height field's cell for a tool of `radius_mm` over `cavity`: a sixteenth of the
/// radius, no finer than [`MIN_CELL_MM`], coarser where the cavity would need more than
/// [`MAX_SURFACE_CELLS`].
fn surface_cell_mm(cavity: &Cavity, radius_mm: f64, allowance_mm: f64) -> f64 {
    let cell = (radius_mm / CELLS_PER_TOOL_RADIUS).max(MIN_CELL_MM);
    let Some(b) = cavity.layers.first().map(|l| l.pocket.bounds()) else {
        return cell;
    };
    let margin = 2.0 * (radius_mm + allowance_mm + 2.0 * cell);
    let area = (b.x_max - b.x_min + margin) * (b.y_max - b.y_min + margin);
    cell.max((area / MAX_SURFACE_CELLS as f64).sqrt())
}

/// The cavity's layer a level at `z_mm` lies in: the first, from the top, whose bottom is at
/// or below it.
fn layer_at(cavity: &Cavity, z_mm: f64) -> u32 {
    let k = cavity.layers.iter().position(|l| l.z_bottom_mm <= z_mm + LENGTH_EPS_MM);
    u32::try_from(k.unwrap_or(cavity.layers.len().saturating_sub(1))).unwrap_or(u32::MAX)
}
