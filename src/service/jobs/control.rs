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
    /// How many jobs this replica runs now, this one among them (none: not counted).
    running_jobs: Option<Arc<AtomicUsize>>,
}

impl Progress for JobControl {
    fn report(&self, fraction: f64) {
        self.progress_bits.store(fraction.clamp(0.0, 1.0).to_bits(), Ordering::Relaxed);
    }

    fn cancelled(&self) -> bool {
        self.cancel.load(Ordering::Relaxed) || self.shutdown.load(Ordering::Relaxed) || self.timed_out()
    }

    /// A core is spare while fewer jobs run than the machine has cores: each job takes one,
    /// and one left over may take a second.
    fn spare_core(&self) -> bool {
        self.running_jobs.as_ref().is_none_or(|running| running.load(Ordering::Relaxed) < threads())
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
            running_jobs: None,
        }
    }

    /// The control, knowing how many jobs run beside it from `running` (the count of
    /// running jobs, this one among them), which it reads for [`Progress::spare_core`].
    pub fn counted_in(self, running: Arc<AtomicUsize>) -> JobControl {
        JobControl { running_jobs: Some(running), ..self }
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
    fn a_job_has_a_spare_core_only_while_fewer_jobs_run_than_the_machine_has_cores() {
        let shutdown = Arc::new(AtomicBool::new(false));
        assert!(JobControl::new(false, shutdown.clone(), None).spare_core(), "a job not counted may take any core");
        let running = Arc::new(AtomicUsize::new(1));
        let job = JobControl::new(false, shutdown, None).counted_in(running.clone());
        assert_eq!(job.spare_core(), threads() > 1);
        running.store(threads(), Ordering::Relaxed);
        assert!(!job.spare_core(), "every core has a job");
    }
}
