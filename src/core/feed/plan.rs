//! Feed optimisation of a whole tool path (seed 002 subsystem (d); MODEL.md §3 and §4):
//! the feed every sample needs, the change-rate limit, one feed per NC block, and the
//! figures before and after.

use super::blocks::{BlockOptions, Piece};
use super::collect::{Collector, Kept, ReasonLengths, Shortfall};
use super::guarantee::pieces_pay;
use super::objective::{ForceCurve, ObjectiveSpec};
use super::rule::{FeedReason, FeedRule, SampleCut};
use super::settle::{self, move_ranges, settle, Settled};
use super::split::sub_move;
use crate::core::analysis::engine::SampleResult;
use crate::core::analysis::kept::KeptStock;
use crate::core::analysis::report::{Accumulator, PathPoint, Stats};
use crate::core::analysis::samples::{PathSamples, SampleCollector, DRAWING_SAMPLE_BINS};
use crate::core::analysis::{analyze_from, Analysis, AnalysisSpec, Stack};
use crate::core::progress::Progress;
use crate::core::toolpath::move_length;
use crate::core::toolpath::{Event, Motion, Move, Toolpath};
use crate::core::CoreError;
use serde::Serialize;
use std::ops::Range;

/// Default limit on the change of feed along the path, mm/min per mm (assumed: a
/// corner feed of 500 mm/min is reached from 5760 in about 5 mm).
pub const DEFAULT_MAX_FEED_CHANGE_PER_MM: f64 = 1000.0;
/// Most samples one feed optimisation keeps (it keeps a 44-byte record of every sample
/// for the change-rate limit and the blocks: about 440 MB).
pub const MAX_FEED_SAMPLES: f64 = 10_000_000.0;
/// The slowest feed a written program may carry, mm/min (`F1`): feed limits below it are
/// refused (a feed rounded to `F0` would not be a feed).
pub const MIN_FEED_MM_MIN: f64 = 1.0;

/// How to optimise.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FeedSpec {
    pub rule: FeedRule,
    /// mm/min per mm of path; `None`: no limit.
    pub max_change_per_mm: Option<f64>,
    pub blocks: BlockOptions,
    /// For the time figures, mm/min.
    pub rapid_mm_min: f64,
}

/// Figures of one program.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Figures {
    /// Predicted force over the cutting samples, N (length-weighted).
    pub force_n: Option<Stats>,
    /// Feed over the feed moves, mm/min (length-weighted).
    pub feed_mm_min: Stats,
    /// Feed moves at their feeds plus rapids at the rapid rate, min.
    pub time_min: f64,
}

/// The feed of one block of the optimised program.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct BlockFeed {
    /// Source line of the move the block comes from.
    pub line: u32,
    pub length_mm: f64,
    /// `None` for rapids.
    pub programmed_mm_min: Option<f64>,
    pub feed_mm_min: Option<f64>,
}

/// The optimised program and what changed.
#[derive(Debug, Clone, PartialEq)]
pub struct FeedPlan {
    pub path: Toolpath,
    /// The rapid rate the time figures use, mm/min.
    pub rapid_mm_min: f64,
    pub blocks: Vec<BlockFeed>,
    /// Per move of the input (by index): its pieces, from fraction `t0` to `t1` of its
    /// length, each with its feed (one piece `0..1` at the programmed feed where the move
    /// keeps it; none for rapids). `path` holds the same pieces as moves.
    pub pieces: Vec<Vec<Piece>>,
    /// Moves whose new feeds would have cost more than their programmed feed, and that
    /// keep it (min_cost).
    pub kept_moves: usize,
    pub before: Figures,
    pub after: Figures,
    pub lengths: ReasonLengths,
    /// Length where the change-rate limit lowered the feed, mm.
    pub rate_limited_mm: f64,
    pub shortfalls: Vec<Shortfall>,
    /// The analysis of the input path (side milling).
    pub analysis: Option<Analysis>,
    pub warnings: Vec<String>,
    /// Samples kept for drawing, before and after (side milling).
    pub drawing: Option<FeedDrawing>,
}

