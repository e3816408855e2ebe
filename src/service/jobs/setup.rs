//! What a job resolves to in the database at submission, shared by the kinds: the rows it
//! names (material, tool, force model, machine, standard conditions) as a snapshot stored
//! with the job, the setup of a job that reads a tool path, and the tool life, rates and
//! machine limits a program is costed with. Look-ups of single rows are in
//! [`crate::service::lookup`]; no kind imports another's helpers.
use crate::core::analysis::feed_cap::cap_feeds;
use crate::core::analysis::{AnalysisSpec, DEFAULT_ALPHA_LIMIT_DEG, DEFAULT_STOCK_MEMORY_BYTES};
use crate::core::costing::cost::Rates;
use crate::core::costing::estimate::CostModel;
use crate::core::force_model::ForceModel;
use crate::core::kinematics::MachineLimits;
use crate::core::operation::Operation;
use crate::core::tool::{EndMill, ToolType};
use crate::core::tool_life::ToolLifeModel;
use crate::core::toolpath::Toolpath;
use crate::service::error::{ApiError, Validator};
use crate::service::jobs::inputs::{read_stock, Stock, StockInput};
use crate::service::jobs::kept_stock::{CarriedStock, FIELD as STOCK_FROM_JOB};
use crate::service::jobs::kind::standard_cut_off_runtime;
use crate::service::jobs::program_input::{read_program, ProgramContext, ProgramInput, ReadProgram};
use crate::service::lookup;
use crate::service::resources::force_models::ForceModelRecord;
use crate::service::resources::materials::Material;
use crate::service::resources::standard_conditions::StandardConditions;
use crate::service::resources::tools::Tool;
use crate::service::resources::Source;
use crate::service::store::Pool;
use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

/// The default maximum feed of a job that sets feeds, as a multiple of the tool's
/// standard feed (MODEL.md §3: seed 003 caps at about 2.1 × standard).
pub const MAX_FEED_PER_STANDARD: f64 = 2.0;

/// A row named by id and name.
#[derive(Debug, Clone, Serialize, Deserialize, ToSchema)]
pub struct NamedRef {
    pub id: i64,
    pub name: String,
}

/// The tool of a result.
#[derive(Debug, Clone, Serialize, Deserialize, ToSchema)]
pub struct ToolRef {
    pub id: i64,
    pub name: String,
    #[serde(flatten)]
    #[schema(inline)]
    pub geometry: ToolGeometry,
}

/// Tool geometry in a result.
#[derive(Debug, Clone, Copy, Serialize, Deserialize, ToSchema)]
pub struct ToolGeometry {
    pub tool_type: ToolType,
    pub diameter_mm: f64,
    pub flutes: u32,
    pub corner_radius_mm: f64,
}

impl From<EndMill> for ToolGeometry {
    fn from(t: EndMill) -> Self {
        ToolGeometry {
            tool_type: t.tool_type,
            diameter_mm: t.diameter_mm,
            flutes: t.flutes,
            corner_radius_mm: t.corner_radius_mm,
        }
    }
}

impl From<ToolGeometry> for EndMill {
    fn from(g: ToolGeometry) -> Self {
        EndMill {
            tool_type: g.tool_type,
            diameter_mm: g.diameter_mm,
            flutes: g.flutes,
            corner_radius_mm: g.corner_radius_mm,
        }
    }
}

/// The standard-conditions row used.
#[derive(Debug, Clone, Serialize, Deserialize, ToSchema)]
pub struct StandardRef {
    pub id: i64,
    pub source: Source,
    pub reference: String,
    pub fz_min_mm: f64,
    pub fz_max_mm: Option<f64>,
    pub ad_last_layer_mm: Option<f64>,
    pub notes: String,
}

/// The force model used.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct ForceModelRef {
    pub id: i64,
    pub source: Source,
    pub reference: String,
    pub model: ForceModel,
}

impl From<&Tool> for ToolRef {
    fn from(tool: &Tool) -> Self {
        ToolRef {
            id: tool.id,
            name: tool.data.name.clone(),
            geometry: ToolGeometry {
                tool_type: tool.data.tool_type,
                diameter_mm: tool.data.diameter_mm,
                flutes: tool.data.flutes,
                corner_radius_mm: tool.data.resolved_corner_radius_mm(),
            },
        }
    }
}

