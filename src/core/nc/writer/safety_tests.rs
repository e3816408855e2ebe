//! The rules every written program follows, one test each, and a property test of the
//! output read back: Z alone to the safe height before any XY move (at the start and after
//! every tool change), `T… M6` and `G43 H…`, no rapid in XY and Z at once, a comment before
//! each part, the footer's retract, N numbers, and no coolant unless asked.

use proptest::prelude::*;

use super::round_trip_tests::random_case;
use super::*;
use crate::core::nc::{parse_gcode, ParseOptions};
use crate::core::toolpath::{Section, Step, Units};

/// Room for the written resolution, mm.
const TOL_MM: f64 = 1e-3;

/// Where the parser has the tool before the program: nowhere near the paths (the machine's
/// position is unknown), so that every XY move the writer makes to enter is seen.
const UNKNOWN_POSITION: P3 = P3::new(-7_777.7, 8_888.8, 0.0);

fn rapid(from: P3, to: P3) -> Move {
    Move {
        motion: Motion::Rapid,
        start: from,
        end: to,
        feed_mm_min: None,
        spindle_rpm: Some(4800.0),
        tool: None,
        line: 0,
    }
}

fn line(from: P3, to: P3) -> Move {
    Move { motion: Motion::Linear, feed_mm_min: Some(2880.0), ..rapid(from, to) }
}

fn path(moves: Vec<Move>, events: Vec<(EventKind, usize)>) -> Toolpath {
    let events = events.into_iter().map(|(kind, before_move)| Event { kind, before_move, line: 0 }).collect();
    Toolpath { moves, events, source_units: Units::Mm, warnings: Vec::new() }
}

/// A planner's path in short: from the safe height (5) down to 1 over (50, 25), a plunge, a
/// cut, and back up.
fn planner_like() -> Toolpath {
    let p = |x, z| P3::new(x, 25.0, z);
    path(
        vec![
            rapid(p(50.0, 5.0), p(50.0, 1.0)),
            line(p(50.0, 1.0), p(50.0, -10.0)),
            line(p(50.0, -10.0), p(60.0, -10.0)),
            rapid(p(60.0, -10.0), p(60.0, 5.0)),
        ],
        vec![(EventKind::SpindleOn { clockwise: true }, 0), (EventKind::SpindleOff, 4)],
    )
}

fn lines_of(text: &str) -> Vec<&str> {
    text.lines().collect()
}

#[test]
fn the_program_calls_its_tool_then_moves_z_alone_to_the_safe_height_before_its_first_xy_move() {
    let text = write_program(&planner_like(), &WriterOptions::default());
    assert_eq!(
        lines_of(&text)[2..9],
        ["G21 G17 G90 G94 G40 G80 G49", "T1 M6", "G0 G43 H1 Z5.", "S4800 M3", "X50. Y25.", "Z1.", "G1 Z-10. F2880."],
        "{text}"
    );
}

#[test]
fn the_tool_and_length_offset_numbers_come_from_the_options_the_path_or_t1() {
    let named = WriterOptions { tool_number: Some(12), length_offset: Some(32), ..WriterOptions::default() };
    assert!(write_program(&planner_like(), &named).contains("\nT12 M6\nG0 G43 H32 Z5.\n"));
    let mut own = planner_like();
    own.moves.iter_mut().for_each(|m| m.tool = Some(4));
    assert!(write_program(&own, &WriterOptions::default()).contains("\nT4 M6\nG0 G43 H4 Z5.\n"));
    assert!(write_program(&planner_like(), &WriterOptions::default()).contains("\nT1 M6\nG0 G43 H1 Z5.\n"));
}

#[test]
fn a_tool_change_in_the_path_retracts_z_alone_calls_the_tool_and_comes_back_down_over_the_next_point() {
    let mut p = planner_like();
    p.events.insert(1, Event { kind: EventKind::ToolChange { tool: 4 }, before_move: 2, line: 0 });
    let text = write_program(&p, &WriterOptions { dialect: Dialect::LinuxCnc, ..WriterOptions::default() });
    assert!(
        text.contains("G1 Z-10 F2880\nG0 Z5\nT4 M6\nG0 G43 H4 Z5\nX50 Y25\nZ-10\nG1 X60\n"),
        "the feed move after the change starts where the tool was: {text}"
    );
}

