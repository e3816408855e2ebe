//! Tests of the whole parser on the real programs in `shared/data`, and its throughput.

use std::hint::black_box;
use std::time::{Duration, Instant};

use super::*;
use crate::core::tolerance::approx_eq;
use crate::core::toolpath::{EventKind, Motion};

/// Feeds and speeds in the files are written with few decimals: read exactly.
const VALUE_TOL: f64 = 1e-9;

fn data(name: &str) -> String {
    let path = format!("{}/../shared/data/{name}", env!("CARGO_MANIFEST_DIR"));
    std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{path}: {e}"))
}

/// Lines whose first word is a G0 or G1 motion code.
fn motion_lines(text: &str) -> usize {
    text.lines().filter(|l| l.starts_with("G0 ") || l.starts_with("G1 ")).count()
}

#[test]
fn tiger_gives_one_move_per_motion_line_with_feed_and_speed_as_written() {
    let text = data("tiger.nc");
    let path = parse_gcode(&text, &ParseOptions::default()).unwrap();
    // Every G0/G1 line of tiger.nc moves the tool (none is of zero length).
    assert_eq!(motion_lines(&text), 67_424);
    assert_eq!(path.moves.len(), 67_424);
    assert!(path.warnings.is_empty(), "{:?}", path.warnings);
    let first = path.moves[0];
    assert_eq!((first.motion, first.line), (Motion::Rapid, 2));
    assert_eq!((first.feed_mm_min, first.spindle_rpm), (None, None));
    // Line 3: `G1 Y-1.833 Z0.000 F300 S2000`.
    let second = path.moves[1];
    assert_eq!((second.motion, second.line), (Motion::Linear, 3));
    assert!(approx_eq(second.feed_mm_min.unwrap(), 300.0, VALUE_TOL));
    assert!(approx_eq(second.spindle_rpm.unwrap(), 2000.0, VALUE_TOL));
    assert!(approx_eq(second.end.z, 0.0, VALUE_TOL));
    // Line 4: `G1 Y-1.833 Z-10.000 F150`, the speed stays.
    let third = path.moves[2];
    assert_eq!(third.line, 4);
    assert!(approx_eq(third.feed_mm_min.unwrap(), 150.0, VALUE_TOL));
    assert!(approx_eq(third.spindle_rpm.unwrap(), 2000.0, VALUE_TOL));
    assert_eq!(path.events[0].kind, EventKind::SpindleOn { clockwise: true });
    let end = path.events.last().unwrap();
    assert_eq!((end.kind, end.before_move), (EventKind::End, 67_424));
}

#[test]
fn trochoidal_parses_and_ends_with_its_m30() {
    let text = data("trochoidal.ngc");
    let path = parse_gcode(&text, &ParseOptions::default()).unwrap();
    // 11 357 G0/G1 lines; 6 repeat the position they start from (`G1 Z5` after `G0 Z5`,
    // `G1 Y43.636` after plunging there) and are dropped.
    assert_eq!(motion_lines(&text), 11_357);
    assert_eq!(path.moves.len(), 11_351);
    assert!(path.warnings.is_empty(), "{:?}", path.warnings);
    let last_line = u32::try_from(text.lines().count()).unwrap();
    let end = path.events.last().unwrap();
    assert_eq!((end.kind, end.line), (EventKind::End, last_line));
    assert_eq!(end.before_move, path.moves.len());
    // F300 on line 14, F3600 on line 18, F150 on line 11373.
    let feed_at = |line: u32| match line {
        ..18 => 300.0,
        18..11_373 => 3600.0,
        _ => 150.0,
    };
    assert!(path.moves.iter().all(|m| approx_eq(m.feed_mm_min.unwrap(), feed_at(m.line), VALUE_TOL)));
}

