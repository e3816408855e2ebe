//! The scene of a trochoid insertion (seed 004 §2): the pocket, its medial axis by R/r
//! class, the base path with its overloads, and the planned path with its trochoids and
//! the engagement it keeps.

use super::analysis_scene::alpha_limit;
use super::charts::distance_chart;
use super::medial::medial_edges;
use super::outlines::pocket_outlines;
use super::paths::{move_feeds, traced};
use super::regions::marks_of_samples;
use super::scene::{LayerInfo, Quantity, Scene, TrochoidMark};
use super::trace::layer_of;
use crate::core::analysis::samples::PathSamples;
use crate::core::geometry::Pocket;
use crate::core::insertion::{InsertionPlan, InsertionSpec, Treatment, TreatmentKind};

/// The path before the insertion.
pub const BASE_PATH: &str = "base";
/// The path after it.
pub const PLANNED_PATH: &str = "planned";

/// The cutting levels as layers: level k spans from the level above (the pocket's top
/// for the first) down to it.
pub fn level_layers(z_top_mm: f64, levels_mm: &[f64]) -> Vec<LayerInfo> {
    levels_mm
        .iter()
        .enumerate()
        .map(|(k, &z)| {
            let top = if k == 0 { z_top_mm } else { levels_mm[k - 1] };
            LayerInfo { name: format!("level {} (z {z:.3})", k + 1), z_top: top, z_bottom: z }
        })
        .collect()
}

/// The samples with the engagement of the exempt ones (approach holes, ramps, z-cut
/// regions: the verification counts them apart) removed: what the overload marks read.
fn limited(samples: &PathSamples) -> PathSamples {
    let mut out = samples.clone();
    for (alpha, exempt) in out.alpha_deg.iter_mut().zip(&samples.exempt) {
        if *exempt {
            *alpha = None;
        }
    }
    out
}

/// The smallest pitch of the trochoids of loop radius `rho`, mm (of any trochoid when
/// none reports that radius).
fn loop_pitch(plan: &InsertionPlan, rho: f64) -> Option<f64> {
    let trochoids = || plan.treatments.iter().filter(|t| t.kind == TreatmentKind::Trochoid);
    let fits = |t: &&Treatment| {
        let (lo, hi) = (t.loop_radius_min_mm.unwrap_or(f64::NAN), t.loop_radius_max_mm.unwrap_or(f64::NAN));
        rho >= lo - RADIUS_MATCH_MM && rho <= hi + RADIUS_MATCH_MM
    };
    let smallest = |list: Vec<f64>| list.into_iter().filter(|p| p.is_finite() && *p > 0.0).reduce(f64::min);
    smallest(trochoids().filter(fits).filter_map(|t| t.pitch_min_mm).collect())
        .or_else(|| smallest(trochoids().filter_map(|t| t.pitch_min_mm).collect()))
}

/// How far a span's loop radius may be from a treatment's range to be of it, mm.
const RADIUS_MATCH_MM: f64 = 1e-6;

/// The scene of `plan` for `pocket`.
pub fn insertion_scene(pocket: &Pocket, spec: &InsertionSpec, plan: &InsertionPlan) -> Scene {
    let layers = level_layers(spec.z_top_mm, &plan.levels_mm);
    let d = &plan.drawing;
    let at = |z: f64| layer_of(z, &layers);
    let limit = spec.alpha_limit_deg;
    let diameter = spec.tool.diameter_mm;
    // The planned path's trace takes longest: the base path's, the overload marks and the
    // chart are made beside it.
    let (planned, (base, regions, alpha)) = std::thread::scope(|scope| {
        let beside = scope.spawn(|| {
            let base = traced(BASE_PATH, &d.base_path, Some(&d.base_samples), Vec::new(), &layers);
            let mut regions = marks_of_samples(&d.base_samples, limit, diameter, BASE_PATH, at);
            let cutting = limited(&d.planned_samples);
            regions.extend(marks_of_samples(&cutting, limit, diameter, PLANNED_PATH, at));
            let lines =
                [(BASE_PATH, &d.base_samples), ("planned (ramps, approach holes and z-cut regions apart)", &cutting)];
            let alpha = distance_chart(
                "alpha",
                "Engagement α before and after the insertion",
                Quantity::Alpha,
                &lines,
                alpha_limit(limit),
            );
            (base, regions, alpha)
        });
        let planned = traced(
            PLANNED_PATH,
            &plan.toolpath,
            Some(&d.planned_samples),
            vec![(Quantity::Feed, move_feeds(&plan.toolpath))],
            &layers,
        );
        (planned, beside.join().unwrap_or_else(|panic| std::panic::resume_unwind(panic)))
    });
    let trochoids = d
        .trochoids
        .iter()
        .map(|(points, rho)| TrochoidMark {
            layer: None,
            points: points.clone(),
            loop_radius_mm: *rho,
            pitch_mm: loop_pitch(plan, *rho),
            path: Some(PLANNED_PATH.to_string()),
        })
        .collect();
    Scene {
        title: format!(
            "Trochoid insertion: {} mm end mill, {} treatments, base max α {:.1}°, planned max α {:.1}°",
            diameter,
            plan.treatments.len(),
            plan.base_max_alpha_deg,
            plan.verification.outside_zcut.max_alpha_deg
        ),
        tool_diameter_mm: Some(diameter),
        alpha_limit_deg: Some(limit),
        outlines: pocket_outlines(pocket),
        layers,
        paths: vec![base, planned],
        medial: medial_edges(&plan.axis, &plan.classes, None),
        regions,
        trochoids,
        charts: alpha.into_iter().collect(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_cutting_level_spans_from_the_level_above_down_to_itself() {
        let layers = level_layers(0.0, &[-5.0, -10.0]);
        assert_eq!(layers.len(), 2);
        assert!((layers[0].z_top - 0.0).abs() < 1e-12 && (layers[0].z_bottom + 5.0).abs() < 1e-12);
        assert!((layers[1].z_top + 5.0).abs() < 1e-12 && (layers[1].z_bottom + 10.0).abs() < 1e-12);
        assert_eq!(layers[1].name, "level 2 (z -10.000)");
    }
}
