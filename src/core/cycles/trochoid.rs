//! Trochoid cycles along a guide curve (seed 004 §2.2–2.3 and its first report; seed 002
//! §2.2.3 "trochoid milling"; MODEL.md §7): circles of radius `ρ` whose centres advance by a
//! pitch `p` per loop along the guide, written as true arcs (G2/G3).
//!
//! Each loop is a circle about its centre `c_k`, written as two arcs: a half circle from
//! the loop's entry point, then the rest of the turn to its exit point. Consecutive loops
//! are joined by a straight G1 link on their common outer tangent — on the right of the
//! guide for a climb cut — so the path is tangent-continuous: the "circle + advance"
//! trochoid. On a straight guide every loop is a full 360°; where the guide turns by `Δ`
//! between two links, the loop between them turns `360° + Δ` (left turns add, right turns
//! subtract, for a climb cut).
//!
//! **Direction** (M3 spindle, see [`CutDirection`]): the tool cuts on the front of each
//! loop with the material outside the circle, so a climb cut runs the loops
//! counter-clockwise (G3) and the links lie on the right of the guide; a conventional cut
//! runs them clockwise (G2) with the links on the left.
//!
//! The swept band is `2(ρ + r)` wide; the radial depth at the front of a loop is the pitch.
//!
//! **Lean loops**: loop `k` meets new material only in the crescent of its disc (radius
//! `ρ + r`) outside the previous loop's disc, which lies where `cos φ > −p/(2(ρ + r))`
//! (φ from the direction of advance) for equal radii: the front half, which the first arc
//! sweeps. The second arc, the return half, then runs through swept space and is written at
//! the setup's air feed ([`CycleSetup::air_feed_mm_min`]). It stays a half circle: the
//! shortest return that keeps the path tangent-continuous, so the machine never stops at a
//! corner (a straight chord back would turn 90° at both ends).

use super::arcs::{at_z, helix_turns, on_circle, PathBuilder};
use super::guide::Guide;
use super::report::{Cycle, CycleReport};
use super::setup::{CutDirection, CycleSetup};
use crate::core::error::{require_finite, require_positive};
use crate::core::geometry::Point;
use crate::core::medial::CLASS_C_RATIO;
use crate::core::tolerance::LENGTH_EPS_MM;
use crate::core::CoreError;

/// Default `(ρ + r)/r` of a fixed-radius trochoid: the machined width over the tool diameter
/// is 1.2, so ρ = 0.2·r (seed 004 §2.2; MODEL.md §7: a 12 mm slot with a 10 mm tool gives
/// ρ = 1 mm).
pub const DEFAULT_RADIUS_RATIO: f64 = 1.2;

/// Smallest loop radius written, mm (below it an arc is a point to the NC controls).
pub const MIN_LOOP_RADIUS_MM: f64 = 0.01;

/// Largest turn of the guide between two consecutive links, deg: a sharper turn would leave
/// the loop less than a quarter of a circle before it links on. Split the guide there.
pub const MAX_LOOP_TURN_DEG: f64 = 135.0;

/// Most loops one trochoid may have.
pub const MAX_LOOPS: usize = 2_000_000;

/// The radius `ρ` of the loops.
#[derive(Debug, Clone, PartialEq)]
pub enum LoopRadius {
    /// `ρ = (DEFAULT_RADIUS_RATIO − 1)·r` (MODEL.md §7).
    Default,
    /// A fixed radius, mm.
    Fixed { rho_mm: f64 },
    /// Variable radius (seed 004 Figure 5, MODEL.md §7): `ρ(s) = R(s) − r − allowance`, with
    /// the clearance `R` given at each vertex of the guide (a medial-axis branch's
    /// `clearance_mm`) and interpolated linearly by arc length.
    Clearance { clearance_mm: Vec<f64>, allowance_mm: f64 },
}

/// How the tool gets down to the cutting height at the start of a pass.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Entry {
    /// Straight down at the plunge feed, into an approach hole (seed 004 Table 1 steps 1–2).
    Plunge,
    /// Helical ramp on the first loop's circle, at most `pitch_mm` down per turn, at the
    /// cutting feed.
    Helix { pitch_mm: f64 },
}

/// A trochoid along a guide at one height.
#[derive(Debug, Clone, PartialEq)]
pub struct TrochoidParams {
    /// Tool radius r, mm.
    pub tool_radius_mm: f64,
    pub loop_radius: LoopRadius,
    /// Advance per loop, mm; default the conditions' Rd (MODEL.md §7: 0.5 mm for 10 mm).
    pub pitch_mm: Option<f64>,
    /// Tool-tip height of the pass, mm.
    pub z_mm: f64,
    pub direction: CutDirection,
    pub entry: Entry,
}

