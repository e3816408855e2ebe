//! The probe's shortcuts (certified coarse points, recent centres filtered to those that
//! can reach the leading half, coarse states remembered along a line) give exactly the
//! contact of the plain scan that probes every coarse point and checks every recent
//! centre.

use super::probe::{certified_ahead, AngleTable, Contact, ProbeSite, COARSE_STEP, PROBE_STEPS_PER_TURN};
use super::recent::Corridor;
use super::scan_memory::{Line, ScanMemory};
use crate::core::stock::{Certified, Raster, Rect};
use proptest::prelude::*;
use std::f64::consts::PI;

pub(super) const RADIUS: f64 = 5.0;
pub(super) const CELL: f64 = 0.1;
pub(super) const SIDE: f64 = 60.0;
/// Contacts are whole probe steps (1e-3 rad): anything closer is the same contact.
const SAME_RAD: f64 = 1e-12;
/// Half the length of a rib, mm.
const RIB_HALF_MM: f64 = 8.0;
/// Sample spacing along a line, mm.
const SPACING: f64 = 0.05;

/// `true` when two contacts count the same probe steps.
fn same(got: &Contact, want: &Contact) -> bool {
    // Both count whole probe steps: equal up to rounding of the conversion.
    let close = |a: f64, b: f64| (a - b).abs() < SAME_RAD;
    close(got.alpha_rad, want.alpha_rad) && close(got.entry_rad, want.entry_rad) && close(got.exit_rad, want.exit_rad)
}

