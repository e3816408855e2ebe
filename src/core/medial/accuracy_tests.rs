//! Accuracy of the medial axis on shapes whose axis is known (seed 004 §2.1).

use super::test_shapes::*;
use super::*;
use crate::core::geometry::{Loop, Point};

/// The brief's accuracy: positions and clearances within this fraction of the sampling step.
const STEP_FRACTION: f64 = 0.01;

/// Steps tried on every shape (mm); `None` is the default step.
const STEPS_MM: [Option<f64>; 4] = [None, Some(0.5), Some(1.0), Some(2.0)];

/// An end of a branch into a sharp corner stops within this many steps of the corner.
const CORNER_END_STEPS: f64 = 1.0;

fn axis_of(pocket: &crate::core::geometry::Pocket) -> MedialAxis {
    medial_axis(pocket, &MedialOptions::default()).unwrap()
}

/// Nodes and branches refer to each other, branches start and end at their nodes' points,
/// lengths add up, and node kinds match their degree.
pub(super) fn assert_consistent(axis: &MedialAxis) {
    for (b, branch) in axis.branches.iter().enumerate() {
        let (start, end) = (&axis.nodes[branch.start_node], &axis.nodes[branch.end_node]);
        assert!(branch.points[0].point.near(start.point.point, 0.0));
        assert!(branch.points[branch.points.len() - 1].point.near(end.point.point, 0.0));
        assert!(start.branches.contains(&b) && end.branches.contains(&b));
        assert_eq!(branch.closed, branch.start_node == branch.end_node);
        let length: f64 = branch.points.windows(2).map(|w| w[0].point.distance_mm(w[1].point)).sum();
        assert!((length - branch.length_mm).abs() < 1e-9);
    }
    for node in &axis.nodes {
        let degree: usize = node.branches.iter().map(|&b| if axis.branches[b].closed { 2 } else { 1 }).sum();
        let kind = match degree {
            0 => NodeKind::Isolated,
            1 => NodeKind::End,
            2 => NodeKind::CycleStart,
            _ => NodeKind::Junction,
        };
        assert_eq!(node.kind, kind);
    }
}

/// Every point is inside the pocket, has R > 0 equal to its distance to its nearest contact,
/// and (with two or more contacts) is equally far from its two nearest within `tol_mm`.
pub(super) fn assert_points_are_centres_of_inscribed_circles(
    pocket: &crate::core::geometry::Pocket,
    axis: &MedialAxis,
    tol_mm: f64,
) {
    for p in axis.points() {
        assert!(pocket.contains(p.point.x, p.point.y), "{:?} outside", p.point);
        assert!(p.clearance_mm > 0.0);
        assert!((p.nearest[0].distance_mm(p.point) - p.clearance_mm).abs() <= tol_mm, "{p:?}");
        if let Some(second) = p.nearest.get(1) {
            assert!((second.distance_mm(p.point) - p.clearance_mm).abs() <= tol_mm, "{p:?}");
        }
    }
}

fn kinds(axis: &MedialAxis, kind: NodeKind) -> Vec<&AxisNode> {
    axis.nodes.iter().filter(|n| n.kind == kind).collect()
}

#[test]
fn the_rectangles_axis_is_the_middle_segment_at_clearance_20_and_four_corner_branches() {
    let (pocket, _) = rectangle();
    let axis = axis_of(&pocket);
    let tol = STEP_FRACTION * axis.step_mm;
    assert_consistent(&axis);
    assert_eq!(axis.branches.len(), 5);
    let junctions = kinds(&axis, NodeKind::Junction);
    assert_eq!(junctions.len(), 2);
    for j in &junctions {
        let at_left = j.point.point.near(Point::new(20.0, 20.0), tol);
        assert!(at_left || j.point.point.near(Point::new(40.0, 20.0), tol), "{:?}", j.point);
        assert!((j.point.clearance_mm - 20.0).abs() <= tol);
    }
    let middle: Vec<_> = axis
        .branches
        .iter()
        .filter(|b| {
            axis.nodes[b.start_node].kind == NodeKind::Junction && axis.nodes[b.end_node].kind == NodeKind::Junction
        })
        .collect();
    assert_eq!(middle.len(), 1);
    assert!((middle[0].length_mm - 20.0).abs() <= tol);
    for p in &middle[0].points {
        assert!((p.point.y - 20.0).abs() <= tol && (p.clearance_mm - 20.0).abs() <= tol);
    }
    // The junctions touch three sides, the middle segment's inner points two.
    let points = &middle[0].points;
    assert_eq!((points[0].nearest.len(), points[points.len() - 1].nearest.len()), (3, 3));
    assert!(points[1..points.len() - 1].iter().all(|p| p.nearest.len() == 2));
    let ends = kinds(&axis, NodeKind::End);
    assert_eq!(ends.len(), 4);
    for corner in [(0.0, 0.0), (60.0, 0.0), (60.0, 40.0), (0.0, 40.0)] {
        let corner = Point::new(corner.0, corner.1);
        assert!(ends.iter().any(|e| e.point.point.near(corner, CORNER_END_STEPS * axis.step_mm)), "{corner:?}");
    }
    assert_points_are_centres_of_inscribed_circles(&pocket, &axis, tol);
}

