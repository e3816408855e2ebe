use super::*;
use crate::core::geometry::{Loop, Pocket};
use crate::core::process::CavityLayer;
use crate::core::progress::NoProgress;
use crate::core::tool::ToolType;

/// A round cavity whose wall slopes at 45° from r 30 at z −5 to r 15 at z −20, given as a
/// CAM system slices it: a first layer of r 30 down to −5 and three of 5 mm, each the
/// section at its bottom (r 25, 20, 15).
fn cone() -> Cavity {
    let layer = |r: f64, top: f64, bottom: f64| CavityLayer {
        pocket: Pocket::new(Loop::circle(0.0, 0.0, r), Vec::new()).unwrap(),
        z_top_mm: top,
        z_bottom_mm: bottom,
    };
    Cavity {
        layers: vec![
            layer(30.0, 0.0, -5.0),
            layer(25.0, -5.0, -10.0),
            layer(20.0, -10.0, -15.0),
            layer(15.0, -15.0, -20.0),
        ],
    }
}

/// The cone's surface over radius `rho`: the wall of the first layer, the 45° slope, the floor.
fn cone_height(rho: f64) -> f64 {
    if rho >= 30.0 {
        0.0
    } else if rho <= 15.0 {
        -20.0
    } else {
        rho - 35.0
    }
}

/// The distance from `(rho, z)` to the cone's meridian (wall, slope, floor), mm.
fn distance_to_cone(rho: f64, z: f64) -> f64 {
    let meridian = [(30.0, 0.0), (30.0, -5.0), (15.0, -20.0), (0.0, -20.0)];
    meridian
        .windows(2)
        .map(|w| {
            let ((a0, a1), (b0, b1)) = (w[0], w[1]);
            let (d0, d1): (f64, f64) = (b0 - a0, b1 - a1);
            let t = (((rho - a0) * d0 + (z - a1) * d1) / (d0 * d0 + d1 * d1)).clamp(0.0, 1.0);
            (rho - a0 - t * d0).hypot(z - a1 - t * d1)
        })
        .fold(f64::INFINITY, f64::min)
}

/// How far a ring may come into the allowance: the rings are interpolated linearly between
/// the cells' centres, mm.
const STAIR_RESOLUTION_MM: f64 = 0.05;

fn r5_ball() -> EndMill {
    EndMill { tool_type: ToolType::Ball, diameter_mm: 10.0, flutes: 2, corner_radius_mm: 5.0 }
}

fn spec(tool: EndMill, allowance_mm: f64) -> StairSpec {
    StairSpec {
        tool,
        conditions: CuttingConditions { spindle_rpm: 10000.0, fz_mm: 0.3, rd_mm: 4.0, ad_mm: 0.6 },
        allowance_mm,
        safe_z_mm: 5.0,
        tool_number: 2,
    }
}

#[test]
fn the_surface_between_the_sections_of_a_sloped_wall_is_the_slope() {
    let s = Surface::of(&cone(), 0.25, 6.0);
    let mut worst: f64 = 0.0;
    for c in 0..s.grid.cells() {
        let (x, y) = s.centre(c);
        let rho = x.hypot(y);
        // Cells a cell from a section's edge take it on the one side or the other.
        if [15.0, 20.0, 25.0, 30.0].iter().any(|e| (rho - e).abs() < 0.4) {
            continue;
        }
        worst = worst.max((s.height_mm[c] - cone_height(rho)).abs());
    }
    assert!(worst < 0.3, "the interpolated surface is {worst} mm off the cone");
    // The roughing left each ring at its layer's bottom: a step of 5 mm at the next
    // section's edge, none at its own.
    let at = |x: f64| s.cell_at(x, 0.1).unwrap();
    assert!((s.roughed_mm[at(27.5)] + 5.0).abs() < 1e-9);
    assert!((s.stair_mm(at(25.2)) - 4.8).abs() < 0.3, "{}", s.stair_mm(at(25.2)));
    assert!(s.stair_mm(at(29.8)) < 0.4, "{}", s.stair_mm(at(29.8)));
    assert!(s.stair_mm(at(10.0)) < 1e-9, "the floor has no step");
}

#[test]
fn a_ball_over_a_flat_floor_stands_on_it_and_keeps_the_allowance() {
    let s = Surface::of(&cone(), 0.25, 6.0);
    let tip = tip::tip_heights_mm(&s, &Profile::of(&r5_ball()), 0.3);
    let c = s.cell_at(0.1, 0.1).unwrap();
    assert!((tip[c] - (-20.0 + 0.3)).abs() < 1e-9, "{}", tip[c]);
    // Over the 45° slope the ball's centre stays R + allowance off it.
    let c = s.cell_at(22.0, 0.1).unwrap();
    let (x, _) = s.centre(c);
    let d = distance_to_cone(x, tip[c] + 5.0);
    assert!((d - 5.3).abs() < 0.2, "{d}");
}

