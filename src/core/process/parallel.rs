//! Independent parts of a plan (candidates, layers) run side by side: scoped threads take
//! the parts in order from a shared counter, so a slow part does not hold up the others.
//! A computation runs on as many cores as its job is given: its own, and the spare ones it
//! claims ([`Progress::claim_spare_core`]) while they are free, so that jobs running
//! together share the machine's cores instead of each taking all of them (and their parts'
//! memory with them). Progress is the mean of the parts' own fractions; cancelling reaches
//! every part through its checkpoints.

use crate::core::progress::Progress;
use std::sync::atomic::{AtomicU64, AtomicUsize, Ordering};
use std::sync::Mutex;

/// The machine's cores: the most threads one computation runs on.
pub fn threads() -> usize {
    std::thread::available_parallelism().map_or(1, std::num::NonZeroUsize::get)
}

/// Cores claimed from a computation's progress beside the one it runs on, given back when
/// dropped.
pub struct ClaimedCores<'a> {
    progress: &'a dyn Progress,
    count: usize,
}

impl<'a> ClaimedCores<'a> {
    /// Claims up to `wanted` spare cores from `progress`, one at a time, while it gives
    /// them (and the machine has them: never more than [`threads`] − 1).
    pub fn claim(progress: &'a dyn Progress, wanted: usize) -> ClaimedCores<'a> {
        let mut claimed = ClaimedCores { progress, count: 0 };
        while claimed.count < wanted.min(threads().saturating_sub(1)) && progress.claim_spare_core() {
            claimed.count += 1;
        }
        claimed
    }

    /// No core claimed (of `progress`).
    pub fn none(progress: &'a dyn Progress) -> ClaimedCores<'a> {
        ClaimedCores { progress, count: 0 }
    }

    /// How many were claimed.
    pub fn count(&self) -> usize {
        self.count
    }

    /// The claimed cores one by one, each given back when it is dropped.
    pub fn one_by_one(mut self) -> impl Iterator<Item = ClaimedCores<'a>> {
        let (progress, count) = (self.progress, std::mem::take(&mut self.count));
        (0..count).map(move |_| ClaimedCores { progress, count: 1 })
    }
}

impl Drop for ClaimedCores<'_> {
    fn drop(&mut self) {
        for _ in 0..self.count {
            self.progress.release_core();
        }
    }
}

/// `f(index, item)` for each of `items`, on one thread and as many more as `progress` gives
/// spare cores for (see [`ClaimedCores`]; at most one thread per item); the results in
/// the order of `items`. Each thread beside the first gives its core back as soon as no
/// part is left for it to take. A panic in `f` is a panic here.
pub fn map<T: Sync, R: Send>(progress: &dyn Progress, items: &[T], f: impl Fn(usize, &T) -> R + Sync) -> Vec<R> {
    let claimed = ClaimedCores::claim(progress, items.len().saturating_sub(1));
    if claimed.count() == 0 {
        return items.iter().enumerate().map(|(i, t)| f(i, t)).collect();
    }
    let next = AtomicUsize::new(0);
    let slots: Vec<Mutex<Option<R>>> = items.iter().map(|_| Mutex::new(None)).collect();
    let work = |_core: ClaimedCores| loop {
        let i = next.fetch_add(1, Ordering::Relaxed);
        let Some(item) = items.get(i) else { break };
        let result = f(i, item);
        if let Ok(mut slot) = slots[i].lock() {
            *slot = Some(result);
        }
    };
    std::thread::scope(|scope| {
        for core in claimed.one_by_one() {
            scope.spawn(move || work(core));
        }
        work(ClaimedCores::none(progress));
    });
    slots.into_iter().filter_map(|s| s.into_inner().ok().flatten()).collect()
}

/// The progress of `count` parts run side by side, within `[from, from + span]` of `inner`:
/// the mean of the parts' fractions, never reported lower than before.
pub struct Shares<'a> {
    inner: &'a dyn Progress,
    from: f64,
    span: f64,
    /// Per part, its fraction (f64 bits).
    parts: Vec<AtomicU64>,
    /// The highest fraction reported; held while reporting, so that two parts never
    /// report out of order.
    reported: Mutex<f64>,
}

impl<'a> Shares<'a> {
    pub fn new(inner: &'a dyn Progress, from: f64, span: f64, count: usize) -> Self {
        Shares {
            inner,
            from,
            span,
            parts: (0..count.max(1)).map(|_| AtomicU64::new(0)).collect(),
            reported: Mutex::new(0.0),
        }
    }

