//! Round trips: a path written in either dialect and read back by the parser gives the
//! same moves (endpoints and centres to the written resolution) and the same events, on the
//! real programs of `shared/data` and on random lines, arcs, helices and full circles.

use proptest::prelude::*;
use std::f64::consts::TAU;

use super::*;
use crate::core::nc::{parse_gcode, ParseOptions};
use crate::core::toolpath::Units;

/// Room for float error on top of the written resolution, mm.
const FLOAT_SLACK_MM: f64 = 1e-9;

fn data(name: &str) -> String {
    let path = format!("{}/../shared/data/{name}", env!("CARGO_MANIFEST_DIR"));
    std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{path}: {e}"))
}

/// One unit of the last written digit.
fn resolution(decimals: u32) -> f64 {
    Fixed { units: 1, decimals }.value()
}

fn close(p: P3, q: P3, tol: f64) -> bool {
    (p.x - q.x).abs() <= tol && (p.y - q.y).abs() <= tol && (p.z - q.z).abs() <= tol
}

fn close_option(a: Option<f64>, b: Option<f64>, tol: f64) -> bool {
    match (a, b) {
        (Some(a), Some(b)) => (a - b).abs() <= tol,
        (None, None) => true,
        _ => false,
    }
}

/// The moves the parser should read back, with the index each original move starts at:
/// Fanuc writes an arc with turns as its pieces.
fn expected_moves(path: &Toolpath, options: &WriterOptions) -> (Vec<Move>, Vec<usize>) {
    let mut moves = Vec::with_capacity(path.moves.len());
    let mut starts = Vec::with_capacity(path.moves.len() + 1);
    for m in &path.moves {
        starts.push(moves.len());
        // A rapid or linear move of zero length is not written (the reader drops it).
        if !matches!(m.motion, Motion::Arc { .. }) && close(m.start, m.end, 0.0) {
            continue;
        }
        match options.dialect {
            Dialect::Fanuc => moves.extend(split_turns(m)),
            Dialect::LinuxCnc => moves.push(*m),
        }
    }
    starts.push(moves.len());
    (moves, starts)
}

/// The events the parser should read back: the path's up to its end, with what the header
/// and footer add (spindle start, coolant on and off, the end).
fn expected_events(path: &Toolpath, options: &WriterOptions, starts: &[usize]) -> Vec<(EventKind, usize)> {
    let end = path.events.iter().position(|e| e.kind == EventKind::End);
    let own = &path.events[..end.unwrap_or(path.events.len())];
    let mut events: Vec<(EventKind, usize)> = Vec::new();
    let first_feed = path.moves.iter().position(|m| !matches!(m.motion, Motion::Rapid)).unwrap_or(path.moves.len());
    let started = own.iter().any(|e| matches!(e.kind, EventKind::SpindleOn { .. }) && e.before_move <= first_feed);
    if !started {
        events.push((EventKind::SpindleOn { clockwise: true }, 0));
    }
    // Dwells as written (to the millisecond): the parser reads back exactly that decimal.
    let as_written = |kind| match kind {
        EventKind::Dwell { seconds } => EventKind::Dwell { seconds: Fixed::round(seconds, DWELL_DECIMALS).value() },
        other => other,
    };
    events.extend(own.iter().map(|e| (as_written(e.kind), starts[e.before_move.min(path.moves.len())])));
    let end_at = end.map_or(starts[path.moves.len()], |i| starts[path.events[i].before_move]);
    let add_coolant = options.coolant && !own.iter().any(|e| matches!(e.kind, EventKind::Coolant { .. }));
    if add_coolant {
        let spindle = events.iter().position(|e| matches!(e.0, EventKind::SpindleOn { .. })).unwrap_or(0);
        events.insert(spindle + 1, (EventKind::Coolant { on: true }, events[spindle].1));
        events.push((EventKind::Coolant { on: false }, end_at));
    }
    events.push((EventKind::End, end_at));
    events
}

/// Writes `path`, reads it back and compares move by move and event by event.
fn assert_round_trip(path: &Toolpath, options: &WriterOptions) -> Result<(), TestCaseError> {
    let text = write_program(path, options);
    let read = parse_gcode(&text, &ParseOptions::default())
        .map_err(|e| TestCaseError::fail(format!("{:?}: the output does not parse: {e}", options.dialect)))?;
    let (expected, starts) = expected_moves(path, options);
    let tol = resolution(options.decimals) + FLOAT_SLACK_MM;
    let feed_tol = resolution(options.feed_decimals) / 2.0 + FLOAT_SLACK_MM;
    let spindle_tol = 0.5 + FLOAT_SLACK_MM;
    prop_assert_eq!(read.moves.len(), expected.len(), "{:?}: move count of\n{}", options.dialect, text);
    for (i, (got, want)) in read.moves.iter().zip(&expected).enumerate() {
        let context = format!("{:?} move {i} (source line {}): {got:?} vs {want:?}", options.dialect, want.line);
        match (got.motion, want.motion) {
            (Motion::Rapid, Motion::Rapid) | (Motion::Linear, Motion::Linear) => {}
            (
                Motion::Arc { center: c1, clockwise: w1, plane: p1, turns: t1 },
                Motion::Arc { center: c2, clockwise: w2, plane: p2, turns: t2 },
            ) => {
                prop_assert!((w1, p1, t1) == (w2, p2, t2), "{}", context);
                prop_assert!(close(c1, c2, tol), "centre: {}", context);
            }
            _ => prop_assert!(false, "motion kind: {}", context),
        }
        prop_assert!(close(got.end, want.end, tol), "end: {}", context);
        // A rapid carries no F (its modal feed is whatever was written before).
        if !matches!(want.motion, Motion::Rapid) {
            prop_assert!(close_option(got.feed_mm_min, want.feed_mm_min, feed_tol), "feed: {}", context);
        }
        prop_assert!(close_option(got.spindle_rpm, want.spindle_rpm, spindle_tol), "speed: {}", context);
        prop_assert_eq!(got.tool, want.tool, "tool: {}", context);
    }
    let got: Vec<(EventKind, usize)> = read.events.iter().map(|e| (e.kind, e.before_move)).collect();
    prop_assert_eq!(got, expected_events(path, options, &starts), "{:?}: events", options.dialect);
    Ok(())
}

