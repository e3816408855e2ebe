//! The checks of a plan (issue: "analysing the new path shows no sample above the engagement
//! limit outside the reported z-cut regions, the pocket is fully cleared and no move gouges
//! the contour or an island"), run on the finished program by the full simulation.

use super::cleared_zone::{AirLookup, ClearedZone};
use crate::core::analysis::engine::SampleResult;
use crate::core::analysis::handoff::analyze_handing_off;
use crate::core::analysis::samples::{PathSamples, SampleCollector, DRAWING_SAMPLE_BINS};
use crate::core::analysis::sampling::MovePoints;
use crate::core::analysis::{AnalysisSpec, Stack};
use crate::core::geometry::{Pocket, Point};
use crate::core::medial::Boundary;
use crate::core::progress::Progress;
use crate::core::toolpath::move_length;
use crate::core::toolpath::{Move, Toolpath};
use crate::core::CoreError;
use serde::Serialize;

/// A move is a gouge when its tool centre comes closer than `r + allowance` to a wall by
/// more than this, mm.
pub const GOUGE_TOLERANCE_MM: f64 = 1e-3;

/// Spacing of the gouge test along the moves, mm.
pub const GOUGE_STEP_MM: f64 = 0.1;

/// Where a check failed.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, utoipa::ToSchema)]
pub struct Spot {
    /// mm.
    #[serde(rename = "x")]
    pub x_mm: f64,
    /// mm.
    #[serde(rename = "y")]
    pub y_mm: f64,
    /// mm.
    #[serde(rename = "z")]
    pub z_mm: f64,
    /// The program's move (1-based) there.
    #[serde(rename = "move_index")]
    pub line: u32,
    /// α (deg) for an overload, the wall margin (mm, negative) for a gouge.
    pub value: f64,
}

/// Most overloaded stretches listed one by one (all are counted in
/// [`Verification::overload_stretches`]).
pub const MAX_LISTED_OVERLOADS: usize = 64;

/// A stretch of consecutive cutting samples of the full-depth moves above the limit: a spike
/// at a corner is a few samples long; each is listed with its program lines.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Overload {
    /// The program's moves (1-based) of its first and last sample.
    pub line_from: u32,
    pub line_to: u32,
    pub samples: usize,
    /// Path length over its samples, mm.
    pub length_mm: f64,
    /// Where α peaks (`value`: α, deg).
    pub peak: Spot,
    /// Some of it lies in a region the z-cut division cut first, on a move at the full depth
    /// (the wall pass crossing it at a corner, for example).
    pub in_zcut_region: bool,
}

impl Overload {
    /// The first and last line of a written program that the stretch spans: `moves` are the
    /// program's moves that may hold it, each with the line the writer ended it on
    /// ([`crate::core::nc::WrittenProgram::move_lines`]); a move is in the stretch when its
    /// source `line` is (blocks split from one move keep its line).
    pub fn written_lines<'a>(&self, moves: impl IntoIterator<Item = (&'a Move, u32)>) -> Option<(u32, u32)> {
        moves
            .into_iter()
            .filter(|(m, _)| (self.line_from..=self.line_to).contains(&m.line))
            .fold(None, |span, (_, line)| {
                Some(span.map_or((line, line), |(a, b): (u32, u32)| (a.min(line), b.max(line))))
            })
    }
}

/// The engagement of one kind of sample.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, utoipa::ToSchema)]
pub struct EngagementCheck {
    pub samples: usize,
    pub max_alpha_deg: f64,
    /// Samples above the limit.
    pub overloaded: usize,
}

impl EngagementCheck {
    fn add(&mut self, alpha_deg: f64, limit_deg: f64) {
        self.samples += 1;
        self.max_alpha_deg = self.max_alpha_deg.max(alpha_deg);
        if alpha_deg > limit_deg {
            self.overloaded += 1;
        }
    }
}

