//! The `costing` job (seed 002 subsystems (e) and (f); MODEL.md §9 and §10): the time,
//! tool-life consumption and cost of machining an NC program.

use super::costing_result::CostingResult;
use super::inputs::{check_from_job, StockInput};
use super::kept_stock;
use super::kind::off_runtime_with;
use super::model::{JobId, ProgramPart};
use super::program_input::ProgramInput;
use super::setup::{path_job_refs, read_inputs, resolve, resolve_cost, CostSetup, PathSetup, Sampling};
use super::store;
use crate::core::analysis::kept::{keep, KeptStock};
use crate::core::analysis::{check, AnalysisSpec};
use crate::core::costing::estimate::estimate_from;
use crate::core::drawing::costing_scene::costing_scene;
use crate::core::drawing::scene::Scene;
use crate::core::progress::Progress;
use crate::core::tool::ToolType;
use crate::core::toolpath::Toolpath;
use crate::core::CoreError;
use crate::service::error::{ApiError, Validator};
use crate::service::jobs::kind::{JobKindSpec, Produced, Submission};
use crate::service::jobs::model::JobKind;
use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

/// What to cost: a program (or a finished job's program) cut with a tool in a stock.
#[derive(Debug, Clone, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
#[schema(example = json!({
    "program": {"gcode": "G21 G90 G17\nS9600 M3\nG0 X-10 Y4.5 Z5\nG1 Z-10 F1000\nG1 X110 F5760\nG0 Z5\nM30"},
    "tool_type": "square", "diameter_mm": 10,
    "stock": {"box": {"x_min": 0, "y_min": -40, "z_min": -10, "x_max": 100, "y_max": 0, "z_max": 0}}
}))]
pub struct CostingRequest {
    /// The program (give this or `job_id`).
    pub program: Option<ProgramInput>,
    /// A finished job whose NC program to cost (e.g. a `feeds` job); a planner's key may
    /// name only its own jobs.
    pub job_id: Option<JobId>,
    pub tool_id: Option<i64>,
    pub tool_type: Option<ToolType>,
    pub diameter_mm: Option<f64>,
    pub material_id: Option<i64>,
    /// Material name (default SKD61).
    pub material: Option<String>,
    /// The stock of the layer the program cuts.
    pub stock: StockInput,
    /// Machine for the rapid rate and the kinematic limits (default: the first machine).
    pub machine_id: Option<i64>,
    /// Cost rates (default: the first ones).
    pub cost_rates_id: Option<i64>,
    /// Price of one tool (default: the tool's price, else the rates' default).
    pub tool_price: Option<f64>,
    /// Spindle speed where the program has no S word (default: the standard one).
    pub spindle_rpm: Option<f64>,
    /// Distance between samples, mm (default min(0.05, D/100)).
    pub sample_spacing_mm: Option<f64>,
    /// Raster cell of the stock simulation, mm.
    pub cell_mm: Option<f64>,
}

/// What the request resolved to.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct CostingPrepared {
    #[serde(flatten)]
    pub base: PathSetup,
    /// The program text when it came from a job.
    pub job_program: Option<String>,
    /// How that job read its own program (its control, tool table, arc tolerance…), so
    /// that the program it wrote is read the same way (absent in jobs stored before).
    #[serde(default)]
    pub job_program_options: Option<ProgramInput>,
    #[serde(flatten)]
    pub cost: CostSetup,
}

impl CostingRequest {
    fn sampling(&self) -> Sampling {
        Sampling {
            sample_spacing_mm: self.sample_spacing_mm,
            cell_mm: self.cell_mm,
            alpha_limit_deg: None,
            series_points: 0,
        }
    }

    /// The path and the analysis of the program this request costs.
    fn analysis(&self, prepared: &CostingPrepared) -> Result<(Toolpath, AnalysisSpec), ApiError> {
        let program = self.program(&prepared.job_program, prepared.job_program_options.as_ref())?;
        prepared.base.analysis(&program, &self.stock, &self.sampling())
    }

