//! `"stock": {"from_job": "<id>"}`: a job starts from the stock another job left (issue 32
//! item 3): rough with one program, then analyse the next on what it left.

use crate::common::{assert_problem, close, long_analysis, upload, TestApp};
use flate2::read::ZlibDecoder;
use flate2::write::ZlibEncoder;
use serde_json::{json, Value};
use std::io::{Read, Write};

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

/// `body` sent as multipart: its G-code as the file `wall.ngc`, the rest as the request.
async fn upload_program(app: &TestApp, path: &str, mut body: Value) -> crate::common::Answer {
    let program = body["program"]["gcode"].as_str().unwrap().to_string();
    body.as_object_mut().unwrap().remove("program");
    let request = body.to_string();
    upload(app, path, &[("program", Some("wall.ngc"), program.as_bytes()), ("request", None, request.as_bytes())]).await
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
    let a = upload_program(&app, "/v1/analysis", intermediate(&id)).await;
    assert_eq!((a.status.as_u16(), a.body["status"].as_str()), (201, Some("succeeded")), "{}", a.text);
    assert_eq!(a.body["result"]["stock_from_job"], json!(id));
    assert!(close(&a.body["result"]["summary"]["alpha_deg"]["max"], 36.87, 2.0), "{}", a.text);
    // A request part naming no job, or a job that does not exist, is refused naming the field.
    let refused = upload_program(&app, "/v1/analysis", intermediate("00000000-0000-4000-8000-000000000000")).await;
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
async fn a_costing_starts_from_a_kept_stock_and_keeps_its_own() {
    let app = TestApp::start().await;
    let id = rough(&app).await;
    let c = app.post_wait("/v1/costing", intermediate(&id)).await;
    assert_eq!((c.status.as_u16(), c.body["status"].as_str()), (201, Some("succeeded")), "{}", c.text);
    assert!(close(&c.body["result"]["removed_volume_mm3"], 2_000.0, 40.0), "{}", c.text);
    // The costing's own stock: the wall stepped into is gone.
    let again = app.post_wait("/v1/analysis", intermediate(c.body["id"].as_str().unwrap())).await;
    assert!(close(&again.body["result"]["summary"]["removed_volume_mm3"], 0.0, 1.0), "{}", again.text);
    app.stop().await;
}

/// The intermediate pass of [`intermediate`] on the block as it was.
fn intermediate_on_the_block() -> Value {
    let mut body = intermediate("");
    body["stock"] = roughing()["stock"].clone();
    body
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_feeds_job_optimises_the_intermediate_pass_on_what_the_roughing_left_and_keeps_the_stock_it_leaves() {
    let app = TestApp::start().await;
    let id = rough(&app).await;
    let carried = app.post_wait("/v1/feeds", intermediate(&id)).await;
    assert_eq!(
        (carried.status.as_u16(), carried.body["status"].as_str()),
        (201, Some("succeeded")),
        "{}",
        carried.text
    );
    let fresh = app.post_wait("/v1/feeds", intermediate_on_the_block()).await;
    assert_eq!(fresh.body["status"].as_str(), Some("succeeded"), "{}", fresh.text);
    let (c, f) = (&carried.body["result"], &fresh.body["result"]);
    assert_eq!(c["stock_from_job"], json!(id));
    assert!(f["stock_from_job"].is_null());
    // 1 mm into the wall: acos(0.8) = 36.87°, where the block as it was is a full slot.
    assert!(close(&c["analysis"]["alpha_deg"]["max"], 36.87, 2.0), "{}", c["analysis"]);
    assert!(f["analysis"]["alpha_deg"]["max"].as_f64().unwrap() > 170.0, "{}", f["analysis"]);
    // So the feeds are higher and the program shorter than on the block.
    let mean = |r: &Value| r["after"]["feed_mm_min"]["mean"].as_f64().unwrap();
    assert!(mean(c) > 1.5 * mean(f), "{} against {}", mean(c), mean(f));
    let time = |r: &Value| r["after"]["kinematic_time_min"].as_f64().unwrap();
    assert!(time(c) < time(f), "{} against {}", time(c), time(f));
    assert!(close(&c["analysis"]["remaining_volume_mm3"], 58_000.0, 300.0), "{}", c["analysis"]);
    // The feeds job keeps the stock its pass leaves: the wall stepped into is gone.
    let feeds_id = carried.body["id"].as_str().unwrap();
    let after = app.post_wait("/v1/analysis", intermediate(feeds_id)).await;
    assert!(close(&after.body["result"]["summary"]["removed_volume_mm3"], 0.0, 1.0), "{}", after.text);
    // Through POST /v1/jobs, and with the program uploaded as a file: the same feeds.
    let queued = app.post("/v1/jobs", json!({"kind": "feeds", "input": intermediate(&id)})).await;
    assert_eq!(queued.status.as_u16(), 202, "{}", queued.text);
    let done = app.wait_for_job(queued.body["id"].as_str().unwrap()).await;
    assert_eq!(done["result"]["blocks"], c["blocks"]);
    let uploaded = upload_program(&app, "/v1/feeds", intermediate(&id)).await;
    assert_eq!(uploaded.body["status"].as_str(), Some("succeeded"), "{}", uploaded.text);
    assert_eq!(uploaded.body["result"]["blocks"], c["blocks"]);
    app.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_feeds_job_refuses_a_kept_stock_with_a_cell_or_for_surface_finishing_naming_each_field() {
    let app = TestApp::start().await;
    let id = rough(&app).await;
    let mut with_cell = intermediate(&id);
    with_cell["cell_mm"] = json!(0.1);
    assert_problem(&app.post("/v1/feeds", with_cell).await, 422, Some("cell_mm"));
    let mut surface = intermediate(&id);
    surface["mode"] = json!("surface_finishing");
    surface["tool_type"] = json!("ball");
    let refused = app.post("/v1/feeds", surface).await;
    assert_problem(&refused, 422, Some("stock.from_job"));
    assert!(refused.text.contains("surface finishing simulates no stock"), "{}", refused.text);
    let unknown = app.post("/v1/feeds", intermediate("00000000-0000-4000-8000-000000000000")).await;
    assert_problem(&unknown, 422, Some("stock.from_job"));
    app.stop().await;
}

/// Passes along y = 20 at each of `levels`, on the stock `from` left.
fn on_down(from: &str, levels: &[f64]) -> Value {
    json!({"program": {"gcode": passes(20.0, levels)}, "tool_type": "square", "diameter_mm": 10,
        "stock": {"from_job": from}})
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_job_cuts_below_the_kept_bottom_into_the_stock_as_it_was_given_down_to_its_floor() {
    let app = TestApp::start().await;
    // The roughing's layer ends at −20 in a box whose bottom is at −30.
    let mut body = roughing();
    body["stock"]["box"]["z_min"] = json!(-30);
    body["stock"]["z_bottom"] = json!(-20);
    let a = app.post_wait("/v1/analysis", body).await;
    assert_eq!(a.body["status"].as_str(), Some("succeeded"), "{}", a.text);
    let id = a.body["id"].as_str().unwrap();
    // On down the slot to −25: the box below the kept layer is slotted, 10 × 100 × 5 mm³.
    let b = app.post_wait("/v1/analysis", on_down(id, &[-20.0, -25.0])).await;
    let s = &b.body["result"]["summary"];
    assert!(close(&s["removed_volume_mm3"], 5_000.0, 100.0), "{}", b.text);
    assert!(s["alpha_deg"]["max"].as_f64().unwrap() > 170.0, "{s}");
    let bottoms: Vec<f64> = s["slices"].as_array().unwrap().iter().map(|l| l["z_bottom"].as_f64().unwrap()).collect();
    assert_eq!(bottoms, vec![-20.0, -25.0]);
    // Down to −40: no further than the box's bottom at −30.
    let c = app.post_wait("/v1/analysis", on_down(b.body["id"].as_str().unwrap(), &[-40.0])).await;
    let s = &c.body["result"]["summary"];
    assert!(close(&s["removed_volume_mm3"], 5_000.0, 100.0), "{}", c.text);
    assert_eq!(s["slices"].as_array().unwrap().last().unwrap()["z_bottom"], json!(-30.0));
    // A pocket's cavity runs on down in its outline.
    let pocket = json!({"program": {"gcode": passes(20.0, &[-10.0])}, "tool_type": "square", "diameter_mm": 10,
        "stock": {"contour": {"outer": [[0, 0], [100, 0], [100, 40], [0, 40]]}, "z_top": 0, "z_bottom": -10}});
    let p = app.post_wait("/v1/analysis", pocket).await;
    let deeper = app.post_wait("/v1/analysis", on_down(p.body["id"].as_str().unwrap(), &[-10.0, -30.0])).await;
    let s = &deeper.body["result"]["summary"];
    assert!(close(&s["removed_volume_mm3"], 20_000.0, 400.0), "{}", deeper.text);
    assert!(close(&s["rest_material"]["volume_mm3"], 90_000.0, 900.0), "{s}");
    app.stop().await;
}

/// `body`, a kept stock in format 2, as format 1 stored it: without what lies under the
/// layer (a u8, a floor's f64 and the footprint's cells after the rasters).
fn as_format_1(body: &[u8]) -> Vec<u8> {
    let mut raw = Vec::new();
    ZlibDecoder::new(body).read_to_end(&mut raw).unwrap();
    let u32_at = |k: usize| u32::from_le_bytes(raw[k..k + 4].try_into().unwrap()) as usize;
    let cells = u32_at(24) * u32_at(28);
    raw.truncate(raw.len() - 1 - 8 - cells);
    let mut z = ZlibEncoder::new(Vec::new(), flate2::Compression::fast());
    z.write_all(&raw).unwrap();
    z.finish().unwrap()
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_stock_kept_in_format_1_is_read_and_a_cut_below_it_is_refused_since_what_lies_there_is_not_known() {
    let app = TestApp::start().await;
    let id = rough(&app).await;
    let pool = app.pool().await;
    let (format, body): (i64, Vec<u8>) = sqlx::query_as("SELECT format, body FROM job_stocks WHERE job_id = $1")
        .bind(&id)
        .fetch_one(&pool)
        .await
        .unwrap();
    assert_eq!(format, 2);
    sqlx::query("UPDATE job_stocks SET format = 1, body = $1 WHERE job_id = $2")
        .bind(as_format_1(&body))
        .bind(&id)
        .execute(&pool)
        .await
        .unwrap();
    // Within the kept layer, format 1 reads as it always did.
    let within = app.post_wait("/v1/analysis", intermediate(&id)).await;
    assert!(close(&within.body["result"]["summary"]["alpha_deg"]["max"], 36.87, 2.0), "{}", within.text);
    // Below it, nothing is known: refused at submission, naming the field.
    for path in ["/v1/analysis", "/v1/feeds", "/v1/costing"] {
        let refused = app.post(path, on_down(&id, &[-20.0, -25.0])).await;
        assert_problem(&refused, 422, Some("stock.from_job"));
        assert!(refused.text.contains("not known"), "{path}: {}", refused.text);
    }
    app.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_trochoids_job_keeps_the_stock_its_verified_program_leaves() {
    let app = TestApp::start().await;
    // The README's slot box: an 80 × 60 mm pocket with a 12 mm slot, 10 mm deep.
    let box_with_slot =
        json!({"outer": [[0, 0], [80, 0], [80, 24], [120, 24], [120, 36], [80, 36], [80, 60], [0, 60]]});
    let t = app
        .post_wait(
            "/v1/trochoids",
            json!({"contour": box_with_slot, "z_top": 0, "z_bottom": -10,
            "tool_type": "square", "diameter_mm": 10}),
        )
        .await;
    assert_eq!(t.body["status"].as_str(), Some("succeeded"), "{}", t.text);
    let id = t.body["id"].as_str().unwrap();
    // A pass through the middle of the cleared pocket meets no material.
    let pass = "G21 G90 G17\nS9600 M3\nG0 X10 Y30 Z5\nG1 Z-10 F1000\nG1 X70 F2000\nG0 Z5\nM30\n";
    let a = app
        .post_wait(
            "/v1/analysis",
            json!({"program": {"gcode": pass}, "tool_type": "square", "diameter_mm": 10,
            "stock": {"from_job": id}}),
        )
        .await;
    assert_eq!(a.body["status"].as_str(), Some("succeeded"), "{}", a.text);
    let s = &a.body["result"]["summary"];
    assert_eq!(a.body["result"]["stock_from_job"], json!(id));
    assert!(close(&s["removed_volume_mm3"], 0.0, 1.0), "{s}");
    assert!(s["rest_material"].is_object(), "a pocket's stock is a cavity: {s}");
    app.stop().await;
}
