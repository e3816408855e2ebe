//! Path analysis (seed 002 subsystem (b), seed 004 §2.1; MODEL.md §6): simulate the
//! material removal of a layer along a tool path and report, per sample, the engagement,
//! chip thickness and force, and the critical regions where the tool is overloaded.

pub mod arcs;
pub mod budget;
pub mod chunk;
pub mod continued;
pub mod engages;
pub mod engine;
pub mod feed_cap;
pub mod geometry;
pub mod handoff;
pub mod height_map;
pub mod kept;
pub mod levels;
pub mod lines;
pub mod outside;
pub mod painted;
pub mod probe;
pub mod profile;
pub mod recent;
pub mod region;
pub mod report;
pub mod rest;
pub mod same_below;
pub mod samples;
pub mod sampling;
pub mod scan_memory;
pub mod slice_probes;
pub mod slice_radii;
pub mod slices;
pub mod spare_buffer;
pub mod split;
pub mod stack;
#[cfg(test)]
pub mod test_paths;

use crate::core::error::require_positive;
use crate::core::force_model::ForceModel;
use crate::core::progress::{Progress, Stage};
use crate::core::stock::{Raster, Rect};
use crate::core::tool::{EndMill, ToolType};
use crate::core::toolpath::{Motion, Toolpath};
use crate::core::CoreError;
pub use budget::{resolution, DEFAULT_STOCK_MEMORY_BYTES};
use engine::{simulate, Cutter};
use kept::KeptStock;
use outside::{ForceOverload, OutsideModel};
pub use region::StockRegion;
use report::{CriticalRegion, FinishedReport, HistogramBin, ReportBuilder, Series, Stats};
use rest::RestMaterial;
use serde::Serialize;
pub use stack::Stack;

/// Engagement above this is critical by default (seed 002 §2.4, seed 004 §2.1), deg.
pub const DEFAULT_ALPHA_LIMIT_DEG: f64 = 40.0;
/// Largest engagement limit a request may set, deg (180° is full slotting: a limit there
/// would mark nothing).
pub const MAX_ALPHA_LIMIT_DEG: f64 = 179.9;
/// Samples are never further apart than this by default, mm (issue: 0.05 mm or D/100).
pub const DEFAULT_MAX_SPACING_MM: f64 = 0.05;
/// Default spacing as a fraction of the tool diameter.
pub const SPACING_PER_DIAMETER: f64 = 0.01;
/// Default raster cell as a fraction of the tool diameter (0.1 mm for 10 mm): the
/// distance raster places boundaries curved like the tool to a small fraction of a cell.
pub const CELL_PER_DIAMETER: f64 = 1.0 / 100.0;
/// Raster cell bounds, mm.
pub const MIN_CELL_MM: f64 = 0.002;
pub const MAX_CELL_MM: f64 = 0.5;
/// Painting this many raster cells takes about as long as simulating one sample: the
/// weight of painting the stock in a job's progress. (BENCHMARKS.md: tiger.nc's stock,
/// 8.4 M cells, paints in about 50 ms, and its samples take about 0.8 µs each; the
/// synthetic pocket's, 0.4 µs.)
pub const PAINTED_CELLS_PER_SAMPLE: f64 = 100.0;
/// Most series points a request may ask for.
pub const MAX_SERIES_POINTS: usize = 100_000;
/// Most samples one analysis takes (5 km of path at 0.05 mm).
pub const MAX_SAMPLES: f64 = 100_000_000.0;
/// Coordinates beyond ±100 m are refused, mm.
pub const MAX_COORDINATE_MM: f64 = 100_000.0;

/// Rapid rate used for the time estimate when none is given, mm/min (**assumed**: the
/// papers do not give the OKK VM4-II's rapid rate).
pub const DEFAULT_RAPID_MM_MIN: f64 = 20_000.0;

/// What to analyse and how finely.
#[derive(Debug, Clone)]
pub struct AnalysisSpec {
    pub tool: EndMill,
    /// Where the material is at the start: the union of these.
    pub stock: Vec<StockRegion>,
    /// Regions already open (a pre-drilled hole, a previous layer).
    pub open: Vec<StockRegion>,
    /// The layer's z range, mm.
    pub z_top: f64,
    pub z_bottom: f64,
    pub force_model: Option<ForceModel>,
    /// Used where the program has no S word.
    pub default_spindle_rpm: Option<f64>,
    /// The machine's rapid rate, mm/min.
    pub rapid_mm_min: f64,
    pub sample_spacing_mm: Option<f64>,
    pub cell_mm: Option<f64>,
    pub alpha_limit_deg: f64,
    /// 0: no series.
    pub series_points: usize,
    /// Memory the stock's slices may take, bytes (see [`budget`]).
    pub stock_memory_bytes: usize,
}

