//! Real programs in, safe and cheaper programs out: a Fanuc post-processor program and a
//! hand-written LinuxCNC inch program (tests/programs/) are analysed, and come back from
//! the feeds job as their own text with only F words changed, every changed line listed,
//! at no higher cost.

use crate::common::{assert_problem, TestApp};
use dieplan::core::nc::{parse_gcode, ParseOptions};
use dieplan::core::toolpath::{Motion, Toolpath};
use serde_json::{json, Value};

fn program_file(name: &str) -> String {
    let path = format!("{}/tests/programs/{name}", env!("CARGO_MANIFEST_DIR"));
    std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{path}: {e}"))
}

/// The Fanuc program's slots and wall: a 100 × 60 block, 12 mm deep.
fn fanuc_request() -> Value {
    json!({
        "program": {"gcode": program_file("fanuc_post.nc")},
        "tool_type": "square", "diameter_mm": 10,
        "stock": {"box": {"x_min": 0, "y_min": 0, "z_min": -12, "x_max": 100, "y_max": 60, "z_max": 0}}
    })
}

/// The LinuxCNC program contours a 3.9 × 2.3 in block out of a 0.4 in larger stock.
fn linuxcnc_request() -> Value {
    json!({
        "program": {"gcode": program_file("linuxcnc_inch.ngc"), "tool_table": [{"number": 1, "radius_mm": 5.0, "length_mm": 75.0}]},
        "tool_type": "square", "diameter_mm": 10,
        "stock": {"box": {"x_min": -10.16, "y_min": -10.16, "z_min": -7.62, "x_max": 109.22, "y_max": 68.58, "z_max": 0}}
    })
}

async fn job_program(app: &TestApp, job: &Value) -> String {
    let a = app.get(&format!("/v1/jobs/{}/program", job["id"].as_str().unwrap())).await;
    assert_eq!(a.status, 200, "{}", a.text);
    a.text
}

/// Reads a program as the tests' 10 mm end mill would cut it (G41/G42 need its radius).
fn read(text: &str) -> Toolpath {
    let options = ParseOptions { tool_radius_mm: Some(5.0), ..ParseOptions::default() };
    parse_gcode(text, &options).unwrap_or_else(|e| panic!("{e}\n{text}"))
}

/// The edited program is the input with only the listed lines changed, those only in
/// their F words unless split, and it reads back to the same motion.
fn assert_only_feeds_changed(input: &str, output: &str, result: &Value) {
    let changes = result["edit"]["changed_lines"].as_array().expect("changed lines");
    assert!(!changes.is_empty(), "the optimisation changed nothing: {result}");
    let mut expected = String::new();
    for (k, line) in input.split('\n').enumerate() {
        match changes.iter().find(|c| c["line"] == k as u64 + 1) {
            Some(c) => {
                assert_eq!(c["before"], line, "line {}", k + 1);
                let after = c["after"].as_str().unwrap();
                if !after.contains('\n') {
                    let strip = |s: &str| {
                        s.split_whitespace().filter(|w| !w.starts_with('F')).map(str::to_string).collect::<Vec<_>>()
                    };
                    assert_eq!(strip(line), strip(after), "line {} changed more than its feed", k + 1);
                }
                expected.push_str(after);
            }
            None => expected.push_str(line),
        }
        expected.push('\n');
    }
    assert_eq!(expected.trim_end_matches('\n'), output.trim_end_matches('\n'));
    let (before, after) = (read(input), read(output));
    let ends = |p: &Toolpath| p.moves.iter().filter(|m| m.motion == Motion::Rapid).map(|m| m.end).collect::<Vec<_>>();
    let (a, b) = (ends(&before), ends(&after));
    assert_eq!(a.len(), b.len());
    for (p, q) in a.iter().zip(&b) {
        assert!((p.x - q.x).abs() < 1e-6 && (p.y - q.y).abs() < 1e-6 && (p.z - q.z).abs() < 1e-6, "{p:?} {q:?}");
    }
}

