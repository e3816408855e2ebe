//! Round trips: a path written in either dialect and read back by the parser gives the
//! same feed moves (endpoints and centres to the written resolution) and the same events,
//! and its rapids reach the same points by the safe rules, on the real programs of
//! `shared/data`, on the small path, and on random paths of lines, arcs, helices, full
//! circles, rapids and tool changes. What the writer adds is modelled here
//! ([`expected_program`]); `safety_tests.rs` checks the rules themselves on the output.

use proptest::prelude::*;
use std::f64::consts::TAU;

use super::*;
use crate::core::nc::{parse_gcode, ParseOptions};
use crate::core::toolpath::{Section, Step, Units};

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

/// What the parser should read back: the moves and the events (kind, index of the move
/// they precede).
struct Expected {
    moves: Vec<Move>,
    events: Vec<(EventKind, usize)>,
}

/// A model of the writer: the path's moves (Fanuc: arcs with turns as their pieces) with
/// the rapids it adds or splits, and its events with those of the header and footer.
struct Model<'a> {
    options: &'a WriterOptions,
    decimals: u32,
    safe_mm: f64,
    out: Expected,
    /// Where the parser has the tool (it starts at the origin).
    at: P3,
    /// Whether the writer knows where the tool is in Z (not before the first tool call).
    z_known: bool,
    xy_known: bool,
    tool: Option<u32>,
    spindle_running: bool,
    coolant_on: bool,
    coolant_pending: bool,
}

impl Model<'_> {
    fn units(&self, v: f64) -> i64 {
        Fixed::round(v, self.decimals).units
    }

    /// A rapid to `to`, dropped (as the parser drops it) when nothing written changes.
    fn rapid(&mut self, to: P3) {
        let same = [(self.at.x, to.x), (self.at.y, to.y), (self.at.z, to.z)]
            .iter()
            .all(|&(a, b)| self.units(a) == self.units(b));
        if !same {
            let m = Move {
                motion: Motion::Rapid,
                start: self.at,
                end: to,
                feed_mm_min: None,
                spindle_rpm: None,
                tool: self.tool,
                line: 0,
            };
            self.out.moves.push(m);
            self.at = to;
        }
    }

    /// Z up first, XY, then Z down.
    fn rapid_pieces(&mut self, to: P3) {
        let moves_xy = self.units(self.at.x) != self.units(to.x) || self.units(self.at.y) != self.units(to.y);
        if moves_xy && self.units(to.z) > self.units(self.at.z) {
            self.rapid(P3::new(self.at.x, self.at.y, to.z));
        }
        self.rapid(P3::new(to.x, to.y, self.at.z));
        self.rapid(to);
    }

    fn event(&mut self, kind: EventKind) {
        let at = self.out.moves.len();
        self.out.events.push((kind, at));
    }

    /// Z alone up to the safe height, if the writer knows the tool is below it.
    fn retract(&mut self) {
        if self.z_known && self.units(self.at.z) < self.units(self.safe_mm) {
            self.rapid(P3::new(self.at.x, self.at.y, self.safe_mm));
        }
    }

    fn call_tool(&mut self, tool: u32) {
        self.retract();
        self.event(EventKind::ToolChange { tool });
        self.tool = Some(tool);
        self.rapid(P3::new(self.at.x, self.at.y, self.safe_mm));
        (self.z_known, self.xy_known) = (true, false);
    }

    fn spindle_on(&mut self, clockwise: bool) {
        self.event(EventKind::SpindleOn { clockwise });
        self.spindle_running = true;
        if std::mem::take(&mut self.coolant_pending) {
            self.coolant_on = true;
            self.event(EventKind::Coolant { on: true });
        }
    }
}