impl AnalysisSpec {
    /// `tool` through `stock` from `z_top` down to `z_bottom`, with the defaults for the
    /// rest: nothing open, no force model or spindle speed, the default rapid rate, sample
    /// spacing, cell and engagement limit, no series, and the default stock memory budget.
    pub fn new(tool: EndMill, stock: Vec<StockRegion>, z_top: f64, z_bottom: f64) -> AnalysisSpec {
        AnalysisSpec {
            tool,
            stock,
            open: vec![],
            z_top,
            z_bottom,
            force_model: None,
            default_spindle_rpm: None,
            rapid_mm_min: DEFAULT_RAPID_MM_MIN,
            sample_spacing_mm: None,
            cell_mm: None,
            alpha_limit_deg: DEFAULT_ALPHA_LIMIT_DEG,
            series_points: 0,
            stock_memory_bytes: DEFAULT_STOCK_MEMORY_BYTES,
        }
    }
}

/// One z slice of the simulated stock. The slices follow the z levels the program cuts:
/// every layer it cuts flat, and its other levels merged down to 16 slices; where the
/// stock memory budget holds fewer, levels are merged further, the layers last.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, utoipa::ToSchema)]
pub struct SliceSummary {
    pub z_top: f64,
    pub z_bottom: f64,
    /// Area the path removed in this slice, mm².
    pub removed_area_mm2: f64,
}

/// The figures of a whole analysis.
#[derive(Debug, Clone, PartialEq, Serialize, utoipa::ToSchema)]
pub struct Summary {
    pub samples: usize,
    pub sample_spacing_mm: f64,
    pub cell_mm: f64,
    /// Memory the slices' rasters took at the end of the simulation, bytes: slices that
    /// were still alike shared one raster.
    pub raster_memory_bytes: usize,
    /// Memory the slices' rasters were allowed, bytes: levels beyond what it holds at the
    /// cell are merged, and the cell is coarsened where even 16 slices do not fit.
    pub stock_memory_budget_bytes: usize,
    pub slices: Vec<SliceSummary>,
    /// Length of feed moves in material, mm.
    pub cutting_length_mm: f64,
    /// Length of feed moves in the air, mm.
    pub air_cut_length_mm: f64,
    pub rapid_length_mm: f64,
    /// Feed moves at their programmed feeds plus rapids at the machine's rapid rate, min.
    pub time_at_programmed_feeds_min: f64,
    pub removed_volume_mm3: f64,
    /// Volume of the stock left in the layer after the path, mm³ (the slices' material
    /// areas times their heights).
    pub remaining_volume_mm3: f64,
    /// What is left inside the cavity, where the stock was a pocket's (a contour or a
    /// DXF, or the stock a job on one left); null for a box, whose material is not all to
    /// be cut.
    pub rest_material: Option<RestMaterial>,
    /// Engagement angle α, deg.
    pub alpha_deg: Stats,
    /// Maximum undeformed chip thickness at the programmed feed, µm.
    pub t_m_um: Stats,
    /// Predicted XY force, N (null without a force model).
    pub force_n: Option<Stats>,
    /// Cut length per 10° of engagement.
    pub alpha_histogram: Vec<HistogramBin>,
    pub alpha_limit_deg: f64,
    pub critical_length_mm: f64,
    /// Where the forces leave the force model's experimental domain, and how far (null
    /// without a force model).
    pub outside_model: Option<OutsideModel>,
    /// Where the predicted force exceeds 3 × the tool's standard force, by line (null
    /// without a force model).
    pub force_overload: Option<ForceOverload>,
    pub warnings: Vec<String>,
}

/// The answer of an analysis.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Analysis {
    pub summary: Summary,
    pub critical_regions: Vec<CriticalRegion>,
    pub series: Option<Series>,
}

/// The sample spacing of an analysis of `path` and the number of samples it takes.
pub fn sample_count(path: &Toolpath, spec: &AnalysisSpec) -> (f64, f64) {
    let (spacing, _) = resolution(spec, region::union_bounds(&spec.stock), 1);
    let samples = path.moves.iter().map(|m| (crate::core::toolpath::move_length(m) / spacing).ceil().max(1.0)).sum();
    (spacing, samples)
}

