//! The answer of an `analysis` job, as the API documents it.

use super::setup::PathSetup;
use super::setup::{NamedRef, ToolRef};
use crate::core::analysis::outside::{Extent, ForceOverload, OutsideModel};
use crate::core::analysis::report::{CriticalRegion, HistogramBin, PathPoint, RegionKind, Series, Stats};
use crate::core::analysis::{Analysis, SliceSummary, Summary};
use serde::Serialize;
use utoipa::ToSchema;

/// Length-weighted statistics over the cutting samples.
#[derive(Debug, Clone, Copy, Serialize, ToSchema)]
pub struct StatsDto {
    pub max: f64,
    pub mean: f64,
    pub std_dev: f64,
}

impl From<Stats> for StatsDto {
    fn from(s: Stats) -> Self {
        StatsDto { max: s.max, mean: s.mean, std_dev: s.std_dev }
    }
}

/// Cut length with α in [from_deg, to_deg).
#[derive(Debug, Clone, Copy, Serialize, ToSchema)]
pub struct HistogramBinDto {
    pub from_deg: f64,
    pub to_deg: f64,
    pub length_mm: f64,
}

/// One z slice of the simulated stock. The slices follow the z levels the program cuts
/// (at most 16; where levels are merged, the layers the program cuts flat stay exact).
#[derive(Debug, Clone, Copy, Serialize, ToSchema)]
pub struct SliceDto {
    pub z_top: f64,
    pub z_bottom: f64,
    pub removed_area_mm2: f64,
}

/// The smallest and largest value of a quantity.
#[derive(Debug, Clone, Copy, Serialize, ToSchema)]
pub struct ExtentDto {
    pub min: f64,
    pub max: f64,
}

impl From<Extent> for ExtentDto {
    fn from(e: Extent) -> Self {
        ExtentDto { min: e.min, max: e.max }
    }
}

/// Where the forces rest on the force model outside its experiments: the
/// central-composite designs of seed 001 reach a coded radius of √2 (MODEL.md §3). The
/// forces of those samples, and the tool wear and cost computed from them, are
/// extrapolations.
#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct OutsideModelDto {
    /// Cutting length outside the design region (|X| > √2), mm.
    pub length_mm: f64,
    /// That length over the cutting length, 0–1.
    pub share: f64,
    /// Largest coded radius |X| = √(X1² + X2²) reached.
    pub max_coded_radius: f64,
    /// √2, where the experiments end.
    pub design_coded_radius: f64,
    /// Coded chip thickness X1 = (t_m − t0)/δt over the cutting samples.
    pub x1: ExtentDto,
    /// Coded arc length X2 = (L − L0)/δL over the cutting samples.
    pub x2: ExtentDto,
    /// Chip thickness over the cutting samples, µm.
    pub t_m_um: ExtentDto,
    /// The experiments' chip thickness, t0 ± √2·δt, µm.
    pub design_t_m_um: ExtentDto,
    /// Engagement arc length over the cutting samples, mm.
    pub arc_length_mm: ExtentDto,
    /// The experiments' arc length, L0 ± √2·δL, mm.
    pub design_arc_length_mm: ExtentDto,
    /// The sample furthest outside.
    pub furthest: Option<PathPointDto>,
}

impl From<OutsideModel> for OutsideModelDto {
    fn from(o: OutsideModel) -> Self {
        OutsideModelDto {
            length_mm: o.length_mm,
            share: o.share,
            max_coded_radius: o.max_coded_radius,
            design_coded_radius: o.design_coded_radius,
            x1: o.x1.into(),
            x2: o.x2.into(),
            t_m_um: o.t_m_um.into(),
            design_t_m_um: o.design_t_m_um.into(),
            arc_length_mm: o.arc_length_mm.into(),
            design_arc_length_mm: o.design_arc_length_mm.into(),
            furthest: o.furthest.map(Into::into),
        }
    }
}

/// An NC line whose predicted force exceeds the overload threshold.
#[derive(Debug, Clone, Copy, Serialize, ToSchema)]
pub struct OverloadLineDto {
    pub line: u32,
    pub max_force_n: f64,
}

