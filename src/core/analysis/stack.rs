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
//! same remembered capsule), so the simulation is the same as with a raster per slice.

use super::kept::{KeptSlice, KeptStock, Source};
use super::slices::{SliceStock, Z_CONTACT_EPS_MM};
use crate::core::stock::{Raster, Rect};
use crate::core::CoreError;

/// One z slice of the stock.
#[derive(Clone)]
pub struct Slice {
    pub z_bottom: f64,
    pub z_top: f64,
    /// Its own stock, or `None` while it holds exactly the cells of the slice below.
    own: Option<SliceStock>,
}

/// The slices of a layer, top first; the last always has its own stock.
#[derive(Clone)]
pub struct Stack {
    slices: Vec<Slice>,
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
            })
            .collect();
        slices[n - 1].own = Some(SliceStock::new(raster));
        Stack { slices }
    }

    /// Builds the slices between `levels` with material painted by `paint` (whose error it
    /// returns).
    pub fn build(
        levels: &[f64],
        bounds: Rect,
        cell_mm: f64,
        paint: impl FnOnce(&mut Raster) -> Result<(), CoreError>,
    ) -> Result<Stack, CoreError> {
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
    /// cells.
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

    /// Gives slice `k` its own copy of the stock it shares, if it shares one.
    pub fn separate(&mut self, k: usize) {
        if self.slices[k].own.is_none() {
            let copy = self.stock(k).clone();
            self.slices[k].own = Some(copy);
        }
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
            slices.push(Slice { z_top, z_bottom: levels.get(k + 1).copied().unwrap_or(0.0), own });
        }
        Ok(Stack { slices })
    }

    /// Memory the slices' rasters may come to, bytes: a raster each (as the budget
    /// counts them, see [`super::budget`]).
    pub fn most_memory_bytes(&self) -> usize {
        self.slices.len().saturating_mul(self.raster(self.len() - 1).memory_bytes())
    }

    /// Memory the slices' rasters take, bytes (a shared stock counts once).
    pub fn memory_bytes(&self) -> usize {
        self.slices.iter().filter_map(|s| s.own.as_ref()).map(|s| s.raster.memory_bytes()).sum()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::core::analysis::region::{paint, StockRegion};
    use crate::core::progress::NoProgress;

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
}
