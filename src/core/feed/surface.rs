//! Constant feed at the cutting point for 3-D finishing with a ball end mill (seed 000,
//! Eq. 1; MODEL.md §4): the tool-centre path's curvature comes from a local quadratic
//! fit over the minute segments of CAM output (exact on arcs), the cutting point is the
//! ball centre plus r along the contact normal, and `F_c = R · F_p / |PO|` with `|PO|`
//! measured in the osculating plane.

use super::collect::{Collector, SampleIn};
use super::plan::{assemble, check_spec, FeedPlan, FeedSpec};
use super::rule::{FeedStrategy, SampleCut};
use crate::core::analysis::report::PathPoint;
use crate::core::analysis::sampling::point_on;
use crate::core::curvature::CORNER_ANGLE_DEG;
use crate::core::progress::Progress;
use crate::core::toolpath::move_length;
use crate::core::toolpath::{Motion, Move, Plane, Toolpath};
use crate::core::CoreError;
use nalgebra::{SMatrix, Vector3};

/// Half-width of the window of the local fit by default, mm (as for 2.5-D paths).
pub const DEFAULT_SURFACE_FIT_HALF_WIDTH_MM: f64 = 1.0;
/// Smallest ratio of cutting-point feed to centre feed (a convex path about as tight as
/// the ball): the feed is clamped to the maximum there anyway.
const MIN_RATIO: f64 = 0.05;
/// Vectors shorter than this have no direction.
const TINY: f64 = 1e-9;
/// Samples between progress reports.
const PROGRESS_EVERY: usize = 16_384;

/// Where the ball touches the surface.
#[derive(Debug, Clone, PartialEq)]
pub enum ContactNormal {
    /// Straight down, made perpendicular to the path: the surface normal lies in the
    /// vertical plane of travel (raster finishing from above).
    Down,
    /// The path's principal normal, turned to point downwards.
    PrincipalNormal,
    /// One direction per move (from the ball centre to the contact point).
    PerMove(Vec<[f64; 3]>),
}

/// The tool and the sampling of a surface-finishing path.
#[derive(Debug, Clone, PartialEq)]
pub struct SurfaceSpec {
    pub ball_radius_mm: f64,
    pub sample_spacing_mm: f64,
    pub fit_half_width_mm: f64,
    pub contact: ContactNormal,
}

/// Curvature of the 3-D tool-centre path at a point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Curvature3 {
    /// 1 / radius, 1/mm (0 on straight paths).
    pub kappa: f64,
    pub tangent: Vector3<f64>,
    /// Unit principal normal (towards the centre of curvature); zero when straight.
    pub normal: Vector3<f64>,
}

fn v(p: crate::core::toolpath::P3) -> Vector3<f64> {
    Vector3::new(p.x, p.y, p.z)
}

fn straight(tangent: Vector3<f64>) -> Curvature3 {
    Curvature3 { kappa: 0.0, tangent, normal: Vector3::zeros() }
}

/// Curvature from the first and second derivatives of a curve.
fn from_derivatives(d1: Vector3<f64>, d2: Vector3<f64>) -> Curvature3 {
    let speed = d1.norm();
    if speed < TINY {
        return straight(Vector3::zeros());
    }
    let tangent = d1 / speed;
    let kappa = d1.cross(&d2).norm() / speed.powi(3);
    let perpendicular = d2 - tangent * d2.dot(&tangent);
    let normal = if perpendicular.norm() < TINY { Vector3::zeros() } else { perpendicular.normalize() };
    Curvature3 { kappa, tangent, normal }
}

/// Degree of the local fit: a quartic follows a circle over the window with a curvature
/// error far below a quadratic's.
const FIT_DEGREE: usize = 4;
type Normal = SMatrix<f64, { FIT_DEGREE + 1 }, { FIT_DEGREE + 1 }>;

/// Local polynomial least-squares fit of `points` (arc-length parameters `s`, centred on
/// `s0`): the curvature at `s0` (seed 000 §2: curvature from a local polynomial fit).
/// Fits of lower degree are used when there are too few points.
fn fit(points: &[Vector3<f64>], s: &[f64], s0: f64) -> Option<Curvature3> {
    let degree = FIT_DEGREE.min(points.len().saturating_sub(1));
    if degree < 2 {
        return None;
    }
    let mut a = Normal::zeros();
    let mut b = [Vector3::<f64>::zeros(); FIT_DEGREE + 1];
    // Scaled parameter keeps the normal matrix well conditioned.
    let scale = s.iter().map(|si| (si - s0).abs()).fold(0.0, f64::max).max(TINY);
    for (p, &si) in points.iter().zip(s) {
        let u = (si - s0) / scale;
        let mut basis = [0.0; FIT_DEGREE + 1];
        let mut power = 1.0;
        for slot in basis.iter_mut().take(degree + 1) {
            *slot = power;
            power *= u;
        }
        for r in 0..=degree {
            for c in 0..=degree {
                a[(r, c)] += basis[r] * basis[c];
            }
            b[r] += p * basis[r];
        }
    }
    for k in degree + 1..=FIT_DEGREE {
        a[(k, k)] = 1.0;
    }
    let inv = a.try_inverse()?;
    let coef = |k: usize| (0..=degree).fold(Vector3::zeros(), |acc, j| acc + b[j] * inv[(k, j)]);
    Some(from_derivatives(coef(1) / scale, coef(2) * 2.0 / (scale * scale)))
}