#[test]
fn a_rapid_in_xy_and_z_rises_in_z_first_and_descends_in_xy_first() {
    let (a, b, c) = (P3::new(0.0, 0.0, -5.0), P3::new(30.0, 10.0, 2.0), P3::new(40.0, 0.0, -1.0));
    let p = path(
        vec![rapid(P3::new(0.0, 0.0, 5.0), a), rapid(a, b), rapid(b, c), line(c, P3::new(50.0, 0.0, -1.0))],
        vec![],
    );
    let text = write_program(&p, &WriterOptions { dialect: Dialect::LinuxCnc, ..WriterOptions::default() });
    assert!(text.contains("\nX0 Y0\nZ-5\nZ2\nX30 Y10\nX40 Y0\nZ-1\nG1 X50 F2880\n"), "{text}");
}

#[test]
fn the_safe_height_is_the_options_or_the_paths_highest_point_whichever_is_higher() {
    let higher = WriterOptions { safe_z_mm: Some(25.0), ..WriterOptions::default() };
    let text = write_program(&planner_like(), &higher);
    assert!(text.contains("G0 G43 H1 Z25.\n") && text.ends_with("G0 Z5.\nZ25.\nM5\nM30\n%\n"), "{text}");
    let lower = WriterOptions { safe_z_mm: Some(2.0), ..WriterOptions::default() };
    assert!(write_program(&planner_like(), &lower).contains("G0 G43 H1 Z5.\n"));
    // An arc in the ZX plane rises above its ends: the top of its circle counts.
    let over = Move {
        motion: Motion::Arc { center: P3::new(10.0, 0.0, 0.0), clockwise: true, plane: Plane::Zx, turns: 0 },
        ..line(P3::new(0.0, 0.0, 0.0), P3::new(20.0, 0.0, 0.0))
    };
    assert_eq!(highest_point_mm(&path(vec![over], vec![])), Some(10.0));
    assert_eq!(highest_point_mm(&path(vec![], vec![])), None);
}

#[test]
fn the_footer_retracts_z_alone_then_stops_the_spindle_and_the_coolant_before_the_end() {
    let mut p = planner_like();
    p.moves.pop();
    p.events.retain(|e| e.kind != EventKind::SpindleOff);
    for (dialect, tail) in
        [(Dialect::Fanuc, "\nX60.\nG0 Z5.\nM5\nM9\nM30\n%\n"), (Dialect::LinuxCnc, "\nX60\nG0 Z5\nM5\nM9\nM2\n")]
    {
        let options = WriterOptions { dialect, coolant: Coolant::Mist, ..WriterOptions::default() };
        let text = write_program(&p, &options);
        assert!(text.ends_with(tail), "{text}");
    }
}

#[test]
fn no_coolant_is_written_unless_asked_and_mist_is_m7_and_flood_m8() {
    let words = |coolant| {
        let text = write_program(&planner_like(), &WriterOptions { coolant, ..WriterOptions::default() });
        text.split_whitespace().filter(|w| w.starts_with('M')).map(str::to_string).collect::<Vec<_>>()
    };
    assert_eq!(words(Coolant::Off), ["M6", "M3", "M5", "M30"]);
    assert_eq!(words(Coolant::Mist), ["M6", "M3", "M7", "M5", "M9", "M30"]);
    assert_eq!(words(Coolant::Flood), ["M6", "M3", "M8", "M5", "M9", "M30"]);
}

/// The planner-like path with a label before the plunge and another before the cut.
fn labelled() -> Toolpath {
    let mut p = planner_like();
    let boring = Section { layer: 0, z_mm: -10.0, step: Step::HelicalBoring, region: Some(0) };
    let rough = Section { layer: 1, z_mm: -20.0, step: Step::RoughSideCutting, region: None };
    p.events.insert(1, Event { kind: EventKind::Section(boring), before_move: 0, line: 1 });
    p.events.insert(2, Event { kind: EventKind::Section(rough), before_move: 2, line: 3 });
    p
}