/// Checks that `path` and `spec` can be analysed: every value in range, every feed move
/// with a feed, and a sample count within [`MAX_SAMPLES`].
pub fn check(path: &Toolpath, spec: &AnalysisSpec) -> Result<(), CoreError> {
    require_positive("tool.diameter_mm", spec.tool.diameter_mm)?;
    if let Some(s) = spec.sample_spacing_mm {
        require_positive("sample_spacing_mm", s)?;
    }
    if let Some(c) = spec.cell_mm {
        require_positive("cell_mm", c)?;
    }
    require_positive("rapid_mm_min", spec.rapid_mm_min)?;
    if spec.stock_memory_bytes == 0 {
        return Err(CoreError::invalid("stock_memory_bytes", "must be positive"));
    }
    if !(spec.alpha_limit_deg > 0.0 && spec.alpha_limit_deg < 180.0) {
        return Err(CoreError::invalid("alpha_limit_deg", "must be between 0 and 180"));
    }
    if !(spec.z_top.is_finite() && spec.z_bottom.is_finite() && spec.z_top > spec.z_bottom) {
        return Err(CoreError::invalid("layer", "z_top must be finite and above z_bottom"));
    }
    if spec.series_points > MAX_SERIES_POINTS {
        return Err(CoreError::invalid("series_points", format!("at most {MAX_SERIES_POINTS}")));
    }
    if spec.stock.is_empty() {
        return Err(CoreError::invalid("stock", "no stock region given"));
    }
    let b = region::union_bounds(&spec.stock);
    if [b.x_min, b.y_min, b.x_max, b.y_max, spec.z_top, spec.z_bottom].iter().any(|v| v.abs() > MAX_COORDINATE_MM) {
        return Err(CoreError::invalid("stock", format!("coordinates beyond ±{MAX_COORDINATE_MM} mm")));
    }
    for m in &path.moves {
        if !matches!(m.motion, Motion::Rapid) && m.feed_mm_min.is_none_or(|f| f <= 0.0) {
            return Err(CoreError::invalid("program", format!("line {}: a feed move with no feed (F)", m.line)));
        }
        let far =
            [m.start.x, m.start.y, m.start.z, m.end.x, m.end.y, m.end.z].iter().any(|v| v.abs() > MAX_COORDINATE_MM);
        if far {
            return Err(CoreError::invalid(
                "program",
                format!("line {}: coordinates beyond ±{MAX_COORDINATE_MM} mm", m.line),
            ));
        }
    }
    let (spacing, samples) = sample_count(path, spec);
    if samples > MAX_SAMPLES {
        return Err(CoreError::invalid(
            "sample_spacing_mm",
            format!(
                "the path needs {samples:.0} samples at {spacing} mm; at most {MAX_SAMPLES:.0}: sample more coarsely"
            ),
        ));
    }
    Ok(())
}

/// Analyses `path` in the layer of `spec`.
pub fn analyze(path: &Toolpath, spec: &AnalysisSpec, progress: &dyn Progress) -> Result<Analysis, CoreError> {
    analyze_with(path, spec, progress, |_| {})
}

/// Analyses `path` as [`analyze`] does, also handing every sample's result to `sink`
/// (the feed optimiser keeps what it needs of them).
pub fn analyze_with(
    path: &Toolpath,
    spec: &AnalysisSpec,
    progress: &dyn Progress,
    sink: impl FnMut(&engine::SampleResult),
) -> Result<Analysis, CoreError> {
    analyze_from(path, spec, None, progress, sink).map(|(analysis, _)| analysis)
}

/// Analyses `path` as [`analyze_with`] does, on the stock `start` when given (the stock
/// another job left, see [`kept`]: its grid and slices replace the painting of
/// `spec.stock`, which then only bounds the layer; the layer reaches below the kept one
/// where the path cuts deeper, see [`kept::layer_bottom`]), and hands back the stock the
/// simulation left.
pub fn analyze_from(
    path: &Toolpath,
    spec: &AnalysisSpec,
    start: Option<&KeptStock>,
    progress: &dyn Progress,
    sink: impl FnMut(&engine::SampleResult),
) -> Result<(Analysis, Stack), CoreError> {
    analyze_on(path, spec, start, false, progress, sink)
}

