//! Arc centres: from I/J/K offsets or from an R radius, in any of the three planes, and the
//! checks every arc must pass (non-zero radius, same radius at both ends).
//!
//! In a plane the two in-plane axes are called *a* and *b* and the normal *n*, ordered so
//! that a × b = n: XY (a = X, b = Y, n = Z), ZX (a = Z, b = X, n = Y), YZ (a = Y, b = Z,
//! n = X). Clockwise is seen looking down the positive normal, as G2 is.

use super::options::ArcTolerance;
use super::MM_PER_INCH;
use crate::core::tolerance::LENGTH_EPS_MM;
use crate::core::toolpath::{Plane, Units, P3};

/// Smallest tolerance on the difference between an arc's radius to its start and to its
/// end, mm (LinuxCNC's default is of the same order).
pub const ARC_RADIUS_TOLERANCE_MM: f64 = 0.002;

/// Tolerance on that difference relative to the radius (0.1 %), for large arcs.
pub const ARC_RADIUS_TOLERANCE_RATIO: f64 = 0.001;

/// The tolerance on the start/end radius difference of an arc of radius `radius_mm`:
/// max([`ARC_RADIUS_TOLERANCE_MM`], [`ARC_RADIUS_TOLERANCE_RATIO`] × radius).
pub fn arc_radius_tolerance_mm(radius_mm: f64) -> f64 {
    ARC_RADIUS_TOLERANCE_MM.max(ARC_RADIUS_TOLERANCE_RATIO * radius_mm.abs())
}

/// Axis indices (a, b, n) of a plane, 0 = X, 1 = Y, 2 = Z.
pub(crate) fn plane_axes(plane: Plane) -> [usize; 3] {
    match plane {
        Plane::Xy => [0, 1, 2],
        Plane::Zx => [2, 0, 1],
        Plane::Yz => [1, 2, 0],
    }
}

/// Coordinate `axis` (0 = X, 1 = Y, 2 = Z) of `p`.
pub(crate) fn coord(p: P3, axis: usize) -> f64 {
    match axis {
        0 => p.x,
        1 => p.y,
        _ => p.z,
    }
}

/// `p` with coordinate `axis` set to `value`.
pub(crate) fn with_coord(mut p: P3, axis: usize, value: f64) -> P3 {
    match axis {
        0 => p.x = value,
        1 => p.y = value,
        _ => p.z = value,
    }
    p
}

/// The centre of an arc from its offsets along the plane's a and b axes: relative to the
/// start (`absolute` false, G91.1) or absolute coordinates (G90.1). The centre's normal
/// coordinate is the start's.
pub(crate) fn centre_from_offsets(start: P3, plane: Plane, a_mm: f64, b_mm: f64, absolute: bool) -> P3 {
    let [a, b, _] = plane_axes(plane);
    let (base_a, base_b) = if absolute { (0.0, 0.0) } else { (coord(start, a), coord(start, b)) };
    with_coord(with_coord(start, a, base_a + a_mm), b, base_b + b_mm)
}

/// mm per unit of `units`.
fn mm_per(units: Units) -> f64 {
    match units {
        Units::Mm => 1.0,
        Units::Inch => MM_PER_INCH,
    }
}

