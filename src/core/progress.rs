//! How a long computation reports progress, learns that it should stop, and learns how
//! many cores it may take.

use crate::core::CoreError;

/// Progress sink, cancellation source and giver of spare cores handed to long computations.
pub trait Progress: Sync {
    /// Reports the finished fraction, 0..=1.
    fn report(&self, fraction: f64);
    /// `true` once the caller wants the computation to stop.
    fn cancelled(&self) -> bool;

    /// Takes one more core for this computation when one is free now, `true` if it did:
    /// parts that can run side by side ([`crate::core::process::parallel::map`]) and a
    /// simulation that can be split over two cores at some extra cost
    /// ([`crate::core::analysis::split`]) take more cores only so, and give each back with
    /// [`Progress::release_core`]. A job's control gives one only while its replica's jobs
    /// and the cores they took already are fewer than the machine's cores; with no one to
    /// ask (tests, benchmarks, the CLI), there is always one.
    fn claim_spare_core(&self) -> bool {
        true
    }

    /// Gives back a core [`Progress::claim_spare_core`] took.
    fn release_core(&self) {}

    /// Returns `Err(CoreError::Cancelled)` when cancelled: call it at safe points.
    fn checkpoint(&self) -> Result<(), CoreError> {
        if self.cancelled() {
            Err(CoreError::Cancelled)
        } else {
            Ok(())
        }
    }
}

/// A progress sink that ignores reports and never cancels (tests, benchmarks, CLI).
pub struct NoProgress;

impl Progress for NoProgress {
    fn report(&self, _fraction: f64) {}
    fn cancelled(&self) -> bool {
        false
    }
}

/// Work running beside another part that reports the progress: reports nothing, and is
/// cancelled when `inner` is or when the other part gave up (`abandoned`).
pub struct Beside<'a> {
    pub inner: &'a dyn Progress,
    pub abandoned: &'a std::sync::atomic::AtomicBool,
}

impl Progress for Beside<'_> {
    fn report(&self, _fraction: f64) {}
    fn cancelled(&self) -> bool {
        self.inner.cancelled() || self.abandoned.load(std::sync::atomic::Ordering::Relaxed)
    }
    fn claim_spare_core(&self) -> bool {
        self.inner.claim_spare_core()
    }
    fn release_core(&self) {
        self.inner.release_core()
    }
}

/// A part of a longer computation: reports `from + fraction · span` of the whole to `inner`,
/// and is cancelled when `inner` is.
pub struct Stage<'a> {
    pub inner: &'a dyn Progress,
    pub from: f64,
    pub span: f64,
}

impl<'a> Stage<'a> {
    /// Stage `index` of `count` equal stages within `[from, from + span]`.
    pub fn nth(inner: &'a dyn Progress, from: f64, span: f64, index: usize, count: usize) -> Self {
        let each = span / count.max(1) as f64;
        Stage { inner, from: from + each * index as f64, span: each }
    }
}

impl Progress for Stage<'_> {
    fn report(&self, fraction: f64) {
        self.inner.report(self.from + fraction.clamp(0.0, 1.0) * self.span);
    }
    fn cancelled(&self) -> bool {
        self.inner.cancelled()
    }
    fn claim_spare_core(&self) -> bool {
        self.inner.claim_spare_core()
    }
    fn release_core(&self) {
        self.inner.release_core()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::atomic::{AtomicBool, Ordering};

    struct Cancellable(AtomicBool);

    impl Progress for Cancellable {
        fn report(&self, _fraction: f64) {}
        fn cancelled(&self) -> bool {
            self.0.load(Ordering::Relaxed)
        }
    }

    #[test]
    fn work_beside_stops_when_the_job_is_cancelled_or_the_other_part_gives_up() {
        let (job, abandoned) = (Cancellable(AtomicBool::new(false)), AtomicBool::new(false));
        let beside = Beside { inner: &job, abandoned: &abandoned };
        assert!(beside.checkpoint().is_ok());
        abandoned.store(true, Ordering::Relaxed);
        assert!(matches!(beside.checkpoint(), Err(CoreError::Cancelled)));
        abandoned.store(false, Ordering::Relaxed);
        job.0.store(true, Ordering::Relaxed);
        assert!(matches!(beside.checkpoint(), Err(CoreError::Cancelled)));
    }
}
