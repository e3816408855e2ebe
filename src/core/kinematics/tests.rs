//! Worked cases with closed-form expectations (MODEL.md §10).

use super::*;
use crate::core::toolpath::{Event, EventKind, Motion, Move, Plane, Toolpath, Units, P3};
use std::f64::consts::PI;

/// The seeded OKK VM-4 row.
pub(super) fn vm4() -> MachineLimits {
    MachineLimits::SEEDED_OKK_VM4
}

const A: f64 = 2000.0;
const J: f64 = 50000.0;
const RELATIVE: f64 = 1e-6;

fn close(actual: f64, expected: f64) -> bool {
    (actual - expected).abs() <= RELATIVE * expected.abs()
}

fn feed(start: P3, end: P3, feed_mm_min: f64) -> Move {
    Move { motion: Motion::Linear, start, end, feed_mm_min: Some(feed_mm_min), spindle_rpm: None, tool: None, line: 1 }
}

fn rapid(start: P3, end: P3) -> Move {
    Move { motion: Motion::Rapid, feed_mm_min: None, ..feed(start, end, 1.0) }
}

fn path(moves: Vec<Move>) -> Toolpath {
    Toolpath { moves, events: vec![], source_units: Units::Mm, warnings: vec![] }
}

fn time(p: &Toolpath) -> MachiningTime {
    machining_time(p, &vm4(), &TimeOptions::default()).expect("valid")
}

/// Independent S-curve ramp time for a speed change `dv` (mm/s).
fn ramp(dv: f64, a: f64, j: f64) -> f64 {
    if dv >= a * a / j {
        dv / a + a / j
    } else {
        2.0 * (dv / j).sqrt()
    }
}

/// Time lost by a ramp between `v_lo` and a cruise at `v`, against covering its length at `v`.
fn ramp_loss(v_lo: f64, v: f64) -> f64 {
    let t = ramp(v - v_lo, A, J);
    t - 0.5 * (v_lo + v) * t / v
}

fn x(mm: f64) -> P3 {
    P3::new(mm, 0.0, 0.0)
}

#[test]
fn a_single_long_straight_move_takes_nominal_plus_the_s_curve_overhead() {
    let (length, v) = (100.0, 100.0);
    let t = time(&path(vec![feed(x(0.0), x(length), 6000.0)]));
    assert!(close(t.nominal_min * 60.0, length / v));
    // Speed-up and slow-down each take v/a + a/j (v ≥ a²/j) and cover half that at v.
    assert!(close(t.kinematic_min * 60.0, length / v + v / A + A / J), "{t:?}");
}

#[test]
fn without_a_jerk_limit_a_long_move_takes_the_trapezoid_time() {
    let mut machine = vm4();
    machine.jerk_mm_s3 = [1e18; 3];
    let t = machining_time(&path(vec![feed(x(0.0), x(100.0), 6000.0)]), &machine, &TimeOptions::default()).unwrap();
    assert!(close(t.kinematic_min * 60.0, 100.0 / 100.0 + 100.0 / A));
}

#[test]
fn a_move_too_short_to_reach_its_feed_takes_the_triangular_profile_time() {
    let length = 1.0;
    let t = time(&path(vec![feed(x(0.0), x(length), 6000.0)]));
    // Peak below a²/j = 80 mm/s: each half covers v·sqrt(v/j) = length/2.
    let peak = (length * J.sqrt() / 2.0).powf(2.0 / 3.0);
    assert!(peak < A * A / J, "below a²/j = 80 mm/s, itself below the feed of 100 mm/s");
    assert!(close(t.kinematic_min * 60.0, 4.0 * (peak / J).sqrt()), "{} vs {}", t.kinematic_min * 60.0, peak);

    let mut machine = vm4();
    machine.jerk_mm_s3 = [1e18; 3];
    let t = machining_time(&path(vec![feed(x(0.0), x(length), 6000.0)]), &machine, &TimeOptions::default()).unwrap();
    assert!(close(t.kinematic_min * 60.0, 2.0 * (length / A).sqrt()));
}

