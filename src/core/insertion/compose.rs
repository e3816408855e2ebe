//! The program of the plan, level by level (MODEL.md §8): at each cutting level of the base
//! path, first the trochoids (each entered by a helix on its first loop, the approach hole
//! of seed 004 Table 1 step 1), then the z-cut division stretches (slots along the axis in
//! passes of the reduced axial depth, alternating direction), then the base path with what
//! the trochoids removed cut out and re-linked. Between treatments the tool goes over at the
//! safe height. A trochoid that starts where the treatments before it at the level have
//! already swept (several branches leave one medial-axis node) goes straight down there.

use super::cleared::{trim_path, Relink, TrimReport, SAME_LEVEL_MM};
use super::cleared_zone::ClearedZone;
use super::opening::OpeningStretch;
use super::pitch::loop_exceeds;
use super::spec::{InsertionSpec, PITCH_DESIGN_MARGIN_DEG};
use super::treatments::{Stretch, TrochoidStretch, ZCutStretch};
use crate::core::cycles::arcs::helix_turns;
use crate::core::cycles::arcs::{at_z, PathBuilder};
use crate::core::cycles::setup::DEFAULT_PLUNGE_FEED_RATIO;
use crate::core::cycles::trochoid::Entry;
use crate::core::cycles::{z_levels, CycleSetup};
use crate::core::geometry::Point;
use crate::core::tolerance::LENGTH_EPS_MM;
use crate::core::toolpath::move_length;
use crate::core::toolpath::{Motion, Move, Section, Step, P3};
use crate::core::CoreError;

/// The helical entries start this far above the level they enter from, mm (**assumed**: a
/// common shop clearance for ramps).
pub const RAMP_START_ABOVE_MM: f64 = 1.0;

/// What one level of the program contains.
#[derive(Debug, Clone, Default)]
pub struct LevelMoves {
    /// Moves of each stretch (indexed as the stretches), at this level.
    pub stretch_moves: Vec<Vec<Move>>,
    /// The trimmed base path at this level.
    pub base: Vec<Move>,
    pub trim: TrimReport,
}

/// The grooving setup for a level entered from `z_from_mm`.
fn grooving_setup(spec: &InsertionSpec, z_from_mm: f64) -> CycleSetup {
    CycleSetup {
        retract_z_mm: Some(z_from_mm + RAMP_START_ABOVE_MM),
        air_feed_mm_min: Some(spec.air_feed_mm_min()),
        rapid_mm_min: spec.rapid_mm_min,
        ..CycleSetup::new(spec.grooving, spec.tool.flutes, spec.safe_z_mm)
    }
}

/// Moves of the first loop, written after the helix: a half circle and the rest of the turn.
const FIRST_LOOP_MOVES: usize = 2;

/// Loops whose whole disc the parts of a level written so far have swept: centre and loop
/// radius ρ (the tool is in the air wherever its centre lies within ρ of one).
#[derive(Debug, Default)]
struct Swept {
    discs: Vec<(Point, f64)>,
}

impl Swept {
    /// Adds what `stretch` sweeps: the loops of a trochoid no larger than the tool (a larger
    /// loop leaves a core), the final circle of an opening.
    fn add(&mut self, stretch: &Stretch, r_mm: f64) {
        match stretch {
            Stretch::Trochoid(t) => {
                let whole = t.plan.centres.iter().zip(&t.plan.rho_mm).filter(|(_, rho)| **rho <= r_mm + LENGTH_EPS_MM);
                self.discs.extend(whole.map(|(c, rho)| (*c, *rho)));
            }
            Stretch::Opening(o) if o.final_radius_mm() <= r_mm + LENGTH_EPS_MM => {
                self.discs.push((o.centre, o.final_radius_mm()));
            }
            Stretch::Opening(_) | Stretch::ZCut(_) => {}
        }
    }

