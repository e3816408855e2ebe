//! What the pocketing path removes, checked with the path analysis (MODEL.md §6) and by
//! geometry: the whole reachable area, no ridge between loops, and the engagement along it.

use super::test_support::*;
use super::*;
use crate::core::analysis::{analyze, Analysis, AnalysisSpec, StockRegion, DEFAULT_ALPHA_LIMIT_DEG};
use crate::core::engagement::straight_engagement_angle_rad;
use crate::core::geometry::Loop;
use crate::core::progress::NoProgress;
use crate::core::tool::{EndMill, ToolType};
use crate::core::toolpath::Motion;
use std::f64::consts::PI;

const R_MM: f64 = 5.0;

/// The analysis of `path` cutting the layer `z_mm`…0 of `pocket` with a 10 mm end mill.
fn analysis(pocket: &Pocket, path: &Toolpath, series_points: usize) -> Analysis {
    let spec = AnalysisSpec {
        tool: EndMill { tool_type: ToolType::Square, diameter_mm: 2.0 * R_MM, flutes: 6, corner_radius_mm: 0.0 },
        stock: vec![StockRegion::Pocket(pocket.clone())],
        open: vec![],
        z_top: 0.0,
        z_bottom: Z_MM,
        force_model: None,
        default_spindle_rpm: None,
        rapid_mm_min: 20000.0,
        sample_spacing_mm: None,
        cell_mm: None,
        alpha_limit_deg: DEFAULT_ALPHA_LIMIT_DEG,
        series_points,
        stock_memory_bytes: crate::core::analysis::DEFAULT_STOCK_MEMORY_BYTES,
    };
    analyze(path, &spec, &NoProgress).unwrap()
}

/// Area removed over all slices, each weighted by its share of the layer (mm²).
fn removed_area_mm2(a: &Analysis) -> f64 {
    a.summary.removed_volume_mm3 / -Z_MM
}

/// What a tool of radius `r` cannot reach in the four right-angle corners of a rectangle:
/// each corner keeps a square r × r less a quarter disc.
fn corner_residue_mm2(r_mm: f64) -> f64 {
    (4.0 - PI) * r_mm * r_mm
}

/// The raster of the analysis places each boundary to a fraction of its cell (0.1 mm for a
/// 10 mm tool); over a pocket a few hundred mm around that is well under 0.2 % of its area.
const AREA_REL_TOL: f64 = 0.002;

#[test]
fn the_path_removes_the_whole_rectangle_but_its_four_corner_cusps() {
    let p = pocket(Loop::rectangle(0.0, 0.0, 60.0, 40.0), vec![]);
    let out = contour_parallel(&p, &spec(R_MM, 2.0)).unwrap();
    let a = analysis(&p, &out.toolpath, 0);
    let expected = p.area() - corner_residue_mm2(R_MM);
    let removed = removed_area_mm2(&a);
    let slice = a.summary.slices[0].removed_area_mm2;
    println!("rectangle: removed {removed:.2} mm² (slice 0: {slice:.2}), expected {expected:.2} mm²");
    assert!((removed - expected).abs() / expected < AREA_REL_TOL, "{removed} vs {expected}");
    assert!(a.summary.warnings.iter().all(|w| !w.contains("rapid")), "{:?}", a.summary.warnings);
}

#[test]
fn the_path_removes_the_pocket_around_a_round_island_but_the_corner_cusps() {
    let p = pocket(Loop::rectangle(0.0, 0.0, 80.0, 60.0), vec![Loop::circle(40.0, 30.0, 8.0)]);
    let out = contour_parallel(&p, &spec(R_MM, 2.0)).unwrap();
    let a = analysis(&p, &out.toolpath, 0);
    // A convex island is reached all round: only the outer corners keep material.
    let expected = p.area() - corner_residue_mm2(R_MM);
    let removed = removed_area_mm2(&a);
    println!("island: removed {removed:.2} mm², expected {expected:.2} mm²");
    assert!((removed - expected).abs() / expected < AREA_REL_TOL, "{removed} vs {expected}");
}

/// Every point of the rectangle the tool can reach (within r of the region 5 mm inside the
/// walls) lies within r of a cutting move: no ridge between loops and no core. With `Rd ≤ r`
/// this holds by construction (module documentation); `Rd < 2r` would suffice only between
/// straight parallel loops.
#[test]
fn no_step_over_leaves_a_ridge_between_loops() {
    let (w, h) = (60.0, 40.0);
    let p = pocket(Loop::rectangle(0.0, 0.0, w, h), vec![]);
    for rd in [1.0, 2.0, 3.5, R_MM] {
        let out = contour_parallel(&p, &spec(R_MM, rd)).unwrap();
        let segments: Vec<_> = cutting_moves(&out.toolpath).into_iter().map(|(_, s)| s).collect();
        let step_mm = 0.25;
        let mut worst: f64 = 0.0;
        for i in 0..=(w / step_mm) as usize {
            for j in 0..=(h / step_mm) as usize {
                let q = crate::core::geometry::Point::new(i as f64 * step_mm, j as f64 * step_mm);
                let dx = (R_MM - q.x).max(q.x - (w - R_MM)).max(0.0);
                let dy = (R_MM - q.y).max(q.y - (h - R_MM)).max(0.0);
                if dx.hypot(dy) > R_MM - 1e-6 {
                    continue; // in a corner cusp: out of reach
                }
                let d = segments.iter().map(|s| s.distance_mm(q)).fold(f64::INFINITY, f64::min);
                worst = worst.max(d - R_MM);
            }
        }
        println!("Rd {rd}: farthest reachable point {worst:e} mm beyond the tool");
        assert!(worst <= 1e-9, "Rd {rd}: a point {worst} mm beyond the tool's reach");
    }
}

