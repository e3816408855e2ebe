//! The analytic cases of MODEL.md §2 that the simulation must reproduce within 0.5°.

use super::*;
use crate::core::engagement::{
    concave_engagement_angle_rad, convex_engagement_angle_rad, straight_engagement_angle_rad,
};
use crate::core::progress::NoProgress;
use crate::core::tool::ToolType;
use crate::core::toolpath::{Move, Plane, Units, P3};

const R: f64 = 5.0;
const TOLERANCE_DEG: f64 = 0.5;

fn tool() -> EndMill {
    EndMill { tool_type: ToolType::Square, diameter_mm: 2.0 * R, flutes: 6, corner_radius_mm: 0.0 }
}

fn spec(stock: Vec<StockRegion>, open: Vec<StockRegion>) -> AnalysisSpec {
    AnalysisSpec {
        tool: tool(),
        stock,
        open,
        z_top: 0.0,
        z_bottom: -10.0,
        force_model: None,
        default_spindle_rpm: Some(9600.0),
        rapid_mm_min: 20000.0,
        sample_spacing_mm: None,
        cell_mm: None,
        alpha_limit_deg: DEFAULT_ALPHA_LIMIT_DEG,
        series_points: 2000,
        stock_memory_bytes: crate::core::analysis::DEFAULT_STOCK_MEMORY_BYTES,
    }
}

fn feed(motion: Motion, start: P3, end: P3) -> Move {
    Move { motion, start, end, feed_mm_min: Some(5760.0), spindle_rpm: Some(9600.0), tool: None, line: 1 }
}

fn path(moves: Vec<Move>) -> Toolpath {
    Toolpath { moves, events: vec![], source_units: Units::Mm, warnings: vec![] }
}

/// α (deg) of the series point nearest path distance `s`.
fn alpha_at(a: &Analysis, s: f64) -> f64 {
    let series = a.series.as_ref().unwrap();
    let i = series.s_mm.iter().enumerate().min_by(|x, y| (x.1 - s).abs().total_cmp(&(y.1 - s).abs())).unwrap().0;
    series.alpha_deg[i]
}

fn big_block() -> StockRegion {
    StockRegion::Rect(Rect { x_min: -60.0, y_min: -60.0, x_max: 60.0, y_max: 60.0 })
}

#[test]
fn straight_side_cuts_engage_acos_1_minus_rd_over_r() {
    for rd in [0.25, 0.5, 1.0, 2.5, 5.0, 7.5] {
        // Material below y = 0; the tool's flank reaches rd into it.
        let stock = StockRegion::Rect(Rect { x_min: 0.0, y_min: -40.0, x_max: 100.0, y_max: 0.0 });
        let y = R - rd;
        let p = path(vec![feed(Motion::Linear, P3::new(-10.0, y, -5.0), P3::new(110.0, y, -5.0))]);
        let a = analyze(&p, &spec(vec![stock], vec![]), &NoProgress).unwrap();
        let expected = straight_engagement_angle_rad(rd, R).to_degrees();
        let got = alpha_at(&a, 60.0);
        assert!((got - expected).abs() < TOLERANCE_DEG, "Rd {rd}: {got} vs {expected}");
    }
}

#[test]
fn a_full_slot_engages_180_degrees() {
    let p = path(vec![feed(Motion::Linear, P3::new(-70.0, 0.0, -5.0), P3::new(50.0, 0.0, -5.0))]);
    let a = analyze(&p, &spec(vec![big_block()], vec![]), &NoProgress).unwrap();
    let got = alpha_at(&a, 80.0);
    assert!((got - 180.0).abs() < TOLERANCE_DEG, "{got}");
    assert_eq!(a.critical_regions.len(), 1);
    assert_eq!(a.critical_regions[0].kind, report::RegionKind::FullSlotting);
}

/// A full circle of the tool centre about the origin, radius `rc`, counter-clockwise,
/// starting on the +x axis.
fn circle_path(rc: f64) -> Toolpath {
    let s = P3::new(rc, 0.0, -5.0);
    path(vec![feed(
        Motion::Arc { center: P3::new(0.0, 0.0, -5.0), clockwise: false, plane: Plane::Xy, turns: 0 },
        s,
        s,
    )])
}

