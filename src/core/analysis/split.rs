//! One simulation on two cores (issue 29, "Plans in seconds"). What the rasters hold as the
//! tool moves along a path never depends on what the probes find: the updates follow from
//! the samples' positions alone (see [`super::chunk`]). So a second thread that replays the
//! updates of a path's first part without measuring any sample (up to half the work of
//! simulating it: along a trochoid's loops the updates cost as much as the probes) holds
//! exactly the stock the simulation holds where the first part
//! ends, and simulates the rest from there, while the calling thread simulates the first
//! part. The samples are handed on in the order of the path, the second part's once the
//! first part's are: they come over in batches as the second thread makes them (batches
//! kept from one simulation to the next, see [`super::spare_buffer`]), and wait only while
//! the first part is simulated. The stock left is the second thread's, the whole path's.

use super::engine::{simulate, simulate_range, Cutter, SampleRange, SampleResult};
use super::spare_buffer;
use super::stack::Stack;
use crate::core::process::parallel::{ClaimedCores, Shares};
use crate::core::progress::{Progress, Stage};
use crate::core::toolpath::Toolpath;
use crate::core::CoreError;

/// The share of the samples the calling thread simulates; the second thread replays their
/// updates and simulates the rest. A trochoid program's first samples (its trochoids) cost
/// the most, and replaying one costs up to half of simulating it; and the calling thread
/// hands on the first part's samples as they come, then the second part's while the second
/// thread finishes. Measured side by side on the slot box (shares 0.40 to 0.52, each the
/// fastest of twelve runs), 0.43 to 0.46 finished first.
pub const FIRST_PART_SHARE: f64 = 0.44;

/// Paths of fewer samples are simulated on one core: the copy of the stock and the thread
/// would cost more than they spare (**assumed**: a tenth of the slot box's base path; a
/// split of the bench's pockets spares tens of milliseconds, the thread and the copy well
/// under one).
pub const MIN_SPLIT_SAMPLES: usize = 20_000;

/// Most memory the second part's samples may take while they wait for the first part's,
/// bytes (**assumed**: a few times a pocket's stock; the trochoid programs' second parts
/// take about 40 MB). A longer path is simulated on one core.
pub const MAX_SPLIT_BUFFER_BYTES: usize = 256 << 20;

/// The sample where the second part starts, of `total` ([`FIRST_PART_SHARE`]).
pub fn split_sample(total: usize) -> usize {
    (total as f64 * FIRST_PART_SHARE).round() as usize
}

/// [`simulate`] on two threads, as the module says, when the path has at least
/// [`MIN_SPLIT_SAMPLES`], its second part's samples fit in [`MAX_SPLIT_BUFFER_BYTES`], two
/// copies of the slices' stock fit in `budget_bytes` (each may come to a raster per slice),
/// and `progress` gives the computation a second core ([`Progress::claim_spare_core`]: the
/// replay costs a third more work, which only pays where that core would idle); otherwise
/// on the calling thread alone. `sink` sees every sample in the order of the path, on the
/// calling thread. Progress is the mean of the two threads' shares of their work; either
/// stops when `progress` is cancelled.
pub fn simulate_split(
    path: &Toolpath,
    cutter: Cutter,
    slices: &mut Stack,
    budget_bytes: usize,
    progress: &dyn Progress,
    sink: impl FnMut(&SampleResult),
) -> Result<(), CoreError> {
    let total = cutter.total_samples;
    let at = split_sample(total);
    let buffered_bytes = total.saturating_sub(at).saturating_mul(std::mem::size_of::<SampleResult>());
    let two_stocks = slices.most_memory_bytes().saturating_mul(2);
    let fits = total >= MIN_SPLIT_SAMPLES && buffered_bytes <= MAX_SPLIT_BUFFER_BYTES && two_stocks <= budget_bytes;
    let second = ClaimedCores::claim(progress, usize::from(fits));
    if second.count() == 0 {
        return simulate(path, cutter, slices, progress, sink);
    }
    simulate_split_at(path, cutter, slices, at, second, progress, sink)
}

