//! Trochoid insertion (seed 004 §2; MODEL.md §6–8): the contour-parallel path of a pocket —
//! generated, or the one given — is analysed; its overloaded samples are mapped onto the
//! medial axis ([`critical_branches`]); each critical stretch gets trochoid cycles (classes A
//! and B) or z-cut division (class C); the base path is cut where the trochoids have removed
//! the material and re-linked; and the finished program is checked by the full simulation.
//!
//! Rounds: samples still above the limit after a round (outside z-cut regions and ramps) are
//! mapped onto the axis again and their stretches treated too, up to [`MAX_ROUNDS`] rounds.

mod cleared;
mod cleared_zone;
mod compose;
mod coverage;
mod distance_transform;
mod observer;
mod opening;
mod path_checks;
pub mod pitch;
mod report;
mod spec;
mod treatments;
mod verify;

#[cfg(test)]
pub(crate) mod program_tests;
#[cfg(test)]
mod tests;

pub use cleared::TrimReport;
pub use cleared_zone::ClearedZone;
pub use compose::{append_over, RAMP_START_ABOVE_MM};
pub use observer::SampleObserver;
pub use report::{InsertionPlan, Treatment, TreatmentKind};
pub use spec::{
    InsertionSpec, LoopSize, DEFAULT_INSERTION_ALPHA_LIMIT_DEG, DEFAULT_WALL_GAP_MM, PITCH_DESIGN_MARGIN_DEG,
};
pub use verify::{EngagementCheck, Overload, Spot, Verification, MAX_LISTED_OVERLOADS};

use crate::core::analysis::geometry::{PathGeometry, SampleGeometry};
use crate::core::analysis::{AnalysisSpec, Stack, StockRegion};
use crate::core::conditions::feed_mm_min;
use crate::core::cycles::setup::DEFAULT_PLUNGE_FEED_RATIO;
use crate::core::cycles::z_levels;
use crate::core::force_model::ForceModel;
use crate::core::geometry::Pocket;
use crate::core::medial::{
    classify, critical_branches, medial_axis, Boundary, CriticalInterval, MedialOptions, NodeKind,
};
use crate::core::pocketing::{contour_parallel, PocketingSpec};
use crate::core::process::parallel;
use crate::core::progress::{Progress, Stage};
use crate::core::toolpath::{section_events, Event, EventKind, Section, Toolpath, Units};
use crate::core::CoreError;
use cleared_zone::ClearedZone as Zone;
use std::collections::HashMap;
use treatments::Stretch;

/// How much longer than its base path a plan may be, for the size check at submission (the
/// test pockets' plans are 1.7–2.7 times as long: trochoid air cuts).
pub const PLANNED_PATH_GROWTH: f64 = 4.0;

/// Most rounds of treatment.
pub const MAX_ROUNDS: usize = 3;

/// The share of a plan's progress its base path's check reports (its share of the slot
/// box's time: 55 of 400 ms).
pub const BASE_CHECK_PROGRESS: f64 = 0.15;

/// The share of the progress still to come that a round's verification reports: a round
/// after it takes its share of what is left, so the progress never goes back.
pub const ROUND_PROGRESS_SHARE: f64 = 0.875;

/// Overloaded samples within this many tool radii of a branch count on it.
pub const AXIS_DISTANCE_RADII: f64 = 1.0;

/// In the later rounds, overloaded samples within this many tool radii of a branch count on
/// it: they are where the base path steps onto the edge of a trochoid band, which lies up to
/// `ρ + r ≤ a·r` from the axis.
pub const REMAP_DISTANCE_RADII: f64 = 2.0;

/// Overloaded samples closer than this many tool radii along a branch form one interval,
/// which is widened by the same amount at both ends.
pub const INTERVAL_MERGE_RADII: f64 = 1.0;

