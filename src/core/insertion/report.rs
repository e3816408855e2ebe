//! What the planner returns: the axis and its classes, the treatments with the area each
//! removes, the program, and the checks of the finished program.

use super::cleared::TrimReport;
use super::compose::LevelMoves;
use super::path_checks::PathChecks;
use super::spec::InsertionSpec;
use super::treatments::{interval_class, Stretch};
use super::verify::{EngagementOutcome, Verification};
use crate::core::analysis::samples::PathSamples;
use crate::core::cycles::CycleReport;
use crate::core::medial::{BranchClasses, CriticalBranches, CriticalInterval, MedialAxis, RadiusClass};
use crate::core::toolpath::Toolpath;
use serde::Serialize;

/// Most moves a warning names (all are in `verification.overloads`).
const MAX_MOVES_IN_WARNING: usize = 8;

/// What a region got.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, utoipa::ToSchema)]
#[serde(rename_all = "snake_case")]
pub enum TreatmentKind {
    /// The contour-parallel (base) path as it is, trimmed where the trochoids cut first.
    Kept,
    /// Trochoid cycles along a stretch of the medial axis.
    Trochoid,
    /// z-cut division: the stretch cut in passes of the reduced axial depth.
    ZCut,
    /// A round region opened from its centre: helical entry, then a spiral out to the walls
    /// in limit-keeping steps (approach hole and spiral hole expansion, seed 004 Table 1).
    Opening,
}

/// What one region got (seed 004 §2.2–2.3) and what it removes, over all levels.
#[derive(Debug, Clone, PartialEq, Serialize, utoipa::ToSchema)]
pub struct Treatment {
    pub kind: TreatmentKind,
    /// The medial-axis branch and the stretch of it (arc length from its first point, mm),
    /// walked from `s_from_mm` to `s_to_mm`; null for the kept path.
    pub branch: Option<usize>,
    pub s_from_mm: Option<f64>,
    pub s_to_mm: Option<f64>,
    /// Radius class of the critical interval the stretch belongs to (its smallest R).
    pub class: Option<RadiusClass>,
    /// Trochoid loops per level.
    pub loops: usize,
    pub pitch_min_mm: Option<f64>,
    pub pitch_max_mm: Option<f64>,
    pub loop_radius_min_mm: Option<f64>,
    pub loop_radius_max_mm: Option<f64>,
    /// z-cut passes per level.
    pub passes_per_level: usize,
    /// Area of the pocket this treatment removes first (at the bottom level), mm².
    pub area_mm2: f64,
    /// Feed length, rapid length and time at the programmed feeds, over all levels.
    pub feed_length_mm: f64,
    pub rapid_length_mm: f64,
    pub time_min: f64,
}

/// The plan.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct InsertionPlan {
    pub axis: MedialAxis,
    pub classes: Vec<BranchClasses>,
    /// Moves of the base path (generated or given).
    pub base_moves: usize,
    /// The base path's engagement before any treatment.
    pub base_max_alpha_deg: f64,
    pub base_overloaded_samples: usize,
    /// Its overloaded samples mapped onto the axis.
    pub critical: CriticalBranches,
    /// The stretches treated (after all rounds).
    pub treated: Vec<CriticalInterval>,
    pub treatments: Vec<Treatment>,
    /// The cutting levels, top first, mm.
    pub levels_mm: Vec<f64>,
    pub toolpath: Toolpath,
    /// Per move of the toolpath: the index of the treatment it belongs to (the moves over the
    /// safe height that lead to a treatment belong to it).
    #[serde(skip)]
    pub move_treatment: Vec<usize>,
    /// Per move: part of an approach hole (a helical entry and the full circle after it).
    #[serde(skip)]
    pub move_entry: Vec<bool>,
    /// What was cut out of the base path, over all levels.
    pub trim: TrimReport,
    pub verification: Verification,
    pub rounds: usize,
    pub pocket_area_mm2: f64,
    /// Feed length that cut nothing, mm: of the base path (its check) and of the finished
    /// program (its verification).
    pub base_air_cut_length_mm: f64,
    pub air_cut_length_mm: f64,
    pub warnings: Vec<String>,
    /// What the drawing of the plan needs beyond the above.
    #[serde(skip)]
    pub drawing: InsertionDrawing,
}

/// The base path, the samples of both simulations and the trochoid loops, for drawing.
#[derive(Debug, Clone, PartialEq)]
pub struct InsertionDrawing {
    pub base_path: Toolpath,
    pub base_samples: PathSamples,
    pub planned_samples: PathSamples,
    /// Per trochoid stretch: the loop centres (the base path of the loops), mm, and the
    /// largest loop radius ρ, mm.
    pub trochoids: Vec<(Vec<[f64; 2]>, f64)>,
}

