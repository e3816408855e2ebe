//! The answer of a `trochoids` job, as the API documents it: the medial axis with its
//! classes, the treatments with the area each removes, the checks, and the new path as JSON
//! moves (the G-code is at the job's `program` link).

use super::feeds_result::ProgramInfoDto;
use super::setup::{NamedRef, ToolRef};
use super::trochoids::TrochoidsPrepared;
use crate::core::conditions::CuttingConditions;
use crate::core::insertion::{EngagementCheck, InsertionPlan, Overload, Spot, Treatment, TreatmentKind};
use crate::core::medial::{NodeKind, RadiusClass};
use crate::core::nc::{toolpath_to_json, JsonProgram, WrittenProgram};
use serde::Serialize;
use utoipa::ToSchema;

/// Cutting conditions used.
#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct UsedConditionsDto {
    pub spindle_rpm: f64,
    pub fz_mm: f64,
    pub rd_mm: f64,
    pub ad_mm: f64,
    /// Where they come from.
    pub source: String,
}

fn used(c: CuttingConditions, source: String) -> UsedConditionsDto {
    UsedConditionsDto { spindle_rpm: c.spindle_rpm, fz_mm: c.fz_mm, rd_mm: c.rd_mm, ad_mm: c.ad_mm, source }
}

/// A node of the medial axis.
#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct AxisNodeDto {
    pub x: f64,
    pub y: f64,
    /// Clearance radius R, mm.
    pub clearance_mm: f64,
    /// `end`, `junction`, `cycle_start` or `isolated`.
    #[schema(value_type = String)]
    pub kind: NodeKind,
}

/// A stretch of a branch in one radius-ratio class (seed 004 §2.3).
#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct ClassIntervalDto {
    /// `A` (R/r ≥ a: contour-parallel), `B` (trochoids) or `C` (R/r < 1.1: z-cut division).
    #[schema(value_type = String)]
    pub class: RadiusClass,
    pub s_start_mm: f64,
    pub s_end_mm: f64,
}

/// A branch of the medial axis.
#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct AxisBranchDto {
    pub start_node: usize,
    pub end_node: usize,
    pub closed: bool,
    pub length_mm: f64,
    /// `[x, y, R]` of every point, mm.
    pub points: Vec<[f64; 3]>,
    pub classes: Vec<ClassIntervalDto>,
}

/// The medial axis graph (seed 004 §2.1).
#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct AxisDto {
    /// Boundary sampling step, mm.
    pub step_mm: f64,
    pub nodes: Vec<AxisNodeDto>,
    pub branches: Vec<AxisBranchDto>,
}

/// A stretch of a branch where the base path overloads the tool.
#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct CriticalDto {
    pub branch: usize,
    pub s_start_mm: f64,
    pub s_end_mm: f64,
    pub max_alpha_deg: f64,
    pub min_clearance_mm: f64,
    pub samples: usize,
}

/// What one region got (seed 004 §2.2–2.3) and what it removes.
#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct TreatmentDto {
    /// `kept` (the contour-parallel path), `trochoid`, `z_cut`, or `opening` (a round region
    /// opened from its centre: helical entry and a spiral out; `loops` are its turns and
    /// `pitch_*` its growth per turn).
    #[schema(value_type = String)]
    pub kind: TreatmentKind,
    pub branch: Option<usize>,
    /// The stretch of the branch, walked from `s_from_mm` to `s_to_mm`.
    pub s_from_mm: Option<f64>,
    pub s_to_mm: Option<f64>,
    #[schema(value_type = Option<String>)]
    pub class: Option<RadiusClass>,
    /// Trochoid loops per level.
    pub loops: usize,
    pub pitch_min_mm: Option<f64>,
    pub pitch_max_mm: Option<f64>,
    pub loop_radius_min_mm: Option<f64>,
    pub loop_radius_max_mm: Option<f64>,
    /// z-cut passes per level.
    pub passes_per_level: usize,
    /// Pocket area this treatment removes first, mm².
    pub area_mm2: f64,
    pub feed_length_mm: f64,
    pub rapid_length_mm: f64,
    /// At the programmed feeds, min.
    pub time_min: f64,
}

impl From<&Treatment> for TreatmentDto {
    fn from(t: &Treatment) -> Self {
        TreatmentDto {
            kind: t.kind,
            branch: t.branch,
            s_from_mm: t.s_from_mm,
            s_to_mm: t.s_to_mm,
            class: t.class,
            loops: t.loops,
            pitch_min_mm: t.pitch_min_mm,
            pitch_max_mm: t.pitch_max_mm,
            loop_radius_min_mm: t.loop_radius_min_mm,
            loop_radius_max_mm: t.loop_radius_max_mm,
            passes_per_level: t.passes_per_level,
            area_mm2: t.area_mm2,
            feed_length_mm: t.feed_length_mm,
            rapid_length_mm: t.rapid_length_mm,
            time_min: t.time_min,
        }
    }
}