fn expected_program(path: &Toolpath, options: &WriterOptions) -> Expected {
    let decimals = options.decimals.min(MAX_DECIMALS);
    let safe_mm = [options.safe_z_mm, highest_point_mm(path)]
        .into_iter()
        .flatten()
        .map(|z| Fixed::round(z, decimals))
        .max_by_key(|f| f.units)
        .map_or(0.0, Fixed::value);
    let has_coolant = path.events.iter().any(|e| matches!(e.kind, EventKind::Coolant { .. }));
    let mut model = Model {
        options,
        decimals,
        safe_mm,
        out: Expected { moves: Vec::new(), events: Vec::new() },
        at: P3::default(),
        z_known: false,
        xy_known: false,
        tool: None,
        spindle_running: false,
        coolant_on: false,
        coolant_pending: options.coolant != Coolant::Off && !has_coolant,
    };
    let mut events: Vec<&Event> = path.events.iter().collect();
    events.sort_by_key(|e| e.before_move);
    if !events.iter().any(|e| matches!(e.kind, EventKind::ToolChange { .. }) && e.before_move == 0) {
        let tool = options.tool_number.or_else(|| path.moves.first().and_then(|m| m.tool));
        model.call_tool(tool.unwrap_or(DEFAULT_TOOL_NUMBER));
    }
    let first_feed = path.moves.iter().position(|m| !matches!(m.motion, Motion::Rapid)).unwrap_or(path.moves.len());
    let mut start_pending =
        !events.iter().any(|e| matches!(e.kind, EventKind::SpindleOn { .. }) && e.before_move <= first_feed);
    // Events up to move `i` (up to the End for `None`); `false` at the End.
    let mut next = 0;
    let mut events_up_to = |model: &mut Model, i: Option<usize>, start_pending: &mut bool| -> bool {
        while let Some(e) = events.get(next).filter(|e| i.is_none_or(|i| e.before_move <= i)) {
            next += 1;
            match e.kind {
                EventKind::End => return false,
                EventKind::Section(_) => {
                    if std::mem::take(start_pending) {
                        model.spindle_on(true);
                    }
                }
                EventKind::ToolChange { tool } => model.call_tool(tool),
                EventKind::SpindleOn { clockwise } => model.spindle_on(clockwise),
                EventKind::SpindleOff => {
                    model.spindle_running = false;
                    model.event(EventKind::SpindleOff);
                }
                EventKind::Coolant { on } => {
                    model.coolant_on = on;
                    model.event(EventKind::Coolant { on });
                }
                EventKind::Dwell { seconds } => {
                    model.event(EventKind::Dwell { seconds: Fixed::round(seconds, DWELL_DECIMALS).value() })
                }
                other => model.event(other),
            }
        }
        true
    };
    let end = events.iter().find(|e| e.kind == EventKind::End).map_or(usize::MAX, |e| e.before_move);
    for (i, m) in path.moves.iter().enumerate().take(end) {
        events_up_to(&mut model, Some(i), &mut start_pending);
        if std::mem::take(&mut start_pending) {
            model.spindle_on(true);
        }
        let rapid = matches!(m.motion, Motion::Rapid);
        if !model.xy_known {
            model.rapid_pieces(if rapid { m.end } else { m.start });
            model.xy_known = true;
            if rapid {
                continue;
            }
        }
        if rapid {
            model.rapid_pieces(m.end);
            continue;
        }
        let pieces = match model.options.dialect {
            Dialect::Fanuc => split_turns(m),
            Dialect::LinuxCnc => vec![*m],
        };
        for piece in pieces {
            model.out.moves.push(Move { start: model.at, tool: model.tool, ..piece });
            model.at = piece.end;
        }
    }
    model.retract();
    events_up_to(&mut model, None, &mut start_pending);
    model.retract();
    if model.spindle_running {
        model.event(EventKind::SpindleOff);
    }
    if model.coolant_on {
        model.event(EventKind::Coolant { on: false });
    }
    model.event(EventKind::End);
    model.out
}

