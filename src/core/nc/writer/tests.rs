//! The writer's output, line by line: golden files of a small hand-made path in both
//! dialects, determinism and the modal rules.
//!
//! The golden files are in `src/core/nc/golden/` (see `core/golden.rs`).

use super::*;
use crate::core::golden::check_golden;
use crate::core::nc::arcs::check_arc;
use crate::core::nc::{parse_gcode, ParseOptions};
use crate::core::toolpath::Units;

fn at(x: f64, y: f64, z: f64) -> P3 {
    P3::new(x, y, z)
}

fn arc(center: P3, clockwise: bool, plane: Plane, turns: u32) -> Motion {
    Motion::Arc { center, clockwise, plane, turns }
}

/// Moves from `start` through each `(motion, end, feed, rpm)`, each starting where the
/// one before ends; lines numbered from 1.
fn chain(start: P3, steps: &[(Motion, P3, Option<f64>, Option<f64>)]) -> Vec<Move> {
    let mut from = start;
    let mut moves = Vec::with_capacity(steps.len());
    for (i, &(motion, end, feed_mm_min, spindle_rpm)) in steps.iter().enumerate() {
        let line = u32::try_from(i + 1).unwrap_or(u32::MAX);
        moves.push(Move { motion, start: from, end, feed_mm_min, spindle_rpm, tool: Some(3), line });
        from = end;
    }
    moves
}

fn path_of(moves: Vec<Move>, events: Vec<(EventKind, usize)>) -> Toolpath {
    let events = events.into_iter().map(|(kind, before_move)| Event { kind, before_move, line: 0 }).collect();
    Toolpath { moves, events, source_units: Units::Mm, warnings: Vec::new() }
}

/// The small path of the golden files: a rapid, a plunge, lines, a CW arc, a CCW full
/// circle, a helix with two extra turns, a dwell, a G18 arc, feed and spindle changes.
pub(super) fn small_path() -> Toolpath {
    let (s1, s2) = (Some(8000.0), Some(9500.0));
    let moves = chain(
        at(0.0, 0.0, 50.0),
        &[
            (Motion::Rapid, at(10.0, 0.0, 5.0), None, s1),
            (Motion::Linear, at(10.0, 0.0, -1.0), Some(200.0), s1),
            (Motion::Linear, at(30.0, 0.0, -1.0), Some(600.0), s1),
            (Motion::Linear, at(30.0, 10.0, -1.0), Some(600.0), s1),
            (arc(at(30.0, 0.0, -1.0), true, Plane::Xy, 0), at(40.0, 0.0, -1.0), Some(600.0), s1),
            (arc(at(35.0, 0.0, -1.0), false, Plane::Xy, 0), at(40.0, 0.0, -1.0), Some(450.0), s1),
            (arc(at(35.0, 0.0, -1.0), false, Plane::Xy, 2), at(30.0, 0.0, -3.5), Some(450.0), s1),
            (Motion::Rapid, at(30.0, 0.0, 5.0), Some(450.0), s1),
            (Motion::Rapid, at(0.0, 20.0, 5.0), Some(450.0), s1),
            (Motion::Linear, at(0.0, 20.0, -2.0), Some(200.0), s2),
            (arc(at(10.0, 20.0, -2.0), true, Plane::Zx, 0), at(10.0, 20.0, -12.0), Some(333.3), s2),
            (Motion::Rapid, at(10.0, 20.0, 50.0), Some(333.3), s2),
        ],
    );
    let events = vec![
        (EventKind::ToolChange { tool: 3 }, 0),
        (EventKind::SpindleOn { clockwise: true }, 0),
        (EventKind::Dwell { seconds: 0.5 }, 7),
        (EventKind::End, 12),
    ];
    path_of(moves, events)
}

fn options(dialect: Dialect, numbered: bool) -> WriterOptions {
    WriterOptions {
        dialect,
        title: Some("Small die (test)".to_string()),
        line_numbers: numbered.then(LineNumbers::default),
        ..WriterOptions::default()
    }
}

#[test]
fn the_small_path_matches_its_golden_files_in_both_dialects_with_and_without_n_numbers() {
    let path = small_path();
    let cases = [
        ("small_fanuc.nc", Dialect::Fanuc, false),
        ("small_fanuc_numbered.nc", Dialect::Fanuc, true),
        ("small_linuxcnc.ngc", Dialect::LinuxCnc, false),
        ("small_linuxcnc_numbered.ngc", Dialect::LinuxCnc, true),
    ];
    for (name, dialect, numbered) in cases {
        let text = write_program(&path, &options(dialect, numbered));
        check_golden(name, &text);
        parse_gcode(&text, &ParseOptions::default()).unwrap_or_else(|e| panic!("{name} does not parse: {e}"));
    }
}

