//! The medial axis of the `border.dxf` drawing, the classes along real axes, the JSON form and
//! the refused options.

use super::accuracy_tests::{assert_consistent, assert_points_are_centres_of_inscribed_circles};
use super::test_shapes::*;
use super::*;
use crate::core::geometry::Point;

/// Tolerance of results exact up to the sampling (a small fraction of the step) (mm).
const TOL_MM: f64 = 1e-3;

#[test]
fn the_axis_of_border_dxf_is_its_middle_segment_and_four_branches_to_the_corner_arcs_centres() {
    let (pocket, _) = border_dxf();
    let axis = medial_axis(&pocket, &MedialOptions::default()).unwrap();
    assert_consistent(&axis);
    assert_points_are_centres_of_inscribed_circles(&pocket, &axis, TOL_MM);
    assert_eq!(axis.branches.len(), 5);
    assert_eq!(axis.nodes.iter().filter(|n| n.kind == NodeKind::Junction).count(), 2);
    // The branches end at the centres of the corner arcs, where R is the arcs' radius 10.
    for centre in [(10.0, 10.0), (92.0, 10.0), (92.0, 127.0), (10.0, 127.0)] {
        let end = axis.nodes.iter().find(|n| n.point.point.near(Point::new(centre.0, centre.1), TOL_MM));
        let end = end.unwrap_or_else(|| panic!("no end at {centre:?}"));
        assert_eq!(end.kind, NodeKind::End);
        assert!((end.point.clearance_mm - 10.0).abs() < TOL_MM);
    }
    assert!((axis.max_clearance_mm() - 51.0).abs() < TOL_MM);
}

#[test]
#[ignore = "timing print; run with --ignored --nocapture (in release for real numbers)"]
fn the_axis_of_border_dxf_builds_in_milliseconds() {
    let (pocket, _) = border_dxf();
    for step_mm in [None, Some(0.1)] {
        let start = std::time::Instant::now();
        let axis = medial_axis(&pocket, &MedialOptions { step_mm, ..MedialOptions::default() }).unwrap();
        let points = axis.points().count();
        println!("border.dxf, step {:.3} mm: {points} axis points in {:?}", axis.step_mm, start.elapsed());
    }
}

#[test]
fn a_rectangles_corner_branch_passes_from_class_a_to_b_to_c_towards_the_corner() {
    let (pocket, _) = rectangle();
    let axis = medial_axis(&pocket, &MedialOptions::default()).unwrap();
    let classes = classify(&axis, 5.0, CLASS_A_RATIO_DEFAULT).unwrap();
    assert_eq!(classes.len(), axis.branches.len());
    for (c, branch) in classes.iter().zip(&axis.branches) {
        let end_kinds = (axis.nodes[branch.start_node].kind, axis.nodes[branch.end_node].kind);
        if end_kinds == (NodeKind::Junction, NodeKind::Junction) {
            assert_eq!(c.intervals.len(), 1);
            assert_eq!(c.intervals[0].class, RadiusClass::A);
            continue;
        }
        // Along a diagonal from the junction (R = 20) R falls by s/√2: A until R = 2·5 = 10,
        // B until R = 1.1·5 = 5.5, then C.
        let from_junction = axis.nodes[branch.start_node].kind == NodeKind::Junction;
        let mut intervals = c.intervals.clone();
        if !from_junction {
            intervals.reverse();
        }
        let classes: Vec<RadiusClass> = intervals.iter().map(|i| i.class).collect();
        assert_eq!(classes, vec![RadiusClass::A, RadiusClass::B, RadiusClass::C]);
        let (ab, bc) = if from_junction {
            (intervals[0].s_end_mm, intervals[1].s_end_mm)
        } else {
            (branch.length_mm - intervals[0].s_start_mm, branch.length_mm - intervals[1].s_start_mm)
        };
        let sqrt2 = 2f64.sqrt();
        assert!((ab - 10.0 * sqrt2).abs() < TOL_MM, "{ab}");
        assert!((bc - 14.5 * sqrt2).abs() < TOL_MM, "{bc}");
        assert!((c.intervals.last().unwrap().s_end_mm - branch.length_mm).abs() < 1e-9);
    }
}

#[test]
fn a_12_mm_slot_is_class_b_for_a_10_mm_tool_and_class_c_for_an_11_mm_tool() {
    let (pocket, _) = stadium(80.0, 12.0);
    let axis = medial_axis(&pocket, &MedialOptions::default()).unwrap();
    let for_tool = |r: f64| classify(&axis, r, CLASS_A_RATIO_DEFAULT).unwrap()[0].intervals.clone();
    // R / r = 6 / 5 = 1.2 (seed 004 §2.3: the 12 mm slot grooved by trochoids with a 10 mm tool).
    let b = for_tool(5.0);
    assert_eq!(b.len(), 1);
    assert_eq!(b[0].class, RadiusClass::B);
    assert!((b[0].s_end_mm - 68.0).abs() < TOL_MM);
    assert_eq!(for_tool(5.5)[0].class, RadiusClass::C);
    assert_eq!(for_tool(2.5)[0].class, RadiusClass::A);
}

