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
//! over its z range: the raster of the lowest kept slice it overlaps (a kept slice's
//! material lies inside that of the slice below it, so that raster holds the material of
//! all the kept slices above it). A new slice that lies inside one kept slice is exactly
//! that slice; one that spans a kept level gets the lower slice's material; where the
//! levels are the same, the stock is the kept one cell for cell, and the next program is
//! simulated exactly as if it had run on after the first on one stock. Where the first
//! program never cut below the layer's top, every slice is the untouched stock, as it was.

use crate::core::stock::Grid;

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
        Ok(())
    }

    /// The index of the kept raster a new slice from `z_top` down to `z_bottom` holds:
    /// that of the lowest kept slice the range overlaps (see the module's doc); the bottom
    /// slice's below the kept layer, the top slice's above it.
    pub fn raster_for(&self, z_top: f64, z_bottom: f64) -> usize {
        let eps = super::slices::Z_CONTACT_EPS_MM;
        self.slices
            .iter()
            .rev()
            .find(|s| s.z_top > z_bottom + eps && s.z_bottom < z_top - eps)
            .or_else(|| if z_top <= self.z_bottom() + eps { self.slices.last() } else { self.slices.first() })
            .map_or(0, |s| s.raster)
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
        }
    }

    #[test]
    fn a_new_slice_holds_the_material_of_the_lowest_kept_slice_it_overlaps() {
        let k = kept();
        assert!(k.validate().is_ok());
        // Inside the top kept slice: the top slice's raster.
        assert_eq!(k.raster_for(0.0, -2.5), 0);
        assert_eq!(k.raster_for(-7.5, -10.0), 0);
        // Across the level at −10: the slice below's.
        assert_eq!(k.raster_for(-7.5, -12.5), 1);
        // Below the kept layer: its bottom slice's; above: its top slice's.
        assert_eq!(k.raster_for(-30.0, -35.0), 1);
        assert_eq!(k.raster_for(5.0, 0.0), 0);
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
    }
}