#[test]
fn the_slots_axis_is_one_branch_along_its_centre_line_at_clearance_6() {
    let (pocket, _) = stadium(80.0, 12.0);
    let axis = axis_of(&pocket);
    let tol = STEP_FRACTION * axis.step_mm;
    assert_consistent(&axis);
    assert_eq!(axis.branches.len(), 1);
    assert_eq!(axis.nodes.len(), 2);
    let branch = &axis.branches[0];
    assert!((branch.length_mm - 68.0).abs() <= tol);
    for p in &branch.points {
        assert!((p.clearance_mm - 6.0).abs() <= tol, "{p:?}");
        assert!((p.point.y - 6.0).abs() <= tol);
    }
    for end in &axis.nodes {
        let at_left = end.point.point.near(Point::new(6.0, 6.0), tol);
        assert!(at_left || end.point.point.near(Point::new(74.0, 6.0), tol), "{:?}", end.point);
    }
    assert_points_are_centres_of_inscribed_circles(&pocket, &axis, tol);
}

#[test]
fn a_circles_axis_is_its_centre_alone_at_clearance_20() {
    let pocket = crate::core::geometry::Pocket::new(Loop::circle(3.0, -4.0, 20.0), vec![]).unwrap();
    let axis = axis_of(&pocket);
    let tol = STEP_FRACTION * axis.step_mm;
    assert_consistent(&axis);
    assert!(axis.branches.is_empty());
    assert_eq!(axis.nodes.len(), 1);
    assert_eq!(axis.nodes[0].kind, NodeKind::Isolated);
    assert!(axis.nodes[0].point.point.near(Point::new(3.0, -4.0), tol));
    assert!((axis.nodes[0].point.clearance_mm - 20.0).abs() <= tol);
    assert!((axis.max_clearance_mm() - 20.0).abs() <= tol);
}

#[test]
fn the_ls_axis_has_three_junctions_and_five_corner_ends_and_bends_around_the_reflex_corner() {
    let (pocket, analytic) = l_shape();
    let axis = axis_of(&pocket);
    let tol = STEP_FRACTION * axis.step_mm;
    assert_consistent(&axis);
    assert_eq!(axis.branches.len(), 7);
    assert_eq!(kinds(&axis, NodeKind::End).len(), 5);
    let junctions = kinds(&axis, NodeKind::Junction);
    assert_eq!(junctions.len(), 3);
    // The elbow's junction lies on the outer corner's diagonal where R = √2·(20 − R).
    let t = 20.0 * 2f64.sqrt() / (1.0 + 2f64.sqrt());
    assert!(junctions
        .iter()
        .any(|j| j.point.point.near(Point::new(t, t), tol) && (j.point.clearance_mm - t).abs() <= tol));
    for (x, y) in [(50.0, 10.0), (10.0, 50.0)] {
        let j = junctions.iter().find(|j| j.point.point.near(Point::new(x, y), tol)).expect("a leg's end junction");
        assert!((j.point.clearance_mm - 10.0).abs() <= tol);
    }
    // Along the legs' centre lines R = 10; on the parabola R = y.
    for p in axis.points() {
        if (20.0..=50.0).contains(&p.point.x) && p.point.y < 20.0 {
            assert!((p.point.y - 10.0).abs() <= tol && (p.clearance_mm - 10.0).abs() <= tol, "{p:?}");
        }
        if (t..20.0).contains(&p.point.x) && p.point.y < p.point.x {
            assert!((p.clearance_mm - p.point.y).abs() <= tol, "{p:?}");
        }
    }
    let (d, r) = worst_errors(&pocket, &axis, &analytic);
    assert!(d <= tol && r <= tol, "{d} {r}");
}