fn both_dialects() -> [WriterOptions; 2] {
    [Dialect::Fanuc, Dialect::LinuxCnc].map(|dialect| WriterOptions { dialect, ..WriterOptions::default() })
}

#[test]
fn the_real_programs_read_back_move_by_move_in_both_dialects() {
    for name in ["trochoidal.ngc", "tiger.nc"] {
        let path = parse_gcode(&data(name), &ParseOptions::default()).unwrap_or_else(|e| panic!("{name}: {e}"));
        for options in both_dialects() {
            assert_round_trip(&path, &options).unwrap_or_else(|e| panic!("{name}: {e}"));
        }
    }
}

#[test]
fn the_small_path_reads_back_with_its_helix_turns_expanded_for_fanuc() {
    let path = super::tests::small_path();
    for options in both_dialects() {
        assert_round_trip(&path, &options).unwrap_or_else(|e| panic!("{e}"));
        let numbered = WriterOptions { line_numbers: Some(LineNumbers::default()), ..options };
        assert_round_trip(&path, &numbered).unwrap_or_else(|e| panic!("{e}"));
    }
}

/// One random step of a path: a line, or an arc in XY (helix if `dz` ≠ 0, full circle if
/// `full`).
#[derive(Debug, Clone, Copy)]
enum Step {
    Line { dx: f64, dy: f64, dz: f64, feed: f64 },
    Arc { radius: f64, centre_angle: f64, sweep: f64, clockwise: bool, full: bool, turns: u32, dz: f64, feed: f64 },
}

fn step() -> impl Strategy<Value = Step> {
    let feed = 10.0..5000.0f64;
    prop_oneof![
        (-50.0..50.0f64, -50.0..50.0f64, -5.0..5.0f64, feed.clone()).prop_map(|(dx, dy, dz, feed)| Step::Line {
            dx,
            dy,
            dz,
            feed
        }),
        (
            (1.0..40.0f64, 0.0..TAU, 0.1..6.1f64, any::<bool>()),
            (prop::bool::weighted(0.2), 0u32..4, prop_oneof![Just(0.0), -5.0..5.0f64], feed),
        )
            .prop_map(|((radius, centre_angle, sweep, clockwise), (full, turns, dz, feed))| Step::Arc {
                radius,
                centre_angle,
                sweep,
                clockwise,
                full,
                turns,
                dz,
                feed
            }),
    ]
}

/// The path of `steps` from `start`, after a rapid to it.
fn random_path(start: P3, steps: &[Step], rpm: f64) -> Toolpath {
    let mut moves = vec![Move {
        motion: Motion::Rapid,
        start: P3::default(),
        end: start,
        feed_mm_min: None,
        spindle_rpm: Some(rpm),
        tool: None,
        line: 1,
    }];
    let mut at = start;
    for (i, s) in steps.iter().enumerate() {
        let (motion, end, feed) = match *s {
            Step::Line { dx, dy, dz, feed } => (Motion::Linear, P3::new(at.x + dx, at.y + dy, at.z + dz), feed),
            Step::Arc { radius, centre_angle, sweep, clockwise, full, turns, dz, feed } => {
                let center = P3::new(at.x + radius * centre_angle.cos(), at.y + radius * centre_angle.sin(), at.z);
                let a0 = (at.y - center.y).atan2(at.x - center.x);
                let a1 = if clockwise { a0 - sweep } else { a0 + sweep };
                let end = if full {
                    P3::new(at.x, at.y, at.z + dz)
                } else {
                    P3::new(center.x + radius * a1.cos(), center.y + radius * a1.sin(), at.z + dz)
                };
                (Motion::Arc { center, clockwise, plane: Plane::Xy, turns }, end, feed)
            }
        };
        let line = u32::try_from(i + 2).unwrap_or(u32::MAX);
        moves.push(Move { motion, start: at, end, feed_mm_min: Some(feed), spindle_rpm: Some(rpm), tool: None, line });
        at = end;
    }
    let events = vec![Event { kind: EventKind::SpindleOn { clockwise: true }, before_move: 0, line: 1 }];
    Toolpath { moves, events, source_units: Units::Mm, warnings: Vec::new() }
}

proptest! {
    #[test]
    fn random_lines_arcs_helices_and_full_circles_read_back_in_both_dialects(
        // Above the origin, so that the first rapid (from the parser's origin) has a length.
        start in (-100.0..100.0f64, -100.0..100.0f64, 1.0..20.0f64),
        steps in prop::collection::vec(step(), 1..12),
        rpm in 1000.0..30000.0f64,
        decimals in 3u32..5,
        coolant in any::<bool>(),
    ) {
        let path = random_path(P3::new(start.0, start.1, start.2), &steps, rpm);
        for options in both_dialects() {
            assert_round_trip(&path, &WriterOptions { decimals, coolant, ..options })?;
        }
    }
}
