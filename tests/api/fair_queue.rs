//! A fair queue: short jobs have their own lane and worker, so a conditions job is not
//! starved behind long ones.

use crate::common::{long_analysis, TestApp};
use std::time::{Duration, Instant};

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_conditions_job_submitted_behind_three_long_jobs_finishes_within_a_second() {
    let app = TestApp::start_with(|c| c.workers = Some(1)).await;
    let mut long = Vec::new();
    for _ in 0..3 {
        long.push(app.post("/v1/analysis", long_analysis()).await.body["id"].as_str().unwrap().to_string());
    }
    app.wait_until_running(&long[0]).await;
    let started = Instant::now();
    let a = app.post_wait("/v1/conditions", serde_json::json!({"tool_type": "square", "diameter_mm": 10})).await;
    let took = started.elapsed();
    assert_eq!(a.status, 201, "{}", a.text);
    assert_eq!(a.body["status"], "succeeded");
    assert!(took < Duration::from_secs(1), "took {took:?}");
    for id in &long {
        app.delete(&format!("/v1/jobs/{id}")).await;
    }
    app.stop().await;
}