/// The checks of the new path by the full simulation.
#[derive(Debug, Clone, PartialEq, Serialize, utoipa::ToSchema)]
pub struct Verification {
    pub alpha_limit_deg: f64,
    /// Horizontal cutting samples outside the z-cut regions: must have no overload.
    pub outside_zcut: EngagementCheck,
    /// Samples of the z-cut passes (cut at the reduced axial depth).
    pub inside_zcut: EngagementCheck,
    /// Samples of the full-depth moves where they cross a z-cut region (the wall pass at a
    /// corner the z-cut division cut first): their overloads, short spikes, do not fail the
    /// check, but each is listed in `overloads` with its lines.
    pub crossing_zcut: EngagementCheck,
    /// Samples of ramps and plunges (the tool going down: axial engagement) and of the
    /// approach holes (a trochoid's helical entry and the full circle at its bottom).
    pub ramps: EngagementCheck,
    /// The first overloaded sample outside the z-cut regions.
    pub first_overload: Option<Spot>,
    /// Stretches of overloaded samples of the full-depth moves, outside the z-cut regions or
    /// crossing them, in program order (at most [`MAX_LISTED_OVERLOADS`]), and how many
    /// there are (reported with the lines of the written program).
    #[serde(skip)]
    pub overloads: Vec<Overload>,
    pub overload_stretches: usize,
    /// Test points where the tool comes closer to a wall than `r + allowance`.
    pub gouges: usize,
    /// Smallest `clearance − r − allowance` of the tool centre below the top, mm.
    pub min_wall_margin_mm: f64,
    pub first_gouge: Option<Spot>,
    /// Area the tool could reach but nothing removed, mm².
    pub uncleared_area_mm2: f64,
    /// A point of the uncleared area (named in the candidate's reason).
    #[serde(skip)]
    pub uncleared_at: Option<(f64, f64)>,
    /// `true` when all three checks pass.
    pub passed: bool,
}

/// Overloaded samples outside the z-cut zone, as `(xy, α deg)` (for another round of
/// treatment) and the engagement checks.
pub struct EngagementOutcome {
    pub outside: EngagementCheck,
    pub inside: EngagementCheck,
    pub crossing: EngagementCheck,
    pub ramps: EngagementCheck,
    pub first_overload: Option<Spot>,
    pub overloaded: Vec<(Point, f64)>,
    pub overloads: Vec<Overload>,
    pub overload_stretches: usize,
    /// The samples kept for drawing (see [`SampleCollector`]).
    pub samples: PathSamples,
    /// Material the path removed, mm³.
    pub removed_volume_mm3: f64,
    /// The stock the simulation left (kept by a trochoids job for another to start from).
    pub stack: Option<Stack>,
    /// Feed length that cut nothing (the analysis's air cut), mm.
    pub air_cut_length_mm: f64,
}

/// Which moves of a program are which, for [`check_engagement`].
pub struct MoveRoles<'a> {
    /// Per move: part of an approach hole (judged with the ramps).
    pub entry: &'a [bool],
    /// Per move: a pass of the z-cut division (cut at the reduced axial depth).
    pub zcut: &'a [bool],
    /// The regions the z-cut division clears (to flag the full-depth moves crossing them).
    pub zcut_zone: &'a ClearedZone,
}