impl ForceModelRef {
    /// The model of a row for its tool: forces scale with that tool's engaged edge length.
    pub fn of_tool(m: ForceModelRecord, tool: &Tool) -> Self {
        let model = m.data.model(tool.data.resolved_corner_radius_mm());
        ForceModelRef { id: m.id, source: m.data.source, model, reference: m.data.reference }
    }
}

/// What a job that reads a tool path (analysis, feeds, costing, trochoids, a plan's
/// candidates) resolved to in the database: the tool, material, force model and machine.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct PathSetup {
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
    /// The stock the job starts from, when it names one (`stock.from_job`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub carried_stock: Option<CarriedStock>,
}

impl PathSetup {
    /// Reads the program and lowers every feed above the machine's maximum to it, as the
    /// machine runs it (the warning goes with the path's).
    pub fn read_program(&self, program: &ProgramInput, stock_top_mm: Option<f64>) -> Result<ReadProgram, ApiError> {
        let context = ProgramContext { tool_radius_mm: Some(self.tool.geometry.diameter_mm / 2.0), stock_top_mm };
        let read = read_program(program, context)?;
        Ok(match self.max_feed_mm_min {
            Some(max) => {
                let ReadProgram { path, map } = read;
                let (mut capped, warning) = cap_feeds(path, max);
                capped.warnings.extend(warning);
                ReadProgram { path: capped, map }
            }
            None => read,
        })
    }
}

/// How a path is sampled and simulated, as a request sets it (each `None` is the core's
/// default).
pub struct Sampling {
    pub sample_spacing_mm: Option<f64>,
    pub cell_mm: Option<f64>,
    pub alpha_limit_deg: Option<f64>,
    pub series_points: usize,
}

impl PathSetup {
    /// Reads the program and the stock and puts the analysis of the path together.
    pub fn analysis(
        &self,
        program: &ProgramInput,
        stock: &StockInput,
        sampling: &Sampling,
    ) -> Result<(Toolpath, AnalysisSpec), ApiError> {
        let stock = read_stock(stock, self.carried_stock.as_ref())?;
        let path = self.read_program(program, Some(stock.z_top))?.path;
        Ok((path, self.spec(stock, sampling)))
    }

    /// The analysis of a path in `stock`, sampled as the request says.
    pub fn spec(&self, stock: Stock, sampling: &Sampling) -> AnalysisSpec {
        AnalysisSpec {
            tool: self.tool.geometry.into(),
            stock: stock.regions,
            open: stock.open,
            z_top: stock.z_top,
            z_bottom: stock.z_bottom,
            force_model: self.force_model.as_ref().map(|f| f.model),
            default_spindle_rpm: self.default_spindle_rpm,
            rapid_mm_min: self.rapid_mm_min,
            sample_spacing_mm: sampling.sample_spacing_mm,
            cell_mm: sampling.cell_mm,
            alpha_limit_deg: sampling.alpha_limit_deg.unwrap_or(DEFAULT_ALPHA_LIMIT_DEG),
            series_points: sampling.series_points,
            stock_memory_bytes: DEFAULT_STOCK_MEMORY_BYTES,
        }
    }
}

/// The stock and program of a path job as read at submission.
pub struct PathInputs {
    /// `None` when the job has none (surface finishing) or it was refused.
    pub stock: Option<Stock>,
    /// `None` when it was refused.
    pub program: Option<ReadProgram>,
}

/// Reads a path job's stock (when it has one) and program (when it is known) at
/// submission, each on its own, adding every fault to `faults`. The program is read with
/// the tool's radius when the tool is known (`setup`), else by radius 0, so that no fault
/// of the program comes from an unknown tool. A stock or program an earlier stage refused
/// is not read.
pub fn read_inputs(
    setup: Option<&PathSetup>,
    program: Option<&ProgramInput>,
    stock: Option<&StockInput>,
    faults: &mut Validator,
) -> Result<PathInputs, ApiError> {
    let carried = setup.and_then(|s| s.carried_stock.as_ref());
    let stock = match stock {
        Some(_) if faults.refused("stock") => None,
        // A stock from a job not resolved: its fault is said (or the tool's that kept it).
        Some(stock) if stock.from_job.is_some() && (carried.is_none() || faults.refused(STOCK_FROM_JOB)) => None,
        Some(stock) => faults.take(read_stock(stock, carried))?,
        None => None,
    };
    let stock_top_mm = stock.as_ref().map(|s| s.z_top);
    let read = match (program, setup) {
        (Some(_), _) if faults.refused_any(&["program.gcode", "program.moves"]) => None,
        (Some(program), Some(setup)) => Some(setup.read_program(program, stock_top_mm)),
        (Some(program), None) => {
            Some(read_program(program, ProgramContext { tool_radius_mm: Some(0.0), stock_top_mm }))
        }
        (None, _) => None,
    };
    let program = match read {
        Some(read) => faults.take(read)?,
        None => None,
    };
    if let (Some(carried), Some(_), Some(read)) = (carried, &stock, &program) {
        faults.take(carried.check_reach(&read.path))?;
    }
    Ok(PathInputs { stock, program })
}