/// Writes `path`, reads it back and compares move by move and event by event.
fn assert_round_trip(path: &Toolpath, options: &WriterOptions) -> Result<(), TestCaseError> {
    let text = write_program(path, options);
    let read = parse_gcode(&text, &ParseOptions::default())
        .map_err(|e| TestCaseError::fail(format!("{:?}: the output does not parse: {e}\n{text}", options.dialect)))?;
    let expected = expected_program(path, options);
    let tol = resolution(options.decimals) + FLOAT_SLACK_MM;
    let feed_tol = resolution(options.feed_decimals) / 2.0 + FLOAT_SLACK_MM;
    let spindle_tol = 0.5 + FLOAT_SLACK_MM;
    prop_assert_eq!(read.moves.len(), expected.moves.len(), "{:?}: move count\n{}", options.dialect, text);
    for (i, (got, want)) in read.moves.iter().zip(&expected.moves).enumerate() {
        let context = format!("{:?} move {i} (source line {}): {got:?} vs {want:?}", options.dialect, want.line);
        match (got.motion, want.motion) {
            (Motion::Rapid, Motion::Rapid) => {}
            (Motion::Linear, Motion::Linear) => {}
            (
                Motion::Arc { center: c1, clockwise: w1, plane: p1, turns: t1 },
                Motion::Arc { center: c2, clockwise: w2, plane: p2, turns: t2 },
            ) => {
                prop_assert!((w1, p1, t1) == (w2, p2, t2), "{}", context);
                prop_assert!(close(c1, c2, tol), "centre: {}", context);
            }
            _ => prop_assert!(false, "motion kind: {}", context),
        }
        prop_assert!(close(got.start, want.start, tol), "start: {}", context);
        prop_assert!(close(got.end, want.end, tol), "end: {}", context);
        // A rapid carries no F (its modal feed is whatever was written before), and the
        // rapids the writer adds no S of their own.
        if !matches!(want.motion, Motion::Rapid) {
            prop_assert!(close_option(got.feed_mm_min, want.feed_mm_min, feed_tol), "feed: {}", context);
            prop_assert!(close_option(got.spindle_rpm, want.spindle_rpm, spindle_tol), "speed: {}", context);
        }
        prop_assert_eq!(got.tool, want.tool, "tool: {}", context);
    }
    let got: Vec<(EventKind, usize)> = read.events.iter().map(|e| (e.kind, e.before_move)).collect();
    prop_assert_eq!(got, expected.events, "{:?}: events\n{}", options.dialect, text);
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
        let numbered = WriterOptions { line_numbers: Some(LineNumbers::default()), coolant: Coolant::Mist, ..options };
        assert_round_trip(&path, &numbered).unwrap_or_else(|e| panic!("{e}"));
    }
}

/// One random step of a path: a line, an arc in XY (helix if `dz` ≠ 0, full circle if
/// `full`), a rapid (possibly diagonal), or a tool change.
#[derive(Debug, Clone, Copy)]
enum RandomStep {
    Line { dx: f64, dy: f64, dz: f64, feed: f64 },
    Arc { radius: f64, centre_angle: f64, sweep: f64, clockwise: bool, full: bool, turns: u32, dz: f64, feed: f64 },
    Rapid { dx: f64, dy: f64, dz: f64 },
    ToolChange { tool: u32 },
}

fn random_step() -> impl Strategy<Value = RandomStep> {
    let feed = 10.0..5000.0f64;
    prop_oneof![
        3 => (-50.0..50.0f64, -50.0..50.0f64, -5.0..5.0f64, feed.clone()).prop_map(|(dx, dy, dz, feed)| RandomStep::Line {
            dx,
            dy,
            dz,
            feed
        }),
        3 => (
            (1.0..40.0f64, 0.0..TAU, 0.1..6.1f64, any::<bool>()),
            (prop::bool::weighted(0.2), 0u32..4, prop_oneof![Just(0.0), -5.0..5.0f64], feed),
        )
            .prop_map(|((radius, centre_angle, sweep, clockwise), (full, turns, dz, feed))| RandomStep::Arc {
                radius,
                centre_angle,
                sweep,
                clockwise,
                full,
                turns,
                dz,
                feed
            }),
        1 => (
            prop_oneof![Just(0.0), -50.0..50.0f64],
            prop_oneof![Just(0.0), -50.0..50.0f64],
            prop_oneof![Just(0.0), -10.0..10.0f64]
        )
            .prop_map(|(dx, dy, dz)| RandomStep::Rapid { dx, dy, dz }),
        1 => (1u32..30).prop_map(|tool| RandomStep::ToolChange { tool }),
    ]
}

