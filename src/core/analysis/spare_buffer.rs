//! The batches a split simulation's second part hands its samples over in (see
//! [`super::split`]), kept from one simulation to the next. The batches wait while the first
//! part is simulated: memory taken fresh from the system costs a page fault for every 4 KiB
//! they fill (the slot box's second part fills 43 MB: some 10 000 faults and about 15 ms of
//! its thread, a tenth of its time). Batches given back are kept for the next simulation of
//! the process, up to [`MAX_SPARE_BUFFER_BYTES`], so an idle service holds at most that much.

use super::engine::SampleResult;
use std::sync::{Mutex, MutexGuard};

/// Samples a batch holds (a megabyte: large enough that handing one over costs little per
/// sample, small enough that the hand-on follows the second thread closely).
pub const BATCH_SAMPLES: usize = 4096;

/// Most memory the batches kept for the next simulation take, bytes (**assumed**: a few
/// trochoid programs' second parts; beyond it batches given back are let go, and the next
/// simulation that needs more takes them fresh).
pub const MAX_SPARE_BUFFER_BYTES: usize = 64 << 20;

/// Batches kept at most.
const MAX_SPARE_BATCHES: usize = MAX_SPARE_BUFFER_BYTES / (BATCH_SAMPLES * std::mem::size_of::<SampleResult>());

/// The batches kept, empty.
static SPARE: Mutex<Vec<Vec<SampleResult>>> = Mutex::new(Vec::new());

/// The batches kept, locked.
fn spare() -> MutexGuard<'static, Vec<Vec<SampleResult>>> {
    // Empty batches hold no state that a panic elsewhere could leave half made.
    SPARE.lock().unwrap_or_else(|poisoned| poisoned.into_inner())
}

/// An empty batch for [`BATCH_SAMPLES`] samples: one kept, or a fresh one.
pub fn take() -> Vec<SampleResult> {
    spare().pop().unwrap_or_else(|| Vec::with_capacity(BATCH_SAMPLES))
}

/// Keeps `batch`, emptied, for the next simulation, unless [`MAX_SPARE_BUFFER_BYTES`] of
/// batches are kept already.
pub fn give_back(mut batch: Vec<SampleResult>) {
    batch.clear();
    let mut kept = spare();
    if kept.len() < MAX_SPARE_BATCHES && batch.capacity() >= BATCH_SAMPLES {
        kept.push(batch);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_batch_given_back_is_taken_again_empty_and_no_more_than_the_limit_are_kept() {
        // (Other tests' simulations may take and give back batches meanwhile: only what
        // holds whatever they do is checked.)
        let mut taken = take();
        assert!(taken.is_empty() && taken.capacity() >= BATCH_SAMPLES);
        taken.push(any_sample());
        give_back(taken);
        let again = take();
        assert!(again.is_empty() && again.capacity() >= BATCH_SAMPLES);
        give_back(again);
        for _ in 0..MAX_SPARE_BATCHES + 3 {
            give_back(Vec::with_capacity(BATCH_SAMPLES));
        }
        assert!(spare().len() <= MAX_SPARE_BATCHES, "more batches kept than the limit");
    }

    /// A sample of no path (its figures do not matter here).
    fn any_sample() -> SampleResult {
        let sample = crate::core::analysis::sampling::Sample {
            p: crate::core::toolpath::P3::new(0.0, 0.0, 0.0),
            heading: (1.0, 0.0),
            step_mm: 0.05,
            move_index: 0,
            line: 1,
            feed_mm_min: 0.0,
            spindle_rpm: None,
            rapid: false,
            curvature: crate::core::curvature::PointCurvature::STRAIGHT,
        };
        SampleResult {
            sample,
            s_mm: 0.0,
            contact: Default::default(),
            arc_length_mm: 0.0,
            ad_mm: 0.0,
            t_m_um: 0.0,
            contact_radius_mm: 0.0,
            force_n: None,
            plunge: false,
            force_extrapolated: false,
            coded: None,
            cutting_point_ratio: 1.0,
            centre_radius_mm: f64::INFINITY,
        }
    }
}
