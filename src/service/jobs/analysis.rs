//! The `analysis` job (seed 002 subsystem (b), seed 004 §2.1): where a tool path
//! overloads the tool.

use super::analysis_result::AnalysisResult;
use super::inputs::{check_from_job, StockInput};
use super::kept_stock;
use super::kind::off_runtime_with;
use super::program_input::ProgramInput;
use super::setup::{path_job_refs, read_inputs, resolve, PathJobRefs, PathSetup, Sampling};
use crate::core::analysis::kept::{keep, KeptStock};
use crate::core::analysis::samples::{SampleCollector, DRAWING_SAMPLE_BINS};
use crate::core::analysis::{analyze_from, check, AnalysisSpec, MAX_ALPHA_LIMIT_DEG, MAX_SERIES_POINTS};
use crate::core::drawing::analysis_scene::analysis_scene;
use crate::core::drawing::scene::Scene;
use crate::core::progress::Progress;
use crate::core::tool::ToolType;
use crate::core::toolpath::move_length;
use crate::core::toolpath::Toolpath;
use crate::core::CoreError;
use crate::service::error::{ApiError, Validator};
use crate::service::jobs::kind::{JobKindSpec, Produced, Submission};
use crate::service::jobs::model::JobKind;
use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

/// A tool path to analyse in a layer of stock.
#[derive(Debug, Clone, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
#[schema(example = json!({
    "program": {"gcode": "G21 G90 G17\nG0 X-10 Y5 Z5\nS9600 M3\nG1 Z-5 F1000\nG1 X110 F5760\nM30"},
    "tool_type": "square", "diameter_mm": 10,
    "stock": {"box": {"x_min": 0, "y_min": -40, "z_min": -10, "x_max": 100, "y_max": 0, "z_max": 0}},
    "series_points": 200
}))]
pub struct AnalysisRequest {
    pub program: ProgramInput,
    pub tool_id: Option<i64>,
    pub tool_type: Option<ToolType>,
    pub diameter_mm: Option<f64>,
    pub material_id: Option<i64>,
    /// Material name (default SKD61).
    pub material: Option<String>,
    pub stock: StockInput,
    /// Spindle speed where the program has no S word (default: the tool's standard
    /// side-cutting speed).
    pub spindle_rpm: Option<f64>,
    /// Machine for the rapid rate (default: the first machine).
    pub machine_id: Option<i64>,
    /// Engagement above this is critical (default 40°).
    pub alpha_limit_deg: Option<f64>,
    /// Distance between samples, mm (default min(0.05, D/100)).
    pub sample_spacing_mm: Option<f64>,
    /// Raster cell of the stock simulation, mm (default D/100, kept within 0.002–0.5 mm).
    pub cell_mm: Option<f64>,
    /// Per-sample series downsampled to this many points (0: none).
    #[serde(default)]
    pub series_points: usize,
}

/// Checks the values of the request that need no database.
pub fn check_request(request: &AnalysisRequest, v: &mut Validator) {
    if let Some(a) = request.alpha_limit_deg {
        v.above_and_at_most("alpha_limit_deg", a, 0.0, MAX_ALPHA_LIMIT_DEG);
    }
    for (field, value) in [
        ("sample_spacing_mm", request.sample_spacing_mm),
        ("cell_mm", request.cell_mm),
        ("spindle_rpm", request.spindle_rpm),
    ] {
        if let Some(x) = value {
            v.positive(field, x);
        }
    }
    if let Some(s) = request.sample_spacing_mm {
        v.within("sample_spacing_mm", s, 1e-4, 5.0);
    }
    if let Some(c) = request.cell_mm {
        v.within("cell_mm", c, 1e-3, 5.0);
    }
    v.check(request.series_points <= MAX_SERIES_POINTS, "series_points", format!("at most {MAX_SERIES_POINTS}"));
    check_from_job(&request.stock, v);
    if request.stock.from_job.is_some() && request.cell_mm.is_some() {
        v.fail("cell_mm", "not with stock.from_job: the stock keeps the cell of the job that left it");
    }
}

