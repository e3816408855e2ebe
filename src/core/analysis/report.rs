//! What an analysis reports: the summary, the critical regions (MODEL.md §6: runs of
//! samples with α above the limit) and, on request, per-sample series downsampled by
//! path distance (the peak of every bin is kept).

use super::engine::SampleResult;
use super::outside::{ForceOverload, ModelDomain, OutsideModel};
use crate::core::force_model::ForceModel;
use serde::Serialize;
use utoipa::ToSchema;

/// Width of one bin of the engagement histogram, deg.
pub const HISTOGRAM_BIN_DEG: f64 = 10.0;
/// Largest engagement angle, deg.
const MAX_ALPHA_DEG: f64 = 180.0;
/// A critical region reaching this engagement is full slotting, deg.
pub const FULL_SLOT_DEG: f64 = 175.0;
/// A critical region no longer than this many tool diameters is an inner corner;
/// longer ones are narrow regions.
pub const CORNER_LENGTH_DIAMETERS: f64 = 2.0;

/// A point of the path.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, ToSchema)]
pub struct PathPoint {
    /// Path distance from the start, mm.
    pub s_mm: f64,
    /// NC line number.
    pub line: u32,
    pub x: f64,
    pub y: f64,
    pub z: f64,
}

/// What kind of overload a critical region is: full slotting (α reaches 175°), an inner
/// corner (at most two diameters long) or a narrow region (longer).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, ToSchema)]
#[serde(rename_all = "snake_case")]
pub enum RegionKind {
    FullSlotting,
    InnerCorner,
    NarrowRegion,
}

impl RegionKind {
    /// The kind of a run of samples above the limit that peaks at `max_alpha_deg` over
    /// `length_mm` of path, for a tool of `diameter_mm`.
    pub fn classify(max_alpha_deg: f64, length_mm: f64, diameter_mm: f64) -> RegionKind {
        if max_alpha_deg >= FULL_SLOT_DEG {
            RegionKind::FullSlotting
        } else if length_mm <= CORNER_LENGTH_DIAMETERS * diameter_mm {
            RegionKind::InnerCorner
        } else {
            RegionKind::NarrowRegion
        }
    }

    /// The name used in JSON.
    pub fn as_str(self) -> &'static str {
        match self {
            RegionKind::FullSlotting => "full_slotting",
            RegionKind::InnerCorner => "inner_corner",
            RegionKind::NarrowRegion => "narrow_region",
        }
    }
}

/// A run of samples with α above the limit.
#[derive(Debug, Clone, PartialEq, Serialize, ToSchema)]
pub struct CriticalRegion {
    pub kind: RegionKind,
    pub start: PathPoint,
    pub end: PathPoint,
    pub length_mm: f64,
    pub max_alpha_deg: f64,
    /// Where α is largest.
    pub at_max: PathPoint,
    pub max_force_n: Option<f64>,
}

/// One bin of the engagement histogram: path length cut with α in [from, to).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, ToSchema)]
pub struct HistogramBin {
    pub from_deg: f64,
    pub to_deg: f64,
    pub length_mm: f64,
}

/// Length-weighted statistics of one quantity over the cutting samples.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, ToSchema)]
pub struct Stats {
    pub max: f64,
    pub mean: f64,
    pub std_dev: f64,
}

/// Accumulates length-weighted [`Stats`].
#[derive(Debug, Default, Clone, Copy)]
pub struct Accumulator {
    weight: f64,
    sum: f64,
    sum_sq: f64,
    max: f64,
}

impl Accumulator {
    pub fn add(&mut self, value: f64, weight: f64) {
        self.weight += weight;
        self.sum += value * weight;
        self.sum_sq += value * value * weight;
        self.max = self.max.max(value);
    }

    pub fn stats(&self) -> Stats {
        if self.weight <= 0.0 {
            return Stats::default();
        }
        let mean = self.sum / self.weight;
        Stats { max: self.max, mean, std_dev: (self.sum_sq / self.weight - mean * mean).max(0.0).sqrt() }
    }
}