#[test]
#[ignore = "prints throughput: cargo test --release -- --ignored --nocapture throughput"]
fn parse_throughput_is_printed_in_mb_per_s() {
    const RUNS: usize = 30;
    let options = ParseOptions::default();
    for name in ["tiger.nc", "trochoidal.ngc"] {
        let text = data(name);
        let mut times = Vec::with_capacity(RUNS);
        for _ in 0..RUNS {
            let started = Instant::now();
            let path = parse_gcode(black_box(&text), &options).unwrap();
            times.push(started.elapsed());
            black_box(path);
        }
        times.sort();
        let rate = |t: Duration| text.len() as f64 / t.as_secs_f64() / 1e6;
        println!(
            "{name}: {} bytes, median {:.0} MB/s, best {:.0} MB/s ({RUNS} runs)",
            text.len(),
            rate(times[RUNS / 2]),
            rate(times[0])
        );
    }
}

mod gcode {
    //! The G-code features, one program each.

    use super::*;
    use crate::core::error::CoreError;
    use crate::core::toolpath::{Move, Toolpath, Units, P3};

    /// Coordinates in these programs are short decimals; results match to rounding.
    const TOL_MM: f64 = 1e-9;

    fn parse(text: &str) -> Toolpath {
        parse_gcode(text, &ParseOptions::default()).unwrap_or_else(|e| panic!("{e}"))
    }

    fn errors(text: &str) -> Vec<NcError> {
        parse_gcode(text, &ParseOptions::default()).unwrap_err().0
    }

    fn at(m: &Move, x: f64, y: f64, z: f64) -> bool {
        approx_eq(m.end.x, x, TOL_MM) && approx_eq(m.end.y, y, TOL_MM) && approx_eq(m.end.z, z, TOL_MM)
    }

    #[test]
    fn comments_of_both_kinds_percent_lines_and_n_words_are_read_around() {
        let path = parse(
            "%\n(header; with a semicolon)\nN10 G0 X1 (inline) Y2 (twice) ; the rest Z9\n\n\
             n20 g1 x3 f100 ; done\n%\n",
        );
        assert_eq!(path.moves.len(), 2);
        assert!(at(&path.moves[0], 1.0, 2.0, 0.0));
        assert_eq!(path.moves[0].line, 3);
        assert!(at(&path.moves[1], 3.0, 2.0, 0.0));
        assert_eq!(path.moves[1].line, 5);
    }

    #[test]
    fn spaces_signs_and_lower_case_are_read_as_in_the_spec() {
        let path = parse("g0x1 Y -2.\tz .5\nG01 X +2.5 F 100");
        assert!(at(&path.moves[0], 1.0, -2.0, 0.5));
        assert!(at(&path.moves[1], 2.5, -2.0, 0.5));
    }

    #[test]
    fn crlf_line_ends_an_empty_program_and_fanuc_g80_g0_lines_are_read() {
        let path = parse("G0 X1\r\nG80 G0 X2\r\n\r\n");
        assert_eq!(path.moves.len(), 2);
        assert!(at(&path.moves[1], 2.0, 0.0, 0.0));
        let empty = parse("");
        assert!(empty.moves.is_empty() && empty.events.is_empty() && empty.warnings.is_empty());
        assert!(errors("G80 X1")[0].reason.contains("G80 ends the motion mode"));
    }

    #[test]
    fn a_line_with_axis_words_only_uses_the_modal_motion() {
        let path = parse("G1 X1 F100\nY1\nG0 Z5\nX0");
        let kinds: Vec<_> = path.moves.iter().map(|m| m.motion).collect();
        assert_eq!(kinds, [Motion::Linear, Motion::Linear, Motion::Rapid, Motion::Rapid]);
    }

    #[test]
    fn the_first_move_starts_at_the_initial_position() {
        let options = ParseOptions { initial_position: P3::new(1.0, 2.0, 50.0), ..ParseOptions::default() };
        let path = parse_gcode("G0 X5", &options).unwrap();
        assert_eq!(path.moves[0].start, P3::new(1.0, 2.0, 50.0));
        assert!(at(&path.moves[0], 5.0, 2.0, 50.0));
    }

    #[test]
    fn g91_moves_add_to_the_position_until_g90() {
        let path = parse("G0 X10 Y10\nG91 G1 X1 Y-2 F100\nX1\nG90 X0");
        assert!(at(&path.moves[1], 11.0, 8.0, 0.0));
        assert!(at(&path.moves[2], 12.0, 8.0, 0.0));
        assert!(at(&path.moves[3], 0.0, 8.0, 0.0));
    }

