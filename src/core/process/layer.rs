//! Each layer's sequence (seed 004 Table 1, MODEL.md §8): helical entries, spiral hole
//! expansion, trochoidal grooving of the critical regions, z-cut division, and the rough
//! (last layer: intermediate-rough) contour-parallel side cutting, planned by the trochoid
//! insertion planner. A layer like one already planned (same contour, thickness and role)
//! is that plan moved down.

use super::cavity::{Cavity, LayerRole};
use super::parallel::{self, Shares};
use super::spec::{ProcessOptions, ToolCandidate};
use crate::core::analysis::geometry::{PathGeometry, SampleGeometry};
use crate::core::analysis::{analyze_with, AnalysisSpec, Stack};
use crate::core::insertion::{analysis_spec, plan_insertion_sampled, InsertionPlan, InsertionSpec};
use crate::core::progress::Progress;
pub use crate::core::toolpath::Step;
use crate::core::toolpath::{labels_of, EventKind, Motion, Toolpath};
use crate::core::CoreError;
use std::sync::Arc;

/// Layers whose thicknesses differ by less than this are alike, mm.
const SAME_THICKNESS_MM: f64 = 1e-6;

/// Points this close below the safe height are at it (they stay when a plan is moved), mm.
const AT_SAFE_Z_MM: f64 = 1e-6;

/// One layer's plan.
#[derive(Debug, Clone)]
pub struct LayerPlan {
    pub index: usize,
    pub role: LayerRole,
    pub z_top_mm: f64,
    pub z_bottom_mm: f64,
    /// The layer this one is a copy of (moved down), if any.
    pub copy_of: Option<usize>,
    /// The insertion planner's plan (shared by the copies, at the original's heights).
    pub insertion: Arc<InsertionPlan>,
    /// The program of this layer, at its heights, its parts labelled by section events
    /// (layer counted within the insertion plan's levels).
    pub toolpath: Toolpath,
    /// Per move: its step (from the section labels).
    pub steps: Vec<Step>,
    /// The simulation of this layer (with the candidate's force model).
    pub analysis: AnalysisSpec,
    /// The geometry of every sample of the program, as its verification simulated it (the
    /// original layers only; `None` once let go).
    pub geometry: Option<Arc<PathGeometry>>,
    /// The stock the program leaves in the layer, as its verification simulated it (the
    /// original layers of a full plan only; `None` once let go). A copy leaves its
    /// original's, moved down.
    pub stock: Option<Arc<Stack>>,
}

/// The insertion spec of layer `index` for `candidate`, simulated on cells of `cell_mm`
/// (`None`: the analysis's default).
pub fn layer_spec(
    cavity: &Cavity,
    index: usize,
    candidate: &ToolCandidate,
    options: &ProcessOptions,
    cell_mm: Option<f64>,
) -> InsertionSpec {
    let layer = &cavity.layers[index];
    let (roughing, base_step) = match cavity.role(index) {
        LayerRole::Rough => (candidate.roughing, Step::RoughSideCutting),
        LayerRole::IntermediateRough => (candidate.intermediate, Step::IntermediateRoughSideCutting),
    };
    let mut spec = InsertionSpec::new(candidate.tool, roughing, candidate.grooving, layer.z_top_mm, layer.z_bottom_mm);
    spec.base_step = base_step;
    spec.safe_z_mm = options.safe_z_mm;
    spec.allowance_mm = options.allowance_mm;
    spec.alpha_limit_deg = options.alpha_limit_deg;
    spec.rapid_mm_min = options.machine.rapid_mm_min;
    spec.sample_spacing_mm = options.sample_spacing_mm;
    spec.cell_mm = cell_mm;
    spec.stock_memory_bytes = options.stock_memory_bytes;
    spec
}

/// Plans every layer of `cavity` with `candidate`: the distinct layers side by side, each
/// keeping the geometry of its program's samples; a layer like one above it (same contour,
/// thickness and role) is that plan moved down.
pub fn plan_layers(
    cavity: &Cavity,
    candidate: &ToolCandidate,
    options: &ProcessOptions,
    progress: &dyn Progress,
) -> Result<Vec<LayerPlan>, CoreError> {
    plan_layers_on_cells(cavity, candidate, options, None, progress)
}

