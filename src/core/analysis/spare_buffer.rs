//! The buffer a split simulation's second part holds its samples in until the first part's
//! are handed on (see [`super::split`]), kept from one simulation to the next. A buffer taken
//! fresh from the system costs a page fault for every 4 KiB the samples fill: the slot box's
//! second part fills 43 MB, some 10 000 faults and about 15 ms of its thread, a tenth of its
//! time. A buffer given back is kept for the next simulation of the process, one at a time
//! and only up to [`MAX_SPARE_BUFFER_BYTES`], so an idle service holds at most that much.

use super::engine::SampleResult;
use std::sync::{Mutex, MutexGuard};

/// The largest buffer kept for the next simulation, bytes (**assumed**: a few trochoid
/// programs' second parts; a larger buffer is let go, and the next simulation that needs one
/// takes it fresh).
pub const MAX_SPARE_BUFFER_BYTES: usize = 64 << 20;

/// The buffer kept, empty (none: no capacity).
static SPARE: Mutex<Vec<SampleResult>> = Mutex::new(Vec::new());

fn spare() -> MutexGuard<'static, Vec<SampleResult>> {
    // A buffer holds no state that a panic elsewhere could leave half made.
    SPARE.lock().unwrap_or_else(|poisoned| poisoned.into_inner())
}

/// An empty buffer for at least `capacity` samples: the one kept, grown if need be, or a
/// fresh one.
pub fn take(capacity: usize) -> Vec<SampleResult> {
    let mut buffer = std::mem::take(&mut *spare());
    buffer.clear();
    buffer.reserve(capacity);
    buffer
}

/// Keeps `buffer`, emptied, for the next simulation, unless it is larger than
/// [`MAX_SPARE_BUFFER_BYTES`] or the one kept is as large.
pub fn give_back(mut buffer: Vec<SampleResult>) {
    buffer.clear();
    if buffer.capacity().saturating_mul(std::mem::size_of::<SampleResult>()) > MAX_SPARE_BUFFER_BYTES {
        return;
    }
    let mut kept = spare();
    if buffer.capacity() > kept.capacity() {
        *kept = buffer;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_buffer_given_back_is_taken_again_empty_and_one_too_large_is_let_go() {
        // (Other tests' simulations may take and give back buffers meanwhile: only what
        // holds whatever they do is checked.)
        let taken = take(1000);
        assert!(taken.is_empty() && taken.capacity() >= 1000);
        give_back(taken);
        let again = take(10);
        assert!(again.is_empty() && again.capacity() >= 10);
        give_back(again);
        let too_large = MAX_SPARE_BUFFER_BYTES / std::mem::size_of::<SampleResult>() + 1;
        give_back(Vec::with_capacity(too_large));
        assert!(spare().capacity() < too_large, "a buffer larger than the limit is kept");
    }
}
