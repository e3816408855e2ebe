//! Two clients cannot lose each other's edits: PATCH reads, merges and writes in one
//! transaction, every row has an entity tag, and `If-Match` refuses a stale write (412).

use crate::common::{assert_problem, TestApp};
use reqwest::Method;
use serde_json::json;

/// Rounds of two concurrent patches (the issue lost one in 4 of 20).
const ROUNDS: usize = 20;

#[tokio::test(flavor = "multi_thread", worker_threads = 4)]
async fn two_concurrent_patches_of_different_fields_both_land_every_time() {
    let app = TestApp::start_with(|c| c.workers = Some(0)).await;
    let tool = app.tool_id("square", 10.0).await;
    let path = format!("/v1/tools/{tool}");
    for round in 0..ROUNDS {
        let (coating, price) = (format!("coat {round}"), 100.0 + round as f64);
        let (a, b) =
            tokio::join!(app.patch(&path, json!({"coating": coating})), app.patch(&path, json!({"price": price})));
        assert_eq!((a.status.as_u16(), b.status.as_u16()), (200, 200), "{} {}", a.text, b.text);
        let row = app.get(&path).await.body;
        assert_eq!(row["coating"], coating.as_str(), "round {round}: {row}");
        assert_eq!(row["price"], price, "round {round}: {row}");
    }
    app.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_write_with_a_stale_if_match_is_refused_with_412_and_changes_nothing() {
    let app = TestApp::start_with(|c| c.workers = Some(0)).await;
    let made = app.post("/v1/materials", json!({"name": "NAK80", "hardness_hrc": 40})).await;
    assert_eq!(made.status, 201, "{}", made.text);
    let path = made.header("location").unwrap().to_string();
    let created_tag = made.header("etag").expect("ETag on create").to_string();
    let read = app.get(&path).await;
    let tag = read.header("etag").expect("ETag on read").to_string();
    assert_eq!(tag, created_tag);
    assert!(tag.starts_with('"') && tag.ends_with('"'), "{tag}");

    let first = app.send(Method::PATCH, &path, Some(json!({"hardness_hrc": 41})), &[("if-match", &tag)]).await;
    assert_eq!(first.status, 200, "{}", first.text);
    let new_tag = first.header("etag").unwrap().to_string();
    assert_ne!(new_tag, tag);

    let stale = app.send(Method::PATCH, &path, Some(json!({"hardness_hrc": 30})), &[("if-match", &tag)]).await;
    assert_problem(&stale, 412, None);
    let body = json!({"name": "NAK80", "hardness_hrc": 20});
    assert_problem(&app.send(Method::PUT, &path, Some(body.clone()), &[("if-match", &tag)]).await, 412, None);
    assert_problem(&app.send(Method::DELETE, &path, None, &[("if-match", &tag)]).await, 412, None);
    assert_eq!(app.get(&path).await.body["hardness_hrc"], 41.0, "nothing changed");

    let put = app.send(Method::PUT, &path, Some(body), &[("if-match", &new_tag)]).await;
    assert_eq!(put.status, 200, "{}", put.text);
    let deleted = app.send(Method::DELETE, &path, None, &[("if-match", put.header("etag").unwrap())]).await;
    assert_eq!(deleted.status, 204, "{}", deleted.text);
    app.stop().await;
}
