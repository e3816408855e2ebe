//! What a caller sees of the two simulations of an insertion that describe its programs: the
//! base path's check and the finished program's verification. A caller that needs more of
//! them than the plan reports (the wear of each program, for its cost) counts it from their
//! samples instead of simulating the programs again.

use crate::core::analysis::engine::SampleResult;

/// Receives the samples of the base path's check and of the verifications. Each round of
/// treatment verifies its program again: only the last verification's samples describe the
/// finished program, so a new one starts with [`SampleObserver::restart`]. The samples are
/// handed over on another thread than the caller's (see
/// [`crate::core::analysis::handoff`]): an observer is `Send`.
pub trait SampleObserver: Send {
    /// A sample of the base path, as its check simulated it.
    fn base(&mut self, sample: &SampleResult);
    /// A round's verification begins: the samples seen since the last restart no longer count.
    fn restart(&mut self);
    /// A sample of the round's program, as its verification simulated it.
    fn verified(&mut self, sample: &SampleResult);
}
