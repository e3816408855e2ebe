//! The plan's stair-step intermediate roughing as a request names it (issue 32 item 4): a
//! ball or radius end mill that takes off the steps a sloped wall or floor leaves between the
//! layers' sections, and the database rows it is resolved to.

use super::plan_tools::{self, ConditionsFrom, StairDepths};
use super::plans::CandidatePrepared;
use crate::core::tool::ToolType;
use crate::service::error::{ApiError, Validator};
use crate::service::lookup;
use crate::service::store::Pool;
use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

/// The default tool: the R5 ball of seed 004 (its conventional and case-II cuts).
pub const DEFAULT_STAIR_BALL_DIAMETER_MM: f64 = 10.0;
/// The least depth between levels or rings a request may give, mm (a stair step at a
/// hundredth of that would take hours to plan and run; the step itself also refuses rings
/// closer than its surface's cell).
pub const MIN_STAIR_DEPTH_MM: f64 = 0.05;
/// The largest, mm (the largest end mills are 16 mm across).
pub const MAX_STAIR_DEPTH_MM: f64 = 50.0;

/// The stair-step roughing of a plan, for layers that are sections of a sloped wall or floor
/// (each layer's contour the section at its bottom): a ball or radius end mill takes off the
/// steps the roughing leaves, in z levels over the surface interpolated between the
/// sections. Every field is optional (`{}`: the R5 ball at its standard side cut, seed 004
/// Table 7: Ad 0.6, Rd 4).
#[derive(Debug, Clone, Default, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct StairStepInput {
    /// Plan the step where the layers leave steps (default true).
    pub enabled: Option<bool>,
    /// The tool by id: a ball or radius end mill (not with `tool_type` or `diameter_mm`).
    pub tool_id: Option<i64>,
    /// `ball` (default) or `radius`: the default tool of that type and `diameter_mm`.
    pub tool_type: Option<ToolType>,
    /// Diameter of the default tool, mm (default 10).
    pub diameter_mm: Option<f64>,
    /// Depth between levels, mm (default: a ball's standard Ad; 0.06 D for a radius end mill).
    pub axial_depth_mm: Option<f64>,
    /// Depth between rings at a level, mm (default: a ball's standard Rd; 0.4 D for a radius
    /// end mill).
    pub radial_depth_mm: Option<f64>,
}

/// Checks the values of `input` that need no database.
pub fn check(input: &StairStepInput, v: &mut Validator) {
    let by_id = input.tool_id.is_some();
    v.check(
        !(by_id && (input.tool_type.is_some() || input.diameter_mm.is_some())),
        "stair_step.tool_id",
        "give either tool_id, or tool_type and diameter_mm",
    );
    v.check(
        !matches!(input.tool_type, Some(ToolType::Square)),
        "stair_step.tool_type",
        "the stair steps need a ball or radius end mill",
    );
    if let Some(d) = input.diameter_mm {
        v.positive("stair_step.diameter_mm", d);
    }
    if let Some(ad) = input.axial_depth_mm {
        v.within("stair_step.axial_depth_mm", ad, MIN_STAIR_DEPTH_MM, MAX_STAIR_DEPTH_MM);
    }
    if let Some(rd) = input.radial_depth_mm {
        v.within("stair_step.radial_depth_mm", rd, MIN_STAIR_DEPTH_MM, MAX_STAIR_DEPTH_MM);
    }
}

/// Resolves the step's tool: `Ok(Some(..))` with its data, `Ok(None)` when the request asks
/// for no step (no `stair_step`, or `enabled: false`) or a fault was added to `faults` (a
/// tool that is not there, not a ball or radius end mill, or without the data to plan with).
pub async fn resolve(
    pool: &Pool,
    input: Option<&StairStepInput>,
    material_id: i64,
    machine_id: i64,
    default_tool_price: f64,
    faults: &mut Validator,
) -> Result<Option<CandidatePrepared>, ApiError> {
    let Some(asked) = input.filter(|i| i.enabled != Some(false)) else {
        return Ok(None);
    };
    if faults.refused_any(&["stair_step", "stair_step.tool_id", "stair_step.tool_type", "stair_step.diameter_mm"]) {
        return Ok(None);
    }
    let (field, found) = match asked.tool_id {
        Some(id) => ("stair_step.tool_id", lookup::tool(pool, Some(id), None, None).await),
        None => {
            let tool_type = asked.tool_type.unwrap_or(ToolType::Ball);
            let d = asked.diameter_mm.unwrap_or(DEFAULT_STAIR_BALL_DIAMETER_MM);
            ("stair_step.diameter_mm", lookup::default_tool(pool, tool_type, d).await)
        }
    };
    let tool = match found {
        Ok(tool) => tool,
        Err(ApiError::Validation(errors)) => {
            errors.into_iter().for_each(|e| faults.fail(field, e.reason));
            return Ok(None);
        }
        Err(other) => return Err(other),
    };
    if tool.data.tool_type == ToolType::Square {
        faults.fail(
            field,
            format!(
                "tool {} ({}) is a square end mill: the stair steps need a ball or radius end mill",
                tool.id, tool.data.name
            ),
        );
        return Ok(None);
    }
    let depths = StairDepths { axial_depth_mm: asked.axial_depth_mm, radial_depth_mm: asked.radial_depth_mm };
    let from = ConditionsFrom::StairStep(depths);
    match plan_tools::resolve(pool, tool.id, material_id, machine_id, default_tool_price, from).await? {
        Ok((prepared, _)) => Ok(Some(prepared)),
        Err(reason) => {
            faults.fail(field, reason);
            Ok(None)
        }
    }
}
