//! A tool's standard straight cut as the analyses see it: its chip thickness `t_m`, arc
//! length `L` and the force F* there. The tool life is calibrated at this cut (its life is
//! the length of it the tool lasts, MODEL.md §9), and the constant-force feed targets F*
//! (MODEL.md §3), so the analyses must measure the same cut the same way.
//!
//! A square end mill's standard cut is MODEL.md §2's straight case: `α = acos(1 − Rd/r)`,
//! `L = r·α`. A radius or ball end mill is simulated with its profile (see
//! [`crate::core::analysis::profile`]): where its corner cuts, each slice engages at the
//! tool's radius there (a ball at Ad 0.6 and Rd 0.4 D is 2.4 mm across at the surface, not
//! 5, and engages about 62°, not 78.5°). So its standard cut is a straight pass at Rd and Ad
//! along a wall, simulated, and read in the middle; [`contour_parallel_cut`] is the same
//! pass beside a previous one, as contour-parallel roughing in thin layers takes it.

use crate::core::analysis::profile::Profile;
use crate::core::analysis::{analyze_with, AnalysisSpec, StockRegion};
use crate::core::conditions::{feed_mm_min, standard_centres, CuttingConditions};
use crate::core::force_model::ForceModel;
use crate::core::progress::NoProgress;
use crate::core::stock::Rect;
use crate::core::tool::EndMill;
use crate::core::toolpath::{Motion, Move, Toolpath, Units, P3};
use crate::core::CoreError;

/// The simulated pass is this many tool diameters long; it is read in its middle.
const PASS_DIAMETERS: f64 = 6.0;
/// The block's material reaches this many tool diameters below the last pass.
const WALL_DEPTH_DIAMETERS: f64 = 2.0;
/// Passes cut before the one read, each Rd beside the one before (the first a groove): by
/// the second, what a pass meets repeats.
const PASSES_BEFORE: usize = 2;

/// A tool's standard straight cut.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StandardCut {
    /// Maximum undeformed chip thickness, µm.
    pub t_m_um: f64,
    /// Engagement arc length, mm.
    pub arc_length_mm: f64,
    /// The force there, N (F*), when a force model is given: a square end mill's at the
    /// model's reference depth, as seed 001 measured it; a shaped tool's summed over the
    /// slices it engages at the cut's Ad.
    pub force_n: Option<f64>,
}

/// The standard straight cut of `tool` at `conditions` (with `model`'s force).
pub fn standard_cut(
    tool: &EndMill,
    conditions: CuttingConditions,
    model: Option<&ForceModel>,
) -> Result<StandardCut, CoreError> {
    let (t_m_um, arc_length_mm) = standard_centres(tool.radius_mm(), conditions)?;
    let flank = || {
        let force_n = model.map(|m| m.force_n(t_m_um, arc_length_mm, m.ad_ref_mm));
        StandardCut { t_m_um, arc_length_mm, force_n }
    };
    if Profile::of(tool).is_cylinder() {
        return Ok(flank());
    }
    // Conditions whose corner never reaches the wall at their Ad (a shop's own, far from
    // the seeded ones) keep the flank's figures, as before the profile was simulated.
    Ok(simulated(tool, conditions, model, 0)?.unwrap_or_else(flank))
}

/// The same cut taken as contour-parallel roughing in thin layers takes it, which the ball's
/// standard row describes (seed 004 case II, Table 7): a pass Rd beside the pass before it,
/// which left not a wall but its groove's rounded side (a ball engages it far more: the R5
/// at Rd 4, Ad 0.6 about 90° at its most engaged slice, against 62° along a wall). A square
/// end mill's is its [`standard_cut`], which a previous pass leaves as a wall.
pub fn contour_parallel_cut(
    tool: &EndMill,
    conditions: CuttingConditions,
    model: Option<&ForceModel>,
) -> Result<StandardCut, CoreError> {
    if Profile::of(tool).is_cylinder() {
        return standard_cut(tool, conditions, model);
    }
    match simulated(tool, conditions, model, PASSES_BEFORE)? {
        Some(cut) => Ok(cut),
        None => standard_cut(tool, conditions, model),
    }
}