#[test]
fn a_square_ring_has_one_cycle_around_the_island_and_four_corner_branches() {
    let (pocket, analytic) = square_ring();
    let axis = axis_of(&pocket);
    let tol = STEP_FRACTION * axis.step_mm;
    assert_consistent(&axis);
    assert_eq!(kinds(&axis, NodeKind::Junction).len(), 4);
    assert_eq!(kinds(&axis, NodeKind::End).len(), 4);
    assert_eq!(axis.branches.len(), 8);
    // A connected graph with as many branches as nodes has exactly one cycle.
    assert_eq!(axis.branches.len() + 1 - axis.nodes.len(), 1);
    // Midway along each side R = 10.
    for (x, y) in [(30.0, 10.0), (50.0, 30.0), (30.0, 50.0), (10.0, 30.0)] {
        let (d, _) = nearest_on(&[axis.points().map(|p| p.point).collect()], Point::new(x, y));
        assert!(d < axis.step_mm, "({x}, {y})");
    }
    let (d, r) = worst_errors(&pocket, &axis, &analytic);
    assert!(d <= tol && r <= tol, "{d} {r}");
    assert_points_are_centres_of_inscribed_circles(&pocket, &axis, tol);
}

#[test]
fn a_circular_ring_has_a_closed_axis_of_radius_20_at_clearance_10() {
    let (pocket, _) = circle_ring();
    let axis = axis_of(&pocket);
    let tol = STEP_FRACTION * axis.step_mm;
    assert_consistent(&axis);
    assert_eq!(axis.branches.len(), 1);
    assert!(axis.branches[0].closed);
    assert_eq!(axis.nodes.len(), 1);
    assert_eq!(axis.nodes[0].kind, NodeKind::CycleStart);
    for p in axis.points() {
        assert!((p.point.distance_mm(Point::new(0.0, 0.0)) - 20.0).abs() <= tol, "{p:?}");
        assert!((p.clearance_mm - 10.0).abs() <= tol);
    }
    // The polygon through the points is a little shorter than the circle (2π·20).
    let circle = std::f64::consts::TAU * 20.0;
    assert!(axis.branches[0].length_mm < circle && axis.branches[0].length_mm > 0.99 * circle);
    assert_points_are_centres_of_inscribed_circles(&pocket, &axis, tol);
}

#[test]
fn every_axis_point_lies_on_the_analytic_axis_within_one_percent_of_the_step_for_coarse_and_fine_steps() {
    for (name, (pocket, analytic)) in [
        ("rectangle", rectangle()),
        ("slot", stadium(80.0, 12.0)),
        ("L", l_shape()),
        ("square ring", square_ring()),
        ("circular ring", circle_ring()),
        ("border.dxf", border_dxf()),
    ] {
        for step_mm in STEPS_MM {
            let axis = medial_axis(&pocket, &MedialOptions { step_mm, ..MedialOptions::default() }).unwrap();
            let tol = STEP_FRACTION * axis.step_mm;
            let (d, r) = worst_errors(&pocket, &axis, &analytic);
            println!(
                "{name}, step {:.3} mm: worst distance from the axis {d:.1e} mm, worst R error {r:.1e} mm",
                axis.step_mm
            );
            assert!(d <= tol && r <= tol, "{name} at step {:?}: {d} {r}", axis.step_mm);
            // Every analytic branch is found: each analytic vertex is near an axis point,
            // except the sharp corners where the axis stops about half a step short.
            let points: Vec<Point> = axis.points().map(|p| p.point).collect();
            for v in analytic.iter().flat_map(|line| [line[0], line[line.len() - 1]]) {
                let (d, _) = nearest_on(std::slice::from_ref(&points), v);
                assert!(d <= CORNER_END_STEPS * axis.step_mm, "{name}: nothing near {v:?}");
            }
            assert_points_are_centres_of_inscribed_circles(&pocket, &axis, tol);
        }
    }
}
