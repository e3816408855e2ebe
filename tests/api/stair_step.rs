//! A plan takes off the steps a sloped floor leaves between its layers (issue 32 item 4): the
//! stair-step roughing with a ball or radius end mill, in the plan's time, cost and program.

use crate::common::{assert_problem, close, TestApp};
use serde_json::{json, Value};

/// A 60 × 40 mm cavity whose floor slopes 1 in 3 along x, from z −5 at x 60 to −20 at x 15,
/// sliced as a CAM system slices it at Ad 5 (each layer's contour is its bottom section).
pub fn slanted_floor(stair_step: Option<Value>) -> Value {
    let layer = |x: f64, top: f64, bottom: f64| json!({"contour": {"outer": [[0, 0], [x, 0], [x, 40], [0, 40]]}, "z_top": top, "z_bottom": bottom});
    let mut body = json!({
        "layers": [layer(60.0, 0.0, -5.0), layer(45.0, -5.0, -10.0), layer(30.0, -10.0, -15.0), layer(15.0, -15.0, -20.0)],
        "diameters_mm": [10], "sample_spacing_mm": 0.2, "baseline": false
    });
    if let Some(step) = stair_step {
        body["stair_step"] = step;
    }
    body
}

/// The steps over the slope: three wedges 15 mm wide and 5 mm high across the 40 mm, mm³.
const STEPS_MM3: f64 = 3.0 * 15.0 * 5.0 / 2.0 * 40.0;