/// Per-sample values downsampled by path distance (each point is the peak-α sample of
/// its stretch), with the NC line of every point.
#[derive(Debug, Clone, Default, PartialEq, Serialize, ToSchema)]
pub struct Series {
    pub s_mm: Vec<f64>,
    pub line: Vec<u32>,
    pub x: Vec<f64>,
    pub y: Vec<f64>,
    pub z: Vec<f64>,
    pub alpha_deg: Vec<f64>,
    pub entry_deg: Vec<f64>,
    pub exit_deg: Vec<f64>,
    pub arc_length_mm: Vec<f64>,
    pub t_m_um: Vec<f64>,
    pub force_n: Vec<Option<f64>>,
    pub ad_mm: Vec<f64>,
    pub feed_mm_min: Vec<f64>,
    pub curvature_radius_mm: Vec<Option<f64>>,
    /// Centre of curvature `[x, y]` of the tool-centre path (null on straight stretches
    /// and at sharp corners).
    #[schema(value_type = Vec<Option<Vec<f64>>>)]
    pub curvature_center: Vec<Option<(f64, f64)>>,
    /// Turn direction: +1 left (counter-clockwise), −1 right, 0 straight.
    pub turn: Vec<i8>,
}

/// Collects the sample results into the report.
pub struct ReportBuilder {
    alpha_limit_deg: f64,
    diameter_mm: f64,
    alpha: Accumulator,
    force: Accumulator,
    t_m: Accumulator,
    histogram: Vec<f64>,
    pub cutting_length_mm: f64,
    pub air_cut_length_mm: f64,
    pub rapid_in_material: Vec<u32>,
    pub plunge_samples: usize,
    pub samples: usize,
    domain: Option<ModelDomain>,
    regions: Vec<CriticalRegion>,
    open: Option<CriticalRegion>,
    bins: Vec<Option<SampleResult>>,
    bin_length_mm: f64,
}

fn point(r: &SampleResult) -> PathPoint {
    PathPoint { s_mm: r.s_mm, line: r.sample.line, x: r.sample.p.x, y: r.sample.p.y, z: r.sample.p.z }
}

impl ReportBuilder {
    /// `series_points`: how many points of series to keep over `total_length_mm`; the
    /// force model's domain is followed when one is given.
    pub fn new(
        alpha_limit_deg: f64,
        diameter_mm: f64,
        series_points: usize,
        total_length_mm: f64,
        force_model: Option<ForceModel>,
    ) -> Self {
        let bins = (MAX_ALPHA_DEG / HISTOGRAM_BIN_DEG).ceil() as usize;
        ReportBuilder {
            alpha_limit_deg,
            diameter_mm,
            alpha: Accumulator::default(),
            force: Accumulator::default(),
            t_m: Accumulator::default(),
            histogram: vec![0.0; bins],
            cutting_length_mm: 0.0,
            air_cut_length_mm: 0.0,
            rapid_in_material: Vec::new(),
            plunge_samples: 0,
            samples: 0,
            domain: force_model.map(ModelDomain::new),
            regions: Vec::new(),
            open: None,
            bins: vec![None; series_points],
            bin_length_mm: if series_points > 0 {
                (total_length_mm / series_points as f64).max(f64::MIN_POSITIVE)
            } else {
                0.0
            },
        }
    }