fn cost(result: &Value, side: &str) -> f64 {
    result[side]["cost"]["total"].as_f64().unwrap_or_else(|| panic!("{side} cost: {result}"))
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_fanuc_post_program_with_subprograms_g43_g53_and_n_numbers_is_analysed_and_edited_in_place() {
    let app = TestApp::start().await;
    let a = app.post_wait("/v1/analysis", fanuc_request()).await;
    assert_eq!(a.body["status"], "succeeded", "{}", a.text);
    let r = &a.body["result"];
    let warnings = r["summary"]["warnings"].to_string();
    assert!(warnings.contains("G28") && warnings.contains("G53"), "{warnings}");
    // The slots are full-width cuts: critical regions on the subprogram's lines.
    let regions = r["critical_regions"].as_array().unwrap();
    assert!(!regions.is_empty(), "{r}");

    let f = app.post_wait("/v1/feeds", fanuc_request()).await;
    assert_eq!(f.body["status"], "succeeded", "{}", f.text);
    let r = &f.body["result"];
    let input = program_file("fanuc_post.nc");
    let output = job_program(&app, &f.body).await;
    assert!(output.starts_with("%\nO1001 (DIE INSERT 12-034 ROUGH SLOTS)\n"), "{output}");
    assert_only_feeds_changed(&input, &output, r);
    // Subprogram blocks run twice: one feed, never split.
    for c in r["edit"]["changed_lines"].as_array().unwrap() {
        let line = c["line"].as_u64().unwrap();
        if line >= 35 {
            assert!(!c["after"].as_str().unwrap().contains('\n'), "subprogram line {line} was split: {c}");
        }
    }
    assert!(cost(r, "after") <= cost(r, "before") + 1e-9, "{}", r["after"]["cost"]);
    app.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_linuxcnc_inch_program_with_parameters_o_words_and_g41_is_analysed_and_edited_in_inches() {
    let app = TestApp::start().await;
    let a = app.post_wait("/v1/analysis", linuxcnc_request()).await;
    assert_eq!(a.body["status"], "succeeded", "{}", a.text);
    let f = app.post_wait("/v1/feeds", linuxcnc_request()).await;
    assert_eq!(f.body["status"], "succeeded", "{}", f.text);
    let r = &f.body["result"];
    let input = program_file("linuxcnc_inch.ngc");
    let output = job_program(&app, &f.body).await;
    assert_only_feeds_changed(&input, &output, r);
    // Feeds are written in inches per minute: far below the mm figures.
    for c in r["edit"]["changed_lines"].as_array().unwrap() {
        for word in c["after"].as_str().unwrap().split_whitespace().filter(|w| w.starts_with('F')) {
            if let Ok(v) = word[1..].parse::<f64>() {
                assert!(v < 600.0, "{word} is not an inch feed: {c}");
            }
        }
    }
    assert!(cost(r, "after") <= cost(r, "before") + 1e-9);
    app.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn the_constructs_real_programs_were_refused_for_are_read() {
    let app = TestApp::start().await;
    let stock = json!({"box": {"x_min": -60, "y_min": -60, "z_min": -10, "x_max": 60, "y_max": 60, "z_max": 0}});
    let programs = [
        // Parameters with expressions and functions.
        "G21 G90\n#1 = 10\nG0 X[#1*2+SIN[30]] Y0 Z5\nG1 Z-1 F[#1*30]\nG1 X[-#1] F600\nM2\n",
        // A machine-coordinate retract.
        "G21 G90\nG0 X0 Y0 Z5\nG1 Z-2 F300\nG1 X20 F600\nG0 G53 Z-10\nM30\n",
        // An O-word repeat loop with polar words.
        "G21 G90\nG0 X10 Y0 Z5\nG1 Z-1 F300\no100 repeat [36]\n  G91 G1 ^10\no100 endrepeat\nG90 G0 Z5\nM2\n",
        // Cutter compensation with a D word.
        "G21 G90\nG0 X-40 Y-10 Z5\nG1 Z-2 F300\nG41 D1 G1 X-20 Y0 F600\nG1 X20\nG40 G1 X40 Y-10\nG0 Z5\nM2\n",
        // An inch arc rounded to four decimals.
        "G20 G90\nG0 X0.5 Y0 Z0.2\nG1 Z-0.04 F10\nG2 X-0.1545 Y-0.4755 I-0.5 J0.0001 F20\nG0 Z0.2\nM2\n",
    ];
    for gcode in programs {
        let body = json!({"program": {"gcode": gcode}, "tool_type": "square", "diameter_mm": 10, "stock": stock});
        let a = app.post_wait("/v1/analysis", body).await;
        assert_eq!(a.body["status"], "succeeded", "{gcode}\n{}", a.text);
    }
    app.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn programs_that_cannot_run_and_bad_reading_options_are_refused_naming_the_line_or_field() {
    let app = TestApp::start().await;
    let stock = json!({"box": {"x_min": -60, "y_min": -60, "z_min": -10, "x_max": 60, "y_max": 60, "z_max": 0}});
    let refused = |gcode: &str, program: Value| {
        let mut p = program;
        p["gcode"] = json!(gcode);
        json!({"program": p, "tool_type": "square", "diameter_mm": 10, "stock": stock})
    };
    let a = app
        .post("/v1/analysis", refused("G0 X0\no1 while [1]\nG0 X1\no1 endwhile\n", json!({"max_loop_iterations": 50})))
        .await;
    assert_problem(&a, 422, Some("program.gcode"));
    assert!(a.text.contains("line 4") && a.text.contains("more than 50 times"), "{}", a.text);
    let a = app.post("/v1/analysis", refused("G0 X0 Y0\nG1 X1 $$ Y2 F100 Q\n", json!({}))).await;
    assert_problem(&a, 422, Some("program.gcode"));
    assert!(a.text.contains("column 7 ($$)") && a.text.contains("column 18 (Q)"), "{}", a.text);
    let bad_options =
        json!({"arc_tolerance": {"relative": -1}, "tool_table": [{"number": 1, "radius_mm": -2}], "max_call_depth": 0});
    let a = app.post("/v1/analysis", refused("G0 X1\n", bad_options)).await;
    assert_problem(&a, 422, None);
    for field in ["program.arc_tolerance.relative", "program.tool_table[0].radius_mm", "program.max_call_depth"] {
        assert!(a.text.contains(field), "{field}: {}", a.text);
    }
    app.stop().await;
}
