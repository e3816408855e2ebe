//! Retention: finished jobs older than `--job-retention-days` are removed with their
//! results, programs and scenes, and the file gives the freed pages back to the disk
//! (SQLite's incremental vacuum, then a WAL checkpoint that truncates the log).

use crate::service::jobs::store as jobs;
use crate::service::store::Pool;
use std::sync::OnceLock;
use std::time::Duration;
use tokio::task::JoinHandle;

/// How often old jobs are looked for.
const RETENTION_INTERVAL: Duration = Duration::from_secs(3600);

/// Removes the finished jobs older than `days` now and every [`RETENTION_INTERVAL`];
/// `days = 0` keeps every job (no task).
pub fn start(pool: Pool, days: u64) -> Option<JoinHandle<()>> {
    (days > 0).then(|| {
        tokio::spawn(async move {
            let mut tick = tokio::time::interval(RETENTION_INTERVAL);
            loop {
                tick.tick().await;
                match jobs::purge_finished_before(&pool, days).await {
                    Ok(0) => {}
                    Ok(purged) => {
                        tracing::info!(purged, days, "removed finished jobs past their retention");
                        vacuum(&pool).await;
                    }
                    Err(e) => tracing::error!(error = %e, "could not remove old jobs"),
                }
            }
        })
    })
}

/// Gives the pages freed by a purge back to the disk, in the background.
pub fn vacuum_later(pool: &Pool) {
    let pool = pool.clone();
    tokio::spawn(async move { vacuum(&pool).await });
}

/// Gives free pages back to the disk: `PRAGMA incremental_vacuum`, then a checkpoint that
/// moves the log into the file and truncates both. One at a time.
pub async fn vacuum(pool: &Pool) {
    if crate::service::store::Backend::of(pool) != crate::service::store::Backend::Sqlite {
        return; // PostgreSQL's autovacuum frees the space of deleted rows by itself.
    }
    static ONE_AT_A_TIME: OnceLock<tokio::sync::Mutex<()>> = OnceLock::new();
    let _turn = ONE_AT_A_TIME.get_or_init(Default::default).lock().await;
    let result = async {
        let mut conn = pool.acquire().await?;
        sqlx::query("PRAGMA incremental_vacuum").execute(&mut *conn).await?;
        sqlx::query("PRAGMA wal_checkpoint(TRUNCATE)").execute(&mut *conn).await?;
        Ok::<_, sqlx::Error>(())
    }
    .await;
    if let Err(e) = result {
        tracing::warn!(error = %e, "could not give freed pages back to the disk; the next purge will");
    }
}