/// The loops of a trochoid, planned once and written at any height.
#[derive(Debug, Clone, PartialEq)]
pub struct LoopPlan {
    /// Loop centres, on the guide.
    pub centres: Vec<Point>,
    /// Arc length of each centre along the guide, mm.
    pub s_mm: Vec<f64>,
    /// Loop radii ρ, mm.
    pub rho_mm: Vec<f64>,
    /// Unit direction from each centre to its link's tangent point (one per link).
    normals: Vec<(f64, f64)>,
    /// Loops run clockwise (G2).
    pub clockwise: bool,
    /// Tool radius r, mm.
    pub tool_radius_mm: f64,
    /// Warnings about the loops (class C radii).
    pub warnings: Vec<String>,
}

/// `ρ` of the default fixed-radius trochoid for a tool of radius `r`, mm.
pub fn default_loop_radius_mm(tool_radius_mm: f64) -> f64 {
    (DEFAULT_RADIUS_RATIO - 1.0) * tool_radius_mm
}

/// Arc lengths of the loop centres: every `pitch` from 0, and the end of the guide.
fn centre_stations(length_mm: f64, pitch_mm: f64) -> Result<Vec<f64>, CoreError> {
    let whole = ((length_mm + LENGTH_EPS_MM) / pitch_mm).floor();
    if whole + 2.0 > MAX_LOOPS as f64 {
        return Err(CoreError::invalid("pitch_mm", format!("gives more than {MAX_LOOPS} loops")));
    }
    let mut s: Vec<f64> = (0..=whole as usize).map(|k| k as f64 * pitch_mm).collect();
    if length_mm - whole * pitch_mm > LENGTH_EPS_MM {
        s.push(length_mm);
    }
    Ok(s)
}

fn radii(guide: &Guide, radius: &LoopRadius, r: f64, s: &[f64]) -> Result<Vec<f64>, CoreError> {
    let rho: Vec<f64> = match radius {
        LoopRadius::Default => vec![default_loop_radius_mm(r); s.len()],
        LoopRadius::Fixed { rho_mm } => vec![require_positive("rho_mm", *rho_mm)?; s.len()],
        LoopRadius::Clearance { clearance_mm, allowance_mm } => {
            require_finite("allowance_mm", *allowance_mm)?;
            if clearance_mm.len() != guide.vertex_s_mm().len() {
                return Err(CoreError::invalid(
                    "clearance_mm",
                    format!(
                        "needs one value per guide vertex ({}), got {}",
                        guide.vertex_s_mm().len(),
                        clearance_mm.len()
                    ),
                ));
            }
            if let Some(v) = clearance_mm.iter().find(|v| !v.is_finite()) {
                return Err(CoreError::invalid("clearance_mm", format!("must be finite, got {v}")));
            }
            s.iter().map(|&s| guide.interpolate(clearance_mm, s) - r - allowance_mm).collect()
        }
    };
    if let Some((k, v)) = rho.iter().enumerate().find(|(_, v)| **v < MIN_LOOP_RADIUS_MM) {
        return Err(CoreError::invalid(
            "loop_radius",
            format!(
                "ρ = {v:.4} mm at loop {k} (s = {:.3} mm) is below {MIN_LOOP_RADIUS_MM} mm: the region is too narrow for a trochoid (z-cut division, seed 004 §2.3)",
                s[k]
            ),
        ));
    }
    Ok(rho)
}

/// Signed angle from `a` to `b`, rad, in (−π, π].
fn turn_rad(a: (f64, f64), b: (f64, f64)) -> f64 {
    (a.0 * b.1 - a.1 * b.0).atan2(a.0 * b.0 + a.1 * b.1)
}

impl LoopPlan {
    /// Plans the loops along `guide` for a tool of radius `r`.
    pub fn new(
        guide: &Guide,
        radius: &LoopRadius,
        tool_radius_mm: f64,
        pitch_mm: f64,
        direction: CutDirection,
    ) -> Result<LoopPlan, CoreError> {
        let r = require_positive("tool_radius_mm", tool_radius_mm)?;
        let pitch = require_positive("pitch_mm", pitch_mm)?;
        let s_mm = centre_stations(guide.length_mm(), pitch)?;
        let rho_mm = radii(guide, radius, r, &s_mm)?;
        LoopPlan::from_stations(guide, s_mm, rho_mm, r, direction)
    }

