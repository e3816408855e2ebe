//! The worker pool: takes queued jobs from the table, runs them on blocking threads,
//! reports progress, honours cancellation and leaves interrupted jobs resumable. Several
//! replicas may share the table: each holds a lease on the jobs it runs
//! ([`super::lease`]), renewed by its lease keeper, which also notices cancellations
//! asked for on other replicas and queues again the jobs of replicas that died.

use super::kinds;
use super::lease::{self as store, Lease};
use super::model::{JobKind, ProgramPart};
use super::notify::{self, Event};
use crate::core::progress::Progress;
use crate::core::CoreError;
use crate::service::error::ApiError;
use crate::service::store::Pool;
use std::collections::HashMap;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};
use tokio::sync::{broadcast, watch, Notify};
use tokio::task::JoinHandle;

/// How often an idle worker looks at the table even without a wake-up.
const IDLE_POLL: Duration = Duration::from_secs(2);
/// How often a running job's progress is written to the table.
const PROGRESS_FLUSH: Duration = Duration::from_millis(250);
/// A job started this many times without finishing is failed instead of run again
/// (it may be what brought the service down).
pub const MAX_ATTEMPTS: i64 = 3;
/// How often the lease keeper looks for cancellations of this replica's running jobs.
const CANCEL_POLL: Duration = Duration::from_secs(1);
/// Capacity of the channel that announces finished jobs.
const FINISHED_CHANNEL: usize = 256;
/// Largest result, program or scene one job stores, bytes: SQLite refuses a text of 1 GB
/// (its default `SQLITE_MAX_LENGTH`), and no client could use one this large.
pub const MAX_STORED_BYTES: usize = 256 * 1024 * 1024;

/// Cancellation flags, time limit and progress of one running job; handed to the core
/// as its [`Progress`].
pub struct JobControl {
    cancel: AtomicBool,
    shutdown: Arc<AtomicBool>,
    progress_bits: AtomicU64,
    /// When the job has run for as long as a job may (none: no limit).
    deadline: Option<Instant>,
}

impl Progress for JobControl {
    fn report(&self, fraction: f64) {
        self.progress_bits.store(fraction.clamp(0.0, 1.0).to_bits(), Ordering::Relaxed);
    }

    fn cancelled(&self) -> bool {
        self.cancel.load(Ordering::Relaxed) || self.shutdown.load(Ordering::Relaxed) || self.timed_out()
    }
}

impl JobControl {
    fn new(cancel: bool, shutdown: Arc<AtomicBool>, time_limit: Option<Duration>) -> JobControl {
        JobControl {
            cancel: AtomicBool::new(cancel),
            shutdown,
            progress_bits: AtomicU64::new(0f64.to_bits()),
            deadline: time_limit.and_then(|limit| Instant::now().checked_add(limit)),
        }
    }

    fn progress(&self) -> f64 {
        f64::from_bits(self.progress_bits.load(Ordering::Relaxed))
    }

    /// `true` once the job has run past its time limit.
    fn timed_out(&self) -> bool {
        self.deadline.is_some_and(|deadline| Instant::now() >= deadline)
    }

    /// Why a computation that stopped as cancelled stopped.
    fn stop_reason(&self) -> StopReason {
        if self.cancel.load(Ordering::Relaxed) {
            StopReason::Cancelled
        } else if self.shutdown.load(Ordering::Relaxed) {
            StopReason::Shutdown
        } else {
            StopReason::TimedOut
        }
    }
}

/// Why a job's computation stopped before it finished.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum StopReason {
    /// A client cancelled the job.
    Cancelled,
    /// The service is stopping: the job runs again at the next start.
    Shutdown,
    /// The job ran past the configured time limit.
    TimedOut,
}

struct Inner {
    pool: Pool,
    /// Wakes a worker of either kind.
    wake: Notify,
    /// Wakes the interactive worker.
    wake_interactive: Notify,
    /// Set when the service begins to stop: clients waiting for a job answer at once.
    stopping: watch::Sender<bool>,
    finished: broadcast::Sender<String>,
    running: Mutex<HashMap<String, Arc<JobControl>>>,
    shutdown: Arc<AtomicBool>,
    workers: Mutex<Vec<JoinHandle<()>>>,
    /// Longest a job may run (none: no limit).
    time_limit: Option<Duration>,
    /// This replica's lease on the jobs it runs.
    lease: Lease,
    /// The lease keeper and the notification listener, stopped at shutdown.
    helpers: Mutex<Vec<JoinHandle<()>>>,
}