    #[test]
    fn an_inch_program_is_stored_in_mm_feed_included() {
        let path = parse("G20\nG1 X1 Y-2 F10\nG2 X3 Y-2 I1 J2");
        let m = path.moves[0];
        assert!(at(&m, 25.4, -50.8, 0.0));
        assert!(approx_eq(m.feed_mm_min.unwrap(), 254.0, TOL_MM));
        assert!(at(&path.moves[1], 76.2, -50.8, 0.0));
        match path.moves[1].motion {
            Motion::Arc { center, .. } => {
                assert!(approx_eq(center.x, 50.8, TOL_MM) && approx_eq(center.y, 0.0, TOL_MM))
            }
            other => panic!("{other:?}"),
        }
        assert_eq!(path.source_units, Units::Inch);
        assert_eq!(parse("G20\nG21 G0 X1").source_units, Units::Mm);
    }

    #[test]
    fn spindle_tool_coolant_dwell_and_stop_become_events_between_moves() {
        let path = parse("T3 M6\nS8000 M3\nM8\nG0 X1\nG4 P0.5\nM0\nG1 X2 F100\nM9 M5\nM30\nG0 X99\nthis is not G-code");
        let kinds: Vec<_> = path.events.iter().map(|e| (e.kind, e.before_move, e.line)).collect();
        assert_eq!(
            kinds,
            [
                (EventKind::ToolChange { tool: 3 }, 0, 1),
                (EventKind::SpindleOn { clockwise: true }, 0, 2),
                (EventKind::Coolant { on: true }, 0, 3),
                (EventKind::Dwell { seconds: 0.5 }, 1, 5),
                (EventKind::Stop, 1, 6),
                (EventKind::SpindleOff, 2, 8),
                (EventKind::Coolant { on: false }, 2, 8),
                (EventKind::End, 2, 9),
            ]
        );
        assert_eq!(path.moves.len(), 2);
        assert_eq!((path.moves[0].tool, path.moves[0].spindle_rpm), (Some(3), Some(8000.0)));
    }

    #[test]
    fn a_t_word_takes_effect_at_m6_and_m6_needs_one() {
        let path = parse("T1 M6\nT2\nG0 X1\nM6\nG0 X2");
        assert_eq!(path.moves[0].tool, Some(1));
        assert_eq!(path.moves[1].tool, Some(2));
        assert!(errors("M6")[0].reason.contains("T word"));
    }

    #[test]
    fn accepted_modal_codes_change_nothing_and_a_g64_tolerance_is_a_warning() {
        let path = parse("G17 G21 G40 G49 G54 G61 G80 G90 G94 G98 G15 G69\nG43 H1\nG59.3 G61.1\nG64 P0.01 Q0.005\nG64");
        assert!(path.moves.is_empty() && path.events.is_empty());
        assert_eq!(path.warnings, ["line 4: the G64 blending tolerance (P/Q) is ignored"]);
    }

    #[test]
    fn a_zero_length_move_is_dropped_but_its_feed_still_applies() {
        let path = parse("G0 Z5\nG1 Z5 F200\nG1 X1");
        assert_eq!(path.moves.len(), 2);
        assert_eq!(path.moves[1].feed_mm_min, Some(200.0));
    }

    #[test]
    fn a_block_delete_line_is_read_with_a_warning() {
        let path = parse("/G0 X1");
        assert_eq!(path.moves.len(), 1);
        assert_eq!(path.warnings, ["line 1: block delete (/) is not honoured: the line is read"]);
    }

    #[test]
    fn an_unknown_word_is_rejected_with_its_line_and_column_or_warned_about() {
        let text = "G0 X1\nG1 X2 E5 F100\nG12.5 X3\n";
        let e = errors(text);
        assert_eq!((e[0].line, e[0].column, e[0].word.as_str()), (2, 7, "E5"));
        assert_eq!((e[1].line, e[1].column, e[1].word.as_str()), (3, 1, "G12.5"));
        assert_eq!(e[0].to_string(), format!("line 2, column 7 (E5): {}", e[0].reason));
        let options = ParseOptions { unknown_words: UnknownWords::Warn, ..ParseOptions::default() };
        let path = parse_gcode(text, &options).unwrap();
        assert_eq!(path.moves.len(), 3);
        assert_eq!(path.warnings, ["line 2: unknown word E5 ignored", "line 3: unknown word G12.5 ignored"]);
    }