/// Curvature at the start and end of every move.
pub fn move_curvatures_3d(path: &Toolpath, half_width_mm: f64) -> Vec<(Curvature3, Curvature3)> {
    let moves = &path.moves;
    let mut out: Vec<(Curvature3, Curvature3)> = moves
        .iter()
        .map(|m| {
            let d = v(m.end) - v(m.start);
            let t = if d.norm() < TINY { Vector3::zeros() } else { d.normalize() };
            (straight(t), straight(t))
        })
        .collect();
    let is_line = |m: &Move| matches!(m.motion, Motion::Linear) && move_length(m) > TINY;
    let cos_corner = CORNER_ANGLE_DEG.to_radians().cos();
    let mut i = 0;
    while i < moves.len() {
        if let Motion::Arc { .. } = moves[i].motion {
            out[i] = (arc_curvature(&moves[i], 0.0), arc_curvature(&moves[i], 1.0));
            i += 1;
            continue;
        }
        if !is_line(&moves[i]) {
            i += 1;
            continue;
        }
        let start = i;
        while i < moves.len() && is_line(&moves[i]) {
            i += 1;
        }
        let mut pts = vec![v(moves[start].start)];
        pts.extend(moves[start..i].iter().map(|m| v(m.end)));
        let mut s = vec![0.0];
        for w in pts.windows(2) {
            s.push(s[s.len() - 1] + (w[1] - w[0]).norm());
        }
        let mut at_vertex = vec![None; pts.len()];
        for j in 0..pts.len() {
            // A sharp corner is no curvature: both sides stay straight.
            if j > 0 && j + 1 < pts.len() {
                let (a, b) = ((pts[j] - pts[j - 1]).normalize(), (pts[j + 1] - pts[j]).normalize());
                if a.dot(&b) < cos_corner {
                    continue;
                }
            }
            let lo = (0..j).rev().take_while(|&k| s[j] - s[k] <= half_width_mm).last().unwrap_or(j);
            let hi = (j + 1..pts.len()).take_while(|&k| s[k] - s[j] <= half_width_mm).last().unwrap_or(j);
            let (lo, hi) = (lo.min(j.saturating_sub(1)), hi.max((j + 1).min(pts.len() - 1)));
            if hi - lo >= 2 {
                at_vertex[j] = fit(&pts[lo..=hi], &s[lo..=hi], s[j]);
            }
        }
        for (n, slot) in out[start..i].iter_mut().enumerate() {
            if let Some(k) = at_vertex[n] {
                slot.0 = k;
            }
            if let Some(k) = at_vertex[n + 1] {
                slot.1 = k;
            }
        }
    }
    out
}

/// Exact curvature of an arc move at fraction `t` (the helix pitch is neglected).
fn arc_curvature(m: &Move, t: f64) -> Curvature3 {
    let Motion::Arc { center, plane, .. } = m.motion else { return straight(Vector3::zeros()) };
    let p = v(point_on(m, t).0);
    let eps = 1e-6;
    let (a, b) = (v(point_on(m, (t - eps).max(0.0)).0), v(point_on(m, (t + eps).min(1.0)).0));
    let tangent = (b - a).try_normalize(TINY).unwrap_or_else(Vector3::zeros);
    let axis = match plane {
        Plane::Xy => Vector3::z(),
        Plane::Zx => Vector3::y(),
        Plane::Yz => Vector3::x(),
    };
    let mut to_centre = v(center) - p;
    to_centre -= axis * to_centre.dot(&axis);
    let r = to_centre.norm();
    if r < TINY {
        return straight(tangent);
    }
    Curvature3 { kappa: 1.0 / r, tangent, normal: to_centre / r }
}

fn interpolate(ends: (Curvature3, Curvature3), t: f64) -> Curvature3 {
    let kappa = ends.0.kappa + (ends.1.kappa - ends.0.kappa) * t;
    let mix = |a: Vector3<f64>, b: Vector3<f64>| {
        let m = a * (1.0 - t) + b * t;
        m.try_normalize(TINY).unwrap_or(if t < 0.5 { a } else { b })
    };
    Curvature3 { kappa, tangent: mix(ends.0.tangent, ends.1.tangent), normal: mix(ends.0.normal, ends.1.normal) }
}

/// Feed at the cutting point over feed at the ball centre, `|PO| / R` (seed 000, Eq. 1),
/// with `n` the unit direction from the ball centre to the cutting point: in the
/// osculating plane `P − O = r·n − R·N`, so `|PO|/R = √((rκ n·N − 1)² + (rκ n·T)²)`.
pub fn cutting_point_ratio_3d(k: &Curvature3, ball_radius_mm: f64, n: &Vector3<f64>) -> f64 {
    let rk = ball_radius_mm * k.kappa;
    ((rk * n.dot(&k.normal) - 1.0).powi(2) + (rk * n.dot(&k.tangent)).powi(2)).sqrt().max(MIN_RATIO)
}