/// Engagement of one kind of sample.
#[derive(Debug, Clone, Copy, Serialize, ToSchema)]
pub struct EngagementCheckDto {
    pub samples: usize,
    pub max_alpha_deg: f64,
    /// Samples above the limit.
    pub overloaded: usize,
}

impl From<EngagementCheck> for EngagementCheckDto {
    fn from(c: EngagementCheck) -> Self {
        EngagementCheckDto { samples: c.samples, max_alpha_deg: c.max_alpha_deg, overloaded: c.overloaded }
    }
}

/// Where a check failed.
#[derive(Debug, Clone, Copy, Serialize, ToSchema)]
pub struct SpotDto {
    pub x: f64,
    pub y: f64,
    pub z: f64,
    /// The program's move (1-based).
    pub move_index: u32,
    /// α, deg (overload) or the wall margin, mm (gouge).
    pub value: f64,
}

impl From<Spot> for SpotDto {
    fn from(s: Spot) -> Self {
        SpotDto { x: s.x_mm, y: s.y_mm, z: s.z_mm, move_index: s.line, value: s.value }
    }
}

/// A stretch of consecutive samples above the engagement limit (a short spike at a corner
/// of a wall pass is a few samples long).
#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct OverloadDto {
    /// First and last line of the job's program (`GET /v1/jobs/{id}/program`) it spans.
    pub program_lines: Option<[u32; 2]>,
    /// First and last move (1-based) of the planned path (of the layer's own plan, in a
    /// plan; the line of the given program, for a given path).
    pub layer_moves: [u32; 2],
    pub samples: usize,
    pub length_mm: f64,
    /// The largest engagement, deg, and where it is (mm; z of the layer's plan, before a
    /// copy of the layer moves down).
    pub max_alpha_deg: f64,
    pub x: f64,
    pub y: f64,
    pub z: f64,
    /// In a region the z-cut division cleared, but on a move at the full depth.
    pub in_zcut_region: bool,
}

impl OverloadDto {
    pub fn new(o: &Overload, program_lines: Option<(u32, u32)>) -> Self {
        OverloadDto {
            program_lines: program_lines.map(|(a, b)| [a, b]),
            layer_moves: [o.line_from, o.line_to],
            samples: o.samples,
            length_mm: o.length_mm,
            max_alpha_deg: o.peak.value,
            x: o.peak.x_mm,
            y: o.peak.y_mm,
            z: o.peak.z_mm,
            in_zcut_region: o.in_zcut_region,
        }
    }
}

/// The checks of the new path by the full simulation.
#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct VerificationDto {
    pub alpha_limit_deg: f64,
    /// Cutting samples outside the z-cut regions: none may be above the limit.
    pub outside_zcut: EngagementCheckDto,
    /// Samples of the z-cut passes (cut at the reduced axial depth).
    pub inside_zcut: EngagementCheckDto,
    /// Samples of the full-depth moves where they cross a z-cut region (the wall pass at a
    /// corner the z-cut division cut first): their spikes are listed in `overloads`.
    pub crossing_zcut: EngagementCheckDto,
    /// Ramps, plunges and the approach holes (helical entries and the circle after them).
    pub ramps: EngagementCheckDto,
    pub first_overload: Option<SpotDto>,
    /// The stretches of samples of the full-depth moves above the limit (outside the z-cut
    /// regions, or crossing them), each with its lines (at most 64 listed; all counted in
    /// `overload_stretches`).
    pub overloads: Vec<OverloadDto>,
    pub overload_stretches: usize,
    /// Test points closer to a wall than r + allowance.
    pub gouges: usize,
    pub min_wall_margin_mm: f64,
    pub first_gouge: Option<SpotDto>,
    /// Area the tool could reach that nothing removed, mm².
    pub uncleared_area_mm2: f64,
    /// `true` when there is no overload outside z-cut, no gouge and nothing uncleared.
    pub passed: bool,
}