    /// The program costed: the request's, or the text of the job it names, read as that
    /// job read its own (`options`).
    fn program(&self, job_program: &Option<String>, options: Option<&ProgramInput>) -> Result<ProgramInput, ApiError> {
        match (&self.program, job_program) {
            (Some(p), None) => Ok(p.clone()),
            (None, Some(text)) => Ok(ProgramInput::of_text(text.clone(), options)),
            _ => Err(ApiError::field("program", "give exactly one of program and job_id")),
        }
    }
}

/// Checks the values of the request that need no database.
pub fn check_request(request: &CostingRequest, v: &mut Validator) {
    v.check(request.program.is_some() != request.job_id.is_some(), "program", "give exactly one of program and job_id");
    check_from_job(&request.stock, v);
    if request.stock.from_job.is_some() && request.cell_mm.is_some() {
        v.fail("cell_mm", "not with stock.from_job: the stock keeps the cell of the job that left it");
    }
    if let Some(p) = request.tool_price {
        v.within("tool_price", p, 0.0, crate::service::resources::tools::MAX_PRICE);
    }
    for (field, value) in [
        ("spindle_rpm", request.spindle_rpm),
        ("sample_spacing_mm", request.sample_spacing_mm),
        ("cell_mm", request.cell_mm),
    ] {
        if let Some(x) = value {
            v.positive(field, x);
        }
    }
}

/// The NC program of the finished job `id` and how that job read its own; a planner may
/// name only its own jobs. Faults name `job_id`.
async fn job_program(
    submission: &Submission<'_>,
    id: &JobId,
) -> Result<(Option<String>, Option<ProgramInput>), ApiError> {
    let pool = submission.pool;
    let row = store::get_visible(pool, submission.caller, id).await.map_err(|e| match e {
        ApiError::NotFound(_) => ApiError::field("job_id", format!("no job with id {id}")),
        other => other,
    })?;
    let text = store::program_part(pool, id, ProgramPart::Main).await?.ok_or_else(|| {
        ApiError::field("job_id", format!("job {id} ({}, {}) has no NC program", row.kind, row.status))
    })?;
    // The input may be large: it is read off the async runtime.
    let input = store::input(pool, id).await?.unwrap_or_default();
    let options = tokio::task::spawn_blocking(move || ProgramInput::options_of_job_input(&input))
        .await
        .map_err(|e| ApiError::Internal(e.to_string()))?;
    Ok((Some(text), options))
}

/// Resolves the request against the database and reads its program and stock, adding
/// every fault to `faults`; then, when it has none, checks the analysis as the core will
/// run it. A `job_id` must name a job the caller may see (a planner's own).
pub async fn prepare(
    submission: &Submission<'_>,
    request: CostingRequest,
    faults: &mut Validator,
) -> Result<Option<CostingPrepared>, ApiError> {
    let pool = submission.pool;
    let job = match &request.job_id {
        Some(id) if !faults.refused_any(&["job_id", "program"]) => faults.take(job_program(submission, id).await)?,
        Some(_) => None,
        None => Some((None, None)),
    };
    let carried = match &request.stock.from_job {
        Some(id) if !faults.refused(kept_stock::FIELD) => faults.take(kept_stock::carried(submission, id).await)?,
        _ => None,
    };
    let refs = path_job_refs!(request, request.machine_id, request.spindle_rpm);
    let resolved = resolve(pool, &refs, faults).await?;
    let (base, standard) = resolved.map(|r| (PathSetup { carried_stock: carried, ..r.prepared }, r.standard)).unzip();
    let cost = resolve_cost(
        pool,
        base.as_ref(),
        standard.flatten().as_ref(),
        request.cost_rates_id,
        request.tool_price,
        faults,
    )
    .await?;
    let (job_program, job_program_options) = job.unzip();
    let checked = base.clone();
    let (text, options) = (job_program.clone().flatten(), job_program_options.clone().flatten());
    // The program is unknown when the job it names is refused (or it was refused itself).
    let known = job_program.is_some() && !faults.refused("program");
    off_runtime_with(faults, move |faults| {
        let program = if known { faults.take(request.program(&text, options.as_ref()))? } else { None };
        let inputs = read_inputs(checked.as_ref(), program.as_ref(), Some(&request.stock), faults)?;
        if let (Some(base), Some(stock), Some(read)) = (&checked, inputs.stock, inputs.program) {
            if !faults.has_errors() {
                faults.take(check(&read.path, &base.spec(stock, &request.sampling())))?;
            }
        }
        Ok(())
    })
    .await?;
    let (Some(base), Some(cost), Some(job_program), Some(job_program_options)) =
        (base, cost, job_program, job_program_options)
    else {
        return Ok(None);
    };
    Ok(Some(CostingPrepared { job_program, job_program_options, cost, base }))
}

