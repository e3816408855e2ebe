//! The `jobs` table and its blobs. A job's row holds what lists and polls show (status,
//! progress, times, sizes, a few headline figures); its input, prepared form and result are
//! in `job_blobs`, its NC programs in `job_programs` and its drawing in `job_scenes`, read
//! only by the routes that serve them, as stored.

use super::labels::{contains_pattern, JobLabels};
use super::lane::Lane;
use super::model::{Job, JobKind, JobLinks, JobStatus, JobSummary, ProgramPart};
use crate::service::auth::Caller;
use crate::service::error::{excerpt, ApiError, Problem};
use crate::service::store::{Pool, Text};

/// The columns of a [`JobRow`]: the row's own, and whether the job left a main program.
const ROW_COLUMNS: &str = "id, kind, status, progress, error, error_title, attempts, cancel_requested, created_at,
    started_at, finished_at, updated_at, key_id, lane, input_bytes, result_bytes, summary, name, tags,
    EXISTS (SELECT 1 FROM job_programs p WHERE p.job_id = jobs.id AND p.part = 'main') AS has_program";

/// A row of `jobs`: everything about a job but its blobs.
#[derive(Debug, Clone, sqlx::FromRow)]
pub struct JobRow {
    pub id: String,
    pub kind: String,
    pub status: String,
    pub progress: f64,
    /// The problem of a failed job (JSON).
    pub error: Option<String>,
    pub error_title: Option<String>,
    pub attempts: i64,
    #[sqlx(try_from = "crate::service::store::Flag")]
    pub cancel_requested: bool,
    pub created_at: String,
    pub started_at: Option<String>,
    pub finished_at: Option<String>,
    pub updated_at: String,
    /// The key that created it (none: made while the service ran open).
    pub key_id: Option<i64>,
    /// The queue lane it waits in (`interactive` or `batch`).
    pub lane: String,
    pub input_bytes: i64,
    pub result_bytes: Option<i64>,
    /// Headline figures of the result (a small JSON object).
    pub summary: Option<String>,
    /// What the user called the job.
    pub name: Option<String>,
    /// Its tags (a JSON array of strings).
    pub tags: String,
    /// The job left a main NC program.
    #[sqlx(try_from = "crate::service::store::Flag")]
    pub has_program: bool,
}

impl JobRow {
    pub fn kind(&self) -> Result<JobKind, ApiError> {
        JobKind::parse(&self.kind)
            .ok_or_else(|| ApiError::Internal(format!("job {} has unknown kind {}", self.id, self.kind)))
    }

    pub fn status(&self) -> Result<JobStatus, ApiError> {
        JobStatus::parse(&self.status)
            .ok_or_else(|| ApiError::Internal(format!("job {} has unknown status {}", self.id, self.status)))
    }

    /// A small JSON column of the row (`what`), read.
    fn stored<T: serde::de::DeserializeOwned>(&self, what: &str, text: Option<&str>) -> Result<Option<T>, ApiError> {
        text.map(serde_json::from_str)
            .transpose()
            .map_err(|e| ApiError::Internal(format!("job {}: stored {what} unreadable: {e}", self.id)))
    }

    fn links(&self) -> Result<JobLinks, ApiError> {
        let drawn = self.status()? == JobStatus::Succeeded && super::drawings::draws(self.kind()?);
        Ok(JobLinks {
            this: format!("/v1/jobs/{}", self.id),
            input: format!("/v1/jobs/{}/input", self.id),
            program: self.has_program.then(|| format!("/v1/jobs/{}/program", self.id)),
            views: drawn.then(|| format!("/v1/jobs/{}/views", self.id)),
            drawing: drawn.then(|| format!("/v1/jobs/{}/drawing.svg", self.id)),
        })
    }

    /// Its tags, read.
    fn tags(&self) -> Result<Vec<String>, ApiError> {
        Ok(self.stored("tags", Some(&self.tags))?.unwrap_or_default())
    }

    /// The job as the API shows it, without its result (which the routes serve as stored:
    /// [`super::routes`]).
    pub fn to_job(&self) -> Result<Job, ApiError> {
        let error: Option<Problem> = self.stored("error", self.error.as_deref())?;
        Ok(Job {
            id: self.id.clone(),
            kind: self.kind()?,
            name: self.name.clone(),
            tags: self.tags()?,
            status: self.status()?,
            progress: self.progress,
            attempts: self.attempts,
            cancel_requested: self.cancel_requested,
            created_at: self.created_at.clone(),
            started_at: self.started_at.clone(),
            finished_at: self.finished_at.clone(),
            updated_at: self.updated_at.clone(),
            key_id: self.key_id,
            input_bytes: self.input_bytes,
            result_bytes: self.result_bytes,
            result: None,
            error,
            links: self.links()?,
        })
    }