/// [`analyze_from`] without a kept stock, on a second core too when one is spare (see
/// [`split`]): the same analysis, samples and stock.
pub fn analyze_split(
    path: &Toolpath,
    spec: &AnalysisSpec,
    progress: &dyn Progress,
    sink: impl FnMut(&engine::SampleResult),
) -> Result<(Analysis, Stack), CoreError> {
    analyze_on(path, spec, None, true, progress, sink)
}

/// [`analyze_from`], split over two cores when `split` and [`split::simulate_split`] can.
fn analyze_on(
    path: &Toolpath,
    spec: &AnalysisSpec,
    start: Option<&KeptStock>,
    split: bool,
    progress: &dyn Progress,
    mut sink: impl FnMut(&engine::SampleResult),
) -> Result<(Analysis, Stack), CoreError> {
    check(path, spec)?;
    let bounds: Rect = region::union_bounds(&spec.stock);
    // A kept stock's layer reaches down to the program's deepest feed move, within what
    // lies under it (see [`kept`]).
    let z_bottom = match start {
        Some(kept) => kept::layer_bottom(kept.z_bottom(), kept.floor(), kept::deepest_feed_mm(path))
            .map_err(|e| CoreError::invalid("stock.from_job", e))?,
        None => spec.z_bottom,
    };
    let wanted = levels::Levels::of(path, z_bottom.min(spec.z_bottom), spec.z_top, spec.tool.diameter_mm).wanted();
    let wanted_slices = wanted.slices();
    let (kept_slices, wanted_cell) = budget::slices_within(spec, wanted_slices, bounds, start.map(|k| k.grid));
    let levels = wanted.merged_to(kept_slices).z();
    let levels = match start {
        Some(kept) => kept::with_kept_bottom(levels, kept.z_bottom()),
        None => levels,
    };
    // A radius or ball end mill's corner levels, as many as the budget holds.
    let room = budget::slices_within(spec, budget::MOST_SLICES, bounds, start.map(|k| k.grid)).0;
    let levels = profile::with_corner_levels(levels, &profile::Profile::of(&spec.tool), room);
    let (spacing, painted_cell) = resolution(spec, bounds, levels.len() - 1);
    let total_samples: usize =
        path.moves.iter().map(|m| ((crate::core::toolpath::move_length(m) / spacing).ceil() as usize).max(1)).sum();
    let (mut slices, paint_share, cavity) = match start {
        Some(kept) => {
            let stack = Stack::carried(&levels, kept).map_err(|e| CoreError::invalid("stock.from_job", e))?;
            (stack, 0.0, kept.cavity)
        }
        None => {
            // Painting and simulating share the progress by their expected times.
            let painting = Raster::cell_count(bounds, painted_cell) as f64 / PAINTED_CELLS_PER_SAMPLE;
            let paint_share = painting / (painting + total_samples as f64);
            let paint_stage = Stage { inner: progress, from: 0.0, span: paint_share };
            let raster = painted::painted(bounds, painted_cell, &spec.stock, &spec.open, &paint_stage)?;
            let stack = Stack::new(&levels, raster);
            (stack, paint_share, spec.stock.iter().any(|r| matches!(r, StockRegion::Pocket(_))))
        }
    };
    let cell = slices.raster(0).cell_mm();
    let initial = slices.material_areas_fine_mm2();

    let total_length: f64 = path.moves.iter().map(crate::core::toolpath::move_length).sum();
    let cutter = Cutter {
        profile: profile::Profile::of(&spec.tool),
        flutes: spec.tool.flutes,
        default_spindle_rpm: spec.default_spindle_rpm,
        force_model: spec.force_model,
        spacing_mm: spacing,
        total_samples,
    };
    let mut builder = ReportBuilder::new(
        spec.alpha_limit_deg,
        spec.tool.diameter_mm,
        spec.series_points,
        total_length,
        spec.force_model,
    );
    let simulation_stage = Stage { inner: progress, from: paint_share, span: 1.0 - paint_share };
    let take = |r: &engine::SampleResult| {
        builder.add(r);
        sink(r);
    };
    match split {
        false => simulate(path, cutter, &mut slices, &simulation_stage, take)?,
        true => split::simulate_split(path, cutter, &mut slices, spec.stock_memory_bytes, &simulation_stage, take)?,
    }
    progress.report(1.0);
    let report = builder.finish();
    let remaining = slices.material_areas_fine_mm2();
    let mut analysis = assemble(path, spec, report, &slices, (&initial, &remaining), spacing, cell);
    analysis.summary.rest_material = cavity.then(|| RestMaterial::of(&slices, &remaining));
    analysis.summary.warnings.extend(budget::warning(spec, (wanted_slices, wanted_cell), (kept_slices, cell)));
    Ok((analysis, slices))
}

