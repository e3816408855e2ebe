//! The `costing` job (seed 002 subsystems (e) and (f); MODEL.md §9 and §10): the time,
//! tool-life consumption and cost of machining an NC program.

use super::analysis::{build, resolve, AnalysisPrepared, AnalysisRequest, PathJobRefs, Resolved};
use super::conditions::NamedRef;
use super::costing_result::CostingResult;
use super::inputs::StockInput;
use super::model::ProgramPart;
use super::program_input::ProgramInput;
use super::store;
use crate::core::analysis::check;
use crate::core::conditions::standard_centres;
use crate::core::costing::cost::Rates;
use crate::core::costing::estimate::{estimate, CostModel};
use crate::core::drawing::costing_scene::costing_scene;
use crate::core::drawing::scene::Scene;
use crate::core::kinematics::MachineLimits;
use crate::core::progress::Progress;
use crate::core::tool::ToolType;
use crate::core::tool_life::ToolLifeModel;
use crate::core::CoreError;
use crate::service::error::{excerpt, ApiError, Validator};
use crate::service::lookup;
use crate::service::resources::machines::Machine;
use crate::service::resources::standard_conditions::StandardConditions;
use crate::service::store::Pool;
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
    /// A finished job whose NC program to cost (e.g. a `feeds` job).
    pub job_id: Option<String>,
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
    pub base: AnalysisPrepared,
    /// The program text when it came from a job.
    pub job_program: Option<String>,
    /// How that job read its own program (its control, tool table, arc tolerance…), so
    /// that the program it wrote is read the same way (absent in jobs stored before).
    #[serde(default)]
    pub job_program_options: Option<ProgramInput>,
    #[serde(flatten)]
    pub cost: CostSetup,
}

/// The tool life, machine and rates a program is costed with (MODEL.md §9 and §10).
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct CostSetup {
    pub tool_life_id: i64,
    pub life_m: f64,
    pub gamma_table: Vec<(f64, f64)>,
    pub force_exponent: f64,
    pub standard_arc_length_mm: f64,
    pub standard_fz_mm: f64,
    pub standard_force_n: Option<f64>,
    pub cost_rates: NamedRef,
    pub machine_rate_per_hour: f64,
    pub tool_price: f64,
    pub currency: String,
    /// The machine's limits for the kinematic time.
    pub limits: MachineLimits,
}

impl CostingRequest {
    /// The analysis of the program this request costs.
    fn analysis(&self, program: ProgramInput) -> AnalysisRequest {
        AnalysisRequest {
            program,
            tool_id: self.tool_id,
            tool_type: self.tool_type,
            diameter_mm: self.diameter_mm,
            material_id: self.material_id,
            material: self.material.clone(),
            stock: self.stock.clone(),
            spindle_rpm: self.spindle_rpm,
            machine_id: self.machine_id,
            alpha_limit_deg: None,
            sample_spacing_mm: self.sample_spacing_mm,
            cell_mm: self.cell_mm,
            series_points: 0,
        }
    }

    fn program(&self, prepared: &CostingPrepared) -> Result<ProgramInput, ApiError> {
        match (&self.program, &prepared.job_program) {
            (Some(p), None) => Ok(p.clone()),
            (None, Some(text)) => Ok(ProgramInput::of_text(text.clone(), prepared.job_program_options.as_ref())),
            _ => Err(ApiError::field("program", "give exactly one of program and job_id")),
        }
    }
}

/// Checks the request and resolves it against the database.
pub async fn prepare(pool: &Pool, request: CostingRequest) -> Result<CostingPrepared, ApiError> {
    let mut v = Validator::new();
    v.check(request.program.is_some() != request.job_id.is_some(), "program", "give exactly one of program and job_id");
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
    v.finish()?;
    let (job_program, job_program_options) = match &request.job_id {
        Some(id) => {
            let row = store::get(pool, id)
                .await
                .map_err(|_| ApiError::field("job_id", format!("no job with id {}", excerpt(id))))?;
            let text = store::program_part(pool, id, ProgramPart::Main).await?.ok_or_else(|| {
                ApiError::field("job_id", format!("job {id} ({}, {}) has no NC program", row.kind, row.status))
            })?;
            // The input may be large: it is read off the async runtime.
            let input = store::input(pool, id).await?.unwrap_or_default();
            let options = tokio::task::spawn_blocking(move || ProgramInput::options_of_job_input(&input))
                .await
                .map_err(|e| ApiError::Internal(e.to_string()))?;
            (Some(text), options)
        }
        None => (None, None),
    };
    let refs = PathJobRefs {
        tool_id: request.tool_id,
        tool_type: request.tool_type,
        diameter_mm: request.diameter_mm,
        material_id: request.material_id,
        material: request.material.as_deref(),
        machine_id: request.machine_id,
        spindle_rpm: request.spindle_rpm,
    };
    let Resolved { prepared: base, standard, .. } = resolve(pool, &refs).await?;
    let cost = resolve_cost(pool, &base, standard.as_ref(), request.cost_rates_id, request.tool_price).await?;
    let prepared = CostingPrepared { job_program, job_program_options, cost, base };
    let checked = prepared.clone();
    tokio::task::spawn_blocking(move || -> Result<(), ApiError> {
        let analysis = request.analysis(request.program(&checked)?);
        let (path, spec) = build(&analysis, &checked.base)?;
        check(&path, &spec)?;
        Ok(())
    })
    .await
    .map_err(|e| ApiError::Internal(e.to_string()))??;
    Ok(prepared)
}