/// The contour-parallel roughing path of `pocket` at every level of the layer (`Ad` of the
/// roughing conditions), the levels joined over the safe height.
pub fn base_path(pocket: &Pocket, spec: &InsertionSpec) -> Result<Toolpath, CoreError> {
    let mut moves = Vec::new();
    for z in z_levels(spec.z_top_mm, spec.z_bottom_mm, spec.roughing.ad_mm)? {
        let feed = feed_mm_min(spec.roughing.fz_mm, spec.tool.flutes, spec.roughing.spindle_rpm);
        let level = contour_parallel(
            pocket,
            &PocketingSpec {
                tool_radius_mm: spec.r_mm(),
                radial_depth_mm: spec.roughing.rd_mm,
                allowance_mm: spec.allowance_mm,
                z_mm: z,
                safe_z_mm: spec.safe_z_mm,
                feed_mm_min: feed,
                plunge_feed_mm_min: DEFAULT_PLUNGE_FEED_RATIO * feed,
                spindle_rpm: spec.roughing.spindle_rpm,
                climb: matches!(spec.direction, crate::core::cycles::CutDirection::Climb),
                corner_loops: false,
            },
        )?;
        compose::append_over(&mut moves, &level.toolpath.moves, spec.safe_z_mm);
    }
    Ok(program(moves))
}

/// Most segments a pocket may have (outer loop and islands together) to be planned. The
/// planners offset the contour dozens of times, and each offset loop can keep as many
/// segments: a saw-tooth edge of 8 000 segments takes 20 s for one contour-parallel path,
/// and the plan and its check take several. **Assumed**: far above a die's contour
/// (`border.dxf` has 8 segments), and low enough that the check before a job is queued
/// stays well within a request.
pub const MAX_PLANNED_SEGMENTS: usize = 10_000;

/// Refuses (naming `field`) a pocket with more segments than the planners take.
pub fn check_pocket_size(pocket: &Pocket, field: &str) -> Result<(), CoreError> {
    let segments: usize = std::iter::once(&pocket.outer).chain(&pocket.islands).map(|l| l.vertices.len()).sum();
    if segments > MAX_PLANNED_SEGMENTS {
        return Err(CoreError::invalid(
            field,
            format!(
                "has {segments} segments (outer loop and islands); the planners take at most {MAX_PLANNED_SEGMENTS}: simplify the contour (fewer, longer lines, or arcs)"
            ),
        ));
    }
    Ok(())
}

/// Checks what can be checked before planning: the spec, the size of the pocket, and
/// (without a given path) that the tool fits in the pocket at all.
pub fn check_plan(pocket: &Pocket, spec: &InsertionSpec, existing: Option<&Toolpath>) -> Result<(), CoreError> {
    spec.validate()?;
    check_pocket_size(pocket, "contour")?;
    let generated;
    let base = match existing {
        Some(path) => path,
        None => {
            generated = base_path(pocket, spec)?;
            &generated
        }
    };
    let analysis = analysis_spec(pocket, spec);
    crate::core::analysis::check(base, &analysis)?;
    let (spacing, samples) = crate::core::analysis::sample_count(base, &analysis);
    let limit = crate::core::analysis::MAX_SAMPLES / PLANNED_PATH_GROWTH;
    if samples > limit {
        return Err(CoreError::invalid(
            "contour",
            format!(
                "the base path takes {samples:.0} samples at {spacing} mm and its plan about {PLANNED_PATH_GROWTH} times as many, more than the {} one analysis may take: plan a smaller pocket or a coarser sample_spacing_mm",
                crate::core::analysis::MAX_SAMPLES
            ),
        ));
    }
    Ok(())
}

/// A tool path of `moves` with the spindle on (clockwise) before the first and off after the
/// last, its moves of no length dropped and the others numbered from 1.
pub fn program(moves: Vec<crate::core::toolpath::Move>) -> Toolpath {
    let unlabelled = vec![None; moves.len()];
    labelled_program(moves, unlabelled)
}

