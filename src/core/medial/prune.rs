//! Pruning the spurious twigs of a sampled medial axis, and joining branches at points of
//! degree 2.
//!
//! Rule (erosion, as in the λ-medial axis; seed 004 §2.1 needs the true branches only): a
//! terminal branch from a junction `J` to an end `E`, of length `L`, is *insignificant* when
//!
//! ```text
//!     R(E) + L ≤ R(J) + δ
//! ```
//!
//! i.e. when the end's inscribed disc lies (up to `δ`) within the junction's: removing the
//! branch removes no region the junction's disc does not already cover. Along the true axis R
//! changes by at most the distance travelled, so `R(E) + L − R(J) ≥ 0`, and a twig created by
//! the sampling has `R(E) + L − R(J)` of the order of the sampling error. A branch into a
//! convex corner of opening angle `θ` gains `L·(1 − sin(θ/2))` (0.29·L at 90°) and stays
//! unless it is shorter than `δ / (1 − sin(θ/2))`.
//!
//! Each round removes, at every junction, the least significant of its insignificant terminal
//! branches, then joins the branches meeting at points left with degree 2; rounds repeat until
//! nothing changes. A branch whose both ends are free (no junction left) is insignificant when
//! either end satisfies the rule against the other; it collapses to its point of largest R.

use super::graph::{path_length_mm, Skeleton};
use crate::core::geometry::Point;
use std::collections::BTreeMap;

/// Removes the insignificant terminal branches of `skeleton` and joins branches at points of
/// degree 2, until stable. `clearance_mm` gives R per point, `delta_mm` is `δ`.
pub(crate) fn prune(skeleton: &mut Skeleton, points: &[Point], clearance_mm: &[f64], delta_mm: f64) {
    join_at_degree_two(skeleton);
    loop {
        let degree = degrees(skeleton);
        let mut changed = false;
        let mut weakest: BTreeMap<usize, (f64, usize)> = BTreeMap::new();
        let mut collapsed = Vec::new();
        for (b, path) in skeleton.branches.iter().enumerate() {
            let Some(path) = path else { continue };
            let (p, q) = (path[0], path[path.len() - 1]);
            if p == q {
                continue;
            }
            let length = path_length_mm(points, path);
            let gain = |end: usize, other: usize| clearance_mm[end] + length - clearance_mm[other];
            match (degree[&p], degree[&q]) {
                (1, 1) if gain(p, q).min(gain(q, p)) <= delta_mm => collapsed.push(b),
                (1, d) | (d, 1) if d >= 3 => {
                    let (end, junction) = if degree[&p] == 1 { (p, q) } else { (q, p) };
                    let s = gain(end, junction);
                    if s <= delta_mm && weakest.get(&junction).is_none_or(|&(best, _)| s < best) {
                        weakest.insert(junction, (s, b));
                    }
                }
                _ => {}
            }
        }
        for b in collapsed {
            if let Some(path) = skeleton.branches[b].take() {
                let top = path.iter().copied().max_by(|&i, &j| clearance_mm[i].total_cmp(&clearance_mm[j]));
                skeleton.isolated.extend(top);
                changed = true;
            }
        }
        for (_, (_, b)) in weakest {
            skeleton.branches[b] = None;
            changed = true;
        }
        if !changed {
            break;
        }
        join_at_degree_two(skeleton);
    }
}

/// Number of branch ends at each node (a closed branch counts twice at its anchor).
fn degrees(skeleton: &Skeleton) -> BTreeMap<usize, usize> {
    let mut degree = BTreeMap::new();
    for path in skeleton.branches.iter().flatten() {
        *degree.entry(path[0]).or_insert(0) += 1;
        *degree.entry(path[path.len() - 1]).or_insert(0) += 1;
    }
    degree
}

