//! Tests of [`super::Pocket`]: validation, orientation, containment and row intervals.

use super::*;
use crate::core::geometry::test_support::bounds_near;
use crate::core::geometry::Vertex;
use proptest::prelude::*;
use std::f64::consts::PI;

/// Tolerance of the exact results (mm, mm²).
const TOL: f64 = 1e-9;

/// Rows integrated for the area check.
const ROWS: usize = 400;

/// Largest relative error of the integrated area.
const AREA_REL_TOL: f64 = 0.005;

fn field_and_reason(err: CoreError) -> (String, String) {
    match err {
        CoreError::InvalidInput { field, reason } => (field, reason),
        other => panic!("unexpected error {other:?}"),
    }
}

/// 100 × 50 rectangle with a circular island of radius 10 at (50, 25).
fn plate_with_hole() -> Pocket {
    Pocket::new(Loop::rectangle(0.0, 0.0, 100.0, 50.0), vec![Loop::circle(50.0, 25.0, 10.0)]).unwrap()
}

fn assert_intervals(actual: &[(f64, f64)], expected: &[(f64, f64)]) {
    assert_eq!(actual.len(), expected.len(), "{actual:?} vs {expected:?}");
    for (a, e) in actual.iter().zip(expected) {
        assert!((a.0 - e.0).abs() < TOL && (a.1 - e.1).abs() < TOL, "{actual:?} vs {expected:?}");
    }
}

#[test]
fn a_clockwise_outer_is_accepted_and_turned_counter_clockwise_and_islands_clockwise() {
    let outer = Loop::rectangle(0.0, 0.0, 10.0, 10.0).reversed();
    assert!(!outer.is_ccw());
    let pocket = Pocket::new(outer, vec![Loop::circle(5.0, 5.0, 2.0)]).unwrap();
    assert!(pocket.outer.is_ccw());
    assert!(!pocket.islands[0].is_ccw());
    assert!((pocket.area() - (100.0 - PI * 4.0)).abs() < TOL);
    let expected = Bounds { x_min: 0.0, y_min: 0.0, x_max: 10.0, y_max: 10.0 };
    assert!(bounds_near(&pocket.bounds(), &expected, TOL));
    assert!(pocket.contains(1.0, 1.0));
    assert!(!pocket.contains(5.0, 5.0));
    assert!(!pocket.contains(11.0, 5.0));
}

#[test]
fn an_island_outside_the_outer_loop_is_refused() {
    let err = Pocket::new(
        Loop::rectangle(0.0, 0.0, 10.0, 10.0),
        vec![Loop::circle(5.0, 5.0, 1.0), Loop::circle(20.0, 5.0, 1.0)],
    )
    .unwrap_err();
    let (field, reason) = field_and_reason(err);
    assert_eq!(field, "islands[1]");
    assert!(reason.contains("outside"), "{reason}");
}

#[test]
fn an_island_crossing_or_touching_the_outer_loop_is_refused_with_the_point() {
    let outer = Loop::rectangle(0.0, 0.0, 10.0, 10.0);
    let err = Pocket::new(outer.clone(), vec![Loop::circle(10.0, 5.0, 2.0)]).unwrap_err();
    let (field, reason) = field_and_reason(err);
    assert_eq!(field, "islands[0]");
    assert!(reason.contains("touches or crosses"), "{reason}");
    let touching = Pocket::new(outer, vec![Loop::circle(8.0, 5.0, 2.0)]).unwrap_err();
    assert!(field_and_reason(touching).1.contains("(10, 5)"));
}

#[test]
fn two_overlapping_islands_are_refused_and_so_are_nested_ones() {
    let outer = Loop::rectangle(0.0, 0.0, 100.0, 100.0);
    let err =
        Pocket::new(outer.clone(), vec![Loop::circle(30.0, 50.0, 15.0), Loop::circle(50.0, 50.0, 15.0)]).unwrap_err();
    let (field, reason) = field_and_reason(err);
    assert_eq!(field, "islands[1]");
    assert!(reason.contains("islands must be apart"), "{reason}");
    let nested = Pocket::new(outer, vec![Loop::circle(50.0, 50.0, 5.0), Loop::circle(50.0, 50.0, 20.0)]).unwrap_err();
    let (field, reason) = field_and_reason(nested);
    assert_eq!(field, "islands[0]");
    assert!(reason.contains("lies inside islands[1]"), "{reason}");
}

