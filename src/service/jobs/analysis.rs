//! The `analysis` job (seed 002 subsystem (b), seed 004 §2.1): where a tool path
//! overloads the tool.

use super::analysis_result::AnalysisResult;
use super::conditions::{ForceModelRef, NamedRef, ToolRef};
use super::inputs::{read_stock, StockInput};
use super::program_input::{read_program, ProgramContext, ProgramInput, ReadProgram};
use crate::core::analysis::feed_cap::cap_feeds;
use crate::core::analysis::sampling::move_length;
use crate::core::analysis::{
    analyze_with, check, AnalysisSpec, DEFAULT_ALPHA_LIMIT_DEG, MAX_ALPHA_LIMIT_DEG, MAX_SERIES_POINTS,
};
use crate::core::drawing::analysis_scene::analysis_scene;
use crate::core::drawing::samples::{SampleCollector, DRAWING_SAMPLE_BINS};
use crate::core::drawing::scene::Scene;
use crate::core::operation::Operation;
use crate::core::progress::Progress;
use crate::core::tool::ToolType;
use crate::core::toolpath::Toolpath;
use crate::core::CoreError;
use crate::service::error::{ApiError, Validator};
use crate::service::lookup;
use crate::service::resources::machines::Machine;
use crate::service::resources::standard_conditions::StandardConditions;
use crate::service::store::Pool;
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
    /// Raster cell of the stock simulation, mm (default D/200).
    pub cell_mm: Option<f64>,
    /// Per-sample series downsampled to this many points (0: none).
    #[serde(default)]
    pub series_points: usize,
}

/// What the request resolved to in the database.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct AnalysisPrepared {
    pub material: NamedRef,
    pub tool: ToolRef,
    pub force_model: Option<ForceModelRef>,
    pub machine: NamedRef,
    pub rapid_mm_min: f64,
    /// The machine's largest feed, mm/min: faster feeds are analysed at it (absent in
    /// jobs stored before it was kept).
    #[serde(default)]
    pub max_feed_mm_min: Option<f64>,
    pub default_spindle_rpm: Option<f64>,
    /// The machine's coolant, for the programs the job writes (jobs stored before it was
    /// kept: off).
    #[serde(default)]
    pub coolant: crate::core::coolant::Coolant,
}

impl AnalysisPrepared {
    /// Reads the program and lowers every feed above the machine's maximum to it, as the
    /// machine runs it (the warning goes with the path's).
    pub fn read_program(&self, program: &ProgramInput, stock_top_mm: Option<f64>) -> Result<ReadProgram, ApiError> {
        let context = ProgramContext { tool_radius_mm: Some(self.tool.geometry.diameter_mm / 2.0), stock_top_mm };
        let read = read_program(program, context)?;
        Ok(match self.max_feed_mm_min {
            Some(max) => {
                let (mut capped, warning) = cap_feeds(&read.path, max);
                capped.warnings.extend(warning);
                ReadProgram { path: capped, ..read }
            }
            None => read,
        })
    }
}

/// Checks the request (parsing the program and the stock) and resolves it.
pub async fn prepare(pool: &Pool, request: AnalysisRequest) -> Result<AnalysisPrepared, ApiError> {
    let mut v = Validator::new();
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
    v.finish()?;

    let Resolved { prepared, .. } = resolve(pool, &request.path_job()).await?;
    // Parse and check everything now, off the async runtime, so that bad input is a 4xx
    // at submission and never a job that fails later.
    let checked = prepared.clone();
    tokio::task::spawn_blocking(move || -> Result<(), ApiError> {
        let (path, spec) = build(&request, &checked)?;
        check(&path, &spec)?;
        Ok(())
    })
    .await
    .map_err(|e| ApiError::Internal(e.to_string()))??;
    Ok(prepared)
}

/// What names the database rows of a path job.
pub struct PathJobRefs<'a> {
    pub tool_id: Option<i64>,
    pub tool_type: Option<ToolType>,
    pub diameter_mm: Option<f64>,
    pub material_id: Option<i64>,
    pub material: Option<&'a str>,
    pub machine_id: Option<i64>,
    pub spindle_rpm: Option<f64>,
}

impl AnalysisRequest {
    fn path_job(&self) -> PathJobRefs<'_> {
        PathJobRefs {
            tool_id: self.tool_id,
            tool_type: self.tool_type,
            diameter_mm: self.diameter_mm,
            material_id: self.material_id,
            material: self.material.as_deref(),
            machine_id: self.machine_id,
            spindle_rpm: self.spindle_rpm,
        }
    }
}

