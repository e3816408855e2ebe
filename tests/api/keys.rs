//! API keys: the service is open without keys (on loopback), closed once one exists;
//! roles reader, planner and admin; a planner's own jobs; rate limits; the environment's
//! admin key; the `dieplan keys` command; refusing to listen beyond loopback unprotected;
//! `--allowed-hosts`.

use crate::common::{assert_problem, TestApp};
use reqwest::Method;
use serde_json::json;

fn conditions() -> serde_json::Value {
    json!({"tool_type": "square", "diameter_mm": 10})
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_service_without_keys_is_open_until_the_first_key_which_must_be_an_admin_key() {
    let app = TestApp::start().await;
    assert_eq!(app.get("/v1/tools").await.status, 200);
    let refused = app.post("/v1/keys", json!({"role": "planner", "name": "cam 1"})).await;
    assert_problem(&refused, 409, None);
    let made = app.post("/v1/keys", json!({"role": "admin", "name": "shop admin"})).await;
    assert_eq!(made.status, 201, "{}", made.text);
    let admin = made.body["key"].as_str().unwrap();
    assert!(admin.starts_with("dpk_") && admin.len() > 40, "{admin}");
    assert_eq!(made.header("location"), Some(format!("/v1/keys/{}", made.body["id"]).as_str()));

    let closed = app.get("/v1/tools").await;
    assert_problem(&closed, 401, None);
    assert_eq!(closed.header("www-authenticate"), Some("Bearer realm=\"dieplan\""));
    assert_eq!(app.send(Method::HEAD, "/v1/tools", None, &[]).await.status, 401, "HEAD needs a key as GET does");
    assert_eq!(app.send_as(admin, Method::GET, "/v1/tools", None).await.status, 200);
    for open in ["/healthz", "/readyz", "/openapi.json", "/", "/app.js", "/docs/"] {
        assert_eq!(app.get(open).await.status, 200, "{open} stays open");
    }
    assert_problem(&app.send_as("dpk_not-a-key", Method::GET, "/v1/tools", None).await, 401, None);
    let basic = app.send(Method::GET, "/v1/tools", None, &[("authorization", "Basic YWRtaW46YWRtaW4=")]).await;
    assert_problem(&basic, 401, None);

    // The list never shows a secret, only its start.
    let keys = app.send_as(admin, Method::GET, "/v1/keys", None).await;
    assert_eq!(keys.body.as_array().unwrap().len(), 1);
    assert!(!keys.text.contains(admin));
    assert_eq!(keys.body[0]["prefix"].as_str().unwrap(), format!("{}…", &admin[..12]));
    app.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn each_role_does_what_it_is_for_and_is_told_403_beyond_it() {
    let app = TestApp::start().await;
    let admin = app.make_key(None, "admin", "admin").await;
    let reader = app.make_key(Some(&admin), "reader", "MES dashboard").await;
    let planner = app.make_key(Some(&admin), "planner", "CAM station 1").await;
    let tool =
        app.send_as(&admin, Method::GET, "/v1/tools?limit=1", None).await.body["items"][0]["id"].as_i64().unwrap();
    let patch = || Some(json!({"coating": "TiAlN"}));

    assert_eq!(app.send_as(&reader, Method::GET, "/v1/tools", None).await.status, 200);
    assert_problem(&app.send_as(&reader, Method::POST, "/v1/conditions", Some(conditions())).await, 403, None);
    assert_problem(&app.send_as(&reader, Method::PATCH, &format!("/v1/tools/{tool}"), patch()).await, 403, None);

    let job = app
        .send(
            Method::POST,
            "/v1/conditions",
            Some(conditions()),
            &[("authorization", &format!("Bearer {planner}")), ("prefer", "wait=10")],
        )
        .await;
    assert_eq!(job.status, 201, "{}", job.text);
    assert_eq!(job.body["status"], "succeeded");
    let forbidden = app.send_as(&planner, Method::PATCH, &format!("/v1/tools/{tool}"), patch()).await;
    assert_problem(&forbidden, 403, None);
    assert!(forbidden.body["detail"].as_str().unwrap().contains("admin"), "{}", forbidden.text);
    assert_problem(&app.send_as(&planner, Method::GET, "/v1/keys", None).await, 403, None);

    assert_eq!(app.send_as(&admin, Method::PATCH, &format!("/v1/tools/{tool}"), patch()).await.status, 200);

    // A revoked key is refused from then on, and stays listed.
    let keys = app.send_as(&admin, Method::GET, "/v1/keys", None).await;
    let reader_id =
        keys.body.as_array().unwrap().iter().find(|k| k["role"] == "reader").unwrap()["id"].as_i64().unwrap();
    let revoked = app.send_as(&admin, Method::DELETE, &format!("/v1/keys/{reader_id}"), None).await;
    assert_eq!(revoked.status, 200, "{}", revoked.text);
    assert!(revoked.body["revoked_at"].is_string());
    assert_problem(&app.send_as(&reader, Method::GET, "/v1/tools", None).await, 401, None);
    app.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_planner_sees_and_cancels_its_own_jobs_and_an_admin_every_job() {
    let app = TestApp::start_with(|c| c.workers = Some(0)).await;
    let admin = app.make_key(None, "admin", "admin").await;
    let alice = app.make_key(Some(&admin), "planner", "station A").await;
    let bob = app.make_key(Some(&admin), "planner", "station B").await;
    let reader = app.make_key(Some(&admin), "reader", "dashboard").await;
    let a = app.send_as(&alice, Method::POST, "/v1/conditions", Some(conditions())).await;
    let b = app.send_as(&bob, Method::POST, "/v1/conditions", Some(conditions())).await;
    let (job_a, job_b) = (a.body["id"].as_str().unwrap(), b.body["id"].as_str().unwrap());
    assert!(a.body["key_id"].is_i64() && a.body["key_id"] != b.body["key_id"], "jobs record their key");

    let mine = app.send_as(&alice, Method::GET, "/v1/jobs", None).await;
    assert_eq!(mine.body["total"], 1);
    assert_eq!(mine.body["items"][0]["id"], job_a);
    assert_problem(&app.send_as(&alice, Method::GET, &format!("/v1/jobs/{job_b}"), None).await, 404, None);
    assert_problem(&app.send_as(&alice, Method::DELETE, &format!("/v1/jobs/{job_b}"), None).await, 404, None);
    assert_problem(&app.send_as(&alice, Method::GET, &format!("/v1/jobs/{job_b}/program"), None).await, 404, None);
    assert_eq!(app.send_as(&alice, Method::DELETE, &format!("/v1/jobs/{job_a}"), None).await.status, 200);

    assert_eq!(app.send_as(&admin, Method::GET, "/v1/jobs", None).await.body["total"], 2);
    assert_eq!(app.send_as(&reader, Method::GET, "/v1/jobs", None).await.body["total"], 2);
    assert_eq!(app.send_as(&reader, Method::GET, &format!("/v1/jobs/{job_b}"), None).await.status, 200);
    assert_problem(&app.send_as(&reader, Method::DELETE, &format!("/v1/jobs/{job_b}"), None).await, 403, None);
    let cancelled = app.send_as(&admin, Method::DELETE, &format!("/v1/jobs/{job_b}"), None).await;
    assert_eq!(cancelled.status, 200, "{}", cancelled.text);
    assert_eq!(cancelled.body["status"], "cancelled");
    app.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_key_past_its_rate_limit_is_answered_429_with_retry_after() {
    let app = TestApp::start().await;
    let admin = app.make_key(None, "admin", "admin").await;
    let made = app
        .send_as(
            &admin,
            Method::POST,
            "/v1/keys",
            Some(json!({"role": "reader", "name": "script", "rate_limit_per_minute": 3})),
        )
        .await;
    assert_eq!(made.body["rate_limit_per_minute"], 3);
    let script = made.body["key"].as_str().unwrap();
    for _ in 0..3 {
        assert_eq!(app.send_as(script, Method::GET, "/v1/materials", None).await.status, 200);
    }
    let refused = app.send_as(script, Method::GET, "/v1/materials", None).await;
    assert_problem(&refused, 429, None);
    let retry: u64 = refused.header("retry-after").expect("Retry-After").parse().unwrap();
    assert!((1..=20).contains(&retry), "{retry}");
    assert_eq!(app.send_as(&admin, Method::GET, "/v1/materials", None).await.status, 200, "other keys go on");
    let bad = app
        .send_as(
            &admin,
            Method::POST,
            "/v1/keys",
            Some(json!({"role": "reader", "name": " ", "rate_limit_per_minute": -1})),
        )
        .await;
    assert_problem(&bad, 422, Some("rate_limit_per_minute"));
    assert_problem(&bad, 422, Some("name"));
    app.stop().await;
}

const ENV_KEY: &str = "0123456789abcdef0123456789abcdef-first";
const ENV_KEY_2: &str = "fedcba9876543210fedcba9876543210-second";

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn the_environments_admin_key_is_set_up_at_start_and_replaced_when_it_changes() {
    let secret = |s: &str| Some(dieplan::service::config::Secret(s.to_string()));
    let app = TestApp::start_with(|c| c.admin_key = secret(ENV_KEY)).await;
    assert_problem(&app.get("/v1/tools").await, 401, None);
    let keys = app.send_as(ENV_KEY, Method::GET, "/v1/keys", None).await;
    assert_eq!(keys.status, 200, "{}", keys.text);
    assert_eq!(keys.body[0]["origin"], "environment");
    let id = keys.body[0]["id"].as_i64().unwrap();
    assert_problem(&app.send_as(ENV_KEY, Method::DELETE, &format!("/v1/keys/{id}"), None).await, 409, None);

    let app = app.restart_with(|c| c.admin_key = secret(ENV_KEY_2)).await;
    assert_problem(&app.send_as(ENV_KEY, Method::GET, "/v1/tools", None).await, 401, None);
    assert_eq!(app.send_as(ENV_KEY_2, Method::GET, "/v1/tools", None).await.status, 200);
    let dir = app.stop().await;

    let mut short = dieplan::service::config::Config::with_database(dir.path().join("dieplan.sqlite"));
    short.admin_key = secret("too-short");
    let refused = dieplan::service::app::start(short).await.err().expect("a short key is refused");
    assert!(refused.to_string().contains("at least 32 characters"), "{refused}");
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn the_service_refuses_to_listen_beyond_loopback_without_a_key_unless_told_it_may() {
    let dir = tempfile::tempdir().unwrap();
    let mut config = dieplan::service::config::Config::with_database(dir.path().join("dieplan.sqlite"));
    config.addr = "0.0.0.0:0".parse().unwrap();
    config.workers = Some(0);
    let refused = dieplan::service::app::start(config.clone()).await.err().expect("refused");
    assert!(refused.to_string().contains("--insecure-no-auth"), "{refused}");

    config.insecure_no_auth = true;
    dieplan::service::app::start(config.clone()).await.expect("starts when told").stop().await;
    config.insecure_no_auth = false;
    config.admin_key = Some(dieplan::service::config::Secret(ENV_KEY.to_string()));
    dieplan::service::app::start(config).await.expect("starts with a key").stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn the_keys_command_makes_a_key_the_service_accepts() {
    let app = TestApp::start_with(|c| c.workers = Some(0)).await;
    let database = app.database_arg().await;
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_dieplan"))
        .args(["keys", "create", "--role", "planner", "--name", "CAM 3", "--database", &database])
        .output()
        .expect("dieplan runs");
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let key = String::from_utf8(out.stdout).unwrap().trim().to_string();
    assert!(key.starts_with("dpk_"), "{key}");
    assert_problem(&app.get("/v1/materials").await, 401, None);
    assert_eq!(app.send_as(&key, Method::GET, "/v1/materials", None).await.status, 200);
    let list = std::process::Command::new(env!("CARGO_BIN_EXE_dieplan"))
        .args(["keys", "list", "--database", &database])
        .output()
        .unwrap();
    let listed = String::from_utf8(list.stdout).unwrap();
    assert!(listed.contains("planner") && listed.contains("CAM 3") && !listed.contains(&key), "{listed}");
    app.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn allowed_hosts_refuse_a_request_for_another_host_name_but_not_the_probes() {
    let app = TestApp::start_with(|c| c.allowed_hosts = vec!["dieplan.shop.test".into()]).await;
    assert_problem(&app.get("/v1/materials").await, 400, None);
    assert_eq!(app.send(Method::GET, "/v1/materials", None, &[("host", "dieplan.shop.test")]).await.status, 200);
    assert_eq!(app.get("/healthz").await.status, 200);
    assert_eq!(app.get("/readyz").await.status, 200);
    app.stop().await;
}