/// [`program`] with a section event before each part: `labels` has one entry per move (the
/// part it belongs to), and a section event starts each run of equal labels.
pub fn labelled_program(moves: Vec<crate::core::toolpath::Move>, labels: Vec<Option<Section>>) -> Toolpath {
    debug_assert_eq!(moves.len(), labels.len());
    // Joins and trims can leave moves of no length; a program has none (our parser drops them).
    let (mut moves, labels): (Vec<_>, Vec<_>) = moves
        .into_iter()
        .zip(labels.into_iter().chain(std::iter::repeat(None)))
        .filter(|(m, _)| {
            matches!(m.motion, crate::core::toolpath::Motion::Arc { .. })
                || crate::core::toolpath::move_length(m) > crate::core::tolerance::LENGTH_EPS_MM
        })
        .unzip();
    for (i, m) in moves.iter_mut().enumerate() {
        m.line = u32::try_from(i + 1).unwrap_or(u32::MAX);
    }
    let last = u32::try_from(moves.len()).unwrap_or(u32::MAX);
    let mut events = vec![Event { kind: EventKind::SpindleOn { clockwise: true }, before_move: 0, line: 1 }];
    events.extend(section_events(&labels));
    events.push(Event { kind: EventKind::SpindleOff, before_move: moves.len(), line: last });
    Toolpath { moves, events, source_units: Units::Mm, warnings: Vec::new() }
}

/// The simulation of a plan's paths.
pub fn analysis_spec(pocket: &Pocket, spec: &InsertionSpec) -> AnalysisSpec {
    AnalysisSpec {
        tool: spec.tool,
        stock: vec![StockRegion::Pocket(pocket.clone())],
        open: Vec::new(),
        z_top: spec.z_top_mm,
        z_bottom: spec.z_bottom_mm,
        force_model: None,
        default_spindle_rpm: Some(spec.roughing.spindle_rpm),
        rapid_mm_min: spec.rapid_mm_min,
        sample_spacing_mm: spec.sample_spacing_mm,
        cell_mm: spec.cell_mm,
        alpha_limit_deg: spec.alpha_limit_deg,
        series_points: 0,
        stock_memory_bytes: spec.stock_memory_bytes,
    }
}

/// Adds `found` to `intervals`, merging overlapping intervals of the same branch.
fn merge_intervals(intervals: &mut Vec<CriticalInterval>, found: Vec<CriticalInterval>) {
    intervals.extend(found);
    intervals.sort_by(|a, b| a.branch.cmp(&b.branch).then(a.s_start_mm.total_cmp(&b.s_start_mm)));
    let mut merged: Vec<CriticalInterval> = Vec::new();
    for c in intervals.drain(..) {
        match merged.last_mut() {
            Some(last) if last.branch == c.branch && c.s_start_mm <= last.s_end_mm => {
                last.s_end_mm = last.s_end_mm.max(c.s_end_mm);
                last.max_alpha_deg = last.max_alpha_deg.max(c.max_alpha_deg);
                last.min_clearance_mm = last.min_clearance_mm.min(c.min_clearance_mm);
                last.samples += c.samples;
            }
            _ => merged.push(c),
        }
    }
    *intervals = merged;
}

/// Plans the trochoid insertion for `pocket`: `existing` is the path to modify (its cutting
/// levels are treated where it first goes down to them), or `None` for the generated
/// contour-parallel path (see the module documentation).
pub fn plan_insertion(
    pocket: &Pocket,
    spec: &InsertionSpec,
    existing: Option<&Toolpath>,
    progress: &dyn Progress,
) -> Result<InsertionPlan, CoreError> {
    plan_rounds(pocket, spec, existing, None, None, false, progress).map(|(plan, _, _)| plan)
}

/// [`plan_insertion`], handing the samples of the base path's check and of the
/// verifications to `observer` when given, and handing back the stock the finished path's
/// verification left.
pub fn plan_insertion_kept(
    pocket: &Pocket,
    spec: &InsertionSpec,
    existing: Option<&Toolpath>,
    observer: Option<&mut dyn SampleObserver>,
    progress: &dyn Progress,
) -> Result<(InsertionPlan, Stack), CoreError> {
    let (plan, _, stack) = plan_rounds(pocket, spec, existing, None, observer, true, progress)?;
    let stack = stack.ok_or_else(|| CoreError::unsolvable("stock", "the verification kept no stock"))?;
    Ok((plan, stack))
}