/// Handle to the worker pool.
#[derive(Clone)]
pub struct JobQueue {
    inner: Arc<Inner>,
}

impl JobQueue {
    /// Recovers jobs a previous run left behind and starts `workers` workers, and with
    /// them one more that runs only the interactive lane (see [`super::lane`]); a job
    /// that runs longer than `time_limit` is stopped and fails. The replica's leases last
    /// `lease_duration`; another replica takes its jobs that long after it died.
    pub async fn start(
        pool: Pool,
        workers: usize,
        time_limit: Option<Duration>,
        lease_duration: Duration,
    ) -> Result<JobQueue, sqlx::Error> {
        let requeued = store::recover_interrupted(&pool).await?;
        if requeued > 0 {
            tracing::info!(requeued, "re-queued jobs interrupted by the previous run");
        }
        let (finished, _) = broadcast::channel(FINISHED_CHANNEL);
        let queue = JobQueue {
            inner: Arc::new(Inner {
                pool,
                wake: Notify::new(),
                wake_interactive: Notify::new(),
                stopping: watch::channel(false).0,
                finished,
                running: Mutex::new(HashMap::new()),
                shutdown: Arc::new(AtomicBool::new(false)),
                workers: Mutex::new(Vec::new()),
                time_limit,
                lease: Lease::new(lease_duration),
                helpers: Mutex::new(Vec::new()),
            }),
        };
        tracing::info!(replica = %queue.inner.lease.owner, lease_s = lease_duration.as_secs_f64(), "job queue started");
        let mut helpers = vec![tokio::spawn(keep_leases(queue.inner.clone()))];
        let inner = Arc::downgrade(&queue.inner);
        helpers.extend(notify::listen(&queue.inner.pool, move |event, id| {
            if let Some(inner) = inner.upgrade() {
                on_event(&inner, event, id);
            }
        }));
        *queue.inner.helpers.lock().unwrap_or_else(|p| p.into_inner()) = helpers;
        let interactive = usize::from(workers > 0);
        let handles: Vec<_> = (0..workers + interactive)
            .map(|n| {
                let inner = queue.inner.clone();
                tokio::spawn(async move { worker_loop(inner, n, n == workers).await })
            })
            .collect();
        *queue.inner.workers.lock().unwrap_or_else(|p| p.into_inner()) = handles;
        Ok(queue)
    }

    /// Tells the workers, of this replica and of the others, that a job was queued.
    pub fn wake(&self) {
        self.inner.wake.notify_one();
        self.inner.wake_interactive.notify_one();
        let pool = self.inner.pool.clone();
        tokio::spawn(async move { notify::send(&pool, Event::Queued, "").await });
    }

    /// Watches whether the service is stopping (`true` from then on).
    pub fn stopping(&self) -> watch::Receiver<bool> {
        self.inner.stopping.subscribe()
    }

    /// Tells the clients waiting for jobs that the service is stopping.
    pub fn begin_stop(&self) {
        self.inner.stopping.send_replace(true);
    }

    /// Subscribes to the ids of jobs as they finish.
    pub fn subscribe(&self) -> broadcast::Receiver<String> {
        self.inner.finished.subscribe()
    }

    /// Asks a running job to stop, on whichever replica runs it.
    pub fn cancel_running(&self, id: &str) {
        if !self.inner.cancel_local(id) {
            let (pool, id) = (self.inner.pool.clone(), id.to_string());
            tokio::spawn(async move { notify::send(&pool, Event::CancelRequested, &id).await });
        }
    }

