//! What a simulation leaves in the layer: the remaining volume of its stock and, where the
//! stock was a pocket's, the rest material inside the cavity per slice (issue 32 item 3),
//! for the next program to remove.

use super::kept::KeptStock;
use super::stack::Stack;
use crate::core::stock::Raster;
use serde::Serialize;

/// The rest material of one slice.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, utoipa::ToSchema)]
pub struct RestLevel {
    pub z_top: f64,
    pub z_bottom: f64,
    /// Area of material left in the slice, mm².
    pub area_mm2: f64,
    /// A point of it, `[x, y]` mm: the centre of a cell as deep in the material as any
    /// (null when none is left).
    pub point: Option<[f64; 2]>,
}

/// The material left inside the cavity after the path.
#[derive(Debug, Clone, PartialEq, Serialize, utoipa::ToSchema)]
pub struct RestMaterial {
    /// Volume left, mm³.
    pub volume_mm3: f64,
    /// Per slice, top first.
    pub levels: Vec<RestLevel>,
}

impl RestMaterial {
    /// The rest material of the slices of `stack`, whose areas of material are `areas_mm2`
    /// ([`Stack::material_areas_fine_mm2`]).
    pub fn of(stack: &Stack, areas_mm2: &[f64]) -> RestMaterial {
        let levels = stack.slices().iter().zip(areas_mm2).enumerate().map(|(k, (s, &area_mm2))| RestLevel {
            z_top: s.z_top,
            z_bottom: s.z_bottom,
            area_mm2,
            point: deepest_point(stack.raster(k)),
        });
        RestMaterial::of_levels(levels.collect())
    }

    /// The rest material of the slices of a kept stock (each distinct raster read once).
    pub fn of_kept(kept: &KeptStock) -> Result<RestMaterial, String> {
        let mut levels: Vec<RestLevel> = Vec::with_capacity(kept.slices.len());
        let mut read: Option<(usize, Raster)> = None;
        for s in &kept.slices {
            if read.as_ref().is_none_or(|(k, _)| *k != s.raster) {
                let cells = kept.rasters.get(s.raster).ok_or("a slice names no kept raster")?;
                read = Some((s.raster, Raster::from_cells(kept.grid, cells.clone())?));
            }
            if let Some((_, raster)) = &read {
                levels.push(level(s.z_top, s.z_bottom, raster));
            }
        }
        Ok(RestMaterial::of_levels(levels))
    }

    fn of_levels(levels: Vec<RestLevel>) -> RestMaterial {
        let volume_mm3 = levels.iter().map(|l| l.area_mm2 * (l.z_top - l.z_bottom)).sum();
        RestMaterial { volume_mm3, levels }
    }
}

/// The rest material of the slice from `z_top` down to `z_bottom` holding `raster`.
fn level(z_top: f64, z_bottom: f64, raster: &Raster) -> RestLevel {
    RestLevel { z_top, z_bottom, area_mm2: raster.material_area_fine_mm2(), point: deepest_point(raster) }
}

/// A point of the material of `raster` as deep in it as any, `[x, y]` mm.
fn deepest_point(raster: &Raster) -> Option<[f64; 2]> {
    raster.deepest_material_point().map(|(x, y)| [x, y])
}

/// The volume of material the slices of `stack` hold, mm³.
pub fn remaining_volume_mm3(stack: &Stack) -> f64 {
    stack
        .slices()
        .iter()
        .enumerate()
        .map(|(k, s)| stack.raster(k).material_area_fine_mm2() * (s.z_top - s.z_bottom))
        .sum()
}
