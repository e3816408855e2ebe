//! The candidate tools of a plan: which tools the request names (by diameter, by id, or
//! the default range) and what each needs from the database.

use super::kind::standard_cut_off_runtime;
use super::plans::{CandidatePrepared, PlanRequest, CANDIDATE_DIAMETER_RANGE_MM};
use super::setup::{resolve as resolve_path_job, PathJobRefs, PathSetup, Resolved, MAX_FEED_PER_STANDARD};
use crate::core::conditions::{feed_mm_min, CuttingConditions};
use crate::core::operation::Operation;
use crate::core::process::stair_conditions;
use crate::core::tool::{EndMill, ToolType};
use crate::service::error::{ApiError, Validator};
use crate::service::lookup;
use crate::service::resources::tools::Tool;
use crate::service::store::Pool;

/// A candidate tool and the request field that named it (none: the default range, whose
/// tools without the data to plan with are skipped rather than refused).
#[derive(Debug, Clone, PartialEq)]
pub struct Pick {
    pub tool_id: i64,
    pub field: Option<String>,
}

/// The candidate tools of a request: the default tool of `tool_type` of every diameter of
/// `diameters_mm`, then the tools of `tool_ids` (a tool named twice is one candidate); or,
/// when neither is given, the default tool of every diameter of the range. Every unknown
/// diameter or id, and every ball end mill among the ids, is added to `faults`; a diameter
/// or id an earlier stage refused is not looked up.
pub async fn pick(
    pool: &Pool,
    request: &PlanRequest,
    tool_type: ToolType,
    faults: &mut Validator,
) -> Result<Option<Vec<Pick>>, ApiError> {
    if faults.refused_any(&["diameters_mm", "tool_ids"]) {
        return Ok(None);
    }
    if request.diameters_mm.is_none() && request.tool_ids.is_none() {
        let ids = sqlx::query_scalar::<_, i64>(
            "SELECT id FROM tools WHERE tool_type = $1 AND is_default = 1 AND diameter_mm BETWEEN $2 AND $3
             ORDER BY diameter_mm, id",
        )
        .bind(tool_type.as_str())
        .bind(CANDIDATE_DIAMETER_RANGE_MM.0)
        .bind(CANDIDATE_DIAMETER_RANGE_MM.1)
        .fetch_all(pool)
        .await?;
        return Ok(Some(ids.into_iter().map(|tool_id| Pick { tool_id, field: None }).collect()));
    }
    let mut picks: Vec<Pick> = Vec::new();
    let mut add = |tool_id: i64, field: String| {
        if picks.iter().all(|p| p.tool_id != tool_id) {
            picks.push(Pick { tool_id, field: Some(field) });
        }
    };
    for (i, d) in request.diameters_mm.iter().flatten().enumerate() {
        let field = format!("diameters_mm[{i}]");
        if faults.refused(&field) {
            continue;
        }
        match lookup::default_tool(pool, tool_type, *d).await {
            Ok(tool) => add(tool.id, field),
            Err(ApiError::Validation(errors)) => errors.into_iter().for_each(|e| faults.fail(field.clone(), e.reason)),
            Err(other) => return Err(other),
        }
    }
    for (i, id) in request.tool_ids.iter().flatten().enumerate() {
        let field = format!("tool_ids[{i}]");
        if faults.refused(&field) {
            continue;
        }
        let tool = sqlx::query_as::<_, Tool>("SELECT * FROM tools WHERE id = $1").bind(id).fetch_optional(pool).await?;
        match tool {
            None => faults.fail(field, format!("no tool with id {id}")),
            Some(t) if t.data.tool_type == ToolType::Ball => faults.fail(
                field,
                format!("tool {id} ({}) is a ball end mill: the proposed strategy needs flat end mills", t.data.name),
            ),
            Some(t) => add(t.id, field),
        }
    }
    Ok(Some(picks))
}

/// The depths a request gives the step, the rest from the tool's standard side cut.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct StairDepths {
    pub axial_depth_mm: Option<f64>,
    pub radial_depth_mm: Option<f64>,
}

impl StairDepths {
    /// The step's conditions for `tool`, whose standard side cut is `standard` (see
    /// [`stair_conditions`]).
    pub fn conditions(&self, tool: &EndMill, standard: CuttingConditions) -> CuttingConditions {
        stair_conditions(tool, standard, self.axial_depth_mm, self.radial_depth_mm)
    }
}

