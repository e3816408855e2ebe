//! Running jobs and their leases: several replicas share one database, and a job a worker
//! runs belongs to its replica only while the replica's lease on it lasts.
//!
//! - A claim takes the oldest queued job of the fair queue ([`super::lane`]) and gives it
//!   a lease (PostgreSQL: `SELECT … FOR UPDATE SKIP LOCKED`, so that replicas claiming at
//!   once take different jobs without waiting for each other; SQLite has one writer).
//! - The replica renews the leases of its running jobs (its heartbeat, [`renew`]).
//! - A job whose lease has expired (its replica died) is queued again by any replica
//!   ([`requeue_expired`]), its attempt counted, and the next claim takes it.
//! - Every write of a running job (progress, outcome, requeue) names its lease owner, so a
//!   replica that lost the lease (paused past it) stores nothing: a result is stored once.

use super::model::ProgramPart;
use crate::service::error::Problem;
use crate::service::store::{Backend, Pool};
use std::time::Duration;

/// A replica's identity on the jobs it claims, and how long its leases last.
#[derive(Debug, Clone)]
pub struct Lease {
    /// A random id per process.
    pub owner: String,
    /// How long a claim or a renewal holds the job.
    pub duration: Duration,
}

impl Lease {
    /// A new replica identity with leases of `duration`.
    pub fn new(duration: Duration) -> Lease {
        Lease { owner: uuid::Uuid::new_v4().simple().to_string(), duration }
    }

    /// The strftime modifier that puts the lease's end at now + its duration.
    fn modifier(&self) -> String {
        format!("+{:.3} seconds", self.duration.as_secs_f64())
    }
}

/// A job a worker has claimed: what it needs to know before it reads the job's blobs.
#[derive(Debug, Clone, sqlx::FromRow)]
pub struct Claimed {
    pub id: String,
    pub kind: String,
    /// Times a worker has started it, this time included.
    pub attempts: i64,
    /// A cancellation asked for before an interruption.
    #[sqlx(try_from = "crate::service::store::Flag")]
    pub cancel_requested: bool,
}

/// Takes the oldest queued job of the interactive lane, else (unless `interactive_only`)
/// the oldest of the batch lane, marks it running under `lease`, and returns its id, kind
/// and counters, never its blobs.
pub async fn claim_next(pool: &Pool, lease: &Lease, interactive_only: bool) -> Result<Option<Claimed>, sqlx::Error> {
    let lock = match Backend::of(pool) {
        Backend::Postgres => " FOR UPDATE SKIP LOCKED",
        Backend::Sqlite => "",
    };
    let sql = format!(
        "UPDATE jobs SET status = 'running', started_at = strftime('%Y-%m-%dT%H:%M:%fZ', 'now'),
             updated_at = strftime('%Y-%m-%dT%H:%M:%fZ', 'now'), attempts = attempts + 1, progress = 0,
             lease_owner = $2, lease_until = strftime('%Y-%m-%dT%H:%M:%fZ', 'now', $3)
         WHERE id = (SELECT id FROM jobs WHERE status = 'queued' AND (lane = 'interactive' OR $1 = 0)
                     ORDER BY lane = 'batch', created_at, rowid LIMIT 1{lock}) AND status = 'queued'
         RETURNING id, kind, attempts, cancel_requested"
    );
    sqlx::query_as::<_, Claimed>(sqlx::AssertSqlSafe(sql))
        .bind(i64::from(interactive_only))
        .bind(&lease.owner)
        .bind(lease.modifier())
        .fetch_optional(pool)
        .await
}