    /// Whether trochoid `t` may go straight down into the space already swept instead of
    /// ramping into the material: its start lies within a swept disc, and its first loop,
    /// cut against that disc, engages no more than the pitch design limit (the engagement
    /// of a loop after the previous one, MODEL.md §7, at the distance between their centres).
    fn holds_start_of(&self, t: &TrochoidStretch, spec: &InsertionSpec) -> bool {
        let (start, c, rho) = (t.plan.start(), t.plan.centres[0], t.plan.rho_mm[0]);
        let limit = spec.alpha_limit_deg - PITCH_DESIGN_MARGIN_DEG;
        self.discs.iter().any(|&(d, rho_d)| {
            start.distance_mm(d) <= rho_d && !loop_exceeds(rho_d, rho, c.distance_mm(d), spec.r_mm(), limit)
        })
    }
}

/// The moves of a trochoid at `z_mm`, from the safe height above its start back to it, and
/// how many of them make the approach hole (up to the helix and the full circle at the
/// bottom that follows it: seed 004 Table 1 step 1). A trochoid that starts in space
/// already swept (`in_swept_space`) goes straight down there at the plunge feed instead, and
/// has no approach hole.
pub fn trochoid_moves(
    t: &TrochoidStretch,
    spec: &InsertionSpec,
    z_from_mm: f64,
    z_mm: f64,
    in_swept_space: bool,
) -> Result<(Vec<Move>, usize), CoreError> {
    let setup = grooving_setup(spec, z_from_mm);
    let mut b = PathBuilder::starting_at(at_z(t.plan.start(), spec.safe_z_mm), &setup);
    let entry =
        if in_swept_space { Entry::Plunge } else { Entry::Helix { pitch_mm: spec.ramp_pitch_mm(t.plan.rho_mm[0]) } };
    t.plan.append_pass(&mut b, z_mm, entry, &setup)?;
    b.rapid_z(spec.safe_z_mm);
    let moves = b.finish();
    let helix = moves.iter().position(|m| matches!(m.motion, Motion::Arc { .. }) && m.end.z < m.start.z);
    let entry = helix.map_or(0, |h| (h + 1 + FIRST_LOOP_MOVES).min(moves.len()));
    Ok((moves, entry))
}

/// The moves of an opening at `z_mm`: a helix on its first circle, a full circle there at the
/// bottom, the spiral out and the last circle; and how many make the approach hole (up to the
/// full circle after the helix).
pub fn opening_moves(
    o: &OpeningStretch,
    spec: &InsertionSpec,
    z_from_mm: f64,
    z_mm: f64,
) -> Result<(Vec<Move>, usize), CoreError> {
    let setup = grooving_setup(spec, z_from_mm);
    let clockwise = spec.direction.outside_material_clockwise();
    let feed = setup.feed_mm_min();
    let mut b = PathBuilder::starting_at(at_z(o.start(), spec.safe_z_mm), &setup);
    b.rapid_z(setup.retract_z_mm());
    let turns = helix_turns("ramp_pitch_mm", setup.retract_z_mm() - z_mm, spec.ramp_pitch_mm(o.radii_mm[0]))?;
    b.helix_down(o.centre, z_mm, turns, clockwise, feed);
    b.full_circle(o.centre, clockwise, feed);
    let entry = b.len();
    o.append_spiral(&mut b, clockwise, feed);
    b.rapid_z(spec.safe_z_mm);
    Ok((b.finish(), entry))
}

/// The moves of a z-cut stretch from `z_from_mm` down to `z_mm`: a pass along the axis at
/// each level of at most the z-cut depth, back and forth.
pub fn zcut_moves(z: &ZCutStretch, spec: &InsertionSpec, z_from_mm: f64, z_mm: f64) -> Result<Vec<Move>, CoreError> {
    let setup = grooving_setup(spec, z_from_mm);
    let feed = setup.feed_mm_min();
    let plunge = setup.plunge_feed_mm_min();
    let levels = z_levels(z_from_mm, z_mm, spec.zcut_ad_mm)?;
    let start = z.path[0];
    let mut b = PathBuilder::starting_at(at_z(start, spec.safe_z_mm), &setup);
    b.rapid_z(setup.retract_z_mm());
    let mut forward = true;
    for level in levels {
        let here = b.position();
        b.line(P3::new(here.x, here.y, level), plunge);
        let points: Vec<_> = if forward { z.path.clone() } else { z.path.iter().rev().copied().collect() };
        for p in points.iter().skip(1) {
            b.line(at_z(*p, level), feed);
        }
        forward = !forward;
    }
    b.rapid_z(spec.safe_z_mm);
    Ok(b.finish())
}