/// The centre of an arc from `start` to `end` of radius |`radius_mm`|: positive for the
/// short way (≤ 180°), negative for the long way, on the side that `clockwise` implies.
///
/// Errors (as a reason to report): zero radius, end = start in the plane (a full circle
/// needs I/J/K), radius smaller than half the chord beyond the tolerance (in `units`).
pub(crate) fn centre_from_radius(
    start: P3,
    end: P3,
    plane: Plane,
    clockwise: bool,
    radius_mm: f64,
    units: Units,
    tolerance: &ArcTolerance,
) -> Result<P3, String> {
    let [a, b, _] = plane_axes(plane);
    let r = radius_mm.abs();
    if r <= LENGTH_EPS_MM {
        return Err("the arc radius is zero".to_string());
    }
    let (sa, sb) = (coord(start, a), coord(start, b));
    let (da, db) = (coord(end, a) - sa, coord(end, b) - sb);
    let chord = da.hypot(db);
    if chord <= LENGTH_EPS_MM {
        return Err("an R arc cannot end where it starts: program a full circle with I/J/K".to_string());
    }
    let half = chord / 2.0;
    let unit = mm_per(units);
    if half - r > 0.0 && !tolerance.accepts(units, (half - r) / unit, r / unit) {
        return Err(format!(
            "the radius R {r:.4} mm is smaller than half the distance to the end point \
             ({half:.4} mm)"
        ));
    }
    let height = (r * r - half * half).max(0.0).sqrt();
    let (ua, ub) = (da / chord, db / chord);
    // G2 with R > 0 (and G3 with R < 0) has its centre on the right of the chord.
    let right = clockwise == (radius_mm > 0.0);
    let (na, nb) = if right { (ub, -ua) } else { (-ub, ua) };
    let ca = sa + da / 2.0 + height * na;
    let cb = sb + db / 2.0 + height * nb;
    Ok(with_coord(with_coord(start, a, ca), b, cb))
}

/// Checks a centre-format arc against the tolerance (in `units`). The arc keeps its
/// programmed centre and end, as a control runs it: a slight spiral from the start radius
/// to the end radius (the difference is at most the accepted miss).
pub(crate) fn check_centre(
    start: P3,
    centre: P3,
    end: P3,
    plane: Plane,
    units: Units,
    tolerance: &ArcTolerance,
) -> Result<(), String> {
    let [a, b, _] = plane_axes(plane);
    let radius = |p: P3| (coord(p, a) - coord(centre, a)).hypot(coord(p, b) - coord(centre, b));
    let (r_start, r_end) = (radius(start), radius(end));
    if r_start <= LENGTH_EPS_MM || r_end <= LENGTH_EPS_MM {
        return Err("the arc radius is zero: the centre is at the start or end point".to_string());
    }
    let unit = mm_per(units);
    let miss = (r_start - r_end).abs();
    if !tolerance.accepts(units, miss / unit, r_start.max(r_end) / unit) {
        let (absolute, maximum) = tolerance.in_units(units);
        let name = match units {
            Units::Mm => "mm",
            Units::Inch => "in",
        };
        return Err(format!(
            "the arc's radius to the start ({r_start:.4} mm) and to the end ({r_end:.4} mm) \
             differ by {miss:.4} mm: more than {absolute} {name}, or {} % of the radius up to {maximum} {name}",
            tolerance.relative * 100.0
        ));
    }
    Ok(())
}

