//! Schemathesis, with every check, against the real app: the OpenAPI document is what the
//! service does (tests/schemathesis/run.sh).

use crate::common::TestApp;
use serde_json::json;

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn schemathesis_finds_no_answer_the_openapi_document_does_not_promise() {
    let app = TestApp::start_with(|config| {
        config.workers = Some(1);
        config.rate_limit_per_minute = 0;
        config.max_wait_s = 2;
        config.job_time_limit_s = 20;
    })
    .await;
    let made = app.post("/v1/keys", json!({"role": "admin", "name": "schemathesis"})).await;
    assert_eq!(made.status, 201, "{}", made.text);
    let key = made.body["key"].as_str().expect("the secret").to_string();
    let root = env!("CARGO_MANIFEST_DIR");
    let base = app.base.clone();
    let output = tokio::task::spawn_blocking(move || {
        std::process::Command::new("bash")
            .arg(format!("{root}/tests/schemathesis/run.sh"))
            .env("DIEPLAN", base)
            .env("DIEPLAN_KEY", key)
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
