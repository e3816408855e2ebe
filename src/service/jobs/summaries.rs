//! Headline figures of jobs that succeeded before they were kept in the row (migration
//! 0013 moved results out of `jobs` but could not compute their `summary` in SQL): filled
//! in once, in the background after start, one job at a time, each result parsed off the
//! async runtime. Until a job's turn comes, lists show it without a summary.

use super::kinds::off_runtime;
use super::model::headline;
use super::store;
use crate::service::error::ApiError;
use crate::service::store::Pool;
use tokio::task::JoinHandle;

/// Fills the summaries of succeeded jobs that lack one, in the background.
pub fn start(pool: Pool) -> JoinHandle<()> {
    tokio::spawn(async move {
        match backfill(&pool).await {
            Ok(0) => {}
            Ok(filled) => tracing::info!(filled, "headline figures computed for jobs stored before they were kept"),
            Err(e) => tracing::error!(error = %e, "could not compute the headline figures of older jobs"),
        }
    })
}

/// Computes and stores the summary of every succeeded job without one; returns how many.
pub async fn backfill(pool: &Pool) -> Result<u64, ApiError> {
    let ids: Vec<String> =
        sqlx::query_scalar("SELECT id FROM jobs WHERE status = 'succeeded' AND summary IS NULL ORDER BY rowid")
            .fetch_all(pool)
            .await?;
    let mut filled = 0;
    for id in ids {
        let Some(result) = store::result(pool, &id).await? else {
            continue;
        };
        let summary = off_runtime(move || {
            let value: serde_json::Value = serde_json::from_str(&result)
                .map_err(|e| ApiError::Internal(format!("stored result unreadable: {e}")))?;
            Ok(headline(&value).to_string())
        })
        .await;
        match summary {
            Ok(summary) => {
                filled += sqlx::query("UPDATE jobs SET summary = $1 WHERE id = $2 AND summary IS NULL")
                    .bind(summary)
                    .bind(&id)
                    .execute(pool)
                    .await?
                    .rows_affected();
            }
            Err(e) => tracing::warn!(job = %id, error = %e, "no headline figures for this job"),
        }
    }
    Ok(filled)
}
