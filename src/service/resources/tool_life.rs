//! Tool-life data: `/v1/tool-life` (seed 002 Eq. 2-3, seed 003; MODEL.md §9).

use super::{Reference, Resource, Source, SqlValue, ToolMaterialFilter};
use crate::service::error::Validator;
use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

/// Tool life the consumption model accepts, m of cut (a millimetre to 10 000 km).
const MIN_LIFE_M: f64 = 1e-3;
const MAX_LIFE_M: f64 = 1e7;
/// Largest exponent of the force in the life model.
const MAX_FORCE_EXPONENT: f64 = 20.0;

/// Largest engagement angle, deg.
const MAX_ENGAGEMENT_DEG: f64 = 180.0;

/// One point of the engagement-angle correction γ(α) (seed 002 Eq. 3).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct GammaPoint(
    /// Engagement angle α, deg.
    pub f64,
    /// Wear factor γ at that angle (1 = as the standard cut).
    pub f64,
);

impl utoipa::PartialSchema for GammaPoint {
    fn schema() -> utoipa::openapi::RefOr<utoipa::openapi::schema::Schema> {
        use utoipa::openapi::schema::{ArrayBuilder, ArrayItems, ObjectBuilder, Type};
        let angle = ObjectBuilder::new()
            .schema_type(Type::Number)
            .minimum(Some(0.0))
            .maximum(Some(MAX_ENGAGEMENT_DEG))
            .description(Some("Engagement angle α, deg"));
        let factor = ObjectBuilder::new()
            .schema_type(Type::Number)
            .exclusive_minimum(Some(0.0))
            .description(Some("Wear factor γ (1 = as the standard cut)"));
        ArrayBuilder::new()
            .prefix_items([angle, factor])
            .items(ArrayItems::False)
            .min_items(Some(2))
            .max_items(Some(2))
            .description(Some("[engagement angle α in deg, wear factor γ]"))
            .examples([serde_json::json!([40.0, 1.0])])
            .into()
    }
}

impl ToSchema for GammaPoint {
    fn name() -> std::borrow::Cow<'static, str> {
        std::borrow::Cow::Borrowed("GammaPoint")
    }
}

/// A tool's life in a material and how engagement and force shorten it.
#[derive(Debug, Clone, Serialize, Deserialize, sqlx::FromRow, ToSchema)]
#[serde(deny_unknown_fields)]
#[schema(example = json!({"tool_id": 7, "material_id": 1, "life_m": 320.0, "gamma_table": [[0, 1], [40, 1], [50, 2], [60, 4], [90, 8], [180, 12]], "force_exponent": 2.4}))]
pub struct ToolLifeData {
    pub tool_id: i64,
    pub material_id: i64,
    /// Life as machined length at the standard straight conditions, m.
    #[schema(minimum = 0.001, maximum = 10000000)]
    pub life_m: f64,
    /// γ(α) as `[angle_deg, factor]` pairs, angles increasing from 0 to at most 180;
    /// linear in between.
    #[sqlx(try_from = "crate::service::store::JsonText<Vec<GammaPoint>>")]
    #[schema(min_items = 1)]
    pub gamma_table: Vec<GammaPoint>,
    /// Exponent k of the force factor φ = (F/F*)^k above the target force.
    #[schema(minimum = 0, maximum = 20)]
    pub force_exponent: f64,
    #[serde(default = "Source::user")]
    pub source: Source,
    #[serde(default)]
    pub reference: String,
}

impl Resource for ToolLifeData {
    const TABLE: &'static str = "tool_life";
    const SINGULAR: &'static str = "tool-life row";
    const COLUMNS: &'static [&'static str] =
        &["tool_id", "material_id", "life_m", "gamma_table", "force_exponent", "source", "reference"];

    fn values(&self) -> Vec<SqlValue> {
        vec![
            self.tool_id.into(),
            self.material_id.into(),
            self.life_m.into(),
            serde_json::to_string(&self.gamma_table).unwrap_or_default().into(),
            self.force_exponent.into(),
            self.source.as_str().into(),
            self.reference.clone().into(),
        ]
    }

    fn validate(&self, v: &mut Validator) {
        v.within("life_m", self.life_m, MIN_LIFE_M, MAX_LIFE_M);
        v.within("force_exponent", self.force_exponent, 0.0, MAX_FORCE_EXPONENT);
        v.check(!self.gamma_table.is_empty(), "gamma_table", "needs at least one point");
        let mut previous = f64::NEG_INFINITY;
        for (i, GammaPoint(angle, factor)) in self.gamma_table.iter().enumerate() {
            v.within(&format!("gamma_table[{i}][0]"), *angle, 0.0, MAX_ENGAGEMENT_DEG);
            v.positive(&format!("gamma_table[{i}][1]"), *factor);
            v.check(*angle > previous, &format!("gamma_table[{i}][0]"), "angles must increase");
            previous = *angle;
        }
    }

    fn references(&self) -> Vec<Reference> {
        vec![
            Reference { field: "tool_id", table: "tools", id: self.tool_id },
            Reference { field: "material_id", table: "materials", id: self.material_id },
        ]
    }
}

crate::record!(
    /// Tool-life data of one tool in one material.
    ToolLife,
    ToolLifeData
);

crate::crud_api!(
    module: api,
    record: ToolLife,
    data: ToolLifeData,
    filter: ToolMaterialFilter,
    collection: "/v1/tool-life",
    item: "/v1/tool-life/{id}",
    tag: "database",
    ids: ["listToolLife", "getToolLife", "createToolLife", "replaceToolLife", "updateToolLife", "deleteToolLife"],
);

impl From<crate::service::store::JsonText<Vec<GammaPoint>>> for Vec<GammaPoint> {
    fn from(json: crate::service::store::JsonText<Vec<GammaPoint>>) -> Vec<GammaPoint> {
        json.0
    }
}