#[test]
fn concave_arcs_engage_as_model_section_2_says() {
    let rd = 0.5;
    for ratio in [1.2, 1.6, 2.0, 3.0] {
        let big_r = ratio * R;
        let open = StockRegion::Circle { cx: 0.0, cy: 0.0, r: big_r - rd };
        let p = circle_path(big_r - R);
        let a = analyze(&p, &spec(vec![big_block()], vec![open]), &NoProgress).unwrap();
        let expected = concave_engagement_angle_rad(big_r, rd, R).to_degrees();
        let half = std::f64::consts::PI * (big_r - R);
        let got = alpha_at(&a, half);
        assert!((got - expected).abs() < TOLERANCE_DEG, "R/r {ratio}: {got} vs {expected}");
    }
}

#[test]
fn convex_arcs_engage_as_model_section_2_says() {
    let rd = 0.5;
    for ratio in [1.2, 1.6, 2.0, 3.0] {
        let big_r = ratio * R;
        let island = StockRegion::Circle { cx: 0.0, cy: 0.0, r: big_r + rd };
        let p = circle_path(big_r + R);
        let a = analyze(&p, &spec(vec![island], vec![]), &NoProgress).unwrap();
        let expected = convex_engagement_angle_rad(big_r, rd, R).to_degrees();
        let half = std::f64::consts::PI * (big_r + R);
        let got = alpha_at(&a, half);
        assert!((got - expected).abs() < TOLERANCE_DEG, "R/r {ratio}: {got} vs {expected}");
    }
}

#[test]
fn a_second_pass_over_cut_ground_engages_nothing_and_counts_as_air() {
    let line = |x0: f64, x1: f64| feed(Motion::Linear, P3::new(x0, 0.0, -5.0), P3::new(x1, 0.0, -5.0));
    let p = path(vec![line(-70.0, 50.0), line(50.0, -50.0)]);
    let a = analyze(&p, &spec(vec![big_block()], vec![]), &NoProgress).unwrap();
    assert!(alpha_at(&a, 170.0) < TOLERANCE_DEG);
    assert!(a.summary.air_cut_length_mm > 99.0);
    // The tool tip is at z = −5 in a layer from 0 to −10: it cuts 5 mm deep.
    let expected_volume = (110.0 * 2.0 * R + std::f64::consts::PI * R * R / 2.0) * 5.0;
    assert!(
        (a.summary.removed_volume_mm3 - expected_volume).abs() / expected_volume < 0.01,
        "{} vs {expected_volume}",
        a.summary.removed_volume_mm3
    );
}

#[test]
fn a_pass_below_a_roughed_layer_cuts_the_material_the_roughing_left() {
    // A ramp ends 0.02 mm above the roughing layer at −10, outside the stock; zig-zag
    // passes 4 mm apart then clear the block down to −10, and a last pass at −10.5 slots
    // through the 0.5 mm the roughing left.
    let block = Rect { x_min: 0.0, y_min: 0.0, x_max: 40.0, y_max: 40.0 };
    let mut at = P3::new(-10.0, -10.0, 0.0);
    let mut moves = Vec::new();
    let mut to = |end: P3, moves: &mut Vec<Move>| {
        moves.push(feed(Motion::Linear, at, end));
        at = end;
    };
    to(P3::new(-10.0, -5.0, -9.98), &mut moves);
    to(P3::new(-10.0, -5.0, -10.0), &mut moves);
    for pass in 0..13 {
        let y = -5.0 + 4.0 * f64::from(pass);
        let (x_start, x_end) = if pass % 2 == 0 { (-10.0, 50.0) } else { (50.0, -10.0) };
        to(P3::new(x_start, y, -10.0), &mut moves);
        to(P3::new(x_end, y, -10.0), &mut moves);
    }
    to(P3::new(-10.0, 20.0, -10.0), &mut moves);
    to(P3::new(-10.0, 20.0, -10.5), &mut moves);
    let before_last: f64 = moves.iter().map(crate::core::toolpath::move_length).sum();
    to(P3::new(50.0, 20.0, -10.5), &mut moves);
    let mut s = spec(vec![StockRegion::Rect(block)], vec![]);
    s.z_bottom = -12.0;
    let a = analyze(&path(moves), &s, &NoProgress).unwrap();
    let middle = before_last + 30.0;
    let got = alpha_at(&a, middle);
    assert!((got - 180.0).abs() < TOLERANCE_DEG, "α {got}° below the roughed layer");
    let series = a.series.as_ref().unwrap();
    let i = series.s_mm.iter().position(|&v| v >= middle).unwrap();
    assert!((series.ad_mm[i] - 0.5).abs() < 1e-9, "Ad {} mm", series.ad_mm[i]);
}