/// The answer of a `trochoids` job.
#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct TrochoidsResult {
    pub material: NamedRef,
    pub tool: ToolRef,
    pub machine: NamedRef,
    pub roughing: UsedConditionsDto,
    pub grooving: UsedConditionsDto,
    /// `generated` (contour-parallel) or `given` (the request's program).
    pub base_path: String,
    /// The base path's largest engagement and its samples above the limit.
    pub base_max_alpha_deg: f64,
    pub base_overloaded_samples: usize,
    pub axis: AxisDto,
    /// Where the base path overloads the tool, on the axis.
    pub critical: Vec<CriticalDto>,
    /// Overloaded samples not near the axis (links, entries).
    pub off_axis_samples: usize,
    pub treatments: Vec<TreatmentDto>,
    /// Cutting levels, top first, mm.
    pub levels_mm: Vec<f64>,
    /// Length of the base path left out where the trochoids had cleared, mm; the straight
    /// links and hops written instead.
    pub trimmed_mm: f64,
    pub relinks: usize,
    pub hops: usize,
    pub verification: VerificationDto,
    pub rounds: usize,
    pub pocket_area_mm2: f64,
    pub program: ProgramInfoDto,
    /// The new path as JSON moves (the form `program.moves` of other jobs accepts).
    #[schema(value_type = Object)]
    pub path: JsonProgram,
    pub warnings: Vec<String>,
}

impl TrochoidsResult {
    pub fn new(prepared: TrochoidsPrepared, given: bool, program: &WrittenProgram, plan: InsertionPlan) -> Self {
        let branches = plan
            .axis
            .branches
            .iter()
            .enumerate()
            .map(|(i, b)| AxisBranchDto {
                start_node: b.start_node,
                end_node: b.end_node,
                closed: b.closed,
                length_mm: b.length_mm,
                points: b.points.iter().map(|p| [p.point.x, p.point.y, p.clearance_mm]).collect(),
                classes: plan
                    .classes
                    .iter()
                    .filter(|c| c.branch == i)
                    .flat_map(|c| c.intervals.iter())
                    .map(|c| ClassIntervalDto { class: c.class, s_start_mm: c.s_start_mm, s_end_mm: c.s_end_mm })
                    .collect(),
            })
            .collect();
        let nodes = plan
            .axis
            .nodes
            .iter()
            .map(|n| AxisNodeDto {
                x: n.point.point.x,
                y: n.point.point.y,
                clearance_mm: n.point.clearance_mm,
                kind: n.kind,
            })
            .collect();
        let v = &plan.verification;
        TrochoidsResult {
            roughing: used(prepared.roughing, prepared.roughing_source),
            grooving: used(prepared.grooving, prepared.grooving_source),
            material: prepared.base.material,
            tool: prepared.base.tool,
            machine: prepared.base.machine,
            base_path: if given { "given" } else { "generated" }.to_string(),
            base_max_alpha_deg: plan.base_max_alpha_deg,
            base_overloaded_samples: plan.base_overloaded_samples,
            axis: AxisDto { step_mm: plan.axis.step_mm, nodes, branches },
            critical: plan
                .critical
                .intervals
                .iter()
                .map(|c| CriticalDto {
                    branch: c.branch,
                    s_start_mm: c.s_start_mm,
                    s_end_mm: c.s_end_mm,
                    max_alpha_deg: c.max_alpha_deg,
                    min_clearance_mm: c.min_clearance_mm,
                    samples: c.samples,
                })
                .collect(),
            off_axis_samples: plan.critical.off_axis_samples,
            treatments: plan.treatments.iter().map(TreatmentDto::from).collect(),
            levels_mm: plan.levels_mm.clone(),
            trimmed_mm: plan.trim.removed_mm,
            relinks: plan.trim.links,
            hops: plan.trim.hops,
            verification: VerificationDto {
                alpha_limit_deg: v.alpha_limit_deg,
                outside_zcut: v.outside_zcut.into(),
                inside_zcut: v.inside_zcut.into(),
                crossing_zcut: v.crossing_zcut.into(),
                ramps: v.ramps.into(),
                first_overload: v.first_overload.map(SpotDto::from),
                overloads: v
                    .overloads
                    .iter()
                    .map(|o| {
                        let moves = plan.toolpath.moves.iter().zip(program.move_lines.iter().copied());
                        OverloadDto::new(o, o.written_lines(moves))
                    })
                    .collect(),
                overload_stretches: v.overload_stretches,
                gouges: v.gouges,
                min_wall_margin_mm: v.min_wall_margin_mm,
                first_gouge: v.first_gouge.map(SpotDto::from),
                uncleared_area_mm2: v.uncleared_area_mm2,
                passed: v.passed,
            },
            rounds: plan.rounds,
            pocket_area_mm2: plan.pocket_area_mm2,
            program: ProgramInfoDto {
                moves_in: plan.base_moves,
                moves_out: plan.toolpath.moves.len(),
                lines: program.text.lines().count(),
                bytes: program.text.len(),
            },
            path: toolpath_to_json(&plan.toolpath),
            warnings: plan.warnings,
        }
    }
}
