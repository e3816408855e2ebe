//! Running one claimed job: its input read, the core run on a blocking thread under the
//! job's [`JobControl`] with its progress written as it goes, and its outcome (result,
//! programs, scene, or the problem that stopped it) recorded under the replica's lease.

use super::control::{JobControl, StopReason};
use super::kinds;
use super::lease::{self as store, Lease};
use super::model::{JobKind, ProgramPart};
use crate::core::CoreError;
use crate::service::error::ApiError;
use crate::service::store::Pool;
use std::sync::Arc;
use std::time::Duration;

/// How often a running job's progress is written to the table.
const PROGRESS_FLUSH: Duration = Duration::from_millis(250);
/// A job started this many times without finishing is failed instead of run again
/// (it may be what brought the service down).
pub const MAX_ATTEMPTS: i64 = 3;
/// Largest result, program or scene one job stores, bytes: SQLite refuses a text of 1 GB
/// (its default `SQLITE_MAX_LENGTH`), and no client could use one this large.
pub const MAX_STORED_BYTES: usize = 256 * 1024 * 1024;

/// The problem of a job whose output has a part (name, bytes) larger than
/// [`MAX_STORED_BYTES`], if any.
fn oversized(parts: &[(&str, usize)]) -> Option<crate::service::error::Problem> {
    let &(name, bytes) = parts.iter().find(|(_, bytes)| *bytes > MAX_STORED_BYTES)?;
    const MB: f64 = 1024.0 * 1024.0;
    let detail = format!(
        "the job finished, but its {name} ({:.0} MB) is larger than the {:.0} MB a job may store: ask for less (fewer layers or candidates, a shorter program, a coarser sampling)",
        bytes as f64 / MB,
        MAX_STORED_BYTES as f64 / MB
    );
    Some(ApiError::Status { status: axum::http::StatusCode::PAYLOAD_TOO_LARGE, detail }.problem())
}

/// The problem of a job stopped after running for `limit`, `progress` of the way.
fn timed_out(limit: Duration, progress: f64) -> crate::service::error::Problem {
    let detail = format!(
        "the job was stopped after running for {} s, the longest a job may run here (DIEPLAN_JOB_TIME_LIMIT), {:.0} % of the way: ask for less (a coarser sampling, fewer layers or candidates, a shorter program) or ask the operator for a longer limit",
        limit.as_secs(),
        progress * 100.0
    );
    ApiError::Status { status: axum::http::StatusCode::PAYLOAD_TOO_LARGE, detail }.problem()
}

/// A job's output, serialized on the blocking thread that computed it: the result as
/// JSON text with its headline figures, the programs and the scene.
struct Serialized {
    result: String,
    summary: String,
    program: Option<String>,
    baseline: Option<String>,
    base: Option<String>,
    scene: Option<String>,
    stock: Option<super::kept_stock::EncodedStock>,
}

