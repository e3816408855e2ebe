//! Critical branches (seed 004 §2.1): where a path overloads the tool, it runs along or
//! across the medial axis (inner corners, narrow regions); the overloaded samples of the
//! full simulation are mapped to the nearest axis branch and gathered into intervals of
//! arc length along it, which the trochoid planner then treats.

use super::axis::{AxisBranch, MedialAxis};
use crate::core::geometry::Point;
use serde::Serialize;

/// A stretch of a branch where the base path overloads the tool.
#[derive(Debug, Clone, PartialEq, Serialize, utoipa::ToSchema)]
pub struct CriticalInterval {
    pub branch: usize,
    /// Arc length along the branch from its first point, mm.
    pub s_start_mm: f64,
    pub s_end_mm: f64,
    pub max_alpha_deg: f64,
    /// The smallest clearance R in the interval, mm.
    pub min_clearance_mm: f64,
    /// Overloaded samples mapped to it.
    pub samples: usize,
}

/// The overloaded samples and where they lie.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CriticalBranches {
    pub intervals: Vec<CriticalInterval>,
    /// Overloaded samples farther than the search distance from any branch (entries,
    /// links): the axis does not explain them.
    pub off_axis_samples: usize,
}

/// Where a point projects onto a branch.
struct Projection {
    branch: usize,
    s_mm: f64,
    distance_mm: f64,
    clearance_mm: f64,
}

/// Arc length of every point of `b`, from its first point.
fn stations(b: &AxisBranch) -> Vec<f64> {
    let mut s = Vec::with_capacity(b.points.len());
    let mut total = 0.0;
    for (i, p) in b.points.iter().enumerate() {
        if i > 0 {
            total += p.point.distance_mm(b.points[i - 1].point);
        }
        s.push(total);
    }
    s
}

fn project(axis: &MedialAxis, stations: &[Vec<f64>], q: Point) -> Option<Projection> {
    let mut best: Option<Projection> = None;
    for (bi, b) in axis.branches.iter().enumerate() {
        for (i, w) in b.points.windows(2).enumerate() {
            let (a, c) = (w[0].point, w[1].point);
            let (dx, dy) = (c.x - a.x, c.y - a.y);
            let len2 = dx * dx + dy * dy;
            let t = if len2 > 0.0 { (((q.x - a.x) * dx + (q.y - a.y) * dy) / len2).clamp(0.0, 1.0) } else { 0.0 };
            let foot = Point::new(a.x + t * dx, a.y + t * dy);
            let d = foot.distance_mm(q);
            if best.as_ref().is_none_or(|p| d < p.distance_mm) {
                best = Some(Projection {
                    branch: bi,
                    s_mm: stations[bi][i] + t * (stations[bi][i + 1] - stations[bi][i]),
                    distance_mm: d,
                    clearance_mm: w[0].clearance_mm + t * (w[1].clearance_mm - w[0].clearance_mm),
                });
            }
        }
    }
    best
}

