//! Helical boring of an approach hole (seed 002 §2.2.3 and Fig. 3(a); seed 004 Table 1
//! steps 1 and 5, Table 2: ball end mill R5, 2 flutes, S 2800, fz 0.05, 0.6 mm down per
//! turn; MODEL.md §8 step 1): the tool centre follows a helix of radius `R_h − r` from the
//! top of the material to the bottom, then a flat full circle at the bottom.
//!
//! The whole helix is one G2/G3 block with `turns = n − 1` extra turns (`n` turns, ending
//! above its start), its pitch `depth / n` no more than the pitch asked for. A climb cut
//! (material outside the circle, M3) runs counter-clockwise (G3).

use super::arcs::{at_z, helix_turns, on_circle, xy, PathBuilder};
use super::report::{Cycle, CycleReport};
use super::setup::{CutDirection, CycleSetup};
use super::trochoid::MIN_LOOP_RADIUS_MM;
use crate::core::error::{require_finite, require_positive};
use crate::core::geometry::Point;
use crate::core::tolerance::LENGTH_EPS_MM;
use crate::core::CoreError;

/// Largest hole radius over tool radius: beyond `R_h = 2r` the tool centre's circle
/// (`R_h − r > r`) leaves a core standing in the middle of the hole.
pub const MAX_HOLE_TO_TOOL_RADIUS: f64 = 2.0;

/// An approach hole to bore.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HelicalBoringParams {
    /// Hole centre, mm.
    pub center: Point,
    /// Hole radius R_h, mm (r < R_h ≤ 2r).
    pub hole_radius_mm: f64,
    /// Tool radius r, mm.
    pub tool_radius_mm: f64,
    /// Top of the material and bottom of the hole, mm.
    pub z_top_mm: f64,
    pub z_bottom_mm: f64,
    /// Depth per turn, mm; default the conditions' Ad (0.6 mm per turn in seed 004 Table 2).
    pub pitch_mm: Option<f64>,
    pub direction: CutDirection,
}

