//! Several replicas of the release binary on one PostgreSQL (issue 31): a replica killed
//! with `kill -9` in the middle of a job loses nothing, and cancel and progress work across
//! replicas. Each test starts its replicas as processes on a database of its own on the
//! test PostgreSQL (`postgres.rs`); it runs in the PostgreSQL run of the API tests
//! (`postgres_backend.rs`) and is skipped in the SQLite one.

use super::postgres;
use reqwest::StatusCode;
use serde_json::{json, Value};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

/// The lease of these tests' replicas, seconds: short, so that a dead replica's job moves
/// on quickly.
const LEASE_S: u64 = 2;

/// A replica: the release binary serving on a port of its own.
struct Replica {
    base: String,
    child: Child,
}

impl Replica {
    async fn start(database: &str, workers: usize) -> Replica {
        let port = std::net::TcpListener::bind("127.0.0.1:0").expect("a free port").local_addr().expect("port").port();
        let child = Command::new(env!("CARGO_BIN_EXE_dieplan"))
            .args(["serve", "--addr", &format!("127.0.0.1:{port}"), "--database", database])
            .args(["--workers", &workers.to_string(), "--job-lease-seconds", &LEASE_S.to_string()])
            .env("DIEPLAN_LOG", "warn")
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .spawn()
            .expect("the release binary starts");
        let replica = Replica { base: format!("http://127.0.0.1:{port}"), child };
        let deadline = Instant::now() + Duration::from_secs(60);
        while Instant::now() < deadline {
            if reqwest::get(format!("{}/readyz", replica.base)).await.is_ok_and(|r| r.status() == StatusCode::OK) {
                return replica;
            }
            tokio::time::sleep(Duration::from_millis(100)).await;
        }
        panic!("replica on port {port} did not become ready");
    }

    async fn get(&self, path: &str) -> Value {
        reqwest::get(format!("{}{path}", self.base)).await.expect("answered").json().await.expect("JSON")
    }

    async fn post(&self, path: &str, body: &Value) -> (StatusCode, Value) {
        let r = reqwest::Client::new().post(format!("{}{path}", self.base)).json(body).send().await.expect("answered");
        (r.status(), r.json().await.unwrap_or(Value::Null))
    }

    async fn delete(&self, path: &str) -> StatusCode {
        reqwest::Client::new().delete(format!("{}{path}", self.base)).send().await.expect("answered").status()
    }

    async fn status(&self, id: &str) -> Value {
        self.get(&format!("/v1/jobs/{id}")).await
    }

    /// Waits until job `id` satisfies `done`, for at most `seconds`.
    async fn wait_until(&self, id: &str, seconds: u64, done: impl Fn(&Value) -> bool) -> Value {
        let deadline = Instant::now() + Duration::from_secs(seconds);
        loop {
            let job = self.status(id).await;
            if done(&job) {
                return job;
            }
            assert!(Instant::now() < deadline, "job {id} never got there: {job}");
            tokio::time::sleep(Duration::from_millis(100)).await;
        }
    }

    /// Kills the process at once (SIGKILL: no shutdown, no requeue).
    fn kill(mut self) {
        self.child.kill().expect("kill -9");
        self.child.wait().ok();
    }
}

impl Drop for Replica {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

/// An analysis of tiger.nc sampled finely enough to run for seconds on any machine.
fn job_of_seconds() -> Value {
    let mut job = super::common::long_analysis();
    job["sample_spacing_mm"] = json!(0.05);
    json!({"kind": "analysis", "input": job})
}

fn finished(job: &Value) -> bool {
    ["succeeded", "failed", "cancelled"].contains(&job["status"].as_str().unwrap_or(""))
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_replica_killed_mid_job_loses_nothing_and_every_job_finishes_once_on_the_other() {
    if !postgres::selected() {
        return;
    }
    let database = postgres::fresh_database().await;
    let doomed = Replica::start(&database, 1).await;
    let (status, first) = doomed.post("/v1/jobs", &job_of_seconds()).await;
    assert_eq!(status, StatusCode::ACCEPTED, "{first}");
    let first = first["id"].as_str().expect("id").to_string();
    doomed.wait_until(&first, 60, |j| j["status"] == "running").await;

    let survivor = Replica::start(&database, 1).await;
    let mut ids = vec![first.clone()];
    for _ in 0..3 {
        let (status, job) = survivor
            .post("/v1/jobs", &json!({"kind": "conditions", "input": {"tool_type": "square", "diameter_mm": 10}}))
            .await;
        assert!(status.is_success(), "{job}");
        ids.push(job["id"].as_str().expect("id").to_string());
    }
    doomed.kill();

    for id in &ids {
        let job = survivor.wait_until(id, 120, finished).await;
        assert_eq!(job["status"], "succeeded", "{job}");
    }
    let job = survivor.status(&first).await;
    assert_eq!(job["attempts"], 2, "the killed attempt counts, and one more ran it: {job}");
    let result = survivor.get(&format!("/v1/jobs/{first}")).await;
    assert!(result["result"].is_object(), "{result}");

    let page = survivor.get("/v1/jobs?limit=100").await;
    assert_eq!(page["total"], ids.len(), "no job lost or duplicated: {page}");
    let stored = count_results(&database).await;
    assert_eq!(stored, ids.len() as i64, "one stored result per job");
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_job_running_on_one_replica_shows_its_progress_and_is_cancelled_through_another() {
    if !postgres::selected() {
        return;
    }
    let database = postgres::fresh_database().await;
    let worker = Replica::start(&database, 1).await;
    let front = Replica::start(&database, 0).await;
    let mut long = super::common::long_analysis();
    long["sample_spacing_mm"] = json!(0.005);
    let (status, job) = front.post("/v1/jobs", &json!({"kind": "analysis", "input": long})).await;
    assert_eq!(status, StatusCode::ACCEPTED, "{job}");
    let id = job["id"].as_str().expect("id").to_string();
    front.wait_until(&id, 60, |j| j["status"] == "running" && j["progress"].as_f64().is_some_and(|p| p > 0.0)).await;

    let asked = Instant::now();
    assert!(front.delete(&format!("/v1/jobs/{id}")).await.is_success());
    let job = front.wait_until(&id, 30, finished).await;
    assert_eq!(job["status"], "cancelled", "{job}");
    assert!(asked.elapsed() < Duration::from_secs(10), "cancelled after {:?}", asked.elapsed());
    drop(worker);
}

/// The number of stored results, read from the database itself.
async fn count_results(database: &str) -> i64 {
    use sqlx::Connection;
    let mut conn = sqlx::PgConnection::connect(database).await.expect("database");
    sqlx::query_scalar("SELECT COUNT(*) FROM job_blobs WHERE part = 'result'")
        .fetch_one(&mut conn)
        .await
        .expect("count")
}
