//! Each layer's sequence (seed 004 Table 1, MODEL.md §8): helical entries, spiral hole
//! expansion, trochoidal grooving of the critical regions, z-cut division, and the rough
//! (last layer: intermediate-rough) contour-parallel side cutting, planned by the trochoid
//! insertion planner. A layer like one already planned (same contour, thickness and role)
//! is that plan moved down.

use super::cavity::{Cavity, LayerRole};
use super::spec::{ProcessOptions, ToolCandidate};
use crate::core::analysis::AnalysisSpec;
use crate::core::insertion::{analysis_spec, plan_insertion, InsertionPlan, InsertionSpec};
use crate::core::progress::{Progress, Stage};
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
}

/// The insertion spec of layer `index` for `candidate`.
pub fn layer_spec(cavity: &Cavity, index: usize, candidate: &ToolCandidate, options: &ProcessOptions) -> InsertionSpec {
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
    spec
}

/// Plans every layer of `cavity` with `candidate`.
pub fn plan_layers(
    cavity: &Cavity,
    candidate: &ToolCandidate,
    options: &ProcessOptions,
    progress: &dyn Progress,
) -> Result<Vec<LayerPlan>, CoreError> {
    let mut plans: Vec<LayerPlan> = Vec::with_capacity(cavity.layers.len());
    for (index, layer) in cavity.layers.iter().enumerate() {
        progress.checkpoint()?;
        let role = cavity.role(index);
        let spec = layer_spec(cavity, index, candidate, options);
        let mut analysis = analysis_spec(&layer.pocket, &spec);
        analysis.force_model = Some(candidate.force_model);
        let like = plans.iter().find(|p| {
            p.copy_of.is_none()
                && p.role == role
                && cavity.layers[p.index].pocket == layer.pocket
                && ((p.z_top_mm - p.z_bottom_mm) - layer.thickness_mm()).abs() < SAME_THICKNESS_MM
        });
        let plan = match like {
            Some(original) => LayerPlan {
                index,
                role,
                z_top_mm: layer.z_top_mm,
                z_bottom_mm: layer.z_bottom_mm,
                copy_of: Some(original.index),
                insertion: Arc::clone(&original.insertion),
                toolpath: moved_down(&original.toolpath, layer.z_top_mm - original.z_top_mm, options.safe_z_mm),
                steps: original.steps.clone(),
                analysis,
            },
            None => {
                let stage = Stage::nth(progress, 0.0, 1.0, index, cavity.layers.len());
                let insertion = plan_insertion(&layer.pocket, &spec, None, &stage)?;
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
                }
            }
        };
        plans.push(plan);
    }
    progress.report(1.0);
    Ok(plans)
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