    /// Stops the workers: running jobs are interrupted and queued again, without counting
    /// the attempt, so the next start resumes them. Waits at most `grace` for the workers;
    /// a job still running then is queued again all the same.
    pub async fn shutdown(&self, grace: Duration) {
        self.begin_stop();
        self.inner.shutdown.store(true, Ordering::SeqCst);
        for helper in std::mem::take(&mut *self.inner.helpers.lock().unwrap_or_else(|p| p.into_inner())) {
            helper.abort();
        }
        self.inner.wake.notify_waiters();
        self.inner.wake_interactive.notify_waiters();
        let handles = std::mem::take(&mut *self.inner.workers.lock().unwrap_or_else(|p| p.into_inner()));
        let all = futures_join(handles);
        if tokio::time::timeout(grace, all).await.is_err() {
            let ids: Vec<String> =
                self.inner.running.lock().unwrap_or_else(|p| p.into_inner()).keys().cloned().collect();
            tracing::warn!(jobs = ids.len(), "workers did not stop in time; their jobs resume at the next start");
            if let Err(e) = store::requeue(&self.inner.pool, &self.inner.lease, &ids).await {
                tracing::error!(error = %e, "could not queue the interrupted jobs again; the next start will");
            }
        }
    }
}

impl Inner {
    /// Stops job `id` if this replica runs it; `false` when it does not.
    fn cancel_local(&self, id: &str) -> bool {
        match self.running.lock().unwrap_or_else(|p| p.into_inner()).get(id) {
            Some(control) => {
                control.cancel.store(true, Ordering::Relaxed);
                true
            }
            None => false,
        }
    }

    /// The ids of the jobs this replica runs.
    fn running_ids(&self) -> Vec<String> {
        self.running.lock().unwrap_or_else(|p| p.into_inner()).keys().cloned().collect()
    }
}

/// What another replica (or this one) told every replica about a job.
fn on_event(inner: &Inner, event: Event, id: &str) {
    match event {
        Event::Queued => {
            inner.wake.notify_one();
            inner.wake_interactive.notify_one();
        }
        Event::CancelRequested => {
            inner.cancel_local(id);
        }
        Event::Finished => {
            let _ = inner.finished.send(id.to_string());
        }
    }
}

/// The lease keeper: every [`CANCEL_POLL`], stops the running jobs whose cancellation was
/// asked for on any replica; every third of the lease, renews this replica's leases and
/// queues again the jobs of replicas whose leases expired.
async fn keep_leases(inner: Arc<Inner>) {
    let renew_every = (inner.lease.duration / 3).max(CANCEL_POLL);
    let mut tick = tokio::time::interval(CANCEL_POLL);
    let mut last_renewal = Instant::now();
    loop {
        tick.tick().await;
        if !inner.running_ids().is_empty() {
            match store::cancels_requested(&inner.pool, &inner.lease).await {
                Ok(ids) => ids.iter().for_each(|id| {
                    inner.cancel_local(id);
                }),
                Err(e) => tracing::warn!(error = %e, "could not read the cancellations of running jobs"),
            }
        }
        if last_renewal.elapsed() < renew_every {
            continue;
        }
        last_renewal = Instant::now();
        if let Err(e) = store::renew(&inner.pool, &inner.lease).await {
            tracing::error!(error = %e, "could not renew the leases of running jobs; another replica may take them");
        }
        match store::requeue_expired(&inner.pool).await {
            Ok(0) => {}
            Ok(requeued) => {
                tracing::warn!(requeued, "queued again the jobs of a replica whose leases expired");
                inner.wake.notify_waiters();
                inner.wake_interactive.notify_waiters();
            }
            Err(e) => tracing::warn!(error = %e, "could not look for jobs with expired leases"),
        }
    }
}

async fn futures_join(handles: Vec<JoinHandle<()>>) {
    for h in handles {
        let _ = h.await;
    }
}

async fn worker_loop(inner: Arc<Inner>, n: usize, interactive_only: bool) {
    tracing::debug!(worker = n, interactive_only, "worker started");
    while !inner.shutdown.load(Ordering::SeqCst) {
        match store::claim_next(&inner.pool, &inner.lease, interactive_only).await {
            Ok(Some(row)) => run_one(&inner, row).await,
            Ok(None) => {
                let wake = if interactive_only { &inner.wake_interactive } else { &inner.wake };
                let _ = tokio::time::timeout(IDLE_POLL, wake.notified()).await;
            }
            Err(e) => {
                tracing::error!(error = %e, "worker could not read the job table");
                tokio::time::sleep(IDLE_POLL).await;
            }
        }
    }
    tracing::debug!(worker = n, "worker stopped");
}

