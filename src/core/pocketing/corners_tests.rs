//! Corner loops: their size and place, where they are left out, and how the path runs them.

use super::*;
use crate::core::geometry::Pocket;
use crate::core::pocketing::offsets::offset_tree;
use crate::core::pocketing::test_support::{assert_continuous, cutting_moves, pocket, spec};
use crate::core::pocketing::{contour_parallel, PocketingSpec};
use crate::core::toolpath::{Motion, Toolpath};
use std::f64::consts::{FRAC_PI_2, TAU};

/// Tolerance of exact constructions (mm).
const TOL_MM: f64 = 1e-9;

fn rectangle() -> Pocket {
    pocket(Loop::rectangle(0.0, 0.0, 60.0, 40.0), vec![])
}

/// The regular polygon of `n` sides inscribed in a circle of radius `r_mm` about the origin.
fn polygon(n: usize, r_mm: f64) -> Pocket {
    let v = (0..n).map(|k| {
        let a = TAU * k as f64 / n as f64;
        Vertex::new(r_mm * a.cos(), r_mm * a.sin(), 0.0)
    });
    pocket(Loop::new(v.collect()), vec![])
}

fn with_loops(s: PocketingSpec) -> PocketingSpec {
    PocketingSpec { corner_loops: true, ..s }
}

/// The half circles of the path's corner loops, with their sense (clockwise or not).
fn half_circles(path: &Toolpath) -> Vec<bool> {
    path.moves
        .iter()
        .filter_map(|m| match m.motion {
            Motion::Arc { center, clockwise, .. } => {
                let (sx, sy) = (m.start.x - center.x, m.start.y - center.y);
                let (ex, ey) = (m.end.x - center.x, m.end.y - center.y);
                // Start and end diametrically opposite.
                ((sx + ex).hypot(sy + ey) < 1e-6).then_some(clockwise)
            }
            _ => None,
        })
        .collect()
}

#[test]
fn the_loop_radius_is_1_71_rd_at_a_right_angle_and_rd_at_a_turn_of_120_degrees() {
    let rd = 2.0;
    assert!((corner_loop_radius_mm(rd, FRAC_PI_2) - rd / (2.0 - std::f64::consts::SQRT_2)).abs() < TOL_MM);
    assert!((corner_loop_radius_mm(rd, 120f64.to_radians()) - rd).abs() < TOL_MM);
}

#[test]
fn a_right_angled_corner_loop_reaches_halfway_from_the_rings_corner_to_the_previous_rings() {
    // Offsets 5, 7, 9 … of a 60 × 40 rectangle: ring 1 has corners (7, 7) …, ring 2 (9, 9) ….
    let tree = offset_tree(&rectangle(), 5.0, 2.0).unwrap();
    let region = &tree.components[1];
    let looped = with_corner_loops(&region.loops[0], region, 2.0, true);
    let loops = loops_of(&looped.lp);
    assert_eq!((looped.corner_loops, loops.len()), (4, 4));
    let radius = corner_loop_radius_mm(2.0, FRAC_PI_2);
    let corners = [(7.0, 7.0, 1.0, 1.0), (53.0, 7.0, -1.0, 1.0), (53.0, 33.0, -1.0, -1.0), (7.0, 33.0, 1.0, -1.0)];
    for lp in &loops {
        let nearest = |c: &&(f64, f64, f64, f64)| lp.center.distance_mm(Point::new(c.0, c.1));
        let &(px, py, ix, iy) = corners.iter().min_by(|a, b| nearest(a).total_cmp(&nearest(b))).unwrap();
        assert!((lp.radius_mm - radius).abs() < TOL_MM, "{lp:?}");
        // The apex, nearest to the corner, is the midpoint of the two rings' corners.
        let apex = Point::new(px + ix, py + iy);
        assert!((lp.center.distance_mm(apex) - radius).abs() < 1e-9, "{lp:?}");
        let (cx, cy) = lp.center.vector_to(apex);
        assert!((cx * iy - cy * ix).abs() < TOL_MM && cx * ix < 0.0, "the apex is on the bisector: {lp:?}");
        // It leaves the incoming side tangentially, ρ before the corner.
        assert!((lp.start.distance_mm(Point::new(px, py)) - radius).abs() < TOL_MM, "{lp:?}");
    }
    // Every loop is followed by the side into its corner, and the ring is otherwise intact.
    assert!((looped.lp.perimeter_mm() - region.loops[0].perimeter_mm() - 4.0 * TAU * radius).abs() < 1e-6);
}