/// The kept samples of the input path at its programmed feeds (`before`) and at the
/// optimised feeds (`after`: feed and predicted force changed, positions the same).
#[derive(Debug, Clone, PartialEq)]
pub struct FeedDrawing {
    pub before: PathSamples,
    pub after: PathSamples,
}

/// Checks the spec.
pub fn check_spec(spec: &FeedSpec) -> Result<(), CoreError> {
    let r = &spec.rule;
    let positive = |field: &str, v: f64| crate::core::error::require_positive(field, v).map(|_| ());
    for (field, feed) in [
        ("min_feed_mm_min", r.min_feed_mm_min),
        ("max_feed_mm_min", r.max_feed_mm_min),
        ("air_feed_mm_min", r.air_feed_mm_min),
    ] {
        if !(feed.is_finite() && feed >= MIN_FEED_MM_MIN) {
            return Err(CoreError::invalid(
                field,
                format!("must be a finite feed of at least {MIN_FEED_MM_MIN} mm/min"),
            ));
        }
    }
    positive("rapid_mm_min", spec.rapid_mm_min)?;
    if r.min_feed_mm_min > r.max_feed_mm_min {
        return Err(CoreError::invalid("min_feed_mm_min", "must not be above max_feed_mm_min"));
    }
    if r.strategy.needs_force_model() {
        if r.force_model.is_none() {
            return Err(CoreError::invalid("strategy", "constant force needs a force model for the tool"));
        }
        positive("target_force_n", r.target_force_n)?;
    }
    if let Some(rate) = spec.max_change_per_mm {
        positive("max_feed_change_per_mm", rate)?;
    }
    let b = &spec.blocks;
    if !(b.min_block_mm.is_finite() && b.min_block_mm >= 0.0) {
        return Err(CoreError::invalid("min_block_mm", "must be a finite number ≥ 0"));
    }
    if !(b.tolerance.is_finite() && b.tolerance >= 0.0) {
        return Err(CoreError::invalid("feed_tolerance", "must be a finite number ≥ 0"));
    }
    if !(b.feed_step_mm_min.is_finite() && b.feed_step_mm_min >= 0.0) {
        return Err(CoreError::invalid("feed_step_mm_min", "must be a finite number ≥ 0"));
    }
    Ok(())
}

/// Refuses an optimisation of more than [`MAX_FEED_SAMPLES`] samples.
pub fn check_sample_count((spacing_mm, samples): (f64, f64)) -> Result<(), CoreError> {
    if samples > MAX_FEED_SAMPLES {
        return Err(CoreError::invalid(
            "sample_spacing_mm",
            format!(
                "the path needs {samples:.0} samples at {spacing_mm} mm; feed optimisation takes at most {MAX_FEED_SAMPLES:.0}: sample more coarsely"
            ),
        ));
    }
    Ok(())
}

/// Optimises the feeds of a 2.5-D side-milling path by the papers' rule of its strategy,
/// simulating the stock of `analysis`.
pub fn optimize_side_milling(
    path: &Toolpath,
    analysis: &AnalysisSpec,
    spec: &FeedSpec,
    progress: &dyn Progress,
) -> Result<FeedPlan, CoreError> {
    optimize_side_milling_with(path, analysis, None, spec, None, progress, |_| {}).map(|(plan, _)| plan)
}

