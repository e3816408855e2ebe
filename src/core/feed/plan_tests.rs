//! The whole-path feed optimiser on paths whose answer is known (MODEL.md §3 and §4).

use super::blocks::BlockOptions;
use super::plan::{optimize_side_milling, FeedSpec};
use super::rule::{FeedRule, FeedStrategy};
use super::surface::{optimize_surface_finishing, ContactNormal, SurfaceSpec};
use crate::core::analysis::{analyze, AnalysisSpec, StockRegion, DEFAULT_ALPHA_LIMIT_DEG};
use crate::core::fixtures::seed_001_ten_mm;
use crate::core::progress::NoProgress;
use crate::core::stock::Rect;
use crate::core::tool::{EndMill, ToolType};
use crate::core::toolpath::{Event, EventKind, Motion, Move, Plane, Toolpath, Units, P3};

const R: f64 = 5.0;
const TARGET_N: f64 = 269.1;
const STANDARD_FEED: f64 = 5760.0;
const MIN_FEED: f64 = 288.0;
const MAX_FEED: f64 = 2.0 * STANDARD_FEED;

fn analysis_spec(open: Vec<StockRegion>) -> AnalysisSpec {
    AnalysisSpec {
        tool: EndMill { tool_type: ToolType::Square, diameter_mm: 2.0 * R, flutes: 6, corner_radius_mm: 0.0 },
        stock: vec![StockRegion::Rect(Rect { x_min: -60.0, y_min: -60.0, x_max: 60.0, y_max: 60.0 })],
        open,
        z_top: 0.0,
        z_bottom: -10.0,
        force_model: Some(seed_001_ten_mm()),
        default_spindle_rpm: Some(9600.0),
        rapid_mm_min: 20000.0,
        sample_spacing_mm: None,
        cell_mm: None,
        alpha_limit_deg: DEFAULT_ALPHA_LIMIT_DEG,
        series_points: 4000,
        stock_memory_bytes: crate::core::analysis::DEFAULT_STOCK_MEMORY_BYTES,
    }
}

fn spec(strategy: FeedStrategy, max_change_per_mm: Option<f64>) -> FeedSpec {
    FeedSpec {
        rule: FeedRule {
            strategy,
            force_model: Some(seed_001_ten_mm()),
            target_force_n: TARGET_N,
            flutes: 6,
            min_feed_mm_min: MIN_FEED,
            max_feed_mm_min: MAX_FEED,
            air_feed_mm_min: MAX_FEED,
        },
        max_change_per_mm,
        blocks: BlockOptions::default(),
        rapid_mm_min: 20000.0,
    }
}

fn feed_move(motion: Motion, start: P3, end: P3, line: u32) -> Move {
    Move { motion, start, end, feed_mm_min: Some(STANDARD_FEED), spindle_rpm: Some(9600.0), tool: None, line }
}

fn path(moves: Vec<Move>) -> Toolpath {
    Toolpath { moves, events: vec![], source_units: Units::Mm, warnings: vec![] }
}

/// An approach from the centre through open ground, then a full circle whose outer wall is a concave
/// arc of radius `ratio · r` (Rd 0.5, the whole 10 mm depth).
fn concave_circle(ratio: f64) -> (Toolpath, Vec<StockRegion>) {
    let rc = (ratio - 1.0) * R;
    let z = -10.0;
    let s = P3::new(rc, 0.0, z);
    let approach = feed_move(Motion::Linear, P3::new(0.0, 0.0, z), s, 1);
    let circle =
        feed_move(Motion::Arc { center: P3::new(0.0, 0.0, z), clockwise: false, plane: Plane::Xy, turns: 0 }, s, s, 2);
    let open = vec![StockRegion::Circle { cx: 0.0, cy: 0.0, r: ratio * R - 0.5 }];
    (path(vec![approach, circle]), open)
}

#[test]
fn constant_force_in_a_concave_arc_of_r_over_r_2_runs_at_the_model_section_3_feed() {
    let (p, open) = concave_circle(2.0);
    let plan =
        optimize_side_milling(&p, &analysis_spec(open), &spec(FeedStrategy::ConstantForce, None), &NoProgress).unwrap();
    // Most of the circle is one block at the constant-force feed.
    let arc = plan.blocks.iter().filter(|b| b.line == 2).max_by(|a, b| a.length_mm.total_cmp(&b.length_mm)).unwrap();
    let feed = arc.feed_mm_min.unwrap();
    assert!((feed - 1160.0).abs() / 1160.0 < 0.02 && arc.length_mm > 20.0, "{:?}", plan.blocks);
    // The approach is in the air and the end of the circle re-enters its own cut.
    assert!(plan.blocks.iter().any(|b| b.line == 1 && b.feed_mm_min == Some(MAX_FEED)));
    // The approach ends head-on into the wall (α up to 73°): no feed holds the target
    // there, and that is reported.
    assert!(plan.shortfalls.iter().any(|s| s.end.line == 1 && s.max_alpha_deg > 60.0), "{:?}", plan.shortfalls);
    let (before, after) = (plan.before.force_n.unwrap(), plan.after.force_n.unwrap());
    assert!(after.max < before.max && after.std_dev < before.std_dev, "{before:?} → {after:?}");
}

