//! Starting the app for a test and talking to it.

use dieplan::service::app::{start, RunningServer};
use dieplan::service::config::Config;
use dieplan::service::store::{Location, Pool};
use reqwest::{header::HeaderMap, Method, StatusCode};
use serde_json::Value;
use std::path::PathBuf;
use std::sync::Arc;
use tempfile::TempDir;

/// A running app on a temporary database.
pub struct TestApp {
    pub base: String,
    pub client: reqwest::Client,
    pub dir: Arc<TempDir>,
    server: RunningServer,
}

/// An HTTP answer: status, headers, JSON body (Null when not JSON).
pub struct Answer {
    pub status: StatusCode,
    pub headers: HeaderMap,
    pub body: Value,
    pub text: String,
}

impl Answer {
    pub fn header(&self, name: &str) -> Option<&str> {
        self.headers.get(name).and_then(|v| v.to_str().ok())
    }

    pub fn content_type(&self) -> &str {
        self.header("content-type").unwrap_or("")
    }
}

impl TestApp {
    pub async fn start() -> TestApp {
        TestApp::start_with(|_| {}).await
    }

    pub async fn start_with(configure: impl FnOnce(&mut Config)) -> TestApp {
        let dir = Arc::new(tempfile::tempdir().expect("temp dir"));
        TestApp::start_in(dir, configure).await
    }

    pub async fn start_in(dir: Arc<TempDir>, configure: impl FnOnce(&mut Config)) -> TestApp {
        let mut config = Config::with_database(database_of(&dir).await);
        config.workers = Some(1);
        configure(&mut config);
        let server = start(config).await.expect("app starts");
        TestApp { base: format!("http://{}", server.addr), client: reqwest::Client::new(), dir, server }
    }

    /// Stops the app gracefully and starts it again on the same database.
    pub async fn restart_with(self, configure: impl FnOnce(&mut Config)) -> TestApp {
        let dir = self.dir.clone();
        self.server.stop().await;
        TestApp::start_in(dir, configure).await
    }

    /// Stops the app; the returned directory keeps the database until dropped.
    pub async fn stop(self) -> Arc<TempDir> {
        self.server.stop().await;
        self.dir
    }

    /// The app's SQLite file (in the SQLite run).
    pub fn database(&self) -> PathBuf {
        db_path(&self.dir)
    }

    /// The app's database as `--database` takes it: the SQLite file, or in the PostgreSQL
    /// run the URL of the test's database.
    pub async fn database_arg(&self) -> String {
        match database_of(&self.dir).await {
            Location::Sqlite(path) => path.display().to_string(),
            Location::Postgres(url) => url,
        }
    }

    /// A pool on the app's database, to look at or change its tables behind its back.
    pub async fn pool(&self) -> Pool {
        database_pool(&self.dir).await
    }

    pub fn url(&self, path: &str) -> String {
        format!("{}{}", self.base, path)
    }

    pub async fn send(&self, method: Method, path: &str, body: Option<Value>, headers: &[(&str, &str)]) -> Answer {
        let mut req = self.client.request(method, self.url(path));
        for (k, v) in headers {
            req = req.header(*k, *v);
        }
        if let Some(body) = body {
            req = req.json(&body);
        }
        let resp = req.send().await.expect("request is answered");
        let status = resp.status();
        let headers = resp.headers().clone();
        let text = resp.text().await.expect("body");
        let body = serde_json::from_str(&text).unwrap_or(Value::Null);
        Answer { status, headers, body, text }
    }

    pub async fn get(&self, path: &str) -> Answer {
        self.send(Method::GET, path, None, &[]).await
    }

    pub async fn post(&self, path: &str, body: Value) -> Answer {
        self.send(Method::POST, path, Some(body), &[]).await
    }

    /// POST with `Prefer: wait=10`: the finished job.
    pub async fn post_wait(&self, path: &str, body: Value) -> Answer {
        self.send(Method::POST, path, Some(body), &[("prefer", "wait=10")]).await
    }

    pub async fn put(&self, path: &str, body: Value) -> Answer {
        self.send(Method::PUT, path, Some(body), &[]).await
    }

