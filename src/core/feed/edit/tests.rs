//! The editor on small programs as controls run them, and a property test that an edited
//! program reads back to the same motion with only its F words changed.

use super::*;
use crate::core::nc::{interpret, parse_gcode, Interpreted, ParseOptions};
use crate::core::tolerance::approx_eq;
use crate::core::toolpath::{Move, Toolpath};
use proptest::prelude::*;

fn read(text: &str) -> Interpreted {
    interpret(text, &ParseOptions::default()).unwrap_or_else(|e| panic!("{e}\n{text}"))
}

fn path(text: &str) -> Toolpath {
    parse_gcode(text, &ParseOptions::default()).unwrap_or_else(|e| panic!("{e}\n{text}"))
}

/// Pieces for every feed move: `f(move index, line)` gives its pieces.
fn pieces_by(program: &Interpreted, f: impl Fn(usize, u32) -> Vec<Piece>) -> Vec<Vec<Piece>> {
    program
        .path
        .moves
        .iter()
        .enumerate()
        .map(|(i, m)| if matches!(m.motion, Motion::Rapid) { Vec::new() } else { f(i, m.line) })
        .collect()
}

fn whole(feed: f64) -> Vec<Piece> {
    vec![Piece { t0: 0.0, t1: 1.0, feed_mm_min: feed }]
}

fn halves(a: f64, b: f64) -> Vec<Piece> {
    vec![Piece { t0: 0.0, t1: 0.5, feed_mm_min: a }, Piece { t0: 0.5, t1: 1.0, feed_mm_min: b }]
}

#[test]
fn a_block_whose_feed_changes_inside_is_split_and_keeps_its_n_number_and_comment() {
    let text = "G21 G90\nG0 X0 Y0 Z5\nG1 Z-1 F500\nN40 G1 X30 F1000 (cut)\nM30\n";
    let program = read(text);
    let pieces = pieces_by(&program, |_, line| if line == 4 { halves(1000.0, 400.0) } else { whole(500.0) });
    let edited = edit_feeds(text, &program.path, &program.map, &pieces);
    assert_eq!(edited.text, "G21 G90\nG0 X0 Y0 Z5\nG1 Z-1 F500\nN40 G1 X15 F1000 (cut)\nG1 X30 F400\nM30\n");
    assert_eq!(edited.changes.len(), 1);
    assert_eq!(edited.changes[0].line, 4);
    assert_eq!(edited.changes[0].before, "N40 G1 X30 F1000 (cut)");
    assert_eq!(edited.changes[0].after, "N40 G1 X15 F1000 (cut)\nG1 X30 F400");
    assert_eq!(edited.split_blocks, 1);
}

#[test]
fn a_block_that_relied_on_a_changed_modal_feed_gets_its_own_f_word() {
    let text = "G0 X0 Y0\nG1 X10 F1000\nX20\nX30\n";
    let program = read(text);
    let pieces = pieces_by(&program, |_, line| whole(if line == 2 { 500.0 } else { 1000.0 }));
    let edited = edit_feeds(text, &program.path, &program.map, &pieces);
    assert_eq!(edited.text, "G0 X0 Y0\nG1 X10 F500\nX20 F1000\nX30\n");
    let feeds: Vec<f64> = path(&edited.text).moves.iter().map(|m| m.feed_mm_min.unwrap()).collect();
    assert_eq!(feeds, [500.0, 1000.0, 1000.0]);
}

#[test]
fn inch_per_revolution_and_inverse_time_feeds_are_written_in_the_programs_own_terms() {
    let text = "G20 G90\nG0 X0 Y0\nG1 X1 F40.\nG95 S1000\nG1 X2 F0.002\nG93 G1 X3 F10.\n";
    let program = read(text);
    let edited = edit_feeds(text, &program.path, &program.map, &pieces_by(&program, |_, _| whole(500.0)));
    // 500 mm/min: 19.68 in/min (rounded down), 0.01968 in/rev at 1000 min⁻¹, and
    // 1 inch in 25.4/500 min: F19.685 → 19.6850 inverse minutes.
    assert_eq!(edited.text, "G20 G90\nG0 X0 Y0\nG1 X1 F19.68\nG95 S1000\nG1 X2 F0.01968\nG93 G1 X3 F19.685\n");
    let moves = path(&edited.text).moves;
    assert!(moves.iter().skip(1).all(|m| m.feed_mm_min.unwrap() <= 500.0 + 1e-9));
}

