//! Cutter radius compensation as G-code programs it: lead-ins of both controls, convex
//! and concave corners, arcs, gouges, and a property test that the tool never cuts into
//! the contour it runs beside.

use super::*;
use crate::core::analysis::sampling::point_on;
use crate::core::tolerance::approx_eq;
use crate::core::toolpath::{Motion, Toolpath, P3};
use proptest::prelude::*;

/// A 5 mm tool radius as D1.
fn options(control: Control) -> ParseOptions {
    ParseOptions {
        control,
        tool_table: vec![ToolEntry { number: 1, radius_mm: Some(5.0), length_mm: None }],
        ..ParseOptions::default()
    }
}

fn run(text: &str, control: Control) -> Toolpath {
    parse_gcode(text, &options(control)).unwrap_or_else(|e| panic!("{e}\n{text}"))
}

fn error(text: &str) -> String {
    parse_gcode(text, &options(Control::LinuxCnc)).unwrap_err().to_string()
}

/// Distance from `p` to the segment `a`–`b` in XY.
fn to_segment(p: P3, a: (f64, f64), b: (f64, f64)) -> f64 {
    let (dx, dy) = (b.0 - a.0, b.1 - a.1);
    let t = (((p.x - a.0) * dx + (p.y - a.1) * dy) / (dx * dx + dy * dy)).clamp(0.0, 1.0);
    (p.x - a.0 - t * dx).hypot(p.y - a.1 - t * dy)
}

/// Tool-centre points along the compensated moves of `lines`.
fn samples(path: &Toolpath, lines: std::ops::RangeInclusive<u32>) -> Vec<P3> {
    path.moves
        .iter()
        .filter(|m| lines.contains(&m.line) && m.motion != Motion::Rapid)
        .flat_map(|m| (0..=20).map(move |k| point_on(m, f64::from(k) / 20.0).0))
        .collect()
}

#[test]
fn the_linuxcnc_lead_in_ends_tangent_to_the_tool_circle_about_the_programmed_point() {
    let text = "G0 X-20 Y-10 Z0\nG41 G1 X0 Y0 D1 F100\nG1 X50\nG40 G1 X60 Y-10\n";
    let path = run(text, Control::LinuxCnc);
    let lead_in = path.moves.iter().find(|m| m.line == 2).unwrap();
    let e = lead_in.end;
    assert!(approx_eq(e.x.hypot(e.y), 5.0, 1e-9), "{e:?}");
    // The lead-in is tangent there: square to the radius from the programmed point.
    let (dx, dy) = (e.x - lead_in.start.x, e.y - lead_in.start.y);
    assert!(approx_eq(dx * e.x + dy * e.y, 0.0, 1e-9));
    // It goes round the programmed corner on an arc, then along X on the left of the
    // contour, 5 mm above it.
    let corner = path.moves.iter().find(|m| m.line == 3).unwrap();
    assert!(matches!(corner.motion, Motion::Arc { center, .. } if center.x.hypot(center.y) < 1e-12));
    let along = path.moves.iter().filter(|m| m.line == 3 && m.motion == Motion::Linear).collect::<Vec<_>>();
    assert_eq!(along.len(), 1);
    assert!(approx_eq(along[0].start.y, 5.0, 1e-9) && approx_eq(along[0].end.y, 5.0, 1e-9), "{along:?}");
    let last = path.moves.last().unwrap();
    assert!(approx_eq(last.end.x, 60.0, 1e-9) && approx_eq(last.end.y, -10.0, 1e-9));
}

#[test]
fn the_fanuc_lead_in_ends_square_to_the_next_move_at_its_start() {
    let text = "%\nO0001\nG0 X-20 Y-10 Z0\nG41 G1 X0 Y0 D1 F100\nG1 X50\nG40 G1 X60 Y-10\nM30\n%\n";
    let path = run(text, Control::Auto);
    let lead_in = path.moves.iter().find(|m| m.line == 4).unwrap();
    assert!(approx_eq(lead_in.end.x, 0.0, 1e-9) && approx_eq(lead_in.end.y, 5.0, 1e-9), "{lead_in:?}");
}

