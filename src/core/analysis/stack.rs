//! The slices of a layer's stock, top first, with the stock of slices that are still alike
//! held once.
//!
//! Every slice starts as the same raster, and each update removes material from a run of
//! slices from the top (see [`super::slices`]). So until an update cuts a slice but not the
//! one below it, the two hold exactly the same cells, and the upper one shares the lower
//! one's stock instead of keeping a copy: an update that cuts both is applied once. Where a
//! slot is cut to full depth in one pass, as most of a trochoid program is, the slices of
//! its z-cut passes are all one stock until those passes reach them. A slice gets its own
//! copy ([`Stack::separate`]) just before the first update that cuts it and not the slice
//! below; a copy behaves exactly as the stock it was taken from (same cells, same versions,
//! same remembered capsule), so the simulation is the same as with a raster per slice. A
//! slice cut apart shares the stock below again once no probe can tell the two apart
//! ([`Stack::rejoin_when_alike`]): they may differ only in the stale distances of air with
//! no material beside it, which no probe reads, so every sample is still the same. (The
//! stock kept for a later job then holds the lower slice's stale distances in those cells.)

use super::kept::{KeptSlice, KeptStock, Source};
use super::slices::{SliceStock, Z_CONTACT_EPS_MM};
use crate::core::stock::{Raster, WriteMark};

/// One z slice of the stock.
pub struct Slice {
    pub z_bottom: f64,
    pub z_top: f64,
    /// Its own stock, or `None` while it holds exactly the cells of the slice below (or
    /// cells no probe tells from them, see [`Stack::rejoin_when_alike`]).
    own: Option<SliceStock>,
    /// Numbers its own stock among the stocks the stack's slices were given (see [`Spare`]).
    birth: u64,
    /// When its own stock is next compared with the one below.
    rejoin: RejoinTries,
    /// While it shares the stock below: the stock it held, to be cut apart again.
    spare: Option<Spare>,
}

impl Clone for Slice {
    /// Without its spare stock, which only spares work.
    fn clone(&self) -> Slice {
        let Slice { z_bottom, z_top, own, birth, rejoin, spare: _ } = self;
        Slice { z_bottom: *z_bottom, z_top: *z_top, own: own.clone(), birth: *birth, rejoin: *rejoin, spare: None }
    }
}

/// The stock a slice held when it shared the stock below again: cells no probe tells from
/// the shared stock's. When the slice is cut apart again while the same stock is shared,
/// only the blocks written to the shared stock since are copied into it
/// ([`SliceStock::copy_from`]), not the whole raster: along a trochoid program a slice is
/// cut apart and joined again dozens of times, its loops writing a few blocks in between.
struct Spare {
    stock: SliceStock,
    /// The slice whose stock was shared, and that stock's birth.
    holder: usize,
    holder_birth: u64,
    /// The shared stock's writes when it was shared again.
    mark: WriteMark,
}

/// After a comparison of a slice's own stock with the one below failed, this many updates
/// that cut both pass before the next comparison, the wait doubling after each failure up
/// to [`MAX_REJOIN_WAIT`]. (**Assumed**: a comparison mostly stops at the material counts
/// per block, a hundredth of an update's work; one that reads every cell, where the counts
/// agree and a cell tells the two apart, costs about as much as two updates of the slot
/// box's trochoid loops, and more on a larger raster.)
pub const FIRST_REJOIN_WAIT: u32 = 1;
/// The longest wait between two comparisons of a slice with the one below, updates.
pub const MAX_REJOIN_WAIT: u32 = 32;

/// The comparisons of a slice's own stock with the one below.
#[derive(Debug, Clone, Copy, Default)]
struct RejoinTries {
    /// Updates still to go before the next comparison.
    wait: u32,
    /// The wait after the next comparison that fails.
    next_wait: u32,
}

/// The slices of a layer, top first; the last always has its own stock.
#[derive(Clone)]
pub struct Stack {
    slices: Vec<Slice>,
    /// Stocks given to slices so far (see [`Slice::birth`]).
    births: u64,
    /// Tests compare simulations with and without a slice cut apart again taking the cells
    /// written since it was joined alone, and count how often it did.
    #[cfg(test)]
    pub(crate) full_copies: bool,
    #[cfg(test)]
    caught_up: usize,
    /// Tests compare simulations with and without slices sharing a stock again.
    #[cfg(test)]
    pub(crate) never_rejoin: bool,
}

