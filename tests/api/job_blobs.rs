//! Jobs that scale with their count, not their size: a job's input, result, programs and
//! scene are stored apart from its row; reads and lists come from the row, the input has
//! its own route, and a purge removes everything.

use crate::common::{assert_problem, database_before, TestApp};
use dieplan::service::store::Pool;
use reqwest::Method;
use serde_json::{json, Value};

fn conditions() -> Value {
    json!({"tool_type": "square", "diameter_mm": 10, "operation": "rough_side_cutting"})
}

/// A feeds job on a short program: it leaves a program and a scene.
fn feeds() -> Value {
    json!({"program": {"gcode": "G21 G90\nG0 X-6 Y10 Z5\nG1 Z-5 F500\nG1 X50 F2000\nM30\n"},
           "tool_type": "square", "diameter_mm": 10,
           "stock": {"box": {"x_min": 0, "y_min": 0, "z_min": -5, "x_max": 40, "y_max": 20, "z_max": 0}}})
}

async fn count(pool: &Pool, sql: &str, id: &str) -> i64 {
    sqlx::query_scalar(sqlx::AssertSqlSafe(sql.to_string())).bind(id).fetch_one(pool).await.unwrap()
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_job_is_read_with_its_result_but_without_its_input_which_has_its_own_route() {
    let app = TestApp::start().await;
    let a = app.post_wait("/v1/conditions", conditions()).await;
    assert_eq!(a.status, 201, "{}", a.text);
    assert!(a.body.get("input").is_none(), "{}", a.text);
    let id = a.body["id"].as_str().unwrap();
    let job = app.get(&format!("/v1/jobs/{id}")).await;
    assert_eq!(job.status, 200);
    assert!(job.content_type().starts_with("application/json"), "{}", job.content_type());
    assert!(job.body.get("input").is_none(), "{}", job.text);
    assert_eq!(job.body["result"]["operation"], "rough_side_cutting", "{}", job.text);
    assert_eq!(job.body["result"], a.body["result"]);
    assert_eq!(job.body["links"]["input"], format!("/v1/jobs/{id}/input"));
    let input = app.get(&format!("/v1/jobs/{id}/input")).await;
    assert_eq!(input.status, 200, "{}", input.text);
    assert!(input.content_type().starts_with("application/json"), "{}", input.content_type());
    assert_eq!(input.body, conditions());
    assert_eq!(job.body["input_bytes"].as_u64(), Some(input.text.len() as u64));
    assert!(job.body["result_bytes"].as_u64().is_some_and(|n| n > 100), "{}", job.text);
    assert_problem(&app.get("/v1/jobs/00000000-0000-4000-8000-000000000000/input").await, 404, None);
    app.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_queued_job_is_read_without_a_result_and_its_input_is_there_at_once() {
    let app = TestApp::start_with(|c| c.workers = Some(0)).await;
    let a = app.post("/v1/jobs", json!({"kind": "conditions", "input": conditions()})).await;
    assert_eq!(a.status, 202, "{}", a.text);
    assert!(a.body.get("result").is_none() && a.body.get("input").is_none(), "{}", a.text);
    let input = app.get(a.body["links"]["input"].as_str().unwrap()).await;
    assert_eq!(input.body, conditions());
    app.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_planner_reads_the_input_of_its_own_jobs_only() {
    let app = TestApp::start_with(|c| c.workers = Some(0)).await;
    let admin = app.make_key(None, "admin", "admin").await;
    let alice = app.make_key(Some(&admin), "planner", "station A").await;
    let bob = app.make_key(Some(&admin), "planner", "station B").await;
    let a = app.send_as(&alice, Method::POST, "/v1/conditions", Some(conditions())).await;
    let input = format!("/v1/jobs/{}/input", a.body["id"].as_str().unwrap());
    assert_eq!(app.send_as(&alice, Method::GET, &input, None).await.body, conditions());
    assert_problem(&app.send_as(&bob, Method::GET, &input, None).await, 404, None);
    assert_eq!(app.send_as(&admin, Method::GET, &input, None).await.status, 200);
    assert_problem(&app.get(&input).await, 401, None);
    app.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn the_list_of_many_jobs_comes_from_their_rows_and_carries_no_blob() {
    let app = TestApp::start().await;
    let mut ids = Vec::new();
    for _ in 0..12 {
        let a = app.post_wait("/v1/conditions", conditions()).await;
        assert_eq!(a.status, 201, "{}", a.text);
        ids.push(a.body["id"].as_str().unwrap().to_string());
    }
    let feeds = app.post_wait("/v1/feeds", feeds()).await;
    assert_eq!(feeds.body["status"], "succeeded", "{}", feeds.text);
    // Blobs no list may read: were it to parse them, it would fail.
    let pool = app.pool().await;
    sqlx::query("UPDATE job_blobs SET body = 'not JSON'").execute(&pool).await.unwrap();
    pool.close().await;

    let list = app.get("/v1/jobs?limit=50").await;
    assert_eq!(list.status, 200, "{}", list.text);
    assert_eq!(list.body["total"], 13);
    let items = list.body["items"].as_array().unwrap();
    for item in items {
        assert!(item.get("input").is_none() && item.get("result").is_none(), "{item}");
        assert_eq!(item["status"], "succeeded", "{item}");
    }
    // Newest first: the feeds job, with its program, and headline figures of its result.
    assert_eq!(items[0]["kind"], "feeds");
    assert_eq!(items[0]["links"]["program"], format!("/v1/jobs/{}/program", feeds.body["id"].as_str().unwrap()));
    assert!(items[0]["summary"].is_object(), "{}", items[0]);
    let conditions = &items[1];
    assert_eq!(conditions["summary"]["operation"], "rough_side_cutting", "{conditions}");
    assert_eq!(conditions["summary"]["material.name"], "SKD61", "{conditions}");
    assert!(conditions["links"].get("program").is_none(), "{conditions}");
    app.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_purge_removes_the_jobs_blobs_programs_and_scene() {
    let app = TestApp::start().await;
    let a = app.post_wait("/v1/feeds", feeds()).await;
    assert_eq!(a.body["status"], "succeeded", "{}", a.text);
    let id = a.body["id"].as_str().unwrap().to_string();
    let pool = app.pool().await;
    let tables = [
        "SELECT COUNT(*) FROM job_blobs WHERE job_id = $1",
        "SELECT COUNT(*) FROM job_programs WHERE job_id = $1",
        "SELECT COUNT(*) FROM job_scenes WHERE job_id = $1",
    ];
    let before: Vec<i64> = futures_counts(&pool, &tables, &id).await;
    assert_eq!(before, vec![3, 1, 1], "input, prepared and result; the program; the scene");
    assert_eq!(app.delete(&format!("/v1/jobs/{id}?purge=true")).await.status, 204);
    assert_eq!(futures_counts(&pool, &tables, &id).await, vec![0, 0, 0]);
    pool.close().await;
    app.stop().await;
}

async fn futures_counts(pool: &Pool, tables: &[&str], id: &str) -> Vec<i64> {
    let mut counts = Vec::new();
    for sql in tables {
        counts.push(count(pool, sql, id).await);
    }
    counts
}

/// The last migration before jobs kept their blobs apart.
const BEFORE_JOB_BLOBS: i64 = 12;

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn jobs_stored_before_the_blobs_moved_out_are_read_as_before() {
    let (dir, path, pool) = database_before(BEFORE_JOB_BLOBS).await;
    let error = json!({"type": "about:blank", "title": "Unprocessable Content", "status": 422, "detail": "no"});
    for sql in [
        "INSERT INTO jobs (id, kind, status, input, prepared, result, program, finished_at) VALUES ('0a0a0a0a-0000-4000-8000-00000000fee0', 'feeds', 'succeeded', '{\"tool_type\":\"square\"}', '{}', '{\"summary\":{\"lines\":3}}', 'G0 X0', '2026-01-01T00:00:00Z')",
        "INSERT INTO jobs (id, kind, status, input, prepared, finished_at) VALUES ('0a0a0a0a-0000-4000-8000-0000000000fa', 'plan', 'failed', '{\"z_top\":0}', '{}', '2026-01-02T00:00:00Z')",
    ] {
        sqlx::query(sqlx::AssertSqlSafe(sql)).execute(&pool).await.unwrap();
    }
    sqlx::query("UPDATE jobs SET error = ? WHERE id = '0a0a0a0a-0000-4000-8000-0000000000fa'")
        .bind(error.to_string())
        .execute(&pool)
        .await
        .unwrap();
    pool.close().await;

    // Kept whatever their age (their finish dates are fixed).
    let app = TestApp::start_in(dir, |c| {
        c.database = path.into();
        c.job_retention_days = 0;
    })
    .await;
    let feeds = app.get("/v1/jobs/0a0a0a0a-0000-4000-8000-00000000fee0").await;
    assert_eq!(feeds.body["result"], json!({"summary": {"lines": 3}}), "{}", feeds.text);
    assert_eq!(feeds.body["input_bytes"], 22, "{}", feeds.text);
    assert_eq!(
        app.get("/v1/jobs/0a0a0a0a-0000-4000-8000-00000000fee0/input").await.body,
        json!({"tool_type": "square"})
    );
    assert_eq!(app.get("/v1/jobs/0a0a0a0a-0000-4000-8000-00000000fee0/program").await.text, "G0 X0");
    let failed = app.get("/v1/jobs/0a0a0a0a-0000-4000-8000-0000000000fa").await;
    assert_eq!(failed.body["error"]["detail"], "no", "{}", failed.text);
    let list = app.get("/v1/jobs").await;
    assert_eq!(list.body["total"], 2, "{}", list.text);
    assert_eq!(list.body["items"][0]["error_title"], "Unprocessable Content", "{}", list.text);
    assert_eq!(
        list.body["items"][1]["links"]["program"], "/v1/jobs/0a0a0a0a-0000-4000-8000-00000000fee0/program",
        "{}",
        list.text
    );
    // Its headline figures, which the migration could not compute, are filled in after start.
    let mut summary = Value::Null;
    for _ in 0..100 {
        summary = app.get("/v1/jobs?status=succeeded").await.body["items"][0]["summary"].clone();
        if !summary.is_null() {
            break;
        }
        tokio::time::sleep(std::time::Duration::from_millis(50)).await;
    }
    assert_eq!(summary, json!({"summary.lines": 3}));
    app.stop().await;
}
