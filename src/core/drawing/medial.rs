//! The medial axis of a pocket in the scene: each branch cut into stretches of one radius
//! class (seed 004 §2.3, Figure 6), with their clearance range.

use super::scene::{MedialClass, MedialEdge};
use crate::core::medial::{AxisBranch, BranchClasses, MedialAxis, RadiusClass};

fn class_of(c: RadiusClass) -> MedialClass {
    match c {
        RadiusClass::A => MedialClass::A,
        RadiusClass::B => MedialClass::B,
        RadiusClass::C => MedialClass::C,
    }
}

/// The points of `branch` between arc lengths `from` and `to` (mm), with their clearances.
fn stretch(branch: &AxisBranch, from: f64, to: f64) -> (Vec<[f64; 2]>, f64, f64) {
    let (mut points, mut lo, mut hi) = (Vec::new(), f64::INFINITY, 0.0_f64);
    let mut s = 0.0;
    for (i, p) in branch.points.iter().enumerate() {
        if i > 0 {
            s += branch.points[i - 1].point.distance_mm(p.point);
        }
        if s >= from - 1e-9 && s <= to + 1e-9 {
            points.push([p.point.x, p.point.y]);
            lo = lo.min(p.clearance_mm);
            hi = hi.max(p.clearance_mm);
        }
    }
    (points, lo, hi)
}

/// The axis as class stretches for `layer`.
pub fn medial_edges(axis: &MedialAxis, classes: &[BranchClasses], layer: Option<usize>) -> Vec<MedialEdge> {
    let mut edges = Vec::new();
    for bc in classes {
        let Some(branch) = axis.branches.get(bc.branch) else { continue };
        for interval in &bc.intervals {
            let (points, lo, hi) = stretch(branch, interval.s_start_mm, interval.s_end_mm);
            if points.len() >= 2 {
                edges.push(MedialEdge {
                    class: class_of(interval.class),
                    layer,
                    points,
                    min_radius_mm: lo,
                    max_radius_mm: hi,
                });
            }
        }
    }
    edges
}