/// [`plan_insertion`], handing the samples of the base path's check and of the
/// verifications to `observer` (see [`SampleObserver`]).
pub fn plan_insertion_observed(
    pocket: &Pocket,
    spec: &InsertionSpec,
    existing: Option<&Toolpath>,
    observer: &mut dyn SampleObserver,
    progress: &dyn Progress,
) -> Result<InsertionPlan, CoreError> {
    plan_rounds(pocket, spec, existing, None, Some(observer), false, progress).map(|(plan, _, _)| plan)
}

/// [`plan_insertion`], keeping the geometry of every sample of the finished program as its
/// verification simulated it, with `force_model` for the forces at the programmed feeds (so
/// that feeds, wear and time need no other simulation); with `keep_stock`, the stock that
/// verification left too.
pub fn plan_insertion_sampled(
    pocket: &Pocket,
    spec: &InsertionSpec,
    existing: Option<&Toolpath>,
    force_model: ForceModel,
    keep_stock: bool,
    progress: &dyn Progress,
) -> Result<(InsertionPlan, PathGeometry, Option<Stack>), CoreError> {
    let (plan, geometry, stack) = plan_rounds(pocket, spec, existing, Some(force_model), None, keep_stock, progress)?;
    Ok((plan, geometry.unwrap_or_else(|| PathGeometry::new(spec.r_mm())), stack))
}

