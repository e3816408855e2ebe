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
use crate::core::stock::{resample, Grid};

/// What a plan leaves: its stock, and the rest material in it.
#[derive(Debug, Clone, PartialEq)]
pub struct PlanStock {
    pub stock: KeptStock,
    pub rest: RestMaterial,
}

/// The stock the planned `layers` (top first) leave in the cavity, with the cavity's
/// outline running on down under the last one (as a pocket's stock does). Layers of
/// different outlines were simulated on grids of their own: they are brought onto the grid
/// covering them all (at the finest cell among them, each cell interpolated as a probe
/// reads it, see [`resample`]). `Err` says why no stock can be kept: a layer that kept none,
/// a layer whose pocket does not lie on its grid, or layers that do not follow each other
/// from the top down.
pub fn plan_stock(layers: &[LayerPlan]) -> Result<PlanStock, String> {
    // Per original layer: its kept slices and rasters, and its footprint.
    let mut originals: Vec<(usize, KeptStock)> = Vec::new();
    for l in layers.iter().filter(|l| l.copy_of.is_none()) {
        let kept = keep(stack_of(l, l)?, &l.analysis, None, Floor::Unbounded, true).map_err(|e| e.to_string())?;
        if kept.below.is_none() {
            return Err(format!("layer {}'s pocket does not lie on its grid", l.index));
        }
        originals.push((l.index, kept));
    }
    let grids: Vec<Grid> = originals.iter().map(|(_, k)| k.grid).collect();
    let finest = grids.iter().map(|g| g.cell_mm).fold(f64::INFINITY, f64::min);
    let grid = match grids.first() {
        None => return Err("the plan has no layers".to_string()),
        Some(g) if grids.iter().all(|o| same_grid(g, o)) => *g,
        Some(_) => Grid::covering(&grids, finest).ok_or("the plan has no layers")?,
    };
    let onto = |cells: Vec<i8>, from: Grid| if same_grid(&from, &grid) { cells } else { resample(&cells, from, grid) };
    let mut footprints: Vec<Vec<i8>> = Vec::with_capacity(originals.len());
    let mut kept_rasters: Vec<Vec<Vec<i8>>> = Vec::with_capacity(originals.len());
    for (_, kept) in &mut originals {
        let from = kept.grid;
        let below = kept.below.take().map(|b| b.footprint).unwrap_or_default();
        footprints.push(onto(below, from));
        kept_rasters.push(std::mem::take(&mut kept.rasters).into_iter().map(|r| onto(r, from)).collect());
    }
    // The layers in order, copies as their originals moved down.
    let mut slices: Vec<KeptSlice> = Vec::new();
    let mut rasters: Vec<Vec<i8>> = Vec::new();
    // Per layer, the index of its first (top) raster, and of its original (its footprint's).
    let (mut first_raster, mut footprint_of) = (Vec::with_capacity(layers.len()), Vec::with_capacity(layers.len()));
    for l in layers {
        let source = original(layers, l)?;
        let k = originals.iter().position(|(index, _)| *index == source.index).ok_or("a layer was not kept")?;
        let dz = l.z_top_mm - source.z_top_mm;
        first_raster.push(rasters.len());
        footprint_of.push(k);
        let offset = rasters.len();
        slices.extend(originals[k].1.slices.iter().map(|s| KeptSlice {
            z_top: s.z_top + dz,
            z_bottom: s.z_bottom + dz,
            raster: s.raster + offset,
        }));
        rasters.extend(kept_rasters[k].iter().cloned());
    }
    // From the bottom up: each layer loses what the layer below cleared, the cells of that
    // layer's footprint (material there) that its top slice no longer holds.
    for k in (0..layers.len().saturating_sub(1)).rev() {
        let (upper, lower) = rasters.split_at_mut(first_raster[k + 1]);
        let (below, footprint) = (&lower[0], &footprints[footprint_of[k + 1]]);
        for raster in &mut upper[first_raster[k]..] {
            for ((cell, &under), &inside) in raster.iter_mut().zip(below).zip(footprint) {
                if inside > 0 {
                    *cell = (*cell).min(under);
                }
            }
        }
    }
    let last = footprint_of.last().copied().unwrap_or(0);
    let below = Some(Below { footprint: std::mem::take(&mut footprints[last]), floor: Floor::Unbounded });
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