#[test]
fn each_section_label_is_a_comment_before_its_part_in_both_dialects() {
    let fanuc = write_program(&labelled(), &WriterOptions::default());
    assert!(
        fanuc.contains("S4800 M3\n(LAYER 1 Z-10 HELICAL BORING REGION 1)\nX50. Y25.\n")
            && fanuc.contains("G1 Z-10. F2880.\n(LAYER 2 Z-20 ROUGH SIDE CUTTING)\nX60.\n"),
        "{fanuc}"
    );
    let linuxcnc =
        write_program(&labelled(), &WriterOptions { dialect: Dialect::LinuxCnc, ..WriterOptions::default() });
    assert!(linuxcnc.contains("\n(LAYER 2 Z-20 ROUGH SIDE CUTTING)\nX60\n"), "{linuxcnc}");
    // Labels are comments: the program reads back with the same moves and other events.
    let read = |text: &str| {
        let mut p = parse_gcode(text, &ParseOptions::default()).unwrap();
        p.moves.iter_mut().for_each(|m| m.line = 0);
        p.events.iter_mut().for_each(|e| e.line = 0);
        p
    };
    assert_eq!(read(&fanuc), read(&write_program(&planner_like(), &WriterOptions::default())));
}

#[test]
fn n_numbers_go_on_every_line_but_the_tape_marks_and_the_o_line_comments_included() {
    let options = WriterOptions { line_numbers: Some(LineNumbers { start: 5, step: 5 }), ..WriterOptions::default() };
    let text = write_program(&labelled(), &options);
    let numbered: Vec<&str> = text.lines().filter(|l| !l.starts_with('%') && !l.starts_with('O')).collect();
    for (k, l) in numbered.iter().enumerate() {
        assert!(l.starts_with(&format!("N{} ", 5 * (k + 1))), "{l}\n{text}");
    }
    assert!(text.contains(" (LAYER 1 Z-10 HELICAL BORING REGION 1)\n") && text.contains(" G0 G43 H1 Z5.\n"));
    parse_gcode(&text, &ParseOptions::default()).unwrap_or_else(|e| panic!("{e}\n{text}"));
}

#[test]
fn a_path_without_moves_still_calls_its_tool_and_ends() {
    let empty = path(vec![], vec![]);
    assert_eq!(
        write_program(&empty, &WriterOptions { dialect: Dialect::LinuxCnc, ..WriterOptions::default() }),
        "G21 G17 G90 G94 G40 G80 G49\nT1 M6\nG43 H1\nM2\n"
    );
    let safe = WriterOptions { dialect: Dialect::LinuxCnc, safe_z_mm: Some(10.0), ..WriterOptions::default() };
    assert_eq!(write_program(&empty, &safe), "G21 G17 G90 G94 G40 G80 G49\nT1 M6\nG0 G43 H1 Z10\nM2\n");
}

/// The parsed program's feed moves: the path's, Fanuc's arcs with turns in pieces.
fn path_cuts(path: &Toolpath, dialect: Dialect) -> Vec<Move> {
    let end = path.events.iter().filter(|e| e.kind == EventKind::End).map(|e| e.before_move).min();
    let moves = &path.moves[..end.unwrap_or(path.moves.len()).min(path.moves.len())];
    moves
        .iter()
        .filter(|m| !matches!(m.motion, Motion::Rapid))
        .flat_map(|m| if dialect == Dialect::Fanuc { split_turns(m) } else { vec![*m] })
        .collect()
}

/// The words of a line, its N number and comment left out.
fn words_of(line: &str) -> Vec<&str> {
    let code = line.split('(').next().unwrap_or("");
    code.split_whitespace().filter(|w| !w.starts_with('N')).collect()
}

