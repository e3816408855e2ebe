use super::*;
use crate::core::analysis::{analyze_with, StockRegion};
use crate::core::conditions::CuttingConditions;
use crate::core::cycles::test_support::*;
use crate::core::engagement::concave_engagement_angle_rad;
use crate::core::geometry::{Loop, Pocket, Vertex};
use crate::core::progress::NoProgress;
use crate::core::tolerance::approx_eq;
use crate::core::toolpath::Motion;
use std::f64::consts::PI;

/// Seed 004 Table 2 (4): rough side cutting, 10 mm straight, S 4800, fz 0.1, Rd 0.5, Ad 10.
fn side_setup() -> CycleSetup {
    let c = CuttingConditions { spindle_rpm: 4800.0, fz_mm: 0.1, rd_mm: 0.5, ad_mm: 10.0 };
    CycleSetup { retract_z_mm: Some(RETRACT_Z), ..CycleSetup::new(c, 6, CLEARANCE_Z) }
}

/// A corner of interior angle `theta_deg` at the origin, one wall along +x, left at R 10 by
/// a 20 mm tool, finished to R 6 (R/r = 1.2) with the 10 mm tool, 10 mm deep in one level.
fn corner(theta_deg: f64) -> CornerParams {
    let t = theta_deg.to_radians();
    CornerParams {
        vertex: Point::new(0.0, 0.0),
        wall_a: (1.0, 0.0),
        wall_b: (t.cos(), t.sin()),
        final_radius_mm: 6.0,
        previous_radius_mm: 10.0,
        tool_radius_mm: R10,
        alpha_limit_deg: None,
        z_top_mm: 0.0,
        z_bottom_mm: -10.0,
        max_ad_mm: None,
        direction: CutDirection::Climb,
    }
}

#[test]
fn the_largest_radial_depth_inverts_the_concave_engagement_formula() {
    for ratio in [1.05, 1.2, 1.6, 2.0, 3.0, 10.0] {
        for limit_deg in [20.0, 40.0, 60.0, 120.0] {
            let big_r = ratio * R10;
            let rd = max_concave_rd_mm(big_r, R10, f64::to_radians(limit_deg));
            let alpha = concave_engagement_angle_rad(big_r, rd, R10).to_degrees();
            assert!(rd > 0.0 && approx_eq(alpha, limit_deg, 1e-6), "R/r {ratio}, {limit_deg}°: Rd {rd} gives {alpha}°");
        }
    }
}

#[test]
fn each_step_cuts_on_the_bisector_no_deeper_than_the_limit_allows_and_the_last_is_the_finished_radius() {
    for theta in [60.0, 90.0, 120.0] {
        let p = corner(theta);
        let radii = corner_step_radii(&p).unwrap();
        assert!(approx_eq(*radii.last().unwrap(), 6.0, 0.0));
        let k = 1.0 / (theta.to_radians() / 2.0).sin() - 1.0;
        let limit = DEFAULT_CORNER_ALPHA_LIMIT_DEG.to_radians();
        let mut prev = 10.0;
        for (i, &radius) in radii.iter().enumerate() {
            let depth = (prev - radius) * k;
            let allowed = max_concave_rd_mm(radius, R10, limit);
            assert!(radius < prev && depth <= allowed + 1e-9, "{theta}° step {i}: {depth} > {allowed}");
            if i + 1 < radii.len() {
                assert!(approx_eq(depth, allowed, 1e-9), "{theta}° step {i} is not the largest allowed");
            }
            prev = radius;
        }
        eprintln!("{theta}° corner, R 10 → 6 with r 5: steps {radii:.3?}");
    }
}

#[test]
fn the_corner_passes_are_continuous_tangent_and_climb_round_the_fillet_centres() {
    let p = corner(90.0);
    let c = corner_milling(&p, &side_setup()).unwrap();
    assert_continuous(&c.moves);
    assert_tangent_at(&c.moves, -10.0, 1e-9);
    let radii = corner_step_radii(&p).unwrap();
    assert_eq!(c.report.steps, radii.len());
    let arcs: Vec<_> = c.moves.iter().filter(|m| matches!(m.motion, Motion::Arc { .. })).collect();
    assert_eq!(arcs.len(), radii.len());
    for (m, big_r) in arcs.iter().zip(&radii) {
        let Motion::Arc { clockwise, center, .. } = m.motion else { unreachable!() };
        assert!(!clockwise);
        // The fillet centre of a 90° corner is at (R, R); the tool centre runs at R − r.
        assert!(approx_eq(center.x, *big_r, 1e-9) && approx_eq(center.y, *big_r, 1e-9));
        let (rs, re, _) = arc_radii(m).unwrap();
        assert!(approx_eq(rs, big_r - R10, 1e-9) && approx_eq(re, big_r - R10, 1e-9));
        // In along the wall at x = r going down, out along y = r going right.
        assert!(approx_eq(m.start.x, R10, 1e-9) && approx_eq(m.end.y, R10, 1e-9));
    }
    let conventional = CornerParams { direction: CutDirection::Conventional, ..p };
    let c = corner_milling(&conventional, &side_setup()).unwrap();
    assert!(c.moves.iter().all(|m| !matches!(m.motion, Motion::Arc { clockwise: false, .. })));
    assert_tangent_at(&c.moves, -10.0, 1e-9);
}