/// The analysis of `path` from the report of its samples and the slices it left, whose
/// areas of material were `initial` before and are `remaining` now (mm², per slice).
fn assemble(
    path: &Toolpath,
    spec: &AnalysisSpec,
    report: FinishedReport,
    slices: &Stack,
    (initial, remaining): (&[f64], &[f64]),
    spacing: f64,
    cell: f64,
) -> Analysis {
    let mut warnings = path.warnings.clone();
    if report.rapid_in_material.iter().any(|_| true) {
        let lines: Vec<String> = report.rapid_in_material.iter().take(10).map(u32::to_string).collect();
        warnings.push(format!("rapid moves cut material at lines {}", lines.join(", ")));
    }
    if report.plunge_samples > 0 {
        warnings.push(format!("{} samples plunge straight down (no leading half to measure)", report.plunge_samples));
    }
    let (outside_model, force_overload) = report.model_domain.clone().unzip();
    warnings.extend(outside_model.as_ref().and_then(OutsideModel::warning));
    warnings.extend(force_overload.as_ref().and_then(ForceOverload::warning));
    let corner = profile::Profile::of(&spec.tool).corner_mm;
    if spec.force_model.is_some() && corner > 0.0 {
        let tool = match spec.tool.tool_type {
            ToolType::Ball => "ball end mill".to_string(),
            _ => format!("radius end mill (corner radius {corner} mm)"),
        };
        warnings.push(format!(
            "{tool}: the slices its corner cuts are simulated at the corner's radius; their force is extrapolated from the flat end mill's model"
        ));
    }
    if spec.default_spindle_rpm.is_none() {
        if let Some(m) = path.moves.iter().find(|m| !matches!(m.motion, Motion::Rapid) && m.spindle_rpm.is_none()) {
            warnings.push(format!(
                "no spindle speed from line {} on (no S word and none in the request): chip thickness and force are not computed there",
                m.line
            ));
        }
    }
    if spec.force_model.is_none() {
        warnings.push("no force model: forces are not predicted".to_string());
    }
    let slice_summaries: Vec<SliceSummary> = slices
        .slices()
        .iter()
        .zip(initial.iter().zip(remaining))
        .map(|(s, (a0, a1))| SliceSummary { z_top: s.z_top, z_bottom: s.z_bottom, removed_area_mm2: a0 - a1 })
        .collect();
    let removed_volume_mm3 = slice_summaries.iter().map(|s| s.removed_area_mm2 * (s.z_top - s.z_bottom)).sum();
    let (mut rapid_length, mut minutes) = (0.0, 0.0);
    for m in &path.moves {
        let len = crate::core::toolpath::move_length(m);
        if matches!(m.motion, Motion::Rapid) {
            rapid_length += len;
            minutes += len / spec.rapid_mm_min;
        } else {
            minutes += len / m.feed_mm_min.unwrap_or(f64::INFINITY);
        }
    }
    Analysis {
        summary: Summary {
            samples: report.samples,
            sample_spacing_mm: spacing,
            cell_mm: cell,
            raster_memory_bytes: slices.memory_bytes(),
            stock_memory_budget_bytes: spec.stock_memory_bytes,
            slices: slice_summaries,
            cutting_length_mm: report.cutting_length_mm,
            air_cut_length_mm: report.air_cut_length_mm,
            rapid_length_mm: rapid_length,
            time_at_programmed_feeds_min: minutes,
            removed_volume_mm3,
            remaining_volume_mm3: rest::remaining_volume_mm3(slices),
            rest_material: None,
            alpha_deg: report.alpha_deg,
            t_m_um: report.t_m_um,
            force_n: report.force_n,
            alpha_histogram: report.histogram,
            alpha_limit_deg: spec.alpha_limit_deg,
            critical_length_mm: report.regions.iter().map(|r| r.length_mm).sum(),
            outside_model,
            force_overload,
            warnings,
        },
        critical_regions: report.regions,
        series: (spec.series_points > 0).then_some(report.series),
    }
}

#[cfg(test)]
mod accuracy_tests;
#[cfg(test)]
mod depth_tests;
#[cfg(test)]
mod kept_tests;
#[cfg(test)]
mod physical_tests;
#[cfg(test)]
mod probe_tests;
#[cfg(test)]
mod shape_tests;

#[cfg(test)]
mod tests;