#[test]
fn an_outside_contour_goes_round_its_convex_corners_on_arcs_of_the_tool_radius() {
    // Clockwise round a 20 mm square with G41: the tool outside, climb milling.
    let text = "G0 X-10 Y-10 Z-2\nG41 G1 X0 Y0 D1 F300\nY20\nX20\nY0\nX0\nG40 G1 X-10 Y-10\n";
    let path = run(text, Control::LinuxCnc);
    let arcs = path.moves.iter().filter(|m| matches!(m.motion, Motion::Arc { .. })).count();
    assert_eq!(arcs, 3, "{:?}", path.moves);
    let square = [(0.0, 0.0), (0.0, 20.0), (20.0, 20.0), (20.0, 0.0), (0.0, 0.0)];
    for p in samples(&path, 3..=6) {
        let d = square.windows(2).map(|w| to_segment(p, w[0], w[1])).fold(f64::INFINITY, f64::min);
        assert!(approx_eq(d, 5.0, 1e-9), "{p:?} is {d} mm from the square");
    }
}

#[test]
fn a_pocket_contour_cuts_its_concave_corners_back_to_where_the_offsets_meet() {
    // Counter-clockwise inside a 30 mm square with G41: the tool inside.
    let text = "G0 X15 Y10 Z-2\nG41 G1 X15 Y0 D1 F300\nX30\nY30\nX0\nY0\nX15\nG40 G1 X15 Y10\n";
    let path = run(text, Control::LinuxCnc);
    assert!(!path.moves.iter().any(|m| matches!(m.motion, Motion::Arc { .. })));
    let corners: Vec<(f64, f64)> =
        path.moves.iter().filter(|m| (3..=6).contains(&m.line)).map(|m| (m.end.x, m.end.y)).collect();
    let expected = [(25.0, 5.0), (25.0, 25.0), (5.0, 25.0), (5.0, 5.0)];
    for (c, e) in corners.iter().zip(expected) {
        assert!(approx_eq(c.0, e.0, 1e-9) && approx_eq(c.1, e.1, 1e-9), "{corners:?}");
    }
}

#[test]
fn arcs_are_offset_concentrically_and_a_concave_arc_smaller_than_the_tool_is_refused() {
    // A 20 mm radius boss, counter-clockwise with G42: the tool outside at 25 mm.
    let text = "G0 X40 Y-10 Z-2\nG42 G1 X20 Y0 D1 F300\nG3 X20 Y0 I-20 J0\nG40 G1 X40 Y-10\n";
    let path = run(text, Control::LinuxCnc);
    let arc = path.moves.iter().find(|m| m.line == 3 && matches!(m.motion, Motion::Arc { .. })).unwrap();
    assert!(approx_eq(arc.end.x.hypot(arc.end.y), 25.0, 1e-9), "{arc:?}");
    let small = "G0 X0 Y-10 Z-2\nG41 G1 X3 Y0 D1 F300\nG3 X3 Y0 I-3 J0\nG40 G1 X0 Y-10\n";
    assert!(error(small).contains("not larger than the tool radius"), "{}", error(small));
}

#[test]
fn a_move_too_short_for_the_tool_at_a_concave_corner_gouges_and_is_refused() {
    // A 6 mm wide slot with a 10 mm tool.
    let text = "G0 X3 Y10 Z-2\nG41 G1 X3 Y0 D1 F300\nX6\nY30\nX0\nY0\nX3\nG40 G1 X3 Y10\n";
    let e = error(text);
    assert!(e.contains("gouge") || e.contains("does not fit"), "{e}");
}

#[test]
fn lead_ins_shorter_than_the_tool_radius_and_arc_lead_ins_are_refused() {
    assert!(error("G0 X-2 Y0\nG41 G1 X0 Y0 D1 F100\nG1 X20\n").contains("lead-in move is not longer"));
    assert!(error("G0 X-20 Y0\nG41 G2 X0 Y20 I10 J10 D1 F100\n").contains("must be a straight line"));
}

