//! The programs dieplan generates (trochoids, plans) are safe and readable: the safety line,
//! the tool called with `T… M6` and `G43 H…` on a move of Z alone to the safe height, XY
//! only after that, a comment before each operation of each layer, coolant as the machine
//! or the request says, N numbers on request, and a footer that retracts Z before the end.

use crate::common::{assert_problem, TestApp};
use dieplan::core::nc::{parse_gcode, ParseOptions};
use dieplan::core::toolpath::Motion;
use serde_json::{json, Value};

/// Most a job may take in these tests, s (two cores shared with the rest of the suite).
const DEADLINE_S: u64 = 600;

/// A 30 × 20 mm box with corners of radius 6.
fn small_box() -> Value {
    json!({"outer": [[6, 0], [24, 0, 0.414214], [30, 6], [30, 14, 0.414214], [24, 20], [6, 20, 0.414214],
                     [0, 14], [0, 6, 0.414214]]})
}

/// The box 6 mm deep in two levels of 3 mm with the 10 mm end mill.
fn trochoids_request(output: Value) -> Value {
    json!({"contour": small_box(), "z_top": 0, "z_bottom": -6, "tool_type": "square", "diameter_mm": 10,
           "roughing": {"spindle_rpm": 4800, "fz_mm": 0.1, "rd_mm": 0.5, "ad_mm": 3},
           "sample_spacing_mm": 0.1, "output": output})
}

async fn program_of(app: &TestApp, path: &str, body: Value) -> String {
    let a = app.post(path, body).await;
    assert!(a.status == 201 || a.status == 202, "{}", a.text);
    let id = a.body["id"].as_str().unwrap().to_string();
    let job = app.wait_for_job_within(&id, DEADLINE_S).await;
    assert_eq!(job["status"], "succeeded", "{job}");
    let p = app.get(&format!("/v1/jobs/{id}/program")).await;
    assert_eq!(p.status, 200, "{}", p.text);
    p.text
}

/// The words of each line, N numbers and comments left out.
fn words(text: &str) -> Vec<Vec<&str>> {
    text.lines()
        .map(|l| l.split('(').next().unwrap_or("").split_whitespace().filter(|w| !w.starts_with('N')).collect())
        .collect()
}