fn contact_normal(contact: &ContactNormal, k: &Curvature3, move_index: usize) -> Option<Vector3<f64>> {
    match contact {
        ContactNormal::Down => {
            let t = k.tangent;
            (-Vector3::z() + t * t.z).try_normalize(TINY)
        }
        ContactNormal::PrincipalNormal => {
            let n = k.normal;
            (n.norm() > TINY).then(|| if n.z > 0.0 { -n } else { n })
        }
        ContactNormal::PerMove(normals) => {
            normals.get(move_index).and_then(|n| Vector3::new(n[0], n[1], n[2]).try_normalize(TINY))
        }
    }
}

/// The sample spacing of a surface-finishing optimisation and the samples it takes.
pub fn sample_count(path: &Toolpath, surface: &SurfaceSpec) -> (f64, f64) {
    let spacing = surface.sample_spacing_mm;
    (spacing, path.moves.iter().map(|m| (move_length(m) / spacing).ceil().max(1.0)).sum())
}

/// Checks that `path` can be optimised for surface finishing with `surface` and `spec`.
pub fn check_surface(path: &Toolpath, surface: &SurfaceSpec, spec: &FeedSpec) -> Result<(), CoreError> {
    check_spec(spec)?;
    if spec.rule.strategy != FeedStrategy::CuttingPoint {
        return Err(CoreError::invalid(
            "strategy",
            "surface finishing holds the feed at the cutting point only (cutting_point): constant force needs the stock simulation of side milling",
        ));
    }
    crate::core::error::require_positive("sample_spacing_mm", surface.sample_spacing_mm)?;
    crate::core::error::require_positive("fit_half_width_mm", surface.fit_half_width_mm)?;
    if let ContactNormal::PerMove(normals) = &surface.contact {
        if normals.len() != path.moves.len() {
            return Err(CoreError::invalid(
                "contact_normals",
                format!("{} normals for {} moves: give one per move", normals.len(), path.moves.len()),
            ));
        }
        if let Some(i) =
            normals.iter().position(|n| !n.iter().all(|c| c.is_finite()) || n.iter().all(|c| c.abs() < TINY))
        {
            return Err(CoreError::invalid(format!("contact_normals[{i}]"), "must be a finite, non-zero vector"));
        }
    }
    if let Some(m) =
        path.moves.iter().find(|m| !matches!(m.motion, Motion::Rapid) && m.feed_mm_min.is_none_or(|f| f <= 0.0))
    {
        return Err(CoreError::invalid("program", format!("line {}: a feed move with no feed (F)", m.line)));
    }
    super::plan::check_sample_count(sample_count(path, surface))?;
    Ok(())
}

/// Optimises the feeds of a 3-D ball-end finishing path for a constant feed at the
/// cutting point (no stock simulation: every feed move is taken to cut).
pub fn optimize_surface_finishing(
    path: &Toolpath,
    surface: &SurfaceSpec,
    spec: &FeedSpec,
    progress: &dyn Progress,
) -> Result<FeedPlan, CoreError> {
    check_surface(path, surface, spec)?;
    let curvatures = move_curvatures_3d(path, surface.fit_half_width_mm);
    let mut collector = Collector::new(spec.rule);
    let (mut s_mm, mut n) = (0.0, 0usize);
    for (index, m) in path.moves.iter().enumerate() {
        let len = move_length(m);
        let steps = ((len / surface.sample_spacing_mm).ceil() as usize).max(1);
        for k in 1..=steps {
            n += 1;
            if n.is_multiple_of(PROGRESS_EVERY) {
                progress.checkpoint()?;
            }
            let t = k as f64 / steps as f64;
            let p = point_on(m, t).0;
            s_mm += len / steps as f64;
            let curvature = interpolate(curvatures[index], t);
            let ratio = contact_normal(&surface.contact, &curvature, index)
                .map_or(1.0, |nrm| cutting_point_ratio_3d(&curvature, surface.ball_radius_mm, &nrm));
            collector.add(&SampleIn {
                at: PathPoint { s_mm, line: m.line, x: p.x, y: p.y, z: p.z },
                step_mm: len / steps as f64,
                move_index: index,
                rapid: matches!(m.motion, Motion::Rapid),
                cut: SampleCut {
                    alpha_rad: 0.0,
                    arc_length_mm: 0.0,
                    ad_mm: 0.0,
                    cutting_point_ratio: ratio,
                    centre_radius_mm: f64::INFINITY,
                    tool_radius_mm: surface.ball_radius_mm,
                    programmed_feed_mm_min: m.feed_mm_min.unwrap_or(0.0),
                    spindle_rpm: m.spindle_rpm,
                    plunge: false,
                    in_material: true,
                },
                force_before_n: None,
            });
        }
    }
    collector.finish();
    Ok(assemble(path, collector, spec, None, path.warnings.clone()))
}