/// Resolves the request and reads its program and stock, adding every fault to `faults`;
/// then, when it has none, checks the analysis as the core will run it.
pub async fn prepare(
    submission: &Submission<'_>,
    request: AnalysisRequest,
    faults: &mut Validator,
) -> Result<Option<PathSetup>, ApiError> {
    let carried = match &request.stock.from_job {
        Some(id) if !faults.refused(kept_stock::FIELD) => faults.take(kept_stock::carried(submission, id).await)?,
        _ => None,
    };
    let setup = resolve(submission.pool, &request.path_job(), faults)
        .await?
        .map(|r| PathSetup { carried_stock: carried, ..r.prepared });
    // Parse and check everything now, off the async runtime, so that bad input is a 4xx
    // at submission and never a job that fails later.
    let checked = setup.clone();
    off_runtime_with(faults, move |faults| {
        let inputs = read_inputs(checked.as_ref(), Some(&request.program), Some(&request.stock), faults)?;
        if let (Some(setup), Some(stock), Some(read)) = (&checked, inputs.stock, inputs.program) {
            if !faults.has_errors() {
                faults.take(check(&read.path, &setup.spec(stock, &request.sampling())))?;
            }
        }
        Ok(())
    })
    .await?;
    Ok(setup)
}

impl AnalysisRequest {
    fn sampling(&self) -> Sampling {
        Sampling {
            sample_spacing_mm: self.sample_spacing_mm,
            cell_mm: self.cell_mm,
            alpha_limit_deg: self.alpha_limit_deg,
            series_points: self.series_points,
        }
    }

    fn path_job(&self) -> PathJobRefs<'_> {
        path_job_refs!(self, self.machine_id, self.spindle_rpm)
    }
}

/// Runs the analysis.
pub fn run(
    request: AnalysisRequest,
    prepared: PathSetup,
    progress: &dyn Progress,
    stock_memory_bytes: usize,
) -> Result<(AnalysisResult, Scene, KeptStock), CoreError> {
    let reread = |e: ApiError| CoreError::invalid("input", e.to_string());
    let (path, spec) = build(&request, &prepared).map_err(reread)?;
    let spec = AnalysisSpec { stock_memory_bytes, ..spec };
    let total_length_mm: f64 = path.moves.iter().map(move_length).sum();
    let mut collector = SampleCollector::new(total_length_mm, DRAWING_SAMPLE_BINS);
    let start = prepared.carried_stock.as_ref().map(|c| c.decode(stock_memory_bytes)).transpose().map_err(reread)?;
    let (analysis, stack) = analyze_from(&path, &spec, start.as_ref(), progress, |r| collector.add(r))?;
    let scene = analysis_scene(&path, &spec, &analysis, &collector.finish());
    let cavity = analysis.summary.rest_material.is_some();
    let kept = keep(&stack, &spec, start.as_ref(), request.stock.floor(), cavity)?;
    Ok((AnalysisResult::new(prepared, path.moves.len(), analysis), scene, kept))
}

/// Reads the program and the stock and puts the analysis together.
pub fn build(request: &AnalysisRequest, prepared: &PathSetup) -> Result<(Toolpath, AnalysisSpec), ApiError> {
    prepared.analysis(&request.program, &request.stock, &request.sampling())
}

/// The `analysis` job kind.
pub struct Analysis;

impl JobKindSpec for Analysis {
    const KIND: JobKind = JobKind::Analysis;
    const PATH: &'static str = "/v1/analysis";
    const OPERATION_ID: &'static str = "analyzePath";
    const SUMMARY: &'static str = "Analyses a tool path (job kind `analysis`).";
    const DESCRIPTION: &'static str = "Simulates the material removal of the layer along the path (G-code or JSON moves) and reports, per sample, the engagement angle, arc length, chip thickness at the programmed feed and the predicted force; the summary (cutting and air-cut length, time at programmed feeds, α and force statistics with a histogram) and the critical regions where α exceeds the limit (default 40°). Bad NC or contour input is refused here with a 422 naming the line or vertex.";
    const REFUSES: &'static str =
        "Every fault of the request, in one problem: each refused field, each row it names that is not in the database, the NC program's faults (line, column and word) and the stock contour's";
    type Request = AnalysisRequest;
    type Prepared = PathSetup;
    type Output = AnalysisResult;

    fn check(request: &AnalysisRequest, v: &mut Validator) {
        check_request(request, v)
    }

    async fn prepare(
        submission: &Submission<'_>,
        request: AnalysisRequest,
        faults: &mut Validator,
    ) -> Result<Option<PathSetup>, ApiError> {
        prepare(submission, request, faults).await
    }

    fn run(
        request: AnalysisRequest,
        prepared: PathSetup,
        progress: &dyn Progress,
        stock_memory_bytes: usize,
    ) -> Result<Produced<AnalysisResult>, CoreError> {
        let (result, scene, kept) = run(request, prepared, progress, stock_memory_bytes)?;
        Ok(Produced::drawn(result, scene).keeping(kept))
    }
}