/// Runs a claimed job under `control`, each of its stock simulations within
/// `stock_memory_bytes`, and records its outcome; `Ok(false)` when the
/// outcome was not recorded because this replica no longer holds the job's lease (another
/// replica runs it), or the job went back to the queue.
pub async fn execute(
    pool: &Pool,
    lease: &Lease,
    row: &store::Claimed,
    control: Arc<JobControl>,
    stock_memory_bytes: usize,
) -> Result<bool, sqlx::Error> {
    let id = row.id.as_str();
    if row.attempts > MAX_ATTEMPTS {
        let problem = ApiError::Internal(String::new()).problem();
        let problem = crate::service::error::Problem {
            detail: format!(
                "the job was interrupted {} times without finishing and is not run again",
                row.attempts - 1
            ),
            ..problem
        };
        return store::fail(pool, lease, id, &problem).await;
    }
    let kind = match JobKind::parse(&row.kind) {
        Some(kind) => kind,
        None => {
            let problem = ApiError::Internal(format!("unknown job kind {}", row.kind)).problem();
            return store::fail(pool, lease, id, &problem).await;
        }
    };
    let Some((input, prepared)) = super::store::work(pool, id).await? else {
        let problem = ApiError::Internal(format!("job {id} has no stored input")).problem();
        return store::fail(pool, lease, id, &problem).await;
    };
    let worker_control = control.clone();
    let mut task = tokio::task::spawn_blocking(move || {
        let kinds::JobOutput { result: value, program, baseline_program: baseline, base_program: base, scene, stock } =
            kinds::run(kind, &input, &prepared, worker_control.as_ref(), stock_memory_bytes)?;
        let result = serde_json::to_string(&value).unwrap_or_default();
        let summary = super::model::headline(&value).to_string();
        Ok::<_, CoreError>(Serialized { result, summary, program, baseline, base, scene, stock })
    });
    let mut tick = tokio::time::interval(PROGRESS_FLUSH);
    let mut last = 0.0;
    let joined = loop {
        tokio::select! {
            joined = &mut task => break joined,
            _ = tick.tick() => {
                let p = control.progress();
                if (p - last).abs() > f64::EPSILON {
                    // Progress is told on a best-effort basis: a store that cannot take it now
                    // (a lock, a dropped connection) must not abandon a computation that runs
                    // on, uncancellable and uncounted; it is told again at the next tick.
                    match store::set_progress(pool, lease, id, p).await {
                        Ok(()) => last = p,
                        Err(e) => tracing::warn!(job = %id, error = %e, "could not store the job's progress"),
                    }
                }
            }
        }
    };

    match joined {
        Ok(Ok(done)) => {
            let Serialized { result, summary, .. } = &done;
            let (program, baseline, scene) = (done.program.as_deref(), done.baseline.as_deref(), done.scene.as_deref());
            let base = done.base.as_deref();
            let sizes = [
                ("result", result.len()),
                ("program", program.map_or(0, str::len)),
                ("baseline program", baseline.map_or(0, str::len)),
                ("base program", base.map_or(0, str::len)),
                ("scene", scene.map_or(0, str::len)),
                ("kept stock", done.stock.as_ref().map_or(0, |s| s.body.len())),
            ];
            if let Some(problem) = oversized(&sizes) {
                return store::fail(pool, lease, id, &problem).await;
            }
            let programs = [(ProgramPart::Main, program), (ProgramPart::Baseline, baseline), (ProgramPart::Base, base)]
                .into_iter()
                .filter_map(|(part, text)| Some((part, text?)))
                .collect();
            let outcome =
                store::Outcome { result, summary: Some(summary), programs, scene, stock: done.stock.as_ref() };
            match store::succeed(pool, lease, id, &outcome).await {
                Ok(true) => Ok(true),
                Ok(false) => {
                    tracing::warn!(job = %id, "the job's lease had expired and another replica took it: its result is dropped here");
                    Ok(false)
                }
                Err(e) => {
                    // The job must not stay `running` with its outcome lost.
                    tracing::error!(job = %id, error = %e, "could not store the result of a job");
                    store::fail(pool, lease, id, &ApiError::Internal(e.to_string()).problem()).await
                }
            }
        }
        Ok(Err(CoreError::Cancelled)) => match control.stop_reason() {
            StopReason::Cancelled => store::cancelled(pool, lease, id).await,
            StopReason::Shutdown => {
                tracing::info!(job = %id, "job interrupted by shutdown; it resumes at the next start");
                store::requeue(pool, lease, &[id.to_string()]).await.map(|()| false)
            }
            StopReason::TimedOut => {
                let limit = control.time_limit().unwrap_or_default();
                tracing::warn!(job = %id, limit_s = limit.as_secs_f64(), "job stopped at its time limit");
                store::fail(pool, lease, id, &timed_out(limit, control.progress())).await
            }
        },
        Ok(Err(err)) => store::fail(pool, lease, id, &ApiError::from(err).problem()).await,
        Err(join_error) => {
            tracing::error!(job = %id, error = %join_error, "job panicked");
            store::fail(pool, lease, id, &ApiError::Internal(join_error.to_string()).problem()).await
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_output_part_too_large_to_store_fails_the_job_naming_the_part_and_its_size() {
        assert!(oversized(&[("result", MAX_STORED_BYTES), ("program", 10)]).is_none());
        let problem = oversized(&[("result", 10), ("program", MAX_STORED_BYTES + 1), ("scene", 0)]).expect("too large");
        assert_eq!(problem.status, 413);
        assert!(problem.detail.contains("its program (256 MB)"), "{}", problem.detail);
    }

    #[test]
    fn the_time_limit_problem_names_the_limit_the_setting_and_the_progress() {
        let problem = timed_out(Duration::from_secs(90), 0.374);
        assert_eq!(problem.status, 413);
        assert!(problem.detail.contains("90 s"), "{}", problem.detail);
        assert!(problem.detail.contains("DIEPLAN_JOB_TIME_LIMIT"), "{}", problem.detail);
        assert!(problem.detail.contains("37 %"), "{}", problem.detail);
    }
}
