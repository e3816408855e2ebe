//! `"stock": {"from_job": "<id>"}`: a job starts from the stock another job left (issue 32
//! item 3): rough with one program, then analyse the next on what it left.

use crate::common::{assert_problem, close, long_analysis, upload, TestApp};
use serde_json::{json, Value};

/// Passes of the 10 mm tool across the block along y = `y`, one at each of `levels`.
fn passes(y: f64, levels: &[f64]) -> String {
    let mut gcode = String::from("G21 G90 G17\nS9600 M3\n");
    for z in levels {
        gcode += &format!("G0 X-10 Y{y} Z5\nG1 Z{z} F1000\nG1 X110 F2000\nG0 Z5\n");
    }
    gcode + "M30\n"
}

/// A roughing at Ad 10: a slot through the block from y = 15 to 25, 20 mm deep.
fn roughing() -> Value {
    json!({
        "program": {"gcode": passes(20.0, &[-10.0, -20.0])}, "tool_type": "square", "diameter_mm": 10,
        "stock": {"box": {"x_min": 0, "y_min": 0, "z_min": -20, "x_max": 100, "y_max": 40, "z_max": 0}}
    })
}

/// An intermediate pass at Ad 2.5, 1 mm into the slot's wall at y = 25, on the stock of `from`.
fn intermediate(from: &str) -> Value {
    let levels: Vec<f64> = (1..=8).map(|i| -2.5 * f64::from(i)).collect();
    json!({
        "program": {"gcode": passes(21.0, &levels)}, "tool_type": "square", "diameter_mm": 10,
        "stock": {"from_job": from}
    })
}

