//! Tests of the DXF import.

use super::*;
use crate::core::geometry::pocket_from_loops;
use std::f64::consts::PI;

/// Tolerance of the exact results (mm, mm²).
const TOL: f64 = 1e-9;

/// Tolerance of results exact up to rounding.
const EXACT: f64 = 1e-12;

/// A minimal DXF file with the given entities (already formatted) in its ENTITIES section.
fn dxf(entities: &[String]) -> String {
    let mut text = String::from("  0\nSECTION\n  2\nHEADER\n  9\n$ACADVER\n  1\nAC1009\n  0\nENDSEC\n");
    text.push_str("  0\nSECTION\n  2\nENTITIES\n");
    for e in entities {
        text.push_str(e);
    }
    text.push_str("  0\nENDSEC\n  0\nEOF\n");
    text
}

/// A DXF file whose header sets `$INSUNITS` to `units`, with one closed 1 × 1 square.
fn unit_square_in(units: &str) -> String {
    let square = entity(
        "LWPOLYLINE",
        &[(70, "1"), (10, "0"), (20, "0"), (10, "1"), (20, "0"), (10, "1"), (20, "1"), (10, "0"), (20, "1")],
    );
    dxf(&[square]).replacen("$ACADVER\n  1\nAC1009\n", &format!("$INSUNITS\n 70\n{units}\n"), 1)
}

/// One entity: `0 / kind` followed by the groups.
fn entity(kind: &str, groups: &[(i32, &str)]) -> String {
    let mut text = format!("  0\n{kind}\n");
    for (code, value) in groups {
        text.push_str(&format!("{code:>3}\n{value}\n"));
    }
    text
}

/// The 1-based line holding the value `value` for the `nth` time.
fn line_of(text: &str, value: &str, nth: usize) -> usize {
    text.lines().enumerate().filter(|(_, l)| *l == value).nth(nth).map(|(i, _)| i + 1).unwrap()
}

fn reason(err: CoreError) -> String {
    match err {
        CoreError::InvalidInput { field, reason } => {
            assert_eq!(field, "dxf");
            reason
        }
        other => panic!("unexpected error {other:?}"),
    }
}

#[test]
fn border_dxf_loads_as_one_rounded_rectangle_of_four_lines_and_four_arcs() {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../shared/data/border.dxf");
    let text = std::fs::read_to_string(path).unwrap();
    let loops = loops_from_dxf(&text).unwrap();
    assert_eq!(loops.len(), 1);
    let lp = &loops[0];
    let segments: Vec<_> = lp.segments().collect();
    assert_eq!(segments.len(), 8);
    assert_eq!(segments.iter().filter(|s| s.is_arc()).count(), 4);
    assert_eq!(segments.iter().filter(|s| !s.is_arc()).count(), 4);
    // By hand from the entities: lines along x = 0, x = 102, y = 0, y = 137; four 90° arcs of
    // radius 10 centred at (10, 10), (92, 10), (92, 127), (10, 127). The arcs run
    // counter-clockwise (ARC), so the loop does too.
    let b = lp.bounds();
    println!("border.dxf bounds {b:?}, area {} mm²", lp.signed_area());
    assert!(b.x_min.abs() < TOL && (b.x_max - 102.0).abs() < TOL);
    assert!(b.y_min.abs() < TOL && (b.y_max - 137.0).abs() < TOL);
    // 102 × 137 minus the four corner squares 10 × 10 plus four quarter discs of radius 10.
    let area = 102.0 * 137.0 - 4.0 * 100.0 + PI * 100.0;
    assert!((lp.signed_area() - area).abs() < TOL, "{} vs {area}", lp.signed_area());
    for s in segments.iter().filter(|s| s.is_arc()) {
        let arc = s.arc().unwrap();
        assert!((arc.radius_mm - 10.0).abs() < TOL && (arc.sweep_rad - PI / 2.0).abs() < TOL);
    }
    let pocket = pocket_from_loops(loops).unwrap();
    assert!((pocket.area() - area).abs() < TOL);
}