/// The path of `steps` from `start` (where the first move, a rapid, goes), with a section
/// label before every fourth move; `first_tool` is the moves' tool before any change.
fn random_path(start: P3, steps: &[RandomStep], rpm: f64, first_tool: Option<u32>) -> Toolpath {
    let rapid_to = |from: P3, to: P3, tool| Move {
        motion: Motion::Rapid,
        start: from,
        end: to,
        feed_mm_min: None,
        spindle_rpm: Some(rpm),
        tool,
        line: 0,
    };
    let mut moves = vec![rapid_to(P3::default(), start, first_tool)];
    let mut events = vec![Event { kind: EventKind::SpindleOn { clockwise: true }, before_move: 0, line: 1 }];
    let (mut at, mut tool) = (start, first_tool);
    for s in steps {
        let (motion, end, feed) = match *s {
            RandomStep::Line { dx, dy, dz, feed } => {
                (Motion::Linear, P3::new(at.x + dx, at.y + dy, at.z + dz), Some(feed))
            }
            RandomStep::Arc { radius, centre_angle, sweep, clockwise, full, turns, dz, feed } => {
                let center = P3::new(at.x + radius * centre_angle.cos(), at.y + radius * centre_angle.sin(), at.z);
                let a0 = (at.y - center.y).atan2(at.x - center.x);
                let a1 = if clockwise { a0 - sweep } else { a0 + sweep };
                let end = if full {
                    P3::new(at.x, at.y, at.z + dz)
                } else {
                    P3::new(center.x + radius * a1.cos(), center.y + radius * a1.sin(), at.z + dz)
                };
                (Motion::Arc { center, clockwise, plane: Plane::Xy, turns }, end, Some(feed))
            }
            RandomStep::Rapid { dx, dy, dz } => (Motion::Rapid, P3::new(at.x + dx, at.y + dy, at.z + dz), None),
            RandomStep::ToolChange { tool: t } => {
                tool = Some(t);
                events.push(Event { kind: EventKind::ToolChange { tool: t }, before_move: moves.len(), line: 0 });
                continue;
            }
        };
        // The parser drops straight moves of no written length; so do paths.
        if !matches!(motion, Motion::Arc { .. }) && close(at, end, 1e-3) {
            continue;
        }
        let feed = feed.or_else(|| moves.last().and_then(|m: &Move| m.feed_mm_min));
        moves.push(Move { motion, start: at, end, feed_mm_min: feed, spindle_rpm: Some(rpm), tool, line: 0 });
        at = end;
    }
    for (i, m) in moves.iter_mut().enumerate() {
        m.line = u32::try_from(i + 1).unwrap_or(u32::MAX);
    }
    let labels: Vec<Option<Section>> = (0..moves.len())
        .map(|i| {
            let part = u32::try_from(i / 4).unwrap_or(u32::MAX);
            Some(Section {
                layer: part / 2,
                z_mm: -f64::from(part),
                step: Step::TrochoidalGrooving,
                region: Some(part),
            })
        })
        .collect();
    events.extend(crate::core::toolpath::section_events(&labels));
    Toolpath { moves, events, source_units: Units::Mm, warnings: Vec::new() }
}

/// Random writer options: dialect, decimals, coolant, N numbers, tool, safe height.
fn random_options() -> impl Strategy<Value = WriterOptions> {
    (
        any::<bool>(),
        3u32..5,
        prop_oneof![Just(Coolant::Off), Just(Coolant::Mist), Just(Coolant::Flood)],
        any::<bool>(),
        prop::option::of(1u32..100),
        prop::option::of(-20.0..80.0f64),
    )
        .prop_map(|(fanuc, decimals, coolant, numbered, tool_number, safe_z_mm)| WriterOptions {
            dialect: if fanuc { Dialect::Fanuc } else { Dialect::LinuxCnc },
            decimals,
            coolant,
            line_numbers: numbered.then(LineNumbers::default),
            tool_number,
            safe_z_mm,
            ..WriterOptions::default()
        })
}

/// A random path (up to 14 steps from a random start, at a random speed, with or without a
/// tool of its own) and random options to write it with.
pub(super) fn random_case() -> impl Strategy<Value = (Toolpath, WriterOptions)> {
    (
        (-100.0..100.0f64, -100.0..100.0f64, -20.0..20.0f64),
        prop::collection::vec(random_step(), 1..14),
        1000.0..30000.0f64,
        prop::option::of(1u32..30),
        random_options(),
    )
        .prop_map(|(start, steps, rpm, first_tool, options)| {
            (random_path(P3::new(start.0, start.1, start.2), &steps, rpm, first_tool), options)
        })
}

proptest! {
    #[test]
    fn random_paths_read_back_as_the_same_cuts_and_the_same_rapid_points((path, options) in random_case()) {
        assert_round_trip(&path, &options)?;
    }
}
