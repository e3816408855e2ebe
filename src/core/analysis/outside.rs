//! How far a path's forces rest on the force model outside its experiments (MODEL.md §3:
//! central-composite designs with axial points at coded radius √2), and where the
//! predicted force overloads the tool.

use super::engine::SampleResult;
use super::report::PathPoint;
use crate::core::force_model::{ForceModel, DESIGN_REGION_CODED_RADIUS};
use serde::Serialize;
use std::collections::HashMap;
use utoipa::ToSchema;

/// A predicted force above this many times the tool's standard force F* is an overload
/// that a warning names by line (**assumed**: three times the force the tool's life was
/// measured at, well beyond the 2 × F* a plan's force target may be raised to).
pub const OVERLOAD_FORCE_FACTOR: f64 = 3.0;
/// Overloaded lines listed, at most.
pub const MAX_OVERLOAD_LINES: usize = 20;

/// The smallest and largest value of a quantity.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, ToSchema)]
pub struct Extent {
    pub min: f64,
    pub max: f64,
}

impl Extent {
    const EMPTY: Extent = Extent { min: f64::INFINITY, max: f64::NEG_INFINITY };

    fn add(&mut self, v: f64) {
        self.min = self.min.min(v);
        self.max = self.max.max(v);
    }

    /// The extent in physical units of a coded variable `X = (v − centre)/step`.
    fn decoded(self, centre: f64, step: f64) -> Extent {
        Extent { min: centre + step * self.min, max: centre + step * self.max }
    }

    /// `v = centre ± √2·step`: the design region's range of one variable.
    fn design(centre: f64, step: f64) -> Extent {
        Extent::default().decoded(centre, step)
    }
}

impl Default for Extent {
    /// The coded design range, ±√2.
    fn default() -> Self {
        Extent { min: -DESIGN_REGION_CODED_RADIUS, max: DESIGN_REGION_CODED_RADIUS }
    }
}

/// Where the forces rest on the force model outside its experiments: the
/// central-composite designs of seed 001 reach a coded radius of √2 (MODEL.md §3). The
/// forces of those samples, and the tool wear and cost computed from them, are
/// extrapolations.
#[derive(Debug, Clone, PartialEq, Serialize, ToSchema)]
pub struct OutsideModel {
    /// Cutting length whose force rests on the model outside the design region
    /// (|X| > √2), mm.
    pub length_mm: f64,
    /// That length over the cutting length, 0–1.
    pub share: f64,
    /// The largest coded radius |X| = √(X1² + X2²) reached (the design region ends at
    /// `design_coded_radius`).
    pub max_coded_radius: f64,
    /// √2: the axial points of the experiments' central-composite design.
    pub design_coded_radius: f64,
    /// Coded chip thickness X1 = (t_m − t0)/δt over the cutting samples.
    pub x1: Extent,
    /// Coded arc length X2 = (L − L0)/δL over the cutting samples.
    pub x2: Extent,
    /// Chip thickness over the cutting samples, µm.
    pub t_m_um: Extent,
    /// The experiments' chip thickness, t0 ± √2·δt, µm.
    pub design_t_m_um: Extent,
    /// Engagement arc length over the cutting samples, mm.
    pub arc_length_mm: Extent,
    /// The experiments' arc length, L0 ± √2·δL, mm.
    pub design_arc_length_mm: Extent,
    /// The sample furthest outside.
    pub furthest: Option<PathPoint>,
}

/// Where the predicted force exceeds 3 × the tool's standard force F* (the tool may break
/// there).
#[derive(Debug, Clone, PartialEq, Serialize, ToSchema)]
pub struct ForceOverload {
    /// F*: the model's force at its design centre, the standard cut (MODEL.md §3), N.
    pub standard_force_n: f64,
    /// 3 × F*, N.
    pub threshold_n: f64,
    /// Cutting length above the threshold, mm.
    pub length_mm: f64,
    pub max_force_n: f64,
    /// The lines above the threshold with their largest force, largest first (at most 20).
    pub lines: Vec<OverloadLine>,
    /// How many lines are above the threshold in all.
    pub line_count: usize,
}

/// One overloaded NC line.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, ToSchema)]
pub struct OverloadLine {
    pub line: u32,
    pub max_force_n: f64,
}

/// Collects [`OutsideModel`] and [`ForceOverload`] over the cutting samples.
#[derive(Debug, Clone)]
pub struct ModelDomain {
    model: ForceModel,
    cutting_mm: f64,
    outside_mm: f64,
    max_radius_squared: f64,
    x1: Extent,
    x2: Extent,
    furthest: Option<PathPoint>,
    threshold_n: f64,
    overload_mm: f64,
    overloaded: HashMap<u32, f64>,
}