/// Joins the two branches meeting at every node of degree 2 (a closed branch alone at its
/// anchor stays as it is).
pub(crate) fn join_at_degree_two(skeleton: &mut Skeleton) {
    let mut incident: BTreeMap<usize, Vec<usize>> = BTreeMap::new();
    for (b, path) in skeleton.branches.iter().enumerate() {
        if let Some(path) = path {
            incident.entry(path[0]).or_default().push(b);
            incident.entry(path[path.len() - 1]).or_default().push(b);
        }
    }
    let nodes: Vec<usize> = incident.keys().copied().collect();
    for node in nodes {
        let Some(list) = incident.get(&node) else { continue };
        if list.len() != 2 || list[0] == list[1] {
            continue;
        }
        let (keep, gone) = (list[0], list[1]);
        let (Some(mut a), Some(mut b)) = (skeleton.branches[keep].take(), skeleton.branches[gone].take()) else {
            continue;
        };
        if a[a.len() - 1] != node {
            a.reverse();
        }
        if b[0] != node {
            b.reverse();
        }
        let far = b[b.len() - 1];
        a.extend_from_slice(&b[1..]);
        skeleton.branches[keep] = Some(a);
        incident.remove(&node);
        if let Some(far_list) = incident.get_mut(&far) {
            for entry in far_list.iter_mut().filter(|e| **e == gone) {
                *entry = keep;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A junction at the origin (R = 10) with a long arm to (−50, 0) and two short arms: a twig
    /// to (0, 1) whose R barely drops (insignificant) and a corner branch to (7, 7) whose R
    /// drops like a 90° corner's (R = 10 − 7·√2·sin 45° = 3).
    fn star() -> (Skeleton, Vec<Point>, Vec<f64>) {
        let points = vec![Point::new(0.0, 0.0), Point::new(-50.0, 0.0), Point::new(0.0, 1.0), Point::new(7.0, 7.0)];
        let clearance = vec![10.0, 10.0, 9.5, 3.0];
        let skeleton =
            Skeleton { branches: vec![Some(vec![0, 1]), Some(vec![0, 2]), Some(vec![0, 3])], isolated: vec![] };
        (skeleton, points, clearance)
    }

    #[test]
    fn a_twig_whose_disc_lies_within_the_junctions_disc_is_pruned_and_a_corner_branch_stays() {
        let (mut skeleton, points, clearance) = star();
        prune(&mut skeleton, &points, &clearance, 1.0);
        let mut branches: Vec<Vec<usize>> = skeleton.branches.into_iter().flatten().collect();
        branches.sort();
        // The twig went, the junction then had degree 2: the two remaining arms are one branch.
        assert_eq!(branches, vec![vec![1, 0, 3]]);
    }

    #[test]
    fn a_branch_without_a_junction_whose_end_disc_lies_within_the_others_collapses_to_a_point() {
        let points = vec![Point::new(0.0, 0.0), Point::new(0.5, 0.0)];
        let clearance = vec![20.0, 19.6];
        let mut skeleton = Skeleton { branches: vec![Some(vec![0, 1])], isolated: vec![] };
        prune(&mut skeleton, &points, &clearance, 0.5);
        assert!(skeleton.branches.iter().all(Option::is_none));
        assert_eq!(skeleton.isolated, vec![0]);
    }

    #[test]
    fn a_cycle_with_a_twig_becomes_one_closed_branch() {
        let points = vec![Point::new(0.0, 0.0), Point::new(10.0, 0.0), Point::new(5.0, 5.0), Point::new(0.0, 0.2)];
        let clearance = vec![5.0, 5.0, 5.0, 4.9];
        let mut skeleton = Skeleton {
            branches: vec![Some(vec![0, 1]), Some(vec![1, 2]), Some(vec![2, 0]), Some(vec![0, 3])],
            isolated: vec![],
        };
        prune(&mut skeleton, &points, &clearance, 0.5);
        let branches: Vec<Vec<usize>> = skeleton.branches.into_iter().flatten().collect();
        assert_eq!(branches.len(), 1);
        assert_eq!(branches[0].first(), branches[0].last());
        assert_eq!(branches[0].len(), 4);
    }
}
