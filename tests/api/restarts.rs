//! Restarts never fail a job: a graceful stop queues a running job again without counting
//! an attempt, answers a client waiting for a job at once (202 with Location), and ends
//! within the grace period.

use crate::common::{long_analysis, TestApp};
use std::time::{Duration, Instant};

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn three_graceful_restarts_during_a_job_neither_count_as_attempts_nor_fail_it() {
    let mut app = TestApp::start().await;
    let id = app.post("/v1/analysis", long_analysis()).await.body["id"].as_str().unwrap().to_string();
    for _ in 0..3 {
        app.wait_until_running(&id).await;
        app = app.restart_with(|c| c.workers = Some(1)).await;
    }
    app.wait_until_running(&id).await;
    let app = app.restart_with(|c| c.workers = Some(0)).await;
    let job = app.get(&format!("/v1/jobs/{id}")).await.body;
    assert_eq!(job["status"], "queued", "{job}");
    assert_eq!(job["attempts"], 0, "{job}");
    app.delete(&format!("/v1/jobs/{id}")).await;
    app.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_stop_answers_a_client_waiting_for_its_job_at_once_with_202_and_location() {
    let app = TestApp::start_with(|c| c.shutdown_grace_s = 5).await;
    let (client, url) = (app.client.clone(), app.url("/v1/analysis"));
    let waiting = tokio::spawn(async move {
        let answer = client.post(url).header("prefer", "wait=60").json(&long_analysis()).send().await.unwrap();
        (answer.status(), answer.headers().get("location").map(|v| v.to_str().unwrap().to_string()), Instant::now())
    });
    tokio::time::sleep(Duration::from_millis(1500)).await;
    let stopping = Instant::now();
    let dir = app.stop().await;
    let stopped = stopping.elapsed();
    let (status, location, answered) = waiting.await.unwrap();
    assert_eq!(status, 202);
    let location = location.expect("Location");
    assert!(location.starts_with("/v1/jobs/"), "{location}");
    assert!(answered.duration_since(stopping) < Duration::from_secs(2), "answered after {:?}", answered - stopping);
    assert!(stopped < Duration::from_secs(6), "stopped after {stopped:?}, grace 5 s");

    // The job goes on at the next start.
    let app = TestApp::start_in(dir, |c| c.workers = Some(0)).await;
    let job = app.get(&location).await.body;
    assert_eq!(job["status"], "queued", "{job}");
    assert_eq!(job["attempts"], 0, "{job}");
    app.stop().await;
}
