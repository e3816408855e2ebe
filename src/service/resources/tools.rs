//! End mills: `/v1/tools`.

use super::routes::eq;
use super::{ListFilter, PageRequest, Reference, Resource, Source, SqlValue, DIAMETER_FILTER_TOLERANCE_MM};
use crate::core::tool::{EndMill, ToolType};
use crate::service::error::Validator;
use serde::{Deserialize, Serialize};
use utoipa::{IntoParams, ToSchema};

/// How far a ball end mill's corner radius may differ from D/2, mm.
const BALL_RADIUS_TOLERANCE_MM: f64 = 1e-6;
/// The end mills the models are meant for, mm (0.1 mm micro end mills to 100 mm).
const MIN_DIAMETER_MM: f64 = 0.1;
const MAX_DIAMETER_MM: f64 = 100.0;
/// Most flutes an end mill has.
const MAX_FLUTES: u32 = 16;
/// Longest flute, mm.
const MAX_FLUTE_LENGTH_MM: f64 = 1000.0;
/// Highest price of one tool (any currency): beyond it a cost is no longer meaningful.
pub const MAX_PRICE: f64 = 1e7;

/// An end mill's data.
#[derive(Debug, Clone, Serialize, Deserialize, sqlx::FromRow, ToSchema)]
#[serde(deny_unknown_fields)]
#[schema(example = json!({"name": "square D10 z4 shop", "tool_type": "square", "diameter_mm": 10.0, "flutes": 4, "corner_radius_mm": 0.0, "coating": "(Al,Ti)N", "substrate": "micro-grain carbide", "price": 95.0}))]
pub struct ToolData {
    /// Unique name.
    #[schema(min_length = 1, pattern = r"\S")]
    pub name: String,
    #[sqlx(try_from = "String")]
    pub tool_type: ToolType,
    /// Diameter D, mm.
    #[schema(minimum = 0.1, maximum = 100)]
    pub diameter_mm: f64,
    /// Number of flutes z.
    #[schema(minimum = 1, maximum = 16)]
    pub flutes: u32,
    /// Corner radius, mm. Square end mill: 0 (the default when left out). Radius end mill:
    /// required, between 0 and D/2. Ball end mill: D/2, which it takes when left out (when
    /// given it must be D/2). A stored tool always has it.
    #[serde(default)]
    #[schema(minimum = 0)]
    pub corner_radius_mm: Option<f64>,
    /// Length of cut, mm.
    #[serde(default)]
    #[schema(exclusive_minimum = 0, maximum = 1000)]
    pub flute_length_mm: Option<f64>,
    #[serde(default)]
    pub coating: String,
    #[serde(default)]
    pub substrate: String,
    /// Price of one tool in the cost rates' currency; the cost rates' default when null.
    #[serde(default)]
    #[schema(minimum = 0, maximum = 10000000)]
    pub price: Option<f64>,
    #[serde(default = "Source::user")]
    pub source: Source,
    /// Where the values come from (paper file and table, or the rule used).
    #[serde(default)]
    pub reference: String,
}

/// The corner radius an end mill of `tool_type` and diameter `D` has when none is given:
/// 0 for a square end mill, D/2 for a ball; a radius end mill has none of its own.
fn default_corner_radius_mm(tool_type: ToolType, diameter_mm: f64) -> Option<f64> {
    match tool_type {
        ToolType::Square => Some(0.0),
        ToolType::Radius => None,
        ToolType::Ball => Some(diameter_mm / 2.0),
    }
}

impl ToolData {
    /// The corner radius given, else its shape's ([`default_corner_radius_mm`]); 0 for a
    /// radius end mill without one, which validation refuses, so never for a stored tool.
    pub fn resolved_corner_radius_mm(&self) -> f64 {
        self.corner_radius_mm.or(default_corner_radius_mm(self.tool_type, self.diameter_mm)).unwrap_or(0.0)
    }

    pub fn end_mill(&self) -> EndMill {
        EndMill {
            tool_type: self.tool_type,
            diameter_mm: self.diameter_mm,
            flutes: self.flutes,
            corner_radius_mm: self.resolved_corner_radius_mm(),
        }
    }
}