async fn plan(app: &TestApp, body: Value) -> Value {
    let plan = app.send(reqwest::Method::POST, "/v1/plans", Some(body), &[("prefer", "wait=300")]).await;
    assert_eq!(plan.body["status"], "succeeded", "{}", &plan.text[..plan.text.len().min(3000)]);
    plan.body
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_ball_takes_off_the_steps_of_a_slanted_floor_after_the_roughing_in_the_plans_time_cost_and_program() {
    let app = TestApp::start().await;
    let job = plan(&app, slanted_floor(Some(json!({})))).await;
    let r = &job["result"];
    let step = &r["stair_step"];
    assert_eq!(step["tool"], "ball D10 R5", "{step}");
    assert_eq!(step["tool_number"], 2);
    // The R5 ball's standard side cut (seed 004 Table 7): S 10000, Ad 0.6, Rd 4, its F* as
    // contour-parallel roughing takes it, beside the pass before (250 N; 42 N along a wall).
    assert!(close(&step["spindle_rpm"], 10000.0, 1e-6) && close(&step["axial_depth_mm"], 0.6, 1e-9), "{step}");
    assert!(close(&step["radial_depth_mm"], 4.0, 1e-9) && close(&step["target_force_n"], 250.0, 10.0), "{step}");
    // At that cut the ball lasts its 320 m; the rings, up to 180° at the tip, wear it more.
    let used = step["consumption"].as_f64().unwrap();
    assert!(used > 2.3 / 320.0 && used < 0.5, "{step}");
    assert!(step["levels"].as_array().is_some_and(|l| l.len() >= 25), "{step}");
    assert!(close(&step["step_volume_mm3"], STEPS_MM3, 0.03 * STEPS_MM3), "{step}");
    assert!(close(&step["removed_volume_mm3"], 0.9 * STEPS_MM3, 0.15 * STEPS_MM3), "{step}");
    // The plan's totals hold the roughing's layers and the step.
    let layers: f64 = r["layers"].as_array().unwrap().iter().map(|l| l["kinematic_time_min"].as_f64().unwrap()).sum();
    let total = r["totals"]["kinematic_time_min"].as_f64().unwrap();
    let step_min = step["kinematic_time_min"].as_f64().unwrap();
    assert!(step_min > 0.5 && total > layers + 0.9 * step_min, "{} {layers} {step_min}", r["totals"]);
    assert!(r["totals"]["cost"].as_f64().unwrap() > step["cost"]["total"].as_f64().unwrap());
    // The program: the roughing with T1, then the ball with T2 and its levels.
    let id = job["id"].as_str().unwrap();
    let program = app.get(&format!("/v1/jobs/{id}/program")).await.text;
    let (t1, t2) = (program.find("T1 M6").expect("T1"), program.find("T2 M6").expect("T2"));
    assert!(t1 < t2 && program[t2..].contains("G43 H2"), "{}", &program[t2..t2 + 200]);
    assert!(program[t2..].contains("STAIR-STEP INTERMEDIATE ROUGHING"));
    assert!(program[t2..].contains("S10000"));
    // The stock the plan keeps is what the ball left.
    let rest = r["rest_material"]["volume_mm3"].as_f64().unwrap();
    assert!(rest < 0.4 * STEPS_MM3, "{}", r["rest_material"]);
    app.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn layers_of_different_contours_without_a_stair_step_say_how_to_ask_for_it_and_a_radius_end_mill_can_do_it() {
    let app = TestApp::start().await;
    let without = plan(&app, slanted_floor(None)).await;
    assert!(without["result"]["stair_step"].is_null());
    let warnings = without["result"]["warnings"].to_string();
    assert!(warnings.contains("stair_step"), "{warnings}");
    let radius =
        plan(&app, slanted_floor(Some(json!({"tool_type": "radius", "diameter_mm": 10, "radial_depth_mm": 3})))).await;
    let step = &radius["result"]["stair_step"];
    assert_eq!(step["tool_type"], "radius", "{step}");
    // Ad 0.06 D by default, Rd as given.
    assert!(close(&step["axial_depth_mm"], 0.6, 1e-9) && close(&step["radial_depth_mm"], 3.0, 1e-9), "{step}");
    assert!(step["removed_volume_mm3"].as_f64().unwrap() > 0.7 * STEPS_MM3, "{step}");
    app.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_stair_step_request_with_faults_is_refused_naming_each_and_changes_nothing() {
    let app = TestApp::start().await;
    let bad =
        slanted_floor(Some(json!({"tool_id": 1, "tool_type": "square", "axial_depth_mm": -1, "radial_depth_mm": 0})));
    let a = app.post("/v1/plans", bad).await;
    for field in
        ["stair_step.tool_id", "stair_step.tool_type", "stair_step.axial_depth_mm", "stair_step.radial_depth_mm"]
    {
        assert_problem(&a, 422, Some(field));
    }
    let tiny =
        app.post("/v1/plans", slanted_floor(Some(json!({"axial_depth_mm": 0.001, "radial_depth_mm": 1e6})))).await;
    for field in ["stair_step.axial_depth_mm", "stair_step.radial_depth_mm"] {
        assert_problem(&tiny, 422, Some(field));
    }
    let mut last_tool = slanted_floor(Some(json!({})));
    last_tool["output"] = json!({"tool_number": 9999});
    assert_problem(&app.post("/v1/plans", last_tool).await, 422, Some("output.tool_number"));
    let unknown = app.post("/v1/plans", slanted_floor(Some(json!({"tool_id": 987654})))).await;
    assert_problem(&unknown, 422, Some("stair_step.tool_id"));
    let tools = app.get("/v1/tools?tool_type=square").await;
    let square =
        tools.body["items"].as_array().and_then(|t| t.first()).map(|t| t["id"].clone()).expect("a square tool");
    let square = app.post("/v1/plans", slanted_floor(Some(json!({"tool_id": square})))).await;
    assert_problem(&square, 422, Some("stair_step.tool_id"));
    let unknown_field = app.post("/v1/plans", slanted_floor(Some(json!({"depth": 1})))).await;
    assert_eq!(unknown_field.status.as_u16(), 422, "{}", unknown_field.text);
    let jobs = app.get("/v1/jobs").await;
    assert_eq!(jobs.body["items"].as_array().map(Vec::len), Some(0), "{}", jobs.text);
    app.stop().await;
}