/// Optimises the feeds of a 2.5-D side-milling path for `objective` (`None`: the papers'
/// rule of the strategy), simulating the stock of `analysis` (or the stock `start` another
/// simulation left, see [`analyze_from`]) and handing every sample of that simulation to
/// `sink` too. Also hands back the stock the path leaves: the optimised program cuts the
/// same path, so it leaves the same stock.
pub fn optimize_side_milling_with(
    path: &Toolpath,
    analysis: &AnalysisSpec,
    start: Option<&KeptStock>,
    spec: &FeedSpec,
    objective: Option<ObjectiveSpec>,
    progress: &dyn Progress,
    mut sink: impl FnMut(&SampleResult),
) -> Result<(FeedPlan, Stack), CoreError> {
    check_spec(spec)?;
    check_sample_count(crate::core::analysis::sample_count(path, analysis))?;
    let tool_radius_mm = analysis.tool.radius_mm();
    let mut collector = Collector::with_objective(spec.rule, objective, tool_radius_mm);
    let total_length_mm: f64 = path.moves.iter().map(move_length).sum();
    let mut drawing = SampleCollector::new(total_length_mm, DRAWING_SAMPLE_BINS);
    let default_rpm = analysis.default_spindle_rpm;
    let (report, stack) = analyze_from(path, analysis, start, progress, |r| {
        sink(r);
        drawing.add(r);
        let s = &r.sample;
        let in_material = r.contact.alpha_rad > 0.0;
        let cut = SampleCut {
            alpha_rad: r.contact.alpha_rad,
            arc_length_mm: r.arc_length_mm,
            ad_mm: r.ad_mm,
            cutting_point_ratio: r.cutting_point_ratio,
            centre_radius_mm: r.centre_radius_mm,
            tool_radius_mm: r.contact_radius_mm,
            programmed_feed_mm_min: s.feed_mm_min,
            spindle_rpm: s.spindle_rpm.or(default_rpm),
            // A move straight down keeps its feed, in material or not.
            plunge: r.plunge || (!s.rapid && s.heading.0.abs() + s.heading.1.abs() < f64::EPSILON),
            in_material,
        };
        collector.add(&super::collect::SampleIn {
            at: PathPoint { s_mm: r.s_mm, line: s.line, x: s.p.x, y: s.p.y, z: s.p.z },
            step_mm: s.step_mm,
            move_index: s.move_index,
            rapid: s.rapid,
            cut,
            force_before_n: r.force_n.filter(|_| in_material),
        });
    })?;
    collector.finish();
    let mut warnings = report.summary.warnings.clone();
    if spec.rule.force_model.is_some() && collector.kept.len() > 1 && report.summary.slices.len() > 1 {
        warnings.push(
            "the layer is simulated in several z slices: the constant-force feed uses the deepest engagement over the whole depth of cut"
                .to_string(),
        );
    }
    Ok((assemble(path, collector, spec, Some((report, drawing.finish())), warnings), stack))
}