impl Resource for ToolData {
    const TABLE: &'static str = "tools";
    const SINGULAR: &'static str = "tool";
    const COLUMNS: &'static [&'static str] = &[
        "name",
        "tool_type",
        "diameter_mm",
        "flutes",
        "corner_radius_mm",
        "flute_length_mm",
        "coating",
        "substrate",
        "price",
        "source",
        "reference",
    ];
    const REFERENCED_BY: &'static [(&'static str, &'static str, &'static str)] = &[
        ("standard_conditions", "tool_id", "standard conditions"),
        ("force_models", "tool_id", "force models"),
        ("tool_life", "tool_id", "tool-life rows"),
    ];

    fn values(&self) -> Vec<SqlValue> {
        vec![
            self.name.clone().into(),
            self.tool_type.as_str().into(),
            self.diameter_mm.into(),
            i64::from(self.flutes).into(),
            self.resolved_corner_radius_mm().into(),
            self.flute_length_mm.into(),
            self.coating.clone().into(),
            self.substrate.clone().into(),
            self.price.into(),
            self.source.as_str().into(),
            self.reference.clone().into(),
        ]
    }

    fn validate(&self, v: &mut Validator) {
        v.not_blank("name", &self.name);
        v.within("diameter_mm", self.diameter_mm, MIN_DIAMETER_MM, MAX_DIAMETER_MM);
        v.check((1..=MAX_FLUTES).contains(&self.flutes), "flutes", format!("must be 1 to {MAX_FLUTES}"));
        if let Some(rc) = self.corner_radius_mm {
            v.non_negative("corner_radius_mm", rc);
        }
        if let Some(l) = self.flute_length_mm {
            v.above_and_at_most("flute_length_mm", l, 0.0, MAX_FLUTE_LENGTH_MM);
        }
        if let Some(p) = self.price {
            v.within("price", p, 0.0, MAX_PRICE);
        }
        if v.has_errors() {
            return;
        }
        let half = self.diameter_mm / 2.0;
        let rc = self.resolved_corner_radius_mm();
        match self.tool_type {
            ToolType::Square => v.check(
                rc <= BALL_RADIUS_TOLERANCE_MM,
                "corner_radius_mm",
                "a square end mill has no corner radius: use tool_type radius",
            ),
            ToolType::Radius if self.corner_radius_mm.is_none() => v.fail(
                "corner_radius_mm",
                format!("is required for a radius end mill: 0 < corner radius < D/2 = {half}"),
            ),
            ToolType::Radius => v.check(
                rc > BALL_RADIUS_TOLERANCE_MM && rc < half - BALL_RADIUS_TOLERANCE_MM,
                "corner_radius_mm",
                format!("a radius end mill needs 0 < corner radius < D/2 = {half}"),
            ),
            ToolType::Ball => v.check(
                (rc - half).abs() <= BALL_RADIUS_TOLERANCE_MM,
                "corner_radius_mm",
                format!("a ball end mill's corner radius is D/2 = {half} (leave it out to take D/2)"),
            ),
        }
    }

    fn references(&self) -> Vec<Reference> {
        Vec::new()
    }
}

crate::record!(
    /// An end mill.
    Tool,
    ToolData
);

/// Filters of `GET /v1/tools`.
#[derive(Debug, Deserialize, IntoParams)]
#[serde(deny_unknown_fields)]
#[into_params(parameter_in = Query)]
pub struct ToolFilter {
    /// Only tools of this shape.
    #[param(value_type = Option<ToolType>)]
    pub tool_type: Option<String>,
    /// Only tools of this diameter, mm.
    #[param(exclusive_minimum = 0)]
    pub diameter_mm: Option<f64>,
    /// Only tools with standard conditions for this material id.
    pub material_id: Option<i64>,
    /// Only rows of this source.
    pub source: Option<Source>,
    pub limit: Option<i64>,
    pub offset: Option<i64>,
}

impl ListFilter for ToolFilter {
    fn conditions(&self) -> Vec<(String, Vec<SqlValue>)> {
        [
            eq("tool_type", self.tool_type.clone()),
            self.diameter_mm.map(|d| {
                ("abs(diameter_mm - ?) <= ?".to_string(), vec![d.into(), DIAMETER_FILTER_TOLERANCE_MM.into()])
            }),
            self.material_id.map(|m| {
                ("id IN (SELECT tool_id FROM standard_conditions WHERE material_id = ?)".to_string(), vec![m.into()])
            }),
            eq("source", self.source.map(Source::as_str)),
        ]
        .into_iter()
        .flatten()
        .collect()
    }

    fn page(&self) -> PageRequest {
        PageRequest { limit: self.limit, offset: self.offset }
    }

    fn validate(&self, v: &mut Validator) {
        if let Some(d) = self.diameter_mm {
            v.positive("diameter_mm", d);
        }
        if let Some(t) = &self.tool_type {
            v.check(ToolType::parse(t).is_some(), "tool_type", "must be square, radius or ball");
        }
    }
}

crate::crud_api!(
    module: api,
    record: Tool,
    data: ToolData,
    filter: ToolFilter,
    collection: "/v1/tools",
    item: "/v1/tools/{id}",
    tag: "database",
    ids: ["listTools", "getTool", "createTool", "replaceTool", "updateTool", "deleteTool"],
);