    /// Plans loops at the given stations along `guide` (increasing arc lengths, at least two)
    /// with the given radii — the planner's variable pitch (one station per loop).
    pub fn from_stations(
        guide: &Guide,
        s_mm: Vec<f64>,
        rho_mm: Vec<f64>,
        tool_radius_mm: f64,
        direction: CutDirection,
    ) -> Result<LoopPlan, CoreError> {
        let r = require_positive("tool_radius_mm", tool_radius_mm)?;
        if s_mm.len() < 2 || s_mm.len() != rho_mm.len() {
            return Err(CoreError::invalid("stations", "need at least two loops and one radius per loop"));
        }
        if let Some((k, v)) = rho_mm.iter().enumerate().find(|(_, v)| !v.is_finite() || **v < MIN_LOOP_RADIUS_MM) {
            return Err(CoreError::invalid(
                "loop_radius",
                format!("ρ = {v} mm at loop {k} is below {MIN_LOOP_RADIUS_MM} mm: too narrow for a trochoid"),
            ));
        }
        let centres: Vec<Point> = s_mm.iter().map(|&s| guide.point_at(s)).collect();
        let sign = direction.turn_sign();
        let mut normals = Vec::with_capacity(centres.len() - 1);
        for k in 0..centres.len() - 1 {
            let (dx, dy) = centres[k].vector_to(centres[k + 1]);
            let chord = dx.hypot(dy);
            if chord <= LENGTH_EPS_MM {
                return Err(CoreError::invalid("guide", format!("loops {k} and {} coincide", k + 1)));
            }
            let d = (dx / chord, dy / chord);
            // Outer side: right of the guide for counter-clockwise loops, left for clockwise.
            let side = (sign * d.1, -sign * d.0);
            // Common outer tangent of two circles of different radii: tilted by φ with
            // sin φ = (ρ_k − ρ_k+1)/chord (MODEL.md §7, variable radius).
            let sin_phi = (rho_mm[k] - rho_mm[k + 1]) / chord;
            if sin_phi.abs() >= 1.0 - LENGTH_EPS_MM {
                return Err(CoreError::invalid(
                    "loop_radius",
                    format!("ρ changes by more than the loop spacing between loops {k} and {}: no tangent link", k + 1),
                ));
            }
            let cos_phi = (1.0 - sin_phi * sin_phi).sqrt();
            normals.push((cos_phi * side.0 + sin_phi * d.0, cos_phi * side.1 + sin_phi * d.1));
        }
        let max_turn = MAX_LOOP_TURN_DEG.to_radians();
        for (k, w) in normals.windows(2).enumerate() {
            let turn = turn_rad(w[0], w[1]);
            if turn.abs() > max_turn {
                return Err(CoreError::invalid(
                    "guide",
                    format!(
                        "turns by {:.1}° at loop {} (s = {:.3} mm), more than {MAX_LOOP_TURN_DEG}°: split the guide there",
                        turn.to_degrees(),
                        k + 1,
                        s_mm[k + 1]
                    ),
                ));
            }
        }
        let narrow: Vec<usize> = (0..rho_mm.len()).filter(|&k| (rho_mm[k] + r) / r < CLASS_C_RATIO).collect();
        let mut warnings = Vec::new();
        if let (Some(first), Some(last)) = (narrow.first(), narrow.last()) {
            warnings.push(format!(
                "{} loops (s = {:.3} … {:.3} mm) have (ρ + r)/r below {CLASS_C_RATIO}: trochoids overload the tool there; cut that stretch by z-cut division (seed 004 §2.3)",
                narrow.len(),
                s_mm[*first],
                s_mm[*last]
            ));
        }
        Ok(LoopPlan {
            centres,
            s_mm,
            rho_mm,
            normals,
            clockwise: direction.outside_material_clockwise(),
            tool_radius_mm: r,
            warnings,
        })
    }

    /// Number of loops.
    pub fn loops(&self) -> usize {
        self.centres.len()
    }

    /// Direction from loop `k`'s centre to where it is entered.
    fn entry_dir(&self, k: usize) -> (f64, f64) {
        self.normals[k.saturating_sub(1).min(self.normals.len() - 1)]
    }

    /// Direction from loop `k`'s centre to where it is left.
    fn exit_dir(&self, k: usize) -> (f64, f64) {
        self.normals[k.min(self.normals.len() - 1)]
    }

    /// Where the first loop starts.
    pub fn start(&self) -> Point {
        on_circle(self.centres[0], self.rho_mm[0], self.entry_dir(0))
    }