/// Bores the hole: rapid over the start of the circle, down to the retract height, feed to
/// the top of the material, helix to the bottom, a flat full circle, a feed move to the
/// hole's centre (off the wall) and a rapid to the clearance height.
pub fn helical_boring(params: &HelicalBoringParams, setup: &CycleSetup) -> Result<Cycle, CoreError> {
    setup.validate()?;
    let r = require_positive("tool_radius_mm", params.tool_radius_mm)?;
    let hole = require_positive("hole_radius_mm", params.hole_radius_mm)?;
    require_finite("center.x", params.center.x)?;
    require_finite("center.y", params.center.y)?;
    let rc = hole - r;
    if rc < MIN_LOOP_RADIUS_MM {
        return Err(CoreError::invalid(
            "hole_radius_mm",
            format!("a {hole} mm hole radius leaves the tool centre no circle to follow (tool radius {r} mm)"),
        ));
    }
    if hole > MAX_HOLE_TO_TOOL_RADIUS * r + LENGTH_EPS_MM {
        return Err(CoreError::invalid(
            "hole_radius_mm",
            format!(
                "a {hole} mm hole radius is more than {MAX_HOLE_TO_TOOL_RADIUS} tool radii: helical boring would leave a core; bore a smaller hole and expand it (spiral_hole_expansion)"
            ),
        ));
    }
    setup.require_below_retract("z_top_mm", params.z_top_mm)?;
    require_finite("z_bottom_mm", params.z_bottom_mm)?;
    let depth = params.z_top_mm - params.z_bottom_mm;
    if depth <= LENGTH_EPS_MM {
        return Err(CoreError::invalid("z_bottom_mm", "must be below z_top_mm"));
    }
    let helix = helix_turns("pitch_mm", depth, params.pitch_mm.unwrap_or(setup.conditions.ad_mm))?;

    let clockwise = params.direction.outside_material_clockwise();
    let feed = setup.feed_mm_min();
    let start = on_circle(params.center, rc, (1.0, 0.0));
    let mut b = PathBuilder::starting_at(at_z(start, setup.clearance_z_mm), setup);
    b.rapid_z(setup.retract_z_mm());
    b.line(at_z(start, params.z_top_mm), setup.plunge_feed_mm_min());
    b.helix_down(params.center, params.z_bottom_mm, helix, clockwise, feed);
    b.full_circle(params.center, clockwise, feed);
    b.line(at_z(params.center, params.z_bottom_mm), feed);
    b.rapid_z(setup.clearance_z_mm);
    debug_assert!(xy(b.position()).near(params.center, LENGTH_EPS_MM));
    let moves = b.finish();
    let report =
        CycleReport { levels: 1, turns: f64::from(helix) + 1.0, ..CycleReport::of_moves(&moves, setup.rapid_mm_min) };
    Ok(Cycle { moves, report })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::core::analysis::{analyze, StockRegion};
    use crate::core::conditions::CuttingConditions;
    use crate::core::cycles::test_support::*;
    use crate::core::progress::NoProgress;
    use crate::core::stock::Rect;
    use crate::core::tolerance::approx_eq;
    use crate::core::toolpath::move_length;
    use crate::core::toolpath::Motion;
    use std::f64::consts::PI;

    /// Seed 004 Table 2 (1): ball R5, 2 flutes, S 2800, fz 0.05, 0.6 mm per turn.
    fn boring_setup() -> CycleSetup {
        let c = CuttingConditions { spindle_rpm: 2800.0, fz_mm: 0.05, rd_mm: 10.0, ad_mm: 0.6 };
        CycleSetup { retract_z_mm: Some(RETRACT_Z), ..CycleSetup::new(c, 2, CLEARANCE_Z) }
    }

    /// A 20 mm hole 10 mm deep at (30, 20) with the R5 ball.
    fn hole() -> HelicalBoringParams {
        HelicalBoringParams {
            center: Point::new(30.0, 20.0),
            hole_radius_mm: 10.0,
            tool_radius_mm: R10,
            z_top_mm: 0.0,
            z_bottom_mm: -10.0,
            pitch_mm: None,
            direction: CutDirection::Climb,
        }
    }

    #[test]
    fn a_20_mm_hole_10_mm_deep_is_17_turns_of_one_helix_block_then_a_flat_circle() {
        let c = helical_boring(&hole(), &boring_setup()).unwrap();
        assert_continuous(&c.moves);
        let helix = c.moves.iter().find(|m| matches!(m.motion, Motion::Arc { .. })).unwrap();
        let Motion::Arc { center, clockwise, turns, .. } = helix.motion else { unreachable!() };
        // ⌈10 / 0.6⌉ = 17 turns of 10/17 mm.
        assert_eq!(turns, 16);
        assert!(!clockwise, "a climb cut with M3 runs G3");
        assert!(approx_eq(center.x, 30.0, 0.0) && approx_eq(center.y, 20.0, 0.0));
        assert!(approx_eq(helix.start.z, 0.0, 0.0) && approx_eq(helix.end.z, -10.0, 0.0));
        assert!(approx_eq(helix.start.x, helix.end.x, 0.0) && approx_eq(helix.start.y, helix.end.y, 0.0));
        let (rs, _, _) = arc_radii(helix).unwrap();
        assert!(approx_eq(rs, 5.0, 1e-12), "the tool centre follows R_h − r");
        let pitch = 10.0 / 17.0;
        assert!(pitch <= 0.6);
        assert!(approx_eq(move_length(helix), 17.0 * (2.0 * PI * 5.0).hypot(pitch), 1e-9));
        let flat = c.moves[helix.line as usize];
        assert!(matches!(flat.motion, Motion::Arc { turns: 0, .. }) && flat.start == flat.end);
        assert!(approx_eq(flat.start.z, -10.0, 0.0));
        assert!(approx_eq(helix.feed_mm_min.unwrap(), 0.05 * 2.0 * 2800.0, 1e-9));
        assert!(approx_eq(c.report.turns, 18.0, 0.0));
        let last = c.moves.last().unwrap();
        assert!(matches!(last.motion, Motion::Rapid) && approx_eq(last.end.z, CLEARANCE_Z, 0.0));
        assert!(approx_eq(last.end.x, 30.0, 1e-12) && approx_eq(last.end.y, 20.0, 1e-12));
    }

    #[test]
    fn a_conventional_bore_runs_clockwise() {
        let p = HelicalBoringParams { direction: CutDirection::Conventional, ..hole() };
        let c = helical_boring(&p, &boring_setup()).unwrap();
        assert!(c.moves.iter().all(|m| !matches!(m.motion, Motion::Arc { clockwise: false, .. })));
    }

    #[test]
    fn the_bore_clears_the_whole_cylinder() {
        let c = helical_boring(&hole(), &boring_setup()).unwrap();
        let stock = StockRegion::Rect(Rect { x_min: 10.0, y_min: 0.0, x_max: 50.0, y_max: 40.0 });
        let mut s = spec(vec![stock], vec![], 0.0, -10.0);
        s.sample_spacing_mm = Some(0.2);
        let a = analyze(&c.toolpath(), &s, &NoProgress).unwrap();
        let expected = PI * 100.0 * 10.0;
        let got = a.summary.removed_volume_mm3;
        eprintln!("helical boring: removed {got:.1} mm³ vs {expected:.1} mm³");
        assert!((got - expected).abs() / expected < 0.01, "{got} vs {expected}");
    }

    #[test]
    fn holes_the_tool_cannot_bore_are_refused() {
        let err = |p: HelicalBoringParams| helical_boring(&p, &boring_setup()).unwrap_err().to_string();
        assert!(err(HelicalBoringParams { hole_radius_mm: 5.0, ..hole() }).starts_with("hole_radius_mm"));
        assert!(err(HelicalBoringParams { hole_radius_mm: 10.5, ..hole() }).contains("core"));
        assert!(err(HelicalBoringParams { z_bottom_mm: 0.0, ..hole() }).starts_with("z_bottom_mm"));
        assert!(err(HelicalBoringParams { pitch_mm: Some(-1.0), ..hole() }).starts_with("pitch_mm"));
    }
}
