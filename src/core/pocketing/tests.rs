//! Geometry, direction, order and errors of contour-parallel pocketing.

use super::test_support::*;
use super::*;
use crate::core::geometry::{Loop, Vertex};
use crate::core::toolpath::Motion;

/// A path point may come this much closer to the wall than `r + allowance` (mm).
const GOUGE_TOL_MM: f64 = 1e-6;
/// Tolerance of coordinates the offsets compute exactly (mm).
const TOL_MM: f64 = 1e-9;

fn rectangle() -> Pocket {
    pocket(Loop::rectangle(0.0, 0.0, 60.0, 40.0), vec![])
}

fn with_round_island() -> Pocket {
    pocket(Loop::rectangle(0.0, 0.0, 80.0, 60.0), vec![Loop::circle(40.0, 30.0, 8.0)])
}

/// Two 40 × 40 squares joined by a channel `neck_mm` wide and 20 mm long.
fn dumbbell(neck_mm: f64) -> Pocket {
    let (y0, y1) = (20.0 - neck_mm / 2.0, 20.0 + neck_mm / 2.0);
    let v = |x: f64, y: f64| Vertex::new(x, y, 0.0);
    let outer = Loop::new(vec![
        v(0.0, 0.0),
        v(40.0, 0.0),
        v(40.0, y0),
        v(60.0, y0),
        v(60.0, 0.0),
        v(100.0, 0.0),
        v(100.0, 40.0),
        v(60.0, 40.0),
        v(60.0, y1),
        v(40.0, y1),
        v(40.0, 40.0),
        v(0.0, 40.0),
    ]);
    pocket(outer, vec![])
}

/// The loops the path cuts: each run of feed moves at cutting depth that ends where one of
/// its moves started (the straight links before it dropped).
fn cut_loops(path: &Toolpath) -> Vec<Loop> {
    let mut loops = Vec::new();
    let mut current: Vec<Vertex> = Vec::new();
    for (_, seg) in cutting_moves(path) {
        current.push(Vertex::new(seg.start.x, seg.start.y, seg.bulge));
        if let Some(j) = current.iter().position(|v| v.point().near(seg.end, TOL_MM)) {
            loops.push(Loop::new(current.split_off(j)));
            current.clear();
        }
    }
    loops
}

#[test]
fn a_60_by_40_rectangle_with_a_10_mm_tool_at_rd_2_gives_8_nested_rectangles_ending_at_the_wall() {
    let p = rectangle();
    let out = contour_parallel(&p, &spec(5.0, 2.0)).unwrap();
    // Offsets 5, 7, …, 19 mm from the wall: the pocket is 40 mm high.
    assert_eq!(out.loops, 8);
    assert_eq!(out.regions, 1);
    assert_eq!(out.entries.len(), 1);
    assert!(out.warnings.is_empty(), "{:?}", out.warnings);
    assert_continuous(&out.toolpath);
    let moves = cutting_moves(&out.toolpath);
    // The inward offset of a rectangle keeps its corners sharp: no arc anywhere.
    assert!(moves.iter().all(|(_, s)| !s.is_arc()));
    // The last loop is the finishing pass: the rectangle 5 mm inside the wall.
    let finishing = moves.iter().rev().take_while(|(_, s)| wall_distance_mm(&p, s.start) < 5.0 + TOL_MM);
    let mut bounds = crate::core::geometry::Bounds::EMPTY;
    let mut n = 0;
    for (_, s) in finishing {
        bounds.include(s.start);
        bounds.include(s.end);
        n += 1;
    }
    assert!(n >= 4, "{n} moves on the finishing pass");
    let expected = crate::core::geometry::Bounds { x_min: 5.0, y_min: 5.0, x_max: 55.0, y_max: 35.0 };
    assert!(crate::core::geometry::test_support::bounds_near(&bounds, &expected, TOL_MM), "{bounds:?}");
    // The first loop (innermost) is 19 mm from the wall: 22 × 2 mm around (30, 20).
    let first = moves.iter().take_while(|(_, s)| wall_distance_mm(&p, s.start) > 19.0 - TOL_MM).count();
    assert!(first >= 4, "{first}");
    let margin = min_wall_distance_mm(&p, &out.toolpath) - 5.0;
    println!("rectangle: {} moves, no-gouge margin {margin:e} mm", out.toolpath.moves.len());
    assert!(margin >= -GOUGE_TOL_MM, "{margin}");
}

#[test]
fn an_allowance_keeps_every_point_of_the_path_r_plus_allowance_from_the_wall() {
    let p = with_round_island();
    let mut s = spec(5.0, 2.0);
    s.allowance_mm = 0.5;
    let out = contour_parallel(&p, &s).unwrap();
    let margin = min_wall_distance_mm(&p, &out.toolpath) - 5.5;
    assert!(margin >= -GOUGE_TOL_MM, "{margin}");
    assert!(margin < 1e-3, "the finishing pass runs at r + allowance: {margin}");
}