/// [`simulate`] on two threads, the second measuring from sample `at` on (see the module) on
/// `second_core`, which it gives back when it is done.
fn simulate_split_at(
    path: &Toolpath,
    cutter: Cutter,
    slices: &mut Stack,
    at: usize,
    second_core: ClaimedCores,
    progress: &dyn Progress,
    mut sink: impl FnMut(&SampleResult),
) -> Result<(), CoreError> {
    let total = cutter.total_samples.max(at);
    let mut rest = slices.clone();
    let shares = Shares::new(progress, 0.0, 1.0, 2);
    let (first_share, second_share) = (shares.part(0), shares.part(1));
    // The first thread reports its samples against the whole path's: scaled to its part.
    let first_progress = Stage { inner: &first_share, from: 0.0, span: total as f64 / at.max(1) as f64 };
    let later = SampleRange { measure_from: at, stop_at: usize::MAX };
    // The second part's samples go over in batches, in order, as they are made: once the
    // calling thread has handed on the first part's, it hands these on while the second
    // thread still simulates.
    let (to_caller, from_second) = std::sync::mpsc::channel::<Vec<SampleResult>>();
    std::thread::scope(|scope| {
        let rest = &mut rest;
        let second = scope.spawn(move || {
            let _core = second_core;
            let mut batch = spare_buffer::take();
            let simulated = simulate_range(path, cutter, rest, &second_share, later, |r| {
                batch.push(*r);
                if batch.len() == spare_buffer::BATCH_SAMPLES {
                    // (The caller stopped taking them only when its own part failed.)
                    let _ = to_caller.send(std::mem::replace(&mut batch, spare_buffer::take()));
                }
            });
            if !batch.is_empty() {
                let _ = to_caller.send(batch);
            }
            simulated
        });
        let first = SampleRange { measure_from: 0, stop_at: at };
        let simulated = simulate_range(path, cutter, slices, &first_progress, first, &mut sink);
        if simulated.is_ok() {
            // Until the second thread ends (its sender goes with it).
            for batch in from_second.iter() {
                batch.iter().for_each(&mut sink);
                spare_buffer::give_back(batch);
            }
        }
        drop(from_second);
        let second = second.join().unwrap_or_else(|panic| std::panic::resume_unwind(panic));
        simulated.and(second)
    })?;
    *slices = rest;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::core::analysis::profile::Profile;
    use crate::core::analysis::test_paths::{feed_move, relief_cutter, relief_program, relief_slices, sample_bits};
    use crate::core::process::parallel::threads;
    use crate::core::progress::NoProgress;
    use crate::core::toolpath::{Motion, Move, Plane, P3};

    /// The relief program, then loops (full circles) along a line across what it cut: ramps,
    /// straight stretches, corners, arcs and several slices.
    fn program() -> Toolpath {
        let mut path = relief_program();
        let moves = &mut path.moves;
        let mut at = moves[moves.len() - 1].end;
        for k in 0..24 {
            let centre = P3::new(4.0 + f64::from(k), 15.0, -3.0);
            let start = P3::new(centre.x + 2.0, centre.y, centre.z);
            moves.push(feed_move(at, start, moves.len()));
            let arc = Motion::Arc { center: centre, clockwise: false, plane: Plane::Xy, turns: 0 };
            moves.push(Move { motion: arc, ..feed_move(start, start, moves.len()) });
            at = start;
        }
        path
    }

    #[test]
    fn a_simulation_split_over_two_threads_gives_every_sample_and_cell_of_the_whole_one() {
        let path = program();
        let radius_end_mill = Profile::of(&crate::core::tool::EndMill {
            tool_type: crate::core::tool::ToolType::Radius,
            diameter_mm: 4.0,
            flutes: 2,
            corner_radius_mm: 0.8,
        });
        let model = Some(crate::core::fixtures::seed_001_ten_mm());
        // A square end mill with and without forces, and a radius end mill, whose corner
        // takes the slices it reaches at smaller radii.
        for (profile, model) in
            [(Profile::cylinder(2.0), None), (Profile::cylinder(2.0), model), (radius_end_mill, None)]
        {
            let cutter = |total_samples| Cutter {
                profile,
                flutes: 2,
                default_spindle_rpm: Some(9600.0),
                force_model: model,
                spacing_mm: 0.05,
                total_samples,
            };
            let mut whole = relief_slices(&path);
            let mut expected = Vec::new();
            simulate(&path, cutter(0), &mut whole, &NoProgress, |r| expected.push(sample_bits(r))).expect("simulates");
            let n = expected.len();
            assert!(expected.iter().filter(|b| b[1] > 0).count() > n / 2, "too little engagement");
            // Split at points along the passes and the loops, and where either part is empty.
            for at in [split_sample(n), n / 7, n / 3 + 1, 9 * n / 10, 0, n, 2 * n] {
                let mut split = relief_slices(&path);
                let mut found = Vec::new();
                let core = ClaimedCores::none(&NoProgress);
                simulate_split_at(&path, cutter(n), &mut split, at, core, &NoProgress, |r| found.push(sample_bits(r)))
                    .expect("simulates");
                assert!(found == expected, "the samples differ, split at {at} of {n}");
                for k in 0..whole.len() {
                    assert!(split.raster(k).cells() == whole.raster(k).cells(), "slice {k} differs");
                }
            }
        }
    }

    /// Progress that records which threads asked whether to stop, and the cores claimed and
    /// given back, with a spare core or not.
    struct Threads {
        spare: bool,
        asked_from: std::sync::Mutex<std::collections::HashSet<std::thread::ThreadId>>,
        claimed: std::sync::atomic::AtomicUsize,
        released: std::sync::atomic::AtomicUsize,
    }

    impl Progress for Threads {
        fn report(&self, _fraction: f64) {}
        fn cancelled(&self) -> bool {
            self.asked_from.lock().expect("not poisoned").insert(std::thread::current().id());
            false
        }
        fn claim_spare_core(&self) -> bool {
            self.claimed.fetch_add(usize::from(self.spare), std::sync::atomic::Ordering::Relaxed);
            self.spare
        }
        fn release_core(&self) {
            self.released.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
        }
    }

    #[test]
    fn a_simulation_takes_a_second_core_only_when_one_is_free_and_two_stocks_fit_the_budget() {
        let path = program();
        let cutter = Cutter { total_samples: MIN_SPLIT_SAMPLES, ..relief_cutter(None) };
        let threads_asking = |spare: bool, budget_bytes: usize| {
            let progress = Threads { spare, asked_from: Default::default(), claimed: 0.into(), released: 0.into() };
            simulate_split(&path, cutter, &mut relief_slices(&path), budget_bytes, &progress, |_| {})
                .expect("simulates");
            let claimed = progress.claimed.load(std::sync::atomic::Ordering::Relaxed);
            assert_eq!(claimed, progress.released.load(std::sync::atomic::Ordering::Relaxed), "a core kept");
            let asked = progress.asked_from.lock().expect("not poisoned").len();
            asked
        };
        let ample = usize::MAX;
        assert_eq!(threads_asking(false, ample), 1, "no spare core: the calling thread alone");
        assert_eq!(threads_asking(true, ample), if threads() > 1 { 2 } else { 1 });
        let one_stock = relief_slices(&path).most_memory_bytes();
        assert_eq!(threads_asking(true, 2 * one_stock - 1), 1, "two stocks do not fit the budget");
    }
}
