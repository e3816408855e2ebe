//! Radius and ball end mills simulated with their profile (issue 32 item 1): the material
//! they remove, and the engagement of each slice at the radius the tool has there.

use super::profile::Profile;
use super::*;
use crate::core::engagement::straight_engagement_angle_rad;
use crate::core::progress::NoProgress;
use crate::core::toolpath::{Move, Units, P3};

const D: f64 = 10.0;
/// The block the passes cross: 50 mm along x.
const BLOCK: Rect = Rect { x_min: 0.0, y_min: 0.0, x_max: 50.0, y_max: 40.0 };
const VOLUME_TOLERANCE: f64 = 0.01;

fn ball() -> EndMill {
    EndMill { tool_type: ToolType::Ball, diameter_mm: D, flutes: 2, corner_radius_mm: D / 2.0 }
}

fn bull(corner_radius_mm: f64) -> EndMill {
    EndMill { tool_type: ToolType::Radius, diameter_mm: D, flutes: 4, corner_radius_mm }
}

/// One pass along x at `y` with the tip at `z`, from before the block to beyond it.
fn pass(y: f64, z: f64) -> Toolpath {
    let m = Move {
        motion: Motion::Linear,
        start: P3::new(BLOCK.x_min - D, y, z),
        end: P3::new(BLOCK.x_max + D, y, z),
        feed_mm_min: Some(1000.0),
        spindle_rpm: Some(10_000.0),
        tool: None,
        line: 1,
    };
    Toolpath { moves: vec![m], events: vec![], source_units: Units::Mm, warnings: vec![] }
}

fn spec(tool: EndMill) -> AnalysisSpec {
    AnalysisSpec { series_points: 2000, ..AnalysisSpec::new(tool, vec![StockRegion::Rect(BLOCK)], 0.0, -10.0) }
}

/// The exact volume a pass `depth_mm` deep across the block removes: its length times the
/// area of the tool's profile below the surface.
fn exact_volume_mm3(tool: &EndMill, depth_mm: f64) -> f64 {
    (BLOCK.x_max - BLOCK.x_min) * 2.0 * Profile::of(tool).half_section_mm2(depth_mm)
}

fn assert_volume(tool: EndMill, depth_mm: f64) {
    let a = analyze(&pass(20.0, -depth_mm), &spec(tool), &NoProgress).expect("analyses");
    let exact = exact_volume_mm3(&tool, depth_mm);
    let error = a.summary.removed_volume_mm3 / exact - 1.0;
    assert!(
        error.abs() <= VOLUME_TOLERANCE,
        "{:?} {depth_mm} mm deep: {:.2} mm³ against {exact:.2} ({:+.2} %)",
        tool.tool_type,
        a.summary.removed_volume_mm3,
        100.0 * error
    );
}

#[test]
fn a_ball_end_mill_pass_removes_the_segment_below_the_surface_within_one_percent() {
    for depth_mm in [0.2, 0.6, 2.0, 5.0, 7.0] {
        assert_volume(ball(), depth_mm);
    }
}

#[test]
fn a_radius_end_mill_pass_removes_its_flat_end_and_corner_within_one_percent() {
    for depth_mm in [0.3, 1.0, 3.0] {
        assert_volume(bull(1.0), depth_mm);
    }
    assert_volume(bull(2.5), 1.2);
}

#[test]
fn a_radius_end_mill_engages_a_wall_with_its_flank_and_its_corner_at_the_corners_radius() {
    // The flank reaches 0.5 mm into the block's edge at y = 40, 3 mm deep.
    let rd = 0.5;
    let path = pass(BLOCK.y_max + D / 2.0 - rd, -3.0);
    let tool = bull(1.0);
    let mut engaged = Vec::new();
    let a = analyze_with(&path, &spec(tool), &NoProgress, |r| {
        if r.contact.alpha_rad > 0.0 && r.sample.p.x > 10.0 && r.sample.p.x < 40.0 {
            engaged.push((r.contact.alpha_rad.to_degrees(), r.contact_radius_mm, r.ad_mm));
        }
    })
    .expect("analyses");
    assert!(!engaged.is_empty());
    let straight = straight_engagement_angle_rad(rd, D / 2.0).to_degrees();
    for &(alpha_deg, radius_mm, ad_mm) in &engaged {
        assert!((alpha_deg - straight).abs() <= 0.5, "α {alpha_deg:.2}° against {straight:.2}°");
        assert!((radius_mm - D / 2.0).abs() < 1e-9, "the flank's slice engages most");
        // The slices in the corner lie inside the wall's reach only where the corner's
        // radius passes 4.5 mm: the flank's 2 mm and the top of the corner.
        assert!(ad_mm > 2.0 && ad_mm < 3.0, "Ad {ad_mm}");
    }
    // The removed volume is the flank's rectangle and the corner's part beyond 4.5 mm.
    assert!(a.summary.removed_volume_mm3 > 0.0);
}

#[test]
fn a_ball_end_mill_slotting_engages_its_whole_leading_half_in_every_slice_and_cuts_at_the_slices_radii() {
    let path = pass(20.0, -2.0);
    let mut radii = Vec::new();
    analyze_with(&path, &spec(ball()), &NoProgress, |r| {
        if r.sample.p.x > 10.0 && r.sample.p.x < 40.0 {
            assert!((r.contact.alpha_rad.to_degrees() - 180.0).abs() < 0.5, "α {}", r.contact.alpha_rad.to_degrees());
            assert!((r.ad_mm - 2.0).abs() < 1e-9);
            radii.push(r.contact_radius_mm);
        }
    })
    .expect("analyses");
    // The slice engaged most is the widest (the top one, at the ball's mean radius there,
    // below its 4 mm at the surface).
    assert!(radii.iter().all(|&r| r > 3.0 && r < 4.0), "{:?}", &radii[..3]);
}

#[test]
fn a_square_end_mill_is_simulated_as_before_a_cylinder_in_every_slice() {
    let tool = EndMill { tool_type: ToolType::Square, diameter_mm: D, flutes: 4, corner_radius_mm: 0.0 };
    let a = analyze(&pass(20.0, -2.0), &spec(tool), &NoProgress).expect("analyses");
    let exact = 50.0 * D * 2.0;
    assert!((a.summary.removed_volume_mm3 / exact - 1.0).abs() < VOLUME_TOLERANCE);
    assert_eq!(a.summary.slices.len(), 2, "the top slice and the one below the pass: no corner levels");
}

#[test]
fn a_ball_near_an_edge_takes_its_engagement_from_the_slice_of_the_longest_contact_not_the_sliver_at_its_tip() {
    // The centre runs 2 mm inside the block's edge at y = 40, the tip 2 mm deep: the sliver
    // just above the tip (about 1.3 mm across) lies all in material (180°), the top slice
    // (about 3.8 mm) reaches past the edge, and carries the longer contact.
    let path = pass(BLOCK.y_max - 2.0, -2.0);
    let mut seen = Vec::new();
    analyze_with(&path, &spec(ball()), &NoProgress, |r| {
        if r.sample.p.x > 10.0 && r.sample.p.x < 40.0 {
            seen.push((r.contact.alpha_rad.to_degrees(), r.contact_radius_mm, r.arc_length_mm));
        }
    })
    .expect("analyses");
    for &(alpha_deg, radius_mm, arc_mm) in &seen {
        assert!(radius_mm > 3.0, "the sliver's radius {radius_mm} carries the sample");
        assert!(alpha_deg < 179.0 && alpha_deg > 90.0, "α {alpha_deg}");
        assert!((arc_mm - radius_mm * alpha_deg.to_radians()).abs() < 1e-9);
    }
}