impl std::fmt::Debug for Stack {
    /// The slices' z ranges and the memory they take (not their cells).
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let ranges: Vec<(f64, f64)> = self.slices.iter().map(|s| (s.z_top, s.z_bottom)).collect();
        f.debug_struct("Stack").field("slices", &ranges).field("memory_bytes", &self.memory_bytes()).finish()
    }
}

impl Stack {
    /// The slices between consecutive `levels` (top first, at least two), all holding the
    /// material of `raster`.
    pub fn new(levels: &[f64], raster: Raster) -> Stack {
        let n = levels.len().saturating_sub(1).max(1);
        let mut slices: Vec<Slice> = (0..n)
            .map(|k| Slice {
                z_top: levels.get(k).copied().unwrap_or(0.0),
                z_bottom: levels.get(k + 1).copied().unwrap_or(0.0),
                own: None,
                birth: 0,
                rejoin: RejoinTries::default(),
                spare: None,
            })
            .collect();
        slices[n - 1].own = Some(SliceStock::new(raster));
        Stack {
            slices,
            births: 0,
            #[cfg(test)]
            full_copies: false,
            #[cfg(test)]
            caught_up: 0,
            #[cfg(test)]
            never_rejoin: false,
        }
    }

    /// Builds the slices between `levels` with material painted by `paint` (whose error it
    /// returns): the tests' stocks (an analysis paints its stock through
    /// [`super::painted::painted`]).
    #[cfg(test)]
    pub fn build(
        levels: &[f64],
        bounds: crate::core::stock::Rect,
        cell_mm: f64,
        paint: impl FnOnce(&mut Raster) -> Result<(), crate::core::CoreError>,
    ) -> Result<Stack, crate::core::CoreError> {
        let mut raster = Raster::new(bounds, cell_mm);
        paint(&mut raster)?;
        Ok(Stack::new(levels, raster))
    }

    /// The slices' z ranges, top first.
    pub fn slices(&self) -> &[Slice] {
        &self.slices
    }

    pub fn len(&self) -> usize {
        self.slices.len()
    }

    pub fn is_empty(&self) -> bool {
        self.slices.is_empty()
    }

    /// How many slices (from the top) a tool tip at `z` cuts.
    pub fn cut_at(&self, z: f64) -> usize {
        self.slices.iter().take_while(|s| z < s.z_top - Z_CONTACT_EPS_MM).count()
    }

    /// The slice whose stock slice `k` holds: `k` itself or the first below it with its own.
    fn holder(&self, k: usize) -> usize {
        (k..self.slices.len()).find(|&i| self.slices[i].own.is_some()).unwrap_or(self.slices.len() - 1)
    }

    /// `true` while slice `k` shares the stock of the slice below it: the two hold the same
    /// cells (or cells no probe tells apart, see [`Stack::rejoin_when_alike`]).
    pub fn alike_below(&self, k: usize) -> bool {
        self.slices[k].own.is_none()
    }

    /// The stock slice `k` holds.
    pub fn stock(&self, k: usize) -> &SliceStock {
        let holder = self.holder(k);
        self.slices[holder].own.as_ref().expect("the holder has its own stock")
    }

    /// The stock slice `k` holds, to remember what it finds in it (shared with the slices
    /// it is alike with: what it finds holds for them too). Changing its cells changes
    /// theirs: an update of slice `k` alone goes through [`Stack::own`].
    pub fn stock_mut(&mut self, k: usize) -> &mut SliceStock {
        let holder = self.holder(k);
        self.slices[holder].own.as_mut().expect("the holder has its own stock")
    }

    /// The raster of slice `k`.
    pub fn raster(&self, k: usize) -> &Raster {
        &self.stock(k).raster
    }

    /// The area of material of each slice, mm² ([`Raster::material_area_fine_mm2`]), read
    /// once for slices that share one stock.
    pub fn material_areas_fine_mm2(&self) -> Vec<f64> {
        let mut areas = vec![0.0; self.slices.len()];
        for k in (0..self.slices.len()).rev() {
            areas[k] = match self.slices[k].own.as_ref() {
                Some(own) => own.raster.material_area_fine_mm2(),
                // Alike with the slice below: its stock, whose area is found already.
                None => areas.get(k + 1).copied().unwrap_or_else(|| self.raster(k).material_area_fine_mm2()),
            };
        }
        areas
    }

