//! The cutting-condition database: seeds, list filters, create, update, delete.

use crate::common::{assert_problem, close, TestApp};
use serde_json::json;

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn the_database_is_seeded_from_the_model_with_a_source_on_every_row() {
    let app = TestApp::start().await;
    for (path, count) in [
        ("/v1/materials", 1),
        ("/v1/tools", 18),
        ("/v1/conditions/standard", 78),
        ("/v1/force-models", 18),
        ("/v1/tool-life", 18),
        ("/v1/machines", 1),
        ("/v1/cost-rates", 1),
    ] {
        let a = app.get(&format!("{path}?limit=500")).await;
        assert_eq!(a.body["total"], count, "{path}");
        for row in a.body["items"].as_array().unwrap() {
            let sources = ["paper", "extrapolated", "assumed", "inferred", "fitted"];
            assert!(sources.contains(&row["source"].as_str().unwrap()), "{path}: {row}");
            assert!(!row["reference"].as_str().unwrap().is_empty(), "{path}: every seed says where it comes from");
            assert_eq!(row["edited"], false);
        }
    }
    app.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn force_models_are_seed_001_for_6_to_10_mm_and_extrapolated_by_diameter_squared_above() {
    let app = TestApp::start().await;
    for (d, b0, source) in [
        (6.0, 83.84, "paper"),
        (8.0, 163.0, "paper"),
        (10.0, 269.1, "paper"),
        (12.0, 269.1 * 1.44, "extrapolated"),
        (16.0, 269.1 * 2.56, "extrapolated"),
    ] {
        let tool = app.tool_id("square", d).await;
        let a = app.get(&format!("/v1/force-models?tool_id={tool}")).await;
        let m = &a.body["items"][0];
        assert!(close(&m["b0"], b0, 1e-6), "D{d}: {m}");
        assert_eq!(m["source"], source);
        assert!(close(&m["ad_ref_mm"], d, 1e-12));
    }
    let ten = app.tool_id("square", 10.0).await;
    let m = &app.get(&format!("/v1/force-models?tool_id={ten}")).await.body["items"][0];
    for (k, v) in [
        ("b1", 65.84),
        ("b2", 53.66),
        ("b11", 0.0),
        ("b22", 3.763),
        ("b12", 15.45),
        ("dt_um", 15.0),
        ("dl_mm", 0.436),
        ("r_squared", 0.9998),
    ] {
        assert!(close(&m[k], v, 1e-9), "{k}: {m}");
    }
    let life = &app.get(&format!("/v1/tool-life?tool_id={ten}")).await.body["items"][0];
    assert!(close(&life["life_m"], 320.0, 1e-9));
    // γ and k as fitted to MODEL.md §9's table (migrations/0006, src/core/costing/calibration.rs).
    assert_eq!(life["source"], "fitted", "{life}");
    assert!(life["reference"].as_str().unwrap().contains("MODEL.md §9"), "{life}");
    assert!(close(&life["force_exponent"], 2.61, 1e-12));
    assert_eq!(
        life["gamma_table"],
        json!([[0.0, 1.0], [25.842, 1.0], [40.0, 2.03], [50.0, 4.06], [60.0, 8.12], [90.0, 16.24], [180.0, 24.36]])
    );
    app.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn tools_are_filtered_by_type_diameter_material_and_paged() {
    let app = TestApp::start().await;
    let balls = app.get("/v1/tools?tool_type=ball").await;
    assert_eq!(balls.body["total"], 6);
    let tens = app.get("/v1/tools?diameter_mm=10").await;
    assert_eq!(tens.body["total"], 3);
    let skd = app.get("/v1/tools?material_id=1&limit=5&offset=5").await;
    assert_eq!(skd.body["total"], 18);
    assert_eq!(skd.body["items"].as_array().unwrap().len(), 5);
    assert_eq!(skd.body["offset"], 5);
    assert_problem(&app.get("/v1/tools?limit=0").await, 400, None);
    assert_problem(&app.get("/v1/tools?diameter_mm=ten").await, 400, None);
    assert_problem(&app.get("/v1/tools?colour=red").await, 400, None);
    assert_problem(&app.get("/v1/tools?diameter_mm=NaN").await, 400, None);
    assert_problem(&app.get("/v1/tools?tool_type=cone").await, 400, None);
    app.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_tool_is_created_read_replaced_patched_and_deleted() {
    let app = TestApp::start().await;
    let body =
        json!({"name": "shop square 10 z4", "tool_type": "square", "diameter_mm": 10, "flutes": 4, "price": 95.0});
    let created = app.post("/v1/tools", body.clone()).await;
    assert_eq!(created.status, 201, "{}", created.text);
    let id = created.body["id"].as_i64().unwrap();
    assert_eq!(created.header("location"), Some(format!("/v1/tools/{id}").as_str()));
    assert_eq!(created.body["source"], "user");
    assert_eq!(created.body["seed_key"], serde_json::Value::Null);

    let read = app.get(&format!("/v1/tools/{id}")).await;
    assert_eq!(read.body["flutes"], 4);

    let mut replaced = body.clone();
    replaced["flutes"] = json!(3);
    let put = app.put(&format!("/v1/tools/{id}"), replaced).await;
    assert_eq!(put.status, 200, "{}", put.text);
    assert_eq!(put.body["flutes"], 3);
    assert_eq!(put.body["edited"], true);

    let patched = app.patch(&format!("/v1/tools/{id}"), json!({"price": 80.0, "coating": "TiSiN"})).await;
    assert_eq!(patched.status, 200, "{}", patched.text);
    assert_eq!(patched.body["coating"], "TiSiN");
    assert_eq!(patched.body["flutes"], 3);

    assert_eq!(app.delete(&format!("/v1/tools/{id}")).await.status, 204);
    assert_problem(&app.get(&format!("/v1/tools/{id}")).await, 404, None);
    assert_problem(&app.delete(&format!("/v1/tools/{id}")).await, 404, None);
    app.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn refused_writes_name_the_field_and_change_nothing() {
    let app = TestApp::start().await;
    let before = app.get("/v1/tools?limit=500").await.body;
    let bad = [
        (json!({"name": "a", "tool_type": "square", "diameter_mm": -10, "flutes": 4}), 422, Some("diameter_mm")),
        (json!({"name": "a", "tool_type": "square", "diameter_mm": 10, "flutes": -4}), 422, Some("flutes")),
        (json!({"name": "a", "tool_type": "radius", "diameter_mm": 10, "flutes": 2}), 422, Some("corner_radius_mm")),
        (json!({"name": "a", "tool_type": "square", "diameter_mm": 10, "flutes": 4, "spin": 1}), 422, Some("spin")),
        // Values no end mill has.
        (json!({"name": "a", "tool_type": "square", "diameter_mm": 1e308, "flutes": 4}), 422, Some("diameter_mm")),
        (json!({"name": "a", "tool_type": "square", "diameter_mm": 1e-300, "flutes": 4}), 422, Some("diameter_mm")),
        (json!({"name": "a", "tool_type": "square", "diameter_mm": 10, "flutes": 4000000000u32}), 422, Some("flutes")),
        (
            json!({"name": "a", "tool_type": "square", "diameter_mm": 10, "flutes": 4, "price": 1e308}),
            422,
            Some("price"),
        ),
        (json!({"name": "square D10", "tool_type": "square", "diameter_mm": 10, "flutes": 4}), 409, None),
    ];
    for (body, status, field) in bad {
        assert_problem(&app.post("/v1/tools", body).await, status, field);
    }
    assert_problem(&app.send(reqwest::Method::POST, "/v1/tools", None, &[]).await, 415, None);
    let raw = app
        .client
        .post(app.url("/v1/tools"))
        .header("content-type", "application/json")
        .body(r#"{"name": "a", "tool_type": "square", "diameter_mm": 1e999, "flutes": 4}"#)
        .send()
        .await
        .unwrap();
    assert_eq!(raw.status(), 400, "a number beyond f64 is malformed JSON");
    let seeded = app.tool_id("square", 10.0).await;
    let conflict = app.delete(&format!("/v1/tools/{seeded}")).await;
    assert_problem(&conflict, 409, None);
    assert!(conflict.body["detail"].as_str().unwrap().contains("standard conditions"));
    let patch = app.patch(&format!("/v1/tools/{seeded}"), json!({"diameter_mm": 0})).await;
    assert_problem(&patch, 422, Some("diameter_mm"));
    let removal = app.patch(&format!("/v1/tools/{seeded}"), json!({"flutes": null})).await;
    assert_problem(&removal, 422, Some("flutes"));
    assert!(removal.body["detail"].as_str().unwrap().contains("cannot remove it with null"), "{}", removal.text);
    let missing = app.post("/v1/tools", json!({"name": "a", "tool_type": "square", "flutes": 4})).await;
    assert_problem(&missing, 422, Some("diameter_mm"));
    assert!(missing.body["detail"].as_str().unwrap().contains("is required"), "{}", missing.text);
    let cond = app.post("/v1/conditions/standard", json!({"tool_id": 9999, "material_id": 1, "operation": "rough_side_cutting", "spindle_rpm": 1000, "fz_mm": 0.1, "fz_min_mm": 0.01, "rd_mm": 0.5, "ad_mm": 5})).await;
    assert_problem(&cond, 422, Some("tool_id"));
    let life = app.get("/v1/tool-life").await;
    let id = life.body["items"][0]["id"].as_i64().expect("a seeded tool-life row");
    for (field, value, shown) in [("life_m", 1e-300, "got 1e-300"), ("force_exponent", 1e300, "got 1e300")] {
        let patch = app.patch(&format!("/v1/tool-life/{id}"), json!({ field: value })).await;
        assert_problem(&patch, 422, Some(field));
        assert!(patch.body["detail"].as_str().unwrap().contains(shown), "{}", patch.text);
    }
    assert_eq!(app.get("/v1/tools?limit=500").await.body, before, "nothing changed");
    app.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_shops_edit_of_a_seeded_row_is_marked_and_survives_restarts_and_later_seed_corrections() {
    let app = TestApp::start().await;
    let tool = app.tool_id("square", 10.0).await;
    let list = app.get(&format!("/v1/conditions/standard?tool_id={tool}&operation=rough_side_cutting")).await;
    let row = &list.body["items"][0];
    let id = row["id"].as_i64().unwrap();
    assert_eq!(row["source"], "paper");
    let edited = app.patch(&format!("/v1/conditions/standard/{id}"), json!({"spindle_rpm": 5200})).await;
    assert_eq!(edited.status, 200, "{}", edited.text);
    assert_eq!(edited.body["source"], "user");
    assert_eq!(edited.body["edited"], true);
    assert!(close(&edited.body["spindle_rpm"], 5200.0, 1e-9));

    // A later migration corrects seeded rows the documented way (migrations/0001_schema.sql).
    let app = app.restart_with(|c| c.workers = Some(1)).await;
    let pool = app.pool().await;
    let corrected = sqlx::query(
        "UPDATE standard_conditions SET spindle_rpm = 4900 WHERE seed_key LIKE 'conditions:square-10:skd61:%' AND operation IN ('rough_side_cutting', 'spiral_hole_expansion') AND edited = 0",
    )
    .execute(&pool)
    .await
    .unwrap();
    assert_eq!(corrected.rows_affected(), 1, "only the unedited row is corrected");
    pool.close().await;

    let after = app.get(&format!("/v1/conditions/standard/{id}")).await;
    assert!(close(&after.body["spindle_rpm"], 5200.0, 1e-9), "the shop's edit stays: {}", after.text);
    app.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn every_database_resource_answers_create_and_delete() {
    let app = TestApp::start().await;
    let tool = app
        .post(
            "/v1/tools",
            json!({"name": "t", "tool_type": "radius", "diameter_mm": 10, "flutes": 4, "corner_radius_mm": 1}),
        )
        .await;
    let tool_id = tool.body["id"].as_i64().unwrap();
    let material = app.post("/v1/materials", json!({"name": "NAK80", "hardness_hrc": 40})).await;
    let material_id = material.body["id"].as_i64().unwrap();
    let bodies = [
        (
            "/v1/conditions/standard",
            json!({"tool_id": tool_id, "material_id": material_id, "operation": "rough_side_cutting", "spindle_rpm": 6000, "fz_mm": 0.08, "fz_min_mm": 0.01, "rd_mm": 0.5, "ad_mm": 8}),
        ),
        (
            "/v1/force-models",
            json!({"tool_id": tool_id, "material_id": material_id, "t0_um": 40, "dt_um": 10, "l0_mm": 2, "dl_mm": 0.4, "b0": 200, "b1": 50, "b2": 40, "b22": 3, "b12": 10, "ad_ref_mm": 10}),
        ),
        (
            "/v1/tool-life",
            json!({"tool_id": tool_id, "material_id": material_id, "life_m": 500, "gamma_table": [[0, 1], [45, 1.5], [180, 10]], "force_exponent": 2}),
        ),
        (
            "/v1/machines",
            json!({"name": "m", "rapid_mm_min": 30000, "max_feed_mm_min": 20000, "max_spindle_rpm": 24000, "accel_x_mm_s2": 3000, "accel_y_mm_s2": 3000, "accel_z_mm_s2": 2000, "jerk_x_mm_s3": 50000, "jerk_y_mm_s3": 50000, "jerk_z_mm_s3": 50000, "tool_change_s": 5}),
        ),
        (
            "/v1/cost-rates",
            json!({"name": "c", "currency": "EUR", "machine_rate_per_hour": 50, "default_tool_price": 70}),
        ),
    ];
    let mut created = Vec::new();
    for (path, body) in bodies {
        let a = app.post(path, body).await;
        assert_eq!(a.status, 201, "{path}: {}", a.text);
        created.push(format!("{path}/{}", a.body["id"]));
    }
    let bad_gamma = app.post("/v1/tool-life", json!({"tool_id": tool_id, "material_id": material_id, "life_m": 500, "gamma_table": [[50, 1], [40, 2]], "force_exponent": 2})).await;
    assert_problem(&bad_gamma, 422, Some("gamma_table[1][0]"));
    for path in created.iter().rev() {
        assert_eq!(app.delete(path).await.status, 204, "{path}");
    }
    assert_eq!(app.delete(&format!("/v1/tools/{tool_id}")).await.status, 204);
    assert_eq!(app.delete(&format!("/v1/materials/{material_id}")).await.status, 204);
    app.stop().await;
}
