//! The `conditions` job: recommended cutting conditions for a material, tool and
//! operation, with the engagement, chip thickness, arc length and force the models
//! predict for them (seed 002, subsystem "decision of cutting conditions").

use crate::core::conditions::{evaluate_conditions, CuttingConditions};
use crate::core::operation::Operation;
use crate::core::progress::Progress;
use crate::core::tool::ToolType;
use crate::core::CoreError;
use crate::service::error::{ApiError, Validator};
use crate::service::jobs::kind::{JobKindSpec, Produced, Submission};
use crate::service::jobs::model::JobKind;
use crate::service::jobs::setup::{material_and_tool, path_job_refs, ForceModelRef, NamedRef, StandardRef, ToolRef};
use crate::service::lookup;
use crate::service::resources::Source;
use crate::service::store::Pool;
use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

/// The operation used when a request names none.
pub const DEFAULT_OPERATION: Operation = Operation::StandardSideCutting;

/// What to recommend conditions for. Name the tool by `tool_id`, or by `tool_type` and
/// `diameter_mm`; the material by `material_id` or `material` (default SKD61).
#[derive(Debug, Clone, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
#[schema(example = json!({"tool_type": "square", "diameter_mm": 10.0, "operation": "standard_side_cutting"}))]
pub struct ConditionsRequest {
    pub material_id: Option<i64>,
    /// Material name (default SKD61).
    pub material: Option<String>,
    pub tool_id: Option<i64>,
    pub tool_type: Option<ToolType>,
    /// Tool diameter, mm.
    pub diameter_mm: Option<f64>,
    /// Default standard_side_cutting.
    pub operation: Option<Operation>,
    /// Override the standard spindle speed, min⁻¹.
    pub spindle_rpm: Option<f64>,
    /// Override the standard feed per tooth, mm.
    pub fz_mm: Option<f64>,
    /// Override the standard radial depth, mm.
    pub rd_mm: Option<f64>,
    /// Override the standard axial depth, mm.
    pub ad_mm: Option<f64>,
}

/// The material, tool, conditions and force model a request resolved to: a snapshot,
/// so the job's answer does not change if the database does.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct ConditionsPrepared {
    pub material: NamedRef,
    pub tool: ToolRef,
    pub operation: Operation,
    pub standard: StandardRef,
    pub conditions: CuttingConditions,
    pub overridden: Vec<String>,
    pub force_model: Option<ForceModelRef>,
}

/// Checks the values of the request that need no database.
pub fn check_request(request: &ConditionsRequest, v: &mut Validator) {
    for (field, value) in [
        ("spindle_rpm", request.spindle_rpm),
        ("fz_mm", request.fz_mm),
        ("rd_mm", request.rd_mm),
        ("ad_mm", request.ad_mm),
        ("diameter_mm", request.diameter_mm),
    ] {
        if let Some(x) = value {
            v.positive(field, x);
        }
    }
    if request.tool_id.is_some() && (request.tool_type.is_some() || request.diameter_mm.is_some()) {
        v.fail("tool_id", "give tool_id or tool_type with diameter_mm, not both");
    }
    if request.material_id.is_some() && request.material.is_some() {
        v.fail("material_id", "give material_id or material, not both");
    }
}

