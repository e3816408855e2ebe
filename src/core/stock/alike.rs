//! Whether two rasters of one grid hold stocks no probe can tell apart, though their cells
//! may differ. A probe reads the 2 × 2 cells around a point (see [`Raster::is_material_at`])
//! and the tile counts, which follow from the cells' signs. Where the four cells are all
//! air, every probe answers air whatever their values; so an air cell with no material
//! among the eight around it is never read for more than its sign. Such a cell keeps a stale
//! distance (updates leave air without material near as it is, see
//! [`Raster::clear_capsule_rows`]), and since material is only ever removed, it never has
//! material beside it again: two rasters that differ only in such cells answer every probe
//! alike now, and after any update applied to both.

use super::capsule::WORD_CELLS;
use super::Raster;

impl Raster {
    /// `true` when every probe gives the same answer on `self` and `other` (same grid): the
    /// same material counts, and every cell the same but for air cells, in both, with no
    /// material among the eight around them (see the module). The counts are compared first,
    /// so rasters that differ in material are most often told apart without reading a cell.
    pub fn probes_alike(&self, other: &Raster) -> bool {
        if self.grid() != other.grid() || self.blocks != other.blocks {
            return false;
        }
        let (a, b) = (&self.f, &other.f);
        let mut k = 0;
        for (wa, wb) in a.chunks_exact(WORD_CELLS).zip(b.chunks_exact(WORD_CELLS)) {
            if wa != wb && !(k..k + WORD_CELLS).all(|c| self.reads_alike_at(other, c)) {
                return false;
            }
            k += WORD_CELLS;
        }
        (k..a.len()).all(|c| self.reads_alike_at(other, c))
    }

    /// `true` when cell `k` is the same in both rasters, or air in both with no material
    /// among the eight cells around it (in `self`: where the rasters agree on every cell's
    /// sign, in both).
    fn reads_alike_at(&self, other: &Raster, k: usize) -> bool {
        let (v, w) = (self.f[k], other.f[k]);
        if v == w {
            return true;
        }
        if v > 0 || w > 0 {
            return false;
        }
        !self.material_beside(k % self.nx, k / self.nx)
    }

    /// Makes the raster's version newer than `other`'s and its own: what was read from
    /// either (kept by their versions) no longer holds for it.
    pub fn take_version_past(&mut self, other: u64) {
        self.version = self.version.max(other) + 1;
    }
}

#[cfg(test)]
mod tests {
    use super::super::test_blocks::block;

    #[test]
    fn rasters_with_the_same_cells_are_alike() {
        let (a, b) = (block(), block());
        assert!(a.probes_alike(&b));
    }

    #[test]
    fn a_stale_distance_in_air_far_from_material_does_not_tell_two_rasters_apart() {
        let mut a = block();
        a.clear_capsule((10.0, 20.0), (30.0, 20.0), 6.0);
        let mut b = a.clone();
        // The middle of the cleared slot, far from its walls.
        let (fx, fy) = b.grid_position(20.0, 20.0);
        let k = fy.round() as usize * b.nx + fx.round() as usize;
        assert!(b.f[k] < 0);
        b.f[k] = -1;
        assert!(a.probes_alike(&b) && b.probes_alike(&a));
    }

    #[test]
    fn a_different_distance_beside_material_tells_two_rasters_apart() {
        let mut a = block();
        a.clear_capsule((10.0, 20.0), (30.0, 20.0), 6.0);
        // An air cell at the slot's wall: material lies beside it.
        let wall = (0..a.ny)
            .map(|j| j * a.nx + a.nx / 2)
            .find(|&k| a.f[k] <= 0 && a.f[k + a.nx] > 0)
            .expect("the slot has a wall");
        let mut b = a.clone();
        b.f[wall] = if b.f[wall] == 0 { -1 } else { 0 };
        assert!(!a.probes_alike(&b) && !b.probes_alike(&a));
    }

    #[test]
    fn material_cut_from_one_raster_only_tells_the_two_apart() {
        let a = block();
        let mut b = block();
        b.clear_capsule((10.0, 20.0), (10.0, 20.0), 0.3);
        assert!(!a.probes_alike(&b));
    }
}