/// The engagement along the path (MODEL.md §2). Measured on border.dxf with r = 5, Rd = 3
/// (10 mm tool): the innermost loop is a slot from its entry (α = 180°: the helical boring
/// and trochoids of MODEL.md §7–8 are for that). After it, α sits at the straight-cut value
/// acos(1 − Rd/r) = 66.4° along the straight parts (median 66.5°) and rises to 156.5° at the
/// sharp corners of the inner loops; each straight link runs head-on into the next band,
/// 2·acos(1 − Rd/r) = 132.8° (168° for the first one, out of the slot's end). The finishing
/// pass peaks at 91° in the corner arcs. These are what the trochoid planner is to fix.
#[test]
fn the_engagement_is_the_straight_cut_value_on_straight_parts_and_higher_in_corners() {
    let p = border_dxf();
    let rd = 3.0;
    let out = contour_parallel(&p, &spec(R_MM, rd)).unwrap();
    let a = analysis(&p, &out.toolpath, 20_000);
    let series = a.series.as_ref().unwrap();
    let straight = straight_engagement_angle_rad(rd, R_MM).to_degrees();
    // The first loop closes at the first move that ends where the plunge ended.
    let (ex, ey) = out.entries[0];
    let first_loop_end = out
        .toolpath
        .moves
        .iter()
        .skip(2)
        .find(|m| (m.end.x - ex).hypot(m.end.y - ey) < SAME_MM)
        .map(|m| m.line)
        .unwrap();
    let mut after: Vec<f64> =
        series.line.iter().zip(&series.alpha_deg).filter(|(&l, _)| l > first_loop_end).map(|(_, &a)| a).collect();
    after.sort_by(f64::total_cmp);
    let median = after[after.len() / 2];
    let max_after = *after.last().unwrap();
    println!(
        "border.dxf: max α {:.1}° (innermost loop: slotting), after it: median {median:.1}°, max {max_after:.1}°, straight {straight:.1}°, critical {:.0} mm",
        a.summary.alpha_deg.max, a.summary.critical_length_mm
    );
    assert!((median - straight).abs() < 2.0, "{median} vs {straight}");
    assert!(max_after > straight + 5.0);
    assert!(a.summary.alpha_deg.max <= 180.0 + 1e-6);
}

/// Corner loops (seed 004 §3.3) on a 80 × 60 rectangle at the baseline's step-over (r = 5,
/// Rd = 3.5): the engagement where the rings turn their sharp corners, with and without them.
#[test]
fn corner_loops_lower_the_engagement_at_the_sharp_corners_of_the_rings() {
    let p = pocket(Loop::rectangle(0.0, 0.0, 80.0, 60.0), vec![]);
    let rd = 3.5;
    let peak_near_corners = |corner_loops: bool| {
        let out = contour_parallel(&p, &PocketingSpec { corner_loops, ..spec(R_MM, rd) }).unwrap();
        let a = analysis(&p, &out.toolpath, 100_000);
        let s = a.series.as_ref().unwrap();
        // The corners of rings 0 to 5 (offsets 5 … 22.5 mm), which all get a loop (the next
        // ring, 8 mm high, is narrower than the circle's 2ρ = 11.95 mm).
        let corners: Vec<(f64, f64)> = (0..=5)
            .flat_map(|k| {
                let d = R_MM + rd * k as f64;
                [(d, d), (80.0 - d, d), (80.0 - d, 60.0 - d), (d, 60.0 - d)]
            })
            .collect();
        let near = |x: f64, y: f64| corners.iter().any(|&(cx, cy)| (x - cx).hypot(y - cy) < 0.5);
        let peak_where = |keep: &dyn Fn(usize) -> bool| {
            (0..s.alpha_deg.len()).filter(|&i| keep(i)).map(|i| s.alpha_deg[i]).fold(0.0, f64::max)
        };
        // The rectangle's rings have no arcs: the arcs are the corner loops.
        let circle_lines: Vec<u32> =
            out.toolpath.moves.iter().filter(|m| matches!(m.motion, Motion::Arc { .. })).map(|m| m.line).collect();
        let at_corners = peak_where(&|i| near(s.x[i], s.y[i]));
        let on_loops = peak_where(&|i| circle_lines.contains(&s.line[i]));
        (at_corners, on_loops, out.corner_loops)
    };
    let (without, _, _) = peak_near_corners(false);
    let (with, on_loops, loops) = peak_near_corners(true);
    println!("corners: α {without:.1}° without loops; with {loops} loops {with:.1}° at the corners, {on_loops:.1}° on the loops");
    // Measured: 162.6° without loops (α + 90° at a right angle, α = acos(1 − Rd/r) = 72.5°);
    // with them 118.5° at the corners and 94.7° on the loops.
    assert_eq!(loops, 24);
    assert!(with < without - 30.0 && on_loops < without - 30.0, "{with}, {on_loops} against {without}");
}