    #[test]
    fn a_very_long_word_is_quoted_by_its_first_characters_not_echoed_whole() {
        let digits = "9".repeat(400);
        let e = errors(&format!("G1 X{digits} F100\n(é{}", "c".repeat(500)));
        let quoted = format!("X{}…", &digits[..MAX_QUOTED_WORD_CHARS - 1]);
        assert_eq!((e[0].line, e[0].column, e[0].word.as_str()), (1, 4, quoted.as_str()));
        assert_eq!((e[1].line, e[1].word.chars().count()), (2, MAX_QUOTED_WORD_CHARS + 1));
        assert!(e[1].word.starts_with("(éccc") && e[1].reason.contains("not closed"), "{:?}", e[1]);
    }

    #[test]
    fn columns_count_characters_after_a_comment_with_accents() {
        let e = errors("(côté) G0 D1");
        assert_eq!((e[0].column, e[0].word.as_str()), (11, "D1"));
    }

    #[test]
    fn what_cannot_be_planned_is_refused_with_its_reason_even_when_unknown_words_are_warnings() {
        let options = ParseOptions { unknown_words: UnknownWords::Warn, ..ParseOptions::default() };
        let cases = [
            ("G38.2 Z-10 F100", "G38.2", "probe"),
            ("G0 A90", "A90", "rotary"),
            ("G51 X0 Y0 P2", "G51", "scaling"),
            ("G68 X0 Y0 R30", "G68", "rotation"),
            ("G7", "G7", "lathe"),
            ("G5.2 X1 Y1 P1 L3", "G5.2", "NURBS"),
            ("G16", "G16", "polar"),
            ("G43.4 H1", "G43.4", "5-axis"),
            ("G87 X0 Y0 Z-5 R2 F100", "G87", "operator"),
        ];
        for (text, word, reason) in cases {
            let e = parse_gcode(text, &options).unwrap_err().0;
            let hit = e.iter().find(|e| e.word == word).unwrap_or_else(|| panic!("{text}: {e:?}"));
            assert!(hit.reason.contains(reason), "{text}: {}", hit.reason);
        }
    }

    #[test]
    fn a_fanuc_program_number_before_the_first_words_is_ignored() {
        for text in ["%\nO0001 (DIE 12)\nG0 X1\n%\n", "(post v2)\n\no1234\nG0 X1", "O12 ; number\r\nG0 X1"] {
            let path = parse(text);
            assert_eq!(path.moves.len(), 1, "{text}");
            assert!(path.warnings.is_empty(), "{text}: {:?}", path.warnings);
        }
    }

    #[test]
    fn an_o_word_with_other_words_or_without_a_keyword_is_refused() {
        for (text, line, word, reason) in [
            ("O100 G0 X1", 1, "O100 G0 X1", "needs a keyword"),
            ("G0 X1\no100 sub G0 X2\no100 endsub", 2, "o100 sub", "alone"),
        ] {
            let e = errors(text);
            assert_eq!((e[0].line, e[0].word.as_str()), (line, word), "{text}: {e:?}");
            assert!(e[0].reason.contains(reason), "{text}: {}", e[0].reason);
        }
    }

    #[test]
    fn a_fanuc_g4_x_dwell_is_read_in_seconds_and_does_not_move() {
        let path = parse("G0 X5\nG4 X1.5\nG4 P2 X7");
        assert_eq!(path.events[0].kind, EventKind::Dwell { seconds: 1.5 });
        assert_eq!(path.events[1].kind, EventKind::Dwell { seconds: 2.0 });
        // With P, X is an axis word, as LinuxCNC reads it.
        assert_eq!(path.moves.len(), 2);
        assert!(at(&path.moves[1], 7.0, 0.0, 0.0));
        assert!(errors("G4 X-1")[0].reason.contains("negative"));
    }

