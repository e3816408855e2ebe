//! The stock a simulation left, kept after its job so that another job can start from it
//! (issue 32 item 3: rough with one program, then analyse the next on what it left).
//!
//! A kept stock is the layer's slices (top first, with their z ranges) over one grid, and
//! the rasters they hold: slices still alike at the end share one raster (see
//! [`super::stack`]), which is kept once.
//!
//! **From one program's slices to the next's.** The next program cuts its own z levels
//! ([`super::slices::slice_levels`] over the kept layer), which need not be the kept
//! ones. A new slice holds, conservatively, all the material the kept stock has anywhere
//! over its z range: the kept rasters it overlaps together, a cell holding material where
//! any of them does (within one simulation a kept slice's material lies inside that of
//! the slice below it, so that is the lowest one's material; a plan's layers of different
//! contours need not nest outside the lower layer's pocket, though they do inside it, where
//! a program cutting the pocket's rest moves: the simulation's shortcuts that read the
//! slice below for the slices above hold there). A new slice that lies inside one kept slice is exactly
//! that slice; one that spans a kept level gets the material of both; where the
//! levels are the same, the stock is the kept one cell for cell, and the next program is
//! simulated exactly as if it had run on after the first on one stock. Where the first
//! program never cut below the layer's top, every slice is the untouched stock, as it was.
//!
//! **Below the kept bottom.** The next program may cut deeper than the kept layer. What
//! lies there is the stock as the first job was given it ([`Below`]): its footprint (the
//! stock's regions less its open ones, as they were painted before any cut), solid down
//! to the stock's own bottom ([`Floor::At`]: a box's `z_min`; nothing lies below it) or
//! on down ([`Floor::Unbounded`]: a pocket's cavity runs on in its outline). The layer then
//! reaches down to the program's deepest feed move ([`layer_bottom`]), never below the
//! floor, and every new slice below the kept bottom holds the footprint, and one across it
//! the footprint together with the kept slices it overlaps (within one simulation the
//! footprint holds all their material; a plan's upper layers may reach beyond its last). A
//! stock kept before this was recorded (format 1) has no [`Below`]: a program cutting
//! below it is refused, since what lies there is not known.

use crate::core::stock::Grid;
use serde::{Deserialize, Serialize};

/// Grids whose origins differ by less than this share of a cell are one grid.
const GRID_MATCH_CELLS: f64 = 1e-6;

/// How deep the stock under a kept layer goes.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Floor {
    /// Solid down to this z, mm (a box's bottom); nothing lies below it.
    At(f64),
    /// On down without end (a pocket's cavity, cut deeper in its outline).
    Unbounded,
}

/// What lies under a kept layer.
#[derive(Debug, Clone, PartialEq)]
pub struct Below {
    /// The stock's cells before any cut (its regions less its open ones) on the kept grid.
    pub footprint: Vec<i8>,
    pub floor: Floor,
}

/// One slice of a kept stock: its z range, mm, and the raster it holds (an index into
/// [`KeptStock::rasters`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct KeptSlice {
    pub z_top: f64,
    pub z_bottom: f64,
    pub raster: usize,
}

/// The stock a simulation left.
#[derive(Debug, Clone, PartialEq)]
pub struct KeptStock {
    /// The grid every raster lies on.
    pub grid: Grid,
    /// Top first; each names its raster.
    pub slices: Vec<KeptSlice>,
    /// The distinct rasters' cells (see [`crate::core::stock::Raster::cells`]), top first.
    pub rasters: Vec<Vec<i8>>,
    /// The stock was a pocket's (a contour or a DXF): all its material lies inside the
    /// cavity to be cut, and what is left of it is rest material.
    pub cavity: bool,
    /// What lies under the layer (`None`: not known, a stock kept in format 1).
    pub below: Option<Below>,
}