    /// The job as lists show it.
    pub fn to_summary(&self) -> Result<JobSummary, ApiError> {
        let summary = self.stored("summary", self.summary.as_deref())?;
        Ok(JobSummary {
            id: self.id.clone(),
            kind: self.kind()?,
            name: self.name.clone(),
            tags: self.tags()?,
            status: self.status()?,
            progress: self.progress,
            created_at: self.created_at.clone(),
            started_at: self.started_at.clone(),
            finished_at: self.finished_at.clone(),
            key_id: self.key_id,
            error_title: self.error_title.clone(),
            summary,
            links: self.links()?,
        })
    }
}

/// A job to insert: what it computes, for whom, in which lane.
pub struct NewJob<'a> {
    pub id: &'a str,
    pub kind: JobKind,
    pub input: &'a str,
    pub prepared: &'a str,
    pub key_id: Option<i64>,
    pub lane: Lane,
    /// Its name and tags.
    pub labels: &'a JobLabels,
}

/// Inserts a queued job with its input and prepared form, in one transaction.
pub async fn insert(pool: &Pool, job: NewJob<'_>) -> Result<(), ApiError> {
    let mut tx = crate::service::store::begin(pool).await?;
    let tags = serde_json::to_string(&job.labels.tags).map_err(|e| ApiError::Internal(format!("tags: {e}")))?;
    sqlx::query(
        "INSERT INTO jobs (id, kind, status, key_id, lane, input_bytes, name, name_key, tags)
         VALUES ($1, $2, 'queued', $3, $4, $5, $6, $7, $8)",
    )
    .bind(job.id)
    .bind(job.kind.as_str())
    .bind(job.key_id)
    .bind(job.lane.as_str())
    .bind(i64::try_from(job.input.len()).unwrap_or(i64::MAX))
    .bind(job.labels.name.as_deref())
    .bind(job.labels.name_key())
    .bind(tags)
    .execute(&mut *tx)
    .await?;
    insert_tags(&mut tx, job.id, &job.labels.tags).await?;
    for (part, body) in [("input", job.input), ("prepared", job.prepared)] {
        sqlx::query("INSERT INTO job_blobs (job_id, part, body) VALUES ($1, $2, $3)")
            .bind(job.id)
            .bind(part)
            .bind(body.as_bytes())
            .execute(&mut *tx)
            .await?;
    }
    tx.commit().await?;
    Ok(())
}

/// Gives a job the name and tags `change` makes of its current ones (its row and its
/// `job_tags`), read and written in one transaction that no other such write interleaves
/// with (two clients changing the name and the tags at once keep both changes).
pub async fn relabel(
    pool: &Pool,
    id: &str,
    change: impl FnOnce(JobLabels) -> Result<JobLabels, ApiError>,
) -> Result<(), ApiError> {
    let mut tx = crate::service::store::begin_exclusive(pool).await?;
    let (name, tags): (Option<String>, String) = sqlx::query_as("SELECT name, tags FROM jobs WHERE id = $1")
        .bind(id)
        .fetch_optional(&mut *tx)
        .await?
        .ok_or_else(|| ApiError::not_found(format!("no job with id {}", excerpt(id))))?;
    let labels = change(JobLabels { name, tags: serde_json::from_str(&tags).unwrap_or_default() })?;
    let tags = serde_json::to_string(&labels.tags).map_err(|e| ApiError::Internal(format!("tags: {e}")))?;
    sqlx::query("UPDATE jobs SET name = $1, name_key = $2, tags = $3 WHERE id = $4")
        .bind(labels.name.as_deref())
        .bind(labels.name_key())
        .bind(tags)
        .bind(id)
        .execute(&mut *tx)
        .await?;
    sqlx::query("DELETE FROM job_tags WHERE job_id = $1").bind(id).execute(&mut *tx).await?;
    insert_tags(&mut tx, id, &labels.tags).await?;
    tx.commit().await?;
    Ok(())
}

