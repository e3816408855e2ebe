//! Store look-ups shared by the job kinds: resolve the material, tool, standard
//! conditions and force model a request names.

use crate::core::operation::Operation;
use crate::core::tool::ToolType;
use crate::service::error::{excerpt, shown, ApiError};
use crate::service::resources::cost_rates::CostRates;
use crate::service::resources::force_models::ForceModelRecord;
use crate::service::resources::machines::Machine;
use crate::service::resources::materials::Material;
use crate::service::resources::standard_conditions::StandardConditions;
use crate::service::resources::tool_life::ToolLife;
use crate::service::resources::tools::Tool;
use crate::service::resources::DIAMETER_FILTER_TOLERANCE_MM;
use crate::service::store::Pool;

/// The material used when a request names none (MODEL.md §5).
pub const DEFAULT_MATERIAL_NAME: &str = "SKD61";
/// The seed key of that material's row (migrations/0002_seed.sql): it is still the default
/// when a shop has renamed it.
pub const DEFAULT_MATERIAL_SEED_KEY: &str = "material:skd61";

/// The material with `id`, or named `name`, or the default material: the one named
/// [`DEFAULT_MATERIAL_NAME`], else the seeded row, renamed.
pub async fn material(pool: &Pool, id: Option<i64>, name: Option<&str>) -> Result<Material, ApiError> {
    let found = match (id, name) {
        (Some(id), _) => sqlx::query_as::<_, Material>("SELECT * FROM materials WHERE id = $1")
            .bind(id)
            .fetch_optional(pool)
            .await?
            .ok_or_else(|| ApiError::field("material_id", format!("no material with id {id}")))?,
        (None, Some(name)) => sqlx::query_as::<_, Material>("SELECT * FROM materials WHERE name = $1")
            .bind(name)
            .fetch_optional(pool)
            .await?
            .ok_or_else(|| ApiError::field("material", format!("no material named '{}'", excerpt(name))))?,
        (None, None) => sqlx::query_as::<_, Material>(
            "SELECT * FROM materials WHERE name = $1 OR seed_key = $2 ORDER BY name = $3 DESC LIMIT 1",
        )
        .bind(DEFAULT_MATERIAL_NAME)
        .bind(DEFAULT_MATERIAL_SEED_KEY)
        .bind(DEFAULT_MATERIAL_NAME)
        .fetch_optional(pool)
        .await?
        .ok_or_else(|| {
            ApiError::field(
                "material",
                format!(
                    "no material given, and the default ({DEFAULT_MATERIAL_NAME}) is no longer in the database: \
                     give material or material_id"
                ),
            )
        })?,
    };
    Ok(found)
}

/// The tool with `id`, or the default tool of `tool_type` and `diameter_mm` (the `default`
/// flag of `/v1/tools`).
pub async fn tool(
    pool: &Pool,
    id: Option<i64>,
    tool_type: Option<ToolType>,
    diameter_mm: Option<f64>,
) -> Result<Tool, ApiError> {
    if let Some(id) = id {
        let tool = sqlx::query_as::<_, Tool>("SELECT * FROM tools WHERE id = $1")
            .bind(id)
            .fetch_optional(pool)
            .await?
            .ok_or_else(|| ApiError::field("tool_id", format!("no tool with id {id}")))?;
        // A type or diameter given beside the id must describe that tool.
        let what = format!("tool {id} is a {} end mill of {} mm", tool.data.tool_type.as_str(), tool.data.diameter_mm);
        if tool_type.is_some_and(|t| t != tool.data.tool_type) {
            return Err(ApiError::field("tool_type", format!("{what}: leave tool_type out, or give that tool's")));
        }
        if diameter_mm.is_some_and(|d| (d - tool.data.diameter_mm).abs() > DIAMETER_FILTER_TOLERANCE_MM) {
            return Err(ApiError::field("diameter_mm", format!("{what}: leave diameter_mm out, or give that tool's")));
        }
        return Ok(tool);
    }
    let (Some(tool_type), Some(d)) = (tool_type, diameter_mm) else {
        return Err(ApiError::field("tool_id", "give tool_id, or tool_type and diameter_mm"));
    };
    default_tool(pool, tool_type, d).await
}

