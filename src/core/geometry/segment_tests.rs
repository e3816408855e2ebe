//! Tests of [`super::Segment`]: bulge geometry, length, distance, bounds, row crossings.

use super::*;
use proptest::prelude::*;

/// Tolerance of exact results (mm).
const TOL: f64 = 1e-12;

/// Tolerance of computed points and lengths in the property test (mm, relative to
/// max(1 mm, size)).
const GEOM_TOL: f64 = 1e-9;

/// Samples along the segment in the property test.
const SAMPLES: usize = 2000;

/// Largest relative shortfall of the sampled polyline's length.
const POLY_REL_TOL: f64 = 1e-5;

/// Largest gap between exact bounds and the sampled points' bounds (mm).
const SAMPLED_BOUNDS_TOL: f64 = 1e-4;

fn p(x: f64, y: f64) -> Point {
    Point::new(x, y)
}

fn crossings(seg: &Segment, y: f64) -> Vec<f64> {
    let mut out = Vec::new();
    seg.row_crossings(y, |x| out.push(x));
    out
}

#[test]
fn a_half_circle_bulge_has_its_centre_on_the_chord() {
    let seg = Segment::new(p(1.0, 0.0), p(-1.0, 0.0), 1.0);
    let arc = seg.arc().unwrap();
    assert!(arc.center.distance_mm(p(0.0, 0.0)) < TOL);
    assert!((arc.radius_mm - 1.0).abs() < TOL);
    assert!((arc.sweep_rad - PI).abs() < TOL);
    assert!(seg.midpoint().distance_mm(p(0.0, 1.0)) < TOL);
    assert!((seg.length_mm() - PI).abs() < TOL);
}

#[test]
fn an_arc_built_from_its_centre_gives_back_that_centre() {
    let seg = Segment::from_arc(p(3.0, 4.0), 2.0, 0.3, -2.0);
    let arc = seg.arc().unwrap();
    assert!(arc.center.distance_mm(p(3.0, 4.0)) < TOL);
    assert!((arc.radius_mm - 2.0).abs() < TOL);
    assert!((arc.start_angle_rad - 0.3).abs() < TOL);
    assert!((arc.sweep_rad + 2.0).abs() < TOL);
    assert!((seg.length_mm() - 4.0).abs() < TOL);
}

#[test]
fn a_tiny_bulge_is_a_straight_line() {
    let seg = Segment::new(p(0.0, 0.0), p(10.0, 0.0), STRAIGHT_BULGE / 2.0);
    assert!(!seg.is_arc());
    assert!(seg.arc().is_none());
    assert!((seg.length_mm() - 10.0).abs() < TOL);
    assert!(seg.point_at(0.25).distance_mm(p(2.5, 0.0)) < TOL);
}

#[test]
fn distance_to_an_arc_is_radial_inside_the_sweep_and_to_an_end_outside() {
    let seg = Segment::new(p(1.0, 0.0), p(-1.0, 0.0), 1.0);
    assert!((seg.distance_mm(p(0.0, 3.0)) - 2.0).abs() < TOL);
    assert!((seg.distance_mm(p(0.0, 0.5)) - 0.5).abs() < TOL);
    assert!((seg.distance_mm(p(1.0, -1.0)) - 1.0).abs() < TOL);
    let line = Segment::line(p(0.0, 0.0), p(10.0, 0.0));
    assert!((line.distance_mm(p(5.0, 2.0)) - 2.0).abs() < TOL);
    assert!((line.distance_mm(p(13.0, 4.0)) - 5.0).abs() < TOL);
}

#[test]
fn the_bounds_of_an_arc_include_its_extreme_points_within_the_sweep() {
    // Quarter circle from (0,-1) counter-clockwise to (1,0): passes no extreme inside.
    let q = Segment::from_arc(p(0.0, 0.0), 1.0, -FRAC_PI_2, FRAC_PI_2);
    let b = q.bounds();
    assert!((b.x_min).abs() < TOL && (b.x_max - 1.0).abs() < TOL);
    assert!((b.y_min + 1.0).abs() < TOL && (b.y_max).abs() < TOL);
    // Three quarters clockwise from (0,-1) to (1,0) passes the left, top, and right.
    let t = Segment::from_arc(p(0.0, 0.0), 1.0, -FRAC_PI_2, -1.5 * PI);
    let b = t.bounds();
    assert!((b.x_min + 1.0).abs() < TOL && (b.x_max - 1.0).abs() < TOL);
    assert!((b.y_min + 1.0).abs() < TOL && (b.y_max - 1.0).abs() < TOL);
}

