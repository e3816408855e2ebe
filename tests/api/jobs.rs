//! Jobs: create, wait, poll, list, cancel, persistence across restarts.

use crate::common::{assert_problem, database_pool, TestApp};
use serde_json::json;

fn conditions_job() -> serde_json::Value {
    json!({"kind": "conditions", "input": {"tool_type": "square", "diameter_mm": 10}})
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_job_without_wait_is_accepted_with_a_location_and_finishes_when_polled() {
    let app = TestApp::start().await;
    let a = app.post("/v1/jobs", conditions_job()).await;
    assert_eq!(a.status, 202, "{}", a.text);
    let location = a.header("location").unwrap().to_string();
    assert!(location.starts_with("/v1/jobs/"));
    assert_eq!(a.header("retry-after"), Some("1"));
    let id = a.body["id"].as_str().unwrap();
    let job = app.wait_for_job(id).await;
    assert_eq!(job["status"], "succeeded");
    assert_eq!(job["progress"], 1.0);
    assert!(job["started_at"].is_string() && job["finished_at"].is_string());
    assert_eq!(app.get(&format!("{location}/input")).await.body, conditions_job()["input"]);
    assert_eq!(app.get(&location).await.body["id"], id);
    app.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn prefer_wait_returns_the_finished_job_and_says_the_preference_was_applied() {
    let app = TestApp::start().await;
    let a = app.post_wait("/v1/jobs", conditions_job()).await;
    assert_eq!(a.status, 201, "{}", a.text);
    assert_eq!(a.header("preference-applied"), Some("wait=10"));
    assert_eq!(a.body["status"], "succeeded");
    app.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn with_no_worker_a_wait_times_out_into_a_queued_job_that_can_be_cancelled() {
    let app = TestApp::start_with(|c| c.workers = Some(0)).await;
    let a = app.send(reqwest::Method::POST, "/v1/jobs", Some(conditions_job()), &[("prefer", "wait=1")]).await;
    assert_eq!(a.status, 202);
    assert_eq!(a.body["status"], "queued");
    let id = a.body["id"].as_str().unwrap().to_string();
    let cancelled = app.delete(&format!("/v1/jobs/{id}")).await;
    assert_eq!(cancelled.status, 200, "{}", cancelled.text);
    assert_eq!(cancelled.body["status"], "cancelled");
    assert_problem(&app.delete(&format!("/v1/jobs/{id}")).await, 409, None);
    assert_problem(&app.delete("/v1/jobs/00000000-0000-4000-8000-000000000000").await, 404, None);
    app.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_queued_job_survives_a_restart_and_runs_after_it() {
    let app = TestApp::start_with(|c| c.workers = Some(0)).await;
    let a = app.post("/v1/jobs", conditions_job()).await;
    let id = a.body["id"].as_str().unwrap().to_string();
    assert_eq!(app.get(&format!("/v1/jobs/{id}")).await.body["status"], "queued");
    let app = app.restart_with(|c| c.workers = Some(1)).await;
    let job = app.wait_for_job(&id).await;
    assert_eq!(job["status"], "succeeded", "{job}");
    assert!((job["result"]["force"]["fxy_n"].as_f64().unwrap() - 269.1).abs() < 1e-3);
    app.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_job_left_running_by_a_crash_is_queued_again_and_finishes_at_the_next_start() {
    let app = TestApp::start_with(|c| c.workers = Some(0)).await;
    let a = app.post("/v1/jobs", conditions_job()).await;
    let id = a.body["id"].as_str().unwrap().to_string();
    let dir = app.stop().await;
    // Simulate a crash in the middle of the job.
    let pool = database_pool(&dir).await;
    sqlx::query("UPDATE jobs SET status = 'running', attempts = 1, progress = 0.5 WHERE id = $1")
        .bind(&id)
        .execute(&pool)
        .await
        .unwrap();
    pool.close().await;
    let app = TestApp::start_in(dir, |_| {}).await;
    let job = app.wait_for_job(&id).await;
    assert_eq!(job["status"], "succeeded", "{job}");
    assert_eq!(job["attempts"], 2);
    app.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn jobs_are_listed_newest_first_with_filters_and_pages() {
    let app = TestApp::start().await;
    let mut ids = Vec::new();
    for _ in 0..3 {
        ids.push(app.post_wait("/v1/jobs", conditions_job()).await.body["id"].as_str().unwrap().to_string());
    }
    let page = app.get("/v1/jobs?limit=2").await;
    assert_eq!(page.body["total"], 3);
    assert_eq!(page.body["items"].as_array().unwrap().len(), 2);
    assert_eq!(page.body["items"][0]["id"], ids[2].as_str());
    let done = app.get("/v1/jobs?status=succeeded&kind=conditions&offset=2").await;
    assert_eq!(done.body["items"][0]["id"], ids[0].as_str());
    assert_eq!(app.get("/v1/jobs?status=failed").await.body["total"], 0);
    assert_problem(&app.get("/v1/jobs?status=sleeping").await, 400, None);
    app.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_conditions_job_has_no_program_and_a_finished_job_cannot_be_cancelled() {
    let app = TestApp::start().await;
    let id = app.post_wait("/v1/jobs", conditions_job()).await.body["id"].as_str().unwrap().to_string();
    assert_problem(&app.get(&format!("/v1/jobs/{id}/program")).await, 404, None);
    assert_problem(&app.delete(&format!("/v1/jobs/{id}")).await, 409, None);
    assert_problem(&app.get("/v1/jobs/00000000-0000-0000-0000-000000000000").await, 404, None);
    app.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_job_that_runs_past_the_time_limit_is_stopped_and_fails_saying_so() {
    let app = TestApp::start_with(|c| c.job_time_limit_s = 1).await;
    let gcode = std::fs::read_to_string(format!("{}/../shared/data/tiger.nc", env!("CARGO_MANIFEST_DIR")))
        .expect("tiger.nc is in the shared data");
    // tiger.nc at 0.005 mm: some 30 million samples, far more than one second of work.
    let body = json!({
        "program": {"gcode": gcode}, "tool_type": "square", "diameter_mm": 6,
        "stock": {"box": {"x_min": -2, "y_min": -1, "z_min": -32, "x_max": 92, "y_max": 89, "z_max": 0}},
        "sample_spacing_mm": 0.005
    });
    let a = app.send(reqwest::Method::POST, "/v1/analysis", Some(body), &[("prefer", "wait=50")]).await;
    assert_eq!(a.body["status"], "failed", "{}", &a.text[..a.text.len().min(2000)]);
    let error = &a.body["error"];
    assert_eq!(error["status"], 413, "{error}");
    let detail = error["detail"].as_str().unwrap();
    assert!(detail.contains("1 s") && detail.contains("DIEPLAN_JOB_TIME_LIMIT"), "{detail}");
    app.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_malformed_job_id_in_a_path_is_refused_naming_id() {
    let app = TestApp::start_with(|c| c.workers = Some(0)).await;
    for path in
        ["/v1/jobs/abc", "/v1/jobs/abc/input", "/v1/jobs/abc/program", "/v1/jobs/abc/views", "/v1/jobs/abc/drawing.svg"]
    {
        let a = app.get(path).await;
        assert_problem(&a, 400, None);
        assert!(
            a.body["detail"].as_str().unwrap().starts_with("path parameter id: must be a job id"),
            "{path}: {}",
            a.text
        );
    }
    assert_problem(&app.delete("/v1/jobs/abc").await, 400, None);
    app.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_request_with_three_faults_gets_all_three_in_one_problem() {
    let app = TestApp::start_with(|c| c.workers = Some(0)).await;
    let typed = json!({"tool_type": "squar", "diameter_mm": "ten", "operation": "standard_side_cutting", "colour": 1});
    let a = app.post("/v1/conditions", typed).await;
    assert_problem(&a, 422, None);
    let fields: Vec<&str> = a.body["errors"].as_array().unwrap().iter().filter_map(|e| e["field"].as_str()).collect();
    assert_eq!(fields, ["tool_type", "diameter_mm", "colour"], "{}", a.text);
    let bounded = json!({"kind": "conditions", "input": {"tool_type": "square", "diameter_mm": 10, "spindle_rpm": -1, "fz_mm": 0, "rd_mm": -2}});
    let a = app.post("/v1/jobs", bounded).await;
    assert_problem(&a, 422, None);
    let fields: Vec<&str> = a.body["errors"].as_array().unwrap().iter().filter_map(|e| e["field"].as_str()).collect();
    assert_eq!(fields, ["input.spindle_rpm", "input.fz_mm", "input.rd_mm"], "{}", a.text);
    app.stop().await;
}
