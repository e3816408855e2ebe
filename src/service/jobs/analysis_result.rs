//! The answer of an `analysis` job, as the API documents it.

use super::analysis::AnalysisPrepared;
use super::conditions::{NamedRef, ToolRef};
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
    pub fn new(prepared: AnalysisPrepared, moves: usize, a: Analysis) -> AnalysisResult {
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