/// Everything [`assemble`] needs.
pub(super) struct Parts<'a> {
    pub spec: &'a InsertionSpec,
    pub axis: MedialAxis,
    pub classes: Vec<BranchClasses>,
    pub base_check: EngagementOutcome,
    pub critical: CriticalBranches,
    pub intervals: Vec<CriticalInterval>,
    pub stretches: Vec<Stretch>,
    pub per_level: Vec<LevelMoves>,
    pub levels: Vec<f64>,
    pub path: Toolpath,
    pub move_treatment: Vec<usize>,
    pub move_entry: Vec<bool>,
    pub after: EngagementOutcome,
    /// The finished path's geometric checks (found beside its verification).
    pub checks: PathChecks,
    pub rounds: usize,
    pub existing: bool,
    pub base_path: Toolpath,
}

fn range(values: impl Iterator<Item = f64>) -> (Option<f64>, Option<f64>) {
    values.fold((None, None), |(lo, hi), v| {
        (Some(lo.map_or(v, |l: f64| l.min(v))), Some(hi.map_or(v, |h: f64| h.max(v))))
    })
}

pub(super) fn assemble(p: Parts) -> InsertionPlan {
    let spec = p.spec;
    let mut warnings = Vec::new();
    let bottom = p.levels.iter().copied().fold(f64::INFINITY, f64::min);
    let PathChecks {
        coverage,
        base_owner,
        uncleared_mm2: uncleared,
        uncleared_at,
        gouges,
        min_margin_mm: min_margin,
        first_gouge,
    } = p.checks;
    if bottom > spec.z_bottom_mm + super::cleared::SAME_LEVEL_MM {
        warnings.push(format!(
            "the path's lowest cutting level is {bottom} mm, above the layer's bottom {} mm",
            spec.z_bottom_mm
        ));
    }
    let mut treatments = Vec::new();
    for (i, s) in p.stretches.iter().enumerate() {
        let moves: Vec<_> = p.per_level.iter().flat_map(|l| l.stretch_moves[i].iter().copied()).collect();
        let figures = CycleReport::of_moves(&moves, spec.rapid_mm_min);
        let owner = u16::try_from(i).unwrap_or(base_owner);
        let class_of = |branch: usize, s_mm: f64| {
            p.intervals
                .iter()
                .find(|c| c.branch == branch && c.s_start_mm - 1e-6 <= s_mm && s_mm <= c.s_end_mm + 1e-6)
                .map(|c| interval_class(c, spec))
        };
        let t = match s {
            Stretch::Trochoid(t) => {
                let (rho_lo, rho_hi) = range(t.plan.rho_mm.iter().copied());
                Treatment {
                    kind: TreatmentKind::Trochoid,
                    branch: Some(t.branch),
                    s_from_mm: Some(t.s_from_mm),
                    s_to_mm: Some(t.s_to_mm),
                    class: class_of(t.branch, t.s_from_mm),
                    loops: t.plan.loops(),
                    pitch_min_mm: Some(t.pitch_min_mm),
                    pitch_max_mm: Some(t.pitch_max_mm),
                    loop_radius_min_mm: rho_lo,
                    loop_radius_max_mm: rho_hi,
                    passes_per_level: 0,
                    area_mm2: coverage.area_of(owner),
                    feed_length_mm: figures.feed_length_mm,
                    rapid_length_mm: figures.rapid_length_mm,
                    time_min: figures.time_min,
                }
            }
            Stretch::ZCut(z) => Treatment {
                kind: TreatmentKind::ZCut,
                branch: Some(z.branch),
                s_from_mm: Some(z.s_from_mm),
                s_to_mm: Some(z.s_to_mm),
                class: class_of(z.branch, z.s_from_mm),
                loops: 0,
                pitch_min_mm: None,
                pitch_max_mm: None,
                loop_radius_min_mm: None,
                loop_radius_max_mm: None,
                passes_per_level: ((spec.roughing.ad_mm.min(spec.z_top_mm - spec.z_bottom_mm)) / spec.zcut_ad_mm).ceil()
                    as usize,
                area_mm2: coverage.area_of(owner),
                feed_length_mm: figures.feed_length_mm,
                rapid_length_mm: figures.rapid_length_mm,
                time_min: figures.time_min,
            },
            Stretch::Opening(o) => {
                let steps: Vec<f64> = o.radii_mm.windows(2).map(|w| w[1] - w[0]).collect();
                let (step_lo, step_hi) = range(steps.iter().copied());
                Treatment {
                    kind: TreatmentKind::Opening,
                    branch: None,
                    s_from_mm: None,
                    s_to_mm: None,
                    class: None,
                    loops: steps.len(),
                    pitch_min_mm: step_lo,
                    pitch_max_mm: step_hi,
                    loop_radius_min_mm: o.radii_mm.first().copied(),
                    loop_radius_max_mm: Some(o.final_radius_mm()),
                    passes_per_level: 0,
                    area_mm2: coverage.area_of(owner),
                    feed_length_mm: figures.feed_length_mm,
                    rapid_length_mm: figures.rapid_length_mm,
                    time_min: figures.time_min,
                }
            }
        };
        treatments.push(t);
    }
    let base_moves: Vec<_> = p.per_level.iter().flat_map(|l| l.base.iter().copied()).collect();
    let figures = CycleReport::of_moves(&base_moves, spec.rapid_mm_min);
    treatments.push(Treatment {
        kind: TreatmentKind::Kept,
        branch: None,
        s_from_mm: None,
        s_to_mm: None,
        class: None,
        loops: 0,
        pitch_min_mm: None,
        pitch_max_mm: None,
        loop_radius_min_mm: None,
        loop_radius_max_mm: None,
        passes_per_level: 0,
        area_mm2: coverage.area_of(base_owner),
        feed_length_mm: figures.feed_length_mm,
        rapid_length_mm: figures.rapid_length_mm,
        time_min: figures.time_min,
    });
    if p.existing && gouges > 0 {
        warnings.push("the given path comes closer to the walls than the tool radius plus the allowance".to_string());
    }
    let trim = p.per_level.iter().fold(TrimReport::default(), |a, l| TrimReport {
        removed_mm: a.removed_mm + l.trim.removed_mm,
        links: a.links + l.trim.links,
        hops: a.hops + l.trim.hops,
    });
    if p.after.outside.overloaded > 0 {
        warnings.push(format!(
            "{} samples outside the z-cut regions still exceed {}° after {} rounds (largest {:.1}°, first at move {}): see verification.overloads",
            p.after.outside.overloaded,
            spec.alpha_limit_deg,
            p.rounds,
            p.after.outside.max_alpha_deg,
            p.after.first_overload.map_or(0, |o| o.line)
        ));
    }
    if p.after.crossing.overloaded > 0 {
        let spikes = p.after.overloads.iter().filter(|o| o.in_zcut_region);
        let moves: Vec<String> = spikes.map(|o| o.line_from.to_string()).take(MAX_MOVES_IN_WARNING).collect();
        warnings.push(format!(
            "{} samples of full-depth moves exceed {}° where they cross the z-cut regions (largest {:.1}°; short spikes at the corners, at moves {}): see verification.overloads",
            p.after.crossing.overloaded,
            spec.alpha_limit_deg,
            p.after.crossing.max_alpha_deg,
            moves.join(", ")
        ));
    }
    let passed = p.after.outside.overloaded == 0 && gouges == 0 && uncleared <= 0.0;
    let verification = Verification {
        alpha_limit_deg: spec.alpha_limit_deg,
        outside_zcut: p.after.outside,
        inside_zcut: p.after.inside,
        crossing_zcut: p.after.crossing,
        ramps: p.after.ramps,
        first_overload: p.after.first_overload,
        overloads: p.after.overloads.clone(),
        overload_stretches: p.after.overload_stretches,
        gouges,
        min_wall_margin_mm: if min_margin.is_finite() { min_margin } else { 0.0 },
        first_gouge,
        uncleared_area_mm2: uncleared,
        uncleared_at: uncleared_at.map(|q| (q.x, q.y)),
        passed,
    };
    InsertionPlan {
        axis: p.axis,
        classes: p.classes,
        base_moves: p.base_path.moves.len(),
        base_max_alpha_deg: p.base_check.outside.max_alpha_deg,
        base_overloaded_samples: p.base_check.outside.overloaded,
        critical: p.critical,
        treated: p.intervals,
        treatments,
        levels_mm: p.levels,
        toolpath: p.path,
        move_treatment: p.move_treatment,
        move_entry: p.move_entry,
        trim,
        verification,
        rounds: p.rounds,
        pocket_area_mm2: coverage.pocket_area(),
        base_air_cut_length_mm: p.base_check.air_cut_length_mm,
        air_cut_length_mm: p.after.air_cut_length_mm,
        warnings,
        drawing: InsertionDrawing {
            trochoids: trochoid_loops(&p.stretches),
            base_path: p.base_path,
            base_samples: p.base_check.samples,
            planned_samples: p.after.samples,
        },
    }
}