/// Adds the rows of `job_tags` of job `id`.
async fn insert_tags(
    tx: &mut crate::service::store::Transaction,
    id: &str,
    tags: &[String],
) -> Result<(), sqlx::Error> {
    for tag in tags {
        sqlx::query("INSERT INTO job_tags (job_id, tag) VALUES ($1, $2)").bind(id).bind(tag).execute(&mut **tx).await?;
    }
    Ok(())
}

/// Reads one job's row, or 404.
pub async fn get(pool: &Pool, id: &str) -> Result<JobRow, ApiError> {
    sqlx::query_as::<_, JobRow>(sqlx::AssertSqlSafe(format!("SELECT {ROW_COLUMNS} FROM jobs WHERE id = $1")))
        .bind(id)
        .fetch_optional(pool)
        .await?
        .ok_or_else(|| ApiError::not_found(format!("no job with id {}", excerpt(id))))
}

/// Reads one job the caller may see, or 404 (a planner is not told that another key's
/// job exists).
pub async fn get_visible(pool: &Pool, caller: &Caller, id: &str) -> Result<JobRow, ApiError> {
    let row = get(pool, id).await?;
    if caller.may_see_job(row.key_id) {
        Ok(row)
    } else {
        Err(ApiError::not_found(format!("no job with id {}", excerpt(id))))
    }
}

/// A blob of a job (`input`, `prepared` or `result`) as stored, if it has one.
async fn blob(pool: &Pool, id: &str, part: &str) -> Result<Option<String>, sqlx::Error> {
    Ok(sqlx::query_scalar::<_, Text>("SELECT body FROM job_blobs WHERE job_id = $1 AND part = $2")
        .bind(id)
        .bind(part)
        .fetch_optional(pool)
        .await?
        .map(String::from))
}

/// The input of a job as submitted (JSON text).
pub async fn input(pool: &Pool, id: &str) -> Result<Option<String>, ApiError> {
    Ok(blob(pool, id, "input").await?)
}

/// The result of a succeeded job (JSON text).
pub async fn result(pool: &Pool, id: &str) -> Result<Option<String>, ApiError> {
    Ok(blob(pool, id, "result").await?)
}

/// What a worker runs a job from: its input as submitted and its prepared form.
pub async fn work(pool: &Pool, id: &str) -> Result<Option<(String, String)>, sqlx::Error> {
    Ok(blob(pool, id, "input").await?.zip(blob(pool, id, "prepared").await?))
}

/// Which jobs a list shows.
#[derive(Debug, Default)]
pub struct ListFilter<'a> {
    pub status: Option<JobStatus>,
    pub kind: Option<JobKind>,
    /// Only this key's jobs (a planner's).
    pub owner: Option<i64>,
    /// Jobs whose name contains this, in any case.
    pub name: Option<&'a str>,
    /// Jobs that have every one of these tags.
    pub tags: &'a [String],
}

impl ListFilter<'_> {
    /// The `WHERE` clause, its placeholders numbered from `$1`, and the values they take.
    fn clause(&self) -> (String, Vec<Bound>) {
        let mut conditions = Vec::new();
        let mut values: Vec<Bound> = Vec::new();
        let mut bind = |condition: &str, value: Bound| {
            values.push(value);
            conditions.push(condition.replace('?', &format!("${}", values.len())));
        };
        if let Some(status) = self.status {
            bind("status = ?", Bound::Text(status.as_str().to_string()));
        }
        if let Some(kind) = self.kind {
            bind("kind = ?", Bound::Text(kind.as_str().to_string()));
        }
        if let Some(owner) = self.owner {
            bind("key_id = ?", Bound::Int(owner));
        }
        if let Some(name) = self.name {
            bind(r"name_key LIKE ? ESCAPE '\'", Bound::Text(contains_pattern(name)));
        }
        for tag in self.tags {
            bind("EXISTS (SELECT 1 FROM job_tags t WHERE t.job_id = jobs.id AND t.tag = ?)", Bound::Text(tag.clone()));
        }
        let clause = if conditions.is_empty() { String::new() } else { format!("WHERE {}", conditions.join(" AND ")) };
        (clause, values)
    }
}

/// A value bound to a placeholder of a [`ListFilter`]'s clause.
#[derive(Debug, Clone)]
enum Bound {
    Text(String),
    Int(i64),
}

