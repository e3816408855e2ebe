//! The web page's assets at `/` and the built-in examples at `/v1/examples`.

use crate::common::TestApp;
use reqwest::Method;
use serde_json::json;

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn the_page_and_its_assets_are_served_with_their_types_and_revalidated_by_etag() {
    let app = TestApp::start().await;
    for (path, content_type) in [
        ("/", "text/html"),
        ("/app.js", "text/javascript"),
        ("/new-job.js", "text/javascript"),
        ("/app.css", "text/css"),
        ("/favicon.svg", "image/svg+xml"),
        // three.js for the 3-D view, and its licence.
        ("/vendor/three/three.module.js", "text/javascript"),
        ("/vendor/three/three.core.js", "text/javascript"),
        ("/vendor/three/OrbitControls.js", "text/javascript"),
        ("/vendor/three/LICENSE", "text/plain"),
    ] {
        let a = app.get(path).await;
        assert_eq!(a.status, 200, "{path}");
        assert!(a.content_type().starts_with(content_type), "{path}: {}", a.content_type());
        assert_eq!(a.header("cache-control"), Some("no-cache"), "{path}");
        let etag = a.header("etag").expect("an etag").to_string();
        let again = app.send(Method::GET, path, None, &[("if-none-match", &etag)]).await;
        assert_eq!(again.status, 304, "{path}");
    }
    // Every module the page imports is served.
    let html = app.get("/").await.text;
    assert!(html.contains("src=\"/app.js\"") && html.contains("href=\"/app.css\""));
    let pages = ["/app.js", "/ui.js", "/new-job.js", "/job-view.js", "/drawing.js", "/jobs.js", "/database.js"];
    for js in pages.into_iter().chain(["/view3d-panel.js", "/view3d.js", "/scene3d.js"]) {
        for import in app.get(js).await.text.lines().filter_map(|l| l.split("from './").nth(1)) {
            let module = format!("/{}", import.split('\'').next().unwrap_or_default());
            assert_eq!(app.get(&module).await.status, 200, "{js} imports {module}");
        }
    }
    // The import map names three.js for the 3-D view's modules.
    assert!(html.contains(r#""three": "/vendor/three/three.module.js""#), "no import map for three.js");
    // The API docs and unknown routes are unchanged.
    assert_eq!(app.get("/openapi.json").await.status, 200);
    assert_eq!(app.get("/docs/").await.status, 200);
    assert_eq!(app.get("/nope.js").await.status, 404);
    app.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn every_built_in_example_is_accepted_and_the_quick_ones_succeed() {
    let app = TestApp::start().await;
    let list = app.get("/v1/examples").await;
    assert_eq!(list.status, 200, "{}", list.text);
    let items = list.body["items"].as_array().expect("items");
    assert!(items.len() >= 4);
    for example in items {
        let kind = example["kind"].as_str().unwrap();
        let a = app.post("/v1/jobs", json!({"kind": kind, "input": example["input"].clone()})).await;
        assert!(a.status == 201 || a.status == 202, "{}: {}", example["id"], a.text);
        let id = a.body["id"].as_str().unwrap().to_string();
        if kind == "plan" {
            // About a minute: accepted is enough here (tests/api/plans.rs and the README's
            // plan example run plans of this kind to the end).
            app.delete(&format!("/v1/jobs/{id}")).await;
            continue;
        }
        let job = app.wait_for_job_within(&id, 300).await;
        assert_eq!(job["status"], "succeeded", "{}: {job}", example["id"]);
    }
    app.stop().await;
}