#[test]
fn arcs_split_in_their_own_centre_format_and_g91_pieces_add_up_to_the_block() {
    let cases = [
        "G0 X10 Y0\nG3 X-10 Y0 I-10 J0 F600\n",
        "G0 X10 Y0\nG3 X-10 Y0 R10 F600\n",
        "G0 X10 Y0\nG90.1 G3 X-10 Y0 I0 J0 F600\n",
        "G0 X10 Y0\nG91 G3 X-20 Y0 I-10 J0 F600\nG1 X-5\n",
        "G0 X10 Y0 Z0\nG2 X10 Y0 Z-2 I-10 J0 P3 F600\n",
    ];
    for text in cases {
        let program = read(text);
        let pieces = pieces_by(&program, |_, _| {
            vec![
                Piece { t0: 0.0, t1: 0.3, feed_mm_min: 600.0 },
                Piece { t0: 0.3, t1: 0.7, feed_mm_min: 250.0 },
                Piece { t0: 0.7, t1: 1.0, feed_mm_min: 600.0 },
            ]
        });
        let edited = edit_feeds(text, &program.path, &program.map, &pieces);
        let before = path(text);
        let after = path(&edited.text);
        let arcs: Vec<&Move> = after.moves.iter().filter(|m| matches!(m.motion, Motion::Arc { .. })).collect();
        assert!(arcs.len() >= 3, "{text}\n{}", edited.text);
        let (b, a) = (before.moves.last().unwrap(), after.moves.last().unwrap());
        assert!(
            approx_eq(a.end.x, b.end.x, 1e-3) && approx_eq(a.end.y, b.end.y, 1e-3) && approx_eq(a.end.z, b.end.z, 1e-3)
        );
        let length = |p: &Toolpath| p.moves.iter().map(move_length).sum::<f64>();
        assert!(approx_eq(length(&before), length(&after), 2e-3), "{text}\n{}", edited.text);
    }
}

#[test]
fn a_block_run_several_times_gets_the_lowest_feed_any_of_its_runs_needs() {
    let text = "G0 X0 Y0\no1 repeat [3]\n  G91 G1 X10 F800\no1 endrepeat\nG90\n";
    let program = read(text);
    let pieces = pieces_by(&program, |i, _| match i {
        1 => halves(800.0, 300.0),
        _ => whole(600.0),
    });
    let edited = edit_feeds(text, &program.path, &program.map, &pieces);
    assert_eq!(edited.text, "G0 X0 Y0\no1 repeat [3]\n  G91 G1 X10 F300\no1 endrepeat\nG90\n");
}