/// The rules of a generated program, whose tool call is `tool`, `offset` and `safe` (the
/// words, as written in its dialect).
fn assert_safe_and_readable(text: &str, tool: &str, offset: &str, safe: &str) {
    let lines = words(text);
    let safety = lines.iter().position(|l| l.join(" ") == "G21 G17 G90 G94 G40 G80 G49").expect("the safety line");
    assert_eq!(lines[safety + 1], [tool, "M6"], "{text}");
    assert_eq!(lines[safety + 2], ["G0", "G43", offset, safe], "Z alone to the safe height: {text}");
    // Nothing moves in X or Y, nothing cuts, before that; then XY before any other Z.
    let first_xy = lines.iter().position(|l| l.iter().any(|w| w.starts_with('X') || w.starts_with('Y'))).unwrap();
    assert!(first_xy > safety + 2, "{text}");
    for l in &lines[safety + 3..=first_xy] {
        assert!(!l.iter().any(|w| w.starts_with('Z') || ["G1", "G2", "G3"].contains(w)), "{l:?} in {text}");
    }
    // A comment before the first move, and the footer: Z alone back up, then the end.
    let comments: Vec<&str> = text.lines().filter(|l| l.contains("(LAYER ")).collect();
    assert!(!comments.is_empty() && text.find("(LAYER ").unwrap() < text.find(&lines[first_xy].join(" ")).unwrap());
    let last_move = lines
        .iter()
        .rposition(|l| l.iter().any(|w| w.starts_with('X') || w.starts_with('Y') || w.starts_with('Z')))
        .unwrap();
    assert_eq!(lines[last_move].iter().filter(|w| !w.starts_with('G')).collect::<Vec<_>>(), [&safe], "{text}");
    let end = lines.iter().rposition(|l| l.contains(&"M30") || l.contains(&"M2")).unwrap();
    assert!(lines[last_move + 1..end].iter().all(|l| l.iter().all(|w| w.starts_with('M'))), "{text}");
    // Our parser reads it, and nothing moves in XY and Z at once at the rapid rate.
    let read = parse_gcode(text, &ParseOptions::default()).unwrap_or_else(|e| panic!("{e}"));
    for m in read.moves.iter().filter(|m| matches!(m.motion, Motion::Rapid)) {
        let xy = (m.end.x - m.start.x).hypot(m.end.y - m.start.y) > 1e-9;
        assert!(!xy || (m.end.z - m.start.z).abs() < 1e-9, "{m:?}");
    }
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_trochoids_program_calls_its_tool_goes_up_first_and_comments_every_operation_of_every_level() {
    let app = TestApp::start().await;
    let text = program_of(&app, "/v1/trochoids", trochoids_request(json!({}))).await;
    assert_safe_and_readable(&text, "T1", "H1", "Z5.");
    // The seeded machine cuts with oil mist (seed 004 §3.4): M7 after the spindle, M9 at the end.
    let m: Vec<&str> = text.split_whitespace().filter(|w| w.starts_with('M')).collect();
    assert_eq!(m, ["M6", "M3", "M7", "M5", "M9", "M30"], "{text}");
    for level in ["LAYER 1 Z-3", "LAYER 2 Z-6"] {
        for step in ["HELICAL BORING REGION 1", "TROCHOIDAL GROOVING REGION 1", "ROUGH SIDE CUTTING"] {
            assert!(text.contains(&format!("({level} {step})\n")), "{level} {step}: {text}");
        }
    }
    app.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn the_request_names_the_tool_offset_safe_height_coolant_dialect_and_n_numbers() {
    let app = TestApp::start().await;
    let output = json!({"dialect": "linux_cnc", "tool_number": 12, "length_offset": 32, "safe_z": 20,
                        "coolant": "off", "line_numbers": {"start": 100, "step": 5}});
    let text = program_of(&app, "/v1/trochoids", trochoids_request(output)).await;
    assert_safe_and_readable(&text, "T12", "H32", "Z20");
    assert!(!text.contains("M7") && !text.contains("M8") && !text.contains("M9"), "{text}");
    for (k, line) in text.lines().enumerate() {
        assert!(line.starts_with(&format!("N{} ", 100 + 5 * k)), "{line}");
    }
    // The older true/false: true is flood coolant.
    let flood = program_of(&app, "/v1/trochoids", trochoids_request(json!({"coolant": true}))).await;
    assert!(flood.contains("\nM8\n") && flood.contains("\nM9\n"), "{flood}");
    app.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn the_coolant_comes_from_the_machines_row_which_a_shop_can_change() {
    let app = TestApp::start().await;
    let machines = app.get("/v1/machines").await;
    let seeded = &machines.body["items"][0];
    assert_eq!(seeded["coolant"], "mist", "{seeded}");
    assert!(seeded["reference"].as_str().unwrap().contains("seed 004 §3.4"), "{seeded}");
    let id = seeded["id"].as_i64().unwrap();
    let patched = app.patch(&format!("/v1/machines/{id}"), json!({"coolant": "flood"})).await;
    assert_eq!((patched.status.as_u16(), &patched.body["coolant"]), (200, &json!("flood")), "{}", patched.text);
    let text = program_of(&app, "/v1/trochoids", trochoids_request(json!({}))).await;
    assert!(text.contains("\nM8\n") && !text.contains("M7"), "{text}");
    assert_problem(&app.patch(&format!("/v1/machines/{id}"), json!({"coolant": "fog"})).await, 422, Some("coolant"));
    app.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_plans_program_comments_every_operation_of_every_layer_and_follows_the_same_rules() {
    let app = TestApp::start().await;
    let body = json!({"contour": small_box(), "z_top": 0, "z_bottom": -8, "diameters_mm": [10],
                      "baseline": false, "tune": false, "sample_spacing_mm": 0.1, "safe_z": 10});
    let text = program_of(&app, "/v1/plans", body).await;
    assert_safe_and_readable(&text, "T1", "H1", "Z10.");
    for (level, last) in [("LAYER 1 Z-3", "ROUGH SIDE CUTTING"), ("LAYER 2 Z-8", "INTERMEDIATE-ROUGH SIDE CUTTING")] {
        for step in ["HELICAL BORING REGION 1", "TROCHOIDAL GROOVING REGION 1", last] {
            assert!(text.contains(&format!("({level} {step})\n")), "{level} {step}: {text}");
        }
    }
    app.stop().await;
}

#[tokio::test]
async fn output_options_no_control_reads_are_refused_naming_the_field() {
    let app = TestApp::start().await;
    for (output, field) in [
        (json!({"coolant": "oil"}), "output.coolant"),
        (json!({"coolant": 1}), "output.coolant"),
        (json!({"length_offset": 0}), "output.length_offset"),
        (json!({"length_offset": 10000}), "output.length_offset"),
        (json!({"safe_z": 1e9}), "output.safe_z"),
    ] {
        let a = app.post("/v1/trochoids", trochoids_request(output.clone())).await;
        assert_problem(&a, 422, Some(field));
        assert!(!a.text.contains("CoolantInput"), "{}", a.text);
    }
    app.stop().await;
}
