//! `POST /v1/feeds`: feeds optimised for a constant force or a constant cutting-point
//! feed, written back as an NC program that our own parser reads.

use crate::common::{assert_problem, close, TestApp};
use dieplan::core::nc::{parse_gcode, ParseOptions};
use dieplan::core::toolpath::{Motion, Toolpath};
use serde_json::{json, Value};

fn shared(name: &str) -> String {
    let path = format!("{}/../shared/data/{name}", env!("CARGO_MANIFEST_DIR"));
    std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{path}: {e}"))
}

/// From the centre of a pre-opened hole of radius 9.5, out to the wall and once round a
/// concave arc of R/r = 2 (Rd 0.5, Ad 10) with the 10 mm tool.
const CONCAVE_CIRCLE: &str =
    "%\nO0100 (R/r 2)\nG21 G90 G17\nT1 M6\nS9600 M3\nG0 X0 Y0 Z5\nG1 Z-10 F1000\nG1 X5 F5760\nG3 X5 Y0 I-5 J0\nG0 Z5\nM30\n%\n";

fn concave_request() -> Value {
    json!({
        "program": {"gcode": CONCAVE_CIRCLE},
        "tool_type": "square", "diameter_mm": 10,
        "stock": {"box": {"x_min": -30, "y_min": -30, "z_min": -10, "x_max": 30, "y_max": 30, "z_max": 0},
                  "open": [{"circle": {"cx": 0, "cy": 0, "r": 9.5}}]}
    })
}

async fn program(app: &TestApp, job: &Value) -> (String, Toolpath) {
    let a = app.get(&format!("/v1/jobs/{}/program", job["id"].as_str().unwrap())).await;
    assert_eq!(a.status, 200, "{}", a.text);
    assert!(a.content_type().starts_with("text/plain"), "{}", a.content_type());
    let path = parse_gcode(&a.text, &ParseOptions::default()).unwrap_or_else(|e| panic!("{e:?}\n{}", a.text));
    (a.text, path)
}

/// Every feed move's feed lies within the job's limits (or is the programmed feed of a
/// plunge, which the optimiser keeps).
fn assert_feeds_within_limits(path: &Toolpath, result: &Value, programmed: &Toolpath) {
    let (lo, hi) =
        (result["limits"]["min_feed_mm_min"].as_f64().unwrap(), result["limits"]["max_feed_mm_min"].as_f64().unwrap());
    let kept: Vec<f64> = programmed.moves.iter().filter_map(|m| m.feed_mm_min).collect();
    for m in path.moves.iter().filter(|m| !matches!(m.motion, Motion::Rapid)) {
        let f = m.feed_mm_min.unwrap();
        let within = f >= lo - 0.05 && f <= hi + 0.05;
        assert!(within || kept.iter().any(|k| (k - f).abs() < 0.05), "line {}: F{f} outside [{lo}, {hi}]", m.line);
    }
}