/// The open region after the previous tool: the wedge (cut `far` mm out) minus the corner
/// it left, as a counter-clockwise loop with the previous fillet as an arc.
fn wedge(p: &CornerParams, far: f64, fillet: Option<f64>) -> StockRegion {
    let (a, b) = (p.wall_a, p.wall_b);
    let theta = (a.0 * b.1 - a.1 * b.0).atan2(a.0 * b.0 + a.1 * b.1);
    let vertices = match fillet {
        None => vec![
            Vertex::new(0.0, 0.0, 0.0),
            Vertex::new(a.0 * far, a.1 * far, 0.0),
            Vertex::new(b.0 * far, b.1 * far, 0.0),
        ],
        Some(radius) => {
            let t = radius / (theta / 2.0).tan();
            vec![
                Vertex::new(a.0 * t, a.1 * t, 0.0),
                Vertex::new(a.0 * far, a.1 * far, 0.0),
                Vertex::new(b.0 * far, b.1 * far, 0.0),
                Vertex::new(b.0 * t, b.1 * t, ((PI - theta) / 4.0).tan()),
            ]
        }
    };
    StockRegion::Pocket(Pocket::new(Loop::new(vertices), vec![]).unwrap())
}

/// Largest α over the corner cycle, cut from the corner the previous tool left.
fn corner_alpha_max(p: &CornerParams) -> (f64, f64) {
    let c = corner_milling(p, &side_setup()).unwrap();
    let far = 35.0;
    let stock = wedge(p, far, None);
    let open = wedge(p, far, Some(p.previous_radius_mm));
    let mut alpha_max = 0.0f64;
    let s = spec(vec![stock], vec![open], 0.0, -10.0);
    let a =
        analyze_with(&c.toolpath(), &s, &NoProgress, |r| alpha_max = alpha_max.max(r.contact.alpha_rad.to_degrees()))
            .unwrap();
    (alpha_max, a.summary.slices[0].removed_area_mm2)
}

#[test]
fn the_engagement_along_the_corner_passes_stays_within_the_limit() {
    for theta in [60.0, 90.0, 120.0] {
        let p = corner(theta);
        let (alpha_max, removed) = corner_alpha_max(&p);
        // The corner bit between the two fillets: (R_prev² − R_f²)·(cot(θ/2) − (π − θ)/2).
        let half = theta.to_radians() / 2.0;
        let expected = (100.0 - 36.0) * (1.0 / half.tan() - (PI - theta.to_radians()) / 2.0);
        eprintln!("{theta}° corner: α max {alpha_max:.1}° (limit 40°), removed {removed:.2} mm² of {expected:.2}");
        assert!(alpha_max <= DEFAULT_CORNER_ALPHA_LIMIT_DEG + 1.0, "{theta}°: {alpha_max}");
        assert!((removed - expected).abs() / expected < 0.02, "{removed} vs {expected}");
    }
}

#[test]
fn corners_the_tool_cannot_clear_are_refused() {
    let err = |p: CornerParams| corner_milling(&p, &side_setup()).unwrap_err().to_string();
    assert!(err(CornerParams { final_radius_mm: 5.0, ..corner(90.0) }).starts_with("final_radius_mm"));
    assert!(err(CornerParams { previous_radius_mm: 6.0, ..corner(90.0) }).starts_with("previous_radius_mm"));
    assert!(err(CornerParams { wall_b: (-1.0, 0.0), ..corner(90.0) }).starts_with("wall_b"));
    assert!(err(CornerParams { wall_a: (0.0, 0.0), ..corner(90.0) }).starts_with("wall_a"));
    assert!(err(CornerParams { alpha_limit_deg: Some(0.0), ..corner(90.0) }).starts_with("alpha_limit_deg"));
    let tight =
        CornerParams { final_radius_mm: 5.02, previous_radius_mm: 40.0, alpha_limit_deg: Some(5.0), ..corner(30.0) };
    assert!(err(tight).contains("steps"));
}
