//! Default tools: a request by `tool_type` + `diameter_mm` takes the default tool of that
//! type and diameter, so a shop's second tool of a size breaks nothing; plans name tools by
//! id with `tool_ids`.

use crate::common::{assert_problem, close, TestApp};
use serde_json::{json, Value};

/// The README's second 10 mm square end mill.
fn shop_square_d10() -> Value {
    json!({"name": "shop square D10 z4", "tool_type": "square", "diameter_mm": 10, "flutes": 4, "price": 95})
}

/// A 30 × 20 mm box with rounded corners, 3 mm deep: a plan of one layer.
fn small_plan(extra: Value) -> Value {
    let mut body = json!({
        "contour": {"outer": [[6, 0], [24, 0, 0.414214], [30, 6], [30, 14, 0.414214], [24, 20], [6, 20, 0.414214],
                              [0, 14], [0, 6, 0.414214]]},
        "z_top": 0, "z_bottom": -3, "sample_spacing_mm": 0.2, "baseline": false
    });
    body.as_object_mut().unwrap().extend(extra.as_object().unwrap().clone());
    body
}

/// Most a small plan may take here, s.
const PLAN_DEADLINE_S: u64 = 600;

async fn finished_plan(app: &TestApp, body: Value) -> Value {
    let a = app.post("/v1/plans", body).await;
    assert!(a.status == 201 || a.status == 202, "{}", a.text);
    let job = app.wait_for_job_within(a.body["id"].as_str().unwrap(), PLAN_DEADLINE_S).await;
    assert_eq!(job["status"], "succeeded", "{job}");
    job
}

