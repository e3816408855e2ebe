//! Queue lanes: short jobs wait in their own lane, ahead of long ones, and one worker
//! serves only that lane, so a conditions job never waits behind plans.

use super::model::JobKind;

/// Largest input (bytes of JSON) of an analysis or feeds job still counted as short: a
/// hand-written program of a few hundred blocks, which runs in well under a second.
/// Larger programs, costing (whose input may name another job's long program), trochoids
/// and plans go to the batch lane.
pub const SMALL_INPUT_BYTES: usize = 16 * 1024;

/// Where a job waits.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Lane {
    /// Short jobs: served first by every worker, and alone by the interactive worker.
    Interactive,
    /// Everything else, first in, first out.
    Batch,
}

impl Lane {
    pub fn as_str(self) -> &'static str {
        match self {
            Lane::Interactive => "interactive",
            Lane::Batch => "batch",
        }
    }

    /// The lane of a job of `kind` whose input is `input_bytes` long.
    pub fn of(kind: JobKind, input_bytes: usize) -> Lane {
        match kind {
            JobKind::Conditions => Lane::Interactive,
            JobKind::Analysis | JobKind::Feeds if input_bytes <= SMALL_INPUT_BYTES => Lane::Interactive,
            _ => Lane::Batch,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn conditions_and_small_analyses_are_short_and_plans_are_not() {
        assert_eq!(Lane::of(JobKind::Conditions, 10_000_000), Lane::Interactive);
        assert_eq!(Lane::of(JobKind::Analysis, 2_000), Lane::Interactive);
        assert_eq!(Lane::of(JobKind::Analysis, SMALL_INPUT_BYTES + 1), Lane::Batch);
        assert_eq!(Lane::of(JobKind::Plan, 500), Lane::Batch);
        assert_eq!(Lane::of(JobKind::Costing, 500), Lane::Batch);
        assert_eq!(Lane::of(JobKind::Trochoids, 500), Lane::Batch);
    }
}