#[test]
fn an_invalid_island_is_named_by_its_index_and_vertex() {
    let bow = Loop::new(vec![
        Vertex::new(1.0, 1.0, 0.0),
        Vertex::new(3.0, 3.0, 0.0),
        Vertex::new(3.0, 1.0, 0.0),
        Vertex::new(1.0, 3.0, 0.0),
    ]);
    let err = Pocket::new(Loop::rectangle(0.0, 0.0, 10.0, 10.0), vec![bow]).unwrap_err();
    assert_eq!(field_and_reason(err).0, "islands[0][0]");
}

#[test]
fn the_largest_loop_becomes_the_outer_one_whatever_the_order() {
    let pocket =
        pocket_from_loops(vec![Loop::circle(5.0, 5.0, 2.0), Loop::rectangle(0.0, 0.0, 10.0, 10.0).reversed()]).unwrap();
    assert_eq!(pocket.islands.len(), 1);
    assert!((pocket.area() - (100.0 - 4.0 * PI)).abs() < TOL);
    let apart =
        pocket_from_loops(vec![Loop::rectangle(0.0, 0.0, 10.0, 10.0), Loop::circle(50.0, 5.0, 2.0)]).unwrap_err();
    assert_eq!(field_and_reason(apart).0, "loops[1]");
    let nested = pocket_from_loops(vec![
        Loop::circle(50.0, 50.0, 5.0),
        Loop::rectangle(0.0, 0.0, 100.0, 100.0),
        Loop::circle(50.0, 50.0, 20.0),
    ])
    .unwrap_err();
    let (field, reason) = field_and_reason(nested);
    assert_eq!(field, "loops[0]");
    assert!(reason.contains("nesting deeper than one level"), "{reason}");
    assert!(pocket_from_loops(Vec::new()).is_err());
}

#[test]
fn rows_across_a_plate_with_a_hole_give_exactly_the_expected_intervals() {
    let pocket = plate_with_hole();
    let mut out = vec![(1.0, 2.0); 7]; // stale content is cleared
    pocket.row_intervals(25.0, &mut out);
    assert_intervals(&out, &[(0.0, 40.0), (60.0, 100.0)]);
    pocket.row_intervals(30.0, &mut out);
    let h = 75.0_f64.sqrt();
    assert_intervals(&out, &[(0.0, 50.0 - h), (50.0 + h, 100.0)]);
    pocket.row_intervals(18.0, &mut out);
    let h = 51.0_f64.sqrt();
    assert_intervals(&out, &[(0.0, 50.0 - h), (50.0 + h, 100.0)]);
    pocket.row_intervals(5.0, &mut out);
    assert_intervals(&out, &[(0.0, 100.0)]);
    pocket.row_intervals(-1.0, &mut out);
    assert!(out.is_empty());
}

#[test]
fn rows_along_horizontal_edges_and_tangent_to_the_hole_are_stable() {
    let pocket = plate_with_hole();
    let mut out = Vec::new();
    // Bottom edge: the region lies above it, so the row is inside; top edge: outside.
    pocket.row_intervals(0.0, &mut out);
    assert_intervals(&out, &[(0.0, 100.0)]);
    pocket.row_intervals(50.0, &mut out);
    assert!(out.is_empty());
    // Tangent to the hole's top and bottom: the hole takes no width.
    pocket.row_intervals(35.0, &mut out);
    assert_intervals(&out, &[(0.0, 100.0)]);
    pocket.row_intervals(15.0, &mut out);
    assert_intervals(&out, &[(0.0, 100.0)]);
    // Through the vertices where the hole's two half circles meet.
    pocket.row_intervals(25.0, &mut out);
    // Deterministic: repeated calls give bit-identical intervals.
    let bits = |v: &[(f64, f64)]| -> Vec<(u64, u64)> { v.iter().map(|(a, b)| (a.to_bits(), b.to_bits())).collect() };
    let first = bits(&out);
    for _ in 0..3 {
        pocket.row_intervals(25.0, &mut out);
        assert_eq!(bits(&out), first);
    }
}