#[test]
fn re_analysing_the_optimised_path_predicts_the_target_force_wherever_the_feed_is_not_clamped() {
    for ratio in [3.0, 2.0, 1.6] {
        let (p, open) = concave_circle(ratio);
        let aspec = analysis_spec(open);
        let plan =
            optimize_side_milling(&p, &aspec, &spec(FeedStrategy::ConstantForce, Some(1000.0)), &NoProgress).unwrap();
        let again = analyze(&plan.path, &aspec, &NoProgress).unwrap();
        let series = again.series.unwrap();
        let mut checked = 0;
        for i in 0..series.s_mm.len() {
            let (feed, force) = (series.feed_mm_min[i], series.force_n[i].unwrap_or(0.0));
            let clamped = feed >= MAX_FEED - 1.0 || feed <= MIN_FEED + 1.0;
            if series.alpha_deg[i] > 1.0 && !clamped {
                assert!(force <= TARGET_N * 1.02, "R/r {ratio}: {force} N at s {}", series.s_mm[i]);
                // Away from the entry and the exit (where blocks run a little slower).
                let circle = 2.0 * std::f64::consts::PI * (ratio - 1.0) * R;
                let along = series.s_mm[i] - (ratio - 1.0) * R;
                if series.line[i] == 2 && along > 0.2 * circle && along < 0.8 * circle {
                    assert!((force - TARGET_N).abs() / TARGET_N < 0.02, "R/r {ratio}: {force} N at {}", series.s_mm[i]);
                    checked += 1;
                }
            }
        }
        assert!(checked > 10, "R/r {ratio}: only {checked} samples checked");
    }
}

#[test]
fn the_rate_limit_brings_the_feed_down_before_the_arc_and_never_raises_it() {
    let (p, open) = concave_circle(2.0);
    let aspec = analysis_spec(open);
    let free = optimize_side_milling(&p, &aspec, &spec(FeedStrategy::ConstantForce, None), &NoProgress).unwrap();
    let limited =
        optimize_side_milling(&p, &aspec, &spec(FeedStrategy::ConstantForce, Some(1000.0)), &NoProgress).unwrap();
    assert!(limited.rate_limited_mm > 5.0, "{}", limited.rate_limited_mm);
    // The approach ends slower than the air-cut feed: the feed has come down in time.
    let approach: Vec<f64> = limited.blocks.iter().filter(|b| b.line == 1).filter_map(|b| b.feed_mm_min).collect();
    assert!(approach.len() > 1 && *approach.last().unwrap() < 2000.0, "{approach:?}");
    assert!(limited.after.time_min > free.after.time_min);
    assert!(limited.after.force_n.unwrap().max <= free.after.force_n.unwrap().max + 1e-6);
}

#[test]
fn every_feed_lies_within_the_limits_and_events_follow_their_moves() {
    let (mut p, open) = concave_circle(1.2);
    p.events.push(Event { kind: EventKind::Coolant { on: true }, before_move: 1, line: 2 });
    let plan =
        optimize_side_milling(&p, &analysis_spec(open), &spec(FeedStrategy::Both, Some(1000.0)), &NoProgress).unwrap();
    for m in &plan.path.moves {
        let f = m.feed_mm_min.unwrap();
        assert!((MIN_FEED..=MAX_FEED).contains(&f), "{f}");
    }
    assert!(!plan.shortfalls.is_empty(), "R/r 1.2 cannot reach the target");
    let first_arc = plan.path.moves.iter().position(|m| m.line == 2).unwrap();
    assert_eq!(plan.path.events[0].before_move, first_arc);
}

fn surface_spec(contact: ContactNormal) -> SurfaceSpec {
    SurfaceSpec { ball_radius_mm: 3.0, sample_spacing_mm: 0.05, fit_half_width_mm: 1.0, contact }
}

fn cutting_point_spec() -> FeedSpec {
    let mut s = spec(FeedStrategy::CuttingPoint, None);
    s.rule.force_model = None;
    s.rule.max_feed_mm_min = 10_000.0;
    s.rule.min_feed_mm_min = 10.0;
    s
}

