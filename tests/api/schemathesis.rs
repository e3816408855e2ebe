//! Schemathesis, with every check, against the real app: the OpenAPI document is what the
//! service does (tests/schemathesis/run.sh), and a finished job of every kind validates
//! against it (tests/schemathesis/finished_jobs.py).

use crate::common::TestApp;
use dieplan::service::config::Secret;

/// The admin key of the run: set up as `DIEPLAN_ADMIN_KEY` would, so that Schemathesis,
/// which calls `DELETE /v1/keys/{id}` too, cannot revoke it (409).
const ADMIN_KEY: &str = "schemathesis-run-admin-key-0123456789abcdef";

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn schemathesis_finds_no_answer_the_openapi_document_does_not_promise() {
    let app = TestApp::start_with(|config| {
        config.workers = Some(2);
        config.rate_limit_per_minute = 0;
        config.max_wait_s = 2;
        config.job_time_limit_s = 120;
        config.admin_key = Some(Secret(ADMIN_KEY.to_string()));
    })
    .await;
    let root = env!("CARGO_MANIFEST_DIR");
    let base = app.base.clone();
    let output = tokio::task::spawn_blocking(move || {
        std::process::Command::new("bash")
            .arg(format!("{root}/tests/schemathesis/run.sh"))
            .env("DIEPLAN", base)
            .env("DIEPLAN_KEY", ADMIN_KEY)
            .current_dir(root)
            .output()
            .expect("bash runs")
    })
    .await
    .expect("the run finishes");
    let text = format!("{}{}", String::from_utf8_lossy(&output.stdout), String::from_utf8_lossy(&output.stderr));
    app.stop().await;
    assert!(output.status.success(), "Schemathesis found failures (report in target/schemathesis/):\n{text}");
}