/// The cutting levels of a path: the heights of its horizontal feed moves below `z_top_mm`,
/// in the order they are first cut.
pub fn cutting_levels(path: &[Move], z_top_mm: f64) -> Vec<f64> {
    let mut levels: Vec<f64> = Vec::new();
    for m in path {
        let level = !matches!(m.motion, Motion::Rapid)
            && (m.start.z - m.end.z).abs() <= SAME_LEVEL_MM
            && m.end.z < z_top_mm - SAME_LEVEL_MM
            && ((m.end.x - m.start.x).abs() > SAME_LEVEL_MM
                || (m.end.y - m.start.y).abs() > SAME_LEVEL_MM
                || matches!(m.motion, Motion::Arc { .. }));
        if level && !levels.iter().any(|z| (z - m.end.z).abs() <= SAME_LEVEL_MM) {
            levels.push(m.end.z);
        }
    }
    levels
}

/// Splits `path` where each level is first cut: `parts[k]` holds the moves from the first
/// move that goes towards level `k` (after the last move at a higher level) up to the next.
fn split_by_level(path: &[Move], levels: &[f64]) -> Vec<Vec<Move>> {
    let mut parts: Vec<Vec<Move>> = vec![Vec::new(); levels.len().max(1)];
    let mut current = 0;
    for m in path {
        let next = current + 1;
        if next < levels.len() && (m.end.z - levels[next]).abs() <= SAME_LEVEL_MM && m.end.z < m.start.z {
            current = next;
        }
        parts[current].push(*m);
    }
    parts
}

/// Appends `moves` to `out`, going from where `out` ends to their start over the safe height.
pub fn append_over(out: &mut Vec<Move>, moves: &[Move], safe_z_mm: f64) {
    let Some(first) = moves.first() else { return };
    if let Some(last) = out.last().copied() {
        let (a, b) = (last.end, first.start);
        let same = (a.x - b.x).abs() <= SAME_LEVEL_MM
            && (a.y - b.y).abs() <= SAME_LEVEL_MM
            && (a.z - b.z).abs() <= SAME_LEVEL_MM;
        if !same {
            let mut push = |from: P3, to: P3| {
                out.push(Move { motion: Motion::Rapid, start: from, end: to, feed_mm_min: last.feed_mm_min, ..last });
            };
            let up = P3::new(a.x, a.y, safe_z_mm.max(a.z));
            let over = P3::new(b.x, b.y, up.z);
            if a.z < up.z {
                push(a, up);
            }
            push(up, over);
            if b.z < over.z {
                push(over, b);
            }
        }
    }
    out.extend_from_slice(moves);
}

/// A composed program.
pub struct Composed {
    pub moves: Vec<Move>,
    /// Per move: part of an approach hole (helix and the circle after it).
    pub entry: Vec<bool>,
    /// Per move: the stretch it belongs to (its index), or the number of stretches for the
    /// base path. The moves over the safe height that lead to a part belong to it.
    pub owner: Vec<usize>,
    /// Per move: the part of the program it belongs to (level, step, region); `None` only
    /// for a path with no cutting level.
    pub labels: Vec<Option<Section>>,
    /// The cutting levels, in order.
    pub levels: Vec<f64>,
    pub per_level: Vec<LevelMoves>,
}

/// The section of the moves of stretch `i` (`None`: the base path) at level `k` (height
/// `z_mm`): `entry` for the approach hole of a trochoid or an opening.
fn stretch_section(
    stretch: Option<(usize, &Stretch)>,
    entry: bool,
    k: usize,
    z_mm: f64,
    spec: &InsertionSpec,
) -> Section {
    let step = match stretch {
        None => spec.base_step,
        Some((_, Stretch::Trochoid(_) | Stretch::Opening(_))) if entry => Step::HelicalBoring,
        Some((_, Stretch::Trochoid(_))) => Step::TrochoidalGrooving,
        Some((_, Stretch::Opening(_))) => Step::SpiralHoleExpansion,
        Some((_, Stretch::ZCut(_))) => Step::ZCutDivision,
    };
    let as_u32 = |n: usize| u32::try_from(n).unwrap_or(u32::MAX);
    Section { layer: as_u32(k), z_mm, step, region: stretch.map(|(i, _)| as_u32(i)) }
}