    pub async fn patch(&self, path: &str, body: Value) -> Answer {
        self.send(Method::PATCH, path, Some(body), &[]).await
    }

    pub async fn delete(&self, path: &str) -> Answer {
        self.send(Method::DELETE, path, None, &[]).await
    }

    /// Polls a job until it is finished.
    pub async fn wait_for_job(&self, id: &str) -> Value {
        self.wait_for_job_within(id, 10).await
    }

    /// Polls a job until it is finished, for at most about `seconds` (long jobs on a loaded
    /// machine).
    pub async fn wait_for_job_within(&self, id: &str, seconds: u64) -> Value {
        for _ in 0..seconds * 20 {
            let a = self.get(&format!("/v1/jobs/{id}")).await;
            let status = a.body["status"].as_str().unwrap_or("").to_string();
            if ["succeeded", "failed", "cancelled"].contains(&status.as_str()) {
                return a.body;
            }
            tokio::time::sleep(std::time::Duration::from_millis(50)).await;
        }
        panic!("job {id} did not finish");
    }

    /// The id of the seeded tool of this type and diameter.
    pub async fn tool_id(&self, tool_type: &str, diameter: f64) -> i64 {
        let a = self.get(&format!("/v1/tools?tool_type={tool_type}&diameter_mm={diameter}")).await;
        a.body["items"][0]["id"].as_i64().expect("seeded tool")
    }
}

fn db_path(dir: &TempDir) -> PathBuf {
    dir.path().join("dieplan.sqlite")
}

/// The database of a test directory: its SQLite file, or under `DIEPLAN_TEST_BACKEND=postgres`
/// a database of the test PostgreSQL made for it (named in the directory, so that a
/// restart finds the same).
async fn database_of(dir: &TempDir) -> Location {
    if !super::postgres::selected() {
        return Location::Sqlite(db_path(dir));
    }
    let named = dir.path().join("postgres-url");
    let url = match std::fs::read_to_string(&named) {
        Ok(url) => url,
        Err(_) => {
            let url = super::postgres::fresh_database().await;
            std::fs::write(&named, &url).expect("test dir writable");
            url
        }
    };
    Location::Postgres(url)
}

/// A pool on the database of a test directory (of a stopped app, too), whichever the
/// backend: its SQL is written for both (`$1` placeholders).
pub async fn database_pool(dir: &TempDir) -> Pool {
    dieplan::service::store::open(&database_of(dir).await).await.expect("the test database opens")
}

/// Asserts a problem document with `status` naming `field`.
pub fn assert_problem(a: &Answer, status: u16, field: Option<&str>) {
    assert_eq!(a.status.as_u16(), status, "{}", a.text);
    assert!(a.content_type().starts_with("application/problem+json"), "content type {}", a.content_type());
    assert_eq!(a.body["status"], status);
    assert!(a.body["detail"].as_str().is_some_and(|d| !d.is_empty()));
    if let Some(field) = field {
        let fields: Vec<&str> = a.body["errors"]
            .as_array()
            .map(|e| e.iter().filter_map(|x| x["field"].as_str()).collect())
            .unwrap_or_default();
        assert!(fields.contains(&field), "expected field {field} in {}", a.text);
    }
}

pub fn close(actual: &Value, expected: f64, tol: f64) -> bool {
    actual.as_f64().is_some_and(|a| (a - expected).abs() <= tol)
}

/// A polygon of `n` vertices on a circle of radius 40 mm.
pub fn many_sided(n: usize) -> Vec<[f64; 2]> {
    (0..n)
        .map(|k| {
            let a = std::f64::consts::TAU * k as f64 / n as f64;
            [40.0 * a.cos(), 40.0 * a.sin()]
        })
        .collect()
}

/// An analysis job that runs for minutes (tiger.nc sampled every 5 µm: some 30 million
/// samples) and stops at once when cancelled: a job to interrupt, or to queue behind.
pub fn long_analysis() -> Value {
    let gcode = std::fs::read_to_string(format!("{}/../shared/data/tiger.nc", env!("CARGO_MANIFEST_DIR")))
        .expect("tiger.nc is in the shared data");
    serde_json::json!({
        "program": {"gcode": gcode}, "tool_type": "square", "diameter_mm": 6,
        "stock": {"box": {"x_min": -2, "y_min": -1, "z_min": -32, "x_max": 92, "y_max": 89, "z_max": 0}},
        "sample_spacing_mm": 0.005
    })
}

