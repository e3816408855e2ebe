//! A real PostgreSQL for the tests: started once per test process by
//! `tests/postgres/start.sh` (Debian's `postgresql`, `initdb` into a temporary directory,
//! `pg_ctl` as an unprivileged user), stopped when the process exits. Each test gets a
//! database of its own.

use sqlx::{Connection, Executor};
use std::sync::OnceLock;

/// `DIEPLAN_TEST_BACKEND=postgres` runs the API tests against PostgreSQL instead of
/// SQLite (see `postgres_backend.rs`).
pub const BACKEND_VARIABLE: &str = "DIEPLAN_TEST_BACKEND";

/// `true` when this test process runs the API tests against PostgreSQL.
pub fn selected() -> bool {
    std::env::var(BACKEND_VARIABLE).is_ok_and(|v| v == "postgres")
}

/// The server's URL without a database name, e.g. `postgres://dieplan@127.0.0.1:5433`.
pub fn server() -> &'static str {
    static SERVER: OnceLock<String> = OnceLock::new();
    SERVER.get_or_init(start)
}

fn start() -> String {
    let dir = tempfile::Builder::new().prefix("dieplan-pg-").tempdir().expect("temp dir").keep();
    let port = std::net::TcpListener::bind("127.0.0.1:0").expect("a free port").local_addr().expect("port").port();
    let output = std::process::Command::new("bash")
        .arg(format!("{}/tests/postgres/start.sh", env!("CARGO_MANIFEST_DIR")))
        .arg(&dir)
        .arg(port.to_string())
        .arg(std::process::id().to_string())
        .output()
        .expect("bash runs");
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(
        output.status.success(),
        "tests/postgres/start.sh failed:\n{stdout}\n{}",
        String::from_utf8_lossy(&output.stderr)
    );
    stdout.lines().last().expect("the server's URL").trim().to_string()
}

/// A new, empty database on the server; its URL.
pub async fn fresh_database() -> String {
    let base = server();
    let name = format!("t_{}", uuid::Uuid::new_v4().simple());
    let mut admin = sqlx::PgConnection::connect(&format!("{base}/postgres")).await.expect("the test server answers");
    admin.execute(sqlx::AssertSqlSafe(format!("CREATE DATABASE {name}"))).await.expect("database created");
    admin.close().await.ok();
    format!("{base}/{name}")
}
