//! The stock a plan leaves in its cavity (issue 32 item 3), kept so that another job can
//! start from it: the chosen candidate's layers, each as its verification simulated it
//! (a copy as its original's, moved down), stacked into one kept stock.
//!
//! Each layer is simulated on its own, from its own untouched stock, so what one leaves
//! above another is joined here as a vertical end mill leaves it: the tool that cuts a layer
//! also cuts everything above its tip, so no material is left over a place a lower layer's
//! tool passed. Every slice of a layer therefore loses what the layer below cleared: the
//! cells of that layer's footprint (its pocket) that its top slice no longer holds. Where
//! the layers share one contour, each slice's material then lies inside that of the slice
//! below it, as within one simulation (see [`crate::core::analysis::slices`]).

use super::layer::LayerPlan;
use crate::core::analysis::kept::{keep, same_grid, Below, Floor, KeptSlice, KeptStock};
use crate::core::analysis::rest::RestMaterial;
use crate::core::analysis::Stack;
use crate::core::stock::Grid;

/// What a plan leaves: its stock, and the rest material in it.
#[derive(Debug, Clone, PartialEq)]
pub struct PlanStock {
    pub stock: KeptStock,
    pub rest: RestMaterial,
}

/// The stock the planned `layers` (top first) leave in the cavity, with the cavity's
/// outline running on down under the last one (as a pocket's stock does); `Err` says why
/// none can be kept: a layer that kept no stock, or layers simulated on different grids.
pub fn plan_stock(layers: &[LayerPlan]) -> Result<PlanStock, String> {
    let mut grid: Option<Grid> = None;
    let mut slices: Vec<KeptSlice> = Vec::new();
    let mut rasters: Vec<Vec<i8>> = Vec::new();
    // Per layer, the index of its first (top) raster, and its footprint.
    let mut first_raster: Vec<usize> = Vec::with_capacity(layers.len());
    let mut footprints: Vec<Vec<i8>> = Vec::with_capacity(layers.len());
    for l in layers {
        let source = original(layers, l)?;
        let stack = stack_of(source, l)?;
        let dz = l.z_top_mm - source.z_top_mm;
        // A copy's footprint is its original's: painted once.
        let painted = first_raster.iter().zip(layers).position(|(_, o)| o.copy_of.unwrap_or(o.index) == source.index);
        let kept = match painted {
            Some(k) => KeptStock {
                below: Some(Below { footprint: footprints[k].clone(), floor: Floor::Unbounded }),
                ..stack.keep(true)
            },
            None => keep(stack, &source.analysis, None, Floor::Unbounded, true).map_err(|e| e.to_string())?,
        };
        match grid {
            None => grid = Some(kept.grid),
            Some(g) if same_grid(&g, &kept.grid) => {}
            Some(_) => {
                return Err(format!(
                    "layer {} was simulated on another grid than the layers above it (cells of {} mm)",
                    l.index, kept.grid.cell_mm
                ))
            }
        }
        let below = kept.below.ok_or_else(|| format!("layer {}'s pocket does not lie on its grid", l.index))?;
        footprints.push(below.footprint);
        first_raster.push(rasters.len());
        let offset = rasters.len();
        slices.extend(kept.slices.iter().map(|s| KeptSlice {
            z_top: s.z_top + dz,
            z_bottom: s.z_bottom + dz,
            raster: s.raster + offset,
        }));
        rasters.extend(kept.rasters);
    }
    let Some(grid) = grid else {
        return Err("the plan has no layers".to_string());
    };
    // From the bottom up: each layer loses what the layer below cleared; material stays
    // where the top slice below holds some, or outside that layer's footprint. In signed
    // distances: the least of its own and the larger of the one below and the footprint's
    // negation.
    for k in (0..layers.len().saturating_sub(1)).rev() {
        let (upper, lower) = rasters.split_at_mut(first_raster[k + 1]);
        let (below, footprint) = (&lower[0], &footprints[k + 1]);
        for raster in &mut upper[first_raster[k]..] {
            for ((cell, &under), &inside) in raster.iter_mut().zip(below).zip(footprint) {
                *cell = (*cell).min(under.max(inside.saturating_neg()));
            }
        }
    }
    let below = footprints.pop().map(|footprint| Below { footprint, floor: Floor::Unbounded });
    let stock = KeptStock { grid, slices, rasters, cavity: true, below };
    stock.validate()?;
    let rest = RestMaterial::of_kept(&stock)?;
    Ok(PlanStock { stock, rest })
}

/// The layer `l` is planned as: itself, or the one it is a copy of.
fn original<'a>(layers: &'a [LayerPlan], l: &LayerPlan) -> Result<&'a LayerPlan, String> {
    let index = l.copy_of.unwrap_or(l.index);
    layers.iter().find(|o| o.index == index).ok_or_else(|| format!("layer {index} is not among the plan's layers"))
}

/// The stock `source` kept, for layer `l`.
fn stack_of<'a>(source: &'a LayerPlan, l: &LayerPlan) -> Result<&'a Stack, String> {
    source.stock.as_deref().ok_or_else(|| format!("layer {} kept no stock", l.index))
}