/// The default tool of `tool_type` and diameter `d`; the errors name `diameter_mm` (no
/// such tool) or `tool_id` (tools, but none of them the default).
pub async fn default_tool(pool: &Pool, tool_type: ToolType, d: f64) -> Result<Tool, ApiError> {
    if !(d.is_finite() && d > 0.0) {
        return Err(ApiError::field("diameter_mm", format!("must be a finite number > 0, got {}", shown(d))));
    }
    let tools = sqlx::query_as::<_, Tool>(
        "SELECT * FROM tools WHERE tool_type = $1 AND abs(diameter_mm - $2) <= $3
         ORDER BY is_default DESC, abs(diameter_mm - $4), id",
    )
    .bind(tool_type.as_str())
    .bind(d)
    .bind(DIAMETER_FILTER_TOLERANCE_MM)
    .bind(d)
    .fetch_all(pool)
    .await?;
    match tools.first() {
        None => Err(ApiError::field(
            "diameter_mm",
            format!("no {} end mill of diameter {} mm in the database", tool_type.as_str(), shown(d)),
        )),
        Some(t) if t.data.default == Some(true) => Ok(t.clone()),
        Some(_) => Err(ApiError::field(
            "tool_id",
            format!(
                "none of the {} end mills of {d} mm (ids {}) is the default: give tool_id, or make one the default (PATCH /v1/tools/{{id}} with {{\"default\": true}})",
                tool_type.as_str(),
                tools.iter().map(|t| t.id.to_string()).collect::<Vec<_>>().join(", ")
            ),
        )),
    }
}

/// The standard conditions of `operation` for a tool in a material, if any.
pub async fn standard_conditions(
    pool: &Pool,
    tool_id: i64,
    material_id: i64,
    operation: Operation,
) -> Result<Option<StandardConditions>, ApiError> {
    Ok(sqlx::query_as::<_, StandardConditions>(
        "SELECT * FROM standard_conditions WHERE tool_id = $1 AND material_id = $2 AND operation = $3",
    )
    .bind(tool_id)
    .bind(material_id)
    .bind(operation.as_str())
    .fetch_optional(pool)
    .await?)
}

/// The force model in use for a tool in a material: the newest one.
pub async fn force_model(pool: &Pool, tool_id: i64, material_id: i64) -> Result<Option<ForceModelRecord>, ApiError> {
    Ok(sqlx::query_as::<_, ForceModelRecord>(
        "SELECT * FROM force_models WHERE tool_id = $1 AND material_id = $2 ORDER BY id DESC LIMIT 1",
    )
    .bind(tool_id)
    .bind(material_id)
    .fetch_optional(pool)
    .await?)
}

/// The tool-life data of a tool in a material, if any.
pub async fn tool_life(pool: &Pool, tool_id: i64, material_id: i64) -> Result<Option<ToolLife>, ApiError> {
    Ok(sqlx::query_as::<_, ToolLife>("SELECT * FROM tool_life WHERE tool_id = $1 AND material_id = $2")
        .bind(tool_id)
        .bind(material_id)
        .fetch_optional(pool)
        .await?)
}

/// The cost rates with `id`, or the first ones.
pub async fn cost_rates(pool: &Pool, id: Option<i64>) -> Result<CostRates, ApiError> {
    let found = match id {
        Some(id) => {
            sqlx::query_as::<_, CostRates>("SELECT * FROM cost_rates WHERE id = $1")
                .bind(id)
                .fetch_optional(pool)
                .await?
        }
        None => {
            sqlx::query_as::<_, CostRates>("SELECT * FROM cost_rates ORDER BY id LIMIT 1").fetch_optional(pool).await?
        }
    };
    found.ok_or_else(|| ApiError::field("cost_rates_id", "no such cost rates (add some at /v1/cost-rates)"))
}

/// The machine with `id`, or the first one.
pub async fn machine(pool: &Pool, id: Option<i64>) -> Result<Machine, ApiError> {
    let found = match id {
        Some(id) => {
            sqlx::query_as::<_, Machine>("SELECT * FROM machines WHERE id = $1").bind(id).fetch_optional(pool).await?
        }
        None => sqlx::query_as::<_, Machine>("SELECT * FROM machines ORDER BY id LIMIT 1").fetch_optional(pool).await?,
    };
    found.ok_or_else(|| match id {
        Some(id) => ApiError::field("machine_id", format!("no machine with id {id} (add one at /v1/machines)")),
        None => ApiError::field("machine_id", "no machine in the database (add one at /v1/machines)"),
    })
}