async fn default_ids(app: &TestApp, tool_type: &str, diameter: f64) -> Vec<i64> {
    let a = app.get(&format!("/v1/tools?default=true&tool_type={tool_type}&diameter_mm={diameter}")).await;
    assert_eq!(a.status, 200, "{}", a.text);
    a.body["items"].as_array().unwrap().iter().map(|t| t["id"].as_i64().unwrap()).collect()
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn every_seeded_tool_is_the_default_of_its_type_and_diameter() {
    let app = TestApp::start().await;
    let all = app.get("/v1/tools?limit=500").await;
    let defaults = app.get("/v1/tools?default=true&limit=500").await;
    assert_eq!(all.body["total"], defaults.body["total"], "{}", defaults.text);
    assert!(all.body["items"].as_array().unwrap().iter().all(|t| t["default"] == true), "{}", all.text);
    assert_eq!(app.get("/v1/tools?default=false").await.body["total"], 0);
    app.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_second_tool_of_a_size_leaves_requests_by_size_on_the_default_until_it_becomes_the_default() {
    let app = TestApp::start().await;
    let seeded = app.tool_id("square", 10.0).await;
    let mine = app.post("/v1/tools", shop_square_d10()).await;
    assert_eq!(mine.status, 201, "{}", mine.text);
    assert_eq!(mine.body["default"], false, "the second tool of a size is not its default");
    let mine = mine.body["id"].as_i64().unwrap();

    // Conditions by size still use the seeded tool.
    let a = app.post_wait("/v1/conditions", json!({"tool_type": "square", "diameter_mm": 10})).await;
    assert_eq!(a.status, 201, "{}", a.text);
    assert_eq!(a.body["result"]["tool"]["id"], seeded, "{}", a.text);
    assert_eq!(default_ids(&app, "square", 10.0).await, vec![seeded]);

    // The shop's own standard cut, then its tool made the default: requests by size use it.
    let row = app
        .post(
            "/v1/conditions/standard",
            json!({"tool_id": mine, "material_id": 1, "operation": "standard_side_cutting", "spindle_rpm": 8000,
                   "fz_mm": 0.08, "fz_min_mm": 0.004, "rd_mm": 0.5, "ad_mm": 10}),
        )
        .await;
    assert_eq!(row.status, 201, "{}", row.text);
    let made = app.patch(&format!("/v1/tools/{mine}"), json!({"default": true})).await;
    assert_eq!(made.status, 200, "{}", made.text);
    assert_eq!((made.body["default"].as_bool(), made.body["source"].as_str()), (Some(true), Some("user")));
    let old = app.get(&format!("/v1/tools/{seeded}")).await;
    assert_eq!(old.body["default"], false, "{}", old.text);
    // Switching the default is no edit of the seeded tool's data.
    assert_eq!(
        (old.body["source"].as_str(), old.body["edited"].as_bool()),
        (Some("paper"), Some(false)),
        "{}",
        old.text
    );
    let a = app.post_wait("/v1/conditions", json!({"tool_type": "square", "diameter_mm": 10})).await;
    assert_eq!(a.status, 201, "{}", a.text);
    assert_eq!(a.body["result"]["tool"]["id"], mine, "{}", a.text);
    assert!(close(&a.body["result"]["conditions"]["spindle_rpm"], 8000.0, 1e-9), "{}", a.text);

    // Deleting the default makes the oldest remaining tool of its size the default again.
    let row_id = row.body["id"].as_i64().unwrap();
    assert_eq!(app.delete(&format!("/v1/conditions/standard/{row_id}")).await.status, 204);
    assert_eq!(app.delete(&format!("/v1/tools/{mine}")).await.status, 204);
    assert_eq!(default_ids(&app, "square", 10.0).await, vec![seeded]);
    app.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_new_tool_can_take_the_default_at_once_and_a_size_without_a_default_is_refused_naming_the_field() {
    let app = TestApp::start().await;
    let seeded = app.tool_id("square", 10.0).await;
    let mut body = shop_square_d10();
    body["default"] = json!(true);
    let mine = app.post("/v1/tools", body).await;
    assert_eq!((mine.status.as_u16(), mine.body["default"].as_bool()), (201, Some(true)), "{}", mine.text);
    let mine = mine.body["id"].as_i64().unwrap();
    assert_eq!(default_ids(&app, "square", 10.0).await, vec![mine]);

    // No default left: a request by size is refused, naming the field and the tools.
    let cleared = app.patch(&format!("/v1/tools/{mine}"), json!({"default": false})).await;
    assert_eq!(cleared.body["default"], false, "{}", cleared.text);
    assert!(default_ids(&app, "square", 10.0).await.is_empty());
    let a = app.post("/v1/conditions", json!({"tool_type": "square", "diameter_mm": 10})).await;
    assert_problem(&a, 422, Some("tool_id"));
    assert!(a.text.contains(&seeded.to_string()) && a.text.contains(&mine.to_string()), "{}", a.text);

    // A PUT that leaves the flag out keeps it; one that names it sets it.
    let mut again = shop_square_d10();
    again["default"] = json!(true);
    let put = app.put(&format!("/v1/tools/{mine}"), again).await;
    assert_eq!(put.body["default"], true, "{}", put.text);
    let put = app.put(&format!("/v1/tools/{mine}"), shop_square_d10()).await;
    assert_eq!(put.body["default"], true, "{}", put.text);
    app.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_default_tool_moved_to_another_size_hands_its_default_on_and_takes_none_there() {
    let app = TestApp::start().await;
    let seeded_10 = app.tool_id("square", 10.0).await;
    let seeded_12 = app.tool_id("square", 12.0).await;
    let mine = app
        .post("/v1/tools", json!({"name": "shop square D11", "tool_type": "square", "diameter_mm": 11, "flutes": 4}))
        .await;
    assert_eq!(mine.body["default"], true, "the first tool of a size is its default: {}", mine.text);
    let mine = mine.body["id"].as_i64().unwrap();
    let second = app
        .post("/v1/tools", json!({"name": "shop square D11 b", "tool_type": "square", "diameter_mm": 11, "flutes": 2}))
        .await;
    let second = second.body["id"].as_i64().unwrap();
    let moved = app.patch(&format!("/v1/tools/{mine}"), json!({"diameter_mm": 12})).await;
    assert_eq!(moved.status, 200, "{}", moved.text);
    assert_eq!(moved.body["default"], false, "12 mm keeps its default: {}", moved.text);
    assert_eq!(default_ids(&app, "square", 12.0).await, vec![seeded_12]);
    assert_eq!(default_ids(&app, "square", 11.0).await, vec![second], "the one left at 11 mm takes it");
    assert_eq!(default_ids(&app, "square", 10.0).await, vec![seeded_10]);
    app.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn the_database_itself_refuses_two_defaults_of_one_type_and_diameter() {
    let app = TestApp::start().await;
    assert_eq!(app.post("/v1/tools", shop_square_d10()).await.status, 201);
    let pool = app.pool().await;
    let second = sqlx::query("UPDATE tools SET is_default = 1 WHERE name = 'shop square D10 z4'").execute(&pool).await;
    assert!(second.is_err(), "a second default must violate the unique index");
    pool.close().await;
    app.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_plan_by_diameter_takes_the_default_tool_and_a_plan_by_tool_ids_takes_those_tools() {
    let app = TestApp::start().await;
    let seeded = app.tool_id("square", 10.0).await;
    assert_eq!(app.post("/v1/tools", shop_square_d10()).await.status, 201);
    let job = finished_plan(&app, small_plan(json!({"diameters_mm": [10]}))).await;
    let candidates = job["result"]["candidates"].as_array().unwrap();
    assert_eq!(candidates.len(), 1, "{job}");
    assert_eq!(candidates[0]["tool_id"], seeded, "{job}");

    let eight = app.tool_id("square", 8.0).await;
    let radius = app.tool_id("radius", 10.0).await;
    let job = finished_plan(&app, small_plan(json!({"tool_ids": [eight, radius]}))).await;
    let names: Vec<(i64, &str)> = job["result"]["candidates"]
        .as_array()
        .unwrap()
        .iter()
        .map(|c| (c["tool_id"].as_i64().unwrap(), c["name"].as_str().unwrap()))
        .collect();
    assert_eq!(names, vec![(eight, "square D8"), (radius, "radius D10 R1")], "{job}");
    app.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn bad_tool_ids_of_a_plan_are_reported_together_each_by_its_index() {
    let app = TestApp::start().await;
    let ball = app.tool_id("ball", 10.0).await;
    let ten = app.tool_id("square", 10.0).await;
    let a = app.post("/v1/plans", small_plan(json!({"tool_ids": [ten, 99_999, ball, 88_888, ten]}))).await;
    assert_problem(&a, 422, Some("tool_ids[4]"));
    let a =
        app.post("/v1/plans", small_plan(json!({"tool_ids": [ten, 99_999, ball, 88_888], "diameters_mm": [11]}))).await;
    for field in ["tool_ids[1]", "tool_ids[2]", "tool_ids[3]", "diameters_mm[0]"] {
        assert_problem(&a, 422, Some(field));
    }
    assert!(a.text.contains("99999") && a.text.contains("88888"), "{}", a.text);
    assert_problem(&app.post("/v1/plans", small_plan(json!({"tool_ids": []}))).await, 422, Some("tool_ids"));
    // A shop tool without the data to plan with is refused by its index, naming the tool.
    let mine = app.post("/v1/tools", shop_square_d10()).await.body["id"].as_i64().unwrap();
    let a = app.post("/v1/plans", small_plan(json!({"tool_ids": [ten, mine]}))).await;
    assert_problem(&a, 422, Some("tool_ids[1]"));
    assert!(a.text.contains("shop square D10 z4"), "{}", a.text);
    assert_eq!(app.get("/v1/jobs").await.body["total"], 0, "no refused plan became a job");
    app.stop().await;
}
