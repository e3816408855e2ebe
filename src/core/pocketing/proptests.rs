//! Properties of contour-parallel paths on random star-shaped pockets with arcs and islands:
//! the path is continuous, stays `r + allowance` from every wall (corner loops included), and
//! only a tool that fits nowhere is refused.

use super::test_support::*;
use super::*;
use crate::core::geometry::{Loop, Vertex};
use proptest::prelude::*;
use std::f64::consts::TAU;

/// Random cases per property (each builds a path and samples it every 0.02 mm).
const CASES: u32 = 40;

/// A path point may come this much closer to the wall than `r + allowance` (mm): the
/// position precision of the offsets (`cavalier_contours`' default `pos_equal_eps`). Near
/// a wall arc of a bulge of 1e-5 (a radius of hundreds of metres) an offset came 1.07e-6
/// mm too close (the case saved in `proptest-regressions`). The plans' own gouge check
/// allows 1e-3 mm, and programs are written to 1e-3 mm by default.
const GOUGE_TOL_MM: f64 = 1e-5;

/// A star-shaped loop about the origin: vertices at evenly spaced angles, radii and bulges
/// as given (counter-clockwise).
fn star(radii: &[f64], bulges: &[f64]) -> Loop {
    let n = radii.len();
    Loop::new(
        (0..n)
            .map(|k| {
                let a = TAU * k as f64 / n as f64;
                Vertex::new(radii[k] * a.cos(), radii[k] * a.sin(), bulges[k])
            })
            .collect(),
    )
}

/// A square island of half-side `half_mm` about `(cx, cy)` turned by `angle_rad`.
fn square_island(cx: f64, cy: f64, half_mm: f64, angle_rad: f64) -> Loop {
    let corners = (0..4).map(|k| {
        let a = angle_rad + TAU * (k as f64 + 0.5) / 4.0;
        let d = half_mm * std::f64::consts::SQRT_2;
        Vertex::new(cx + d * a.cos(), cy + d * a.sin(), 0.0)
    });
    Loop::new(corners.collect())
}

/// No island, a round one or a square one, as `kind` says.
fn island(kind: u8, size_mm: f64, angle_rad: f64) -> Vec<Loop> {
    match kind {
        0 => vec![],
        1 => vec![Loop::circle(size_mm, 0.0, size_mm)],
        _ => vec![square_island(0.0, 0.0, size_mm, angle_rad)],
    }
}

/// Builds the path of the star pocket (`radii`, `bulges`) with `islands` as `s` says and
/// checks it: continuous, `r + allowance` from every wall, or a clear refusal.
fn check_random_pocket(
    radii: &[f64],
    bulges: &[f64],
    islands: Vec<Loop>,
    s: &PocketingSpec,
) -> Result<(), TestCaseError> {
    let outer = star(radii, &bulges[..radii.len()]);
    let Ok(p) = Pocket::new(outer, islands) else {
        // A random bulge made the loop cross itself: not a pocket.
        return Ok(());
    };
    let (r_mm, allowance_mm) = (s.tool_radius_mm, s.allowance_mm);
    match contour_parallel(&p, s) {
        Ok(out) => {
            assert_continuous(&out.toolpath);
            let margin = min_wall_distance_mm(&p, &out.toolpath) - (r_mm + allowance_mm);
            prop_assert!(margin >= -GOUGE_TOL_MM, "margin {}", margin);
            prop_assert!(out.loops >= out.regions && out.entries.len() >= out.regions);
            prop_assert!(s.corner_loops || out.corner_loops == 0);
        }
        Err(CoreError::Unsolvable { field, reason }) => {
            prop_assert_eq!(field, "tool_radius_mm");
            prop_assert!(reason.contains("does not fit in the pocket"), "{}", reason);
        }
        Err(other) => prop_assert!(false, "{other:?}"),
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(CASES))]

    #[test]
    fn random_pockets_give_continuous_paths_that_never_gouge_or_a_clear_refusal(
        radii in proptest::collection::vec(15.0..45.0f64, 5..12),
        bulges in proptest::collection::vec(-0.3..0.3f64, 12),
        island_kind in 0..3u8,
        island_size in 2.0..6.0f64,
        island_angle in 0.0..TAU,
        r_mm in 1.0..8.0f64,
        rd_fraction in 0.2..1.0f64,
        allowance_mm in 0.0..1.0f64,
        climb in any::<bool>(),
    ) {
        let s = PocketingSpec { allowance_mm, climb, ..spec(r_mm, rd_fraction * r_mm) };
        check_random_pocket(&radii, &bulges, island(island_kind, island_size, island_angle), &s)?;
    }

    /// Mostly straight sides (two bulges in three zero), so that the rings have sharp
    /// corners of every angle: the corner loops stay inside the region the tool may reach.
    #[test]
    fn corner_loops_keep_random_paths_continuous_and_clear_of_every_wall(
        radii in proptest::collection::vec(15.0..45.0f64, 4..10),
        bulges in proptest::collection::vec(prop_oneof![Just(0.0), Just(0.0), -0.3..0.3f64], 12),
        islands in (0..3u8, 2.0..6.0f64, 0.0..TAU).prop_map(|(kind, size, angle)| island(kind, size, angle)),
        s in (1.0..8.0f64, 0.2..1.0f64, 0.0..1.0f64, any::<bool>()).prop_map(|(r_mm, rd_fraction, allowance_mm, climb)| {
            PocketingSpec { allowance_mm, climb, corner_loops: true, ..spec(r_mm, rd_fraction * r_mm) }
        }),
    ) {
        check_random_pocket(&radii, &bulges, islands, &s)?;
    }
}