    /// Gives slice `k` its own copy of the stock it shares, if it shares one: into its
    /// spare stock, if it has one, and of the blocks written since alone where the spare
    /// was taken from the same stock (see [`Spare`]).
    pub fn separate(&mut self, k: usize) {
        if self.slices[k].own.is_some() {
            return;
        }
        let holder = self.holder(k);
        let spare = self.slices[k].spare.take();
        let source = self.slices[holder].own.as_ref().expect("the holder has its own stock");
        let copy = match spare {
            Some(mut spare) => {
                let same = spare.holder == holder && spare.holder_birth == self.slices[holder].birth;
                #[cfg(test)]
                let same = same && !self.full_copies;
                #[cfg(test)]
                {
                    self.caught_up += usize::from(same);
                }
                spare.stock.copy_from(source, same.then_some(spare.mark));
                spare.stock
            }
            None => source.clone(),
        };
        self.births += 1;
        self.slices[k].birth = self.births;
        self.slices[k].own = Some(copy);
    }

    /// Makes slice `k` (not the last) share the stock of the slice below again when no probe
    /// can tell the two stocks apart ([`Raster::probes_alike`]): an update that cuts both is
    /// then applied once, and the simulation goes on exactly as with the two. A slice is
    /// cut apart where a ramp or a z-cut pass reaches it before the slice below, and most
    /// often the passes that follow down to the one below leave the two alike again (a
    /// trochoid program's approach helix keeps its four slices apart for the whole program
    /// otherwise). After a comparison failed, the next calls wait ([`FIRST_REJOIN_WAIT`]
    /// of them, doubling up to [`MAX_REJOIN_WAIT`]), so that slices apart for long cost
    /// little. Returns `true` when the slice shares the stock below.
    pub fn rejoin_when_alike(&mut self, k: usize) -> bool {
        if self.alike_below(k) {
            return true;
        }
        #[cfg(test)]
        if self.never_rejoin {
            return false;
        }
        let tries = &mut self.slices[k].rejoin;
        if tries.wait > 0 {
            tries.wait -= 1;
            return false;
        }
        let (upper, lower) = (self.raster(k), self.raster(k + 1));

        if !upper.probes_alike(lower) {
            let tries = &mut self.slices[k].rejoin;
            tries.wait = tries.next_wait.max(FIRST_REJOIN_WAIT);
            tries.next_wait = (tries.wait * 2).min(MAX_REJOIN_WAIT);
            return false;
        }
        let upper_version = upper.version();
        let holder = self.holder(k + 1);
        let shared = self.slices[holder].own.as_mut().expect("the holder has its own stock");
        let mark = shared.raster.mark_writes();
        let holder_birth = self.slices[holder].birth;
        let stock = self.slices[k].own.take().expect("a slice not alike with the one below has its own stock");
        self.slices[k].spare = Some(Spare { stock, holder, holder_birth, mark });
        self.slices[k].rejoin = RejoinTries::default();
        // What was read from either stock (kept with its version) is read again.
        self.stock_mut(k).raster.take_version_past(upper_version);
        true
    }

    /// Slice `k`'s own stock, separated from the slices below first.
    pub fn own(&mut self, k: usize) -> &mut SliceStock {
        self.separate(k);
        self.slices[k].own.as_mut().expect("separated")
    }

    /// The stock the slices hold now, kept as plain data: each shared raster once.
    /// `cavity` says the stock was a pocket's (see [`KeptStock::cavity`]).
    pub fn keep(&self, cavity: bool) -> KeptStock {
        let mut rasters: Vec<Vec<i8>> = Vec::new();
        let slices = self
            .slices
            .iter()
            .enumerate()
            .map(|(k, s)| {
                if k == 0 || self.slices[k - 1].own.is_some() {
                    // The first slice of a run sharing one raster: the run's raster.
                    rasters.push(Vec::new());
                }
                KeptSlice { z_top: s.z_top, z_bottom: s.z_bottom, raster: rasters.len() - 1 }
            })
            .collect::<Vec<_>>();
        // A run's raster is its last slice's, the one that owns it.
        for (k, s) in slices.iter().enumerate() {
            if self.slices[k].own.is_some() {
                rasters[s.raster] = self.raster(k).cells().to_vec();
            }
        }
        KeptStock { grid: self.raster(self.len() - 1).layout_grid(), slices, rasters, cavity, below: None }
    }