/// Simulates `path` and sorts its samples into the z-cut passes, ramps, the full-depth moves
/// crossing the z-cut regions and the rest (which must stay under the limit), listing the
/// stretches of the last two above it with their lines and handing every sample to `sink`
/// too. The simulation takes a second core when one is spare; the sorting and `sink` run
/// beside it, on a thread of their own (see [`analyze_handing_off`]).
pub fn check_engagement(
    path: &Toolpath,
    analysis: &AnalysisSpec,
    roles: &MoveRoles,
    progress: &dyn Progress,
    mut sink: impl FnMut(&SampleResult) + Send,
) -> Result<EngagementOutcome, CoreError> {
    let limit = analysis.alpha_limit_deg;
    let mut out = EngagementOutcome {
        outside: EngagementCheck::default(),
        inside: EngagementCheck::default(),
        crossing: EngagementCheck::default(),
        ramps: EngagementCheck::default(),
        first_overload: None,
        overloaded: Vec::new(),
        overloads: Vec::new(),
        overload_stretches: 0,
        samples: PathSamples::default(),
        removed_volume_mm3: 0.0,
        air_cut_length_mm: 0.0,
        stack: None,
    };
    let flag = |roles: &[bool], m: usize| roles.get(m).copied().unwrap_or(false);
    // The stretch of overloaded samples being followed, if the last sample was one.
    let mut open: Option<Overload> = None;
    let total_length_mm: f64 = path.moves.iter().map(move_length).sum();
    let mut collector = SampleCollector::new(total_length_mm, DRAWING_SAMPLE_BINS);
    let mut zcut_zone = AirLookup::new(roles.zcut_zone);
    let (simulated, stack) = analyze_handing_off(path, analysis, progress, |r| {
        sink(r);
        if r.sample.rapid {
            collector.add(r);
            return;
        }
        let m = &path.moves[r.sample.move_index];
        let alpha = r.contact.alpha_rad.to_degrees();
        let p = Point::new(r.sample.p.x, r.sample.p.y);
        let entry = flag(roles.entry, r.sample.move_index);
        if entry || r.plunge || (m.end.z - m.start.z).abs() > super::cleared::SAME_LEVEL_MM {
            collector.add_with(r, true);
            out.ramps.add(alpha, limit);
            close(&mut open, &mut out);
        } else if flag(roles.zcut, r.sample.move_index) {
            collector.add_with(r, true);
            out.inside.add(alpha, limit);
            close(&mut open, &mut out);
        } else {
            let crossing = zcut_zone.is_air(p);
            if crossing {
                collector.add_with(r, true);
                out.crossing.add(alpha, limit);
            } else {
                collector.add(r);
                out.outside.add(alpha, limit);
            }
            if alpha > limit {
                let here = Spot { x_mm: p.x, y_mm: p.y, z_mm: r.sample.p.z, line: r.sample.line, value: alpha };
                if !crossing {
                    out.overloaded.push((p, alpha));
                    out.first_overload.get_or_insert(here);
                }
                let run = open.get_or_insert(Overload {
                    line_from: here.line,
                    line_to: here.line,
                    samples: 0,
                    length_mm: 0.0,
                    peak: here,
                    in_zcut_region: false,
                });
                run.line_to = here.line;
                run.samples += 1;
                run.length_mm += r.sample.step_mm;
                if alpha > run.peak.value {
                    run.peak = here;
                }
                run.in_zcut_region |= crossing;
            } else {
                close(&mut open, &mut out);
            }
        }
    })?;
    close(&mut open, &mut out);
    out.samples = collector.finish();
    out.removed_volume_mm3 = simulated.summary.removed_volume_mm3;
    out.air_cut_length_mm = simulated.summary.air_cut_length_mm;
    out.stack = Some(stack);
    Ok(out)
}

/// Ends the stretch of overloaded samples being followed, if any, and lists it.
fn close(open: &mut Option<Overload>, out: &mut EngagementOutcome) {
    if let Some(run) = open.take() {
        out.overload_stretches += 1;
        if out.overloads.len() < MAX_LISTED_OVERLOADS {
            out.overloads.push(run);
        }
    }
}

/// Checks every move that goes below `z_top_mm` against the walls: the tool centre must stay
/// inside the pocket at least `r + allowance` from every wall and island.
pub fn check_gouges(
    path: &Toolpath,
    pocket: &Pocket,
    boundary: &Boundary,
    r_mm: f64,
    allowance_mm: f64,
    z_top_mm: f64,
) -> (usize, f64, Option<Spot>) {
    let mut count = 0;
    let mut min_margin = f64::INFINITY;
    let mut first = None;
    // The margin is a signed distance to the walls less a constant, so it changes no faster
    // than the tool moves: a test point less far along the path from the last one measured
    // than that one's margin exceeds both the smallest margin so far and the gouge
    // tolerance can change neither, and is passed over.
    let mut measured: Option<f64> = None;
    let mut travelled_mm = 0.0;
    for m in &path.moves {
        if m.start.z >= z_top_mm && m.end.z >= z_top_mm {
            travelled_mm += move_length(m);
            continue;
        }
        let length = move_length(m);
        let n = (length / GOUGE_STEP_MM).ceil().max(1.0) as usize;
        let points = MovePoints::of(m);
        for k in 0..=n {
            if k > 0 {
                travelled_mm += length / n as f64;
            }
            // (Passed over before the point is placed: neither test changes anything.)
            if measured.is_some_and(|last| last - travelled_mm > min_margin.max(-GOUGE_TOLERANCE_MM)) {
                continue;
            }
            let (p, _) = points.at(k as f64 / n as f64);
            if p.z >= z_top_mm {
                continue;
            }
            let c = if pocket.contains(p.x, p.y) {
                boundary.clearance_mm(Point::new(p.x, p.y))
            } else {
                -boundary.clearance_mm(Point::new(p.x, p.y))
            };
            let margin = c - r_mm - allowance_mm;
            measured = Some(margin);
            travelled_mm = 0.0;
            min_margin = min_margin.min(margin);
            if margin < -GOUGE_TOLERANCE_MM {
                count += 1;
                first.get_or_insert(Spot { x_mm: p.x, y_mm: p.y, z_mm: p.z, line: m.line, value: margin });
            }
        }
    }
    (count, min_margin, first)
}