    /// The progress of part `index`.
    pub fn part(&self, index: usize) -> Part<'_> {
        Part { shares: self, index }
    }
}

/// One part of [`Shares`].
pub struct Part<'s> {
    shares: &'s Shares<'s>,
    index: usize,
}

impl Progress for Part<'_> {
    fn report(&self, fraction: f64) {
        let s = self.shares;
        if let Some(slot) = s.parts.get(self.index) {
            slot.store(fraction.clamp(0.0, 1.0).to_bits(), Ordering::Relaxed);
        }
        let mean =
            s.parts.iter().map(|p| f64::from_bits(p.load(Ordering::Relaxed))).sum::<f64>() / s.parts.len() as f64;
        let mut reported = s.reported.lock().unwrap_or_else(|p| p.into_inner());
        if mean > *reported {
            *reported = mean;
            s.inner.report(s.from + mean * s.span);
        }
    }

    fn cancelled(&self) -> bool {
        self.shares.inner.cancelled()
    }

    fn claim_spare_core(&self) -> bool {
        self.shares.inner.claim_spare_core()
    }

    fn release_core(&self) {
        self.shares.inner.release_core()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::atomic::AtomicBool;

    struct Recorder {
        last: Mutex<Vec<f64>>,
        cancel: AtomicBool,
    }

    impl Progress for Recorder {
        fn report(&self, fraction: f64) {
            if let Ok(mut v) = self.last.lock() {
                v.push(fraction);
            }
        }
        fn cancelled(&self) -> bool {
            self.cancel.load(Ordering::Relaxed)
        }
    }

    #[test]
    fn parallel_results_come_back_in_the_order_of_the_items() {
        let items: Vec<u64> = (0..23).collect();
        let out = map(&crate::core::progress::NoProgress, &items, |i, x| {
            assert_eq!(i as u64, *x);
            (0..=*x).sum::<u64>()
        });
        assert_eq!(out, items.iter().map(|x| x * (x + 1) / 2).collect::<Vec<_>>());
    }

    #[test]
    fn the_progress_of_parts_is_their_mean_and_never_falls_and_cancelling_reaches_every_part() {
        let r = Recorder { last: Mutex::new(Vec::new()), cancel: AtomicBool::new(false) };
        let shares = Shares::new(&r, 0.5, 0.5, 2);
        shares.part(0).report(1.0);
        shares.part(1).report(0.5);
        shares.part(1).report(0.2);
        let seen = r.last.lock().unwrap().clone();
        assert_eq!(seen, vec![0.75, 0.875]);
        assert!(!shares.part(1).cancelled());
        r.cancel.store(true, Ordering::Relaxed);
        assert!(shares.part(0).checkpoint().is_err() && shares.part(1).checkpoint().is_err());
    }

    /// Progress that gives `free` spare cores, and records the threads its parts ran on.
    struct Cores {
        free: AtomicUsize,
        claimed: AtomicUsize,
        ran_on: Mutex<std::collections::HashSet<std::thread::ThreadId>>,
    }

    impl Progress for Cores {
        fn report(&self, _fraction: f64) {}
        fn cancelled(&self) -> bool {
            false
        }
        fn claim_spare_core(&self) -> bool {
            let taken = self.free.fetch_update(Ordering::Relaxed, Ordering::Relaxed, |n| n.checked_sub(1)).is_ok();
            self.claimed.fetch_add(usize::from(taken), Ordering::Relaxed);
            taken
        }
        fn release_core(&self) {
            self.free.fetch_add(1, Ordering::Relaxed);
        }
    }

    #[test]
    fn parts_run_on_no_more_threads_than_cores_are_given_and_every_core_is_given_back() {
        let items: Vec<u32> = (0..8).collect();
        for free in [0, 1, 5] {
            let cores =
                Cores { free: AtomicUsize::new(free), claimed: 0.into(), ran_on: Mutex::new(Default::default()) };
            let out = map(&cores, &items, |_, x| {
                cores.ran_on.lock().expect("not poisoned").insert(std::thread::current().id());
                // Long enough for every worker to take a part.
                std::thread::sleep(std::time::Duration::from_millis(5));
                x * 2
            });
            assert_eq!(out, items.iter().map(|x| x * 2).collect::<Vec<_>>());
            let claimed = cores.claimed.load(Ordering::Relaxed);
            assert_eq!(claimed, free.min(threads() - 1), "claimed with {free} free");
            assert!(cores.ran_on.lock().expect("not poisoned").len() <= 1 + claimed);
            assert_eq!(cores.free.load(Ordering::Relaxed), free, "every core given back");
        }
    }
}