#[test]
fn a_ball_takes_the_steps_of_a_sloped_wall_in_thin_levels_without_touching_the_surface() {
    let sp = spec(r5_ball(), 0.3);
    let path = plan_stairs(&cone(), &sp, &NoProgress).unwrap().expect("the cone has steps");
    // Levels from the first step's top (−5) down to the slope's foot with the allowance
    // (−19.7), at most Ad 0.6 apart.
    let first = path.levels.first().unwrap().z_mm;
    let last = path.levels.last().unwrap().z_mm;
    assert!(first < -5.0 && first > -5.6 - 1e-9, "{first}");
    assert!((last + 19.7).abs() < 0.35, "{last}");
    assert!(path.levels.windows(2).all(|w| w[0].z_mm - w[1].z_mm <= 0.6 + 1e-9));
    // The steps' volume: three rings of a 5 × 5 triangle's section around the axis, the
    // material between the slope and the bottom of the layer over it (b − ρ high between
    // the sections of radius a and b): Σ ∫ 2πρ (b − ρ) dρ, within 2 %.
    let exact: f64 = [(25.0, 30.0), (20.0, 25.0), (15.0, 20.0)]
        .iter()
        .map(|&(a, b): &(f64, f64)| {
            let f = |r: f64| 2.0 * std::f64::consts::PI * (b * r * r / 2.0 - r.powi(3) / 3.0);
            f(b) - f(a)
        })
        .sum();
    assert!((path.step_volume_mm3 / exact - 1.0).abs() < 0.02, "{} against {exact}", path.step_volume_mm3);
    // No point of any move brings the ball nearer the surface than the allowance, less
    // the height field's resolution.
    let cell = path.cell_mm;
    let mut nearest = f64::INFINITY;
    for m in &path.toolpath.moves {
        for t in [0.0, 0.25, 0.5, 0.75, 1.0] {
            let (x, y, z) = (
                m.start.x + (m.end.x - m.start.x) * t,
                m.start.y + (m.end.y - m.start.y) * t,
                m.start.z + (m.end.z - m.start.z) * t,
            );
            let d = distance_to_cone(x.hypot(y), z + 5.0);
            nearest = nearest.min(d);
            assert!(
                d >= 5.0 + 0.3 - STAIR_RESOLUTION_MM,
                "line {}: the ball's centre {d} mm from the surface; {m:?} at ({x}, {y}, {z}) rho {}",
                m.line,
                x.hypot(y)
            );
        }
    }
    println!("the ball's centre comes {nearest} mm near the surface, cell {cell}");
    // The program calls its tool and labels every level.
    let events = &path.toolpath.events;
    assert!(matches!(events[0].kind, EventKind::ToolChange { tool: 2 }));
    let sections =
        events.iter().filter(|e| matches!(e.kind, EventKind::Section(s) if s.step == Step::StairStepRoughing));
    assert_eq!(sections.count(), path.levels.len());
    assert!(path.toolpath.moves.iter().all(|m| m.tool == Some(2) && m.spindle_rpm == Some(10000.0)));
}

#[test]
fn a_cavity_of_one_contour_leaves_no_steps() {
    let pocket = Pocket::new(Loop::circle(0.0, 0.0, 30.0), Vec::new()).unwrap();
    let cavity = Cavity {
        layers: vec![
            CavityLayer { pocket: pocket.clone(), z_top_mm: 0.0, z_bottom_mm: -10.0 },
            CavityLayer { pocket, z_top_mm: -10.0, z_bottom_mm: -20.0 },
        ],
    };
    assert!(plan_stairs(&cavity, &spec(r5_ball(), 0.0), &NoProgress).unwrap().is_none());
}

#[test]
fn a_negative_allowance_is_refused_by_name() {
    let e = plan_stairs(&cone(), &spec(r5_ball(), -0.1), &NoProgress).unwrap_err();
    assert!(e.to_string().contains("allowance_mm"), "{e}");
}

#[test]
fn rings_closer_than_the_surfaces_cell_and_levels_beyond_the_guard_are_refused_by_name() {
    let mut close = spec(r5_ball(), 0.0);
    close.conditions.rd_mm = 0.05;
    let e = plan_stairs(&cone(), &close, &NoProgress).unwrap_err();
    assert!(e.to_string().contains("stair_step.radial_depth_mm"), "{e}");
    let mut thin = spec(r5_ball(), 0.0);
    thin.conditions.ad_mm = 0.001;
    let e = plan_stairs(&cone(), &thin, &NoProgress).unwrap_err();
    assert!(e.to_string().contains("stair_step.axial_depth_mm"), "{e}");
}