#[test]
fn a_round_island_is_circled_by_true_arcs_and_never_gouged() {
    let p = with_round_island();
    let out = contour_parallel(&p, &spec(5.0, 2.0)).unwrap();
    assert_continuous(&out.toolpath);
    let margin = min_wall_distance_mm(&p, &out.toolpath) - 5.0;
    println!("island: {} loops, {} entries, no-gouge margin {margin:e} mm", out.loops, out.entries.len());
    assert!(margin >= -GOUGE_TOL_MM, "{margin}");
    // The finishing pass around the island: clockwise arcs about its centre, radius 8 + 5.
    let around: Vec<_> = out
        .toolpath
        .moves
        .iter()
        .filter_map(|m| match m.motion {
            Motion::Arc { center, clockwise, .. } => {
                let r = (m.start.x - center.x).hypot(m.start.y - center.y);
                let about_island = (center.x - 40.0).abs() < TOL_MM && (center.y - 30.0).abs() < TOL_MM;
                (about_island && (r - 13.0).abs() < TOL_MM).then_some(clockwise)
            }
            _ => None,
        })
        .collect();
    assert!(!around.is_empty());
    assert!(around.iter().all(|&cw| cw), "climb around an island is clockwise");
}

#[test]
fn climbing_keeps_the_wall_on_the_right_of_the_finishing_passes_and_conventional_on_the_left() {
    let p = with_round_island();
    for climb in [true, false] {
        let mut s = spec(5.0, 2.0);
        s.climb = climb;
        let out = contour_parallel(&p, &s).unwrap();
        let mut checked = 0;
        for (m, seg) in cutting_moves(&out.toolpath) {
            let mid = seg.midpoint();
            // Finishing passes only: the whole move 5 mm from the wall (links are not).
            let on_finishing = [seg.start, mid, seg.end].iter().all(|&q| (wall_distance_mm(&p, q) - 5.0).abs() < 1e-6);
            if !on_finishing || seg.length_mm() < 1e-3 {
                continue;
            }
            let (dx, dy) = direction_at_midpoint(&seg);
            let (wx, wy) = mid.vector_to(nearest_wall_point(&p, mid));
            // cross(direction, to the wall) < 0: the wall is on the right.
            let right = dx * wy - dy * wx < 0.0;
            assert_eq!(right, climb, "line {}: climb {climb}, wall on the right {right}", m.line);
            checked += 1;
        }
        assert!(checked >= 6, "{checked} finishing moves checked");
    }
}

#[test]
fn the_outer_finishing_pass_of_a_climb_path_runs_counter_clockwise() {
    let p = rectangle();
    let loops = cut_loops(&contour_parallel(&p, &spec(5.0, 2.0)).unwrap().toolpath);
    assert_eq!(loops.len(), 8);
    assert!(loops.iter().all(Loop::is_ccw));
    let last = loops.last().unwrap();
    assert!((last.signed_area() - 50.0 * 30.0).abs() < 1e-6, "{}", last.signed_area());
    let conventional = {
        let mut s = spec(5.0, 2.0);
        s.climb = false;
        cut_loops(&contour_parallel(&p, &s).unwrap().toolpath)
    };
    assert!(conventional.iter().all(|lp| !lp.is_ccw()));
}

#[test]
fn loops_are_linked_by_short_feed_moves_and_entered_once() {
    let out = contour_parallel(&rectangle(), &spec(5.0, 2.0)).unwrap();
    let rapids = out.toolpath.moves.iter().filter(|m| matches!(m.motion, Motion::Rapid)).count();
    // Positioning above the entry and the final retract.
    assert_eq!(rapids, 2);
    let plunges = out.toolpath.moves.iter().filter(|m| (m.start.x - m.end.x).hypot(m.start.y - m.end.y) < TOL_MM);
    assert_eq!(plunges.filter(|m| m.end.z < m.start.z).count(), 1);
    // Links between consecutive loops are Rd·√2 at most (across a corner).
    let links = cutting_moves(&out.toolpath)
        .into_iter()
        .filter(|(_, s)| {
            let (a, b) = (wall_distance_mm(&rectangle(), s.start), wall_distance_mm(&rectangle(), s.end));
            (a - b).abs() > 1.0
        })
        .count();
    assert_eq!(links, 7);
    let (first_move, plunge) = (&out.toolpath.moves[0], &out.toolpath.moves[1]);
    assert!(matches!(first_move.motion, Motion::Rapid) && (first_move.end.z - 5.0).abs() < TOL_MM);
    assert!(plunge.feed_mm_min.is_some_and(|f| (f - 300.0).abs() < TOL_MM));
    assert!((out.entries[0].0 - plunge.end.x).abs() < TOL_MM && (out.entries[0].1 - plunge.end.y).abs() < TOL_MM);
}

