//! How a long computation reports progress and learns that it should stop.

use crate::core::CoreError;

/// Progress sink and cancellation source handed to long computations.
pub trait Progress: Sync {
    /// Reports the finished fraction, 0..=1.
    fn report(&self, fraction: f64);
    /// `true` once the caller wants the computation to stop.
    fn cancelled(&self) -> bool;

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