/// Puts the optimised program together from the collected samples.
pub fn assemble(
    path: &Toolpath,
    collector: Collector,
    spec: &FeedSpec,
    analysis: Option<(Analysis, PathSamples)>,
    mut warnings: Vec<String>,
) -> FeedPlan {
    let (analysis, before) = analysis.unzip();
    let drawn: Vec<usize> = before.as_ref().map(|b| b.index.clone()).unwrap_or_default();
    let mut after_values: Vec<(Option<f64>, Option<f64>)> = Vec::with_capacity(drawn.len());
    let Collector { kept, lengths, shortfalls, objective, tool_radius_mm, .. } = collector;
    let ranges = move_ranges(&path.moves, &kept);
    let Settled { limited, rate_limited_mm, keeps_programmed, all_checked } =
        settle(&path.moves, &kept, &ranges, spec, objective.as_ref(), tool_radius_mm);
    let model = spec.rule.force_model;
    let (mut force_before, mut force_after) = (Accumulator::default(), Accumulator::default());
    let mut moves: Vec<Move> = Vec::with_capacity(path.moves.len());
    let mut blocks: Vec<BlockFeed> = Vec::with_capacity(path.moves.len());
    let mut move_pieces: Vec<Vec<Piece>> = Vec::with_capacity(path.moves.len());
    let mut kept_moves = 0;
    let mut first_piece = Vec::with_capacity(path.moves.len() + 1);
    for (index, m) in path.moves.iter().enumerate() {
        first_piece.push(moves.len());
        let Range { start, end: i } = ranges[index].clone();
        let samples = &kept[start..i];
        let mut drawn_here = drawn.partition_point(|&d| d < start)..drawn.partition_point(|&d| d < i);
        if matches!(m.motion, Motion::Rapid) || samples.is_empty() {
            after_values.extend(drawn_here.map(|d| {
                let k = &kept[drawn[d]];
                (finite(k.programmed_mm_min).filter(|_| !matches!(m.motion, Motion::Rapid)), finite(k.force_before_n))
            }));
            blocks.push(BlockFeed {
                line: m.line,
                length_mm: move_length(m),
                programmed_mm_min: None,
                feed_mm_min: None,
            });
            move_pieces.push(match (m.motion, m.feed_mm_min) {
                (Motion::Rapid, _) | (_, None) => vec![],
                (_, Some(f)) => vec![Piece { t0: 0.0, t1: 1.0, feed_mm_min: f }],
            });
            moves.push(*m);
            continue;
        }
        let mut pieces = settle::move_pieces(m, &kept, &limited, start..i, spec);
        // min_cost keeps the programmed feed where the new ones would not pay.
        if let (Some(objective), Some(programmed)) = (&objective, m.feed_mm_min) {
            let pays = || all_checked || pieces_pay(samples, &pieces, &spec.rule, objective, tool_radius_mm);
            if keeps_programmed[index] || !pays() {
                pieces = vec![Piece { t0: 0.0, t1: 1.0, feed_mm_min: programmed }];
                kept_moves += 1;
            }
        }
        let n = samples.len() as f64;
        let mut p = 0;
        for (k, s) in samples.iter().enumerate() {
            let t = (k + 1) as f64 / n;
            while p + 1 < pieces.len() && t > pieces[p].t1 + f64::EPSILON {
                p += 1;
            }
            let mut after_n = None;
            if let (Some(model), Some(before)) = (model, finite(s.force_before_n)) {
                let after = force_at_feed(model, s, pieces[p].feed_mm_min, spec.rule.flutes, tool_radius_mm);
                force_before.add(before, f64::from(s.step_mm));
                force_after.add(after, f64::from(s.step_mm));
                after_n = Some(after);
            }
            if drawn_here.start < drawn_here.end && drawn[drawn_here.start] == start + k {
                after_values.push((Some(pieces[p].feed_mm_min), after_n));
                drawn_here.start += 1;
            }
        }
        push_pieces(m, &pieces, &mut moves, &mut blocks);
        move_pieces.push(pieces);
    }
    first_piece.push(moves.len());
    let events: Vec<Event> = path
        .events
        .iter()
        .map(|e| Event { before_move: first_piece[e.before_move.min(path.moves.len())], ..*e })
        .collect();
    if kept_moves > 0 {
        warnings.push(format!(
            "{kept_moves} move(s) keep their programmed feed: their new feeds would have cost more (min_cost)"
        ));
    }
    if lengths.kept_mm > 0.0 {
        warnings.push(format!(
            "{:.1} mm of cutting kept its programmed feed (plunges, or no spindle speed to compute with)",
            lengths.kept_mm
        ));
    }
    let new_path = Toolpath { moves, events, source_units: path.source_units, warnings: path.warnings.clone() };
    let has_force = model.is_some() && force_before.stats().max > 0.0;
    FeedPlan {
        before: figures(&path.moves, has_force.then(|| force_before.stats()), spec.rapid_mm_min),
        after: figures(&new_path.moves, has_force.then(|| force_after.stats()), spec.rapid_mm_min),
        path: new_path,
        rapid_mm_min: spec.rapid_mm_min,
        blocks,
        pieces: move_pieces,
        kept_moves,
        lengths,
        rate_limited_mm,
        shortfalls,
        analysis,
        warnings,
        drawing: before.map(|before| {
            let after = PathSamples {
                feed_mm_min: after_values.iter().map(|v| v.0).collect(),
                force_n: after_values.iter().map(|v| v.1).collect(),
                ..before.clone()
            };
            FeedDrawing { before, after }
        }),
    }
}