#[test]
fn loops_written_as_arcs_engage_as_the_same_loops_written_as_fine_chords() {
    // Loops tighter than the tool (a trochoid's) and wider.
    for rho in [3.0, 8.0] {
        loops_of_radius_engage_alike_as_arcs_and_as_chords(rho);
    }
}

fn loops_of_radius_engage_alike_as_arcs_and_as_chords(rho: f64) {
    // Loops through the block: full circles of `rho` about centres 1 mm apart, once as G3
    // circles (applied along the arc) and once as chords ending at the very samples of the
    // arcs (applied as capsules): one sample per chord, at its end.
    let chords_per_loop = (std::f64::consts::TAU * rho / 0.05).ceil() as usize;
    let z = -5.0;
    let (mut arcs, mut chords) = (Vec::new(), Vec::new());
    for k in 0..6 {
        let c = P3::new(f64::from(k), 0.0, z);
        let start = P3::new(c.x, -rho, z);
        if k > 0 {
            let link = feed(Motion::Linear, P3::new(c.x - 1.0, -rho, z), start);
            arcs.push(link);
            chords.push(link);
        }
        arcs.push(feed(Motion::Arc { center: c, clockwise: false, plane: Plane::Xy, turns: 0 }, start, start));
        let at = |n: usize| {
            let t = -std::f64::consts::FRAC_PI_2 + std::f64::consts::TAU * n as f64 / chords_per_loop as f64;
            P3::new(c.x + rho * t.cos(), c.y + rho * t.sin(), z)
        };
        chords.extend((0..chords_per_loop).map(|n| feed(Motion::Linear, at(n), at(n + 1))));
    }
    let alphas = |p: &Toolpath| {
        let mut out = Vec::new();
        analyze_with(p, &spec(vec![big_block()], vec![]), &NoProgress, |s| out.push(s.contact.alpha_rad.to_degrees()))
            .expect("analyses");
        out
    };
    let (along_arcs, along_chords) = (alphas(&path(arcs)), alphas(&path(chords)));
    assert_eq!(along_arcs.len(), along_chords.len());
    // The chords' headings turn from the arc's tangent by half a chord's angle (≤ 0.48°),
    // and the chunks of chords sag from the arc by up to 0.05 cells. Where the tool grazes
    // an earlier cut (a loop closing on its start, a link leaving a circle) α hangs on
    // slivers of a few micrometres that this moves: those few samples are left out.
    let close = along_arcs.iter().zip(&along_chords).filter(|(a, b)| (*a - *b).abs() < 2.0 * TOLERANCE_DEG).count();
    assert!(close as f64 > 0.99 * along_arcs.len() as f64, "{close} of {} samples agree", along_arcs.len());
    // The steady loops, after the first (which starts buried in the block).
    let largest = |v: &[f64]| v[chords_per_loop + 1..].iter().copied().fold(0.0, f64::max);
    let (a, b) = (largest(&along_arcs), largest(&along_chords));
    assert!((a - b).abs() < TOLERANCE_DEG, "largest α {a:.2}° along arcs, {b:.2}° along chords");
    assert!(a > 30.0 && a < 170.0, "the loops cut, up to {a:.1}°");
}