async fn rough(app: &TestApp) -> String {
    let a = app.post_wait("/v1/analysis", roughing()).await;
    assert_eq!((a.status.as_u16(), a.body["status"].as_str()), (201, Some("succeeded")), "{}", a.text);
    let s = &a.body["result"]["summary"];
    // 100 × 40 × 20 less the slot's 100 × 10 × 20.
    assert!(close(&s["remaining_volume_mm3"], 60_000.0, 300.0), "{s}");
    assert!(s["rest_material"].is_null(), "a box is not a cavity: {s}");
    a.body["id"].as_str().unwrap().to_string()
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn an_intermediate_pass_analysed_on_what_the_roughing_left_cuts_only_the_wall() {
    let app = TestApp::start().await;
    let id = rough(&app).await;
    let b = app.post_wait("/v1/analysis", intermediate(&id)).await;
    assert_eq!((b.status.as_u16(), b.body["status"].as_str()), (201, Some("succeeded")), "{}", b.text);
    let r = &b.body["result"];
    assert_eq!(r["stock_from_job"], json!(id));
    let s = &r["summary"];
    // 1 mm of a 10 mm tool: α = acos(0.8) = 36.87°, not the 180° of the block as it was.
    assert!(close(&s["alpha_deg"]["max"], 36.87, 2.0), "{s}");
    assert!(close(&s["removed_volume_mm3"], 2_000.0, 40.0), "{s}");
    assert!(close(&s["remaining_volume_mm3"], 58_000.0, 300.0), "{s}");
    assert_eq!(s["slices"].as_array().unwrap().len(), 8, "the pass's own levels: {s}");
    // Through POST /v1/jobs too, and on from the intermediate job's stock in turn.
    let c = app.post("/v1/jobs", json!({"kind": "analysis", "input": intermediate(&id)})).await;
    assert_eq!(c.status.as_u16(), 202, "{}", c.text);
    let done = app.wait_for_job(c.body["id"].as_str().unwrap()).await;
    assert_eq!(done["result"]["summary"]["alpha_deg"], s["alpha_deg"]);
    let again = app.post_wait("/v1/analysis", intermediate(b.body["id"].as_str().unwrap())).await;
    assert!(close(&again.body["result"]["summary"]["removed_volume_mm3"], 0.0, 1.0), "{}", again.text);
    app.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_program_uploaded_as_a_file_starts_from_the_kept_stock_its_request_part_names() {
    let app = TestApp::start().await;
    let id = rough(&app).await;
    let mut request = intermediate(&id);
    let program = request["program"]["gcode"].as_str().unwrap().to_string();
    request.as_object_mut().unwrap().remove("program");
    let request = request.to_string();
    let parts = [("program", Some("wall.ngc"), program.as_bytes()), ("request", None, request.as_bytes())];
    let a = upload(&app, "/v1/analysis", &parts).await;
    assert_eq!((a.status.as_u16(), a.body["status"].as_str()), (201, Some("succeeded")), "{}", a.text);
    assert_eq!(a.body["result"]["stock_from_job"], json!(id));
    assert!(close(&a.body["result"]["summary"]["alpha_deg"]["max"], 36.87, 2.0), "{}", a.text);
    // A request part naming no job, or a job that does not exist, is refused naming the field.
    let unknown = json!({"tool_type": "square", "diameter_mm": 10,
        "stock": {"from_job": "00000000-0000-4000-8000-000000000000"}})
    .to_string();
    let parts = [("program", Some("wall.ngc"), program.as_bytes()), ("request", None, unknown.as_bytes())];
    let refused = upload(&app, "/v1/analysis", &parts).await;
    assert_problem(&refused, 422, Some("stock.from_job"));
    app.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn the_rest_material_of_a_pocket_is_reported_and_carried() {
    let app = TestApp::start().await;
    let pocket = json!({"outer": [[0, 0], [100, 0], [100, 40], [0, 40]]});
    let body = json!({
        "program": {"gcode": passes(20.0, &[-10.0])}, "tool_type": "square", "diameter_mm": 10,
        "stock": {"contour": pocket, "z_top": 0, "z_bottom": -10}
    });
    let a = app.post_wait("/v1/analysis", body).await;
    let rest = &a.body["result"]["summary"]["rest_material"];
    assert!(close(&rest["volume_mm3"], 30_000.0, 150.0), "{}", a.text);
    let level = &rest["levels"][0];
    assert!(close(&level["area_mm2"], 3_000.0, 15.0), "{level}");
    let y = level["point"][1].as_f64().unwrap();
    assert!(!(15.0..=25.0).contains(&y), "the point lies in the slot: {level}");
    let from = a.body["id"].as_str().unwrap();
    let next = json!({"program": {"gcode": passes(26.0, &[-10.0])}, "tool_type": "square", "diameter_mm": 10,
        "stock": {"from_job": from}});
    let b = app.post_wait("/v1/analysis", next).await;
    let left = &b.body["result"]["summary"]["rest_material"]["volume_mm3"];
    // The second pass widens the slot by 6 mm.
    assert!(close(left, 24_000.0, 150.0), "{}", b.text);
    app.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn an_unknown_job_and_a_box_with_it_are_refused_at_once_naming_each_field() {
    let app = TestApp::start().await;
    let mut body = intermediate("0f8e9c3a-2b1d-4e5f-9a7b-6c5d4e3f2a10");
    body["stock"]["box"] = json!({"x_min": 0, "y_min": 0, "z_min": -20, "x_max": 100, "y_max": 40, "z_max": 0});
    body["stock"]["z_bottom"] = json!(-30);
    body["cell_mm"] = json!(0.1);
    let a = app.post("/v1/analysis", body).await;
    for field in ["stock.from_job", "stock.box", "stock.z_bottom", "cell_mm"] {
        assert_problem(&a, 422, Some(field));
    }
    assert!(a.text.contains("no job with id"), "{}", a.text);
    app.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_job_not_succeeded_or_without_a_kept_stock_or_of_an_unknown_format_is_refused() {
    let app = TestApp::start().await;
    // Still running (or queued).
    let long = app.post("/v1/analysis", long_analysis()).await;
    let long_id = long.body["id"].as_str().unwrap().to_string();
    let a = app.post("/v1/analysis", intermediate(&long_id)).await;
    assert_problem(&a, 422, Some("stock.from_job"));
    assert!(a.text.contains("has succeeded"), "{}", a.text);
    app.delete(&format!("/v1/jobs/{long_id}")).await;
    // A kept stock stored in a format this version does not read.
    let id = rough(&app).await;
    let pool = app.pool().await;
    sqlx::query("UPDATE job_stocks SET format = 99 WHERE job_id = $1").bind(&id).execute(&pool).await.unwrap();
    let b = app.post("/v1/analysis", intermediate(&id)).await;
    assert_problem(&b, 422, Some("stock.from_job"));
    assert!(b.text.contains("format 99"), "{}", b.text);
    // No kept stock.
    sqlx::query("DELETE FROM job_stocks WHERE job_id = $1").bind(&id).execute(&pool).await.unwrap();
    let c = app.post("/v1/analysis", intermediate(&id)).await;
    assert_problem(&c, 422, Some("stock.from_job"));
    assert!(c.text.contains("kept no stock"), "{}", c.text);
    app.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_costing_starts_from_a_kept_stock_and_keeps_its_own_and_a_feeds_job_refuses_one() {
    let app = TestApp::start().await;
    let id = rough(&app).await;
    let c = app.post_wait("/v1/costing", intermediate(&id)).await;
    assert_eq!((c.status.as_u16(), c.body["status"].as_str()), (201, Some("succeeded")), "{}", c.text);
    assert!(close(&c.body["result"]["removed_volume_mm3"], 2_000.0, 40.0), "{}", c.text);
    // The costing's own stock: the wall stepped into is gone.
    let again = app.post_wait("/v1/analysis", intermediate(c.body["id"].as_str().unwrap())).await;
    assert!(close(&again.body["result"]["summary"]["removed_volume_mm3"], 0.0, 1.0), "{}", again.text);
    let mut feeds = intermediate(&id);
    feeds["mode"] = json!("side_milling");
    let f = app.post("/v1/feeds", feeds).await;
    assert_problem(&f, 422, Some("stock.from_job"));
    app.stop().await;
}
