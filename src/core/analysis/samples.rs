//! Per-sample values kept for drawing: an analysis hands every sample to a collector,
//! which keeps the sample of highest engagement in each of a fixed number of bins of
//! path distance, so a million-sample job leaves a few tens of thousands of points
//! and its peaks survive.

use crate::core::analysis::engine::SampleResult;
use serde::{Deserialize, Serialize};

/// Bins kept by default: fine enough to colour a drawing 1000 px wide (several bins
/// per pixel along any path that fits it), small enough to store with the job.
pub const DRAWING_SAMPLE_BINS: usize = 40_000;

/// Samples along a path, by path distance (the analysis' `s_mm`).
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct PathSamples {
    pub s_mm: Vec<f64>,
    /// Tool-centre position, mm.
    pub xy: Vec<[f64; 2]>,
    pub z: Vec<f64>,
    /// NC line (or move number) of the sample.
    pub line: Vec<u32>,
    /// Position of the sample in the analysis' order (0 for the first sample handed over).
    pub index: Vec<usize>,
    /// Samples a check exempts from the engagement limit (ramps, approach holes, z-cut
    /// regions cut at a reduced axial depth): drawn, but not marked as overloads.
    pub exempt: Vec<bool>,
    pub alpha_deg: Vec<Option<f64>>,
    pub force_n: Vec<Option<f64>>,
    pub feed_mm_min: Vec<Option<f64>>,
}

impl PathSamples {
    pub fn len(&self) -> usize {
        self.s_mm.len()
    }

    pub fn is_empty(&self) -> bool {
        self.s_mm.is_empty()
    }
}

/// Collects [`PathSamples`] from an analysis' samples (see [`crate::core::analysis::analyze_with`]).
#[derive(Debug, Clone)]
pub struct SampleCollector {
    seen: usize,
    bin_length_mm: f64,
    bins: Vec<Option<Kept>>,
}

#[derive(Debug, Clone, Copy)]
struct Kept {
    index: usize,
    exempt: bool,
    s_mm: f64,
    xy: [f64; 2],
    z: f64,
    line: u32,
    alpha_deg: f64,
    force_n: Option<f64>,
    feed_mm_min: Option<f64>,
    rapid: bool,
}

impl SampleCollector {
    /// `total_length_mm`: the path's length (the largest `s_mm` expected).
    pub fn new(total_length_mm: f64, bins: usize) -> SampleCollector {
        let bins = bins.max(1);
        let bin_length_mm = (total_length_mm / bins as f64).max(f64::MIN_POSITIVE);
        SampleCollector { seen: 0, bin_length_mm, bins: vec![None; bins] }
    }

    /// Keeps `r` if it engages more than what its bin holds.
    pub fn add(&mut self, r: &SampleResult) {
        self.add_with(r, false);
    }

    /// As [`SampleCollector::add`], with `exempt` telling whether the limit applies to it.
    pub fn add_with(&mut self, r: &SampleResult, exempt: bool) {
        let bin = ((r.s_mm / self.bin_length_mm).max(0.0) as usize).min(self.bins.len() - 1);
        let alpha_deg = r.contact.alpha_rad.to_degrees();
        let replace = match &self.bins[bin] {
            Some(old) => alpha_deg > old.alpha_deg,
            None => true,
        };
        if replace {
            let feed = r.sample.feed_mm_min;
            self.bins[bin] = Some(Kept {
                index: self.seen,
                exempt,
                s_mm: r.s_mm,
                xy: [r.sample.p.x, r.sample.p.y],
                z: r.sample.p.z,
                line: r.sample.line,
                alpha_deg,
                force_n: r.force_n,
                feed_mm_min: (feed > 0.0).then_some(feed),
                rapid: r.sample.rapid,
            });
        }
        self.seen += 1;
    }

    pub fn finish(self) -> PathSamples {
        let n = self.bins.iter().flatten().count();
        let mut out = PathSamples {
            s_mm: Vec::with_capacity(n),
            xy: Vec::with_capacity(n),
            z: Vec::with_capacity(n),
            line: Vec::with_capacity(n),
            index: Vec::with_capacity(n),
            exempt: Vec::with_capacity(n),
            alpha_deg: Vec::with_capacity(n),
            force_n: Vec::with_capacity(n),
            feed_mm_min: Vec::with_capacity(n),
        };
        for k in self.bins.into_iter().flatten() {
            out.s_mm.push(k.s_mm);
            out.xy.push(k.xy);
            out.z.push(k.z);
            out.line.push(k.line);
            out.index.push(k.index);
            out.exempt.push(k.exempt);
            out.alpha_deg.push((!k.rapid).then_some(k.alpha_deg));
            out.force_n.push(if k.rapid { None } else { k.force_n });
            out.feed_mm_min.push(if k.rapid { None } else { k.feed_mm_min });
        }
        out
    }
}
