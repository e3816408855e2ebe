//! The interpreter on the constructs LinuxCNC and Fanuc controls run: parameters and
//! expressions, subroutines and loops, offsets, retracts, feed modes, polar words, arc
//! tolerances, canned cycles. Each test is a small program as a control reads it.

use super::*;
use crate::core::tolerance::approx_eq;
use crate::core::toolpath::{EventKind, Motion, Move, Toolpath, P3};

/// Coordinates in these programs are short decimals; results match to rounding.
const TOL_MM: f64 = 1e-9;

fn run(text: &str, options: &ParseOptions) -> Toolpath {
    parse_gcode(text, options).unwrap_or_else(|e| panic!("{e}\n{text}"))
}

fn parse(text: &str) -> Toolpath {
    run(text, &ParseOptions::default())
}

fn errors(text: &str, options: &ParseOptions) -> Vec<NcError> {
    parse_gcode(text, options).unwrap_err().0
}

fn close(p: P3, x: f64, y: f64, z: f64) -> bool {
    approx_eq(p.x, x, TOL_MM) && approx_eq(p.y, y, TOL_MM) && approx_eq(p.z, z, TOL_MM)
}

fn ends(path: &Toolpath) -> Vec<(f64, f64, f64)> {
    path.moves.iter().map(|m| (m.end.x, m.end.y, m.end.z)).collect()
}

fn last(path: &Toolpath) -> Move {
    *path.moves.last().expect("a move")
}

#[test]
fn parameters_and_expressions_give_the_words_their_values() {
    let path = parse("#1 = 10\n#<depth> = -2.5\nG0 X[#1*2+SIN[30]] Y#1 Z5\nG1 Z#<depth> F[#1*30]\n");
    assert!(close(path.moves[0].end, 20.5, 10.0, 5.0), "{:?}", ends(&path));
    assert!(close(path.moves[1].end, 20.5, 10.0, -2.5));
    assert!(approx_eq(path.moves[1].feed_mm_min.unwrap(), 300.0, TOL_MM));
}

#[test]
fn parameters_set_on_a_line_take_effect_after_its_words_are_read() {
    let path = parse("#1=1\n#1=2 G0 X#1\nG0 Y#1");
    assert!(close(path.moves[0].end, 1.0, 0.0, 0.0));
    assert!(close(path.moves[1].end, 1.0, 2.0, 0.0));
}