    /// The slices between `levels` (top first, at least two) holding the material of
    /// `kept`, mapped onto them as [`super::kept`] says (the footprint under it for slices
    /// that reach below it); slices that hold one kept raster share it. `Err` when a kept
    /// raster does not fit its grid, or a slice reaches below a stock that does not know
    /// what lies there.
    pub fn carried(levels: &[f64], kept: &KeptStock) -> Result<Stack, String> {
        let n = levels.len().saturating_sub(1).max(1);
        let held: Vec<Source> = (0..n)
            .map(|k| {
                let top = levels.get(k).copied().unwrap_or(0.0);
                kept.source_for(top, levels.get(k + 1).copied().unwrap_or(top))
            })
            .collect::<Result<_, _>>()?;
        let mut slices = Vec::with_capacity(n);
        for (k, &source) in held.iter().enumerate() {
            let owner = held.get(k + 1) != Some(&source);
            let own = match owner {
                true => Some(SliceStock::new(Raster::from_cells(kept.grid, kept.cells(source).into_owned())?)),
                false => None,
            };
            let z_top = levels.get(k).copied().unwrap_or(0.0);
            let z_bottom = levels.get(k + 1).copied().unwrap_or(0.0);
            slices.push(Slice { z_top, z_bottom, own, birth: 0, rejoin: RejoinTries::default(), spare: None });
        }
        Ok(Stack {
            slices,
            births: 0,
            #[cfg(test)]
            full_copies: false,
            #[cfg(test)]
            caught_up: 0,
            #[cfg(test)]
            never_rejoin: false,
        })
    }

    /// Memory the slices' rasters may come to, bytes: a raster each (as the budget
    /// counts them, see [`super::budget`]).
    pub fn most_memory_bytes(&self) -> usize {
        self.slices.len().saturating_mul(self.raster(self.len() - 1).memory_bytes())
    }