#[test]
fn the_axis_serialises_to_json_with_nodes_branches_and_clearances() {
    let (pocket, _) = stadium(80.0, 12.0);
    let axis = medial_axis(&pocket, &MedialOptions::default()).unwrap();
    let json = serde_json::to_value(&axis).unwrap();
    assert_eq!(json["nodes"][0]["kind"], "end");
    assert!(json["branches"][0]["points"][0]["clearance_mm"].as_f64().is_some());
    assert!(json["branches"][0]["points"][0]["nearest"][0]["x"].as_f64().is_some());
    assert_eq!(json["branches"][0]["closed"], false);
    let classes = classify(&axis, 5.0, CLASS_A_RATIO_DEFAULT).unwrap();
    let json = serde_json::to_value(&classes).unwrap();
    assert_eq!(json[0]["intervals"][0]["class"], "B");
    let options: MedialOptions = serde_json::from_str(r#"{"step_mm": 0.5}"#).unwrap();
    assert_eq!(options.step_mm, Some(0.5));
    assert_eq!(options.prune_threshold_mm, None);
}

#[test]
fn options_that_are_not_positive_or_sample_too_finely_are_refused_naming_the_field() {
    let (pocket, _) = rectangle();
    let field_of = |options: MedialOptions| match medial_axis(&pocket, &options) {
        Err(CoreError::InvalidInput { field, .. }) => field,
        other => panic!("{other:?}"),
    };
    assert_eq!(field_of(MedialOptions { step_mm: Some(0.0), ..MedialOptions::default() }), "step_mm");
    assert_eq!(field_of(MedialOptions { step_mm: Some(1e-5), ..MedialOptions::default() }), "step_mm");
    assert_eq!(field_of(MedialOptions { step_mm: Some(f64::NAN), ..MedialOptions::default() }), "step_mm");
    assert_eq!(
        field_of(MedialOptions { max_arc_angle_rad: Some(-1.0), ..MedialOptions::default() }),
        "max_arc_angle_rad"
    );
    assert_eq!(
        field_of(MedialOptions { prune_threshold_mm: Some(0.0), ..MedialOptions::default() }),
        "prune_threshold_mm"
    );
    assert_eq!(
        field_of(MedialOptions { simplify_tolerance_mm: Some(-1.0), ..MedialOptions::default() }),
        "simplify_tolerance_mm"
    );
}

#[test]
fn without_simplification_every_voronoi_vertex_is_kept_and_the_axis_is_the_same() {
    let (pocket, analytic) = l_shape();
    let full =
        medial_axis(&pocket, &MedialOptions { simplify_tolerance_mm: Some(0.0), ..MedialOptions::default() }).unwrap();
    let simple = medial_axis(&pocket, &MedialOptions::default()).unwrap();
    assert!(full.points().count() > 2 * simple.points().count());
    assert_eq!(full.branches.len(), simple.branches.len());
    let (d, r) = worst_errors(&pocket, &full, &analytic);
    assert!(d <= TOL_MM && r <= TOL_MM);
}

#[test]
fn narrow_gaps_sharp_wedges_and_several_islands_give_consistent_axes_with_one_cycle_per_island() {
    use crate::core::geometry::{Loop, Pocket, Vertex};
    let polygon = |xy: &[(f64, f64)]| Loop::new(xy.iter().map(|&(x, y)| Vertex::new(x, y, 0.0)).collect());
    // A 0.1 mm gap between the rectangle and a round island, far below the 0.36 mm step.
    let gap = Pocket::new(Loop::rectangle(0.0, 0.0, 60.0, 40.0), vec![Loop::circle(30.0, 20.0, 19.9)]).unwrap();
    // Two chambers joined by a 1 mm channel along the bottom.
    let channel = Pocket::new(
        polygon(&[
            (0.0, 0.0),
            (100.0, 0.0),
            (100.0, 40.0),
            (60.0, 40.0),
            (60.0, 1.0),
            (40.0, 1.0),
            (40.0, 40.0),
            (0.0, 40.0),
        ]),
        vec![],
    )
    .unwrap();
    // A wedge of about 3°.
    let wedge = Pocket::new(polygon(&[(0.0, 0.0), (100.0, 0.0), (0.0, 5.0)]), vec![]).unwrap();
    let islands = Pocket::new(
        Loop::rectangle(0.0, 0.0, 100.0, 60.0),
        vec![
            Loop::rectangle(10.0, 10.0, 30.0, 50.0),
            Loop::circle(60.0, 30.0, 10.0),
            Loop::rectangle(80.0, 5.0, 95.0, 55.0),
        ],
    )
    .unwrap();
    for pocket in [&gap, &channel, &wedge, &islands] {
        let axis = medial_axis(pocket, &MedialOptions::default()).unwrap();
        assert_consistent(&axis);
        assert_points_are_centres_of_inscribed_circles(pocket, &axis, TOL_MM);
        assert_eq!(axis.branches.len() + 1 - axis.nodes.len(), pocket.islands.len());
    }
    // The axis passes through the gaps' middles.
    let min_r = |pocket: &Pocket| {
        let axis = medial_axis(pocket, &MedialOptions::default()).unwrap();
        axis.points().map(|p| p.clearance_mm).fold(f64::INFINITY, f64::min)
    };
    assert!((min_r(&gap) - 0.05).abs() < TOL_MM);
    let every_point = MedialOptions { simplify_tolerance_mm: Some(0.0), ..MedialOptions::default() };
    let axis = medial_axis(&channel, &every_point).unwrap();
    let in_channel: Vec<&AxisPoint> = axis.points().filter(|p| p.point.x > 41.0 && p.point.x < 59.0).collect();
    assert!(!in_channel.is_empty());
    assert!(in_channel.iter().all(|p| (p.point.y - 0.5).abs() < TOL_MM && (p.clearance_mm - 0.5).abs() < TOL_MM));
}