/// The program: every level's treatments, then its trimmed base path.
pub fn compose(
    base: &[Move],
    stretches: &[Stretch],
    zone: &ClearedZone,
    spec: &InsertionSpec,
) -> Result<Composed, CoreError> {
    let levels = cutting_levels(base, spec.z_top_mm);
    let parts = split_by_level(base, &levels);
    let mut program = Vec::new();
    let mut entry: Vec<bool> = Vec::new();
    let mut owner: Vec<usize> = Vec::new();
    let mut labels: Vec<Option<Section>> = Vec::new();
    let mut per_level = Vec::new();
    let mut z_from = spec.z_top_mm;
    for (k, part) in parts.iter().enumerate() {
        let Some(&z) = levels.get(k) else {
            // Moves after the last level (the final retract) end the part before them.
            append_over(&mut program, part, spec.safe_z_mm);
            owner.resize(program.len(), stretches.len());
            let last = labels.last().copied().flatten();
            labels.resize(program.len(), last);
            continue;
        };
        let mut level = LevelMoves::default();
        let mut swept = Swept::default();
        for (i, s) in stretches.iter().enumerate() {
            let (moves, entry_moves) = match s {
                Stretch::Trochoid(t) => trochoid_moves(t, spec, z_from, z, swept.holds_start_of(t, spec))?,
                Stretch::ZCut(c) => (zcut_moves(c, spec, z_from, z)?, 0),
                Stretch::Opening(o) => opening_moves(o, spec, z_from, z)?,
            };
            append_over(&mut program, &moves, spec.safe_z_mm);
            entry.resize(program.len(), false);
            owner.resize(program.len(), i);
            let first = program.len() - moves.len();
            entry[first..first + entry_moves].iter_mut().for_each(|e| *e = true);
            // The link over the safe height belongs to the part it leads to.
            labels.resize(first, Some(stretch_section(Some((i, s)), entry_moves > 0, k, z, spec)));
            labels.extend((0..moves.len()).map(|m| Some(stretch_section(Some((i, s)), m < entry_moves, k, z, spec))));
            level.stretch_moves.push(moves);
            swept.add(s, spec.r_mm());
        }
        let relink = Relink {
            z_mm: z,
            hop_z_mm: z_from + RAMP_START_ABOVE_MM,
            rapid_mm_min: spec.rapid_mm_min,
            plunge_feed_mm_min: DEFAULT_PLUNGE_FEED_RATIO
                * crate::core::conditions::feed_mm_min(
                    spec.roughing.fz_mm,
                    spec.tool.flutes,
                    spec.roughing.spindle_rpm,
                ),
            air_feed_mm_min: spec.air_feed_mm_min(),
            tool_radius_mm: spec.r_mm(),
        };
        let (trimmed, trim) = trim_path(part, zone, &relink);
        append_over(&mut program, &trimmed, spec.safe_z_mm);
        owner.resize(program.len(), stretches.len());
        labels.resize(program.len(), Some(stretch_section(None, false, k, z, spec)));
        level.base = trimmed;
        level.trim = trim;
        per_level.push(level);
        z_from = z;
    }
    entry.resize(program.len(), false);
    owner.resize(program.len(), stretches.len());
    labels.resize(program.len(), None);
    // Joins and trims can leave moves of no length; a program has none.
    let keep: Vec<bool> =
        program.iter().map(|m| matches!(m.motion, Motion::Arc { .. }) || move_length(m) > LENGTH_EPS_MM).collect();
    let kept = |i: &usize| keep[*i];
    let mut program: Vec<Move> = (0..program.len()).filter(kept).map(|i| program[i]).collect();
    let entry: Vec<bool> = (0..keep.len()).filter(kept).map(|i| entry[i]).collect();
    let owner: Vec<usize> = (0..keep.len()).filter(kept).map(|i| owner[i]).collect();
    let labels: Vec<Option<Section>> = (0..keep.len()).filter(kept).map(|i| labels[i]).collect();
    for (i, m) in program.iter_mut().enumerate() {
        m.line = u32::try_from(i + 1).unwrap_or(u32::MAX);
    }
    Ok(Composed { moves: program, entry, owner, labels, levels, per_level })
}
