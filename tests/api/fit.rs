//! `POST /v1/tools/{id}/force-model/fit`.

use crate::common::{assert_problem, close, TestApp};
use serde_json::{json, Value};

/// A 13-run central composite design around the seeded 10 mm model's centre, with the
/// forces of a model whose intercept is `b0`.
fn measurements(model: &Value, b0: f64) -> Vec<Value> {
    let s = std::f64::consts::SQRT_2;
    let coded = [
        (-1.0, -1.0),
        (1.0, -1.0),
        (-1.0, 1.0),
        (1.0, 1.0),
        (-s, 0.0),
        (s, 0.0),
        (0.0, -s),
        (0.0, s),
        (0.0, 0.0),
        (0.0, 0.0),
        (0.0, 0.0),
    ];
    let f = |k: &str| model[k].as_f64().unwrap();
    coded
        .iter()
        .map(|(x1, x2)| {
            let force = b0 + f("b1") * x1 + f("b2") * x2 + f("b22") * x2 * x2 + f("b12") * x1 * x2;
            json!({"t_m_um": f("t0_um") + x1 * f("dt_um"), "l_mm": f("l0_mm") + x2 * f("dl_mm"), "fxy_n": force})
        })
        .collect()
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_fit_recovers_the_coefficients_and_a_stored_fit_becomes_the_model_in_use() {
    let app = TestApp::start().await;
    let tool = app.tool_id("square", 10.0).await;
    let seeded = app.get(&format!("/v1/force-models?tool_id={tool}")).await.body["items"][0].clone();

    let a = app
        .post(
            &format!("/v1/tools/{tool}/force-model/fit"),
            json!({"points": measurements(&seeded, 269.1), "include_x1_squared": false}),
        )
        .await;
    assert_eq!(a.status, 200, "{}", a.text);
    for k in ["b0", "b1", "b2", "b22", "b12"] {
        assert!(close(&a.body[k], seeded[k].as_f64().unwrap(), 1e-6), "{k}: {}", a.text);
    }
    assert!(close(&a.body["r_squared"], 1.0, 1e-9));
    assert_eq!(a.body["residuals"].as_array().unwrap().len(), 11);
    assert!(a.body["stored"].is_null());

    let stored = app
        .post(
            &format!("/v1/tools/{tool}/force-model/fit"),
            json!({"points": measurements(&seeded, 280.0), "store": true, "reference": "shop test cuts 2026-11"}),
        )
        .await;
    assert_eq!(stored.status, 201, "{}", stored.text);
    let model_id = stored.body["stored"]["id"].as_i64().unwrap();
    assert_eq!(stored.header("location"), Some(format!("/v1/force-models/{model_id}").as_str()));
    assert_eq!(stored.body["stored"]["source"], "fitted");

    let c = app.post_wait("/v1/conditions", json!({"tool_id": tool})).await;
    assert_eq!(c.body["result"]["force"]["force_model_id"], model_id);
    assert!(close(&c.body["result"]["force"]["fxy_n"], 280.0, 1e-3), "{}", c.text);
    app.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn too_few_or_degenerate_points_are_refused_and_nothing_is_stored() {
    let app = TestApp::start().await;
    let tool = app.tool_id("square", 10.0).await;
    let path = format!("/v1/tools/{tool}/force-model/fit");
    let few = app.post(&path, json!({"points": [{"t_m_um": 40, "l_mm": 2, "fxy_n": 250}], "store": true})).await;
    assert_problem(&few, 422, Some("points"));
    assert!(few.body["detail"].as_str().unwrap().contains("at least 7"));
    let flat: Vec<Value> =
        (0..10).map(|i| json!({"t_m_um": 43.6, "l_mm": 2.0 + 0.1 * i as f64, "fxy_n": 250 + i})).collect();
    assert_problem(&app.post(&path, json!({"points": flat, "store": true})).await, 422, Some("points"));
    let negative: Vec<Value> = (0..10).map(|i| json!({"t_m_um": -1.0 - i as f64, "l_mm": 2.0, "fxy_n": 250})).collect();
    assert_problem(&app.post(&path, json!({"points": negative})).await, 422, Some("points[0].t_m_um"));
    assert_problem(&app.post("/v1/tools/99999/force-model/fit", json!({"points": []})).await, 404, None);
    assert_eq!(app.get(&format!("/v1/force-models?tool_id={tool}")).await.body["total"], 1);
    app.stop().await;
}