#[test]
fn a_circle_inside_a_bulged_polyline_gives_a_pocket_with_one_island_and_text_is_ignored() {
    let text = dxf(&[
        entity("TEXT", &[(5, "1A"), (8, "0"), (10, "5"), (20, "5"), (40, "2.5"), (1, "part 7")]),
        entity(
            "LWPOLYLINE",
            &[
                (5, "2B"),
                (90, "4"),
                (70, "1"),
                (10, "0"),
                (20, "0"),
                (10, "100"),
                (20, "0"),
                (42, "0.4"),
                (10, "100"),
                (20, "60"),
                (10, "0"),
                (20, "60"),
            ],
        ),
        entity("CIRCLE", &[(5, "2C"), (10, "40"), (20, "30"), (40, "10")]),
    ]);
    let loops = loops_from_dxf(&text).unwrap();
    assert_eq!(loops.len(), 2);
    let pocket = pocket_from_loops(loops).unwrap();
    assert_eq!(pocket.islands.len(), 1);
    // Circular segment on the right edge: chord 60, bulge 0.4.
    let (c, b) = (60.0, 0.4_f64);
    let r = c * (1.0 + b * b) / (4.0 * b);
    let theta = 4.0 * b.atan();
    let bulge_area = 0.5 * r * r * (theta - theta.sin());
    let expected = 6000.0 + bulge_area - PI * 100.0;
    assert!((pocket.area() - expected).abs() < TOL, "{} vs {expected}", pocket.area());
    let sagitta = b * c / 2.0;
    assert!((pocket.bounds().x_max - (100.0 + sagitta)).abs() < TOL);
    assert!(!pocket.contains(40.0, 30.0));
    assert!(pocket.contains(105.0, 30.0));
}

#[test]
fn an_open_chain_is_refused_naming_the_dangling_entitys_line_and_handle() {
    let text = dxf(&[
        entity("LINE", &[(5, "10"), (10, "0"), (20, "0"), (11, "50"), (21, "0")]),
        entity("LINE", &[(5, "11"), (10, "50"), (20, "0"), (11, "50"), (21, "30")]),
    ]);
    let why = reason(loops_from_dxf(&text).unwrap_err());
    let second = line_of(&text, "LINE", 1);
    assert!(why.contains(&format!("LINE at line {second} (handle 11) cannot be chained")), "{why}");
    assert!(why.contains(&format!("starts with LINE at line {}", line_of(&text, "LINE", 0))), "{why}");
}

#[test]
fn lines_and_arcs_in_any_direction_chain_into_a_slot() {
    // A 40 × 20 slot: two lines and two half-circle ARCs, one line drawn backwards.
    let text = dxf(&[
        entity("LINE", &[(10, "10"), (20, "0"), (11, "50"), (21, "0")]),
        entity("LINE", &[(10, "10"), (20, "20"), (11, "50"), (21, "20")]),
        entity("ARC", &[(10, "50"), (20, "10"), (40, "10"), (50, "270"), (51, "90")]),
        entity("ARC", &[(10, "10"), (20, "10"), (40, "10"), (50, "90"), (51, "270")]),
    ]);
    let loops = loops_from_dxf(&text).unwrap();
    assert_eq!(loops.len(), 1);
    assert_eq!(loops[0].vertices.len(), 4);
    assert!((loops[0].signed_area().abs() - (800.0 + PI * 100.0)).abs() < TOL);
}

#[test]
fn an_old_style_polyline_with_vertices_and_a_bulge_is_one_loop() {
    let text = dxf(&[
        entity("POLYLINE", &[(5, "40"), (66, "1"), (70, "1")]),
        entity("VERTEX", &[(10, "0"), (20, "0")]),
        entity("VERTEX", &[(10, "20"), (20, "0"), (42, "1")]),
        entity("VERTEX", &[(10, "20"), (20, "20")]),
        entity("VERTEX", &[(10, "0"), (20, "20")]),
        entity("SEQEND", &[]),
    ]);
    let loops = loops_from_dxf(&text).unwrap();
    assert_eq!(loops.len(), 1);
    assert!((loops[0].signed_area() - (400.0 + PI * 50.0)).abs() < TOL);
    assert_eq!(loops[0].vertices.len(), 4);
}