/// Where the predicted force exceeds 3 × the tool's standard force F* (the tool may
/// break there).
#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct ForceOverloadDto {
    /// F*: the force model's force at its design centre, the standard cut, N.
    pub standard_force_n: f64,
    /// 3 × F*, N.
    pub threshold_n: f64,
    /// Cutting length above the threshold, mm.
    pub length_mm: f64,
    pub max_force_n: f64,
    /// The lines above it, largest force first (at most 20).
    pub lines: Vec<OverloadLineDto>,
    /// How many lines are above it in all.
    pub line_count: usize,
}

impl From<ForceOverload> for ForceOverloadDto {
    fn from(o: ForceOverload) -> Self {
        ForceOverloadDto {
            standard_force_n: o.standard_force_n,
            threshold_n: o.threshold_n,
            length_mm: o.length_mm,
            max_force_n: o.max_force_n,
            lines: o.lines.iter().map(|l| OverloadLineDto { line: l.line, max_force_n: l.max_force_n }).collect(),
            line_count: o.line_count,
        }
    }
}

/// The figures of the whole path.
#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct SummaryDto {
    pub moves: usize,
    pub samples: usize,
    pub sample_spacing_mm: f64,
    pub cell_mm: f64,
    pub raster_memory_bytes: usize,
    pub slices: Vec<SliceDto>,
    /// Feed moves in material, mm.
    pub cutting_length_mm: f64,
    /// Feed moves in the air, mm.
    pub air_cut_length_mm: f64,
    pub rapid_length_mm: f64,
    /// Feed moves at their programmed feeds plus rapids at the machine's rapid rate, min.
    pub time_at_programmed_feeds_min: f64,
    pub removed_volume_mm3: f64,
    /// Engagement angle α, deg.
    pub alpha_deg: StatsDto,
    /// Maximum undeformed chip thickness at the programmed feed, µm.
    pub t_m_um: StatsDto,
    /// Predicted XY force, N (null without a force model).
    pub force_n: Option<StatsDto>,
    /// `true` when some of these forces rest on the force model outside its experiments
    /// (see `outside_model`): they are extrapolations.
    pub force_extrapolated: bool,
    /// Where the forces leave the force model's experimental domain, and how far (null
    /// without a force model).
    pub outside_model: Option<OutsideModelDto>,
    /// Where the predicted force exceeds 3 × the tool's standard force, by line (null
    /// without a force model).
    pub force_overload: Option<ForceOverloadDto>,
    /// Cut length per 10° of engagement.
    pub alpha_histogram: Vec<HistogramBinDto>,
    pub alpha_limit_deg: f64,
    pub critical_regions: usize,
    pub critical_length_mm: f64,
    pub warnings: Vec<String>,
}

/// A point of the path.
#[derive(Debug, Clone, Copy, Serialize, ToSchema)]
pub struct PathPointDto {
    pub s_mm: f64,
    /// NC line number.
    pub line: u32,
    pub x: f64,
    pub y: f64,
    pub z: f64,
}

impl From<PathPoint> for PathPointDto {
    fn from(p: PathPoint) -> Self {
        PathPointDto { s_mm: p.s_mm, line: p.line, x: p.x, y: p.y, z: p.z }
    }
}

/// A run of samples with α above the limit.
#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct CriticalRegionDto {
    /// full_slotting, inner_corner or narrow_region.
    pub kind: String,
    pub start: PathPointDto,
    pub end: PathPointDto,
    pub length_mm: f64,
    pub max_alpha_deg: f64,
    pub at_max: PathPointDto,
    pub max_force_n: Option<f64>,
}

impl From<CriticalRegion> for CriticalRegionDto {
    fn from(r: CriticalRegion) -> Self {
        let kind = match r.kind {
            RegionKind::FullSlotting => "full_slotting",
            RegionKind::InnerCorner => "inner_corner",
            RegionKind::NarrowRegion => "narrow_region",
        };
        CriticalRegionDto {
            kind: kind.to_string(),
            start: r.start.into(),
            end: r.end.into(),
            length_mm: r.length_mm,
            max_alpha_deg: r.max_alpha_deg,
            at_max: r.at_max.into(),
            max_force_n: r.max_force_n,
        }
    }
}

