//! Critical regions in the scene: the stretches of a path where the engagement is above
//! the limit (seed 004 §2.1), as polylines through the samples kept for drawing.

use super::scene::RegionMark;
use crate::core::analysis::report::{CriticalRegion, RegionKind};
use crate::core::analysis::samples::PathSamples;

/// Marks for an analysis' critical regions: each through the kept samples between its
/// start and end.
pub fn marks_of_regions(
    regions: &[CriticalRegion],
    samples: &PathSamples,
    path: &str,
    layer_of: impl Fn(f64) -> Option<usize>,
) -> Vec<RegionMark> {
    regions
        .iter()
        .map(|r| {
            let mut points = vec![[r.start.x, r.start.y]];
            let first = samples.s_mm.partition_point(|&s| s <= r.start.s_mm);
            let last = samples.s_mm.partition_point(|&s| s < r.end.s_mm);
            points.extend(samples.xy[first..last.max(first)].iter().copied());
            points.push([r.end.x, r.end.y]);
            RegionMark {
                kind: r.kind.as_str().to_string(),
                path: path.to_string(),
                layer: layer_of(r.at_max.z),
                points,
                max_alpha_deg: r.max_alpha_deg,
                start_line: r.start.line,
                end_line: r.end.line,
            }
        })
        .collect()
}

/// Marks for the runs of kept samples above `limit_deg`, classified as the analysis
/// classifies its regions (seed 004 §2.1).
pub fn marks_of_samples(
    samples: &PathSamples,
    limit_deg: f64,
    diameter_mm: f64,
    path: &str,
    layer_of: impl Fn(f64) -> Option<usize>,
) -> Vec<RegionMark> {
    let mut marks = Vec::new();
    let mut i = 0;
    let n = samples.len();
    let over = |k: usize| samples.alpha_deg[k].is_some_and(|a| a > limit_deg);
    while i < n {
        if !over(i) {
            i += 1;
            continue;
        }
        let start = i;
        while i < n && over(i) {
            i += 1;
        }
        let run = start..i;
        let (mut max_alpha, mut at_max) = (0.0_f64, start);
        for k in run.clone() {
            let a = samples.alpha_deg[k].unwrap_or(0.0);
            if a > max_alpha {
                max_alpha = a;
                at_max = k;
            }
        }
        let length = samples.s_mm[i - 1] - samples.s_mm[start];
        let kind = RegionKind::classify(max_alpha, length, diameter_mm);
        marks.push(RegionMark {
            kind: kind.as_str().to_string(),
            path: path.to_string(),
            layer: layer_of(samples.z[at_max]),
            points: samples.xy[run].to_vec(),
            max_alpha_deg: max_alpha,
            start_line: samples.line[start],
            end_line: samples.line[i - 1],
        });
    }
    marks
}

#[cfg(test)]
mod tests {
    use super::*;

    fn samples(alphas: &[f64]) -> PathSamples {
        let n = alphas.len();
        PathSamples {
            s_mm: (0..n).map(|i| i as f64).collect(),
            xy: (0..n).map(|i| [i as f64, 0.0]).collect(),
            z: vec![-1.0; n],
            line: (0..n).map(|i| i as u32 + 1).collect(),
            index: (0..n).collect(),
            exempt: vec![false; n],
            alpha_deg: alphas.iter().map(|&a| Some(a)).collect(),
            force_n: vec![None; n],
            feed_mm_min: vec![None; n],
        }
    }

    #[test]
    fn runs_above_the_limit_become_marks_with_their_lines_and_peak() {
        let s = samples(&[10.0, 50.0, 60.0, 20.0, 180.0, 10.0]);
        let marks = marks_of_samples(&s, 40.0, 10.0, "input", |_| Some(0));
        assert_eq!(marks.len(), 2);
        assert_eq!((marks[0].start_line, marks[0].end_line), (2, 3));
        assert!((marks[0].max_alpha_deg - 60.0).abs() < 1e-9);
        assert_eq!(marks[0].kind, "inner_corner");
        assert_eq!(marks[1].kind, "full_slotting");
    }
}