#[test]
fn a_z_move_uses_the_z_axis_limits() {
    let t = time(&path(vec![feed(P3::new(0.0, 0.0, 0.0), P3::new(0.0, 0.0, -100.0), 6000.0)]));
    let (a_z, j_z, v) = (1500.0, 40000.0, 100.0);
    assert!(close(t.kinematic_min * 60.0, 1.0 + v / a_z + a_z / j_z));
}

#[test]
fn a_90_degree_corner_at_high_feed_slows_to_the_junction_deviation_speed() {
    let (v, leg) = (100.0, 50.0);
    let corner = P3::new(leg, 0.0, 0.0);
    let p = path(vec![feed(x(0.0), corner, 6000.0), feed(corner, P3::new(leg, leg, 0.0), 6000.0)]);
    let t = time(&p);
    // GRBL: R = δ·s/(1 − s), s = cos(45°); acceleration along (u2 − u1) limited per axis.
    let s = (0.5f64).sqrt();
    let a_corner = A / s;
    let v_corner = (a_corner * DEFAULT_JUNCTION_DEVIATION_MM * s / (1.0 - s)).sqrt();
    let expected = 2.0 * leg / v + 2.0 * ramp_loss(0.0, v) + 2.0 * ramp_loss(v_corner, v);
    assert!(close(t.kinematic_min * 60.0, expected), "{} vs {expected}", t.kinematic_min * 60.0);
    assert_eq!(t.breakdown.slowed_corners, 1);
    let straight = time(&path(vec![feed(x(0.0), x(2.0 * leg), 6000.0)]));
    assert!(t.kinematic_min > straight.kinematic_min + 0.5 * ramp_loss(v_corner, v) / 60.0);
}

#[test]
fn a_corner_with_no_deviation_allowed_stops_the_machine() {
    let corner = x(50.0);
    let p = path(vec![feed(x(0.0), corner, 6000.0), feed(corner, P3::new(50.0, 50.0, 0.0), 6000.0)]);
    let options = TimeOptions { junction_deviation_mm: 0.0, ..TimeOptions::default() };
    let t = machining_time(&p, &vm4(), &options).unwrap();
    assert!(close(t.kinematic_min * 60.0, 2.0 * (0.5 + 100.0 / A + A / J)));
}

#[test]
fn a_full_circle_of_small_radius_at_high_feed_is_limited_by_its_share_of_the_acceleration() {
    let (radius, turns) = (5.0, 9u32);
    let start = P3::new(radius, 0.0, 0.0);
    let circle = Move {
        motion: Motion::Arc { center: P3::new(0.0, 0.0, 0.0), clockwise: false, plane: Plane::Xy, turns },
        ..feed(start, start, 12000.0)
    };
    let t = time(&path(vec![circle]));
    // LinuxCNC's shares: √3/2 of the limit for v²/R, 1/2 for the speed changes along the arc.
    let v = (ARC_NORMAL_ACCEL_SHARE * A * radius).sqrt();
    assert!(v < (J * radius * radius).cbrt(), "the acceleration, not the jerk, binds at R = 5");
    let length = 2.0 * PI * radius * f64::from(turns + 1);
    // From rest to v and back: length / v plus one S-curve ramp time at half the limit.
    let a_along = ARC_TANGENTIAL_ACCEL_SHARE * A;
    assert!(close(t.kinematic_min * 60.0, length / v + ramp(v, a_along, J)), "{t:?}");
    assert!(t.breakdown.arc_limit_min > 0.0);
}

#[test]
fn many_tiny_collinear_segments_take_the_time_of_one_long_move_with_full_look_ahead() {
    let moves: Vec<Move> = (0..1000).map(|i| feed(x(i as f64 * 0.01), x((i + 1) as f64 * 0.01), 6000.0)).collect();
    let whole = path(vec![feed(x(0.0), x(10.0), 6000.0)]);
    let options = TimeOptions { look_ahead_blocks: None, ..TimeOptions::default() };
    let tiny = machining_time(&path(moves.clone()), &vm4(), &options).unwrap();
    let one = machining_time(&whole, &vm4(), &options).unwrap();
    assert!(close(tiny.kinematic_min, one.kinematic_min), "{} vs {}", tiny.kinematic_min, one.kinematic_min);

    // 200 blocks of 0.01 mm: the control must be able to stop within 2 mm.
    let windowed = time(&path(moves));
    assert!(windowed.kinematic_min > one.kinematic_min * (1.0 + RELATIVE));
}