/// Reads a path job's stock (when it has one) and program again as it runs: they were
/// checked at submission, so a fault here is an error.
pub fn reread_inputs(
    setup: &PathSetup,
    program: &ProgramInput,
    stock: Option<&StockInput>,
) -> Result<(Option<Stock>, ReadProgram), ApiError> {
    Validator::collect(|faults| {
        let inputs = read_inputs(Some(setup), Some(program), stock, faults)?;
        Ok(inputs.program.map(|read| (inputs.stock, read)))
    })
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

/// The [`PathJobRefs`] of a request whose fields name its tool (`tool_id`, `tool_type`,
/// `diameter_mm`) and material (`material_id`, `material`), with its machine and spindle
/// speed.
macro_rules! path_job_refs {
    ($request:expr, $machine_id:expr, $spindle_rpm:expr) => {
        $crate::service::jobs::setup::PathJobRefs {
            tool_id: $request.tool_id,
            tool_type: $request.tool_type,
            diameter_mm: $request.diameter_mm,
            material_id: $request.material_id,
            material: $request.material.as_deref(),
            machine_id: $machine_id,
            spindle_rpm: $spindle_rpm,
        }
    };
}
pub(crate) use path_job_refs;

/// The rows a path job resolved to.
pub struct Resolved {
    pub prepared: PathSetup,
    /// The tool's standard side-cutting conditions in the material, if any.
    pub standard: Option<StandardConditions>,
    /// The machine's largest feed, mm/min.
    pub machine_max_feed_mm_min: f64,
    /// The machine's largest spindle speed, min⁻¹.
    pub machine_max_spindle_rpm: f64,
}

/// The material and the tool a request names, each looked up on its own unless a field
/// naming it was refused, adding every fault to `faults`.
pub async fn material_and_tool(
    pool: &Pool,
    refs: &PathJobRefs<'_>,
    faults: &mut Validator,
) -> Result<(Option<Material>, Option<Tool>), ApiError> {
    let material = match faults.refused_any(&["material_id", "material"]) {
        true => None,
        false => faults.take(lookup::material(pool, refs.material_id, refs.material).await)?,
    };
    let tool = match faults.refused_any(&["tool_id", "tool_type", "diameter_mm"]) {
        true => None,
        false => faults.take(lookup::tool(pool, refs.tool_id, refs.tool_type, refs.diameter_mm).await)?,
    };
    Ok((material, tool))
}

/// Resolves the material, tool, force model, machine and standard conditions of a path
/// job (analysis, feeds, costing, trochoids, a plan's candidates), adding every fault to
/// `faults`: each row is looked up on its own, unless a field naming it was refused.
pub async fn resolve(
    pool: &Pool,
    refs: &PathJobRefs<'_>,
    faults: &mut Validator,
) -> Result<Option<Resolved>, ApiError> {
    let (material, tool) = material_and_tool(pool, refs, faults).await?;
    let machine = match faults.refused("machine_id") {
        true => None,
        false => faults.take(lookup::machine(pool, refs.machine_id).await)?,
    };
    if let (Some(machine), Some(rpm)) = (&machine, refs.spindle_rpm) {
        if rpm > machine.data.max_spindle_rpm && !faults.refused("spindle_rpm") {
            let reason = format!("{rpm} is above the machine's maximum of {} min⁻¹", machine.data.max_spindle_rpm);
            faults.fail("spindle_rpm", reason);
        }
    }
    let (Some(material), Some(tool), Some(machine)) = (material, tool, machine) else {
        return Ok(None);
    };
    let force_model = lookup::force_model(pool, tool.id, material.id).await?.map(|m| ForceModelRef::of_tool(m, &tool));
    let standard = lookup::standard_conditions(pool, tool.id, material.id, Operation::StandardSideCutting).await?;
    let default_spindle_rpm = refs.spindle_rpm.or(standard.as_ref().map(|c| c.data.spindle_rpm));
    let prepared = PathSetup {
        material: NamedRef { id: material.id, name: material.data.name },
        tool: ToolRef::from(&tool),
        force_model,
        machine: NamedRef { id: machine.id, name: machine.data.name.clone() },
        rapid_mm_min: machine.data.rapid_mm_min,
        max_feed_mm_min: Some(machine.data.max_feed_mm_min),
        default_spindle_rpm,
        coolant: machine.data.coolant,
        carried_stock: None,
    };
    Ok(Some(Resolved {
        prepared,
        standard,
        machine_max_feed_mm_min: machine.data.max_feed_mm_min,
        machine_max_spindle_rpm: machine.data.max_spindle_rpm,
    }))
}

/// The tool life, machine and rates a program is costed with (MODEL.md §9 and §10).
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct CostSetup {
    pub tool_life_id: i64,
    /// The tool's life in the material (stored flat, as jobs stored before kept it).
    #[serde(flatten)]
    pub life: ToolLifeModel,
    pub cost_rates: NamedRef,
    /// The rates and the tool's price (flat, likewise).
    #[serde(flatten)]
    pub rates: Rates,
    /// The machine's limits for the kinematic time.
    pub limits: MachineLimits,
}

/// The tool life, standard force, rates, tool price and machine limits a program cut by
/// the tool of `base` is costed with, adding every fault to `faults` (named by the field
/// to change). The rates are looked up even when `base` is not known.
pub async fn resolve_cost(
    pool: &Pool,
    base: Option<&PathSetup>,
    standard: Option<&StandardConditions>,
    cost_rates_id: Option<i64>,
    tool_price: Option<f64>,
    faults: &mut Validator,
) -> Result<Option<CostSetup>, ApiError> {
    let rates = match faults.refused("cost_rates_id") {
        true => None,
        false => faults.take(lookup::cost_rates(pool, cost_rates_id).await)?,
    };
    let Some(base) = base else {
        return Ok(None);
    };
    let (tool_id, material) = (base.tool.id, &base.material.name);
    let life = lookup::tool_life(pool, tool_id, base.material.id).await?;
    if life.is_none() {
        let reason = format!("no tool-life data for tool {tool_id} in {material} (add it at /v1/tool-life)");
        faults.fail("tool_id", reason);
    }
    if standard.is_none() {
        faults.fail("tool_id", format!("no standard side-cutting conditions for tool {tool_id} in {material}"));
    }
    let limits = faults.take(machine_limits(pool, base.machine.id).await)?;
    let (Some(life), Some(standard), Some(rates), Some(limits)) = (life, standard, rates, limits) else {
        return Ok(None);
    };
    let model = base.force_model.as_ref().map(|m| m.model);
    let tool: EndMill = base.tool.geometry.into();
    let Some(cut) = faults.take(standard_cut_off_runtime(tool, standard.data.conditions(), model, false).await)? else {
        return Ok(None);
    };
    let (arc_mm, standard_force_n) = (cut.arc_length_mm, cut.force_n);
    let price = sqlx::query_scalar::<_, Option<f64>>("SELECT price FROM tools WHERE id = $1")
        .bind(tool_id)
        .fetch_one(pool)
        .await?;
    let setup = CostSetup {
        tool_life_id: life.id,
        life: ToolLifeModel {
            life_m: life.data.life_m,
            gamma_table: life.data.gamma_table.iter().map(|g| (g.0, g.1)).collect(),
            force_exponent: life.data.force_exponent,
            standard_arc_length_mm: arc_mm,
            standard_fz_mm: standard.data.fz_mm,
            standard_force_n,
        },
        cost_rates: NamedRef { id: rates.id, name: rates.data.name.clone() },
        rates: Rates {
            machine_rate_per_hour: rates.data.machine_rate_per_hour,
            tool_price: tool_price.or(price).unwrap_or(rates.data.default_tool_price),
            currency: rates.data.currency.clone(),
        },
        limits,
    };
    Ok(faults.take(setup.life.validate().map_err(ApiError::from))?.map(|_| setup))
}

/// The kinematic limits of machine `id` (which must exist); errors name `machine_id`.
pub async fn machine_limits(pool: &Pool, id: i64) -> Result<MachineLimits, ApiError> {
    let machine = lookup::machine(pool, Some(id)).await?.data;
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
    /// The costing's model.
    pub fn cost_model(&self) -> CostModel {
        CostModel { life: self.life.clone(), machine: self.limits, rates: self.rates.clone() }
    }
}