    /// Memory the slices' rasters take, bytes (a shared stock counts once), with the spare
    /// stocks of slices that share one (at most a raster per slice in all).
    pub fn memory_bytes(&self) -> usize {
        let stocks = self.slices.iter().filter_map(|s| s.own.as_ref().or(s.spare.as_ref().map(|spare| &spare.stock)));
        stocks.map(|s| s.raster.memory_bytes()).sum()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::core::analysis::engine::simulate;
    use crate::core::analysis::region::{paint, StockRegion};
    use crate::core::analysis::test_paths::{feed_move, relief_cutter, sample_bits};
    use crate::core::progress::NoProgress;
    use crate::core::stock::Rect;
    use crate::core::toolpath::{Toolpath, Units, P3};

    fn block() -> Stack {
        let rect = Rect { x_min: 0.0, y_min: 0.0, x_max: 20.0, y_max: 20.0 };
        Stack::build(&[0.0, -2.0, -4.0, -6.0], rect, 0.1, |raster| {
            paint(raster, &[StockRegion::Rect(rect)], &[], &NoProgress)
        })
        .expect("nothing cancels the painting")
    }

    #[test]
    fn slices_start_as_one_stock_and_a_slice_cut_apart_gets_its_own() {
        let mut stack = block();
        assert_eq!(stack.len(), 3);
        assert!(stack.alike_below(0) && stack.alike_below(1) && !stack.alike_below(2));
        let one = stack.memory_bytes();
        // A cut through the top slice alone.
        stack.own(0).raster.clear_capsule((5.0, 10.0), (15.0, 10.0), 2.0);
        assert!(!stack.alike_below(0) && stack.alike_below(1));
        assert_eq!(stack.memory_bytes(), 2 * one);
        assert!(!stack.raster(0).is_material(10.0, 10.0));
        assert!(stack.raster(1).is_material(10.0, 10.0) && stack.raster(2).is_material(10.0, 10.0));
    }

    #[test]
    fn a_slice_sharing_the_stock_below_sees_every_change_to_it() {
        let mut stack = block();
        stack.own(2).raster.clear_capsule((5.0, 5.0), (5.0, 5.0), 2.0);
        assert!(!stack.raster(0).is_material(5.0, 5.0) && !stack.raster(1).is_material(5.0, 5.0));
        assert_eq!(stack.raster(0).version(), stack.raster(2).version());
    }

    #[test]
    fn the_cut_counts_the_slices_above_the_tip() {
        let stack = block();
        assert_eq!(stack.cut_at(1.0), 0);
        assert_eq!(stack.cut_at(-1.0), 1);
        assert_eq!(stack.cut_at(-2.0), 1);
        assert_eq!(stack.cut_at(-5.0), 3);
    }

    /// A ramp down through the block's slices along y = 10, back up, a pass at full depth
    /// along the same line (which leaves the slices the ramp cut apart alike again), then
    /// passes at full depth across the block.
    fn ramp_then_passes() -> Toolpath {
        let mut moves = Vec::new();
        let mut at = P3::new(-3.0, 10.0, 0.0);
        let ends = [
            P3::new(15.0, 10.0, -5.5),
            P3::new(23.0, 10.0, -5.5),
            P3::new(23.0, 10.0, 1.0),
            P3::new(-3.0, 10.0, 1.0),
            P3::new(-3.0, 10.0, -5.5),
            P3::new(23.0, 10.0, -5.5),
            P3::new(23.0, 14.0, -5.5),
            P3::new(-3.0, 14.0, -5.5),
            P3::new(-3.0, 18.0, -5.5),
            P3::new(23.0, 18.0, -5.5),
        ];
        for end in ends {
            moves.push(feed_move(at, end, moves.len()));
            at = end;
        }
        Toolpath { moves, events: vec![], source_units: Units::Mm, warnings: vec![] }
    }

    #[test]
    fn slices_a_ramp_cut_apart_share_one_stock_again_once_alike_and_every_sample_is_the_same() {
        let path = ramp_then_passes();
        let cutter = relief_cutter(Some(crate::core::fixtures::seed_001_ten_mm()));
        let run = |rejoin: bool| {
            let mut stack = block();
            stack.never_rejoin = !rejoin;
            let mut samples = Vec::new();
            simulate(&path, cutter, &mut stack, &NoProgress, |r| samples.push(sample_bits(r))).expect("simulates");
            (samples, stack)
        };
        let ((joined, rejoined), (apart, separate)) = (run(true), run(false));
        assert!(joined == apart, "a sample differs where slices share a stock again");
        assert!((0..separate.len() - 1).all(|k| !separate.alike_below(k)), "the ramp left a slice alike");
        assert!((0..rejoined.len() - 1).all(|k| rejoined.alike_below(k)), "a slice kept a stock of its own");
        for k in 0..separate.len() {
            assert!(rejoined.raster(k).probes_alike(separate.raster(k)), "slice {k} holds another stock");
        }
    }

    /// Ramps down through the block's slices along three lines, each followed by a pass at
    /// full depth along it: each ramp cuts the slices apart, each pass joins them again.
    fn ramps_and_passes() -> Toolpath {
        let mut moves = Vec::new();
        let mut at = P3::new(-3.0, 4.0, 1.0);
        for y in [4.0, 9.0, 14.0] {
            let ends = [
                P3::new(-3.0, y, 1.0),
                P3::new(15.0, y, -5.5),
                P3::new(23.0, y, -5.5),
                P3::new(23.0, y, 1.0),
                P3::new(-3.0, y, 1.0),
                P3::new(-3.0, y, -5.5),
                P3::new(23.0, y, -5.5),
                P3::new(23.0, y, 1.0),
            ];
            for end in ends {
                moves.push(feed_move(at, end, moves.len()));
                at = end;
            }
        }
        Toolpath { moves, events: vec![], source_units: Units::Mm, warnings: vec![] }
    }

    #[test]
    fn a_slice_cut_apart_again_takes_the_blocks_written_since_it_was_joined_and_every_sample_is_the_same() {
        let path = ramps_and_passes();
        let cutter = relief_cutter(Some(crate::core::fixtures::seed_001_ten_mm()));
        let run = |full_copies: bool| {
            let mut stack = block();
            stack.full_copies = full_copies;
            let mut samples = Vec::new();
            simulate(&path, cutter, &mut stack, &NoProgress, |r| samples.push(sample_bits(r))).expect("simulates");
            (samples, stack)
        };
        let ((caught_up, stack), (copied, full)) = (run(false), run(true));
        assert!(stack.caught_up >= 2 && full.caught_up == 0, "{} slices caught up", stack.caught_up);
        assert!(caught_up == copied, "a sample differs where slices cut apart again take the blocks written");
        for k in 0..stack.len() {
            assert!(stack.raster(k).probes_alike(full.raster(k)), "slice {k} holds another stock");
        }
    }
}