/// The scan without shortcuts (the probe as it was before them).
fn plain_contact(raster: &Raster, center: (f64, f64), heading: (f64, f64), recent: &[(f64, f64)]) -> Contact {
    let step = 2.0 * PI / PROBE_STEPS_PER_TURN as f64;
    let g = raster.grid_position(center.0, center.1);
    let material = |k: usize| {
        let a = k as f64 * 2.0 * PI / PROBE_STEPS_PER_TURN as f64;
        let (x, y) = (center.0 + RADIUS * a.cos(), center.1 + RADIUS * a.sin());
        // The probe's position on the grid, computed as the probe does.
        let at = (g.0 + RADIUS * a.cos() / CELL, g.1 + RADIUS * a.sin() / CELL);
        raster.is_material_at(at) && recent.iter().all(|c| (x - c.0).powi(2) + (y - c.1).powi(2) >= RADIUS * RADIUS)
    };
    let h = (heading.1.atan2(heading.0) / step).round() as i64;
    let quarter = (PROBE_STEPS_PER_TURN / 4) as i64;
    let first = (h - quarter).rem_euclid(PROBE_STEPS_PER_TURN as i64) as usize;
    let span = PROBE_STEPS_PER_TURN / 2;
    let (mut engaged, mut entry, mut exit) = (0usize, None::<usize>, 0usize);
    let mut prev = material(first);
    for b in (COARSE_STEP..=span).step_by(COARSE_STEP) {
        let a = b - COARSE_STEP;
        let now = material(first + b);
        if prev == now {
            if now {
                engaged += b - a;
                entry.get_or_insert(a);
                exit = b;
            }
        } else {
            let (mut lo, mut hi) = (first + a, first + b);
            while hi - lo > 1 {
                let mid = (lo + hi) / 2;
                if material(mid) == prev {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            let at = hi - first;
            let tangent_wall = (prev && a == 0) || (now && b == span);
            let run = if prev { (a, at) } else { (at, b) };
            if !tangent_wall {
                engaged += run.1 - run.0;
                entry.get_or_insert(run.0);
                exit = run.1;
            }
        }
        prev = now;
    }
    let to_rad = |k: usize| k as f64 * step - PI / 2.0;
    Contact {
        alpha_rad: engaged as f64 * step,
        entry_rad: entry.map_or(0.0, to_rad),
        exit_rad: if entry.is_some() { to_rad(exit) } else { 0.0 },
    }
}

/// A block with discs, slots and pairs of slots leaving a thin rib between them cleared
/// from it: walls of every direction, narrow features, wide areas of air and material.
pub(super) fn stock(discs: &[(f64, f64, f64)], slots: &[Slot], ribs: &[Rib]) -> Raster {
    let rect = Rect { x_min: 0.0, y_min: 0.0, x_max: SIDE, y_max: SIDE };
    let mut r = Raster::new(rect, CELL);
    r.paint(
        true,
        |y, out| {
            if (0.0..SIDE).contains(&y) {
                out.push((0.0, SIDE))
            }
        },
        |x, y, _| crate::core::stock::rect_signed_distance(&rect, x, y),
    );
    for &(x, y, radius) in discs {
        r.clear_capsule((x, y), (x, y), radius);
    }
    for &(a, b, radius) in slots {
        r.clear_capsule(a, b, radius);
    }
    for &((x, y), angle, width, radius) in ribs {
        let (ux, uy) = (angle.cos(), angle.sin());
        let offset = radius + width / 2.0;
        for side in [-1.0, 1.0] {
            let (ox, oy) = (-uy * offset * side, ux * offset * side);
            let ends = [
                (x + ox - RIB_HALF_MM * ux, y + oy - RIB_HALF_MM * uy),
                (x + ox + RIB_HALF_MM * ux, y + oy + RIB_HALF_MM * uy),
            ];
            r.clear_capsule(ends[0], ends[1], radius);
        }
    }
    r
}

/// Ends and radius, mm.
type Slot = ((f64, f64), (f64, f64), f64);
/// Centre, direction (rad), width and the radius of the slots either side, mm.
type Rib = ((f64, f64), f64, f64, f64);

pub(super) fn point() -> impl Strategy<Value = (f64, f64)> {
    (0.0..SIDE, 0.0..SIDE)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn the_certified_scan_finds_the_contact_of_the_plain_scan(
        discs in prop::collection::vec((0.0..SIDE, 0.0..SIDE, 0.5..12.0f64), 0..6),
        slots in prop::collection::vec((point(), point(), 0.05..6.0f64), 0..4),
        ribs in prop::collection::vec((point(), 0.0..PI, 0.05..0.6f64, 0.5..4.0f64), 0..4),
        sites in prop::collection::vec((point(), 0.0..2.0 * PI, prop::collection::vec((-4.0..4.0f64, -4.0..4.0f64), 0..6)), 24),
    ) {
        let raster = stock(&discs, &slots, &ribs);
        let table = AngleTable::new(RADIUS, CELL);
        let mut site = ProbeSite::default();
        for (center, angle, offsets) in sites {
            let heading = (angle.cos(), angle.sin());
            // Recent centres behind the tool along its heading, or scattered anywhere.
            let mut recent: Vec<(f64, f64)> =
                (1..=16).map(|k| (center.0 - 0.05 * k as f64 * heading.0, center.1 - 0.05 * k as f64 * heading.1)).collect();
            recent.extend(offsets.iter().map(|o| (center.0 + o.0, center.1 + o.1)));
            for recent in [&recent[..16], &recent[..]] {
                site.set(&table, center, raster.grid_position(center.0, center.1), heading, recent, &Corridor::UNKNOWN, None);
                let got = table.contact(&raster, &site, None);
                let want = plain_contact(&raster, center, heading, recent);
                prop_assert!(same(&got, &want), "at {:?} heading {:?}: {:?} vs {:?}", center, heading, got, want);
            }
        }
    }

    #[test]
    fn remembered_states_along_a_line_give_the_contact_of_the_plain_scan(
        discs in prop::collection::vec((0.0..SIDE, 0.0..SIDE, 0.5..12.0f64), 0..6),
        ribs in prop::collection::vec((point(), 0.0..PI, 0.05..0.6f64, 0.5..4.0f64), 0..4),
        walls in prop::collection::vec((0.0..SIDE, any::<bool>(), 0.3..6.0f64), 0..3),
        start in point(),
        angle in prop_oneof![Just(0.0), Just(PI / 2.0), Just(PI), 0.0..2.0 * PI],
        cuts in prop::collection::vec((50usize..400, point(), 0.3..3.0f64), 0..3),
    ) {
        // Slots along the axes across the whole block: walls along the rows and columns,
        // where the bisections of a tool moving along them are settled.
        let slots: Vec<Slot> = walls
            .iter()
            .map(|&(at, along_x, radius)| {
                if along_x { ((-1.0, at), (SIDE + 1.0, at), radius) } else { ((at, -1.0), (at, SIDE + 1.0), radius) }
            })
            .collect();
        let mut raster = stock(&discs, &slots, &ribs);
        let table = AngleTable::new(RADIUS, CELL);
        let mut site = ProbeSite::default();
        let mut memory = ScanMemory::default();
        let heading = (angle.cos(), angle.sin());
        let steps = 400;
        for n in 0..steps {
            // Material removed now and then changes what the memory may rely on.
            for &(at, (x, y), radius) in &cuts {
                if at == n {
                    raster.clear_capsule((x, y), (x, y), radius);
                }
            }
            let d = SPACING * n as f64;
            let center = (start.0 + d * heading.0, start.1 + d * heading.1);
            let line = Line { id: 0, dir: heading, ahead_cells: SPACING * (steps - n) as f64 / CELL };
            site.set(&table, center, raster.grid_position(center.0, center.1), heading, &[], &Corridor::UNKNOWN, Some(line));
            let got = table.contact(&raster, &site, Some(&mut memory));
            let want = plain_contact(&raster, center, heading, &[]);
            prop_assert!(same(&got, &want), "sample {} at {:?}: {:?} vs {:?}", n, center, got, want);
        }
    }
}

#[test]
fn a_certified_state_holds_ahead_up_to_the_boundary_and_no_further() {
    let r = block_of_40_mm();
    let cell = 0.02;
    // Along x from the air 3 mm left of the block's edge at x = −20, and from deep
    // inside it; the state of every position on the stretch is the probe's.
    for (x0, look_ahead) in [(-23.0, 1000.0), (-10.0, 128.0)] {
        let g = r.grid_position(x0, 0.0);
        let (material, level) = r.probe_at(g);
        assert!(level != Certified::No);
        let held = certified_ahead(&r, g, ((1.0, 0.0), 1.0), (material, level), look_ahead);
        let steps = (held * 10.0) as usize;
        assert!((0..=steps).all(|k| r.is_material_at((g.0 + k as f64 * 0.1, g.1)) == material));
        if material {
            assert!(held >= look_ahead, "deep inside, the whole look ahead holds: {held}");
        } else {
            // It stops short of the edge, within the two tiles (16 cells) around it
            // that certify nothing.
            let to_edge = 3.0 / cell;
            assert!(held < to_edge && held > to_edge - 16.0, "{held} cells of {to_edge}");
        }
    }
}

/// A 40 mm square block on cells of 0.02 mm.
pub(super) fn block_of_40_mm() -> Raster {
    let rect = Rect { x_min: -20.0, y_min: -20.0, x_max: 20.0, y_max: 20.0 };
    let mut r = Raster::new(rect, 0.02);
    r.paint(
        true,
        |y, out| {
            if (-20.0..20.0).contains(&y) {
                out.push((-20.0, 20.0))
            }
        },
        |x, y, _| crate::core::stock::rect_signed_distance(&rect, x, y),
    );
    r
}

/// The contact at a few simple positions.
mod simple {
    use super::block_of_40_mm as block;
    use super::*;

    fn site(table: &AngleTable, center: (f64, f64), heading: (f64, f64), recent: &[(f64, f64)]) -> ProbeSite {
        let mut site = ProbeSite::default();
        site.set(table, center, block().grid_position(center.0, center.1), heading, recent, &Corridor::UNKNOWN, None);
        site
    }

    #[test]
    fn a_tool_buried_in_material_engages_its_whole_leading_half() {
        let table = AngleTable::new(5.0, 0.02);
        let c = table.contact(&block(), &site(&table, (0.0, 0.0), (1.0, 0.0), &[]), None);
        assert!((c.alpha_rad - PI).abs() < 1e-9);
        assert!((c.entry_rad + PI / 2.0).abs() < 1e-9 && (c.exit_rad - PI / 2.0).abs() < 1e-9);
    }

    #[test]
    fn the_recent_centres_remove_what_they_swept() {
        let table = AngleTable::new(5.0, 0.02);
        // A disc about (1, 0) covers the circle where cos θ > 0.1: what stays engaged is
        // 2 × (90° − acos 0.1).
        let c = table.contact(&block(), &site(&table, (0.0, 0.0), (1.0, 0.0), &[(1.0, 0.0)]), None);
        let expected = 2.0 * (PI / 2.0 - 0.1f64.acos());
        assert!((c.alpha_rad - expected).abs() < 0.2f64.to_radians(), "{} vs {expected}", c.alpha_rad);
    }

    #[test]
    fn a_tool_in_the_air_engages_nothing() {
        let table = AngleTable::new(5.0, 0.02);
        let c = table.contact(&block(), &site(&table, (100.0, 0.0), (0.0, 1.0), &[]), None);
        assert!(c.alpha_rad.abs() < 1e-12);
    }
}
