//! Errors are problem documents; the middleware layers behave as configured.

use crate::common::{assert_problem, TestApp};
use serde_json::json;

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn unknown_routes_wrong_methods_and_malformed_bodies_get_problem_documents() {
    let app = TestApp::start().await;
    assert_problem(&app.get("/v2/nothing").await, 404, None);
    assert_problem(&app.put("/healthz", json!({})).await, 405, None);
    assert_problem(&app.get("/v1/tools/abc").await, 400, None);
    let malformed = app
        .client
        .post(app.url("/v1/conditions"))
        .header("content-type", "application/json")
        .body("{\"tool_type\": ")
        .send()
        .await
        .unwrap();
    assert_eq!(malformed.status(), 400);
    let text_body = app
        .client
        .post(app.url("/v1/conditions"))
        .header("content-type", "text/plain")
        .body("square 10")
        .send()
        .await
        .unwrap();
    assert_eq!(text_body.status(), 415);
    app.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_body_over_the_limit_is_refused_with_413() {
    let app = TestApp::start_with(|c| c.body_limit = 1024).await;
    let big = json!({"name": "x".repeat(4096), "tool_type": "square", "diameter_mm": 10, "flutes": 4});
    assert_problem(&app.post("/v1/tools", big).await, 413, None);
    app.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn every_response_carries_a_request_id_and_echoes_the_clients() {
    let app = TestApp::start().await;
    let a = app.get("/healthz").await;
    assert!(a.header("x-request-id").is_some_and(|v| v.len() >= 32));
    let b = app.send(reqwest::Method::GET, "/healthz", None, &[("x-request-id", "abc-123")]).await;
    assert_eq!(b.header("x-request-id"), Some("abc-123"));
    app.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn responses_are_gzipped_when_the_client_accepts_it() {
    let app = TestApp::start().await;
    let a = app.send(reqwest::Method::GET, "/openapi.json", None, &[("accept-encoding", "gzip")]).await;
    assert_eq!(a.header("content-encoding"), Some("gzip"));
    app.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn cors_is_off_by_default_and_allows_the_configured_origins() {
    let app = TestApp::start().await;
    let a = app.send(reqwest::Method::GET, "/healthz", None, &[("origin", "https://cam.example")]).await;
    assert!(a.header("access-control-allow-origin").is_none());
    app.stop().await;
    let app = TestApp::start_with(|c| c.cors_origins = vec!["https://cam.example".into()]).await;
    let a = app.send(reqwest::Method::GET, "/healthz", None, &[("origin", "https://cam.example")]).await;
    assert_eq!(a.header("access-control-allow-origin"), Some("https://cam.example"));
    app.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn health_and_readiness_answer() {
    let app = TestApp::start().await;
    assert_eq!(app.get("/healthz").await.body["status"], "ok");
    assert_eq!(app.get("/readyz").await.body["status"], "ready");
    let docs = app.get("/docs/").await;
    assert_eq!(docs.status, 200);
    assert!(docs.text.contains("swagger"), "the UI is served from the binary");
    app.stop().await;
}
