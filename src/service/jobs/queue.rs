//! The worker pool: takes queued jobs from the table and runs each ([`super::execution`])
//! under a control of its own ([`super::control`]), honours cancellation and leaves
//! interrupted jobs resumable. Several replicas may share the table: each holds a lease on
//! the jobs it runs ([`super::lease`]), renewed by its lease keeper, which also notices
//! cancellations asked for on other replicas and queues again the jobs of replicas that
//! died.

use super::control::JobControl;
use super::execution;
use super::lease::{self as store, Lease};
use super::notify::{self, Event};
use crate::service::store::Pool;
use std::collections::HashMap;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};
use tokio::sync::{broadcast, watch, Notify};
use tokio::task::JoinHandle;

/// How often an idle worker looks at the table even without a wake-up.
const IDLE_POLL: Duration = Duration::from_secs(2);
/// How often the lease keeper looks for cancellations of this replica's running jobs.
const CANCEL_POLL: Duration = Duration::from_secs(1);
/// Capacity of the channel that announces finished jobs.
const FINISHED_CHANNEL: usize = 256;

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
    /// The cores the running jobs take: one each, and the spare cores their computations
    /// claim (see [`JobControl::counted_in`]).
    busy_cores: Arc<AtomicUsize>,
    shutdown: Arc<AtomicBool>,
    workers: Mutex<Vec<JoinHandle<()>>>,
    /// Longest a job may run (none: no limit).
    time_limit: Option<Duration>,
    /// Memory each stock simulation of a job may take, bytes.
    stock_memory_bytes: usize,
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
    /// `lease_duration`; another replica takes its jobs that long after it died. Each
    /// stock simulation of a job may take `stock_memory_bytes`.
    pub async fn start(
        pool: Pool,
        workers: usize,
        time_limit: Option<Duration>,
        lease_duration: Duration,
        stock_memory_bytes: usize,
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
                busy_cores: Arc::new(AtomicUsize::new(0)),
                shutdown: Arc::new(AtomicBool::new(false)),
                workers: Mutex::new(Vec::new()),
                time_limit,
                stock_memory_bytes,
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
                control.cancel();
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

/// The core a running job takes, counted among the busy cores until it is dropped (when
/// the job ends, or its worker's future is dropped or unwinds).
struct CoreTaken(Arc<AtomicUsize>);

impl CoreTaken {
    fn take(busy: &Arc<AtomicUsize>) -> CoreTaken {
        busy.fetch_add(1, Ordering::AcqRel);
        CoreTaken(busy.clone())
    }
}

impl Drop for CoreTaken {
    fn drop(&mut self) {
        self.0.fetch_sub(1, Ordering::AcqRel);
    }
}

async fn run_one(inner: &Arc<Inner>, row: store::Claimed) {
    let id = row.id.clone();
    let control = JobControl::new(row.cancel_requested, inner.shutdown.clone(), inner.time_limit);
    let control = Arc::new(control.counted_in(inner.busy_cores.clone()));
    inner.running.lock().unwrap_or_else(|p| p.into_inner()).insert(id.clone(), control.clone());
    let core = CoreTaken::take(&inner.busy_cores);
    let recorded = match execution::execute(&inner.pool, &inner.lease, &row, control, inner.stock_memory_bytes).await {
        Ok(recorded) => recorded,
        Err(e) => {
            tracing::error!(job = %id, error = %e, "could not record the outcome of a job");
            false
        }
    };
    drop(core);
    inner.running.lock().unwrap_or_else(|p| p.into_inner()).remove(&id);
    if recorded {
        notify::send(&inner.pool, Event::Finished, &id).await;
    }
    let _ = inner.finished.send(id);
}
