//! The committed OpenAPI document is the one the code serves.

use crate::common::TestApp;

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn the_committed_openapi_document_is_what_the_service_serves() {
    let generated = dieplan::service::openapi::document_json();
    let committed_path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("openapi/openapi.json");
    let committed = std::fs::read_to_string(&committed_path).unwrap_or_default();
    assert!(
        committed == generated,
        "openapi/openapi.json is stale: run `cargo run --release -- openapi > openapi/openapi.json`"
    );
    let app = TestApp::start().await;
    let served: serde_json::Value = app.get("/openapi.json").await.body;
    let expected: serde_json::Value = serde_json::from_str(&generated).unwrap();
    assert_eq!(served, expected);
    app.stop().await;
}

#[test]
fn every_route_documents_its_errors_as_problem_documents() {
    let doc: serde_json::Value = serde_json::from_str(&dieplan::service::openapi::document_json()).unwrap();
    let paths = doc["paths"].as_object().unwrap();
    assert!(paths.len() >= 20, "{} paths", paths.len());
    for (path, item) in paths {
        for (method, op) in item.as_object().unwrap() {
            assert!(op["operationId"].is_string(), "{method} {path} has an operation id");
            assert!(op["tags"].is_array(), "{method} {path} has a tag");
            let responses = op["responses"].as_object().unwrap();
            for (code, r) in responses {
                if code.starts_with('4') || code.starts_with('5') {
                    assert!(
                        r["content"]["application/problem+json"].is_object(),
                        "{method} {path} {code} is a problem document"
                    );
                }
            }
        }
    }
}