/// Where a new slice's material comes from (see the module's doc).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Source {
    /// A kept raster, by index.
    Raster(usize),
    /// The footprint under the kept layer.
    Footprint,
    /// The material of the kept rasters `first..=last` together, and of the footprint when
    /// `footprint`: a slice across kept levels, or across the kept bottom.
    Union { first: usize, last: usize, footprint: bool },
}

/// The stock `stack` holds after simulating `spec`'s layer, kept with what lies under it:
/// what lay under `start` when the simulation started from it, else the footprint of
/// `spec`'s stock (painted again on the stack's grid, exactly as the simulation's stock
/// was painted before any cut) down to `floor` (at the layer's bottom at the highest: the
/// layer itself is solid footprint). `cavity` says the stock was a pocket's.
pub fn keep(
    stack: &super::Stack,
    spec: &super::AnalysisSpec,
    start: Option<&KeptStock>,
    floor: Floor,
    cavity: bool,
) -> Result<KeptStock, crate::core::CoreError> {
    let mut kept = stack.keep(cavity);
    kept.below = match start {
        Some(start) => start.below.clone(),
        None => {
            let bounds = super::region::union_bounds(&spec.stock);
            let raster = super::painted::painted(
                bounds,
                kept.grid.cell_mm,
                &spec.stock,
                &spec.open,
                &crate::core::progress::NoProgress,
            )?;
            let floor = match floor {
                Floor::At(z) => Floor::At(z.min(kept.z_bottom())),
                Floor::Unbounded => Floor::Unbounded,
            };
            // The stack's grid is the painted stock's: any other is not this stock's.
            same_grid(&raster.layout_grid(), &kept.grid).then(|| Below { footprint: raster.cells().to_vec(), floor })
        }
    };
    Ok(kept)
}

/// `true` when `a` and `b` are one grid: as many cells, origins and cells within
/// [`GRID_MATCH_CELLS`] of a cell.
pub fn same_grid(a: &Grid, b: &Grid) -> bool {
    let close = |x: f64, y: f64| (x - y).abs() < GRID_MATCH_CELLS * b.cell_mm;
    a.nx == b.nx && a.ny == b.ny && close(a.x0_mm, b.x0_mm) && close(a.y0_mm, b.y0_mm) && close(a.cell_mm, b.cell_mm)
}

/// The slice levels `levels` (top first) of a layer that starts from a kept stock whose
/// bottom is `kept_bottom_mm`, with the kept bottom among them where the layer reaches
/// below it and no level lies within [`super::slices::MIN_SLICE_MM`] of it: the slices
/// above it keep the kept material exactly, and the ones below hold the footprint.
pub fn with_kept_bottom(mut levels: Vec<f64>, kept_bottom_mm: f64) -> Vec<f64> {
    let min = super::slices::MIN_SLICE_MM;
    let below = levels.last().is_some_and(|&z| z <= kept_bottom_mm - min);
    if below && levels.iter().all(|&z| (z - kept_bottom_mm).abs() >= min) {
        let at = levels.partition_point(|&z| z > kept_bottom_mm);
        levels.insert(at, kept_bottom_mm);
    }
    levels
}

/// The lowest z a feed move of `path` reaches, mm (`None` without feed moves): the ends of
/// the moves, as the slices' levels are chosen from them ([`super::slices::slice_levels`]).
pub fn deepest_feed_mm(path: &crate::core::toolpath::Toolpath) -> Option<f64> {
    use crate::core::toolpath::Motion;
    path.moves
        .iter()
        .filter(|m| !matches!(m.motion, Motion::Rapid))
        .flat_map(|m| [m.start.z, m.end.z])
        .min_by(f64::total_cmp)
}

