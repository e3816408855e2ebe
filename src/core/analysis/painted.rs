//! Painted stocks kept from one analysis to the next. A trochoid job paints its pocket three
//! times over: for the base path's check, for the verification of the finished path, and
//! for the footprint of the stock it keeps (each about 3.4 ms of the slot box's 730 000
//! cells, on a core the verification needs); a plan paints one pocket for every candidate.
//! The same regions on the same grid always paint the same cells, so a raster painted once
//! is kept, and a later painting of the same stock is a copy of it. Rasters are kept up to
//! [`MAX_PAINTED_BYTES`], the most recently painted or used first, so an idle service holds
//! at most that much.

use super::region::{paint, StockRegion};
use crate::core::geometry::Loop;
use crate::core::progress::Progress;
use crate::core::stock::{Raster, Rect};
use crate::core::CoreError;
use std::sync::{Mutex, MutexGuard};

/// Most cell memory the kept rasters take, bytes (**assumed**: some forty pockets the size
/// of the slot box at its default cell; a stock larger than this is painted every time).
pub const MAX_PAINTED_BYTES: usize = 32 << 20;

/// A painted stock and what it was painted from.
struct Kept {
    key: Vec<u64>,
    raster: Raster,
}

/// The rasters kept, the most recently painted or used last.
static KEPT: Mutex<Vec<Kept>> = Mutex::new(Vec::new());

/// The rasters kept, locked.
fn kept() -> MutexGuard<'static, Vec<Kept>> {
    // Rasters are kept whole or not at all: a panic elsewhere leaves none half made.
    KEPT.lock().unwrap_or_else(|poisoned| poisoned.into_inner())
}

/// A raster over `bounds` with cells of `cell_mm`, `stock` painted in as material and `open`
/// cleared, as [`paint`] paints it (reporting to `progress`, and stopping when it is
/// cancelled): a copy of the same stock painted before, when one is kept.
pub fn painted(
    bounds: Rect,
    cell_mm: f64,
    stock: &[StockRegion],
    open: &[StockRegion],
    progress: &dyn Progress,
) -> Result<Raster, CoreError> {
    let key = key_of(bounds, cell_mm, stock, open);
    let found = {
        let mut kept = kept();
        kept.iter().position(|k| k.key == key).map(|at| {
            let entry = kept.remove(at);
            let raster = entry.raster.clone();
            kept.push(entry);
            raster
        })
    };
    if let Some(raster) = found {
        progress.report(1.0);
        return Ok(raster);
    }
    let mut raster = Raster::new(bounds, cell_mm);
    paint(&mut raster, stock, open, progress)?;
    keep(key, &raster);
    Ok(raster)
}

/// Keeps a copy of `raster`, painted from `key`, letting the least recently used go beyond
/// [`MAX_PAINTED_BYTES`].
fn keep(key: Vec<u64>, raster: &Raster) {
    if raster.memory_bytes() > MAX_PAINTED_BYTES {
        return;
    }
    let mut kept = kept();
    // (Two analyses may paint one stock at once: it is kept once.)
    if kept.iter().any(|k| k.key == key) {
        return;
    }
    kept.push(Kept { key, raster: raster.clone() });
    let mut bytes: usize = kept.iter().map(|k| k.raster.memory_bytes()).sum();
    while bytes > MAX_PAINTED_BYTES {
        bytes -= kept.remove(0).raster.memory_bytes();
    }
}

/// What a painting depends on, as the bits of every number: the grid, then each region of
/// `stock` and of `open` (a tag, then its numbers). Equal keys paint equal cells.
fn key_of(bounds: Rect, cell_mm: f64, stock: &[StockRegion], open: &[StockRegion]) -> Vec<u64> {
    let mut key: Vec<u64> =
        [bounds.x_min, bounds.y_min, bounds.x_max, bounds.y_max, cell_mm].iter().map(|v| v.to_bits()).collect();
    for (list, regions) in [(0, stock), (1, open)] {
        key.extend([list, regions.len() as u64]);
        for region in regions {
            push_region(&mut key, region);
        }
    }
    key
}

/// Tags of the regions in a key.
const RECT_TAG: u64 = 1;
const CIRCLE_TAG: u64 = 2;
const POCKET_TAG: u64 = 3;

/// Appends `region`'s tag and numbers to `key`.
fn push_region(key: &mut Vec<u64>, region: &StockRegion) {
    let numbers = |key: &mut Vec<u64>, values: &[f64]| key.extend(values.iter().map(|v| v.to_bits()));
    match region {
        StockRegion::Rect(r) => {
            key.push(RECT_TAG);
            numbers(key, &[r.x_min, r.y_min, r.x_max, r.y_max]);
        }
        StockRegion::Circle { cx, cy, r } => {
            key.push(CIRCLE_TAG);
            numbers(key, &[*cx, *cy, *r]);
        }
        StockRegion::Pocket(p) => {
            key.extend([POCKET_TAG, p.islands.len() as u64]);
            for lp in std::iter::once(&p.outer).chain(&p.islands) {
                push_loop(key, lp);
            }
        }
    }
}

