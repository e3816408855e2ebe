//! The tool-life recalibration and the baseline's inferred feed (migrations/0006, MODEL.md §5
//! and §9): the seeded rows say where their values come from, a shop's own rows and edits
//! survive the migration, and a plan's baseline program is served beside the plan's.

use crate::common::{assert_problem, close, database_before, TestApp};
use dieplan::core::nc::{parse_gcode, ParseOptions};
use serde_json::{json, Value};

/// The last migration before the one under test.
const BEFORE_RECALIBRATION: i64 = 5;

/// The one row of `path` for the tool.
async fn one_row(app: &TestApp, path: &str, tool_id: i64) -> Value {
    let a = app.get(&format!("{path}tool_id={tool_id}")).await;
    assert_eq!(a.body["total"], 1, "{path} of tool {tool_id}: {}", a.text);
    a.body["items"][0].clone()
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn the_r5_balls_conventional_roughing_feed_is_inferred_from_seed_004_table_4_and_the_other_balls_follow() {
    let app = TestApp::start().await;
    for d in [6.0, 8.0, 10.0, 12.0, 13.0, 16.0] {
        let ball = app.tool_id("ball", d).await;
        let row = one_row(&app, "/v1/conditions/standard?operation=conventional_ball_roughing&", ball).await;
        // 153.9 m in 42'47" is 3597 mm/min: fz 0.375 at 4800 min⁻¹ with 2 flutes, scaled × D/10.
        let fz = 0.375 * d / 10.0;
        assert!(close(&row["fz_mm"], fz, 1e-9) && close(&row["fz_min_mm"], 0.05 * fz, 1e-9), "D{d}: {row}");
        let reference = row["reference"].as_str().unwrap();
        if d == 10.0 {
            assert_eq!(row["source"], "inferred", "{row}");
            assert!(close(&row["spindle_rpm"], 4800.0, 1e-9) && close(&row["rd_mm"], 3.5, 1e-9), "{row}");
            assert!(reference.contains("Table 4") && reference.contains("MODEL.md §5"), "{reference}");
        } else {
            assert_eq!(row["source"], "assumed", "D{d}: {row}");
            assert!(reference.contains("inferred"), "D{d}: {reference}");
        }
    }
    // The source is one a shop may filter by, and give its own rows.
    let inferred = app.get("/v1/conditions/standard?source=inferred").await;
    assert_eq!(inferred.body["total"], 1, "{}", inferred.text);
    let mine = app
        .post(
            "/v1/materials",
            json!({"name": "NAK80", "hardness_hrc": 40, "source": "inferred", "reference": "from the hardness"}),
        )
        .await;
    assert_eq!(mine.status, 201, "{}", mine.text);
    assert_eq!(mine.body["source"], "inferred");
    app.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn the_recalibration_leaves_a_shops_own_rows_edits_and_jobs_alone() {
    // A shop's database as it was before the migration: it has measured the D8 square end
    // mill's life, edited the R5 ball's conventional conditions, added a tool of its own with
    // its conditions, and finished a job.
    let (dir, path, pool) = database_before(BEFORE_RECALIBRATION).await;
    for sql in [
        "UPDATE tool_life SET life_m = 250, gamma_table = '[[0, 1], [30, 1], [180, 9]]', force_exponent = 2, source = 'user', edited = 1
         WHERE seed_key = 'tool_life:square-8:skd61'",
        "UPDATE standard_conditions SET fz_mm = 0.2, source = 'user', edited = 1 WHERE seed_key = 'conditions:ball-10:skd61:conventional_ball_roughing'",
        "INSERT INTO tools (name, tool_type, diameter_mm, flutes, corner_radius_mm, source, reference) VALUES ('shop square D10 z4', 'square', 10, 4, 0, 'user', 'catalogue')",
        "INSERT INTO standard_conditions (tool_id, material_id, operation, spindle_rpm, fz_mm, fz_min_mm, rd_mm, ad_mm, source, reference)
         SELECT id, 1, 'standard_side_cutting', 8000, 0.08, 0.004, 0.5, 10, 'user', 'shop trial' FROM tools WHERE name = 'shop square D10 z4'",
        "INSERT INTO jobs (id, kind, status, input, prepared, result, program) VALUES ('0a0a0a0a-0000-4000-8000-0000000000b0', 'feeds', 'succeeded', '{}', '{}', '{}', 'G0 X0')",
    ] {
        sqlx::query(sql).execute(&pool).await.unwrap();
    }
    let tools_before: i64 = sqlx::query_scalar("SELECT count(*) FROM tools").fetch_one(&pool).await.unwrap();
    pool.close().await;

    let app = TestApp::start_in(dir, |c| c.database = path.into()).await;
    let eight = app.tool_id("square", 8.0).await;
    let life = one_row(&app, "/v1/tool-life?", eight).await;
    assert_eq!((life["source"].as_str(), life["life_m"].as_f64()), (Some("user"), Some(250.0)), "{life}");
    assert!(close(&life["force_exponent"], 2.0, 0.0), "{life}");
    let ball = app.tool_id("ball", 10.0).await;
    let row = one_row(&app, "/v1/conditions/standard?operation=conventional_ball_roughing&", ball).await;
    assert_eq!((row["source"].as_str(), row["fz_mm"].as_f64()), (Some("user"), Some(0.2)), "{row}");
    // The unedited rows are recalibrated; the shop's tool keeps its id and its conditions.
    let ten = one_row(&app, "/v1/tool-life?", app.tool_id("square", 10.0).await).await;
    assert_eq!(ten["source"], "fitted", "{ten}");
    let mine = app.get("/v1/tools?source=user").await;
    assert_eq!(mine.body["total"], 1, "{}", mine.text);
    let mine_id = mine.body["items"][0]["id"].as_i64().unwrap();
    let conditions = one_row(&app, "/v1/conditions/standard?", mine_id).await;
    assert_eq!(conditions["reference"], "shop trial");
    assert_eq!(app.get("/v1/tools?limit=500").await.body["total"], tools_before);
    // Foreign keys still hold: a tool in use cannot be deleted.
    assert_eq!(app.delete(&format!("/v1/tools/{mine_id}")).await.status, 409);
    let old = app.get("/v1/jobs/0a0a0a0a-0000-4000-8000-0000000000b0/program").await;
    assert_eq!((old.status.as_u16(), old.text.as_str()), (200, "G0 X0"));
    assert_problem(&app.get("/v1/jobs/0a0a0a0a-0000-4000-8000-0000000000b0/program?part=baseline").await, 404, None);
    app.stop().await;
}

/// A 40 × 30 mm box with corners of radius 6 mm.
fn small_box() -> Value {
    json!({"outer": [[6, 0], [34, 0, 0.414214], [40, 6], [40, 24, 0.414214], [34, 30], [6, 30, 0.414214], [0, 24], [0, 6, 0.414214]]})
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_plans_baseline_program_is_served_beside_the_plans_and_other_parts_are_refused() {
    let app = TestApp::start().await;
    let body = json!({
        "contour": small_box(), "z_top": 0, "z_bottom": -3, "diameters_mm": [10], "sample_spacing_mm": 0.2
    });
    let a = app.post("/v1/plans", body).await;
    assert!(a.status == 201 || a.status == 202, "{}", a.text);
    let id = a.body["id"].as_str().unwrap().to_string();
    let job = app.wait_for_job_within(&id, 600).await;
    assert_eq!(job["status"], "succeeded", "{job}");
    let b = &job["result"]["baseline"];
    assert_eq!(b["conditions"]["source"], "inferred", "{b}");
    assert!(close(&b["feed_mm_min"], 3600.0, 1e-9) && close(&b["fz_mm"], 0.375, 1e-12), "{b}");
    let life = &b["equivalent_life"];
    assert!(life["centre_path_m"].as_f64().unwrap() > 0.0 && life["machined_surface_m"].as_f64().is_some(), "{b}");

    let baseline = app.get(&format!("/v1/jobs/{id}/program?part=baseline")).await;
    assert_eq!(baseline.status, 200, "{}", baseline.text);
    assert!(baseline.content_type().starts_with("text/plain"), "{}", baseline.content_type());
    assert_eq!(baseline.text.len() as u64, b["program"]["bytes"].as_u64().unwrap());
    // The ball, called and spun at its conditions, every level commented; it reads back.
    assert!(baseline.text.contains("BALL D10 R5") && baseline.text.contains("S4800 M3"), "{}", &baseline.text[..400]);
    assert!(baseline.text.contains("(LAYER 5 Z-3 CONVENTIONAL BALL-END ROUGHING)"), "{}", baseline.text);
    let parsed = parse_gcode(&baseline.text, &ParseOptions::default()).unwrap_or_else(|e| panic!("{e:?}"));
    assert!(parsed.moves.len() as u64 >= b["program"]["moves_out"].as_u64().unwrap());
    let main = app.get(&format!("/v1/jobs/{id}/program?part=main")).await;
    assert_eq!(main.text, app.get(&format!("/v1/jobs/{id}/program")).await.text);
    assert_ne!(main.text, baseline.text);

    // An unknown part is a bad request; a part the job has not, not found.
    let unknown = app.get(&format!("/v1/jobs/{id}/program?part=finishing")).await;
    assert_problem(&unknown, 400, None);
    assert!(unknown.body["detail"].as_str().unwrap().contains("part"), "{}", unknown.text);
    let conditions = app.post_wait("/v1/conditions", json!({"tool_type": "square", "diameter_mm": 10})).await;
    let none = app.get(&format!("/v1/jobs/{}/program?part=baseline", conditions.body["id"].as_str().unwrap())).await;
    assert_problem(&none, 404, None);
    let without = app
        .post(
            "/v1/plans",
            json!({"contour": small_box(), "z_top": 0, "z_bottom": -3, "diameters_mm": [10],
                                  "sample_spacing_mm": 0.2, "baseline": false}),
        )
        .await;
    let without_id = without.body["id"].as_str().unwrap().to_string();
    assert_eq!(app.wait_for_job_within(&without_id, 600).await["status"], "succeeded");
    assert_problem(&app.get(&format!("/v1/jobs/{without_id}/program?part=baseline")).await, 404, None);
    app.stop().await;
}