/// [`plan_layers`] with the simulations' raster cell `cell_mm` (`None`: the analysis's
/// default, and each original layer keeps the stock its program leaves), for the
/// screening's coarse plans.
pub fn plan_layers_on_cells(
    cavity: &Cavity,
    candidate: &ToolCandidate,
    options: &ProcessOptions,
    cell_mm: Option<f64>,
    progress: &dyn Progress,
) -> Result<Vec<LayerPlan>, CoreError> {
    let keep_stock = cell_mm.is_none();
    let n = cavity.layers.len();
    let alike = |a: usize, b: usize| {
        let (la, lb) = (&cavity.layers[a], &cavity.layers[b]);
        cavity.role(a) == cavity.role(b)
            && la.pocket == lb.pocket
            && (la.thickness_mm() - lb.thickness_mm()).abs() < SAME_THICKNESS_MM
    };
    let mut like: Vec<Option<usize>> = Vec::with_capacity(n);
    for index in 0..n {
        let first = (0..index).find(|&j| like[j].is_none() && alike(j, index));
        like.push(first);
    }
    let originals: Vec<usize> = (0..n).filter(|&i| like[i].is_none()).collect();
    let shares = Shares::new(progress, 0.0, 1.0, originals.len());
    let planned = parallel::map(progress, &originals, |k, &index| {
        let spec = layer_spec(cavity, index, candidate, options, cell_mm);
        let part = shares.part(k);
        part.checkpoint()?;
        plan_insertion_sampled(&cavity.layers[index].pocket, &spec, None, candidate.force_model, keep_stock, &part)
    });
    let mut plans: Vec<LayerPlan> = Vec::with_capacity(n);
    let mut planned = originals.iter().copied().zip(planned);
    for (index, layer) in cavity.layers.iter().enumerate() {
        let role = cavity.role(index);
        let spec = layer_spec(cavity, index, candidate, options, cell_mm);
        let mut analysis = analysis_spec(&layer.pocket, &spec);
        analysis.force_model = Some(candidate.force_model);
        let plan = match like[index] {
            Some(o) => {
                let original = &plans[o];
                LayerPlan {
                    index,
                    role,
                    z_top_mm: layer.z_top_mm,
                    z_bottom_mm: layer.z_bottom_mm,
                    copy_of: Some(o),
                    insertion: Arc::clone(&original.insertion),
                    toolpath: moved_down(&original.toolpath, layer.z_top_mm - original.z_top_mm, options.safe_z_mm),
                    steps: original.steps.clone(),
                    analysis,
                    geometry: None,
                    stock: None,
                }
            }
            None => {
                let (insertion, geometry, stock) = match planned.next() {
                    Some((i, result)) if i == index => result?,
                    _ => return Err(CoreError::unsolvable("layers", format!("layer {index} was not planned"))),
                };
                let steps = steps_of(&insertion.toolpath, role);
                LayerPlan {
                    index,
                    role,
                    z_top_mm: layer.z_top_mm,
                    z_bottom_mm: layer.z_bottom_mm,
                    copy_of: None,
                    toolpath: insertion.toolpath.clone(),
                    insertion: Arc::new(insertion),
                    steps,
                    analysis,
                    geometry: Some(Arc::new(geometry)),
                    stock: stock.map(Arc::new),
                }
            }
        };
        plans.push(plan);
    }
    progress.report(1.0);
    Ok(plans)
}

/// Simulates `path` once and keeps the geometry of its samples.
pub fn simulate_geometry(
    path: &Toolpath,
    analysis: &AnalysisSpec,
    progress: &dyn Progress,
) -> Result<PathGeometry, CoreError> {
    let mut geometry = PathGeometry::new(analysis.tool.radius_mm());
    let default_rpm = analysis.default_spindle_rpm;
    let simulated =
        analyze_with(path, analysis, progress, |r| geometry.samples.push(SampleGeometry::of(r, default_rpm)))?;
    geometry.removed_volume_mm3 = simulated.summary.removed_volume_mm3;
    Ok(geometry)
}

/// The step of every move of a layer's program, from its section labels (a move before the
/// first label, if any, is of the layer's contour-parallel step).
fn steps_of(path: &Toolpath, role: LayerRole) -> Vec<Step> {
    let base = match role {
        LayerRole::Rough => Step::RoughSideCutting,
        LayerRole::IntermediateRough => Step::IntermediateRoughSideCutting,
    };
    labels_of(&path.events, path.moves.len()).into_iter().map(|l| l.map_or(base, |s| s.step)).collect()
}

/// `path` moved by `dz_mm` in z, except the points at the safe height, which stay; its
/// section labels move with it.
pub fn moved_down(path: &Toolpath, dz_mm: f64, safe_z_mm: f64) -> Toolpath {
    let shift = |z: f64| if z >= safe_z_mm - AT_SAFE_Z_MM { z } else { z + dz_mm };
    let mut out = path.clone();
    for m in &mut out.moves {
        m.start.z = shift(m.start.z);
        m.end.z = shift(m.end.z);
        if let Motion::Arc { center, .. } = &mut m.motion {
            center.z = shift(center.z);
        }
    }
    for e in &mut out.events {
        if let EventKind::Section(s) = &mut e.kind {
            s.z_mm = shift(s.z_mm);
        }
    }
    out
}