async fn run_one(inner: &Arc<Inner>, row: store::Claimed) {
    let id = row.id.clone();
    let recorded = match execute(inner, &row).await {
        Ok(recorded) => recorded,
        Err(e) => {
            tracing::error!(job = %id, error = %e, "could not record the outcome of a job");
            false
        }
    };
    inner.running.lock().unwrap_or_else(|p| p.into_inner()).remove(&id);
    if recorded {
        notify::send(&inner.pool, Event::Finished, &id).await;
    }
    let _ = inner.finished.send(id);
}

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
    scene: Option<String>,
}

/// Runs a claimed job and records its outcome; `Ok(false)` when the outcome was not
/// recorded because this replica no longer holds the job's lease (another replica runs
/// it), or the job went back to the queue.
async fn execute(inner: &Arc<Inner>, row: &store::Claimed) -> Result<bool, sqlx::Error> {
    let (pool, lease) = (&inner.pool, &inner.lease);
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
    let control = Arc::new(JobControl::new(row.cancel_requested, inner.shutdown.clone(), inner.time_limit));
    inner.running.lock().unwrap_or_else(|p| p.into_inner()).insert(id.to_string(), control.clone());

    let Some((input, prepared)) = super::store::work(pool, id).await? else {
        let problem = ApiError::Internal(format!("job {id} has no stored input")).problem();
        return store::fail(pool, lease, id, &problem).await;
    };
    let worker_control = control.clone();
    let mut task = tokio::task::spawn_blocking(move || {
        let kinds::JobOutput { result: value, program, baseline_program: baseline, scene } =
            kinds::run(kind, &input, &prepared, worker_control.as_ref())?;
        let result = serde_json::to_string(&value).unwrap_or_default();
        let summary = super::model::headline(&value).to_string();
        Ok::<_, CoreError>(Serialized { result, summary, program, baseline, scene })
    });
    let mut tick = tokio::time::interval(PROGRESS_FLUSH);
    let mut last = 0.0;
    let joined = loop {
        tokio::select! {
            joined = &mut task => break joined,
            _ = tick.tick() => {
                let p = control.progress();
                if (p - last).abs() > f64::EPSILON {
                    last = p;
                    store::set_progress(pool, lease, id, p).await?;
                }
            }
        }
    };

    match joined {
        Ok(Ok(done)) => {
            let Serialized { result, summary, .. } = &done;
            let (program, baseline, scene) = (done.program.as_deref(), done.baseline.as_deref(), done.scene.as_deref());
            let sizes = [
                ("result", result.len()),
                ("program", program.map_or(0, str::len)),
                ("baseline program", baseline.map_or(0, str::len)),
                ("scene", scene.map_or(0, str::len)),
            ];
            if let Some(problem) = oversized(&sizes) {
                return store::fail(pool, lease, id, &problem).await;
            }
            let programs = [(ProgramPart::Main, program), (ProgramPart::Baseline, baseline)]
                .into_iter()
                .filter_map(|(part, text)| Some((part, text?)))
                .collect();
            let outcome = store::Outcome { result, summary: Some(summary), programs, scene };
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
                let limit = inner.time_limit.unwrap_or_default();
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
    fn a_job_past_its_time_limit_reads_as_cancelled_and_says_it_timed_out() {
        let shutdown = Arc::new(AtomicBool::new(false));
        let unlimited = JobControl::new(false, shutdown.clone(), None);
        assert!(!unlimited.cancelled());
        let expired = JobControl::new(false, shutdown.clone(), Some(Duration::ZERO));
        assert!(expired.cancelled());
        assert_eq!(expired.stop_reason(), StopReason::TimedOut);
        let later = JobControl::new(false, shutdown, Some(Duration::from_secs(3600)));
        assert!(!later.cancelled());
    }

    #[test]
    fn a_cancel_or_a_shutdown_outranks_the_time_limit() {
        let shutdown = Arc::new(AtomicBool::new(false));
        let cancelled = JobControl::new(true, shutdown.clone(), Some(Duration::ZERO));
        assert_eq!(cancelled.stop_reason(), StopReason::Cancelled);
        shutdown.store(true, Ordering::SeqCst);
        let stopping = JobControl::new(false, shutdown, Some(Duration::ZERO));
        assert_eq!(stopping.stop_reason(), StopReason::Shutdown);
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