/// Resolves the request against the database, adding every fault to `faults`.
pub async fn prepare(
    pool: &Pool,
    request: ConditionsRequest,
    faults: &mut Validator,
) -> Result<Option<ConditionsPrepared>, ApiError> {
    let refs = path_job_refs!(request, None, None);
    let (Some(material), Some(tool)) = material_and_tool(pool, &refs, faults).await? else {
        return Ok(None);
    };
    if faults.refused("operation") {
        return Ok(None);
    }
    let operation = request.operation.unwrap_or(DEFAULT_OPERATION);
    let Some(standard) = lookup::standard_conditions(pool, tool.id, material.id, operation).await? else {
        faults.fail(
            "operation",
            format!(
                "no standard conditions for {} with tool {} ({}) in {}: add them at /v1/conditions/standard",
                operation.as_str(),
                tool.id,
                tool.data.name,
                material.data.name
            ),
        );
        return Ok(None);
    };
    let base = standard.data.conditions();
    let mut overridden = Vec::new();
    let mut pick = |name: &str, given: Option<f64>, standard: f64| match given {
        Some(x) => {
            overridden.push(name.to_string());
            x
        }
        None => standard,
    };
    let conditions = CuttingConditions {
        spindle_rpm: pick("spindle_rpm", request.spindle_rpm, base.spindle_rpm),
        fz_mm: pick("fz_mm", request.fz_mm, base.fz_mm),
        rd_mm: pick("rd_mm", request.rd_mm, base.rd_mm),
        ad_mm: pick("ad_mm", request.ad_mm, base.ad_mm),
    };
    let force_model = lookup::force_model(pool, tool.id, material.id).await?.map(|m| ForceModelRef::of_tool(m, &tool));
    let tool_ref = ToolRef::from(&tool);
    let geometry = tool_ref.geometry;
    // Refuse now what the computation would refuse later (on a request without faults: a
    // refused override would be checked at its standard value).
    if !faults.has_errors() {
        faults.take(evaluate_conditions(&geometry.into(), conditions, force_model.as_ref().map(|f| &f.model)))?;
    }
    Ok(Some(ConditionsPrepared {
        material: NamedRef { id: material.id, name: material.data.name },
        tool: tool_ref,
        operation,
        standard: StandardRef {
            id: standard.id,
            source: standard.data.source,
            reference: standard.data.reference,
            fz_min_mm: standard.data.fz_min_mm,
            fz_max_mm: standard.data.fz_max_mm,
            ad_last_layer_mm: standard.data.ad_last_layer_mm,
            notes: standard.data.notes,
        },
        conditions,
        overridden,
        force_model,
    }))
}

/// The recommended conditions.
#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct RecommendedConditions {
    /// Spindle speed S, min⁻¹.
    pub spindle_rpm: f64,
    /// Feed per tooth fz, mm/tooth.
    pub fz_mm: f64,
    /// Feed rate F = fz·z·S, mm/min.
    pub feed_mm_min: f64,
    /// Radial depth of cut Rd, mm.
    pub rd_mm: f64,
    /// Axial depth of cut Ad, mm.
    pub ad_mm: f64,
    /// Axial depth on the last layer, mm.
    pub ad_last_layer_mm: Option<f64>,
    /// Cutting speed V = π·D·S/1000, m/min.
    pub cutting_speed_m_min: f64,
    /// Diameter in contact (a ball end mill at Ad < D/2 cuts on a smaller circle), mm.
    pub effective_diameter_mm: f64,
    /// Cutting speed at the effective diameter, m/min.
    pub effective_cutting_speed_m_min: f64,
    /// Feed-optimisation bounds, mm/tooth.
    pub fz_min_mm: f64,
    pub fz_max_mm: Option<f64>,
    /// Which values the request set instead of the standard.
    pub overridden: Vec<String>,
}

/// What the engagement model predicts for a straight cut (MODEL.md §2).
#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct EngagementPrediction {
    /// Engagement angle α, deg.
    pub angle_deg: f64,
    /// Maximum undeformed chip thickness t_m, µm.
    pub max_chip_thickness_um: f64,
    /// Engagement arc length L, mm.
    pub arc_length_mm: f64,
}

/// What the force model predicts (seed 002 Eq. 1).
#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct ForcePrediction {
    /// XY cutting force, N, scaled to the axial depth.
    pub fxy_n: f64,
    /// Coded chip thickness X1.
    pub x1: f64,
    /// Coded arc length X2.
    pub x2: f64,
    pub within_design_region: bool,
    pub force_model_id: i64,
    pub source: Source,
    pub reference: String,
}