/// The rounds of treatment; with `sampled`, each round's verification keeps its samples'
/// geometry (the last round's is returned); `observer` sees the samples of the base check
/// and of the verifications. With `keep_stock`, the stock the last verification left is
/// returned too; without, each verification's stock goes as soon as it is checked.
fn plan_rounds(
    pocket: &Pocket,
    spec: &InsertionSpec,
    existing: Option<&Toolpath>,
    sampled: Option<ForceModel>,
    mut observer: Option<&mut dyn SampleObserver>,
    keep_stock: bool,
    progress: &dyn Progress,
) -> Result<(InsertionPlan, Option<PathGeometry>, Option<Stack>), CoreError> {
    spec.validate()?;
    let axis = medial_axis(pocket, &MedialOptions::default())?;
    let classes = classify(&axis, spec.r_mm(), spec.class_a_ratio)?;
    let boundary = Boundary::of_pocket(pocket);
    let base = match existing {
        Some(path) => path.clone(),
        None => base_path(pocket, spec)?,
    };
    let analysis = analysis_spec(pocket, spec);
    let r = spec.r_mm();
    let empty = Zone::new(r);
    let base_roles = verify::MoveRoles { entry: &[], zcut: &[], zcut_zone: &empty };
    let base_stage = Stage { inner: progress, from: 0.0, span: BASE_CHECK_PROGRESS };
    let mut before = verify::check_engagement(&base, &analysis, &base_roles, &base_stage, |s| {
        if let Some(o) = observer.as_deref_mut() {
            o.base(s);
        }
    })?;
    // The base path's stock is not kept: let it go now, as its simulation always did.
    before.stack = None;
    // The verification of the rounds with the force model, when the samples are kept: it
    // changes no engagement, only adds the forces.
    let verifying = AnalysisSpec { force_model: sampled.or(analysis.force_model), ..analysis.clone() };
    let map = |overloaded: &[(crate::core::geometry::Point, f64)], radii: f64| {
        critical_branches(&axis, overloaded, radii * r, INTERVAL_MERGE_RADII * r, INTERVAL_MERGE_RADII * r)
    };
    let found = map(&before.overloaded, AXIS_DISTANCE_RADII);
    let mut intervals = Vec::new();
    merge_intervals(&mut intervals, found.intervals.clone());
    // Round regions (a lone axis point) the base path overloads are opened from their centre.
    let openings: Vec<Stretch> = axis
        .nodes
        .iter()
        .filter(|n| matches!(n.kind, NodeKind::Isolated))
        .filter(|n| {
            let reach = n.point.clearance_mm - r;
            before.overloaded.iter().any(|(p, _)| p.distance_mm(n.point.point) <= reach)
        })
        .filter_map(|n| opening::plan_opening(n.point.point, n.point.clearance_mm, spec))
        .map(Stretch::Opening)
        .collect();
    // Stretches whose loops may use all the room the clearance leaves (see `uncapped`).
    let mut uncapped: Vec<CriticalInterval> = Vec::new();
    let wide = uncapped_spec(spec);
    // The stretches of each interval treated so far: a later round treats again only the
    // intervals it adds, merges or widens (the treatment depends on nothing else).
    let mut treated: HashMap<TreatedKey, Vec<Stretch>> = HashMap::new();
    // The coverage raster with nothing removed depends on neither path: it is made once,
    // beside the first round's treatments, and every round's checks start from a copy.
    let mut making_coverage = Some(path_checks::coverage_beside(pocket, spec));
    let mut blank_coverage: Option<coverage::Coverage> = None;
    let mut rounds = 0;
    let mut reported = BASE_CHECK_PROGRESS;
    loop {
        rounds += 1;
        let round_stage = Stage { inner: progress, from: reported, span: (1.0 - reported) * ROUND_PROGRESS_SHARE };
        reported += round_stage.span;
        let keyed: Vec<(TreatedKey, &CriticalInterval)> = intervals
            .iter()
            .map(|c| {
                let overlaps = |u: &CriticalInterval| {
                    u.branch == c.branch && u.s_start_mm <= c.s_end_mm && c.s_start_mm <= u.s_end_mm
                };
                ((c.branch, c.s_start_mm.to_bits(), c.s_end_mm.to_bits(), uncapped.iter().any(overlaps)), c)
            })
            .collect();
        // The intervals not treated yet are treated side by side: each treatment depends on
        // its interval alone.
        let untreated: Vec<&(TreatedKey, &CriticalInterval)> =
            keyed.iter().filter(|(key, _)| !treated.contains_key(key)).collect();
        let treatments = parallel::map(progress, &untreated, |_, (key, c)| {
            let spec_here = if key.3 { &wide } else { spec };
            treatments::treat_interval(&axis.branches[c.branch], c, &boundary, pocket, spec_here)
        });
        for ((key, _), treatment) in untreated.iter().zip(treatments) {
            treated.insert(*key, treatment?);
        }
        let mut stretches = openings.clone();
        for (key, _) in &keyed {
            stretches.extend(treated.get(key).into_iter().flatten().cloned());
        }
        let (air, zcut) = zones(&stretches, r);
        let composed = compose::compose(&base.moves, &stretches, &air, spec)?;
        let (levels, per_level) = (composed.levels, composed.per_level);
        let path = labelled_program(composed.moves, composed.labels);
        debug_assert_eq!(path.moves.len(), composed.owner.len());
        let mut geometry = sampled.map(|_| PathGeometry::new(r));
        let default_rpm = analysis.default_spindle_rpm;
        let zcut_moves: Vec<bool> =
            composed.owner.iter().map(|&o| matches!(stretches.get(o), Some(Stretch::ZCut(_)))).collect();
        let roles = verify::MoveRoles { entry: &composed.entry, zcut: &zcut_moves, zcut_zone: &zcut };
        if let Some(o) = observer.as_deref_mut() {
            o.restart();
        }
        let coverage = match making_coverage.take() {
            Some(making) => {
                blank_coverage.insert(making.join().unwrap_or_else(|panic| std::panic::resume_unwind(panic))).clone()
            }
            None => blank_coverage.clone().expect("made in the first round"),
        };
        // The path's geometric checks need no simulation: they run beside the verification
        // (spent in vain when a further round follows).
        let (after, checks) = std::thread::scope(|scope| {
            let checks = scope.spawn(|| {
                let stretches = (stretches.len(), per_level.as_slice());
                path_checks::check_path(pocket, &boundary, spec, stretches, &levels, &path, coverage)
            });
            let after = verify::check_engagement(&path, &verifying, &roles, &round_stage, |s| {
                if let Some(g) = geometry.as_mut() {
                    g.samples.push(SampleGeometry::of(s, default_rpm));
                }
                if let Some(o) = observer.as_deref_mut() {
                    o.verified(s);
                }
            });
            (after, checks.join().unwrap_or_else(|panic| std::panic::resume_unwind(panic)))
        });
        let mut after = after?;
        if !keep_stock {
            after.stack = None;
        }
        if let Some(g) = geometry.as_mut() {
            g.removed_volume_mm3 = after.removed_volume_mm3;
        }
        let more = map(&after.overloaded, REMAP_DISTANCE_RADII);
        let inside = |m: &CriticalInterval, set: &[CriticalInterval]| {
            set.iter().any(|c| c.branch == m.branch && c.s_start_mm <= m.s_start_mm && m.s_end_mm <= c.s_end_mm)
        };
        let grows = more.intervals.iter().any(|m| !inside(m, &intervals));
        // Overloads left inside treated stretches come from the edge of a trochoid band the
        // base path then steps onto: widen those trochoids to the walls.
        let widen: Vec<CriticalInterval> = if matches!(spec.loop_size, LoopSize::Variable) {
            more.intervals.iter().filter(|m| inside(m, &intervals) && !inside(m, &uncapped)).cloned().collect()
        } else {
            Vec::new()
        };
        if after.outside.overloaded == 0 || rounds >= MAX_ROUNDS || (!grows && widen.is_empty()) {
            let stack = after.stack.take();
            let plan = report::assemble(report::Parts {
                spec,
                axis,
                classes,
                base_check: before,
                critical: found,
                intervals,
                stretches,
                per_level,
                levels,
                path,
                move_treatment: composed.owner,
                move_entry: composed.entry,
                after,
                checks,
                rounds,
                existing: existing.is_some(),
                base_path: base.clone(),
            });
            return Ok((plan, geometry, stack));
        }
        for m in widen {
            if let Some(c) = intervals
                .iter()
                .find(|c| c.branch == m.branch && c.s_start_mm <= m.s_start_mm && m.s_end_mm <= c.s_end_mm)
            {
                uncapped.push(c.clone());
            }
        }
        merge_intervals(&mut intervals, more.intervals);
    }
}