impl ModelDomain {
    pub fn new(model: ForceModel) -> Self {
        ModelDomain {
            model,
            cutting_mm: 0.0,
            outside_mm: 0.0,
            max_radius_squared: 0.0,
            x1: Extent::EMPTY,
            x2: Extent::EMPTY,
            furthest: None,
            threshold_n: OVERLOAD_FORCE_FACTOR * model.design_centre_force_n(),
            overload_mm: 0.0,
            overloaded: HashMap::new(),
        }
    }

    /// Adds one cutting sample (α > 0, not a rapid or a plunge) at `at`.
    pub fn add(&mut self, r: &SampleResult, at: PathPoint) {
        let Some(coded) = r.coded else { return };
        let w = r.sample.step_mm;
        self.cutting_mm += w;
        self.x1.add(coded.x1);
        self.x2.add(coded.x2);
        if r.force_extrapolated {
            self.outside_mm += w;
        }
        if coded.radius_squared() > self.max_radius_squared {
            self.max_radius_squared = coded.radius_squared();
            self.furthest = Some(at);
        }
        if let Some(f) = r.force_n.filter(|f| *f > self.threshold_n) {
            self.overload_mm += w;
            let peak = self.overloaded.entry(r.sample.line).or_insert(f);
            *peak = peak.max(f);
        }
    }

    /// The two reports.
    pub fn finish(self) -> (OutsideModel, ForceOverload) {
        let m = self.model;
        let cut = self.cutting_mm > 0.0;
        let (x1, x2) =
            if cut { (self.x1, self.x2) } else { (Extent { min: 0.0, max: 0.0 }, Extent { min: 0.0, max: 0.0 }) };
        let outside = OutsideModel {
            length_mm: self.outside_mm,
            share: if cut { self.outside_mm / self.cutting_mm } else { 0.0 },
            max_coded_radius: self.max_radius_squared.sqrt(),
            design_coded_radius: DESIGN_REGION_CODED_RADIUS,
            x1,
            x2,
            t_m_um: x1.decoded(m.t0_um, m.dt_um),
            design_t_m_um: Extent::design(m.t0_um, m.dt_um),
            arc_length_mm: x2.decoded(m.l0_mm, m.dl_mm),
            design_arc_length_mm: Extent::design(m.l0_mm, m.dl_mm),
            furthest: self.furthest,
        };
        let mut lines: Vec<OverloadLine> =
            self.overloaded.iter().map(|(&line, &max_force_n)| OverloadLine { line, max_force_n }).collect();
        lines.sort_by(|a, b| b.max_force_n.total_cmp(&a.max_force_n).then(a.line.cmp(&b.line)));
        let line_count = lines.len();
        let max_force_n = lines.first().map_or(0.0, |l| l.max_force_n);
        lines.truncate(MAX_OVERLOAD_LINES);
        let overload = ForceOverload {
            standard_force_n: self.threshold_n / OVERLOAD_FORCE_FACTOR,
            threshold_n: self.threshold_n,
            length_mm: self.overload_mm,
            max_force_n,
            lines,
            line_count,
        };
        (outside, overload)
    }
}

impl OutsideModel {
    /// The warning that says how far outside the experiments the forces go, if they do.
    pub fn warning(&self) -> Option<String> {
        (self.length_mm > 0.0).then(|| {
            format!(
                "on {:.1} mm of the cut ({:.0} %) the force model is extrapolated beyond its experiments, up to |X| = {:.1} (the experiments reach {:.2}): chip thickness {:.1}–{:.1} µm (experiments {:.1}–{:.1}), arc length {:.2}–{:.2} mm (experiments {:.2}–{:.2}); the forces there, and the wear and cost computed from them, are extrapolations",
                self.length_mm,
                100.0 * self.share,
                self.max_coded_radius,
                self.design_coded_radius,
                self.t_m_um.min,
                self.t_m_um.max,
                self.design_t_m_um.min,
                self.design_t_m_um.max,
                self.arc_length_mm.min,
                self.arc_length_mm.max,
                self.design_arc_length_mm.min,
                self.design_arc_length_mm.max,
            )
        })
    }
}

impl ForceOverload {
    /// The warning that names the overloaded lines, if any.
    pub fn warning(&self) -> Option<String> {
        (self.line_count > 0).then(|| {
            let lines: Vec<String> = self.lines.iter().map(|l| l.line.to_string()).collect();
            let more = self.line_count - self.lines.len();
            format!(
                "the predicted force exceeds {OVERLOAD_FORCE_FACTOR} × the tool's standard force ({:.0} N) on {:.1} mm of the cut, up to {:.0} N, at line{} {}{}: the tool may break there (trochoids, `POST /v1/trochoids`, or a smaller axial depth lower the load where a feed alone cannot)",
                self.threshold_n,
                self.length_mm,
                self.max_force_n,
                if self.line_count > 1 { "s" } else { "" },
                lines.join(", "),
                if more > 0 { format!(" and {more} more") } else { String::new() }
            )
        })
    }
}