#[test]
fn a_neck_narrower_than_the_tool_leaves_two_regions_each_entered_from_above() {
    let p = dumbbell(8.0);
    let out = contour_parallel(&p, &spec(5.0, 2.0)).unwrap();
    assert_eq!(out.regions, 2);
    assert_eq!(out.entries.len(), 2);
    assert_continuous(&out.toolpath);
    assert!(min_wall_distance_mm(&p, &out.toolpath) >= 5.0 - GOUGE_TOL_MM);
    // Each entry lies in its own square.
    assert!(out.entries.iter().any(|e| e.0 < 40.0) && out.entries.iter().any(|e| e.0 > 60.0));
}

#[test]
fn a_region_that_splits_as_it_shrinks_is_cut_branch_by_branch_and_warns_of_the_extra_entry() {
    let p = dumbbell(14.0);
    let out = contour_parallel(&p, &spec(5.0, 2.0)).unwrap();
    assert_eq!(out.regions, 1);
    assert_eq!(out.entries.len(), 2, "{:?}", out.entries);
    assert_eq!(out.warnings.len(), 1, "{:?}", out.warnings);
    assert_continuous(&out.toolpath);
    assert!(min_wall_distance_mm(&p, &out.toolpath) >= 5.0 - GOUGE_TOL_MM);
    // The last loop is the finishing pass of the whole dumbbell, through the neck.
    let last = cut_loops(&out.toolpath).pop().unwrap();
    assert!(last.bounds().x_min < 6.0 && last.bounds().x_max > 94.0, "{:?}", last.bounds());
}

#[test]
fn border_dxf_with_a_10_mm_tool_at_rd_3_builds_a_continuous_path_that_never_gouges() {
    let p = border_dxf();
    let started = std::time::Instant::now();
    let out = contour_parallel(&p, &spec(5.0, 3.0)).unwrap();
    let elapsed = started.elapsed();
    assert_continuous(&out.toolpath);
    let margin = min_wall_distance_mm(&p, &out.toolpath) - 5.0;
    let arcs = out.toolpath.moves.iter().filter(|m| matches!(m.motion, Motion::Arc { .. })).count();
    println!(
        "border.dxf: {} loops, {} regions, {} entries, {} moves ({arcs} arcs), margin {margin:e} mm, built in {elapsed:?}",
        out.loops,
        out.regions,
        out.entries.len(),
        out.toolpath.moves.len()
    );
    assert!(margin >= -GOUGE_TOL_MM, "{margin}");
    // The corner arcs of radius 10 offset by 5: the finishing pass has arcs of radius 5.
    assert!(arcs >= 4);
    assert_eq!(out.regions, 1);
}

#[test]
fn a_pocket_narrower_than_the_tool_is_refused_naming_the_tool() {
    let p = pocket(Loop::rectangle(0.0, 0.0, 60.0, 9.0), vec![]);
    let err = contour_parallel(&p, &spec(5.0, 2.0)).unwrap_err();
    let text = err.to_string();
    assert!(text.contains("the tool (r = 5 mm) does not fit in the pocket"), "{text}");
    assert!(matches!(err, CoreError::Unsolvable { ref field, .. } if field == "tool_radius_mm"));
}

#[test]
fn step_overs_beyond_the_tool_radius_and_inverted_levels_are_refused() {
    let p = rectangle();
    let refused = |s: PocketingSpec| match contour_parallel(&p, &s).unwrap_err() {
        CoreError::InvalidInput { field, .. } => field,
        other => panic!("{other:?}"),
    };
    assert_eq!(refused(spec(5.0, 5.5)), "radial_depth_mm");
    assert_eq!(refused(spec(5.0, 0.0)), "radial_depth_mm");
    assert_eq!(refused(spec(5.0, 1e-4)), "radial_depth_mm");
    assert_eq!(refused(PocketingSpec { safe_z_mm: -6.0, ..spec(5.0, 2.0) }), "safe_z_mm");
    assert_eq!(refused(PocketingSpec { allowance_mm: -0.1, ..spec(5.0, 2.0) }), "allowance_mm");
    assert_eq!(refused(PocketingSpec { feed_mm_min: f64::NAN, ..spec(5.0, 2.0) }), "feed_mm_min");
}

#[test]
fn a_spec_without_allowance_and_climb_reads_as_climb_with_no_allowance() {
    let json = r#"{"tool_radius_mm": 5, "radial_depth_mm": 2, "z_mm": -5, "safe_z_mm": 5,
        "feed_mm_min": 1000, "plunge_feed_mm_min": 300, "spindle_rpm": 9600}"#;
    let s: PocketingSpec = serde_json::from_str(json).unwrap();
    assert!(s.climb);
    assert!(s.allowance_mm.abs() < TOL_MM);
}