/// Per-sample values downsampled by path distance (each point is the peak-α sample of
/// its stretch), with the NC line of every point.
#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct SeriesDto {
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
    /// Centre of curvature `[x, y]` of the tool-centre path (null when straight or at a
    /// sharp corner).
    #[schema(value_type = Vec<Option<Vec<f64>>>)]
    pub curvature_center: Vec<Option<(f64, f64)>>,
    /// Turn direction: +1 left (counter-clockwise), −1 right, 0 straight.
    pub turn: Vec<i8>,
}

impl From<Series> for SeriesDto {
    fn from(s: Series) -> Self {
        SeriesDto {
            s_mm: s.s_mm,
            line: s.line,
            x: s.x,
            y: s.y,
            z: s.z,
            alpha_deg: s.alpha_deg,
            entry_deg: s.entry_deg,
            exit_deg: s.exit_deg,
            arc_length_mm: s.arc_length_mm,
            t_m_um: s.t_m_um,
            force_n: s.force_n,
            ad_mm: s.ad_mm,
            feed_mm_min: s.feed_mm_min,
            curvature_radius_mm: s.curvature_radius_mm,
            curvature_center: s.curvature_center,
            turn: s.turn,
        }
    }
}

/// The answer of an `analysis` job.
#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct AnalysisResult {
    pub material: NamedRef,
    pub tool: ToolRef,
    pub machine: NamedRef,
    /// The force model used (null: none, forces are not predicted).
    pub force_model_id: Option<i64>,
    pub summary: SummaryDto,
    pub critical_regions: Vec<CriticalRegionDto>,
    pub series: Option<SeriesDto>,
}

pub fn summary(moves: usize, s: Summary, regions: usize) -> SummaryDto {
    SummaryDto {
        moves,
        samples: s.samples,
        sample_spacing_mm: s.sample_spacing_mm,
        cell_mm: s.cell_mm,
        raster_memory_bytes: s.raster_memory_bytes,
        slices: s
            .slices
            .iter()
            .map(|&SliceSummary { z_top, z_bottom, removed_area_mm2 }| SliceDto { z_top, z_bottom, removed_area_mm2 })
            .collect(),
        cutting_length_mm: s.cutting_length_mm,
        air_cut_length_mm: s.air_cut_length_mm,
        rapid_length_mm: s.rapid_length_mm,
        time_at_programmed_feeds_min: s.time_at_programmed_feeds_min,
        removed_volume_mm3: s.removed_volume_mm3,
        alpha_deg: s.alpha_deg.into(),
        t_m_um: s.t_m_um.into(),
        force_n: s.force_n.map(Into::into),
        force_extrapolated: s.outside_model.as_ref().is_some_and(|o| o.length_mm > 0.0),
        outside_model: s.outside_model.map(Into::into),
        force_overload: s.force_overload.map(Into::into),
        alpha_histogram: s
            .alpha_histogram
            .iter()
            .map(|&HistogramBin { from_deg, to_deg, length_mm }| HistogramBinDto { from_deg, to_deg, length_mm })
            .collect(),
        alpha_limit_deg: s.alpha_limit_deg,
        critical_regions: regions,
        critical_length_mm: s.critical_length_mm,
        warnings: s.warnings,
    }
}

impl AnalysisResult {
    pub fn new(prepared: PathSetup, moves: usize, a: Analysis) -> AnalysisResult {
        let regions = a.critical_regions.len();
        AnalysisResult {
            material: prepared.material,
            tool: prepared.tool,
            machine: prepared.machine,
            force_model_id: prepared.force_model.map(|f| f.id),
            summary: summary(moves, a.summary, regions),
            critical_regions: a.critical_regions.into_iter().map(Into::into).collect(),
            series: a.series.map(Into::into),
        }
    }
}