    /// Whether the return half of loop `k` runs in the air: the loop before it swept the
    /// whole disc of radius `ρ_{k−1} + r` about its centre (its radius is at most r, so the
    /// tool covered the centre too), and the loop's own front half sweeps the crescent beyond
    /// that disc, which reaches into the back half only when the loop is larger than the one
    /// before (see the module documentation). The first loop's return cleans the floor its
    /// helical entry left, so it cuts.
    pub fn return_in_air(&self, k: usize) -> bool {
        k > 0
            && k < self.rho_mm.len()
            && self.rho_mm[k - 1] <= self.tool_radius_mm + LENGTH_EPS_MM
            && self.rho_mm[k] <= self.rho_mm[k - 1] + LENGTH_EPS_MM
    }

    /// Writes the loops and links at height `z_mm`, from [`LoopPlan::start`] (where the
    /// builder must be) to the exit of the last loop: the front half of each loop and the
    /// links at `feed_mm_min`, the return halves that cut nothing at `air_feed_mm_min`.
    pub fn append_loops(&self, b: &mut PathBuilder, z_mm: f64, feed_mm_min: f64, air_feed_mm_min: f64) {
        for (k, (&c, &rho)) in self.centres.iter().zip(&self.rho_mm).enumerate() {
            let a_in = self.entry_dir(k);
            let a_out = self.exit_dir(k);
            b.arc_xy(on_circle(c, -rho, a_in), c, self.clockwise, feed_mm_min);
            let exit = on_circle(c, rho, a_out);
            let back = if self.return_in_air(k) { air_feed_mm_min } else { feed_mm_min };
            b.arc_xy(exit, c, self.clockwise, back);
            if k + 1 < self.centres.len() {
                let next = on_circle(self.centres[k + 1], self.rho_mm[k + 1], a_out);
                b.line(at_z(next, z_mm), feed_mm_min);
            }
        }
    }

    /// Rapids over the start at the builder's height, down to the retract height, enters
    /// to `z_mm` (a helical entry ramps on the first loop's circle), cuts the loops and
    /// rapids back to the retract height. Returns the entry's helix turns.
    pub fn append_pass(
        &self,
        b: &mut PathBuilder,
        z_mm: f64,
        entry: Entry,
        setup: &CycleSetup,
    ) -> Result<u32, CoreError> {
        let start = self.start();
        let retract = setup.retract_z_mm();
        b.rapid(at_z(start, b.position().z));
        b.rapid_z(retract);
        let turns = match entry {
            Entry::Plunge => {
                b.line(at_z(start, z_mm), setup.plunge_feed_mm_min());
                0
            }
            Entry::Helix { pitch_mm } => {
                let turns = helix_turns("entry.pitch_mm", retract - z_mm, pitch_mm)?;
                b.helix_down(self.centres[0], z_mm, turns, self.clockwise, setup.feed_mm_min());
                turns
            }
        };
        self.append_loops(b, z_mm, setup.feed_mm_min(), setup.air_feed_mm_min());
        b.rapid_z(retract);
        Ok(turns)
    }
}

/// Checks an entry's parameters.
pub fn validate_entry(entry: Entry) -> Result<(), CoreError> {
    if let Entry::Helix { pitch_mm } = entry {
        require_positive("entry.pitch_mm", pitch_mm)?;
    }
    Ok(())
}

/// A trochoid along `guide` at one height (seed 004 §2.2, MODEL.md §7): rapid to the
/// clearance height above the start, down to the retract height, plunge (or helical entry),
/// the loops, and a retract to the clearance height.
pub fn trochoid_along(guide: &Guide, params: &TrochoidParams, setup: &CycleSetup) -> Result<Cycle, CoreError> {
    setup.validate()?;
    setup.require_below_retract("z_mm", params.z_mm)?;
    validate_entry(params.entry)?;
    let pitch = params.pitch_mm.unwrap_or(setup.conditions.rd_mm);
    let plan = LoopPlan::new(guide, &params.loop_radius, params.tool_radius_mm, pitch, params.direction)?;
    let start = plan.start();
    let mut b = PathBuilder::starting_at(at_z(start, setup.clearance_z_mm), setup);
    let turns = plan.append_pass(&mut b, params.z_mm, params.entry, setup)?;
    b.rapid_z(setup.clearance_z_mm);
    let moves = b.finish();
    let report = CycleReport {
        levels: 1,
        loops: plan.loops(),
        turns: f64::from(turns),
        warnings: plan.warnings.clone(),
        ..CycleReport::of_moves(&moves, setup.rapid_mm_min)
    };
    Ok(Cycle { moves, report })
}

#[cfg(test)]
#[path = "trochoid_tests.rs"]
mod tests;
