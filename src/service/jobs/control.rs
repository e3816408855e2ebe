//! The control of one running job: its cancellation flags (a client's cancel, the
//! service's shutdown), its time limit and its progress, which the core reads and reports
//! through [`Progress`] while the job's queue ([`super::queue`]) and its execution
//! ([`super::execution`]) set and read them.

use crate::core::process::parallel::threads;
use crate::core::progress::Progress;
use std::sync::atomic::{AtomicBool, AtomicU64, AtomicUsize, Ordering};
use std::sync::Arc;
use std::time::{Duration, Instant};

/// Cancellation flags, time limit and progress of one running job; handed to the core
/// as its [`Progress`].
pub struct JobControl {
    cancel: AtomicBool,
    shutdown: Arc<AtomicBool>,
    progress_bits: AtomicU64,
    /// The longest the job may run (none: no limit).
    time_limit: Option<Duration>,
    /// When the job has run for as long as a job may (none: no limit).
    deadline: Option<Instant>,
    /// The cores this replica's jobs take now: one per running job, this one among them,
    /// and the spare cores their computations claimed (none: not counted).
    busy_cores: Option<Arc<AtomicUsize>>,
}

impl Progress for JobControl {
    fn report(&self, fraction: f64) {
        self.progress_bits.store(fraction.clamp(0.0, 1.0).to_bits(), Ordering::Relaxed);
    }

    fn cancelled(&self) -> bool {
        self.cancel.load(Ordering::Relaxed) || self.shutdown.load(Ordering::Relaxed) || self.timed_out()
    }

    /// Takes a core while the replica's jobs and the cores they claimed are fewer than the
    /// machine's cores: each job has one, and a free one may go to a job's parts side by
    /// side or its split simulation until they give it back.
    fn claim_spare_core(&self) -> bool {
        let Some(busy) = self.busy_cores.as_ref() else {
            return true;
        };
        busy.fetch_update(Ordering::AcqRel, Ordering::Acquire, |n| (n < threads()).then_some(n + 1)).is_ok()
    }

    fn release_core(&self) {
        if let Some(busy) = self.busy_cores.as_ref() {
            // A core given back that was never taken is a bug; the count stays at 0 then
            // rather than wrapping round (which would refuse every later claim).
            let given_back = busy.fetch_update(Ordering::AcqRel, Ordering::Acquire, |n| n.checked_sub(1));
            debug_assert!(given_back.is_ok(), "a core given back that was never taken");
        }
    }
}

impl JobControl {
    /// The control of a job starting now: cancelled already when that was asked for before
    /// it started, stopped when `shutdown` is set or after `time_limit`.
    pub fn new(cancel: bool, shutdown: Arc<AtomicBool>, time_limit: Option<Duration>) -> JobControl {
        JobControl {
            cancel: AtomicBool::new(cancel),
            shutdown,
            progress_bits: AtomicU64::new(0f64.to_bits()),
            time_limit,
            deadline: time_limit.and_then(|limit| Instant::now().checked_add(limit)),
            busy_cores: None,
        }
    }

    /// The control, taking its spare cores ([`Progress::claim_spare_core`]) from `busy`:
    /// the cores the replica's jobs take, one per running job (its queue counts them) and
    /// the spare cores claimed.
    pub fn counted_in(self, busy: Arc<AtomicUsize>) -> JobControl {
        JobControl { busy_cores: Some(busy), ..self }
    }

    /// Asks the job to stop: the core sees it cancelled at its next check.
    pub fn cancel(&self) {
        self.cancel.store(true, Ordering::Relaxed);
    }

    /// How far the job is, 0 to 1, as the core last reported it.
    pub fn progress(&self) -> f64 {
        f64::from_bits(self.progress_bits.load(Ordering::Relaxed))
    }

    /// `true` once the job has run past its time limit.
    fn timed_out(&self) -> bool {
        self.deadline.is_some_and(|deadline| Instant::now() >= deadline)
    }

    /// The longest the job may run (none: no limit).
    pub fn time_limit(&self) -> Option<Duration> {
        self.time_limit
    }

    /// Why a computation that stopped as cancelled stopped.
    pub fn stop_reason(&self) -> StopReason {
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
pub enum StopReason {
    /// A client cancelled the job.
    Cancelled,
    /// The service is stopping: the job runs again at the next start.
    Shutdown,
    /// The job ran past the configured time limit.
    TimedOut,
}

#[cfg(test)]
mod tests {
    use super::*;

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
    fn a_job_takes_a_second_core_only_while_one_is_free_and_gives_it_back() {
        let shutdown = Arc::new(AtomicBool::new(false));
        assert!(JobControl::new(false, shutdown.clone(), None).claim_spare_core(), "a job not counted may take any");
        // Every core but one has a job (this one among them).
        let busy = Arc::new(AtomicUsize::new(threads() - 1));
        let job = JobControl::new(false, shutdown, None).counted_in(busy.clone());
        assert!(job.claim_spare_core(), "the last free core");
        assert!(!job.claim_spare_core(), "no core left");
        assert_eq!(busy.load(Ordering::Relaxed), threads());
        job.release_core();
        assert_eq!(busy.load(Ordering::Relaxed), threads() - 1);
        assert!(job.claim_spare_core(), "free again");
    }
}
