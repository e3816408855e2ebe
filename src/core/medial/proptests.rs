//! Properties of the medial axis on random rectangles, slots and star-shaped pockets.

use super::accuracy_tests::{assert_consistent, assert_points_are_centres_of_inscribed_circles};
use super::test_shapes::{nearest_on, turned_stadium};
use super::*;
use crate::core::geometry::{Loop, Pocket, Point, Vertex};
use proptest::prelude::*;
use std::f64::consts::TAU;

/// Positions and clearances within this fraction of the sampling step of the analytic ones.
const STEP_FRACTION: f64 = 0.01;

/// Exact results up to rounding (mm).
const EXACT_MM: f64 = 1e-9;

/// Random cases per property (each builds an axis).
const CASES: u32 = 40;

/// Checks the axis of a pocket whose analytic axis and clearance are known.
fn check_against(pocket: &Pocket, analytic: &[Vec<Point>], clearance: impl Fn(Point) -> f64) {
    let axis = medial_axis(pocket, &MedialOptions::default()).unwrap();
    let tol = STEP_FRACTION * axis.step_mm;
    assert_consistent(&axis);
    assert_points_are_centres_of_inscribed_circles(pocket, &axis, tol);
    for p in axis.points() {
        assert!((p.clearance_mm - clearance(p.point)).abs() <= EXACT_MM, "{p:?}");
        let (d, _) = nearest_on(analytic, p.point);
        assert!(d <= tol, "{p:?} is {d} mm off the axis");
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(CASES))]

    #[test]
    fn rectangles_axes_lie_on_the_middle_segment_and_the_corner_diagonals(
        x0 in -50.0..50.0f64, y0 in -50.0..50.0f64, w in 5.0..100.0f64, h in 5.0..100.0f64,
    ) {
        let pocket = Pocket::new(Loop::rectangle(x0, y0, x0 + w, y0 + h), vec![]).unwrap();
        let m = 0.5 * w.min(h);
        let (a, b) = if w >= h {
            (Point::new(x0 + m, y0 + m), Point::new(x0 + w - m, y0 + m))
        } else {
            (Point::new(x0 + m, y0 + m), Point::new(x0 + m, y0 + h - m))
        };
        // Each corner's diagonal runs to the nearer end of the middle segment.
        let mut analytic = vec![vec![a, b]];
        for c in [Point::new(x0, y0), Point::new(x0 + w, y0), Point::new(x0 + w, y0 + h), Point::new(x0, y0 + h)] {
            analytic.push(vec![c, if c.distance_mm(a) < c.distance_mm(b) { a } else { b }]);
        }
        let exact = |p: Point| (p.x - x0).min(x0 + w - p.x).min(p.y - y0).min(y0 + h - p.y);
        check_against(&pocket, &analytic, exact);
    }

    #[test]
    fn slots_axes_are_one_branch_on_the_centre_line(
        length in 10.0..150.0f64, width_fraction in 0.05..0.9f64, angle in 0.0..TAU,
        x in -50.0..50.0f64, y in -50.0..50.0f64,
    ) {
        let width = width_fraction * length;
        let (pocket, analytic) = turned_stadium(length, width, angle, Point::new(x, y));
        let (a, b) = (analytic[0][0], analytic[0][1]);
        let exact = |p: Point| 0.5 * width - nearest_on(&[vec![a, b]], p).0;
        check_against(&pocket, &analytic, exact);
        let axis = medial_axis(&pocket, &MedialOptions::default()).unwrap();
        prop_assert_eq!(axis.branches.len(), 1);
    }

    #[test]
    fn star_shaped_pockets_with_arcs_give_consistent_axes_of_inscribed_circle_centres(
        radii in proptest::collection::vec(20.0..40.0f64, 5..24),
        bulges in proptest::collection::vec(-0.15..0.15f64, 24),
        island in 0.0..8.0f64,
    ) {
        let n = radii.len();
        let outer = Loop::new(
            (0..n)
                .map(|k| {
                    let a = TAU * k as f64 / n as f64;
                    Vertex::new(radii[k] * a.cos(), radii[k] * a.sin(), bulges[k])
                })
                .collect(),
        );
        let islands = if island > 2.0 { vec![Loop::circle(1.0, -2.0, island)] } else { vec![] };
        let Ok(pocket) = Pocket::new(outer, islands) else { return Ok(()) };
        let axis = medial_axis(&pocket, &MedialOptions::default()).unwrap();
        assert_consistent(&axis);
        assert_points_are_centres_of_inscribed_circles(&pocket, &axis, STEP_FRACTION * axis.step_mm);
        let cycles = axis.branches.len() + 1 - axis.nodes.len();
        prop_assert_eq!(cycles, pocket.islands.len());
    }
}