    pub fn add(&mut self, r: &SampleResult) {
        self.samples += 1;
        let alpha_deg = r.contact.alpha_rad.to_degrees();
        if !self.bins.is_empty() {
            let bin = ((r.s_mm / self.bin_length_mm) as usize).min(self.bins.len() - 1);
            let keep = match &self.bins[bin] {
                Some(old) => alpha_deg > old.contact.alpha_rad.to_degrees(),
                None => true,
            };
            if keep {
                self.bins[bin] = Some(*r);
            }
        }
        if r.sample.rapid {
            if alpha_deg > 0.0 && self.rapid_in_material.last() != Some(&r.sample.line) {
                self.rapid_in_material.push(r.sample.line);
            }
            self.close_region();
            return;
        }
        if r.plunge {
            self.plunge_samples += 1;
            return;
        }
        let w = r.sample.step_mm;
        if let Some(domain) = self.domain.as_mut().filter(|_| alpha_deg > 0.0) {
            domain.add(r, point(r));
        }
        if alpha_deg > 0.0 {
            self.cutting_length_mm += w;
            self.alpha.add(alpha_deg, w);
            self.t_m.add(r.t_m_um, w);
            if let Some(f) = r.force_n {
                self.force.add(f, w);
            }
            let bin = ((alpha_deg / HISTOGRAM_BIN_DEG) as usize).min(self.histogram.len() - 1);
            self.histogram[bin] += w;
        } else {
            self.air_cut_length_mm += w;
        }
        if alpha_deg > self.alpha_limit_deg {
            let p = point(r);
            let region = self.open.get_or_insert(CriticalRegion {
                kind: RegionKind::NarrowRegion,
                start: p,
                end: p,
                length_mm: 0.0,
                max_alpha_deg: alpha_deg,
                at_max: p,
                max_force_n: r.force_n,
            });
            region.end = p;
            region.length_mm = p.s_mm - region.start.s_mm;
            if alpha_deg > region.max_alpha_deg {
                region.max_alpha_deg = alpha_deg;
                region.at_max = p;
            }
            if let Some(f) = r.force_n {
                region.max_force_n = Some(region.max_force_n.map_or(f, |m| m.max(f)));
            }
        } else {
            self.close_region();
        }
    }

    fn close_region(&mut self) {
        if let Some(mut region) = self.open.take() {
            region.kind = RegionKind::classify(region.max_alpha_deg, region.length_mm, self.diameter_mm);
            self.regions.push(region);
        }
    }

    /// The regions, statistics, histogram and series.
    pub fn finish(mut self) -> FinishedReport {
        self.close_region();
        let histogram = self
            .histogram
            .iter()
            .enumerate()
            .map(|(i, &length_mm)| HistogramBin {
                from_deg: i as f64 * HISTOGRAM_BIN_DEG,
                to_deg: ((i + 1) as f64 * HISTOGRAM_BIN_DEG).min(MAX_ALPHA_DEG),
                length_mm,
            })
            .collect();
        let mut series = Series::default();
        for r in self.bins.iter().flatten() {
            series.s_mm.push(r.s_mm);
            series.line.push(r.sample.line);
            series.x.push(r.sample.p.x);
            series.y.push(r.sample.p.y);
            series.z.push(r.sample.p.z);
            series.alpha_deg.push(r.contact.alpha_rad.to_degrees());
            series.entry_deg.push(r.contact.entry_rad.to_degrees());
            series.exit_deg.push(r.contact.exit_rad.to_degrees());
            series.arc_length_mm.push(r.arc_length_mm);
            series.t_m_um.push(r.t_m_um);
            series.force_n.push(r.force_n);
            series.ad_mm.push(r.ad_mm);
            series.feed_mm_min.push(r.sample.feed_mm_min);
            let radius = r.sample.curvature.radius_mm();
            series.curvature_radius_mm.push(radius.is_finite().then_some(radius));
            let k = r.sample.curvature;
            series.curvature_center.push(k.center((r.sample.p.x, r.sample.p.y), r.sample.heading));
            series.turn.push(k.turn());
        }
        FinishedReport {
            alpha_deg: self.alpha.stats(),
            force_n: (self.force.weight > 0.0).then(|| self.force.stats()),
            t_m_um: self.t_m.stats(),
            histogram,
            regions: self.regions,
            series,
            cutting_length_mm: self.cutting_length_mm,
            air_cut_length_mm: self.air_cut_length_mm,
            rapid_in_material: self.rapid_in_material,
            plunge_samples: self.plunge_samples,
            samples: self.samples,
            model_domain: self.domain.map(ModelDomain::finish),
        }
    }
}

/// The collected report.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FinishedReport {
    pub alpha_deg: Stats,
    pub force_n: Option<Stats>,
    pub t_m_um: Stats,
    pub histogram: Vec<HistogramBin>,
    pub regions: Vec<CriticalRegion>,
    pub series: Series,
    pub cutting_length_mm: f64,
    pub air_cut_length_mm: f64,
    pub rapid_in_material: Vec<u32>,
    pub plunge_samples: usize,
    pub samples: usize,
    /// Where the forces leave the force model's experiments, and where they overload the
    /// tool (with a force model).
    pub model_domain: Option<(OutsideModel, ForceOverload)>,
}