/// The tool life, standard force, rates, tool price and machine limits a program cut by
/// the tool of `base` is costed with; errors name the field to change.
pub async fn resolve_cost(
    pool: &Pool,
    base: &AnalysisPrepared,
    standard: Option<&StandardConditions>,
    cost_rates_id: Option<i64>,
    tool_price: Option<f64>,
) -> Result<CostSetup, ApiError> {
    let life = lookup::tool_life(pool, base.tool.id, base.material.id).await?.ok_or_else(|| {
        ApiError::field(
            "tool_id",
            format!("no tool-life data for tool {} in {} (add it at /v1/tool-life)", base.tool.id, base.material.name),
        )
    })?;
    let standard = standard.ok_or_else(|| {
        ApiError::field(
            "tool_id",
            format!("no standard side-cutting conditions for tool {} in {}", base.tool.id, base.material.name),
        )
    })?;
    let (t_um, arc_mm) = standard_centres(base.tool.geometry.diameter_mm / 2.0, standard.data.conditions())?;
    let standard_force_n = base.force_model.as_ref().map(|m| m.model.force_n(t_um, arc_mm, m.model.ad_ref_mm));
    let rates = lookup::cost_rates(pool, cost_rates_id).await?;
    let price = sqlx::query_scalar::<_, Option<f64>>("SELECT price FROM tools WHERE id = $1")
        .bind(base.tool.id)
        .fetch_one(pool)
        .await?;
    let setup = CostSetup {
        tool_life_id: life.id,
        life_m: life.data.life_m,
        gamma_table: life.data.gamma_table.iter().map(|g| (g.0, g.1)).collect(),
        force_exponent: life.data.force_exponent,
        standard_arc_length_mm: arc_mm,
        standard_fz_mm: standard.data.fz_mm,
        standard_force_n,
        cost_rates: NamedRef { id: rates.id, name: rates.data.name.clone() },
        machine_rate_per_hour: rates.data.machine_rate_per_hour,
        tool_price: tool_price.or(price).unwrap_or(rates.data.default_tool_price),
        currency: rates.data.currency.clone(),
        limits: machine_limits(pool, base.machine.id).await?,
    };
    setup.life_model().validate()?;
    Ok(setup)
}

/// The kinematic limits of machine `id` (which must exist); errors name `machine_id`.
pub async fn machine_limits(pool: &Pool, id: i64) -> Result<MachineLimits, ApiError> {
    let machine =
        sqlx::query_as::<_, Machine>("SELECT * FROM machines WHERE id = $1").bind(id).fetch_one(pool).await?.data;
    let limits = MachineLimits {
        rapid_mm_min: machine.rapid_mm_min,
        max_feed_mm_min: machine.max_feed_mm_min,
        accel_mm_s2: [machine.accel_x_mm_s2, machine.accel_y_mm_s2, machine.accel_z_mm_s2],
        jerk_mm_s3: [machine.jerk_x_mm_s3, machine.jerk_y_mm_s3, machine.jerk_z_mm_s3],
        tool_change_s: machine.tool_change_s,
    };
    limits.validate().map_err(|e| ApiError::field("machine_id", format!("machine {id}: {e}")))?;
    Ok(limits)
}

impl CostSetup {
    fn life_model(&self) -> ToolLifeModel {
        ToolLifeModel {
            life_m: self.life_m,
            gamma_table: self.gamma_table.clone(),
            force_exponent: self.force_exponent,
            standard_arc_length_mm: self.standard_arc_length_mm,
            standard_fz_mm: self.standard_fz_mm,
            standard_force_n: self.standard_force_n,
        }
    }

    pub fn rates(&self) -> Rates {
        Rates {
            machine_rate_per_hour: self.machine_rate_per_hour,
            tool_price: self.tool_price,
            currency: self.currency.clone(),
        }
    }

    /// The costing's model.
    pub fn cost_model(&self) -> CostModel {
        CostModel { life: self.life_model(), machine: self.limits, rates: self.rates() }
    }
}

/// Runs the costing.
pub fn run(
    request: CostingRequest,
    prepared: CostingPrepared,
    progress: &dyn Progress,
) -> Result<(CostingResult, Scene), CoreError> {
    let reread = |e: ApiError| CoreError::invalid("input", e.to_string());
    let analysis = request.analysis(request.program(&prepared).map_err(reread)?);
    let (path, spec) = build(&analysis, &prepared.base).map_err(reread)?;
    let (report, estimate) = estimate(&path, &spec, &prepared.cost.cost_model(), progress)?;
    let scene = costing_scene(&path, &spec, &report, &estimate.wear, &estimate.time, &estimate.cost);
    Ok((CostingResult::new(prepared, &path, report, estimate)?, scene))
}