fn finite(v: f32) -> Option<f64> {
    v.is_finite().then_some(f64::from(v))
}

/// The force at a sample when run at `feed` instead of the programmed feed: the force
/// before, scaled by the model's ratio of the two (exact for a single slice; see
/// [`ForceCurve`]).
fn force_at_feed(
    model: crate::core::force_model::ForceModel,
    s: &Kept,
    feed_mm_min: f64,
    flutes: u32,
    tool_radius_mm: f64,
) -> f64 {
    let rpm = f64::from(s.spindle_rpm);
    if rpm <= 0.0 {
        return 0.0;
    }
    let before = finite(s.force_before_n).filter(|_| s.reason != Some(FeedReason::Air));
    ForceCurve::new(model, &s.cut(tool_radius_mm), flutes, rpm, before).force_n(feed_mm_min)
}

/// The optimiser's figures of `moves`: feed statistics and the time at their feeds.
pub fn figures(moves: &[Move], force_n: Option<Stats>, rapid_mm_min: f64) -> Figures {
    let mut feed = Accumulator::default();
    let mut minutes = 0.0;
    for m in moves {
        let len = move_length(m);
        match (m.motion, m.feed_mm_min) {
            (Motion::Rapid, _) => minutes += len / rapid_mm_min,
            (_, Some(f)) if f > 0.0 => {
                minutes += len / f;
                feed.add(f, len);
            }
            _ => {}
        }
    }
    Figures { force_n, feed_mm_min: feed.stats(), time_min: minutes }
}

/// The program of `input` with every move cut into its `pieces` (one per input move; a
/// move without pieces, a rapid, stays as it is), and its blocks.
pub fn written(input: &Toolpath, pieces: &[Vec<Piece>]) -> (Toolpath, Vec<BlockFeed>) {
    let mut moves = Vec::with_capacity(input.moves.len());
    let mut blocks = Vec::with_capacity(input.moves.len());
    let mut first_piece = Vec::with_capacity(input.moves.len() + 1);
    for (m, pieces) in input.moves.iter().zip(pieces) {
        first_piece.push(moves.len());
        if pieces.is_empty() {
            blocks.push(BlockFeed {
                line: m.line,
                length_mm: move_length(m),
                programmed_mm_min: None,
                feed_mm_min: None,
            });
            moves.push(*m);
        }
        push_pieces(m, pieces, &mut moves, &mut blocks);
    }
    first_piece.push(moves.len());
    let events = input
        .events
        .iter()
        .map(|e| Event { before_move: first_piece[e.before_move.min(input.moves.len())], ..*e })
        .collect();
    (Toolpath { moves, events, source_units: input.source_units, warnings: input.warnings.clone() }, blocks)
}

/// Appends the pieces of `m` to `moves`, each the part of `m` between its fractions at its
/// feed, and their blocks.
fn push_pieces(m: &Move, pieces: &[Piece], moves: &mut Vec<Move>, blocks: &mut Vec<BlockFeed>) {
    let length = move_length(m);
    for piece in pieces {
        let mut sub = sub_move(m, piece.t0, piece.t1);
        sub.feed_mm_min = Some(piece.feed_mm_min);
        blocks.push(BlockFeed {
            line: m.line,
            length_mm: length * (piece.t1 - piece.t0),
            programmed_mm_min: m.feed_mm_min,
            feed_mm_min: Some(piece.feed_mm_min),
        });
        moves.push(sub);
    }
}