/// The standard cut of a radius or ball end mill, simulated: passes along x at depth Ad,
/// the one read (at its sample nearest the middle) with the tool's flank reaching Rd below
/// y = 0. With `before` passes before it, each Rd beside the last (the first a groove), into
/// a block of material; with none, along the wall of material below y = 0. `None` when the
/// tool does not reach the material there.
fn simulated(
    tool: &EndMill,
    c: CuttingConditions,
    model: Option<&ForceModel>,
    before: usize,
) -> Result<Option<StandardCut>, CoreError> {
    let d = tool.diameter_mm;
    let length = PASS_DIAMETERS * d;
    let y = tool.radius_mm() - c.rd_mm;
    let first = y + before as f64 * c.rd_mm;
    let top = if before == 0 { 0.0 } else { first + d };
    let block = Rect { x_min: 0.0, y_min: -WALL_DEPTH_DIAMETERS * d, x_max: length, y_max: top };
    let feed = Some(feed_mm_min(c.fz_mm, tool.flutes, c.spindle_rpm));
    let pass = |k: usize, line: u32| {
        let at = first - k as f64 * c.rd_mm;
        // Every other pass runs back, as a contour-parallel path turns at its ends.
        let (from, to) = if k.is_multiple_of(2) { (-d, length + d) } else { (length + d, -d) };
        Move {
            motion: Motion::Linear,
            start: P3::new(from, at, -c.ad_mm),
            end: P3::new(to, at, -c.ad_mm),
            feed_mm_min: feed,
            spindle_rpm: Some(c.spindle_rpm),
            tool: None,
            line,
        }
    };
    let mut moves: Vec<Move> = Vec::new();
    for k in 0..=before {
        let m = pass(k, u32::try_from(k + 1).unwrap_or(u32::MAX));
        if let Some(last) = moves.last().copied() {
            // Over to the next pass's start at the depth, outside the block.
            moves.push(Move { start: last.end, end: m.start, ..m });
        }
        moves.push(m);
    }
    let read = u32::try_from(before + 1).unwrap_or(u32::MAX);
    let path = Toolpath { moves, events: vec![], source_units: Units::Mm, warnings: vec![] };
    let spec = AnalysisSpec {
        force_model: model.copied(),
        ..AnalysisSpec::new(*tool, vec![StockRegion::Rect(block)], 0.0, -c.ad_mm - d)
    };
    let middle = length / 2.0;
    let mut nearest: Option<(f64, StandardCut)> = None;
    analyze_with(&path, &spec, &NoProgress, |r| {
        if r.sample.line != read {
            return;
        }
        let off = (r.sample.p.x - middle).abs();
        if nearest.is_none_or(|(o, _)| off < o) {
            let cut = StandardCut { t_m_um: r.t_m_um, arc_length_mm: r.arc_length_mm, force_n: r.force_n };
            nearest = Some((off, cut));
        }
    })?;
    Ok(nearest.map(|(_, cut)| cut).filter(|cut| cut.arc_length_mm > 0.0))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::core::fixtures::seed_001_ten_mm;
    use crate::core::tool::ToolType;

    fn conditions(rd_mm: f64, ad_mm: f64) -> CuttingConditions {
        CuttingConditions { spindle_rpm: 10_000.0, fz_mm: 0.1, rd_mm, ad_mm }
    }

    #[test]
    fn a_square_end_mills_standard_cut_is_the_straight_case_of_model_section_2() {
        let tool = EndMill { tool_type: ToolType::Square, diameter_mm: 10.0, flutes: 6, corner_radius_mm: 0.0 };
        let model = seed_001_ten_mm();
        let cut = standard_cut(&tool, conditions(0.5, 10.0), Some(&model)).expect("cuts");
        assert!((cut.t_m_um - 43.6).abs() < 0.05 && (cut.arc_length_mm - 2.26).abs() < 0.005);
        assert!((cut.force_n.expect("a model") - 269.1).abs() < 0.5, "F* is β0 at the design centre");
    }

    #[test]
    fn a_balls_standard_cut_engages_at_its_radius_near_the_surface() {
        let tool = EndMill { tool_type: ToolType::Ball, diameter_mm: 10.0, flutes: 2, corner_radius_mm: 5.0 };
        let cut = standard_cut(&tool, conditions(4.0, 0.6), None).expect("cuts");
        // The wall lies 1 mm from the axis; the ball is 2.375 mm in radius at the surface
        // and 0 at its tip: the slice engaged most, near the surface, engages between the
        // cylinder's acos(1/5) and the surface's acos(1/2.375).
        // t_m = fz·sin α on a straight cut, and L = ρ·α at the slice's radius ρ.
        let alpha = (cut.t_m_um / 1000.0 / 0.1).asin();
        assert!(alpha.to_degrees() > 55.0 && alpha.to_degrees() < 65.2, "α {}", alpha.to_degrees());
        let rho = cut.arc_length_mm / alpha;
        assert!(rho > 1.0 && rho < 2.375, "ρ {rho}");
    }

    #[test]
    fn a_ball_beside_its_previous_pass_engages_more_than_along_a_wall_and_a_square_end_mill_alike() {
        let ball = EndMill { tool_type: ToolType::Ball, diameter_mm: 10.0, flutes: 2, corner_radius_mm: 5.0 };
        let model = seed_001_ten_mm();
        let wall = standard_cut(&ball, conditions(4.0, 0.6), Some(&model)).expect("cuts");
        let beside = contour_parallel_cut(&ball, conditions(4.0, 0.6), Some(&model)).expect("cuts");
        let alpha = |c: &StandardCut| (c.t_m_um / 1000.0 / 0.1).min(1.0).asin().to_degrees();
        // The groove's rounded side reaches the ball's tip: its most engaged slice takes 90°.
        assert!(alpha(&beside) > 85.0 && alpha(&wall) < 65.2, "{} against {}", alpha(&beside), alpha(&wall));
        assert!(beside.arc_length_mm > wall.arc_length_mm && beside.force_n > wall.force_n, "{beside:?} {wall:?}");
        let square = EndMill { tool_type: ToolType::Square, diameter_mm: 10.0, flutes: 6, corner_radius_mm: 0.0 };
        let c = conditions(0.5, 10.0);
        assert_eq!(contour_parallel_cut(&square, c, Some(&model)).ok(), standard_cut(&square, c, Some(&model)).ok());
    }

    #[test]
    fn a_ball_whose_corner_never_reaches_the_wall_at_its_depth_keeps_the_flanks_standard_cut() {
        // A D20 ball 0.6 mm deep is 3.4 mm across at the surface; the wall lies 6.5 mm off.
        let tool = EndMill { tool_type: ToolType::Ball, diameter_mm: 20.0, flutes: 2, corner_radius_mm: 10.0 };
        let (t, l) = standard_centres(10.0, conditions(3.5, 0.6)).expect("cuts");
        let cut = standard_cut(&tool, conditions(3.5, 0.6), None).expect("no error");
        assert_eq!((cut.t_m_um, cut.arc_length_mm), (t, l));
    }

    #[test]
    fn a_radius_end_mills_standard_cut_at_full_depth_is_its_flanks() {
        let tool = EndMill { tool_type: ToolType::Radius, diameter_mm: 10.0, flutes: 6, corner_radius_mm: 1.0 };
        let (t, l) = standard_centres(5.0, conditions(0.5, 10.0)).expect("cuts");
        let cut = standard_cut(&tool, conditions(0.5, 10.0), None).expect("cuts");
        assert!((cut.arc_length_mm - l).abs() < 0.5f64.to_radians() * 5.0, "{} against {l}", cut.arc_length_mm);
        assert!((cut.t_m_um - t).abs() < 0.02 * t);
    }
}
