//! A simulation whose samples are used on another core: [`analyze_handing_off`] runs the
//! simulation on the calling thread and hands its samples, in order and in batches, to a
//! consumer on a thread of its own. What a caller does with each sample (sorting it,
//! keeping it for a drawing, counting wear) then runs beside the simulation instead of
//! after each sample of it; the consumer sees every sample exactly as a sink of
//! [`super::analyze_from`] would, in the same order, so nothing it computes changes.

use super::engine::SampleResult;
use super::{analyze_split, Analysis, AnalysisSpec, Stack};
use crate::core::progress::Progress;
use crate::core::toolpath::Toolpath;
use crate::core::CoreError;
use std::sync::mpsc::{sync_channel, Receiver, SyncSender};

/// Samples handed over at a time: large enough that the hand-over costs little per
/// sample, small enough that the consumer starts early and a batch stays in cache.
pub const HANDOFF_BATCH_SAMPLES: usize = 512;

/// Batches that may wait for the consumer before the simulation waits for it.
pub const HANDOFF_QUEUED_BATCHES: usize = 8;

/// Fills batches of samples and sends each one full to the consumer.
struct Batcher {
    batch: Vec<SampleResult>,
    to_consumer: SyncSender<Vec<SampleResult>>,
    /// The consumer stopped (it panicked): the rest of the samples are dropped, and its
    /// panic is raised when it is joined.
    consumer_gone: bool,
}

impl Batcher {
    /// Adds `sample` to the batch, sending the batch when it is full.
    fn add(&mut self, sample: &SampleResult) {
        self.batch.push(*sample);
        if self.batch.len() == HANDOFF_BATCH_SAMPLES {
            self.send();
        }
    }

    /// Sends the batch (if it holds any sample) and starts a new one.
    fn send(&mut self) {
        if self.batch.is_empty() || self.consumer_gone {
            self.batch.clear();
            return;
        }
        let full = std::mem::replace(&mut self.batch, Vec::with_capacity(HANDOFF_BATCH_SAMPLES));
        self.consumer_gone = self.to_consumer.send(full).is_err();
    }
}

/// Hands every sample of every batch received, in order, to `consume`, until the sender
/// is dropped.
fn consume_all(from_simulation: &Receiver<Vec<SampleResult>>, consume: &mut impl FnMut(&SampleResult)) {
    for batch in from_simulation.iter() {
        batch.iter().for_each(&mut *consume);
    }
}

/// [`analyze_split`] (on a second core when one is spare), handing every sample to `consume` on another thread, in the order of the simulation;
/// returns when `consume` has seen them all. A panic of `consume` is raised here.
pub fn analyze_handing_off(
    path: &Toolpath,
    spec: &AnalysisSpec,
    progress: &dyn Progress,
    mut consume: impl FnMut(&SampleResult) + Send,
) -> Result<(Analysis, Stack), CoreError> {
    let (to_consumer, from_simulation) = sync_channel(HANDOFF_QUEUED_BATCHES);
    std::thread::scope(|scope| {
        let consumer = scope.spawn(move || consume_all(&from_simulation, &mut consume));
        let mut batcher =
            Batcher { batch: Vec::with_capacity(HANDOFF_BATCH_SAMPLES), to_consumer, consumer_gone: false };
        let simulated = analyze_split(path, spec, progress, |r| batcher.add(r));
        batcher.send();
        // Dropping the sender ends the consumer's loop once it has taken every batch.
        drop(batcher);
        consumer.join().unwrap_or_else(|panic| std::panic::resume_unwind(panic));
        simulated
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::core::analysis::test_paths::{feed_move, sample_bits};
    use crate::core::analysis::{analyze_with, StockRegion};
    use crate::core::progress::NoProgress;
    use crate::core::stock::Rect;
    use crate::core::tool::{EndMill, ToolType};
    use crate::core::toolpath::{Units, P3};

    /// A zig-zag of `passes` slots across a 30 × 30 mm block, each ending where the next
    /// starts: enough samples for several batches.
    fn zig_zag(passes: u32) -> Toolpath {
        let mut moves = Vec::new();
        let mut at = P3::new(-6.0, 2.0, -2.0);
        for pass in 0..passes {
            let y = 2.0 + 3.0 * f64::from(pass);
            let x_end = if pass % 2 == 0 { 36.0 } else { -6.0 };
            for end in [P3::new(at.x, y, -2.0), P3::new(x_end, y, -2.0)] {
                moves.push(feed_move(at, end, moves.len()));
                at = end;
            }
        }
        Toolpath { moves, events: vec![], source_units: Units::Mm, warnings: vec![] }
    }

    /// A 6 mm square end mill in a 30 × 30 × 5 mm block.
    fn block_spec() -> AnalysisSpec {
        let block = Rect { x_min: 0.0, y_min: 0.0, x_max: 30.0, y_max: 30.0 };
        let tool = EndMill { tool_type: ToolType::Square, diameter_mm: 6.0, flutes: 4, corner_radius_mm: 0.0 };
        AnalysisSpec::new(tool, vec![StockRegion::Rect(block)], 0.0, -5.0)
    }

    #[test]
    fn the_consumer_sees_every_sample_of_the_simulation_in_its_order_and_the_summary_is_the_same() {
        // Passes enough for the simulation to be split over two threads too.
        let (path, spec) = (zig_zag(30), block_spec());
        let mut direct = Vec::new();
        let alone = analyze_with(&path, &spec, &NoProgress, |r| direct.push(sample_bits(r))).expect("simulates");
        assert!(direct.len() > crate::core::analysis::split::MIN_SPLIT_SAMPLES, "only {} samples", direct.len());
        let mut handed = Vec::new();
        let (beside, _) =
            analyze_handing_off(&path, &spec, &NoProgress, |r| handed.push(sample_bits(r))).expect("simulates");
        assert!(handed == direct, "the samples handed off differ from the simulation's");
        assert_eq!(alone, beside);
    }

    #[test]
    fn a_panic_of_the_consumer_is_raised_by_the_simulation() {
        let (path, spec) = (zig_zag(3), block_spec());
        let outcome = std::panic::catch_unwind(|| {
            let mut seen = 0;
            analyze_handing_off(&path, &spec, &NoProgress, |_| {
                seen += 1;
                assert!(seen < HANDOFF_BATCH_SAMPLES / 2, "the consumer fails");
            })
        });
        assert!(outcome.is_err(), "the consumer's panic was lost");
    }
}
