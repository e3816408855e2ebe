//! `GET /v1/jobs/{id}/stock`: the stock a job left as a height map (issue 32 item 5), and
//! the trace's colour scales the page's 3-D view colours the path by.

use crate::common::{assert_problem, bearer, close, TestApp};
use base64::Engine;
use reqwest::Method;
use serde_json::{json, Value};

/// A pass of the 10 mm tool across the 100 × 40 block along y = 20 at z = −10: a slot
/// from y = 15 to 25, half the block's 20 mm deep.
fn slot() -> Value {
    json!({
        "program": {"gcode": "G21 G90 G17\nS9600 M3\nG0 X-10 Y20 Z5\nG1 Z-10 F1000\nG1 X110 F2000\nG0 Z5\nM30\n"},
        "tool_type": "square", "diameter_mm": 10,
        "stock": {"box": {"x_min": 0, "y_min": 0, "z_min": -20, "x_max": 100, "y_max": 40, "z_max": 0}}
    })
}

/// The tops of a height map, mm, row by row from the bottom.
fn decode_tops(map: &Value) -> Vec<f32> {
    assert_eq!(map["encoding"], "base64-f32le");
    let bytes = base64::engine::general_purpose::STANDARD.decode(map["tops"].as_str().unwrap()).unwrap();
    bytes.chunks_exact(4).map(|b| f32::from_le_bytes([b[0], b[1], b[2], b[3]])).collect()
}

/// The top at (x, y) mm.
fn top_at(map: &Value, tops: &[f32], x: f64, y: f64) -> f32 {
    let g = &map["grid"];
    let cell = g["cell_mm"].as_f64().unwrap();
    let i = ((x - g["x0_mm"].as_f64().unwrap()) / cell) as usize;
    let j = ((y - g["y0_mm"].as_f64().unwrap()) / cell) as usize;
    tops[j * g["columns"].as_u64().unwrap() as usize + i]
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn the_stock_an_analysis_left_is_a_height_map_with_the_slot_at_its_depth_and_the_top_beside_it() {
    let app = TestApp::start().await;
    let a = app.post_wait("/v1/analysis", slot()).await;
    assert_eq!(a.body["status"], "succeeded", "{}", a.text);
    let id = a.body["id"].as_str().unwrap();
    let map = app.get(&format!("/v1/jobs/{id}/stock")).await;
    assert_eq!(map.status, 200, "{}", map.text);
    let m = &map.body;
    let tops = decode_tops(m);
    let (columns, rows) = (m["grid"]["columns"].as_u64().unwrap(), m["grid"]["rows"].as_u64().unwrap());
    assert_eq!(tops.len() as u64, columns * rows);
    assert!(tops.len() <= 256 * 256, "the default is at most 256 × 256 cells");
    assert!(close(&m["z_top_mm"], 0.0, 1e-9) && close(&m["z_bottom_mm"], -20.0, 1e-9), "{}", map.text);
    assert!((top_at(m, &tops, 50.0, 20.0) + 10.0).abs() < 1e-6, "in the slot");
    assert!(top_at(m, &tops, 50.0, 5.0).abs() < 1e-6 && top_at(m, &tops, 50.0, 35.0).abs() < 1e-6, "beside it");
    assert!(tops.iter().all(|t| t.is_finite() && *t >= -20.0 && *t <= 0.0));
    assert_eq!(m["job_id"], id);

    // Fewer cells: coarser blocks, each the highest top in it.
    let small = app.get(&format!("/v1/jobs/{id}/stock?max_cells=100")).await;
    assert_eq!(small.status, 200, "{}", small.text);
    let coarse = decode_tops(&small.body);
    assert!(coarse.len() <= 100 && small.body["block"].as_u64().unwrap() > 1);
    assert!(coarse.iter().all(|t| t.abs() < 1e-6 || (t + 10.0).abs() < 1e-6 || (t + 20.0).abs() < 1e-6));
    assert_problem(&app.get(&format!("/v1/jobs/{id}/stock?max_cells=2")).await, 422, Some("max_cells"));
    assert_problem(&app.get(&format!("/v1/jobs/{id}/stock?max_cells=many")).await, 400, None);

    // The trace gives the plan view's colour scale of each quantity.
    let trace = app.get(&format!("/v1/jobs/{id}/trace")).await;
    let alpha = &trace.body["scales"]["alpha"];
    assert_eq!(alpha["colors"].as_array().map(Vec::len), Some(32), "{}", trace.text);
    assert!(close(&alpha["limit"], 40.0, 1e-9) && close(&alpha["max"], 180.0, 2.0), "{alpha}");
    assert_eq!(alpha["cool_bins"], 24);
    app.stop().await;
}

/// Submits a job with `key` and waits for it to succeed; its id.
async fn submit(app: &TestApp, key: &str, path: &str, body: Value) -> String {
    let (name, value) = bearer(key);
    let a = app.send(Method::POST, path, Some(body), &[(name, value.as_str()), ("prefer", "wait=60")]).await;
    assert_eq!(a.body["status"], "succeeded", "{}", a.text);
    a.body["id"].as_str().unwrap().to_string()
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_job_without_a_kept_stock_or_of_another_planner_answers_404_saying_why() {
    let app = TestApp::start().await;
    let admin = app.make_key(None, "admin", "admin").await;
    let alice = app.make_key(Some(&admin), "planner", "station A").await;
    let bob = app.make_key(Some(&admin), "planner", "station B").await;
    let reader = app.make_key(Some(&admin), "reader", "dashboard").await;
    let unknown = app.send_as(&admin, Method::GET, "/v1/jobs/00000000-0000-4000-8000-000000000000/stock", None).await;
    assert_problem(&unknown, 404, None);
    let conditions = json!({"tool_type": "square", "diameter_mm": 10});
    let done = submit(&app, &alice, "/v1/conditions", conditions).await;
    let none = app.send_as(&alice, Method::GET, &format!("/v1/jobs/{done}/stock"), None).await;
    assert_problem(&none, 404, None);
    assert!(none.body["detail"].as_str().unwrap().contains("kept no stock"), "{}", none.text);

    let id = submit(&app, &alice, "/v1/analysis", slot()).await;
    let path = format!("/v1/jobs/{id}/stock");
    assert_eq!(app.send_as(&alice, Method::GET, &path, None).await.status, 200);
    assert_eq!(app.send_as(&reader, Method::GET, &path, None).await.status, 200);
    assert_problem(&app.send_as(&bob, Method::GET, &path, None).await, 404, None);
    app.stop().await;
}