/// Loop radii within this ratio of each other draw as one band (see [`trochoid_loops`]).
const BAND_RADIUS_RATIO: f64 = 1.15;

/// The loop centres of every trochoid stretch, cut into pieces whose loop radii ρ stay
/// within [`BAND_RADIUS_RATIO`] of each other, each with its largest ρ (variable loops
/// grow and shrink along a stretch: one band of the largest ρ would overstate them).
fn trochoid_loops(stretches: &[Stretch]) -> Vec<(Vec<[f64; 2]>, f64)> {
    let mut pieces = Vec::new();
    for s in stretches {
        let Stretch::Trochoid(t) = s else { continue };
        let mut piece: Vec<[f64; 2]> = Vec::new();
        let (mut lo, mut hi) = (f64::INFINITY, 0.0_f64);
        for (c, &rho) in t.plan.centres.iter().zip(&t.plan.rho_mm) {
            if !piece.is_empty() && (rho.max(hi) > BAND_RADIUS_RATIO * rho.min(lo)) {
                let last = *piece.last().unwrap_or(&[c.x, c.y]);
                pieces.push((std::mem::take(&mut piece), hi));
                piece.push(last);
                (lo, hi) = (f64::INFINITY, 0.0);
            }
            piece.push([c.x, c.y]);
            lo = lo.min(rho);
            hi = hi.max(rho);
        }
        if !piece.is_empty() {
            pieces.push((piece, hi));
        }
    }
    pieces
}