/// A trochoid written as fine G1 chords: loops of radius 2 mm, 0.1 mm chords, advancing
/// 0.5 mm per loop along X.
fn trochoid_polyline(loops: usize, feed_mm_min: f64) -> Toolpath {
    let (radius, chord, advance) = (2.0, 0.1, 0.5);
    let per_loop = (2.0 * PI * radius / chord).round() as usize;
    let mut points = Vec::new();
    for k in 0..loops * per_loop {
        let angle = 2.0 * PI * k as f64 / per_loop as f64;
        let centre = advance * k as f64 / per_loop as f64;
        points.push(P3::new(centre + radius * angle.cos(), radius * angle.sin(), -1.0));
    }
    path(points.windows(2).map(|w| feed(w[0], w[1], feed_mm_min)).collect())
}

#[test]
fn a_trochoid_like_dense_loop_pattern_is_slower_than_nominal() {
    let t = time(&trochoid_polyline(20, 6000.0));
    println!("trochoid polyline at F6000: kinematic / nominal = {:.3}", t.kinematic_ratio);
    // Chords of a 2 mm circle: v ≤ cbrt(j·R²) ≈ 58 mm/s against 100 programmed.
    assert!(t.kinematic_ratio > 1.5, "{t:?}");
    assert!(t.breakdown.slowed_corners > 1000);
    // At a feed the loop allows, only the start and stop cost time.
    let slow = time(&trochoid_polyline(20, 1200.0));
    assert!(slow.kinematic_ratio < 1.01, "{}", slow.kinematic_ratio);
}

#[test]
fn rapids_tool_changes_and_dwells_are_counted() {
    let mut p = path(vec![
        rapid(P3::new(0.0, 0.0, 50.0), P3::new(200.0, 0.0, 50.0)),
        feed(P3::new(200.0, 0.0, 50.0), P3::new(200.0, 0.0, 0.0), 600.0),
    ]);
    p.events = vec![
        Event { kind: EventKind::ToolChange { tool: 2 }, before_move: 0, line: 1 },
        Event { kind: EventKind::Dwell { seconds: 1.5 }, before_move: 1, line: 2 },
    ];
    let t = time(&p);
    assert!(close(t.rapid_nominal_min, 200.0 / 20000.0));
    assert!(close(t.feed_nominal_min, 50.0 / 600.0));
    assert_eq!(t.tool_changes, 1);
    assert!(close(t.tool_change_min, 8.0 / 60.0));
    assert!(close(t.dwell_min, 1.5 / 60.0));
    assert!(close(t.nominal_min, 200.0 / 20000.0 + 50.0 / 600.0 + 9.5 / 60.0));
    assert!(t.rapid_kinematic_min > t.rapid_nominal_min && t.feed_kinematic_min > t.feed_nominal_min);
    assert_eq!(t.breakdown.exact_stops, 1);
}

#[test]
fn the_kinematic_time_tends_to_the_nominal_time_on_long_straight_moves() {
    let ratio = |length: f64| time(&path(vec![feed(x(0.0), x(length), 3000.0)])).kinematic_ratio;
    assert!(ratio(10.0) > ratio(100.0) && ratio(100.0) > ratio(10_000.0));
    assert!(ratio(10_000.0) - 1.0 < 1e-3 && ratio(1_000_000.0) - 1.0 < 1e-5);
}

#[test]
fn feeds_above_the_machine_maximum_are_clamped_and_reported() {
    let t = time(&path(vec![feed(x(0.0), x(1000.0), 30000.0)]));
    assert!(close(t.breakdown.feed_clamp_min, 1000.0 / 15000.0 - 1000.0 / 30000.0));
    assert!(t.warnings.iter().any(|w| w.contains("maximum feed")), "{:?}", t.warnings);
}