/// The bottom of a layer that starts from a kept stock whose bottom is `kept_bottom_mm`
/// with `floor` under it (`None`: not known), for a program whose feed moves reach down to
/// `deepest_mm`: the kept bottom, or deeper down to the program's deepest move but never
/// below the floor. `Err` says why when the program cuts below the kept stock and what lies
/// there is not known.
pub fn layer_bottom(kept_bottom_mm: f64, floor: Option<Floor>, deepest_mm: Option<f64>) -> Result<f64, String> {
    // Less than the smallest slice below the kept bottom is not a slice of its own.
    let Some(deepest) = deepest_mm.filter(|&z| z <= kept_bottom_mm - super::slices::MIN_SLICE_MM) else {
        return Ok(kept_bottom_mm);
    };
    match floor {
        Some(Floor::Unbounded) => Ok(deepest),
        Some(Floor::At(floor)) => Ok(deepest.max(floor).min(kept_bottom_mm)),
        None => Err(format!(
            "the program cuts down to z {deepest} and the kept stock ends at z {kept_bottom_mm}: what lies below it is not known (the stock was kept by an earlier version of dieplan); analyse the first program again to keep its stock anew"
        )),
    }
}

impl KeptStock {
    /// The top of the layer, mm.
    pub fn z_top(&self) -> f64 {
        self.slices.first().map_or(0.0, |s| s.z_top)
    }

    /// The bottom of the layer, mm.
    pub fn z_bottom(&self) -> f64 {
        self.slices.last().map_or(0.0, |s| s.z_bottom)
    }

    /// How deep the stock under the layer goes (`None`: not known).
    pub fn floor(&self) -> Option<Floor> {
        self.below.as_ref().map(|b| b.floor)
    }

    /// Checks that the slices run top first without gaps, each with a raster of the
    /// grid's size, each raster held by a run of slices ending at the bottom of a run.
    pub fn validate(&self) -> Result<(), String> {
        if self.slices.is_empty() || self.rasters.is_empty() {
            return Err("no slices".to_string());
        }
        let finite = self.slices.iter().all(|s| s.z_top.is_finite() && s.z_bottom.is_finite());
        if !finite || self.slices.iter().any(|s| s.z_top <= s.z_bottom) {
            return Err("every slice's z_top must be finite and above its z_bottom".to_string());
        }
        if self.slices.windows(2).any(|w| (w[0].z_bottom - w[1].z_top).abs() > super::slices::Z_CONTACT_EPS_MM) {
            return Err("the slices must follow each other from the top down".to_string());
        }
        if self.slices.windows(2).any(|w| w[1].raster < w[0].raster) || self.slices[0].raster != 0 {
            return Err("the slices' rasters must run from the top down".to_string());
        }
        if self.slices.last().is_some_and(|s| s.raster + 1 != self.rasters.len())
            || self.slices.windows(2).any(|w| w[1].raster > w[0].raster + 1)
        {
            return Err("every raster must be held by a slice".to_string());
        }
        if self.rasters.iter().any(|r| r.len() != self.grid.cells()) {
            return Err(format!("every raster must have the grid's {} × {} cells", self.grid.nx, self.grid.ny));
        }
        if let Some(below) = &self.below {
            if below.footprint.len() != self.grid.cells() {
                return Err("the footprint must have the grid's cells".to_string());
            }
            if let Floor::At(z) = below.floor {
                if !(z.is_finite() && z <= self.z_bottom() + super::slices::Z_CONTACT_EPS_MM) {
                    return Err("the floor must be finite and at or below the layer's bottom".to_string());
                }
            }
        }
        Ok(())
    }

    /// Where a new slice from `z_top` down to `z_bottom` takes its material from: all the
    /// material the kept stock has over that z range, the kept rasters it overlaps together
    /// ([`KeptStock::rasters_over`]), with the footprint when it reaches below the kept layer
    /// (`Err` when what lies there is not known).
    pub fn source_for(&self, z_top: f64, z_bottom: f64) -> Result<Source, String> {
        let below = z_bottom < self.z_bottom() - super::slices::Z_CONTACT_EPS_MM;
        if below && self.below.is_none() {
            layer_bottom(self.z_bottom(), None, Some(z_bottom))?;
        }
        let within = z_top > self.z_bottom() + super::slices::Z_CONTACT_EPS_MM;
        Ok(match (self.rasters_over(z_top, z_bottom), below) {
            ((first, last), false) if first == last => Source::Raster(first),
            (_, true) if !within => Source::Footprint,
            ((first, last), footprint) => Source::Union { first, last, footprint },
        })
    }