    #[test]
    fn malformed_words_are_errors_naming_them() {
        let cases = [
            ("G1 X F100", "X", "followed by a number"),
            ("G0 X1 X2", "X2", "two X words"),
            ("G0 G1 X1 F1", "G1", "two motion codes"),
            ("G17 G18", "G18", "same modal group"),
            ("M3 M5", "M5", "same group"),
            ("G1 X1", "G1", "no feed rate"),
            ("G1 X1 F0", "F0", "> 0"),
            ("X1", "X1", "no motion mode"),
            ("G0 X1 P2", "P2", "P needs"),
            ("G1 X1 I2 F100", "I2", "G2 or G3"),
            ("G0 (open", "(open", "not closed"),
            ("T1.5", "T1.5", "non-negative integer"),
            ("G4", "G4", "P, the dwell"),
        ];
        for (text, word, reason) in cases {
            let e = errors(text);
            let hit = e.iter().find(|e| e.word == word).unwrap_or_else(|| panic!("{text}: {e:?}"));
            assert!(hit.reason.contains(reason), "{text}: {}", hit.reason);
        }
    }

    #[test]
    fn errors_are_collected_from_several_lines_and_a_bad_line_changes_nothing() {
        let text = "G0 X1\nG1 X2 F100 Q1\nG0 X3 E1\nG2 X1 Y0 I1 J5\nG0 Y1";
        let e = errors(text);
        let lines: Vec<u32> = e.iter().map(|e| e.line).collect();
        assert_eq!(lines, [2, 3, 4]);
        // Line 2 failed, so its F100 never applied: the G1 on line 4 has no feed either.
        assert!(e[2].reason.contains("no feed rate"), "{}", e[2].reason);
        let many = "G0 X1 E1\n".repeat(MAX_NC_ERRORS + 50);
        assert_eq!(errors(&many).len(), MAX_NC_ERRORS);
    }

    #[test]
    fn a_line_of_many_bad_words_keeps_the_first_errors_with_their_columns() {
        // 200 000 repeated words on one line: each is an error, and locating each anew
        // used to walk the line from its start.
        let line = format!("G1 F100 {}", "X1 ".repeat(200_000));
        let e = errors(&line);
        assert_eq!(e.len(), MAX_NC_ERRORS);
        let columns: Vec<u32> = e.iter().take(3).map(|e| e.column).collect();
        assert_eq!(columns, [12, 15, 18], "{:?}", e[0]);
        assert!(e.iter().all(|e| e.line == 1 && e.word == "X1"));
    }

    #[test]
    fn a_program_whose_cycles_make_too_many_moves_is_refused_at_the_line_that_passes_the_limit() {
        // Each hole pecks 0.1 mm at a time through 10 mm: about 300 moves a hole.
        let holes: String = (0..20).map(|k| format!("X{k} Y1\n")).collect();
        let text = format!("G0 Z5\nG83 X0 Y0 Z-10 R1 Q0.1 F100\n{holes}G80\n");
        let options = ParseOptions { max_moves: 2_000, ..ParseOptions::default() };
        let e = parse_gcode(&text, &options).unwrap_err().0;
        assert_eq!(e.len(), 1, "{e:?}");
        assert!(e[0].reason.contains("more than 2000 moves"), "{}", e[0].reason);
        // About 300 moves a hole: the seventh hole (line 8) passes 2 000.
        assert_eq!(e[0].line, 8);
        assert!(parse_gcode(&text, &ParseOptions::default()).is_ok());
    }

    #[test]
    fn the_errors_become_one_core_error_on_the_gcode_field() {
        let e = parse_gcode("G41\nG42", &ParseOptions::default()).unwrap_err();
        let CoreError::InvalidInput { field, reason } = CoreError::from(e) else {
            panic!("not an invalid input");
        };
        assert_eq!(field, "gcode");
        assert!(reason.starts_with("line 1, column 1 (G41): G41/G42 need the tool radius"), "{reason}");
        assert!(reason.ends_with("(and 1 more error)"), "{reason}");
    }
}