/// After every `M6` line: `G0 G43 H… Z<safe>`, then no Z word and no feed motion until a
/// line that moves in X or Y and not in Z (the machine's XY is unknown after a tool
/// change, so the writer always writes it).
fn assert_z_alone_to_safe_height_after_every_tool_call(text: &str, safe: f64) -> Result<(), TestCaseError> {
    let lines: Vec<Vec<&str>> = text.lines().map(words_of).collect();
    let value = |w: &str| w[1..].parse::<f64>().unwrap_or(f64::NAN);
    for (k, _) in lines.iter().enumerate().filter(|(_, l)| l.contains(&"M6")) {
        let call = &lines[k + 1];
        prop_assert!(
            call.starts_with(&["G0", "G43"]) && call[2].starts_with('H'),
            "line {}: {:?}\n{}",
            k + 2,
            call,
            text
        );
        let z = call.iter().find(|w| w.starts_with('Z')).map(|w| value(w));
        prop_assert!(
            z.is_some_and(|z| (z - safe).abs() <= TOL_MM),
            "line {}: {:?}, safe {safe}\n{}",
            k + 2,
            call,
            text
        );
        // Up to the first XY move, or the next tool call.
        let stop = |l: &Vec<&str>| l.iter().any(|w| w.starts_with('X') || w.starts_with('Y') || *w == "M6");
        let Some(xy) = lines[k + 2..].iter().position(stop) else {
            continue;
        };
        let upto = if lines[k + 2 + xy].contains(&"M6") { k + 2 + xy } else { k + 3 + xy };
        for l in &lines[k + 2..upto] {
            let forbidden = |w: &&str| w.starts_with('Z') || ["G1", "G2", "G3"].contains(w);
            prop_assert!(!l.iter().any(forbidden), "{:?} before the first XY move after line {}\n{}", l, k + 2, text);
        }
    }
    Ok(())
}

fn moves_xy(m: &Move) -> bool {
    (m.end.x - m.start.x).abs() > TOL_MM / 2.0 || (m.end.y - m.start.y).abs() > TOL_MM / 2.0
}

proptest! {
    #[test]
    fn any_written_path_goes_to_the_safe_height_in_z_alone_before_any_xy_move_and_reads_back_to_the_same_cuts(
        (path, options) in random_case()
    ) {
        let text = write_program(&path, &options);
        let parse = ParseOptions { initial_position: UNKNOWN_POSITION, ..ParseOptions::default() };
        let read = parse_gcode(&text, &parse).map_err(|e| TestCaseError::fail(format!("{e}\n{text}")))?;
        let safe = options.safe_z_mm.unwrap_or(f64::NEG_INFINITY).max(highest_point_mm(&path).unwrap_or(0.0));
        // At the start and after every tool change: Z alone, then XY at the safe height.
        assert_z_alone_to_safe_height_after_every_tool_call(&text, safe)?;
        // Read back from an unknown position: nothing moves in XY before Z is at the safe
        // height, and the first XY move is made there.
        let first_xy = read.moves.iter().position(moves_xy).unwrap_or(read.moves.len());
        prop_assert!(read.moves[..first_xy].iter().all(|m| !moves_xy(m)));
        if let Some(m) = read.moves.get(first_xy) {
            prop_assert!((m.start.z - safe).abs() <= TOL_MM && (m.end.z - safe).abs() <= TOL_MM, "{:?}\n{}", m, text);
        }
        let calls_first = read.events.first().is_some_and(|e| matches!(e.kind, EventKind::ToolChange { .. }) && e.before_move == 0);
        prop_assert!(calls_first, "{}", text);
        // No rapid in XY and Z at once; the program ends at the safe height.
        for m in read.moves.iter().filter(|m| matches!(m.motion, Motion::Rapid)) {
            prop_assert!(!moves_xy(m) || (m.end.z - m.start.z).abs() <= TOL_MM / 2.0, "{:?}\n{}", m, text);
        }
        prop_assert!(read.moves.last().is_some_and(|m| (m.end.z - safe).abs() <= TOL_MM), "{}", text);
        // The same cuts, in order.
        let cuts: Vec<&Move> = read.moves.iter().filter(|m| !matches!(m.motion, Motion::Rapid)).collect();
        let want = path_cuts(&path, options.dialect);
        prop_assert_eq!(cuts.len(), want.len());
        for (got, want) in cuts.iter().zip(&want) {
            let near = |p: P3, q: P3| (p.x - q.x).abs() <= TOL_MM && (p.y - q.y).abs() <= TOL_MM && (p.z - q.z).abs() <= TOL_MM;
            prop_assert!(near(got.start, want.start) && near(got.end, want.end), "{:?} vs {:?}", got, want);
            prop_assert_eq!(std::mem::discriminant(&got.motion), std::mem::discriminant(&want.motion));
        }
    }
}
