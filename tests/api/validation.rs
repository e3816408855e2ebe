//! A request is validated once: the fields its schema refuses and the values the job's
//! checks refuse come in one problem, for every job kind, and a core's refusal names the
//! request's field.

use crate::common::{assert_problem, TestApp};
use serde_json::{json, Value};

const GCODE: &str = "G21 G90 G17\nG0 X-10 Y5 Z5\nS9600 M3\nG1 Z-5 F1000\nG1 X110 F5760\nM30";

fn stock() -> Value {
    json!({"box": {"x_min": 0, "y_min": -40, "z_min": -10, "x_max": 100, "y_max": 0, "z_max": 0}})
}

fn pocket() -> Value {
    json!({"outer": [[0, 0], [80, 0], [80, 60], [0, 60]]})
}

/// Merges `extra` into `base`.
fn with(mut base: Value, extra: Value) -> Value {
    for (key, value) in extra.as_object().unwrap() {
        base[key] = value.clone();
    }
    base
}

fn fields(body: &Value) -> Vec<String> {
    body["errors"].as_array().unwrap().iter().map(|e| e["field"].as_str().unwrap().to_string()).collect()
}

/// Per kind: its route, a valid request, and a type fault and a range fault in two other
/// fields, with the fields named.
fn cases() -> Vec<(&'static str, Value, Value, [&'static str; 2])> {
    let path_job = json!({"program": {"gcode": GCODE}, "tool_type": "square", "diameter_mm": 10, "stock": stock()});
    let cavity = json!({"contour": pocket(), "z_top": 0, "z_bottom": -10});
    vec![
        (
            "/v1/conditions",
            json!({"tool_type": "square", "diameter_mm": 10}),
            json!({"operation": 5, "spindle_rpm": -1}),
            ["operation", "spindle_rpm"],
        ),
        (
            "/v1/analysis",
            path_job.clone(),
            json!({"alpha_limit_deg": "forty", "cell_mm": -1}),
            ["alpha_limit_deg", "cell_mm"],
        ),
        (
            "/v1/costing",
            path_job.clone(),
            json!({"spindle_rpm": "fast", "tool_price": -5}),
            ["spindle_rpm", "tool_price"],
        ),
        (
            "/v1/feeds",
            path_job,
            json!({"target_force_n": "high", "min_feed_mm_min": -1}),
            ["target_force_n", "min_feed_mm_min"],
        ),
        (
            "/v1/trochoids",
            with(cavity.clone(), json!({"tool_type": "square", "diameter_mm": 10})),
            json!({"pitch_mm": "x", "alpha_limit_deg": 200}),
            ["pitch_mm", "alpha_limit_deg"],
        ),
        (
            "/v1/plans",
            cavity,
            json!({"target_consumption": "half", "max_force_factor": 9}),
            ["target_consumption", "max_force_factor"],
        ),
    ]
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_type_fault_and_a_range_fault_of_every_job_kind_come_in_one_problem() {
    let app = TestApp::start_with(|c| c.workers = Some(0)).await;
    for (path, valid, faults, named) in cases() {
        let a = app.post(path, with(valid.clone(), faults.clone())).await;
        assert_problem(&a, 422, None);
        assert_eq!(fields(&a.body), named, "{path}: {}", a.text);
        assert!(a.body["detail"].as_str().unwrap().ends_with("(and 1 more)"), "{path}: {}", a.text);
        let kind = a.body["type"].clone();
        // The same through the generic route, the fields under `input`.
        let generic = json!({"kind": kind_of(path), "input": with(valid.clone(), faults)});
        let a = app.post("/v1/jobs", generic).await;
        assert_problem(&a, 422, None);
        assert_eq!(fields(&a.body), named.map(|f| format!("input.{f}")), "{path}: {}", a.text);
        assert_eq!(a.body["type"], kind);
        // And the valid request is accepted (queued: no worker runs it).
        let a = app.post(path, valid).await;
        assert_eq!(a.status.as_u16(), 202, "{path}: {}", a.text);
    }
    app.stop().await;
}

fn kind_of(path: &str) -> &'static str {
    match path {
        "/v1/conditions" => "conditions",
        "/v1/analysis" => "analysis",
        "/v1/costing" => "costing",
        "/v1/feeds" => "feeds",
        "/v1/trochoids" => "trochoids",
        _ => "plan",
    }
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_range_fault_is_not_repeated_for_a_field_the_schema_refused() {
    let app = TestApp::start_with(|c| c.workers = Some(0)).await;
    // `program` refused by its schema is set aside; the check "give exactly one of program
    // and job_id" is about it and is not added.
    let body = json!({"program": 7, "tool_type": "square", "diameter_mm": 10, "stock": stock(), "tool_price": -1});
    let a = app.post("/v1/costing", body).await;
    assert_problem(&a, 422, None);
    assert_eq!(fields(&a.body), ["program", "tool_price"], "{}", a.text);
    app.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn the_cores_refusals_name_the_requests_fields_not_the_cores() {
    let app = TestApp::start_with(|c| c.workers = Some(0)).await;
    // A layer thinner than the core's length tolerance passes the request's own check
    // (z_bottom below z_top) and is refused by the core's `z_bottom_mm`.
    let body = json!({"contour": pocket(), "z_top": 0, "z_bottom": -1e-12, "tool_type": "square", "diameter_mm": 10});
    let a = app.post("/v1/trochoids", body).await;
    assert_problem(&a, 422, None);
    assert_eq!(fields(&a.body), ["z_bottom"], "{}", a.text);
    // The same layer under a plan's `layers`, where the core names the layer's own field.
    let body = json!({"layers": [{"contour": pocket(), "z_top": 0, "z_bottom": -1e-12}], "baseline": false});
    let a = app.post("/v1/plans", body).await;
    assert_problem(&a, 422, None);
    let named = fields(&a.body);
    assert!(!named.is_empty() && named.iter().all(|f| !f.ends_with("_mm")), "{}", a.text);
    app.stop().await;
}

/// A program whose third line has a word no control knows (`Q7`).
const BAD_GCODE: &str = "G21\nG1 X1 F100\nG1 X2 Q7\n";

/// Per kind: its route, a valid request, and one fault of the schema or the checks with one
/// found only while resolving the request (an unknown row, or a program's bad word), with
/// the fields they name.
fn resolve_cases() -> Vec<(&'static str, Value, Value, [&'static str; 2])> {
    let valid: Vec<Value> = cases().into_iter().map(|(_, valid, _, _)| valid).collect();
    let bad_program = json!({"gcode": BAD_GCODE});
    vec![
        (
            "/v1/conditions",
            valid[0].clone(),
            json!({"spindle_rpm": -1, "material": "Unobtainium"}),
            ["spindle_rpm", "material"],
        ),
        (
            "/v1/analysis",
            valid[1].clone(),
            json!({"alpha_limit_deg": "forty", "program": bad_program}),
            ["alpha_limit_deg", "program.gcode"],
        ),
        (
            "/v1/costing",
            valid[2].clone(),
            json!({"tool_price": -5, "cost_rates_id": 9999}),
            ["tool_price", "cost_rates_id"],
        ),
        (
            "/v1/feeds",
            valid[3].clone(),
            json!({"min_feed_mm_min": -1, "machine_id": 9999}),
            ["min_feed_mm_min", "machine_id"],
        ),
        (
            "/v1/trochoids",
            valid[4].clone(),
            json!({"pitch_mm": "x", "program": bad_program}),
            ["pitch_mm", "program.gcode"],
        ),
        (
            "/v1/plans",
            valid[5].clone(),
            json!({"max_force_factor": 9, "tool_ids": [9999]}),
            ["max_force_factor", "tool_ids[0]"],
        ),
    ]
}

/// The number of jobs stored.
async fn stored_jobs(app: &TestApp) -> i64 {
    let a = app.get("/v1/jobs").await;
    assert_eq!(a.status.as_u16(), 200, "{}", a.text);
    a.body["total"].as_i64().unwrap()
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_fault_of_the_checks_and_a_fault_found_resolving_the_request_come_in_one_problem_for_every_kind() {
    let app = TestApp::start_with(|c| c.workers = Some(0)).await;
    for (path, valid, faults, named) in resolve_cases() {
        let a = app.post(path, with(valid.clone(), faults.clone())).await;
        assert_problem(&a, 422, None);
        assert_eq!(fields(&a.body), named, "{path}: {}", a.text);
        assert!(a.body["detail"].as_str().unwrap().ends_with("(and 1 more)"), "{path}: {}", a.text);
        if named.contains(&"program.gcode") {
            // The program's fault names its line and word.
            assert!(a.text.contains("line 3, column 7 (Q7)"), "{path}: {}", a.text);
        }
        // The same through the generic route, the fields under `input`.
        let generic = json!({"kind": kind_of(path), "input": with(valid.clone(), faults)});
        let a = app.post("/v1/jobs", generic).await;
        assert_problem(&a, 422, None);
        assert_eq!(fields(&a.body), named.map(|f| format!("input.{f}")), "{path}: {}", a.text);
    }
    app.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_programs_bad_word_is_named_beside_an_unknown_tool_and_material() {
    let app = TestApp::start_with(|c| c.workers = Some(0)).await;
    // The program is read although its tool is unknown, and the material is looked up
    // although the tool is not found.
    let body = json!({"program": {"gcode": BAD_GCODE}, "tool_id": 9999, "material": "Unobtainium", "stock": stock()});
    for path in ["/v1/analysis", "/v1/costing", "/v1/feeds"] {
        let a = app.post(path, body.clone()).await;
        assert_problem(&a, 422, None);
        assert_eq!(fields(&a.body), ["material", "tool_id", "program.gcode"], "{path}: {}", a.text);
    }
    app.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_refused_diameter_is_not_blamed_on_tool_id() {
    let app = TestApp::start_with(|c| c.workers = Some(0)).await;
    let valid: Vec<(&str, Value)> = cases().into_iter().take(5).map(|(path, valid, _, _)| (path, valid)).collect();
    // Refused by its schema (and set aside), by the checks, and by the look-up (no such
    // tool): each time the diameter alone is named.
    for diameter in [json!("ten"), json!(-10), json!(10.37)] {
        for (path, valid) in &valid {
            let a = app.post(path, with(valid.clone(), json!({"diameter_mm": diameter}))).await;
            assert_problem(&a, 422, None);
            assert_eq!(fields(&a.body), ["diameter_mm"], "{path} with {diameter}: {}", a.text);
        }
    }
    app.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn nothing_is_stored_or_queued_when_a_request_has_a_fault_and_a_valid_one_still_is() {
    let app = TestApp::start_with(|c| c.workers = Some(0)).await;
    for (path, valid, faults, _) in resolve_cases() {
        let a = app.post(path, with(valid, faults)).await;
        assert_problem(&a, 422, None);
    }
    // A body that is not JSON is a 400: it has no fields to name.
    let a = app.send(reqwest::Method::POST, "/v1/conditions", None, &[("content-type", "application/json")]).await;
    assert_eq!(a.status.as_u16(), 400, "{}", a.text);
    assert_eq!(stored_jobs(&app).await, 0);
    for (path, valid, _, _) in resolve_cases() {
        let a = app.post(path, valid).await;
        assert_eq!(a.status.as_u16(), 202, "{path}: {}", a.text);
    }
    assert_eq!(stored_jobs(&app).await, 6);
    app.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_pockets_fault_and_a_costings_unknown_job_are_named_beside_the_other_unknown_rows() {
    let app = TestApp::start_with(|c| c.workers = Some(0)).await;
    let bowtie = json!({"outer": [[0, 0], [10, 10], [10, 0], [0, 10]]});
    let trochoids = json!({"contour": bowtie, "z_top": 0, "z_bottom": -10, "tool_id": 9999});
    let plan = json!({"contour": bowtie, "z_top": 0, "z_bottom": -10, "diameters_mm": [10.37]});
    for (path, body, first) in [("/v1/trochoids", trochoids, "tool_id"), ("/v1/plans", plan, "diameters_mm[0]")] {
        let a = app.post(path, body).await;
        assert_problem(&a, 422, None);
        let named = fields(&a.body);
        assert_eq!(named.len(), 2, "{path}: {}", a.text);
        assert_eq!(named[0], first, "{path}: {}", a.text);
        assert!(named[1].starts_with("contour"), "{path}: {}", a.text);
    }
    let costing = json!({"job_id": "00000000-0000-4000-8000-000000000000", "material": "Unobtainium",
        "tool_type": "square", "diameter_mm": 10, "stock": stock()});
    let a = app.post("/v1/costing", costing).await;
    assert_problem(&a, 422, None);
    assert_eq!(fields(&a.body), ["job_id", "material"], "{}", a.text);
    assert_eq!(stored_jobs(&app).await, 0);
    app.stop().await;
}