/// Maps overloaded samples `(xy, α deg)` to the axis: samples within `max_distance_mm` of a
/// branch count on it; per branch, samples closer than `merge_gap_mm` along it form one
/// interval, widened by `pad_mm` at both ends (within the branch).
pub fn critical_branches(
    axis: &MedialAxis,
    overloaded: &[(Point, f64)],
    max_distance_mm: f64,
    merge_gap_mm: f64,
    pad_mm: f64,
) -> CriticalBranches {
    let stations: Vec<Vec<f64>> = axis.branches.iter().map(stations).collect();
    let mut hits: Vec<Vec<(f64, f64, f64)>> = vec![Vec::new(); axis.branches.len()];
    let mut off_axis_samples = 0;
    for &(q, alpha) in overloaded {
        match project(axis, &stations, q) {
            Some(p) if p.distance_mm <= max_distance_mm => hits[p.branch].push((p.s_mm, alpha, p.clearance_mm)),
            _ => off_axis_samples += 1,
        }
    }
    let mut intervals = Vec::new();
    for (branch, mut h) in hits.into_iter().enumerate() {
        if h.is_empty() {
            continue;
        }
        h.sort_by(|a, b| a.0.total_cmp(&b.0));
        let length = stations[branch].last().copied().unwrap_or(0.0);
        let mut current: Option<CriticalInterval> = None;
        for (s, alpha, clearance) in h {
            match &mut current {
                Some(c) if s - c.s_end_mm <= merge_gap_mm => {
                    c.s_end_mm = s;
                    c.max_alpha_deg = c.max_alpha_deg.max(alpha);
                    c.min_clearance_mm = c.min_clearance_mm.min(clearance);
                    c.samples += 1;
                }
                _ => {
                    if let Some(done) = current.take() {
                        intervals.push(done);
                    }
                    current = Some(CriticalInterval {
                        branch,
                        s_start_mm: s,
                        s_end_mm: s,
                        max_alpha_deg: alpha,
                        min_clearance_mm: clearance,
                        samples: 1,
                    });
                }
            }
        }
        intervals.extend(current);
        for c in intervals.iter_mut().filter(|c| c.branch == branch) {
            c.s_start_mm = (c.s_start_mm - pad_mm).max(0.0);
            c.s_end_mm = (c.s_end_mm + pad_mm).min(length);
        }
    }
    CriticalBranches { intervals, off_axis_samples }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::core::analysis::{analyze_with, AnalysisSpec, StockRegion, DEFAULT_ALPHA_LIMIT_DEG};
    use crate::core::medial::{medial_axis, MedialOptions};
    use crate::core::pocketing::{contour_parallel, PocketingSpec};
    use crate::core::progress::NoProgress;
    use crate::core::tool::{EndMill, ToolType};

    #[test]
    fn the_overloaded_corners_of_a_contour_parallel_path_lie_on_the_rectangles_corner_branches() {
        let (pocket, _) = super::super::test_shapes::rectangle();
        let axis = medial_axis(&pocket, &MedialOptions::default()).unwrap();
        let spec = PocketingSpec {
            tool_radius_mm: 5.0,
            radial_depth_mm: 2.0,
            allowance_mm: 0.0,
            z_mm: -5.0,
            safe_z_mm: 5.0,
            feed_mm_min: 5760.0,
            plunge_feed_mm_min: 1000.0,
            spindle_rpm: 9600.0,
            climb: true,
            corner_loops: false,
        };
        let path = contour_parallel(&pocket, &spec).unwrap().toolpath;
        let analysis = AnalysisSpec {
            tool: EndMill { tool_type: ToolType::Square, diameter_mm: 10.0, flutes: 6, corner_radius_mm: 0.0 },
            stock: vec![StockRegion::Pocket(pocket.clone())],
            open: vec![],
            z_top: 0.0,
            z_bottom: -5.0,
            force_model: None,
            default_spindle_rpm: Some(9600.0),
            rapid_mm_min: 20000.0,
            sample_spacing_mm: None,
            cell_mm: None,
            alpha_limit_deg: DEFAULT_ALPHA_LIMIT_DEG,
            series_points: 0,
            stock_memory_bytes: crate::core::analysis::DEFAULT_STOCK_MEMORY_BYTES,
        };
        let mut overloaded = Vec::new();
        analyze_with(&path, &analysis, &NoProgress, |r| {
            let alpha = r.contact.alpha_rad.to_degrees();
            if alpha > DEFAULT_ALPHA_LIMIT_DEG && !r.plunge {
                overloaded.push((Point::new(r.sample.p.x, r.sample.p.y), alpha));
            }
        })
        .unwrap();
        assert!(!overloaded.is_empty());
        let found = critical_branches(&axis, &overloaded, 1.0, 5.0, 5.0);
        // The four diagonal branches end in the corners (0,0), (0,40), (60,0), (60,40).
        let corner_branches: Vec<usize> = axis
            .branches
            .iter()
            .enumerate()
            .filter(|(_, b)| {
                let ends = [b.points[0].point, b.points[b.points.len() - 1].point];
                ends.iter().any(|p| (p.x < 1.0 || p.x > 59.0) && (p.y < 1.0 || p.y > 39.0))
            })
            .map(|(i, _)| i)
            .collect();
        assert_eq!(corner_branches.len(), 4);
        for b in &corner_branches {
            assert!(found.intervals.iter().any(|c| c.branch == *b && c.max_alpha_deg > 60.0), "branch {b}: {found:?}");
        }
        // The corner loads sit where the clearance is a few step-overs above r.
        for c in found.intervals.iter().filter(|c| corner_branches.contains(&c.branch)) {
            assert!(c.min_clearance_mm >= 4.9 && c.s_end_mm > c.s_start_mm, "{c:?}");
        }
    }
}