/// The feed of the longest block that comes from `line`.
fn longest_block_feed(blocks: &Value, line: u64) -> f64 {
    let n = blocks["line"].as_array().unwrap().len();
    let longest = (0..n)
        .filter(|&i| blocks["line"][i] == line)
        .max_by(|&i, &j| blocks["length_mm"][i].as_f64().unwrap().total_cmp(&blocks["length_mm"][j].as_f64().unwrap()))
        .unwrap();
    blocks["feed_mm_min"][longest].as_f64().unwrap()
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_concave_arc_of_r_over_r_2_is_cut_at_the_constant_force_feed_of_model_section_3() {
    let app = TestApp::start().await;
    let mut papers = concave_request();
    papers["objective"] = json!("constant_force");
    let a = app.post_wait("/v1/feeds", papers).await;
    assert_eq!(a.status, 201, "{}", a.text);
    assert_eq!(a.body["status"], "succeeded", "{}", a.text);
    let r = &a.body["result"];
    assert_eq!(r["strategy"], "constant_force");
    assert!(close(&r["target_force_n"], 269.1, 0.5), "{r}");
    assert!(close(&r["limits"]["max_feed_mm_min"], 11520.0, 0.5), "{}", r["limits"]);
    // The longest block of the circle (line 9) runs at ≈ 1160 mm/min.
    assert!((longest_block_feed(&r["blocks"], 9) - 1160.0).abs() < 1160.0 * 0.02, "{}", r["blocks"]);
    assert!(r["before"]["force_n"]["max"].as_f64().unwrap() > r["after"]["force_n"]["max"].as_f64().unwrap());
    assert!(r["after"]["time_min"].as_f64().unwrap() > r["before"]["time_min"].as_f64().unwrap());
    assert!(!r["shortfalls"].as_array().unwrap().is_empty(), "the head-on entry cannot hold the target: {r}");

    let (text, path) = program(&app, &a.body).await;
    // The program sent comes back edited: its own lines, only F words changed, the
    // circle split where its feed changes, and every changed line listed.
    assert!(text.starts_with("%\nO0100 (R/r 2)\nG21 G90 G17\nT1 M6\nS9600 M3\n"), "{text}");
    assert!(text.ends_with("G0 Z5\nM30\n%\n"), "{text}");
    assert_eq!(path.moves.len(), r["program"]["moves_out"].as_u64().unwrap() as usize);
    let changes = r["edit"]["changed_lines"].as_array().unwrap();
    assert!(changes.iter().any(|c| c["line"] == 9 && c["after"].as_str().unwrap().contains('\n')), "{changes:?}");
    assert!(r["edit"]["split_blocks"].as_u64().unwrap() >= 1);
    for (k, line) in CONCAVE_CIRCLE.lines().enumerate() {
        let changed = changes.iter().find(|c| c["line"] == k as u64 + 1);
        match changed {
            Some(c) => assert_eq!(c["before"], line),
            None => assert!(text.contains(&format!("{line}\n")), "line {} is kept: {line}", k + 1),
        }
    }
    let arcs = path.moves.iter().filter(|m| matches!(m.motion, Motion::Arc { .. })).count();
    assert!(arcs >= 2, "the circle is split into arcs, not lines:\n{text}");
    let input = parse_gcode(CONCAVE_CIRCLE, &ParseOptions::default()).unwrap();
    assert_feeds_within_limits(&path, r, &input);

    // The default min_cost holds the same feed on the arc (the force limit is the target)
    // and costs less than the program as written.
    let m = app.post_wait("/v1/feeds", concave_request()).await;
    let r = &m.body["result"];
    assert_eq!(r["objective"], "min_cost");
    assert!((longest_block_feed(&r["blocks"], 9) - 1160.0).abs() < 1160.0 * 0.02, "{}", r["blocks"]);
    assert!(r["after"]["cost"]["total"].as_f64().unwrap() < r["before"]["cost"]["total"].as_f64().unwrap(), "{r}");
    app.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn json_moves_are_written_in_the_asked_dialect_and_the_same_input_gives_the_same_bytes() {
    let app = TestApp::start().await;
    let mut body = concave_request();
    body["program"] = json!({"moves": {"start": {"x": 0, "y": 0, "z": 5}, "spindle_rpm": 9600, "tool": 1, "moves": [
        {"type": "linear", "z": -10, "f": 1000},
        {"type": "linear", "x": 5, "f": 5760},
        {"type": "arc", "x": 5, "y": 0, "center": {"x": 0, "y": 0}, "clockwise": false},
        {"type": "rapid", "z": 5}
    ]}});
    body["strategy"] = json!("both");
    body["output"] = json!({"dialect": "linux_cnc", "line_numbers": {"start": 100, "step": 5}, "title": "corner test"});
    let first = app.post_wait("/v1/feeds", body.clone()).await;
    let second = app.post_wait("/v1/feeds", body).await;
    assert_eq!(first.body["status"], "succeeded", "{}", first.text);
    let (a, path) = program(&app, &first.body).await;
    let (b, _) = program(&app, &second.body).await;
    assert_eq!(a, b);
    assert!(!a.contains('%') && a.contains("N100 ") && a.trim_end().ends_with("M2"), "{a}");
    assert!(path.moves.len() > 3);
    assert!(first.body["result"]["edit"].is_null());
    app.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn g_code_keeps_its_own_dialect_and_output_options_only_warn() {
    let app = TestApp::start().await;
    let mut body = concave_request();
    body["output"] = json!({"dialect": "linux_cnc", "line_numbers": {"start": 100}});
    let a = app.post_wait("/v1/feeds", body).await;
    let (text, _) = program(&app, &a.body).await;
    assert!(text.starts_with("%\nO0100") && !text.contains("N100"), "{text}");
    let warnings = a.body["result"]["warnings"].as_array().unwrap();
    assert!(warnings.iter().any(|w| w.as_str().unwrap().contains("output options")), "{warnings:?}");
    app.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn both_real_programs_come_back_as_valid_programs_with_every_feed_within_its_limits() {
    let app = TestApp::start().await;
    let trochoidal = json!({
        "program": {"gcode": shared("trochoidal.ngc")},
        "tool_type": "square", "diameter_mm": 10,
        "stock": {"box": {"x_min": -60, "y_min": -10, "z_min": -10, "x_max": 40, "y_max": 90, "z_max": 0}}
    });
    let tiger = json!({
        "program": {"gcode": shared("tiger.nc")},
        "tool_id": app.tool_id("square", 6.0).await,
        "stock": {"box": {"x_min": -2, "y_min": -1, "z_min": -32, "x_max": 92, "y_max": 89, "z_max": 0}},
        "sample_spacing_mm": 0.1
    });
    for (name, body) in [("trochoidal.ngc", trochoidal), ("tiger.nc", tiger)] {
        let input = parse_gcode(body["program"]["gcode"].as_str().unwrap(), &ParseOptions::default()).unwrap();
        let a = app.send(reqwest::Method::POST, "/v1/feeds", Some(body), &[("prefer", "wait=60")]).await;
        // On a loaded machine tiger.nc may take longer than the longest wait: poll then.
        let job = app.wait_for_job_within(a.body["id"].as_str().unwrap(), 600).await;
        assert_eq!(job["status"], "succeeded", "{name}: {}", &job.to_string()[..job.to_string().len().min(2000)]);
        let r = &job["result"];
        let (_, path) = program(&app, &job).await;
        assert!(path.moves.len() >= input.moves.len(), "{name}");
        assert_feeds_within_limits(&path, r, &input);
    }
    app.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_ball_end_mill_finishing_a_valley_slows_down_to_hold_the_cutting_point_feed() {
    let app = TestApp::start().await;
    // A valley in the XZ plane: a G18 arc of radius 4.692 about a centre above the path;
    // with the 6 mm ball (r = 3) R/(R + r) = 0.61 (seed 000).
    let gcode =
        "G21 G90 G18\nS8000 M3\nG0 X-2.25 Y0 Z0.578\nG1 X-2.249 F1200\nG3 X2.249 Z0.578 I2.249 K4.114\nG1 X2.25\nM30\n";
    let body = json!({
        "program": {"gcode": gcode}, "tool_type": "ball", "diameter_mm": 6,
        "mode": "surface_finishing", "min_feed_mm_min": 100, "max_feed_mm_min": 4000,
        "max_feed_change_per_mm": 0
    });
    let a = app.post_wait("/v1/feeds", body).await;
    assert_eq!(a.body["status"], "succeeded", "{}", a.text);
    assert_eq!(a.body["result"]["strategy"], "cutting_point");
    let (_, path) = program(&app, &a.body).await;
    let arc = path.moves.iter().find(|m| matches!(m.motion, Motion::Arc { .. })).expect("the arc stays an arc");
    assert!((arc.feed_mm_min.unwrap() - 0.61 * 1200.0).abs() < 2.0, "{arc:?}");
    app.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn bad_feed_requests_are_refused_naming_the_field() {
    let app = TestApp::start().await;
    // A shop's own end mill without a force model cannot hold a constant force.
    let own = app
        .post("/v1/tools", json!({"name": "shop ball D10", "tool_type": "ball", "diameter_mm": 10, "flutes": 2}))
        .await;
    let mut no_model = concave_request();
    no_model.as_object_mut().unwrap().remove("tool_type");
    no_model.as_object_mut().unwrap().remove("diameter_mm");
    no_model["tool_id"] = own.body["id"].clone();
    assert_problem(&app.post("/v1/feeds", no_model).await, 422, Some("strategy"));
    let mut no_stock = concave_request();
    no_stock.as_object_mut().unwrap().remove("stock");
    assert_problem(&app.post("/v1/feeds", no_stock).await, 422, Some("stock"));
    let mut number = concave_request();
    number["output"] = json!({"program_number": 10000});
    assert_problem(&app.post("/v1/feeds", number).await, 422, Some("output.program_number"));
    let mut too_fast = concave_request();
    too_fast["max_feed_mm_min"] = json!(1.0e6);
    assert_problem(&app.post("/v1/feeds", too_fast).await, 422, Some("max_feed_mm_min"));
    let mut inverted = concave_request();
    inverted["min_feed_mm_min"] = json!(5000);
    inverted["max_feed_mm_min"] = json!(1000);
    assert_problem(&app.post("/v1/feeds", inverted).await, 422, Some("min_feed_mm_min"));
    let mut bad_line = concave_request();
    bad_line["program"] = json!({"gcode": "G21\nG1 X10 Q7 F100\n"});
    assert_problem(&app.post("/v1/feeds", bad_line).await, 422, Some("program.gcode"));
    let mut too_many = concave_request();
    too_many["program"] = json!({"gcode": "G21 G90\nS9600 M3\nG1 X5000 Y0 Z-5 F5760\nM30\n"});
    too_many["sample_spacing_mm"] = json!(0.0004);
    assert_problem(&app.post("/v1/feeds", too_many).await, 422, Some("sample_spacing_mm"));
    let mut zero_feed = concave_request();
    zero_feed["min_feed_mm_min"] = json!(1e-300);
    assert_problem(&app.post("/v1/feeds", zero_feed).await, 422, Some("min_feed_mm_min"));
    let mut spindle = concave_request();
    spindle["spindle_rpm"] = json!(1e308);
    assert_problem(&app.post("/v1/feeds", spindle).await, 422, Some("spindle_rpm"));
    let mut normals = concave_request();
    normals.as_object_mut().unwrap().remove("stock");
    normals["mode"] = json!("surface_finishing");
    let square = app.post("/v1/feeds", normals.clone()).await;
    assert_problem(&square, 422, Some("tool_type"));
    assert!(square.body["detail"].as_str().unwrap().contains("needs a ball end mill"), "{}", square.text);
    normals["tool_type"] = json!("ball");
    normals["diameter_mm"] = json!(6);
    normals["min_feed_mm_min"] = json!(100);
    normals["max_feed_mm_min"] = json!(4000);
    normals["contact_normals"] = json!([[0, 0, -1]]);
    assert_problem(&app.post("/v1/feeds", normals.clone()).await, 422, Some("contact_normals"));
    normals.as_object_mut().unwrap().remove("contact_normals");
    normals["strategy"] = json!("both");
    assert_problem(&app.post("/v1/feeds", normals).await, 422, Some("strategy"));
    let jobs = app.get("/v1/jobs?kind=feeds").await;
    assert_eq!(jobs.body["total"], 0, "refused requests make no job: {}", jobs.text);
    app.stop().await;
}

/// Two helical entries (10 turns down 10 mm about a 2 mm circle: a 14 mm hole, the 10 mm
/// tool in a full slot all round), each followed by a full slot 28 mm long.
const HELICAL_ENTRIES: &str = "G21 G90 G17\nS9600 M3\nG0 X17 Y20 Z2\nG1 Z0 F1000\nG2 X17 Y20 Z-10 I-2 J0 P10 F1500\nG1 X45 F2000\nG0 Z2\nG0 X17 Y60\nG1 Z0 F1000\nG2 X17 Y60 Z-10 I-2 J0 P10 F1500\nG1 X45 F2000\nG0 Z5\nM30\n";

fn helical_request() -> Value {
    json!({
        "program": {"gcode": HELICAL_ENTRIES}, "tool_type": "square", "diameter_mm": 10,
        "stock": {"box": {"x_min": 0, "y_min": 0, "z_min": -10, "x_max": 60, "y_max": 80, "z_max": 0}}
    })
}

fn total(figures: &Value) -> f64 {
    figures["cost"]["total"].as_f64().unwrap_or_else(|| panic!("no cost: {figures}"))
}

/// Posts a feeds job and asserts that it succeeded.
async fn feeds(app: &TestApp, body: Value) -> Value {
    let a = app.send(reqwest::Method::POST, "/v1/feeds", Some(body), &[("prefer", "wait=300")]).await;
    assert_eq!(a.body["status"], "succeeded", "{}", &a.text[..a.text.len().min(3000)]);
    a.body
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn on_trochoidal_ngc_the_default_min_cost_never_costs_more_than_the_input_with_6_or_10_mm_tools() {
    let app = TestApp::start().await;
    for diameter in [6.0, 10.0] {
        let body = json!({
            "program": {"gcode": shared("trochoidal.ngc")},
            "tool_type": "square", "diameter_mm": diameter,
            "stock": {"box": {"x_min": -60, "y_min": -10, "z_min": -10, "x_max": 40, "y_max": 90, "z_max": 0}}
        });
        let job = feeds(&app, body.clone()).await;
        let r = &job["result"];
        assert_eq!(r["objective"], "min_cost");
        let (before, after) = (total(&r["before"]), total(&r["after"]));
        assert!(after <= before, "D{diameter}: {before} → {after}");
        for figures in [&r["before"], &r["after"]] {
            for field in ["consumption", "nominal_time_min", "kinematic_time_min", "outside_model", "extrapolated"] {
                assert!(!figures[field].is_null(), "D{diameter}: no {field} in {figures}");
            }
        }
        // The costing job costs the written program as the feeds job did.
        let mut costing = body;
        costing.as_object_mut().unwrap().remove("program");
        costing["job_id"] = job["id"].clone();
        let c = app.send(reqwest::Method::POST, "/v1/costing", Some(costing), &[("prefer", "wait=300")]).await;
        assert_eq!(c.body["status"], "succeeded", "{}", c.text);
        let costed = c.body["result"]["cost"]["total"].as_f64().unwrap();
        assert!((costed - after).abs() <= 0.02 * after, "D{diameter}: costing {costed}, feeds job {after}");
    }
    app.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn full_slot_helical_entries_cost_no_more_after_min_cost_and_never_drop_to_the_minimum_feed() {
    let app = TestApp::start().await;
    let job = feeds(&app, helical_request()).await;
    let r = &job["result"];
    assert!(total(&r["after"]) <= total(&r["before"]), "{} → {}", r["before"]["cost"], r["after"]["cost"]);
    assert!(r["before"]["extrapolated"].as_bool().unwrap(), "a full slot at Ad 10 is outside the experiments");
    let min_feed = r["limits"]["min_feed_mm_min"].as_f64().unwrap();
    let blocks = &r["blocks"];
    for (i, line) in blocks["line"].as_array().unwrap().iter().enumerate() {
        if [5, 10].contains(&line.as_u64().unwrap()) {
            let f = blocks["feed_mm_min"][i].as_f64().unwrap();
            assert!(f > 2.0 * min_feed, "the helix on line {line} runs at F{f}: {blocks}");
        }
    }
    // The papers' rule as written drops what it cannot hold to the minimum feed, and
    // pays for it in tool wear.
    let mut papers = helical_request();
    papers["objective"] = json!("constant_force");
    let constant = feeds(&app, papers).await;
    let c = &constant["result"];
    assert!(c["blocks"]["feed_mm_min"].as_array().unwrap().iter().any(|f| f.as_f64() == Some(min_feed)), "{c}");
    assert!(total(&c["after"]) > total(&r["after"]), "{} vs {}", c["after"]["cost"], r["after"]["cost"]);
    app.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn min_time_with_a_raised_force_limit_is_faster_than_the_constant_force() {
    let app = TestApp::start().await;
    let mut constant = concave_request();
    constant["objective"] = json!("constant_force");
    let mut fast = concave_request();
    fast["objective"] = json!("min_time");
    fast["max_force_n"] = json!(2.0 * 269.1);
    let (c, f) = (feeds(&app, constant).await, feeds(&app, fast).await);
    let time = |j: &Value| j["result"]["after"]["kinematic_time_min"].as_f64().unwrap();
    assert!(time(&f) < time(&c), "{} ≥ {}", time(&f), time(&c));
    assert!(close(&f["result"]["max_force_n"], 538.2, 0.5), "{}", f["result"]);
    let peak = f["result"]["after"]["force_n"]["max"].as_f64().unwrap();
    assert!(peak > 300.0, "the force rises above the target: {peak}");
    app.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn objectives_that_cannot_apply_are_refused_naming_the_field() {
    let app = TestApp::start().await;
    let mut surface = concave_request();
    surface.as_object_mut().unwrap().remove("stock");
    surface["mode"] = json!("surface_finishing");
    surface["tool_type"] = json!("ball");
    surface["diameter_mm"] = json!(6);
    surface["objective"] = json!("min_cost");
    assert_problem(&app.post("/v1/feeds", surface).await, 422, Some("objective"));
    let mut limit = concave_request();
    limit["max_force_n"] = json!(-1);
    assert_problem(&app.post("/v1/feeds", limit).await, 422, Some("max_force_n"));
    let mut unknown = concave_request();
    unknown["objective"] = json!("max_profit");
    assert!(app.post("/v1/feeds", unknown).await.status.is_client_error());
    app.stop().await;
}
