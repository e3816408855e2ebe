//! End mills: `/v1/tools`.

use super::routes::eq;
use super::{Hook, ListFilter, PageRequest, Reference, Resource, Source, SqlValue, DIAMETER_FILTER_TOLERANCE_MM};
use crate::core::tool::{EndMill, ToolType};
use crate::service::error::{ApiError, Validator};
use crate::service::store::{numbered, Conn};
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
    #[sqlx(try_from = "i64")]
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
    /// The default tool of its type and diameter: a request that names a tool by
    /// `tool_type` and `diameter_mm` (and a plan's `diameters_mm`) takes it. One per type
    /// and diameter; the seeded tools are the defaults. `true` makes this tool the default
    /// and the previous one an ordinary tool, in the same transaction; `false` leaves the
    /// type and diameter without a default (requests by size are then refused until one is
    /// chosen). Left out: a new tool is the default when it is the first of its type and
    /// diameter, an updated one keeps its flag (or, moved to another type or diameter, is
    /// the default there when that one had none). When the default is deleted or moved
    /// away, the oldest remaining tool of its type and diameter becomes the default.
    #[serde(default)]
    #[sqlx(rename = "is_default", try_from = "crate::service::store::Flag")]
    pub default: Option<bool>,
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
        "is_default",
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
            // Written clear: `after_write` sets it once the other default of the type and
            // diameter is cleared (the unique index allows one default at every moment).
            0i64.into(),
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

    const FLAGS: &'static [&'static str] = &["default"];

    fn after_write<'a>(conn: &'a mut Conn, id: i64, before: Option<&'a Self>, data: &'a Self) -> Hook<'a> {
        Box::pin(async move {
            let moved = before.is_some_and(|b| !b.same_combination(data));
            let was_default = before.is_some_and(|b| b.default == Some(true));
            let default = match data.default {
                Some(flag) => flag,
                None if before.is_some() && !moved => was_default,
                None => !has_default(conn, data).await?,
            };
            if default {
                make_default(conn, id, data).await?;
            }
            match before {
                Some(b) if moved && was_default => promote_oldest(conn, b).await,
                _ => Ok(()),
            }
        })
    }

    fn after_delete<'a>(conn: &'a mut Conn, _id: i64, deleted: &'a Self) -> Hook<'a> {
        Box::pin(async move {
            if deleted.default == Some(true) {
                promote_oldest(conn, deleted).await?;
            }
            Ok(())
        })
    }
}

/// The SQL condition "of the tool's type and diameter" (two values: the type, the diameter):
/// diameters that agree to 6 decimals (1 nm) are one diameter, as in the unique index of
/// one default per type and diameter (migrations/0012_tool_defaults.sql).
pub const SAME_TYPE_AND_DIAMETER_SQL: &str = "tool_type = ? AND round(diameter_mm, 6) = round(?, 6)";
/// 10^6: the rounding of [`SAME_TYPE_AND_DIAMETER_SQL`], in Rust.
const DIAMETER_ROUNDING: f64 = 1e6;

impl ToolData {
    /// `true` when both tools share a type and diameter, and so a default.
    fn same_combination(&self, other: &ToolData) -> bool {
        let key = |d: f64| (d * DIAMETER_ROUNDING).round() as i64;
        self.tool_type == other.tool_type && key(self.diameter_mm) == key(other.diameter_mm)
    }
}

/// `true` when another tool of `data`'s type and diameter is the default.
async fn has_default(conn: &mut Conn, data: &ToolData) -> Result<bool, ApiError> {
    let sql = format!("SELECT EXISTS (SELECT 1 FROM tools WHERE {SAME_TYPE_AND_DIAMETER_SQL} AND is_default = 1)");
    Ok(sqlx::query_scalar::<_, crate::service::store::Flag>(numbered(&sql))
        .bind(data.tool_type.as_str())
        .bind(data.diameter_mm)
        .fetch_one(&mut *conn)
        .await?
        .0)
}

/// Makes the tool `id` the default of its type and diameter, clearing the previous one.
async fn make_default(conn: &mut Conn, id: i64, data: &ToolData) -> Result<(), ApiError> {
    let clear = format!(
        "UPDATE tools SET is_default = 0, updated_at = strftime('%Y-%m-%dT%H:%M:%fZ', 'now')
         WHERE {SAME_TYPE_AND_DIAMETER_SQL} AND is_default = 1 AND id <> ?"
    );
    sqlx::query(numbered(&clear))
        .bind(data.tool_type.as_str())
        .bind(data.diameter_mm)
        .bind(id)
        .execute(&mut *conn)
        .await?;
    sqlx::query("UPDATE tools SET is_default = 1 WHERE id = $1").bind(id).execute(&mut *conn).await?;
    Ok(())
}

/// Makes the oldest tool of `data`'s type and diameter the default, when none is.
async fn promote_oldest(conn: &mut Conn, data: &ToolData) -> Result<(), ApiError> {
    let sql = format!(
        "UPDATE tools SET is_default = 1, updated_at = strftime('%Y-%m-%dT%H:%M:%fZ', 'now')
         WHERE id = (SELECT id FROM tools WHERE {SAME_TYPE_AND_DIAMETER_SQL} ORDER BY created_at, id LIMIT 1)
           AND NOT EXISTS (SELECT 1 FROM tools WHERE {SAME_TYPE_AND_DIAMETER_SQL} AND is_default = 1)"
    );
    sqlx::query(numbered(&sql))
        .bind(data.tool_type.as_str())
        .bind(data.diameter_mm)
        .bind(data.tool_type.as_str())
        .bind(data.diameter_mm)
        .execute(&mut *conn)
        .await?;
    Ok(())
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
    /// `true`: only the default tool of every type and diameter; `false`: only the others.
    pub default: Option<bool>,
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
            eq("is_default", self.default.map(i64::from)),
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