/// The words of `text` that start with `letter`, line by line (comments skipped).
#[test]
fn the_line_given_for_each_move_is_the_written_block_that_ends_where_the_move_ends() {
    let path = small_path();
    for dialect in [Dialect::Fanuc, Dialect::LinuxCnc] {
        for numbered in [false, true] {
            let written = write_program_mapped(&path, &options(dialect, numbered));
            assert_eq!(written.text, write_program(&path, &options(dialect, numbered)));
            assert_eq!(written.move_lines.len(), path.moves.len(), "every move before the end event");
            let parsed = parse_gcode(&written.text, &ParseOptions::default()).unwrap();
            let tolerance = 10f64.powi(-(DEFAULT_DECIMALS as i32));
            for (m, &line) in path.moves.iter().zip(&written.move_lines) {
                let block = parsed.moves.iter().rev().find(|p| p.line == line);
                let block = block.unwrap_or_else(|| panic!("{dialect:?}: no move on line {line}"));
                let (a, b) = (block.end, m.end);
                let gap = (a.x - b.x).abs().max((a.y - b.y).abs()).max((a.z - b.z).abs());
                assert!(gap <= tolerance, "{dialect:?} line {line}: {a:?} vs {b:?}");
            }
            assert!(written.move_lines.windows(2).all(|w| w[0] < w[1]), "{:?}", written.move_lines);
        }
    }
}

fn words(text: &str, letter: char) -> Vec<String> {
    text.lines()
        .filter(|l| !l.starts_with('(') && !l.starts_with('%') && !l.starts_with('O'))
        .flat_map(|l| l.split_whitespace().filter(|w| w.starts_with(letter)).map(str::to_string).collect::<Vec<_>>())
        .collect()
}

/// Lines along X at Z = -1 with these feeds, after a rapid to the start.
fn lines_with_feeds(feeds: &[f64]) -> Toolpath {
    let mut steps = vec![(Motion::Rapid, at(0.0, 0.0, -1.0), None, Some(6000.0))];
    for (i, &feed) in feeds.iter().enumerate() {
        steps.push((Motion::Linear, at(10.0 * (i + 1) as f64, 0.0, -1.0), Some(feed), Some(6000.0)));
    }
    path_of(chain(at(0.0, 0.0, 50.0), &steps), vec![])
}

#[test]
fn writing_twice_gives_the_same_bytes_and_a_timestamp_appears_only_when_given() {
    let path = small_path();
    for dialect in [Dialect::Fanuc, Dialect::LinuxCnc] {
        let plain = options(dialect, false);
        assert_eq!(write_program(&path, &plain), write_program(&path, &plain));
        let stamped = WriterOptions { timestamp: Some("2025-01-02T03:04:05Z".to_string()), ..plain.clone() };
        let with = write_program(&path, &stamped);
        assert!(with.contains("(2025-01-02T03:04:05Z)\n"), "{with}");
        assert!(!write_program(&path, &plain).contains("2025"));
        assert_eq!(with.replace("(2025-01-02T03:04:05Z)\n", ""), write_program(&path, &plain));
    }
}

#[test]
fn f_is_written_only_when_the_written_feed_changes() {
    // 100.04 rounds to the F100 already written.
    let path = lines_with_feeds(&[100.0, 100.0, 100.04, 250.0, 250.0, 99.96]);
    let text = write_program(&path, &options(Dialect::LinuxCnc, false));
    assert_eq!(words(&text, 'F'), ["F100", "F250", "F100"], "{text}");
    let fine = WriterOptions { feed_decimals: 2, ..options(Dialect::Fanuc, false) };
    assert_eq!(words(&write_program(&path, &fine), 'F'), ["F100.", "F100.04", "F250.", "F99.96"]);
}

#[test]
fn the_g_code_is_written_only_when_the_motion_changes() {
    let text = write_program(&small_path(), &options(Dialect::LinuxCnc, false));
    let codes: Vec<String> =
        words(&text, 'G').into_iter().filter(|g| ["G0", "G1", "G2", "G3"].contains(&g.as_str())).collect();
    assert_eq!(codes, ["G0", "G1", "G2", "G3", "G0", "G1", "G2", "G0"], "{text}");
}

#[test]
fn an_axis_is_written_only_when_its_written_value_changes() {
    // The second move changes X only; the third moves less than half a micron.
    let steps = [
        (Motion::Rapid, at(1.0, 2.0, 3.0), None, None),
        (Motion::Linear, at(5.0, 2.0, 3.0), Some(100.0), None),
        (Motion::Linear, at(5.000_4, 2.0, 3.0), Some(100.0), None),
        (Motion::Linear, at(5.000_4, 2.0002, -3.0), Some(100.0), None),
    ];
    let path = path_of(chain(at(0.0, 0.0, 50.0), &steps), vec![]);
    let text = write_program(&path, &options(Dialect::LinuxCnc, false));
    assert!(text.contains("\nX1 Y2\nZ3\nG1 X5 F100\nZ-3\nG0 Z50\n"), "{text}");
}