#[test]
fn the_path_runs_a_loop_before_every_corner_of_the_rings_it_fits_in_and_stays_continuous() {
    let plain = contour_parallel(&rectangle(), &spec(5.0, 2.0)).unwrap();
    let out = contour_parallel(&rectangle(), &with_loops(spec(5.0, 2.0))).unwrap();
    assert_eq!(plain.corner_loops, 0);
    assert!(half_circles(&plain.toolpath).is_empty());
    // Rings 30, 26, 22, 18, 14 and 10 mm high hold a circle of 2ρ = 6.83 mm; the ring 6 mm
    // high does not, and the innermost (2 mm) is slotted.
    assert_eq!(out.corner_loops, 24);
    assert_eq!(out.loops, plain.loops);
    assert_continuous(&out.toolpath);
    let halves = half_circles(&out.toolpath);
    assert_eq!(halves.len(), 48);
    assert!(halves.iter().all(|&cw| !cw), "climb milling runs them counter-clockwise");
    // Each loop leaves its ring tangentially, and the ring then runs on from there.
    let moves = cutting_moves(&out.toolpath);
    for k in 0..moves.len() - 2 {
        let (first, second, after) = (&moves[k].1, &moves[k + 1].1, &moves[k + 2].1);
        if first.is_arc() && second.is_arc() && first.start.near(second.end, TOL_MM) {
            let (center, _) = first.circle().unwrap();
            let (rx, ry) = center.vector_to(first.start);
            let (ax, ay) = after.start.vector_to(after.end);
            assert!(!after.is_arc() && after.start.near(first.start, TOL_MM), "line {}", moves[k].0.line);
            assert!((rx * ax + ry * ay).abs() < 1e-6 * ax.hypot(ay), "line {}", moves[k].0.line);
        }
    }
}

#[test]
fn conventional_milling_runs_its_corner_loops_clockwise() {
    let s = PocketingSpec { climb: false, ..with_loops(spec(5.0, 2.0)) };
    let out = contour_parallel(&rectangle(), &s).unwrap();
    assert_eq!(out.corner_loops, 24);
    assert_continuous(&out.toolpath);
    assert!(half_circles(&out.toolpath).iter().all(|&cw| cw));
}

#[test]
fn turns_under_45_degrees_and_round_corners_get_no_loop() {
    // A decagon turns 36° at each corner, a hexagon 60°.
    let decagon = contour_parallel(&polygon(10, 40.0), &with_loops(spec(5.0, 2.0))).unwrap();
    assert_eq!(decagon.corner_loops, 0);
    let hexagon = contour_parallel(&polygon(6, 40.0), &with_loops(spec(5.0, 2.0))).unwrap();
    assert!(hexagon.corner_loops >= 6 && hexagon.corner_loops.is_multiple_of(6), "{}", hexagon.corner_loops);
    let round = pocket(Loop::circle(0.0, 0.0, 30.0), vec![]);
    assert_eq!(contour_parallel(&round, &with_loops(spec(5.0, 2.0))).unwrap().corner_loops, 0);
}

#[test]
fn a_ring_never_starts_on_a_corner_loop_or_between_it_and_its_corner() {
    let tree = offset_tree(&rectangle(), 5.0, 2.0).unwrap();
    let region = &tree.components[1];
    let looped = with_corner_loops(&region.loops[0], region, 2.0, true);
    for (segment, owner) in looped.approach_of.iter().enumerate() {
        let at = crate::core::pocketing::seam::Nearest {
            segment,
            t: 0.5,
            point: looped.lp.segment(segment).point_at(0.5),
            distance_mm: 0.0,
        };
        let snapped = looped.snapped(at);
        match owner {
            Some(v) => {
                assert_eq!((snapped.segment, snapped.t), (*v, 0.0));
                assert!(snapped.point.near(looped.lp.vertices[*v].point(), TOL_MM));
            }
            None => assert_eq!(snapped, at),
        }
    }
}