#[test]
fn long_full_and_mirrored_arcs_keep_their_shape() {
    let three_quarters = arc_vertices(0.0, 0.0, 1.0, 0.0, 270.0);
    assert!(!three_quarters.1);
    assert_eq!(three_quarters.0.len(), 3);
    let (full, closed) = arc_vertices(0.0, 0.0, 2.0, 30.0, 30.0);
    assert!(closed);
    assert!((Loop::new(full).signed_area() - 4.0 * PI).abs() < TOL);
    // Extrusion −Z: the OCS centre (5, 0) is the world centre (−5, 0), and the arc runs
    // clockwise in the world; the loop is still a valid circle of radius 1.
    let text = dxf(&[entity("CIRCLE", &[(10, "5"), (20, "0"), (40, "1"), (210, "0"), (220, "0"), (230, "-1")])]);
    let loops = loops_from_dxf(&text).unwrap();
    let b = loops[0].bounds();
    assert!((b.x_min + 6.0).abs() < TOL && (b.x_max + 4.0).abs() < TOL);
    assert!((loops[0].signed_area() + PI).abs() < TOL);
}

#[test]
fn a_self_intersecting_polyline_and_bad_numbers_are_refused_with_their_line() {
    let bow = dxf(&[entity(
        "LWPOLYLINE",
        &[
            (5, "77"),
            (70, "1"),
            (10, "0"),
            (20, "0"),
            (10, "10"),
            (20, "10"),
            (10, "10"),
            (20, "0"),
            (10, "0"),
            (20, "10"),
        ],
    )]);
    let why = reason(loops_from_dxf(&bow).unwrap_err());
    let line = line_of(&bow, "LWPOLYLINE", 0);
    assert!(why.contains(&format!("LWPOLYLINE at line {line} (handle 77)")), "{why}");
    assert!(why.contains("intersects itself"), "{why}");
    let bad = dxf(&[entity("LINE", &[(10, "zero"), (20, "0"), (11, "5"), (21, "0")])]);
    let why = reason(loops_from_dxf(&bad).unwrap_err());
    assert!(why.contains(&format!("line {}: group 10", line_of(&bad, "zero", 0))), "{why}");
    assert!(reason(loops_from_dxf("  0\nEOF\n").unwrap_err()).contains("no ENTITIES"));
    assert!(reason(loops_from_dxf("oops\n").unwrap_err()).contains("line 1"));
}

#[test]
fn drawing_units_from_the_header_are_converted_to_mm() {
    let inch = loops_from_dxf(&unit_square_in("1")).unwrap();
    assert!((inch[0].signed_area() - 25.4 * 25.4).abs() < TOL);
    let mm = loops_from_dxf(&unit_square_in("4")).unwrap();
    assert!((mm[0].signed_area() - 1.0).abs() < EXACT);
    let why = reason(loops_from_dxf(&unit_square_in("13")).unwrap_err());
    assert!(why.contains("unsupported drawing units $INSUNITS = 13"), "{why}");
}

#[test]
fn exact_sines_and_cosines_at_right_angles() {
    // cos(270°) in floating point is about -1.8e-16; the helper gives exactly 0.
    let near = |(c, s): (f64, f64), (ec, es): (f64, f64)| {
        (c - ec).abs() < f64::MIN_POSITIVE && (s - es).abs() < f64::MIN_POSITIVE
    };
    assert!(near(cos_sin_deg(270.0), (0.0, -1.0)));
    assert!(near(cos_sin_deg(-90.0), (0.0, -1.0)));
    assert!(near(cos_sin_deg(360.0), (1.0, 0.0)));
    let (c, s) = cos_sin_deg(45.0);
    assert!((c - s).abs() < EXACT);
}