/// Appends the vertex count and every vertex of `lp` to `key`.
fn push_loop(key: &mut Vec<u64>, lp: &Loop) {
    key.push(lp.vertices.len() as u64);
    for v in &lp.vertices {
        key.extend([v.x.to_bits(), v.y.to_bits(), v.bulge.to_bits()]);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::core::geometry::{Pocket, Vertex};
    use crate::core::progress::NoProgress;

    fn pocket(side: f64) -> StockRegion {
        let v = |x: f64, y: f64| Vertex { x, y, bulge: 0.0 };
        let outer = Loop::new(vec![v(0.0, 0.0), v(side, 0.0), v(side, side), v(0.0, side)]);
        StockRegion::Pocket(Pocket { outer, islands: Vec::new() })
    }

    fn fresh(bounds: Rect, cell_mm: f64, stock: &[StockRegion], open: &[StockRegion]) -> Raster {
        let mut raster = Raster::new(bounds, cell_mm);
        paint(&mut raster, stock, open, &NoProgress).expect("nothing cancels the painting");
        raster
    }

    #[test]
    fn a_stock_painted_again_is_cell_for_cell_the_stock_painted_fresh() {
        let bounds = Rect { x_min: 0.0, y_min: 0.0, x_max: 31.0, y_max: 31.0 };
        let hole = [StockRegion::Circle { cx: 15.0, cy: 15.0, r: 4.0 }];
        for _ in 0..2 {
            let again = painted(bounds, 0.1, &[pocket(31.0)], &hole, &NoProgress).expect("painted");
            assert!(again.cells() == fresh(bounds, 0.1, &[pocket(31.0)], &hole).cells());
            assert_eq!(again.version(), fresh(bounds, 0.1, &[pocket(31.0)], &hole).version());
        }
    }

    #[test]
    fn another_grid_or_region_is_painted_for_itself() {
        let bounds = Rect { x_min: 0.0, y_min: 0.0, x_max: 33.0, y_max: 33.0 };
        let first = painted(bounds, 0.1, &[pocket(33.0)], &[], &NoProgress).expect("painted");
        let smaller = painted(bounds, 0.1, &[pocket(32.0)], &[], &NoProgress).expect("painted");
        assert!(smaller.cells() == fresh(bounds, 0.1, &[pocket(32.0)], &[]).cells());
        assert!(smaller.cells() != first.cells(), "a smaller pocket painted as the larger");
        let finer = painted(bounds, 0.05, &[pocket(33.0)], &[], &NoProgress).expect("painted");
        assert_eq!(finer.size(), fresh(bounds, 0.05, &[pocket(33.0)], &[]).size());
        let opened = [StockRegion::Rect(Rect { x_min: 5.0, y_min: 5.0, x_max: 9.0, y_max: 9.0 })];
        let cleared = painted(bounds, 0.1, &[pocket(33.0)], &opened, &NoProgress).expect("painted");
        assert!(cleared.cells() == fresh(bounds, 0.1, &[pocket(33.0)], &opened).cells());
        // The same region listed as open, not as stock, is another painting.
        assert_ne!(key_of(bounds, 0.1, &[], &[pocket(33.0)]), key_of(bounds, 0.1, &[pocket(33.0)], &[]));
    }

    #[test]
    fn no_more_than_the_limit_is_kept() {
        let big = Rect { x_min: 0.0, y_min: 0.0, x_max: 1000.0, y_max: 1000.0 };
        for k in 0..4 {
            let square = [StockRegion::Rect(Rect { x_max: 900.0 + f64::from(k), ..big })];
            painted(big, 0.25, &square, &[], &NoProgress).expect("painted");
        }
        let bytes: usize = kept().iter().map(|k| k.raster.memory_bytes()).sum();
        assert!(bytes <= MAX_PAINTED_BYTES, "{bytes} bytes kept");
    }

    /// Progress cancelled from the start.
    struct Cancelled;

    impl Progress for Cancelled {
        fn report(&self, _fraction: f64) {}
        fn cancelled(&self) -> bool {
            true
        }
    }

    #[test]
    fn a_cancelled_painting_keeps_nothing() {
        let bounds = Rect { x_min: 0.0, y_min: 0.0, x_max: 37.0, y_max: 37.0 };
        assert!(painted(bounds, 0.1, &[pocket(37.0)], &[], &Cancelled).is_err());
        let key = key_of(bounds, 0.1, &[pocket(37.0)], &[]);
        assert!(!kept().iter().any(|k| k.key == key), "a cancelled painting was kept");
    }
}