#[test]
fn without_a_tool_table_entry_g41_compensates_by_the_tools_radius_with_a_warning() {
    let options = ParseOptions { tool_radius_mm: Some(3.0), ..ParseOptions::default() };
    let path = parse_gcode("G0 X-20 Y-10\nG41 D7 G1 X0 Y0 F100\nG1 X50\nG40 G0 X60 Y-10\n", &options).unwrap();
    assert!(path.warnings.iter().any(|w| w.contains("3.0000 mm") && w.contains("D7 is not in the tool table")));
    let along: Vec<f64> = path.moves.iter().filter(|m| m.line == 3).map(|m| m.end.y).collect();
    assert!(approx_eq(along[0], 3.0, 1e-9), "{along:?}");
}

#[test]
fn z_moves_under_compensation_keep_the_tool_where_it_is() {
    let text = "G0 X-20 Y-10 Z5\nG41 G1 X0 Y0 D1 F100\nG1 Z-2\nG1 X50\nG40 G1 X60 Y-10\n";
    let path = run(text, Control::LinuxCnc);
    let plunge = path.moves.iter().find(|m| m.line == 3).unwrap();
    assert!(approx_eq(plunge.start.x, plunge.end.x, 1e-12) && approx_eq(plunge.start.y, plunge.end.y, 1e-12));
    assert!(approx_eq(plunge.end.z, -2.0, 1e-12));
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// Round a random convex polygon outside (clockwise, G41), the tool centre never comes
    /// nearer the contour than the tool radius, and touches it at that distance.
    #[test]
    fn round_a_convex_contour_the_tool_never_cuts_into_it(
        radius in 1.0f64..8.0,
        angles in proptest::collection::btree_set(0u32..360, 3..9),
        size in 15.0f64..60.0,
    ) {
        let corners: Vec<(f64, f64)> = angles
            .iter()
            .rev()
            .map(|&a| (size * f64::from(a).to_radians().cos(), size * f64::from(a).to_radians().sin()))
            .collect();
        // Skip polygons with a nearly straight corner or a very short side.
        let n = corners.len();
        for k in 0..n {
            let (a, b) = (corners[k], corners[(k + 1) % n]);
            prop_assume!((b.0 - a.0).hypot(b.1 - a.1) > 1.0);
        }
        // In square to the middle of the first side, round, and out the same way.
        let (a, b) = (corners[0], corners[1]);
        let mid = ((a.0 + b.0) / 2.0, (a.1 + b.1) / 2.0);
        let side = (b.0 - a.0).hypot(b.1 - a.1);
        prop_assume!(side > 4.0 * radius);
        let outward = (-(b.1 - a.1) / side, (b.0 - a.0) / side);
        let away = (mid.0 + 3.0 * radius * outward.0, mid.1 + 3.0 * radius * outward.1);
        let mut text = format!("G0 X{:.6} Y{:.6} Z-1\n", away.0, away.1);
        text += &format!("G41 G1 X{:.6} Y{:.6} D1 F300\n", mid.0, mid.1);
        for c in corners.iter().skip(1).chain([&corners[0], &mid]) {
            text += &format!("G1 X{:.6} Y{:.6}\n", c.0, c.1);
        }
        text += &format!("G40 G1 X{:.6} Y{:.6}\n", away.0, away.1);
        let options = ParseOptions {
            tool_table: vec![ToolEntry { number: 1, radius_mm: Some(radius), length_mm: None }],
            ..ParseOptions::default()
        };
        let path = parse_gcode(&text, &options).map_err(|e| TestCaseError::fail(format!("{e}\n{text}")))?;
        let contour: Vec<(f64, f64)> = corners.iter().copied().chain(std::iter::once(corners[0])).collect();
        let last_line = n as u32 + 3;
        let mut nearest = f64::INFINITY;
        for p in samples(&path, 3..=last_line) {
            let d = contour.windows(2).map(|w| to_segment(p, w[0], w[1])).fold(f64::INFINITY, f64::min);
            prop_assert!(d >= radius - 1e-6, "{p:?} is {d} mm from the contour (radius {radius})\n{text}");
            nearest = nearest.min(d);
        }
        prop_assert!(approx_eq(nearest, radius, 1e-6));
    }
}