/// The answer of a `conditions` job.
#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct ConditionsResult {
    pub material: NamedRef,
    pub tool: ToolRef,
    pub operation: Operation,
    pub conditions: RecommendedConditions,
    pub standard_conditions: StandardRef,
    /// Null for ball end mills (the side-milling model does not apply).
    pub engagement: Option<EngagementPrediction>,
    /// Null when no force model applies.
    pub force: Option<ForcePrediction>,
    pub warnings: Vec<String>,
}

/// Runs the computation on a prepared request.
pub fn run(prepared: ConditionsPrepared) -> Result<ConditionsResult, CoreError> {
    let model = prepared.force_model.as_ref();
    let report = evaluate_conditions(&prepared.tool.geometry.into(), prepared.conditions, model.map(|f| &f.model))?;
    Ok(ConditionsResult {
        conditions: RecommendedConditions {
            spindle_rpm: report.conditions.spindle_rpm,
            fz_mm: report.conditions.fz_mm,
            feed_mm_min: report.feed_mm_min,
            rd_mm: report.conditions.rd_mm,
            ad_mm: report.conditions.ad_mm,
            ad_last_layer_mm: prepared.standard.ad_last_layer_mm,
            cutting_speed_m_min: report.cutting_speed_m_min,
            effective_diameter_mm: report.effective_diameter_mm,
            effective_cutting_speed_m_min: report.effective_cutting_speed_m_min,
            fz_min_mm: prepared.standard.fz_min_mm,
            fz_max_mm: prepared.standard.fz_max_mm,
            overridden: prepared.overridden,
        },
        engagement: report.engagement.map(|e| EngagementPrediction {
            angle_deg: e.angle_deg,
            max_chip_thickness_um: e.max_chip_thickness_um,
            arc_length_mm: e.arc_length_mm,
        }),
        force: report.force.zip(model).map(|(f, m)| ForcePrediction {
            fxy_n: f.fxy_n,
            x1: f.x1,
            x2: f.x2,
            within_design_region: f.within_design_region,
            force_model_id: m.id,
            source: m.source,
            reference: m.reference.clone(),
        }),
        warnings: report.warnings,
        material: prepared.material,
        tool: prepared.tool,
        operation: prepared.operation,
        standard_conditions: prepared.standard,
    })
}

/// The `conditions` job kind.
pub struct Conditions;

impl JobKindSpec for Conditions {
    const KIND: JobKind = JobKind::Conditions;
    const PATH: &'static str = "/v1/conditions";
    const OPERATION_ID: &'static str = "recommendConditions";
    const SUMMARY: &'static str = "Recommends cutting conditions (job kind `conditions`).";
    const DESCRIPTION: &'static str = "For a material (default SKD61), a tool (id, or type + diameter) and an operation (default standard_side_cutting): S, fz, F, Rd, Ad and the cutting speed from the database, with the engagement angle, t_m, L and XY force the models predict.";
    const REFUSES: &'static str =
        "Every fault of the request, in one problem: each refused field, and each row it names that is not in the database (tool, material, standard conditions)";
    type Request = ConditionsRequest;
    type Prepared = ConditionsPrepared;
    type Output = ConditionsResult;

    fn check(request: &ConditionsRequest, v: &mut Validator) {
        check_request(request, v)
    }

    async fn prepare(
        submission: &Submission<'_>,
        request: ConditionsRequest,
        faults: &mut Validator,
    ) -> Result<Option<ConditionsPrepared>, ApiError> {
        prepare(submission.pool, request, faults).await
    }

    fn run(
        _request: ConditionsRequest,
        prepared: ConditionsPrepared,
        _progress: &dyn Progress,
        _stock_memory_bytes: usize,
    ) -> Result<Produced<ConditionsResult>, CoreError> {
        Ok(Produced::result(run(prepared)?))
    }
}
