//! The `conditions` job through `POST /v1/conditions` and `POST /v1/jobs`.

use crate::common::{assert_problem, close, TestApp};
use serde_json::json;

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn the_10_mm_standard_conditions_match_model_section_2_and_give_beta0_as_the_force() {
    let app = TestApp::start().await;
    let a = app.post_wait("/v1/conditions", json!({"tool_type": "square", "diameter_mm": 10})).await;
    assert_eq!(a.status, 201, "{}", a.text);
    assert_eq!(a.body["status"], "succeeded");
    let r = &a.body["result"];
    assert_eq!(r["material"]["name"], "SKD61");
    assert_eq!(r["operation"], "standard_side_cutting");
    assert!(close(&r["conditions"]["spindle_rpm"], 9600.0, 1e-9));
    assert!(close(&r["conditions"]["fz_mm"], 0.10, 1e-12));
    assert!(close(&r["conditions"]["feed_mm_min"], 5760.0, 1e-6));
    assert!(close(&r["conditions"]["rd_mm"], 0.5, 1e-12));
    assert!(close(&r["conditions"]["ad_mm"], 10.0, 1e-12));
    assert!(close(&r["conditions"]["cutting_speed_m_min"], 301.6, 0.05), "V = 302 m/min (seed 001 Table 1)");
    assert!(close(&r["engagement"]["angle_deg"], 25.8, 0.05));
    assert!(close(&r["engagement"]["max_chip_thickness_um"], 43.6, 0.05));
    assert!(close(&r["engagement"]["arc_length_mm"], 2.26, 0.005));
    assert!(close(&r["force"]["fxy_n"], 269.1, 1e-3), "β0 of seed 001 Table 4");
    assert_eq!(r["force"]["source"], "paper");
    app.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn the_6_and_8_mm_standards_match_seed_001_table_2_and_give_their_beta0() {
    let app = TestApp::start().await;
    for (d, t_um, l_mm, beta0, feed) in [(6.0, 17.4, 1.35, 83.84, 3600.0), (8.0, 30.5, 1.80, 163.0, 5040.0)] {
        let a = app.post_wait("/v1/conditions", json!({"tool_type": "square", "diameter_mm": d})).await;
        let r = &a.body["result"];
        assert!(close(&r["engagement"]["max_chip_thickness_um"], t_um, 0.05), "D{d}: {}", a.text);
        assert!(close(&r["engagement"]["arc_length_mm"], l_mm, 0.005), "D{d}");
        assert!(close(&r["force"]["fxy_n"], beta0, 1e-3), "D{d}");
        assert!(close(&r["conditions"]["feed_mm_min"], feed, 1e-6), "D{d}");
    }
    app.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn rough_side_cutting_uses_seed_004_conditions_and_halving_the_depth_halves_the_force() {
    let app = TestApp::start().await;
    let id = app.tool_id("square", 10.0).await;
    let full = app
        .post_wait(
            "/v1/jobs",
            json!({"kind": "conditions", "input": {"tool_id": id, "operation": "rough_side_cutting"}}),
        )
        .await;
    let r = &full.body["result"];
    assert!(close(&r["conditions"]["spindle_rpm"], 4800.0, 1e-9), "{}", full.text);
    assert!(close(&r["conditions"]["ad_last_layer_mm"], 5.0, 1e-12));
    assert!(close(&r["force"]["fxy_n"], 269.1, 1e-3));
    let half =
        app.post_wait("/v1/conditions", json!({"tool_id": id, "operation": "rough_side_cutting", "ad_mm": 5.0})).await;
    assert!(close(&half.body["result"]["force"]["fxy_n"], 269.1 / 2.0, 1e-3));
    assert_eq!(half.body["result"]["conditions"]["overridden"], json!(["ad_mm"]));
    app.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_ball_end_mill_gets_conditions_without_a_force_and_says_why() {
    let app = TestApp::start().await;
    let a = app
        .post_wait("/v1/conditions", json!({"tool_type": "ball", "diameter_mm": 10, "operation": "helical_boring"}))
        .await;
    let r = &a.body["result"];
    assert!(close(&r["conditions"]["spindle_rpm"], 2800.0, 1e-9), "{}", a.text);
    assert!(close(&r["conditions"]["feed_mm_min"], 280.0, 1e-9));
    assert!(r["force"].is_null());
    assert!(r["warnings"][0].as_str().unwrap().contains("ball end mill"));
    app.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn bad_conditions_requests_are_refused_at_submission_naming_the_field_and_create_no_job() {
    let app = TestApp::start().await;
    let cases = [
        (json!({"tool_type": "square", "diameter_mm": 11}), "diameter_mm"),
        (json!({"tool_type": "square"}), "tool_id"),
        (json!({"tool_type": "squar", "diameter_mm": 10}), "tool_type"),
        (json!({"tool_id": 99999}), "tool_id"),
        (json!({"tool_type": "square", "diameter_mm": 10, "fz_mm": -0.1}), "fz_mm"),
        (json!({"tool_type": "square", "diameter_mm": 10, "material": "unobtainium"}), "material"),
        (json!({"tool_type": "square", "diameter_mm": 10, "operation": "helical_boring"}), "operation"),
        (json!({"tool_type": "square", "diameter_mm": 10, "colour": "red"}), "colour"),
    ];
    for (body, field) in cases {
        let a = app.post("/v1/conditions", body.clone()).await;
        assert_problem(&a, 422, Some(field));
    }
    let a = app.post("/v1/jobs", json!({"kind": "conditions", "input": {"tool_id": 99999}})).await;
    assert_problem(&a, 422, Some("input.tool_id"));
    let a = app.post("/v1/jobs", json!({"kind": "teleport", "input": {}})).await;
    assert_problem(&a, 422, Some("kind"));
    let jobs = app.get("/v1/jobs").await;
    assert_eq!(jobs.body["total"], 0, "refused requests create no job");
    app.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn the_default_material_is_still_the_seeded_skd61_after_a_shop_renames_it() {
    let app = TestApp::start().await;
    let list = app.get("/v1/materials?name=SKD61").await;
    let id = list.body["items"][0]["id"].as_i64().expect("the seeded SKD61");
    let renamed = app.patch(&format!("/v1/materials/{id}"), json!({"name": "SKD61 (our heat lot)"})).await;
    assert_eq!(renamed.status, 200, "{}", renamed.text);
    let a = app.post_wait("/v1/conditions", json!({"tool_type": "square", "diameter_mm": 10})).await;
    assert_eq!(a.status, 201, "{}", a.text);
    assert_eq!(a.body["result"]["material"]["id"], id);
    assert_eq!(a.body["result"]["material"]["name"], "SKD61 (our heat lot)");
    app.stop().await;
}
