//! Rate limits across replicas (issue 31): on PostgreSQL every replica takes a key's
//! requests from the same bucket (a row of `rate_limit_buckets`), so two replicas allow a
//! key its limit, not twice it, and refuse it alike: 429 with `Retry-After`. Runs in the
//! PostgreSQL run of the API tests (`postgres_backend.rs`); on SQLite one process serves
//! a database, and `keys.rs` tests its limit.

use super::common::{assert_problem, Answer, TestApp};
use super::postgres;
use reqwest::Method;
use serde_json::json;

/// The limited key's requests a minute: one every 15 s once its bucket is empty.
const LIMIT_PER_MINUTE: u64 = 4;

async fn materials(app: &TestApp, key: &str) -> Answer {
    app.send_as(key, Method::GET, "/v1/materials", None).await
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_keys_rate_limit_holds_across_two_replicas_on_one_postgresql() {
    if !postgres::selected() {
        return; // two replicas share a database on PostgreSQL only
    }
    let first = TestApp::start().await;
    let second = TestApp::start_in(first.dir.clone(), |_| {}).await;
    let admin = first.make_key(None, "admin", "admin").await;
    let made = second
        .send_as(
            &admin,
            Method::POST,
            "/v1/keys",
            Some(json!({"role": "reader", "name": "script", "rate_limit_per_minute": LIMIT_PER_MINUTE})),
        )
        .await;
    assert_eq!(made.status, 201, "{}", made.text);
    let script = made.body["key"].as_str().expect("the secret");

    // The limit's requests pass, taken in turn from either replica...
    for n in 0..LIMIT_PER_MINUTE {
        let replica = if n % 2 == 0 { &first } else { &second };
        let a = materials(replica, script).await;
        assert_eq!(a.status, 200, "request {n}: {}", a.text);
    }
    // ...and then each replica refuses the next, saying when the bucket has room again.
    for replica in [&first, &second] {
        let refused = materials(replica, script).await;
        assert_problem(&refused, 429, None);
        let retry: u64 = refused.header("retry-after").expect("Retry-After").parse().expect("whole seconds");
        assert!((1..=60 / LIMIT_PER_MINUTE).contains(&retry), "Retry-After: {retry}");
        assert!(refused.body["detail"].as_str().is_some_and(|d| d.contains("4 requests a minute")), "{}", refused.text);
    }
    // Another key has its own bucket, on both replicas.
    assert_eq!(materials(&first, &admin).await.status, 200);
    assert_eq!(materials(&second, &admin).await.status, 200);
    first.stop().await;
    second.stop().await;
}