/// Minute G1 segments (0.1 mm) along a circle in the XZ plane about (0, `zc`) of radius
/// `rc`, below the centre (a valley) or above it (a bump), from −30° to +30°.
fn xz_arc_polyline(rc: f64, valley: bool) -> Toolpath {
    let n = ((rc * std::f64::consts::FRAC_PI_3) / 0.1).ceil() as usize;
    let point = |k: usize| {
        let a = -std::f64::consts::FRAC_PI_6 + std::f64::consts::FRAC_PI_3 * k as f64 / n as f64;
        let z = if valley { rc - rc * a.cos() } else { rc * a.cos() - rc };
        P3::new(rc * a.sin(), 0.0, z)
    };
    let mut moves = vec![];
    for k in 0..n {
        let mut m = feed_move(Motion::Linear, point(k), point(k + 1), k as u32 + 1);
        m.feed_mm_min = Some(1200.0);
        m.spindle_rpm = Some(8000.0);
        moves.push(m);
    }
    path(moves)
}

fn middle_feed(plan: &super::plan::FeedPlan) -> f64 {
    let n = plan.path.moves.len();
    plan.path.moves[n / 2].feed_mm_min.unwrap()
}

#[test]
fn seed_000_ball_finishing_runs_0_61_times_in_a_valley_and_3_2_times_over_a_bump() {
    // seed 000: a 3 mm ball, 1200 mm/min at the cutting point; R/(R+r) = 0.61 and
    // R/(R−r) = 3.2 (MODEL.md §4).
    let r = 3.0;
    let valley = xz_arc_polyline(0.61 * r / 0.39, true);
    let bump = xz_arc_polyline(3.2 * r / 2.2, false);
    for contact in [ContactNormal::Down, ContactNormal::PrincipalNormal] {
        let v = optimize_surface_finishing(&valley, &surface_spec(contact.clone()), &cutting_point_spec(), &NoProgress)
            .unwrap();
        let b = optimize_surface_finishing(&bump, &surface_spec(contact.clone()), &cutting_point_spec(), &NoProgress)
            .unwrap();
        assert!((middle_feed(&v) / 1200.0 - 0.61).abs() < 0.01, "{contact:?}: valley {}", middle_feed(&v));
        assert!((middle_feed(&b) / 1200.0 - 3.2).abs() < 0.03, "{contact:?}: bump {}", middle_feed(&b));
    }
}

#[test]
fn a_straight_finishing_path_keeps_its_feed_and_a_g18_arc_is_exact() {
    let mut line = feed_move(Motion::Linear, P3::new(0.0, 0.0, 0.0), P3::new(50.0, 0.0, -10.0), 1);
    line.feed_mm_min = Some(1200.0);
    let plan = optimize_surface_finishing(
        &path(vec![line]),
        &surface_spec(ContactNormal::Down),
        &cutting_point_spec(),
        &NoProgress,
    )
    .unwrap();
    assert_eq!(plan.path.moves.len(), 1);
    assert!((plan.path.moves[0].feed_mm_min.unwrap() - 1200.0).abs() < 1e-9);
    // A valley as a G18 arc about (0, 0, 4.692): R/(R + r) = 0.61.
    let rc = 0.61 * 3.0 / 0.39;
    let (a, b) = (0.5f64, -0.5f64);
    let mut arc = feed_move(
        Motion::Arc { center: P3::new(0.0, 0.0, rc), clockwise: false, plane: Plane::Zx, turns: 0 },
        P3::new(rc * b.sin(), 0.0, rc - rc * b.cos()),
        P3::new(rc * a.sin(), 0.0, rc - rc * a.cos()),
        1,
    );
    arc.feed_mm_min = Some(1200.0);
    let plan = optimize_surface_finishing(
        &path(vec![arc]),
        &surface_spec(ContactNormal::Down),
        &cutting_point_spec(),
        &NoProgress,
    )
    .unwrap();
    assert!(matches!(plan.path.moves[0].motion, Motion::Arc { .. }));
    assert!((plan.path.moves[0].feed_mm_min.unwrap() - 0.61 * 1200.0).abs() < 1.0, "{:?}", plan.path.moves[0]);
}

#[test]
fn surface_finishing_refuses_constant_force_and_a_wrong_number_of_normals() {
    let p = xz_arc_polyline(5.0, true);
    let mut s = cutting_point_spec();
    s.rule.strategy = FeedStrategy::ConstantForce;
    s.rule.force_model = Some(seed_001_ten_mm());
    assert!(optimize_surface_finishing(&p, &surface_spec(ContactNormal::Down), &s, &NoProgress).is_err());
    let wrong = ContactNormal::PerMove(vec![[0.0, 0.0, -1.0]]);
    let err = optimize_surface_finishing(&p, &surface_spec(wrong), &cutting_point_spec(), &NoProgress).unwrap_err();
    assert!(err.to_string().contains("contact_normals"), "{err}");
}