/// Runs the costing.
pub fn run(
    request: CostingRequest,
    prepared: CostingPrepared,
    progress: &dyn Progress,
    stock_memory_bytes: usize,
) -> Result<(CostingResult, Scene, KeptStock), CoreError> {
    let reread = |e: ApiError| CoreError::invalid("input", e.to_string());
    let (path, spec) = request.analysis(&prepared).map_err(reread)?;
    let spec = AnalysisSpec { stock_memory_bytes, ..spec };
    let start =
        prepared.base.carried_stock.as_ref().map(|c| c.decode(stock_memory_bytes)).transpose().map_err(reread)?;
    let model = prepared.cost.cost_model();
    let (report, estimate, stack) = estimate_from(&path, &spec, start.as_ref(), &model, progress)?;
    let scene = costing_scene(&path, &spec, &report, &estimate.wear, &estimate.time, &estimate.cost);
    let cavity = report.summary.rest_material.is_some();
    let kept = keep(&stack, &spec, start.as_ref(), request.stock.floor(), cavity)?;
    Ok((CostingResult::new(prepared, &path, report, estimate)?, scene, kept))
}

/// The `costing` job kind.
pub struct Costing;

impl JobKindSpec for Costing {
    const KIND: JobKind = JobKind::Costing;
    const PATH: &'static str = "/v1/costing";
    const OPERATION_ID: &'static str = "costProgram";
    const SUMMARY: &'static str = "Costs an NC program (job kind `costing`).";
    const DESCRIPTION: &'static str = "Simulates the program in its stock and reports the machining time, the tool-life consumption `L_t / L_f` with the lines and engagement angles where the tool wears (MODEL.md §9), the cost `C = c_m · T_m + c_t · L_t / L_f` (seed 002, Eq. 4), the material removed and the removal rate. The program is given, or taken from a finished job of the caller's (`job_id`, e.g. a `feeds` job; a planner's key may name only its own jobs).";
    const REFUSES: &'static str =
        "Every fault of the request, in one problem: each refused field, each row or job it names that is not in the database, the NC program's faults (line, column and word) and the stock contour's";
    type Request = CostingRequest;
    type Prepared = CostingPrepared;
    type Output = CostingResult;

    fn check(request: &CostingRequest, v: &mut Validator) {
        check_request(request, v)
    }

    async fn prepare(
        submission: &Submission<'_>,
        request: CostingRequest,
        faults: &mut Validator,
    ) -> Result<Option<CostingPrepared>, ApiError> {
        prepare(submission, request, faults).await
    }

    fn run(
        request: CostingRequest,
        prepared: CostingPrepared,
        progress: &dyn Progress,
        stock_memory_bytes: usize,
    ) -> Result<Produced<CostingResult>, CoreError> {
        let (result, scene, kept) = run(request, prepared, progress, stock_memory_bytes)?;
        Ok(Produced::drawn(result, scene).keeping(kept))
    }
}