#[test]
fn a_row_through_a_notch_vertex_and_along_its_floor_is_counted_once() {
    // A U shape: the notch's floor at y = 5 is a horizontal edge, its corners are vertices.
    let u = Loop::new(vec![
        Vertex::new(0.0, 0.0, 0.0),
        Vertex::new(30.0, 0.0, 0.0),
        Vertex::new(30.0, 10.0, 0.0),
        Vertex::new(20.0, 10.0, 0.0),
        Vertex::new(20.0, 5.0, 0.0),
        Vertex::new(10.0, 5.0, 0.0),
        Vertex::new(10.0, 10.0, 0.0),
        Vertex::new(0.0, 10.0, 0.0),
    ]);
    let pocket = Pocket::new(u, Vec::new()).unwrap();
    let mut out = Vec::new();
    pocket.row_intervals(5.0, &mut out);
    assert_intervals(&out, &[(0.0, 10.0), (20.0, 30.0)]);
    pocket.row_intervals(4.0, &mut out);
    assert_intervals(&out, &[(0.0, 30.0)]);
    pocket.row_intervals(10.0, &mut out);
    assert!(out.is_empty());
}

#[test]
fn a_pocket_deserialises_only_when_valid() {
    let ok: Pocket =
        serde_json::from_str(r#"{"outer":{"vertices":[{"x":0,"y":10},{"x":10,"y":10},{"x":10,"y":0},{"x":0,"y":0}]}}"#)
            .unwrap();
    assert!(ok.outer.is_ccw());
    let bad = serde_json::from_str::<Pocket>(
        r#"{"outer":{"vertices":[{"x":0,"y":0},{"x":10,"y":10},{"x":10,"y":0},{"x":0,"y":10}]}}"#,
    );
    assert!(bad.unwrap_err().to_string().contains("outer[0]"));
}

/// Midpoint-rule integral of the interval lengths over `rows` rows.
fn integrated_area(pocket: &Pocket, rows: usize) -> f64 {
    let b = pocket.bounds();
    let h = b.height_mm() / rows as f64;
    let mut out = Vec::new();
    let mut area = 0.0;
    for k in 0..rows {
        pocket.row_intervals(b.y_min + (k as f64 + 0.5) * h, &mut out);
        area += h * out.iter().map(|(a, b)| b - a).sum::<f64>();
    }
    area
}

fn shapes() -> impl Strategy<Value = Pocket> {
    let circle = (-100.0f64..100.0, -100.0f64..100.0, 0.5f64..50.0)
        .prop_map(|(x, y, r)| Pocket::new(Loop::circle(x, y, r), Vec::new()).unwrap());
    let rectangle = (-100.0f64..100.0, -100.0f64..100.0, 0.5f64..80.0, 0.5f64..80.0)
        .prop_map(|(x, y, w, h)| Pocket::new(Loop::rectangle(x, y, x + w, y + h), Vec::new()).unwrap());
    let holed =
        (-100.0f64..100.0, -100.0f64..100.0, 4.0f64..80.0, 4.0f64..80.0, 0.1f64..0.45).prop_map(|(x, y, w, h, f)| {
            let island = Loop::circle(x + w / 2.0, y + h / 2.0, f * w.min(h));
            Pocket::new(Loop::rectangle(x, y, x + w, y + h), vec![island]).unwrap()
        });
    let rounded = (0.5f64..20.0, 0.05f64..0.95).prop_map(|(w, b)| {
        let lp = Loop::new(vec![
            Vertex::new(0.0, 0.0, b),
            Vertex::new(w, 0.0, 0.0),
            Vertex::new(w, w, -b / 2.0),
            Vertex::new(0.0, w, 0.0),
        ]);
        Pocket::new(lp, Vec::new()).unwrap()
    });
    prop_oneof![circle, rectangle, holed, rounded]
}

proptest! {
    #[test]
    fn integrating_row_intervals_gives_the_area(pocket in shapes()) {
        let integral = integrated_area(&pocket, ROWS);
        let area = pocket.area();
        prop_assert!(((integral - area) / area).abs() < AREA_REL_TOL, "{integral} vs {area}");
    }

    #[test]
    fn contains_agrees_with_row_intervals(pocket in shapes(), fx in -0.1f64..1.1, fy in -0.1f64..1.1) {
        let b = pocket.bounds();
        let (x, y) = (b.x_min + fx * b.width_mm(), b.y_min + fy * b.height_mm());
        let mut out = Vec::new();
        pocket.row_intervals(y, &mut out);
        let in_rows = out.iter().any(|&(a, b)| a <= x && x < b);
        prop_assert_eq!(pocket.contains(x, y), in_rows);
        for w in out.windows(2) {
            prop_assert!(w[0].1 < w[1].0);
        }
    }
}