/// A random program line: a straight move or an arc, in the modes it is written in.
fn program_case() -> impl Strategy<Value = (bool, bool, bool, Vec<(u8, f64, f64)>)> {
    (
        any::<bool>(),
        any::<bool>(),
        any::<bool>(),
        proptest::collection::vec((0u8..3, -40.0f64..40.0, -40.0f64..40.0), 1..12),
    )
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(96))]

    /// Any program, edited with any feeds, reads back to the same motion: the same end of
    /// every original block, in order, to the written resolution; only F words differ on
    /// lines that were not split.
    #[test]
    fn an_edited_program_reads_back_to_the_same_motion_with_only_its_feeds_changed(
        (inch, incremental, radius_arcs, steps) in program_case(),
        cuts in proptest::collection::vec((0.05f64..0.95, 50.0f64..3000.0), 0..3),
    ) {
        let scale = if inch { 1.0 / 25.4 } else { 1.0 };
        let mut text = String::from(if inch { "G20 G17 G90\n" } else { "G21 G17 G90\n" });
        text += "G0 X0 Y0 Z1\nG1 Z-1 F100\n";
        if incremental { text += "G91\n"; }
        let (mut x, mut y) = (0.0f64, 0.0f64);
        for (kind, a, b) in &steps {
            let (nx, ny) = (x + a * scale, y + b * scale);
            let (wx, wy) = if incremental { (nx - x, ny - y) } else { (nx, ny) };
            match kind {
                0 | 1 => text += &format!("G1 X{wx:.4} Y{wy:.4} F{:.1}\n", 500.0 * scale),
                _ => {
                    // A half circle on the chord, written with R or I/J.
                    if (nx - x).hypot(ny - y) < 0.01 { continue; }
                    let (cx, cy) = ((x + nx) / 2.0, (y + ny) / 2.0);
                    let r = (nx - x).hypot(ny - y) / 2.0;
                    if radius_arcs {
                        text += &format!("G2 X{wx:.4} Y{wy:.4} R{r:.4} F{:.1}\n", 500.0 * scale);
                    } else {
                        text += &format!("G2 X{wx:.4} Y{wy:.4} I{:.4} J{:.4} F{:.1}\n", cx - x, cy - y, 500.0 * scale);
                    }
                }
            }
            let (rx, ry) = (format!("{nx:.4}").parse::<f64>().unwrap(), format!("{ny:.4}").parse::<f64>().unwrap());
            x = if incremental { x + (rx - x) } else { rx };
            y = if incremental { y + (ry - y) } else { ry };
        }
        text += "G90 G0 Z5\nM30\n";
        let Ok(program) = interpret(&text, &ParseOptions::default()) else { return Ok(()) };
        let mut sorted = cuts.clone();
        sorted.sort_by(|a, b| a.0.total_cmp(&b.0));
        let pieces = pieces_by(&program, |i, _| {
            let mut out = Vec::new();
            let mut t0 = 0.0;
            for (k, (t, f)) in sorted.iter().enumerate() {
                if *t <= t0 + 0.01 { continue; }
                out.push(Piece { t0, t1: *t, feed_mm_min: f + (i + k) as f64 });
                t0 = *t;
            }
            out.push(Piece { t0, t1: 1.0, feed_mm_min: 700.0 + i as f64 });
            out
        });
        let edited = edit_feeds(&text, &program.path, &program.map, &pieces);
        let after = parse_gcode(&edited.text, &ParseOptions::default())
            .map_err(|e| TestCaseError::fail(format!("{e}\n{}", edited.text)))?;
        // Every original block's end is reached, in order.
        let resolution = if inch { 0.0001 * 25.4 } else { 0.001 } * 2.0;
        let mut k = 0;
        for m in &program.path.moves {
            while k < after.moves.len() && !close(after.moves[k].end, m.end, resolution) {
                k += 1;
            }
            prop_assert!(k < after.moves.len(), "the end {:?} of line {} is lost\n{}\n{}", m.end, m.line, text, edited.text);
            k += 1;
        }
        // Lines not split differ only in their F word.
        for change in &edited.changes {
            if change.after.contains('\n') { continue; }
            let strip = |s: &str| s.split_whitespace().filter(|w| !w.starts_with('F')).collect::<Vec<_>>().join(" ");
            prop_assert_eq!(strip(&change.before), strip(&change.after));
        }
        // No block runs faster than its slowest piece asks.
        for m in after.moves.iter().filter(|m| !matches!(m.motion, Motion::Rapid)) {
            prop_assert!(m.feed_mm_min.unwrap() <= 3100.0 + 50.0);
        }
    }
}

fn close(a: crate::core::toolpath::P3, b: crate::core::toolpath::P3, tol: f64) -> bool {
    approx_eq(a.x, b.x, tol) && approx_eq(a.y, b.y, tol) && approx_eq(a.z, b.z, tol)
}