#[test]
fn fanuc_lengths_and_feeds_always_have_a_point_and_linuxcnc_ones_never_end_with_one() {
    let fanuc = write_program(&small_path(), &options(Dialect::Fanuc, false));
    let linuxcnc = write_program(&small_path(), &options(Dialect::LinuxCnc, false));
    for letter in ['X', 'Y', 'Z', 'I', 'J', 'K', 'F'] {
        assert!(words(&fanuc, letter).iter().all(|w| w.contains('.')), "{letter}: {fanuc}");
        assert!(words(&linuxcnc, letter).iter().all(|w| !w.ends_with('.')), "{letter}: {linuxcnc}");
    }
    for letter in ['S', 'T', 'H', 'P', 'M', 'G'] {
        assert!(words(&fanuc, letter).iter().all(|w| !w.ends_with('.')), "{letter}: {fanuc}");
    }
    assert!(!fanuc.contains("-0.\n") && !fanuc.contains("-0. ") && !linuxcnc.contains("-0 "));
}

#[test]
fn the_header_calls_the_tool_goes_to_the_safe_height_and_starts_the_spindle_and_coolant_when_the_path_does_not() {
    let path = lines_with_feeds(&[300.0]);
    let with_tool = WriterOptions { tool_number: Some(7), coolant: Coolant::Flood, ..options(Dialect::Fanuc, false) };
    let text = write_program(&path, &with_tool);
    let body: Vec<&str> = text.lines().collect();
    assert_eq!(
        body,
        [
            "%",
            "O0001 (SMALL DIE [TEST])",
            "G21 G17 G90 G94 G40 G80 G49",
            "T7 M6",
            "G0 G43 H7 Z50.",
            "S6000 M3",
            "M8",
            "X0. Y0.",
            "Z-1.",
            "G1 X10. F300.",
            "G0 Z50.",
            "M5",
            "M9",
            "M30",
            "%"
        ]
    );
    // No speed in the path: the option's; no coolant; no tool: T1, H1.
    let mut bare = lines_with_feeds(&[300.0]);
    bare.moves.iter_mut().for_each(|m| (m.spindle_rpm, m.tool) = (None, None));
    let bare_options = WriterOptions { spindle_rpm: Some(1234.4), ..options(Dialect::LinuxCnc, false) };
    let text = write_program(&bare, &bare_options);
    assert_eq!(
        text,
        "(Small die [test])\nG21 G17 G90 G94 G40 G80 G49\nT1 M6\nG0 G43 H1 Z50\nS1234 M3\nX0 Y0\nZ-1\nG1 X10 F300\nG0 Z50\nM5\nM2\n"
    );
}

#[test]
fn the_paths_own_coolant_spindle_and_end_events_are_not_doubled() {
    let mut path = small_path();
    path.events.insert(2, Event { kind: EventKind::Coolant { on: true }, before_move: 0, line: 0 });
    path.events.insert(4, Event { kind: EventKind::Coolant { on: false }, before_move: 11, line: 0 });
    path.events.insert(5, Event { kind: EventKind::SpindleOff, before_move: 11, line: 0 });
    let text = write_program(&path, &options(Dialect::Fanuc, false));
    let m_words = words(&text, 'M');
    assert_eq!(m_words, ["M6", "M3", "M8", "M9", "M5", "M30"], "{text}");
    // Moves after the End event are not written.
    let mut ended = small_path();
    ended.events.last_mut().unwrap().before_move = 2;
    let text = write_program(&ended, &options(Dialect::LinuxCnc, false));
    assert!(text.ends_with("G1 Z-1 F200\nG0 Z50\nM5\nM2\n"), "{text}");
}

#[test]
fn a_dwell_is_g4_p_for_linuxcnc_and_g4_x_for_fanuc_and_both_read_back_in_seconds() {
    for dialect in [Dialect::Fanuc, Dialect::LinuxCnc] {
        let text = write_program(&small_path(), &options(dialect, false));
        let read = parse_gcode(&text, &ParseOptions::default()).unwrap();
        let dwell = read.events.iter().find(|e| matches!(e.kind, EventKind::Dwell { .. })).unwrap();
        let EventKind::Dwell { seconds } = dwell.kind else { unreachable!() };
        assert!((seconds - 0.5).abs() < 1e-12, "{seconds}");
    }
}