/// Where a tool's cutting conditions come from.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ConditionsFrom {
    /// A candidate of the plan: its rough, intermediate-rough and trochoidal-grooving rows.
    Plan,
    /// The stair-step roughing: the tool's standard side cut's S and fz, at these depths.
    StairStep(StairDepths),
}

/// Resolves one tool; `Err(reason)` when the database lacks what it needs.
pub async fn resolve(
    pool: &Pool,
    tool_id: i64,
    material_id: i64,
    machine_id: i64,
    default_tool_price: f64,
    from: ConditionsFrom,
) -> Result<Result<(CandidatePrepared, PathSetup), String>, ApiError> {
    let refs = PathJobRefs {
        tool_id: Some(tool_id),
        tool_type: None,
        diameter_mm: None,
        material_id: Some(material_id),
        material: None,
        machine_id: Some(machine_id),
        spindle_rpm: None,
    };
    let mut found = Validator::new();
    let resolved = resolve_path_job(pool, &refs, &mut found).await?;
    found.finish()?;
    let Some(Resolved { prepared: base, standard, machine_max_feed_mm_min, .. }) = resolved else {
        return Err(ApiError::Internal(format!("tool {tool_id} resolved to nothing")));
    };
    let name = base.tool.name.clone();
    let row = |op: Operation| async move { lookup::standard_conditions(pool, tool_id, material_id, op).await };
    let (Some(standard), Some(model)) = (standard, base.force_model.as_ref()) else {
        return Ok(Err(format!("{name}: no standard side-cutting conditions or force model")));
    };
    let tool: EndMill = base.tool.geometry.into();
    let s = standard.data;
    let (roughing, intermediate, grooving) = match from {
        ConditionsFrom::Plan => {
            let (Some(rough), Some(inter), Some(groove)) = (
                row(Operation::RoughSideCutting).await?,
                row(Operation::IntermediateRoughSideCutting).await?,
                row(Operation::TrochoidalGrooving).await?,
            ) else {
                return Ok(Err(format!(
                    "{name}: needs rough, intermediate-rough and trochoidal-grooving conditions in {}",
                    base.material.name
                )));
            };
            (rough.data.conditions(), inter.data.conditions(), groove.data.conditions())
        }
        ConditionsFrom::StairStep(depths) => {
            let c = depths.conditions(&tool, s.conditions());
            (c, c, c)
        }
    };
    let Some(life) = lookup::tool_life(pool, tool_id, material_id).await? else {
        return Ok(Err(format!("{name}: no tool-life data in {}", base.material.name)));
    };
    // The stair step's rings are contour-parallel roughing in thin layers, which is what a
    // ball's standard row describes: its F* and the cut its life refers to are that cut's.
    let contour_parallel = matches!(from, ConditionsFrom::StairStep(_));
    let cut = standard_cut_off_runtime(tool, s.conditions(), Some(model.model), contour_parallel).await?;
    let (arc_mm, standard_force_n) = (cut.arc_length_mm, cut.force_n.unwrap_or_default());
    let standard_feed = feed_mm_min(s.fz_mm, tool.flutes, s.spindle_rpm);
    let price = sqlx::query_scalar::<_, Option<f64>>("SELECT price FROM tools WHERE id = $1")
        .bind(tool_id)
        .fetch_one(pool)
        .await?;
    let candidate = CandidatePrepared {
        tool_id,
        name,
        tool,
        roughing,
        intermediate,
        grooving,
        force_model: model.model,
        standard_force_n,
        life_m: life.data.life_m,
        gamma_table: life.data.gamma_table.iter().map(|g| (g.0, g.1)).collect(),
        force_exponent: life.data.force_exponent,
        standard_arc_length_mm: arc_mm,
        standard_fz_mm: s.fz_mm,
        min_feed_mm_min: feed_mm_min(s.fz_min_mm, tool.flutes, s.spindle_rpm),
        max_feed_mm_min: (MAX_FEED_PER_STANDARD * standard_feed).min(machine_max_feed_mm_min),
        tool_price: price.unwrap_or(default_tool_price),
    };
    Ok(Ok((candidate, base)))
}