/// `Authorization: Bearer <key>`, as a header pair for [`TestApp::send`].
pub fn bearer(key: &str) -> (&'static str, String) {
    ("authorization", format!("Bearer {key}"))
}

impl TestApp {
    /// A request with an API key.
    pub async fn send_as(&self, key: &str, method: Method, path: &str, body: Option<Value>) -> Answer {
        let (name, value) = bearer(key);
        self.send(method, path, body, &[(name, value.as_str())]).await
    }

    /// Makes a key with `admin_key` (none: while the service is open) and returns its secret.
    pub async fn make_key(&self, admin_key: Option<&str>, role: &str, name: &str) -> String {
        let body = serde_json::json!({"role": role, "name": name});
        let a = match admin_key {
            Some(key) => self.send_as(key, Method::POST, "/v1/keys", Some(body)).await,
            None => self.post("/v1/keys", body).await,
        };
        assert_eq!(a.status, 201, "{}", a.text);
        a.body["key"].as_str().expect("the secret").to_string()
    }

    /// Polls a job until it is running.
    pub async fn wait_until_running(&self, id: &str) {
        for _ in 0..600 {
            if self.get(&format!("/v1/jobs/{id}")).await.body["status"] == "running" {
                return;
            }
            tokio::time::sleep(std::time::Duration::from_millis(50)).await;
        }
        panic!("job {id} did not start");
    }
}

/// A database file migrated up to `version` only (a shop's database before a later
/// migration), in a directory to start the app in; with a pool on it to write rows.
pub async fn database_before(version: i64) -> (Arc<TempDir>, PathBuf, sqlx::SqlitePool) {
    use sqlx::sqlite::{SqliteConnectOptions, SqlitePoolOptions};
    use std::str::FromStr;
    let dir = Arc::new(tempfile::tempdir().expect("temp dir"));
    let path = dir.path().join("shop.sqlite");
    let options = SqliteConnectOptions::from_str(&format!("sqlite://{}", path.display()))
        .expect("sqlite path")
        .create_if_missing(true)
        .foreign_keys(true);
    let pool = SqlitePoolOptions::new().max_connections(1).connect_with(options).await.expect("database");
    dieplan::service::store::MIGRATOR.run_to(version, &pool).await.expect("migrations");
    (dir, path, pool)
}

/// A multipart body of `parts` (name, file name, bytes) with its content type.
pub fn multipart(parts: &[(&str, Option<&str>, &[u8])]) -> (String, Vec<u8>) {
    let boundary = "dieplan-test-boundary-7MA4YWxkTrZu0gW";
    let mut body = Vec::new();
    for (name, file, bytes) in parts {
        body.extend_from_slice(format!("--{boundary}\r\n").as_bytes());
        let file = file.map(|f| format!("; filename=\"{f}\"")).unwrap_or_default();
        body.extend_from_slice(format!("Content-Disposition: form-data; name=\"{name}\"{file}\r\n\r\n").as_bytes());
        body.extend_from_slice(bytes);
        body.extend_from_slice(b"\r\n");
    }
    body.extend_from_slice(format!("--{boundary}--\r\n").as_bytes());
    (format!("multipart/form-data; boundary={boundary}"), body)
}

pub async fn upload(app: &TestApp, path: &str, parts: &[(&str, Option<&str>, &[u8])]) -> Answer {
    let (content_type, body) = multipart(parts);
    let resp = app
        .client
        .post(app.url(path))
        .header("content-type", content_type)
        .header("prefer", "wait=10")
        .body(body)
        .send()
        .await
        .expect("request is answered");
    let (status, headers) = (resp.status(), resp.headers().clone());
    let text = resp.text().await.expect("body");
    Answer { status, headers, body: serde_json::from_str(&text).unwrap_or(Value::Null), text }
}