impl Bound {
    fn bind_to<'q, O>(
        self,
        query: sqlx::query::QueryAs<'q, sqlx::Any, O, sqlx::any::AnyArguments>,
    ) -> sqlx::query::QueryAs<'q, sqlx::Any, O, sqlx::any::AnyArguments> {
        match self {
            Bound::Text(text) => query.bind(text),
            Bound::Int(n) => query.bind(n),
        }
    }
}

/// Lists the jobs `filter` selects, newest first, and counts them all.
pub async fn list(
    pool: &Pool,
    filter: &ListFilter<'_>,
    limit: i64,
    offset: i64,
) -> Result<(Vec<JobRow>, i64), ApiError> {
    let (clause, values) = filter.clause();
    let count = format!("SELECT COUNT(*) FROM jobs {clause}");
    let (total,): (i64,) = values
        .iter()
        .fold(sqlx::query_as(sqlx::AssertSqlSafe(count)), |q, v| v.clone().bind_to(q))
        .fetch_one(pool)
        .await?;
    let n = values.len();
    let sql = format!(
        "SELECT {ROW_COLUMNS} FROM jobs {clause} ORDER BY created_at DESC, rowid DESC LIMIT ${} OFFSET ${}",
        n + 1,
        n + 2
    );
    let rows = values
        .iter()
        .fold(sqlx::query_as::<_, JobRow>(sqlx::AssertSqlSafe(sql)), |q, v| v.clone().bind_to(q))
        .bind(limit)
        .bind(offset)
        .fetch_all(pool)
        .await?;
    Ok((rows, total))
}

/// A program of a job (`job_programs`), if it left one.
pub async fn program_part(pool: &Pool, id: &str, part: ProgramPart) -> Result<Option<String>, ApiError> {
    Ok(sqlx::query_scalar::<_, Text>("SELECT program FROM job_programs WHERE job_id = $1 AND part = $2")
        .bind(id)
        .bind(part.as_str())
        .fetch_optional(pool)
        .await?
        .map(String::from))
}

/// The drawing scene of a job (JSON), if it left one.
pub async fn scene(pool: &Pool, id: &str) -> Result<Option<String>, ApiError> {
    Ok(sqlx::query_scalar::<_, Text>("SELECT scene FROM job_scenes WHERE job_id = $1")
        .bind(id)
        .fetch_optional(pool)
        .await?
        .map(String::from))
}

/// Cancels a queued job at once; returns `false` if it was not queued.
pub async fn cancel_queued(pool: &Pool, id: &str) -> Result<bool, sqlx::Error> {
    let done = sqlx::query("UPDATE jobs SET status = 'cancelled', finished_at = strftime('%Y-%m-%dT%H:%M:%fZ', 'now'), updated_at = strftime('%Y-%m-%dT%H:%M:%fZ', 'now') WHERE id = $1 AND status = 'queued'")
    .bind(id)
    .execute(pool)
    .await?;
    Ok(done.rows_affected() == 1)
}

/// Asks a running job to stop; returns `false` if it was not running.
pub async fn request_cancel(pool: &Pool, id: &str) -> Result<bool, sqlx::Error> {
    let done = sqlx::query("UPDATE jobs SET cancel_requested = 1, updated_at = strftime('%Y-%m-%dT%H:%M:%fZ', 'now') WHERE id = $1 AND status = 'running'")
    .bind(id)
    .execute(pool)
    .await?;
    Ok(done.rows_affected() == 1)
}

/// Removes a finished job with its blobs, programs and scene (the foreign keys cascade);
/// `false` when the job is
/// still queued or running (cancel it first).
pub async fn purge(pool: &Pool, id: &str) -> Result<bool, sqlx::Error> {
    let done = sqlx::query("DELETE FROM jobs WHERE id = $1 AND status IN ('succeeded', 'failed', 'cancelled')")
        .bind(id)
        .execute(pool)
        .await?;
    Ok(done.rows_affected() == 1)
}

/// Removes the jobs that finished more than `days` days ago; returns how many.
pub async fn purge_finished_before(pool: &Pool, days: u64) -> Result<u64, sqlx::Error> {
    let done = sqlx::query(
        "DELETE FROM jobs WHERE status IN ('succeeded', 'failed', 'cancelled')
         AND finished_at < strftime('%Y-%m-%dT%H:%M:%fZ', 'now', '-' || $1 || ' days')",
    )
    .bind(i64::try_from(days).unwrap_or(i64::MAX))
    .execute(pool)
    .await?;
    Ok(done.rows_affected())
}
