//! Independent parts of a plan (candidates, layers) run on every core: scoped threads take
//! the parts in order from a shared counter, so a slow part does not hold up the others.
//! Progress is the mean of the parts' own fractions; cancelling reaches every part through
//! its checkpoints.

use crate::core::progress::Progress;
use std::sync::atomic::{AtomicU64, AtomicUsize, Ordering};
use std::sync::Mutex;

/// Threads a plan uses: one per core.
pub fn threads() -> usize {
    std::thread::available_parallelism().map_or(1, std::num::NonZeroUsize::get)
}

/// `f(index, item)` for each of `items`, on up to [`threads`] threads; the results in the
/// order of `items`. A panic in `f` is a panic here.
pub fn map<T: Sync, R: Send>(items: &[T], f: impl Fn(usize, &T) -> R + Sync) -> Vec<R> {
    let workers = threads().min(items.len());
    if workers <= 1 {
        return items.iter().enumerate().map(|(i, t)| f(i, t)).collect();
    }
    let next = AtomicUsize::new(0);
    let slots: Vec<Mutex<Option<R>>> = items.iter().map(|_| Mutex::new(None)).collect();
    std::thread::scope(|scope| {
        for _ in 0..workers {
            scope.spawn(|| loop {
                let i = next.fetch_add(1, Ordering::Relaxed);
                let Some(item) = items.get(i) else { break };
                let result = f(i, item);
                if let Ok(mut slot) = slots[i].lock() {
                    *slot = Some(result);
                }
            });
        }
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
        let out = map(&items, |i, x| {
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
}