/// Checks an arc about `centre`: non-zero radius, and the radius to the end equals the
/// radius to the start within [`arc_radius_tolerance_mm`]. Returns the start radius, mm.
pub(crate) fn check_arc(start: P3, centre: P3, end: P3, plane: Plane) -> Result<f64, String> {
    let [a, b, _] = plane_axes(plane);
    let radius = |p: P3| (coord(p, a) - coord(centre, a)).hypot(coord(p, b) - coord(centre, b));
    let (r_start, r_end) = (radius(start), radius(end));
    if r_start <= LENGTH_EPS_MM {
        return Err("the arc radius is zero: the centre is at the start point".to_string());
    }
    let tolerance = arc_radius_tolerance_mm(r_start);
    if (r_start - r_end).abs() > tolerance {
        return Err(format!(
            "the arc's radius to the start ({r_start:.4} mm) and to the end ({r_end:.4} mm) \
             differ by more than {tolerance:.4} mm"
        ));
    }
    Ok(r_start)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::core::tolerance::approx_eq;

    /// Centres computed here are exact to rounding.
    const CENTRE_TOL_MM: f64 = 1e-9;

    fn close(p: P3, q: P3) -> bool {
        approx_eq(p.x, q.x, CENTRE_TOL_MM) && approx_eq(p.y, q.y, CENTRE_TOL_MM) && approx_eq(p.z, q.z, CENTRE_TOL_MM)
    }

    #[test]
    fn a_positive_radius_takes_the_short_way_and_a_negative_one_the_long_way() {
        // Quarter circle from (10, 0) to (0, 10) about the origin, counter-clockwise.
        let (s, e) = (P3::new(10.0, 0.0, 0.0), P3::new(0.0, 10.0, 0.0));
        let short = centre_from_radius(s, e, Plane::Xy, false, 10.0, Units::Mm, &ArcTolerance::default()).unwrap();
        assert!(close(short, P3::new(0.0, 0.0, 0.0)), "{short:?}");
        let long = centre_from_radius(s, e, Plane::Xy, false, -10.0, Units::Mm, &ArcTolerance::default()).unwrap();
        assert!(close(long, P3::new(10.0, 10.0, 0.0)), "{long:?}");
        let clockwise = centre_from_radius(s, e, Plane::Xy, true, 10.0, Units::Mm, &ArcTolerance::default()).unwrap();
        assert!(close(clockwise, P3::new(10.0, 10.0, 0.0)), "{clockwise:?}");
    }

    #[test]
    fn the_radius_form_works_in_the_zx_and_yz_planes_and_keeps_the_start_normal() {
        // ZX: a = Z, b = X. Counter-clockwise from z=10 to x=10 about the origin.
        let s = P3::new(0.0, 7.0, 10.0);
        let e = P3::new(10.0, 9.0, 0.0);
        let c = centre_from_radius(s, e, Plane::Zx, false, 10.0, Units::Mm, &ArcTolerance::default()).unwrap();
        assert!(close(c, P3::new(0.0, 7.0, 0.0)), "{c:?}");
        // YZ: a = Y, b = Z.
        let s = P3::new(3.0, 10.0, 0.0);
        let e = P3::new(4.0, 0.0, 10.0);
        let c = centre_from_radius(s, e, Plane::Yz, false, 10.0, Units::Mm, &ArcTolerance::default()).unwrap();
        assert!(close(c, P3::new(3.0, 0.0, 0.0)), "{c:?}");
    }

    #[test]
    fn a_semicircle_within_tolerance_is_accepted_and_a_short_radius_is_not() {
        let (s, e) = (P3::new(-5.0, 0.0, 0.0), P3::new(5.0, 0.0, 0.0));
        let c = centre_from_radius(s, e, Plane::Xy, true, 4.999, Units::Mm, &ArcTolerance::default()).unwrap();
        assert!(close(c, P3::default()), "{c:?}");
        let err = centre_from_radius(s, e, Plane::Xy, true, 4.9, Units::Mm, &ArcTolerance::default()).unwrap_err();
        assert!(err.contains("smaller than half"), "{err}");
    }

    #[test]
    fn zero_radius_and_a_closed_r_arc_are_refused() {
        let s = P3::new(1.0, 1.0, 0.0);
        assert!(
            centre_from_radius(s, P3::default(), Plane::Xy, true, 0.0, Units::Mm, &ArcTolerance::default()).is_err()
        );
        let err = centre_from_radius(s, s, Plane::Xy, true, 3.0, Units::Mm, &ArcTolerance::default()).unwrap_err();
        assert!(err.contains("full circle"), "{err}");
        assert!(check_arc(s, s, P3::default(), Plane::Xy).is_err());
    }

    #[test]
    fn offsets_are_relative_to_the_start_unless_absolute() {
        let s = P3::new(1.0, 2.0, 3.0);
        let relative = centre_from_offsets(s, Plane::Zx, 4.0, 5.0, false);
        assert!(close(relative, P3::new(6.0, 2.0, 7.0)));
        let absolute = centre_from_offsets(s, Plane::Yz, 4.0, 5.0, true);
        assert!(close(absolute, P3::new(1.0, 4.0, 5.0)));
    }

    #[test]
    fn a_radius_mismatch_names_both_radii_and_small_differences_pass() {
        let c = P3::default();
        let s = P3::new(10.0, 0.0, 0.0);
        assert!(check_arc(s, c, P3::new(0.0, 10.005, 0.0), Plane::Xy).is_ok());
        let err = check_arc(s, c, P3::new(0.0, 10.5, 0.0), Plane::Xy).unwrap_err();
        assert!(err.contains("10.0000 mm") && err.contains("10.5000 mm"), "{err}");
        assert!(approx_eq(arc_radius_tolerance_mm(1.0), 0.002, CENTRE_TOL_MM));
        assert!(approx_eq(arc_radius_tolerance_mm(100.0), 0.1, CENTRE_TOL_MM));
    }

    mod in_gcode {
        //! Arcs as G-code writes them.

        use super::*;
        use crate::core::nc::{parse_gcode, ParseOptions};
        use crate::core::toolpath::{Motion, Move};
        use proptest::prelude::*;

        /// Arcs from a program written with 9 decimals: the centre to well within this.
        const PROPTEST_CENTRE_TOL_MM: f64 = 1e-6;

        fn arc(text: &str) -> (Move, P3, bool, Plane, u32) {
            let path = parse_gcode(text, &ParseOptions::default()).unwrap_or_else(|e| panic!("{e}"));
            let m = *path.moves.last().unwrap();
            match m.motion {
                Motion::Arc { center, clockwise, plane, turns } => (m, center, clockwise, plane, turns),
                other => panic!("not an arc: {other:?}"),
            }
        }

        fn error(text: &str) -> String {
            let e = parse_gcode(text, &ParseOptions::default()).unwrap_err();
            e.to_string()
        }

        #[test]
        fn an_r_word_arc_has_the_same_centre_as_its_ijk_form() {
            let (_, ijk, cw, ..) = arc("G0 X10 Y0\nG2 X0 Y-10 I-10 J0 F100");
            let (_, r, ..) = arc("G0 X10 Y0\nG2 X0 Y-10 R10 F100");
            assert!(cw);
            assert!(close(ijk, P3::default()) && close(r, ijk), "{ijk:?} {r:?}");
        }

        #[test]
        fn a_negative_r_takes_the_long_way_round() {
            let (_, c, ..) = arc("G0 X10 Y0\nG3 X0 Y10 R-10 F100");
            assert!(close(c, P3::new(10.0, 10.0, 0.0)), "{c:?}");
        }

        #[test]
        fn a_full_circle_ends_where_it_starts_and_a_p_word_adds_turns() {
            let (m, c, _, _, turns) = arc("G0 X10 Y0\nG3 X10 Y0 I-10 F100");
            assert_eq!(m.start, m.end);
            assert!(close(c, P3::default()));
            assert_eq!(turns, 0);
            let (m, c, _, _, turns) = arc("G0 X10 Y0\nG2 I-10 P3 F100");
            assert_eq!(m.start, m.end);
            assert!(close(c, P3::default()));
            assert_eq!(turns, 2);
            assert!(error("G0 X10\nG2 I-10 P0 F100").contains("positive integer"));
            assert!(error("G0 X10\nG2 X10 R5 F100").contains("full circle"));
        }

        #[test]
        fn a_helix_changes_the_normal_axis_and_keeps_the_centre_at_the_start_height() {
            let (m, c, ..) = arc("G0 X10 Y0 Z5\nG3 X-10 Y0 Z2 I-10 J0 F100");
            assert!(close(m.end, P3::new(-10.0, 0.0, 2.0)));
            assert!(close(c, P3::new(0.0, 0.0, 5.0)), "{c:?}");
        }

        #[test]
        fn g18_uses_i_and_k_and_g19_uses_j_and_k() {
            let (_, c, _, plane, _) = arc("G0 X0 Y3 Z10\nG18 G3 X10 Z0 I0 K-10 F100");
            assert_eq!(plane, Plane::Zx);
            assert!(close(c, P3::new(0.0, 3.0, 0.0)), "{c:?}");
            let (_, r, ..) = arc("G0 X0 Y3 Z10\nG18 G3 X10 Z0 R10 F100");
            assert!(close(r, c), "{r:?}");
            let (_, c, _, plane, _) = arc("G0 X4 Y10 Z0\nG19 G3 Y0 Z10 J-10 F100");
            assert_eq!(plane, Plane::Yz);
            assert!(close(c, P3::new(4.0, 0.0, 0.0)), "{c:?}");
            assert!(error("G0 X10\nG2 X-10 I-10 K1 F100").contains("K is not an arc centre word"));
        }

        #[test]
        fn g90_1_reads_centres_as_absolute_coordinates() {
            let (_, c, ..) = arc("G0 X15 Y5\nG90.1 G2 X5 Y-5 I5 J5 F100");
            assert!(close(c, P3::new(5.0, 5.0, 0.0)), "{c:?}");
            assert!(error("G90.1 G0 X15 Y5\nG2 X5 Y-5 I5 F100").contains("both I and J"));
        }

        #[test]
        fn a_radius_mismatch_is_an_error_naming_the_line_and_both_radii() {
            let e = error("G0 X10 Y0\nG2 X0 Y-10.5 I-10 J0 F100");
            assert!(e.starts_with("line 2, column 1 (G2): "), "{e}");
            assert!(e.contains("10.0000 mm") && e.contains("10.5000 mm"), "{e}");
            assert!(error("G2 X1 I0 J0 F100").contains("radius is zero"));
            assert!(error("G2 X1 Y1 F100").contains("I/J/K"));
            assert!(error("G2 X1 Y1 R1 I1 F100").contains("not both"));
            assert!(error("G0 X-5\nG2 X5 R4 F100").contains("smaller than half"));
        }

        /// One random arc: centre, radius, start angle, signed sweep (rad).
        fn arc_case() -> impl Strategy<Value = (f64, f64, f64, f64, f64, bool)> {
            (
                -100.0..100.0f64,
                -100.0..100.0f64,
                0.1..100.0f64,
                0.0..std::f64::consts::TAU,
                1.0f64..179.0,
                any::<bool>(),
            )
                .prop_map(|(cx, cy, r, a0, sweep_deg, cw)| (cx, cy, r, a0, sweep_deg.to_radians(), cw))
        }

        proptest! {
            #[test]
            fn random_arcs_written_with_ijk_and_with_r_give_the_true_centre(case in arc_case()) {
                let (cx, cy, r, a0, sweep, cw) = case;
                let a1 = if cw { a0 - sweep } else { a0 + sweep };
                let (sx, sy) = (cx + r * a0.cos(), cy + r * a0.sin());
                let (ex, ey) = (cx + r * a1.cos(), cy + r * a1.sin());
                let g = if cw { 2 } else { 3 };
                let start = format!("G0 X{sx:.9} Y{sy:.9}\n");
                let ijk = format!("{start}G{g} X{ex:.9} Y{ey:.9} I{:.9} J{:.9} F100", cx - sx, cy - sy);
                let with_r = format!("{start}G{g} X{ex:.9} Y{ey:.9} R{r:.9} F100");
                for text in [ijk, with_r] {
                    let (_, c, clockwise, ..) = arc(&text);
                    prop_assert_eq!(clockwise, cw);
                    prop_assert!(
                        (c.x - cx).hypot(c.y - cy) <= PROPTEST_CENTRE_TOL_MM,
                        "{} gave {:?}, true centre ({}, {})", text, c, cx, cy
                    );
                }
            }
        }
    }
}