/// At start, on SQLite (one process owns the file): jobs left running whose cancellation
/// was asked for are cancelled, the others are queued again at once, their attempt
/// counted. On PostgreSQL other replicas may be running them: only jobs whose lease has
/// expired are recovered ([`requeue_expired`]). Returns how many were re-queued.
pub async fn recover_interrupted(pool: &Pool) -> Result<u64, sqlx::Error> {
    if Backend::of(pool) == Backend::Postgres {
        return requeue_expired(pool).await;
    }
    sqlx::query("UPDATE jobs SET status = 'cancelled', finished_at = strftime('%Y-%m-%dT%H:%M:%fZ', 'now'), updated_at = strftime('%Y-%m-%dT%H:%M:%fZ', 'now'), lease_owner = NULL, lease_until = NULL
         WHERE status = 'running' AND cancel_requested = 1")
    .execute(pool)
    .await?;
    let requeued = sqlx::query("UPDATE jobs SET status = 'queued', progress = 0, updated_at = strftime('%Y-%m-%dT%H:%M:%fZ', 'now'), lease_owner = NULL, lease_until = NULL WHERE status = 'running'")
    .execute(pool)
    .await?;
    Ok(requeued.rows_affected())
}

/// Queues again the running jobs whose lease has expired (their replica died or lost the
/// database), or cancels them when that was asked for. The interrupted attempt counts, as
/// a crash does. Returns how many were re-queued.
pub async fn requeue_expired(pool: &Pool) -> Result<u64, sqlx::Error> {
    const EXPIRED: &str =
        "status = 'running' AND (lease_until IS NULL OR lease_until < strftime('%Y-%m-%dT%H:%M:%fZ', 'now'))";
    sqlx::query(sqlx::AssertSqlSafe(format!(
        "UPDATE jobs SET status = 'cancelled', finished_at = strftime('%Y-%m-%dT%H:%M:%fZ', 'now'), updated_at = strftime('%Y-%m-%dT%H:%M:%fZ', 'now'), lease_owner = NULL, lease_until = NULL
         WHERE {EXPIRED} AND cancel_requested = 1"
    )))
    .execute(pool)
    .await?;
    let requeued = sqlx::query(sqlx::AssertSqlSafe(format!(
        "UPDATE jobs SET status = 'queued', progress = 0, updated_at = strftime('%Y-%m-%dT%H:%M:%fZ', 'now'), lease_owner = NULL, lease_until = NULL
         WHERE {EXPIRED}"
    )))
    .execute(pool)
    .await?;
    Ok(requeued.rows_affected())
}

/// Renews the leases of every job `lease`'s replica runs (its heartbeat).
pub async fn renew(pool: &Pool, lease: &Lease) -> Result<u64, sqlx::Error> {
    let done = sqlx::query(
        "UPDATE jobs SET lease_until = strftime('%Y-%m-%dT%H:%M:%fZ', 'now', $2)
         WHERE lease_owner = $1 AND status = 'running'",
    )
    .bind(&lease.owner)
    .bind(lease.modifier())
    .execute(pool)
    .await?;
    Ok(done.rows_affected())
}

/// The jobs `lease`'s replica runs whose cancellation a client asked for (on any replica).
pub async fn cancels_requested(pool: &Pool, lease: &Lease) -> Result<Vec<String>, sqlx::Error> {
    sqlx::query_scalar("SELECT id FROM jobs WHERE lease_owner = $1 AND status = 'running' AND cancel_requested = 1")
        .bind(&lease.owner)
        .fetch_all(pool)
        .await
}

/// Records progress of a running job.
pub async fn set_progress(pool: &Pool, lease: &Lease, id: &str, progress: f64) -> Result<(), sqlx::Error> {
    sqlx::query("UPDATE jobs SET progress = $1, updated_at = strftime('%Y-%m-%dT%H:%M:%fZ', 'now') WHERE id = $2 AND status = 'running' AND lease_owner = $3")
        .bind(progress)
        .bind(id)
        .bind(&lease.owner)
        .execute(pool)
        .await?;
    Ok(())
}

/// What a succeeded job leaves: its result (JSON text) and headline figures, its NC
/// programs and its drawing scene.
pub struct Outcome<'a> {
    pub result: &'a str,
    pub summary: Option<&'a str>,
    pub programs: Vec<(ProgramPart, &'a str)>,
    pub scene: Option<&'a str>,
    /// The stock its simulation left, kept for a job to start from.
    pub stock: Option<&'a super::kept_stock::EncodedStock>,
}

/// Marks a running job succeeded with its outcome, in one transaction, if `lease` still
/// holds it; returns `false` (and stores nothing) when another replica has taken it.
pub async fn succeed(pool: &Pool, lease: &Lease, id: &str, outcome: &Outcome<'_>) -> Result<bool, sqlx::Error> {
    let mut tx = crate::service::store::begin(pool).await?;
    let done = sqlx::query("UPDATE jobs SET status = 'succeeded', progress = 1, result_bytes = $1, summary = $2, finished_at = strftime('%Y-%m-%dT%H:%M:%fZ', 'now'), updated_at = strftime('%Y-%m-%dT%H:%M:%fZ', 'now'), lease_owner = NULL, lease_until = NULL
         WHERE id = $3 AND status = 'running' AND lease_owner = $4")
    .bind(i64::try_from(outcome.result.len()).unwrap_or(i64::MAX))
    .bind(outcome.summary)
    .bind(id)
    .bind(&lease.owner)
    .execute(&mut *tx)
    .await?;
    if done.rows_affected() != 1 {
        tx.rollback().await?;
        return Ok(false);
    }
    sqlx::query(
        "INSERT INTO job_blobs (job_id, part, body) VALUES ($1, 'result', $2)
         ON CONFLICT (job_id, part) DO UPDATE SET body = excluded.body",
    )
    .bind(id)
    .bind(outcome.result.as_bytes())
    .execute(&mut *tx)
    .await?;
    for (part, text) in &outcome.programs {
        sqlx::query(
            "INSERT INTO job_programs (job_id, part, program) VALUES ($1, $2, $3)
             ON CONFLICT (job_id, part) DO UPDATE SET program = excluded.program",
        )
        .bind(id)
        .bind(part.as_str())
        .bind(text.as_bytes())
        .execute(&mut *tx)
        .await?;
    }
    if let Some(scene) = outcome.scene {
        sqlx::query(
            "INSERT INTO job_scenes (job_id, scene) VALUES ($1, $2)
             ON CONFLICT (job_id) DO UPDATE SET scene = excluded.scene",
        )
        .bind(id)
        .bind(scene.as_bytes())
        .execute(&mut *tx)
        .await?;
    }
    if let Some(stock) = outcome.stock {
        super::kept_stock::store(&mut tx, id, stock).await?;
    }
    tx.commit().await?;
    Ok(true)
}

/// Marks a running job failed with a problem document, if `lease` still holds it.
pub async fn fail(pool: &Pool, lease: &Lease, id: &str, problem: &Problem) -> Result<bool, sqlx::Error> {
    let text = serde_json::to_string(problem).unwrap_or_default();
    let done = sqlx::query("UPDATE jobs SET status = 'failed', error = $1, error_title = $2, finished_at = strftime('%Y-%m-%dT%H:%M:%fZ', 'now'), updated_at = strftime('%Y-%m-%dT%H:%M:%fZ', 'now'), lease_owner = NULL, lease_until = NULL
         WHERE id = $3 AND status = 'running' AND lease_owner = $4")
    .bind(text)
    .bind(&problem.title)
    .bind(id)
    .bind(&lease.owner)
    .execute(pool)
    .await?;
    Ok(done.rows_affected() == 1)
}

/// Marks a running job cancelled, if `lease` still holds it.
pub async fn cancelled(pool: &Pool, lease: &Lease, id: &str) -> Result<bool, sqlx::Error> {
    let done = sqlx::query("UPDATE jobs SET status = 'cancelled', finished_at = strftime('%Y-%m-%dT%H:%M:%fZ', 'now'), updated_at = strftime('%Y-%m-%dT%H:%M:%fZ', 'now'), lease_owner = NULL, lease_until = NULL
         WHERE id = $1 AND status = 'running' AND lease_owner = $2")
    .bind(id)
    .bind(&lease.owner)
    .execute(pool)
    .await?;
    Ok(done.rows_affected() == 1)
}

/// Puts running jobs of `lease`'s replica back in the queue at a graceful shutdown,
/// without counting the attempt it interrupted: only a crash (a lease that expired, or on
/// SQLite a job found running at start) counts.
pub async fn requeue(pool: &Pool, lease: &Lease, ids: &[String]) -> Result<(), sqlx::Error> {
    for id in ids {
        sqlx::query("UPDATE jobs SET status = 'queued', progress = 0, attempts = CASE WHEN attempts > 0 THEN attempts - 1 ELSE 0 END, updated_at = strftime('%Y-%m-%dT%H:%M:%fZ', 'now'), lease_owner = NULL, lease_until = NULL
             WHERE id = $1 AND status = 'running' AND lease_owner = $2")
        .bind(id)
        .bind(&lease.owner)
        .execute(pool)
        .await?;
    }
    Ok(())
}