/// The rows a path job resolved to.
pub struct Resolved {
    pub prepared: AnalysisPrepared,
    /// The tool's standard side-cutting conditions in the material, if any.
    pub standard: Option<StandardConditions>,
    /// The machine's largest feed, mm/min.
    pub machine_max_feed_mm_min: f64,
    /// The machine's largest spindle speed, min⁻¹.
    pub machine_max_spindle_rpm: f64,
}

/// Resolves the material, tool, force model, machine and standard conditions of a path
/// job (analysis, feeds).
pub async fn resolve(pool: &Pool, refs: &PathJobRefs<'_>) -> Result<Resolved, ApiError> {
    let material = lookup::material(pool, refs.material_id, refs.material).await?;
    let tool = lookup::tool(pool, refs.tool_id, refs.tool_type, refs.diameter_mm).await?;
    let force_model = lookup::force_model(pool, tool.id, material.id).await?.map(|m| ForceModelRef::of_tool(m, &tool));
    let machine = match refs.machine_id {
        Some(id) => {
            sqlx::query_as::<_, Machine>("SELECT * FROM machines WHERE id = $1").bind(id).fetch_optional(pool).await?
        }
        None => sqlx::query_as::<_, Machine>("SELECT * FROM machines ORDER BY id LIMIT 1").fetch_optional(pool).await?,
    }
    .ok_or_else(|| ApiError::field("machine_id", "no such machine (add one at /v1/machines)"))?;
    if let Some(rpm) = refs.spindle_rpm.filter(|rpm| *rpm > machine.data.max_spindle_rpm) {
        return Err(ApiError::field(
            "spindle_rpm",
            format!("{rpm} is above the machine's maximum of {} min⁻¹", machine.data.max_spindle_rpm),
        ));
    }
    let standard = lookup::standard_conditions(pool, tool.id, material.id, Operation::StandardSideCutting).await?;
    let default_spindle_rpm = refs.spindle_rpm.or(standard.as_ref().map(|c| c.data.spindle_rpm));
    let prepared = AnalysisPrepared {
        material: NamedRef { id: material.id, name: material.data.name },
        tool: ToolRef::from(&tool),
        force_model,
        machine: NamedRef { id: machine.id, name: machine.data.name.clone() },
        rapid_mm_min: machine.data.rapid_mm_min,
        max_feed_mm_min: Some(machine.data.max_feed_mm_min),
        default_spindle_rpm,
        coolant: machine.data.coolant,
    };
    Ok(Resolved {
        prepared,
        standard,
        machine_max_feed_mm_min: machine.data.max_feed_mm_min,
        machine_max_spindle_rpm: machine.data.max_spindle_rpm,
    })
}

/// Runs the analysis.
pub fn run(
    request: AnalysisRequest,
    prepared: AnalysisPrepared,
    progress: &dyn Progress,
) -> Result<(AnalysisResult, Scene), CoreError> {
    let reread = |e: ApiError| CoreError::invalid("input", e.to_string());
    let (path, spec) = build(&request, &prepared).map_err(reread)?;
    let total_length_mm: f64 = path.moves.iter().map(move_length).sum();
    let mut collector = SampleCollector::new(total_length_mm, DRAWING_SAMPLE_BINS);
    let analysis = analyze_with(&path, &spec, progress, |r| collector.add(r))?;
    let scene = analysis_scene(&path, &spec, &analysis, &collector.finish());
    Ok((AnalysisResult::new(prepared, path.moves.len(), analysis), scene))
}

/// Reads the program and the stock and puts the analysis together.
pub fn build(request: &AnalysisRequest, prepared: &AnalysisPrepared) -> Result<(Toolpath, AnalysisSpec), ApiError> {
    let stock = read_stock(&request.stock)?;
    let path = prepared.read_program(&request.program, Some(stock.z_top))?.path;
    let spec = AnalysisSpec {
        tool: prepared.tool.geometry.into(),
        stock: stock.regions,
        open: stock.open,
        z_top: stock.z_top,
        z_bottom: stock.z_bottom,
        force_model: prepared.force_model.as_ref().map(|f| f.model),
        default_spindle_rpm: prepared.default_spindle_rpm,
        rapid_mm_min: prepared.rapid_mm_min,
        sample_spacing_mm: request.sample_spacing_mm,
        cell_mm: request.cell_mm,
        alpha_limit_deg: request.alpha_limit_deg.unwrap_or(DEFAULT_ALPHA_LIMIT_DEG),
        series_points: request.series_points,
    };
    Ok((path, spec))
}