/// An interval's treatment as [`plan_rounds`] keeps it: the branch, the bits of the interval's
/// ends, and whether its loops may fill the clearance (see [`uncapped_spec`]).
type TreatedKey = (usize, u64, u64, bool);

/// The spec with no cap on the variable loop radius: loops fill the clearance to the walls
/// (`ρ = R − r − allowance − gap`), which leaves no band edge inside the pocket.
fn uncapped_spec(spec: &InsertionSpec) -> InsertionSpec {
    InsertionSpec { class_a_ratio: f64::INFINITY, ..spec.clone() }
}

/// The air zone of the trochoids (loop centres, radius ρ) and the z-cut zone (the inscribed
/// discs along each z-cut stretch).
fn zones(stretches: &[Stretch], r_mm: f64) -> (Zone, Zone) {
    let (mut air, mut zcut) = (Zone::new(r_mm), Zone::new(r_mm));
    for s in stretches {
        match s {
            Stretch::Trochoid(t) => {
                for (c, rho) in t.plan.centres.iter().zip(&t.plan.rho_mm) {
                    air.add(*c, *rho);
                }
            }
            Stretch::Opening(o) => air.add(o.centre, o.final_radius_mm()),
            Stretch::ZCut(z) => {
                for (w, c) in z.path.windows(2).zip(z.clearance_mm.windows(2)) {
                    let n = (w[0].distance_mm(w[1]) / cleared::AIR_TEST_STEP_MM).ceil().max(1.0) as usize;
                    for k in 0..=n {
                        let t = k as f64 / n as f64;
                        let p = crate::core::geometry::Point::new(
                            w[0].x + (w[1].x - w[0].x) * t,
                            w[0].y + (w[1].y - w[0].y) * t,
                        );
                        zcut.add(p, c[0] + (c[1] - c[0]) * t);
                    }
                }
            }
        }
    }
    (air, zcut)
}
