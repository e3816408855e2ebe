//! Retention: a finished job can be purged with its data, old finished jobs are purged
//! after `--job-retention-days`, and the database file shrinks afterwards.

use crate::common::{assert_problem, database_pool, TestApp};
use serde_json::json;
use std::time::Duration;

/// A queued analysis of a long program of comments (`lines` of 100 bytes).
fn bulky_job(lines: usize) -> serde_json::Value {
    let gcode = format!("G21 G90\n{}G1 X10 F1000\nM30\n", format!("({})\n", "x".repeat(97)).repeat(lines));
    json!({"program": {"gcode": gcode}, "tool_type": "square", "diameter_mm": 10,
           "stock": {"box": {"x_min": 0, "y_min": 0, "z_min": -5, "x_max": 20, "y_max": 20, "z_max": 0}}})
}

/// Bytes of the database with its write-ahead log.
fn stored_bytes(app: &TestApp) -> u64 {
    let db = app.database();
    let wal = db.with_extension("sqlite-wal");
    [db, wal].iter().map(|p| std::fs::metadata(p).map_or(0, |m| m.len())).sum()
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn purging_a_finished_job_removes_it_and_the_file_shrinks() {
    let app = TestApp::start_with(|c| c.workers = Some(0)).await;
    let id = app.post("/v1/analysis", bulky_job(100_000)).await.body["id"].as_str().unwrap().to_string();
    let path = format!("/v1/jobs/{id}");
    assert_problem(&app.delete(&format!("{path}?purge=true")).await, 409, None);
    assert_eq!(app.delete(&path).await.body["status"], "cancelled");
    let before = stored_bytes(&app);
    assert!(before > 10_000_000, "{before} bytes");

    let purged = app.delete(&format!("{path}?purge=true")).await;
    assert_eq!(purged.status, 204, "{}", purged.text);
    assert_problem(&app.get(&path).await, 404, None);
    let mut after = stored_bytes(&app);
    for _ in 0..100 {
        if after < before / 2 {
            break;
        }
        tokio::time::sleep(Duration::from_millis(100)).await;
        after = stored_bytes(&app);
    }
    assert!(after < before / 2, "{before} bytes before the purge, {after} after");
    assert_problem(&app.delete("/v1/jobs/x?purge=maybe").await, 400, None);
    app.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn finished_jobs_older_than_the_retention_are_purged_and_newer_ones_kept() {
    let app = TestApp::start_with(|c| c.workers = Some(0)).await;
    let conditions = json!({"tool_type": "square", "diameter_mm": 10});
    let old = app.post("/v1/conditions", conditions.clone()).await.body["id"].as_str().unwrap().to_string();
    let recent = app.post("/v1/conditions", conditions.clone()).await.body["id"].as_str().unwrap().to_string();
    let queued = app.post("/v1/conditions", conditions).await.body["id"].as_str().unwrap().to_string();
    app.delete(&format!("/v1/jobs/{old}")).await;
    app.delete(&format!("/v1/jobs/{recent}")).await;
    let dir = app.stop().await;
    let pool = database_pool(&dir).await;
    for (id, days) in [(&old, 31), (&recent, 29), (&queued, 400)] {
        sqlx::query("UPDATE jobs SET finished_at = strftime('%Y-%m-%dT%H:%M:%fZ', 'now', $1), created_at = strftime('%Y-%m-%dT%H:%M:%fZ', 'now', $2) WHERE id = $3")
            .bind(format!("-{days} days"))
            .bind(format!("-{days} days"))
            .bind(id)
            .execute(&pool)
            .await
            .unwrap();
    }
    sqlx::query("UPDATE jobs SET finished_at = NULL WHERE id = $1").bind(&queued).execute(&pool).await.unwrap();
    pool.close().await;

    let app = TestApp::start_in(dir, |c| c.workers = Some(0)).await;
    let mut gone = false;
    for _ in 0..100 {
        gone = app.get(&format!("/v1/jobs/{old}")).await.status == 404;
        if gone {
            break;
        }
        tokio::time::sleep(Duration::from_millis(50)).await;
    }
    assert!(gone, "the job finished 31 days ago is purged");
    assert_eq!(app.get(&format!("/v1/jobs/{recent}")).await.status, 200);
    assert_eq!(app.get(&format!("/v1/jobs/{queued}")).await.body["status"], "queued");
    app.stop().await;
}