#[test]
fn an_upper_half_circle_is_crossed_twice_below_its_top_and_never_at_it() {
    let seg = Segment::new(p(1.0, 0.0), p(-1.0, 0.0), 1.0);
    let xs = crossings(&seg, 0.5);
    let h = 0.75_f64.sqrt();
    assert_eq!(xs.len(), 2);
    assert!((xs[0] - h).abs() < TOL && (xs[1] + h).abs() < TOL);
    assert!(crossings(&seg, 1.0).is_empty());
    // At the height of both end points nothing is below, so both ends count once.
    assert_eq!(crossings(&seg, 0.0).len(), 2);
    assert!(crossings(&seg, -0.1).is_empty());
}

#[test]
fn a_clockwise_lower_arc_is_crossed_on_the_correct_sides() {
    // From (1,0) clockwise through (0,-1) to (-1,0).
    let seg = Segment::new(p(1.0, 0.0), p(-1.0, 0.0), -1.0);
    let xs = crossings(&seg, -0.5);
    let h = 0.75_f64.sqrt();
    assert_eq!(xs.len(), 2);
    assert!((xs[0] - h).abs() < TOL && (xs[1] + h).abs() < TOL);
}

proptest! {
    #[test]
    fn arc_length_midpoint_and_bounds_agree(
        bulge in -0.999f64..0.999,
        x0 in -50.0f64..50.0, y0 in -50.0f64..50.0,
        dx in -20.0f64..20.0, dy in -20.0f64..20.0,
    ) {
        prop_assume!(dx.hypot(dy) > 0.1);
        let seg = Segment::new(p(x0, y0), p(x0 + dx, y0 + dy), bulge);
        let mid = seg.midpoint();
        prop_assert!(mid.distance_mm(seg.point_at(0.5)) < GEOM_TOL);
        prop_assert!(seg.distance_mm(mid) < GEOM_TOL);
        // Fine polyline approximation: converges to the arc length from below.
        let n = SAMPLES;
        let mut poly = 0.0;
        let mut prev = seg.start;
        let mut bounds = Bounds::of_point(seg.start);
        for k in 1..=n {
            let q = seg.point_at(k as f64 / n as f64);
            poly += prev.distance_mm(q);
            bounds.include(q);
            prev = q;
        }
        let len = seg.length_mm();
        prop_assert!(len >= seg.chord_mm() - TOL);
        prop_assert!(poly <= len + GEOM_TOL && len - poly < POLY_REL_TOL * len);
        let b = seg.bounds();
        prop_assert!(b.x_min <= bounds.x_min + GEOM_TOL && b.x_max >= bounds.x_max - GEOM_TOL);
        prop_assert!(b.y_min <= bounds.y_min + GEOM_TOL && b.y_max >= bounds.y_max - GEOM_TOL);
        prop_assert!((b.x_min - bounds.x_min).abs() < SAMPLED_BOUNDS_TOL && (b.x_max - bounds.x_max).abs() < SAMPLED_BOUNDS_TOL);
        prop_assert!((b.y_min - bounds.y_min).abs() < SAMPLED_BOUNDS_TOL && (b.y_max - bounds.y_max).abs() < SAMPLED_BOUNDS_TOL);
        if let Some((c, r)) = seg.circle() {
            prop_assert!((c.distance_mm(mid) - r).abs() < GEOM_TOL * r.max(1.0));
            prop_assert!((c.distance_mm(seg.start) - r).abs() < GEOM_TOL * r.max(1.0));
            let sweep = seg.sweep_rad();
            prop_assert!((len - r * sweep.abs()).abs() < GEOM_TOL * len.max(1.0));
            // The sagitta is |b|·chord/2.
            let sag = seg.midpoint().distance_mm(p(x0 + dx / 2.0, y0 + dy / 2.0));
            prop_assert!((sag - bulge.abs() * seg.chord_mm() / 2.0).abs() < GEOM_TOL);
        }
    }
}