#[test]
fn n_numbers_restart_after_the_largest_the_controls_read() {
    let numbers = LineNumbers { start: MAX_SEQUENCE_NUMBER - 1, step: 1 };
    let options = WriterOptions { line_numbers: Some(numbers), ..options(Dialect::LinuxCnc, false) };
    let text = write_program(&lines_with_feeds(&[100.0]), &options);
    let n: Vec<String> = text.lines().map(|l| l.split(' ').next().unwrap_or("").to_string()).collect();
    assert_eq!(n[..4], ["N99998", "N99999", "N99998", "N99999"], "{text}");
}

#[test]
fn an_arc_smaller_than_the_resolution_is_a_g1_and_a_nearly_full_one_a_full_circle() {
    let centre = at(0.0, 0.0, 0.0);
    let tiny = (arc(centre, false, Plane::Xy, 0), at(5.0, 0.000_2, 0.0), Some(100.0), None);
    let nearly_full = (arc(centre, false, Plane::Xy, 0), at(5.0, -0.000_2, 0.0), Some(100.0), None);
    let steps = [(Motion::Rapid, at(5.0, 0.0, 0.0), None, None), tiny, nearly_full];
    let path = path_of(chain(at(0.0, 0.0, 50.0), &steps), vec![]);
    let text = write_program(&path, &options(Dialect::LinuxCnc, false));
    // The tiny arc ends where the written position is: nothing to write.
    assert!(text.contains("\nX5 Y0\nZ0\nG3 I-5 J0 F100\nG0 Z50\n"), "{text}");
}

#[test]
fn an_arc_whose_rounded_centre_fails_the_radius_check_gets_a_neighbouring_grid_centre() {
    // Found by search: rounding start, end and centre to 0.001 mm makes the radii differ
    // by 2.05 µm, more than the parser's 2 µm.
    let (cx, cy, r, a0, sweep): (f64, f64, f64, f64, f64) = (
        2.297_510_726_815_4,
        4.660_233_820_326_955,
        0.955_018_061_768_090_2,
        2.618_012_426_766_942_5,
        3.599_535_207_568_867,
    );
    let start = at(cx + r * a0.cos(), cy + r * a0.sin(), 0.0);
    let end = at(cx + r * (a0 + sweep).cos(), cy + r * (a0 + sweep).sin(), 0.0);
    let centre = at(cx, cy, 0.0);
    let rounded = |p: P3| at(Fixed::round(p.x, 3).value(), Fixed::round(p.y, 3).value(), 0.0);
    assert!(check_arc(rounded(start), rounded(centre), rounded(end), Plane::Xy).is_err());
    let steps = [(Motion::Rapid, start, None, None), (arc(centre, false, Plane::Xy, 0), end, Some(100.0), None)];
    let path = path_of(chain(at(0.0, 0.0, 50.0), &steps), vec![]);
    let text = write_program(&path, &options(Dialect::Fanuc, false));
    let read = parse_gcode(&text, &ParseOptions::default()).unwrap_or_else(|e| panic!("{e}\n{text}"));
    let arc = read.moves.iter().find(|m| matches!(m.motion, Motion::Arc { .. }));
    let Some(Motion::Arc { center, .. }) = arc.map(|m| m.motion) else { panic!("no arc: {text}") };
    assert!((center.x - cx).abs() <= 1e-3 && (center.y - cy).abs() <= 1e-3, "{center:?}");
}

#[test]
fn options_come_from_json_with_defaults_and_unknown_fields_are_refused() {
    let json = r#"{"dialect": "linux_cnc", "line_numbers": {"start": 100}, "decimals": 4}"#;
    let options: WriterOptions = serde_json::from_str(json).unwrap();
    assert_eq!(options.dialect, Dialect::LinuxCnc);
    assert_eq!(options.line_numbers, Some(LineNumbers { start: 100, step: 10 }));
    assert_eq!((options.decimals, options.feed_decimals, options.program_number), (4, 1, 1));
    assert_eq!(options.coolant, Coolant::Off, "no coolant unless asked");
    let mist: WriterOptions =
        serde_json::from_str(r#"{"coolant": "mist", "length_offset": 21, "safe_z_mm": 25}"#).unwrap();
    assert_eq!((mist.coolant, mist.length_offset, mist.safe_z_mm), (Coolant::Mist, Some(21), Some(25.0)));
    let alias: WriterOptions = serde_json::from_str(r#"{"dialect": "linuxcnc"}"#).unwrap();
    assert_eq!(alias.dialect, Dialect::LinuxCnc);
    assert!(serde_json::from_str::<WriterOptions>(r#"{"dialekt": "fanuc"}"#).is_err());
    assert_eq!(serde_json::from_str::<WriterOptions>("{}").unwrap(), WriterOptions::default());
}