#[test]
fn the_breakdown_and_the_per_move_times_add_up() {
    let options = TimeOptions { per_move: true, ..TimeOptions::default() };
    let t = machining_time(&trochoid_polyline(3, 9000.0), &vm4(), &options).unwrap();
    let b = &t.breakdown;
    let parts = b.feed_clamp_min + b.arc_limit_min + b.acceleration_min + b.jerk_min;
    assert!(close(t.nominal_min + parts, t.kinematic_min));
    let per_move: f64 = t.per_move_s.as_ref().unwrap().iter().map(|&s| f64::from(s)).sum();
    assert!((per_move / 60.0 - t.kinematic_min).abs() < 1e-5 * t.kinematic_min);
    assert!(b.jerk_min > 0.0 && b.acceleration_min > 0.0);
}

#[test]
fn an_empty_program_takes_no_time() {
    let t = time(&path(vec![]));
    assert!(t.nominal_min.abs() < f64::EPSILON && t.kinematic_min.abs() < f64::EPSILON);
    assert!((t.kinematic_ratio - 1.0).abs() < f64::EPSILON);
}

#[test]
fn invalid_limits_options_and_moves_are_refused_with_their_field() {
    let p = path(vec![feed(x(0.0), x(1.0), 600.0)]);
    let mut machine = vm4();
    machine.accel_mm_s2[2] = 0.0;
    let e = machining_time(&p, &machine, &TimeOptions::default()).unwrap_err();
    assert!(e.to_string().starts_with("accel_z_mm_s2"), "{e}");
    let mut machine = vm4();
    machine.jerk_mm_s3[0] = f64::NAN;
    assert!(machining_time(&p, &machine, &TimeOptions::default()).unwrap_err().to_string().starts_with("jerk_x"));
    let options = TimeOptions { look_ahead_blocks: Some(0), ..TimeOptions::default() };
    assert!(machining_time(&p, &vm4(), &options).is_err());
    let no_feed = path(vec![Move { feed_mm_min: None, ..feed(x(0.0), x(1.0), 1.0) }]);
    let e = machining_time(&no_feed, &vm4(), &TimeOptions::default()).unwrap_err();
    assert!(e.to_string().starts_with("moves[0].feed_mm_min"), "{e}");
}

#[test]
fn a_gap_between_moves_stops_the_machine_and_is_reported() {
    let p = path(vec![feed(x(0.0), x(50.0), 6000.0), feed(x(51.0), x(101.0), 6000.0)]);
    let t = time(&p);
    assert!(close(t.kinematic_min * 60.0, 2.0 * (0.5 + 100.0 / A + A / J)));
    assert!(t.warnings.iter().any(|w| w.contains("do not start")));
}

#[test]
fn lines_tangent_to_an_arc_in_any_plane_and_sense_meet_it_without_a_slowdown() {
    let radius = 20.0;
    for plane in [Plane::Xy, Plane::Zx, Plane::Yz] {
        // (u, v, w): the plane's two axes and its normal, as in sampling.rs.
        let p = |u: f64, v: f64| match plane {
            Plane::Xy => P3::new(u, v, 0.0),
            Plane::Zx => P3::new(v, 0.0, u),
            Plane::Yz => P3::new(0.0, u, v),
        };
        for clockwise in [false, true] {
            let side = if clockwise { -1.0 } else { 1.0 };
            let (start, end) = (p(radius, 0.0), p(0.0, side * radius));
            let arc = Move {
                motion: Motion::Arc { center: p(0.0, 0.0), clockwise, plane, turns: 0 },
                ..feed(start, end, 3000.0)
            };
            let into = feed(p(radius, -side * 10.0), start, 3000.0);
            let out = feed(end, p(-10.0, side * radius), 3000.0);
            let t = time(&path(vec![into, arc, out]));
            assert_eq!(t.breakdown.slowed_corners, 0, "{plane:?} clockwise {clockwise}");
            // One speed-up and one slow-down with the weakest axis' limits, as on a straight move.
            let (a, j) = if plane == Plane::Xy { (A, J) } else { (1500.0, 40000.0) };
            let (v, length) = (50.0, 20.0 + PI * radius / 2.0);
            let expected = length / v + ramp(v, a, j);
            assert!(close(t.kinematic_min * 60.0, expected), "{plane:?} clockwise {clockwise}: {t:?}");
        }
    }
}