    /// The material of `source`: a kept raster's or the footprint's cells as they are, a
    /// union's as the largest of its cells' signed distances (a cell holds material where
    /// any of them does).
    pub fn cells(&self, source: Source) -> std::borrow::Cow<'_, [i8]> {
        use std::borrow::Cow;
        let footprint = || self.below.as_ref().map_or(&self.rasters[self.rasters.len() - 1], |b| &b.footprint);
        match source {
            Source::Raster(k) => Cow::Borrowed(&self.rasters[k]),
            Source::Footprint => Cow::Borrowed(footprint()),
            Source::Union { first, last, footprint: with_footprint } => {
                let mut cells = self.rasters[first].clone();
                let others = self.rasters[first + 1..=last].iter().chain(with_footprint.then(footprint));
                for other in others {
                    cells.iter_mut().zip(other).for_each(|(cell, &o)| *cell = (*cell).max(o));
                }
                Cow::Owned(cells)
            }
        }
    }

    /// The first and last kept rasters of the kept slices the range from `z_top` down to
    /// `z_bottom` overlaps (rasters run from the top down); the bottom slice's below the kept
    /// layer, the top slice's above it.
    pub fn rasters_over(&self, z_top: f64, z_bottom: f64) -> (usize, usize) {
        let eps = super::slices::Z_CONTACT_EPS_MM;
        let overlaps = |s: &&KeptSlice| s.z_top > z_bottom + eps && s.z_bottom < z_top - eps;
        let outside = || if z_top <= self.z_bottom() + eps { self.slices.last() } else { self.slices.first() };
        let first = self.slices.iter().find(overlaps).or_else(outside).map_or(0, |s| s.raster);
        let last = self.slices.iter().rev().find(overlaps).or_else(outside).map_or(0, |s| s.raster);
        (first, last)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn kept() -> KeptStock {
        let grid = Grid { x0_mm: 0.0, y0_mm: 0.0, cell_mm: 1.0, nx: 2, ny: 2 };
        let slice = |z_top: f64, z_bottom: f64, raster: usize| KeptSlice { z_top, z_bottom, raster };
        KeptStock {
            grid,
            slices: vec![slice(0.0, -10.0, 0), slice(-10.0, -20.0, 1), slice(-20.0, -30.0, 1)],
            rasters: vec![vec![0; 4], vec![1; 4]],
            cavity: false,
            below: Some(Below { footprint: vec![2; 4], floor: Floor::At(-40.0) }),
        }
    }

    #[test]
    fn a_new_slice_holds_the_material_of_every_kept_slice_it_overlaps() {
        let k = kept();
        assert!(k.validate().is_ok());
        // Inside the top kept slice: the top slice's raster.
        assert_eq!(k.source_for(0.0, -2.5), Ok(Source::Raster(0)));
        assert_eq!(k.source_for(-7.5, -10.0), Ok(Source::Raster(0)));
        // Across the level at −10: both, together.
        assert_eq!(k.source_for(-7.5, -12.5), Ok(Source::Union { first: 0, last: 1, footprint: false }));
        assert_eq!(&*k.cells(Source::Union { first: 0, last: 1, footprint: false }), &[1; 4]);
        // Two slices sharing one raster are that raster.
        assert_eq!(k.source_for(-15.0, -25.0), Ok(Source::Raster(1)));
        // Above the kept layer: its top slice's.
        assert_eq!(k.rasters_over(5.0, 0.0), (0, 0));
        assert_eq!(k.rasters_over(-30.0, -35.0), (1, 1));
    }

    #[test]
    fn a_slice_across_kept_levels_holds_material_the_slice_below_does_not() {
        // Layers of different contours (a plan's): the upper slice holds a cell (the second)
        // the lower one does not; a new slice across both holds it.
        let mut k = kept();
        k.rasters = vec![vec![-5, 7, -5, 3], vec![4, -6, -6, 9]];
        assert_eq!(&*k.cells(Source::Union { first: 0, last: 1, footprint: false }), &[4, 7, -5, 9]);
    }

    #[test]
    fn kept_stocks_whose_slices_or_rasters_do_not_fit_are_refused() {
        let mut gap = kept();
        gap.slices[1].z_top = -11.0;
        assert!(gap.validate().is_err());
        let mut unheld = kept();
        unheld.rasters.push(vec![0; 4]);
        assert!(unheld.validate().is_err());
        let mut small = kept();
        small.rasters[1].pop();
        assert!(small.validate().is_err());
        let mut upside_down = kept();
        upside_down.slices[0].raster = 1;
        assert!(upside_down.validate().is_err());
        let mut floating = kept();
        floating.below = Some(Below { footprint: vec![2; 4], floor: Floor::At(-20.0) });
        assert!(floating.validate().is_err(), "a floor above the layer's bottom");
        let mut torn = kept();
        torn.below = Some(Below { footprint: vec![2; 3], floor: Floor::Unbounded });
        assert!(torn.validate().is_err());
    }

    #[test]
    fn a_new_slice_below_or_across_the_kept_bottom_holds_the_footprint_and_one_of_a_stock_that_never_knew_is_refused() {
        let k = kept();
        assert_eq!(k.source_for(-25.0, -30.0), Ok(Source::Raster(1)));
        assert_eq!(k.source_for(-25.0, -32.0), Ok(Source::Union { first: 1, last: 1, footprint: true }));
        assert_eq!(k.source_for(-30.0, -35.0), Ok(Source::Footprint));
        assert_eq!(&*k.cells(Source::Footprint), &[2; 4]);
        assert_eq!(&*k.cells(Source::Union { first: 1, last: 1, footprint: true }), &[2; 4]);
        let unknown = KeptStock { below: None, ..kept() };
        assert!(unknown.source_for(-30.0, -35.0).unwrap_err().contains("not known"));
    }

    #[test]
    fn the_kept_bottom_is_a_level_of_a_layer_reaching_below_it_unless_one_is_close() {
        assert_eq!(with_kept_bottom(vec![0.0, -25.0, -35.0], -30.0), vec![0.0, -25.0, -30.0, -35.0]);
        assert_eq!(with_kept_bottom(vec![0.0, -30.02, -35.0], -30.0), vec![0.0, -30.02, -35.0]);
        assert_eq!(with_kept_bottom(vec![0.0, -30.0], -30.0), vec![0.0, -30.0]);
    }

    #[test]
    fn the_layer_reaches_down_to_the_deepest_feed_move_but_never_below_the_floor() {
        // Not below the kept bottom: the kept layer.
        assert_eq!(layer_bottom(-30.0, None, Some(-30.0)), Ok(-30.0));
        assert_eq!(layer_bottom(-30.0, None, None), Ok(-30.0));
        // A box's bottom at −40: down to the move at −35, not to the move at −50.
        assert_eq!(layer_bottom(-30.0, Some(Floor::At(-40.0)), Some(-35.0)), Ok(-35.0));
        assert_eq!(layer_bottom(-30.0, Some(Floor::At(-40.0)), Some(-50.0)), Ok(-40.0));
        // Less than the smallest slice below: the kept layer.
        assert_eq!(layer_bottom(-30.0, Some(Floor::Unbounded), Some(-30.01)), Ok(-30.0));
        // A box that ended at the kept bottom: nothing below it.
        assert_eq!(layer_bottom(-30.0, Some(Floor::At(-30.0)), Some(-50.0)), Ok(-30.0));
        // A pocket's cavity runs on down.
        assert_eq!(layer_bottom(-30.0, Some(Floor::Unbounded), Some(-50.0)), Ok(-50.0));
        assert!(layer_bottom(-30.0, None, Some(-31.0)).unwrap_err().contains("not known"));
    }
}