#[test]
fn a_linuxcnc_subroutine_called_in_a_repeat_loop_cuts_each_pass_on_its_own_lines() {
    let text = "\
o<slot> sub
  G0 X#1 Y0 Z1
  G1 Z#2 F100
  G1 Y10
  G0 Z1
o<slot> endsub
#10 = 0
o100 repeat [3]
  o<slot> call [#10] [-1]
  #10 = [#10 + 5]
o100 endrepeat
M2
";
    let interpreted = interpret(text, &ParseOptions::default()).unwrap();
    let path = &interpreted.path;
    assert_eq!(path.moves.len(), 12, "{:?}", ends(path));
    let slots: Vec<f64> = path.moves.iter().filter(|m| m.line == 4).map(|m| m.end.x).collect();
    assert_eq!(slots, [0.0, 5.0, 10.0]);
    assert!(path.moves.iter().all(|m| (2..=5).contains(&m.line)));
    assert_eq!(interpreted.map.line(3).unwrap().executions, 3);
    assert_eq!(interpreted.map.line(1).unwrap().executions, 1);
    assert!(interpreted.map.order.is_some());
}

#[test]
fn if_elseif_else_and_while_and_do_loops_branch_as_linuxcnc_does() {
    let text = "\
#1 = 2
o1 if [#1 EQ 1]
  G0 X1
o1 elseif [#1 EQ 2]
  G0 X2
o1 else
  G0 X3
o1 endif
#2 = 0
o2 while [#2 LT 3]
  G0 Y#2
  #2 = [#2 + 1]
o2 endwhile
o3 do
  G0 Z#2
  #2 = [#2 - 1]
o3 while [#2 GT 0]
";
    let path = parse(text);
    let xs: Vec<(f64, f64, f64)> = ends(&path);
    assert_eq!(xs[0], (2.0, 0.0, 0.0));
    // The while loop moves Y to 1 and 2 (Y0 is where the tool is); the do loop Z to 3, 2, 1.
    assert_eq!(&xs[1..], [(2.0, 1.0, 0.0), (2.0, 2.0, 0.0), (2.0, 2.0, 3.0), (2.0, 2.0, 2.0), (2.0, 2.0, 1.0)]);
}

#[test]
fn break_leaves_a_loop_and_continue_goes_to_its_next_round() {
    let text = "\
#1 = 0
o1 while [#1 LT 10]
  #1 = [#1 + 1]
  o2 if [#1 EQ 2]
    o1 continue
  o2 endif
  o3 if [#1 GT 4]
    o1 break
  o3 endif
  G0 X#1
o1 endwhile
G0 Y1
";
    let xs: Vec<f64> = parse(text).moves.iter().map(|m| m.end.x).collect();
    assert_eq!(xs, [1.0, 3.0, 4.0, 4.0]);
}

#[test]
fn fanuc_m98_subprograms_repeat_and_m99_returns_after_the_call() {
    let text = "\
%
O0001 (MAIN)
G90 G54 G17
M98 P1000 L2
G0 X50
M98 P21000
M30
O1000 (SUB)
G91 G1 X10 F500
G90
M99
%
";
    let interpreted = interpret(text, &ParseOptions::default()).unwrap();
    let xs: Vec<f64> = interpreted.path.moves.iter().map(|m| m.end.x).collect();
    assert_eq!(xs, [10.0, 20.0, 50.0, 60.0, 70.0]);
    assert_eq!(interpreted.map.control, Control::Fanuc);
    assert_eq!(interpreted.map.line(9).unwrap().executions, 4);
}

#[test]
fn fanuc_while_loops_and_goto_jumps_run_with_macro_variables() {
    let text = "\
O0002
#1 = 0
WHILE [#1 LT 3] DO 1
G1 X#1 F100
#1 = #1 + 1
END 1
IF [#1 EQ 3] GOTO 20
G0 X99
N20 G0 Y5
M30
";
    let path = parse(text);
    assert_eq!(ends(&path), [(1.0, 0.0, 0.0), (2.0, 0.0, 0.0), (2.0, 5.0, 0.0)]);
}

#[test]
fn a_g65_macro_call_passes_its_arguments_as_local_variables() {
    let text = "O0001\n#1 = 7\nG65 P9000 A5 B2\nG0 Z#1\nM30\nO9000\nG1 X#1 Y#2 F100\nM99\n";
    let path = parse(text);
    assert_eq!(ends(&path), [(5.0, 2.0, 0.0), (5.0, 2.0, 7.0)]);
}

#[test]
fn a_vacant_fanuc_variable_drops_its_word_and_linuxcnc_reads_an_unset_one_as_zero() {
    let fanuc = ParseOptions { control: Control::Fanuc, ..ParseOptions::default() };
    let path = run("G0 X5 Y5\nG0 X#1 Y1", &fanuc);
    assert!(close(last(&path).end, 5.0, 1.0, 0.0));
    let path = parse("G0 X5 Y5\nG0 X#1 Y1");
    assert!(close(last(&path).end, 0.0, 1.0, 0.0));
}

#[test]
fn a_loop_that_never_ends_stops_at_the_iteration_limit_naming_its_line() {
    let options = ParseOptions { max_loop_iterations: 100, ..ParseOptions::default() };
    let e = errors("o1 while [1]\nG0 X1\nG0 X2\no1 endwhile\n", &options);
    assert_eq!(e.len(), 1, "{e:?}");
    assert_eq!(e[0].line, 4);
    assert!(e[0].reason.contains("more than 100 times"), "{}", e[0].reason);
    let e = errors("N10 G0 X1\nGOTO 10\n", &options);
    assert!(e[0].reason.contains("more than 100 times"), "{}", e[0].reason);
}

#[test]
fn calls_nested_beyond_the_limit_and_missing_subroutines_are_errors() {
    let options = ParseOptions { max_call_depth: 5, ..ParseOptions::default() };
    let e = errors("o1 sub\no1 call\no1 endsub\no1 call\n", &options);
    assert!(e[0].reason.contains("deeper than 5"), "{e:?}");
    let e = errors("G0 X1\no<pocket> call [1]\n", &ParseOptions::default());
    assert_eq!((e[0].line, e[0].column), (2, 1));
    assert!(e[0].reason.contains("o<pocket> is not defined"), "{}", e[0].reason);
    let e = errors("O0001\nM98 P2000\nM30\n", &ParseOptions::default());
    assert!(e[0].reason.contains("O2000 is not in the program text"), "{}", e[0].reason);
    let e = errors("O0001\nM98 P2000\nM30\nO2000\nG0 X1\n", &ParseOptions::default());
    assert!(e[0].reason.contains("never returns"), "{e:?}");
}

#[test]
fn polar_words_move_about_the_origin_as_linuxcnc_documents() {
    // LinuxCNC's manual: adding 90° four times in G91 draws a square's corners.
    let path = parse("F100 G1 @.5 ^90\nG91 ^90\n^90\n^90\n^90\nG90 G0 X0 Y0");
    let corners: Vec<(f64, f64)> = path.moves.iter().take(5).map(|m| (m.end.x, m.end.y)).collect();
    let expected = [(0.0, 0.5), (-0.5, 0.0), (0.0, -0.5), (0.5, 0.0), (0.0, 0.5)];
    for (c, e) in corners.iter().zip(expected) {
        assert!(approx_eq(c.0, e.0, 1e-12) && approx_eq(c.1, e.1, 1e-12), "{corners:?}");
    }
    let e = errors("G1 X1 @2 F100", &ParseOptions::default());
    assert!(e[0].reason.contains("not both"), "{e:?}");
}

#[test]
fn a_repeat_loop_of_polar_words_spirals_out_as_written() {
    // A spiral of 2 000 steps of 1.8° and 0.00375 mm from r = 2.5 mm to 10 mm.
    let text = "\
G21 G90 G17
G0 X12.5 Y20 Z10
G92 X2.5 Y0
G1 Z-1 F300
o100 repeat [2000]
  G91 G1 @0.00375 ^1.8
o100 endrepeat
G90 G0 Z10
M2
";
    let path = parse(text);
    let spiral: Vec<&Move> = path.moves.iter().filter(|m| m.line == 6).collect();
    assert_eq!(spiral.len(), 2000);
    let end = spiral.last().unwrap().end;
    // 2 000 × 1.8° is ten turns: the spiral ends at 10 mm on the +X side of (10, 20).
    assert!(approx_eq(end.x, 20.0, 1e-9) && approx_eq(end.y, 20.0, 1e-9), "{end:?}");
}

#[test]
fn g53_g28_and_g30_are_read_as_rapid_retracts_straight_up_with_a_warning() {
    let text = "G0 X10 Y10 Z5\nG1 Z-5 F100\nG0 G53 Z-10\nG1 Z-4\nG91 G28 Z0\nG90\nG30\nG53 G0 X0 Y0\n";
    let path = parse(text);
    let retracts: Vec<&Move> = path.moves.iter().filter(|m| [3, 5].contains(&m.line)).collect();
    assert_eq!(retracts.len(), 2);
    for m in retracts {
        assert_eq!(m.motion, Motion::Rapid);
        assert!(approx_eq(m.start.x, m.end.x, TOL_MM) && approx_eq(m.start.y, m.end.y, TOL_MM));
        assert!(approx_eq(m.end.z, 5.0, TOL_MM), "{m:?}");
    }
    assert_eq!(path.warnings.len(), 4, "{:?}", path.warnings);
    assert!(path.warnings[0].starts_with("line 3: G53 moves in machine coordinates"), "{:?}", path.warnings);
    let high = ParseOptions { retract_z_mm: Some(50.0), ..ParseOptions::default() };
    let path = run(text, &high);
    assert!(approx_eq(path.moves[2].end.z, 50.0, TOL_MM));
}

#[test]
fn work_offsets_the_program_sets_place_the_other_systems() {
    let text = "G10 L2 P1 X0 Y0 Z0\nG10 L2 P2 X100 Y0 Z0\nG54 G0 X10 Y10 Z5\nG55 G0 X10 Y10\n";
    let path = parse(text);
    assert!(close(path.moves[1].end, 110.0, 10.0, 5.0), "{:?}", ends(&path));
    assert!(path.warnings.is_empty(), "{:?}", path.warnings);
    let path = parse("G0 X1\nG55 G0 X2\n");
    assert!(close(last(&path).end, 2.0, 0.0, 0.0));
    assert_eq!(path.warnings, ["line 2: G55: its offset from G54 is not in the program; read as the same origin"]);
    // G10 L20: the tool's position becomes X0 Y0 of G56.
    let path = parse("G0 X30 Y40\nG10 L20 P3 X0 Y0\nG56 G0 X1 Y1\n");
    assert!(close(last(&path).end, 31.0, 41.0, 0.0), "{:?}", ends(&path));
}

#[test]
fn g92_and_g52_shift_every_system_and_g92_1_clears_the_shift() {
    let path = parse("G0 X50 Y20\nG92 X0 Y0\nG0 X10\nG92.1\nG0 X10\nG52 X5\nG0 X0\n");
    let xs: Vec<f64> = path.moves.iter().map(|m| m.end.x).collect();
    assert_eq!(xs, [50.0, 60.0, 10.0, 5.0]);
}

#[test]
fn a_length_offset_of_another_tool_moves_the_tip_by_the_tables_length_difference() {
    let table = vec![
        ToolEntry { number: 1, radius_mm: Some(5.0), length_mm: Some(100.0) },
        ToolEntry { number: 2, radius_mm: Some(4.0), length_mm: Some(120.0) },
    ];
    let options = ParseOptions { tool_table: table, ..ParseOptions::default() };
    let path = run("T1 M6\nG43 H2 G0 Z10\nG43 H1 G0 Z10\n", &options);
    assert!(approx_eq(path.moves[0].end.z, 30.0, TOL_MM), "{:?}", ends(&path));
    assert!(approx_eq(path.moves[1].end.z, 10.0, TOL_MM));
    let path = parse("T1 M6\nG43 H2 G0 Z10\n");
    assert!(approx_eq(path.moves[0].end.z, 10.0, TOL_MM));
    assert!(path.warnings[0].contains("H2 is for another tool"), "{:?}", path.warnings);
}

#[test]
fn inverse_time_and_per_revolution_feeds_become_mm_per_minute() {
    let path = parse("G93 G1 X10 F6\nG95 S1000 G1 X20 F0.1\nG20 G94 G1 X1 F10");
    let feeds: Vec<f64> = path.moves.iter().map(|m| m.feed_mm_min.unwrap()).collect();
    assert!(approx_eq(feeds[0], 60.0, 1e-9) && approx_eq(feeds[1], 100.0, 1e-9) && approx_eq(feeds[2], 254.0, 1e-9));
    let e = errors("G93 G1 X10 F6\nG1 X20", &ParseOptions::default());
    assert!(e[0].reason.contains("inverse-time"), "{e:?}");
    let e = errors("G95 G1 X10 F0.1", &ParseOptions::default());
    assert!(e[0].reason.contains("spindle speed"), "{e:?}");
}

#[test]
fn arcs_off_their_circle_within_the_controls_tolerance_are_read_as_programmed() {
    // An inch arc rounded to four decimals misses by 0.002 mm: accepted, centre and end kept.
    let path = parse("G20 G0 X0.5 Y0\nG2 X-0.1545 Y-0.4755 I-0.5 J0.0001 F10");
    let m = last(&path);
    let Motion::Arc { center, .. } = m.motion else { panic!("not an arc") };
    assert!(close(center, 0.0, 0.0001 * 25.4, 0.0), "{center:?}");
    assert!(close(m.end, -0.1545 * 25.4, -0.4755 * 25.4, 0.0), "{:?}", m.end);
    // 0.02 mm on a 5 mm radius is 0.4 %: refused, unless the request allows more.
    let text = "G0 X5 Y0\nG2 X0 Y-5.02 I-5 J0 F100";
    let e = errors(text, &ParseOptions::default());
    assert!(e[0].reason.contains("0.1 % of the radius"), "{}", e[0].reason);
    let loose = ParseOptions {
        arc_tolerance: ArcTolerance { absolute: Some(0.05), ..ArcTolerance::default() },
        ..ParseOptions::default()
    };
    assert!(parse_gcode(text, &loose).is_ok());
}

#[test]
fn unknown_m_codes_are_warnings_and_standard_auxiliary_codes_pass_silently() {
    let path = parse("M88\nM19\nM50\nG0 X1\nM1\n");
    assert_eq!(path.moves.len(), 1);
    assert_eq!(
        path.warnings,
        ["line 1: M88 is not a standard M code: read as an auxiliary function that moves nothing"]
    );
    assert!(path.events.iter().any(|e| e.kind == EventKind::Stop));
}

#[test]
fn a_bad_line_in_a_loop_is_reported_once_however_often_it_runs() {
    let text = "G1 F100\no1 repeat [3]\nG1 X10 $$$\no1 endrepeat\nM2";
    let e = errors(text, &ParseOptions::default());
    assert!(!e.is_empty(), "the bad word is an error");
    assert_eq!(e.iter().filter(|x| x.line == 3).count(), 1, "{e:?}");
}

#[test]
fn each_bad_word_is_one_error_at_its_column() {
    let e = errors("G1 X10 $$$ Y2 F100 Q", &ParseOptions::default());
    assert_eq!(e.len(), 2, "{e:?}");
    assert_eq!((e[0].column, e[0].word.as_str()), (8, "$$$"));
    assert_eq!((e[1].column, e[1].word.as_str()), (20, "Q"));
    let e = errors("G1 X[1+] Y#<nope> F100", &ParseOptions::default());
    assert_eq!(e.len(), 2, "{e:?}");
    assert_eq!(e[0].word, "X[1+]");
    assert!(e[1].reason.contains("#<nope> is not defined"), "{e:?}");
}

#[test]
fn canned_cycles_tap_bore_break_chips_and_step_in_g91() {
    // G84 taps in and feeds back out to R.
    let path = parse("G0 X0 Y0 Z10\nG99 G84 X5 Y5 Z-8 R2 F150\nG80");
    let feeds: Vec<f64> = path.moves.iter().filter(|m| m.motion == Motion::Linear).map(|m| m.end.z).collect();
    assert_eq!(feeds, [-8.0, 2.0]);
    // G73 backs off 0.254 mm between pecks.
    let path = parse("G0 Z10\nG73 X0 Y0 Z-3 R1 Q1 F100\nG80");
    let backs = path.moves.iter().filter(|m| m.motion == Motion::Rapid && m.end.z < 1.0 - 1e-9).count();
    assert_eq!(backs, 3);
    // G91 with L3: three holes 10 mm apart, R 2 mm below the start and Z 5 mm below R.
    let path = parse("G0 X0 Y0 Z10\nG91 G81 X10 Z-5 R-8 L3 F100\nG90 G80");
    let holes: Vec<(f64, f64)> =
        path.moves.iter().filter(|m| m.motion == Motion::Linear).map(|m| (m.end.x, m.end.z)).collect();
    assert_eq!(holes, [(10.0, -3.0), (20.0, -3.0), (30.0, -3.0)]);
}
