//! The cutting-condition database as REST resources: one file per table, all sharing
//! the generic create/read/update/delete of [`crud`] and the routes of [`crud_api!`].

pub mod cost_rates;
pub mod crud;
pub mod force_models;
pub mod machines;
pub mod materials;
pub mod record_schema;
pub mod routes;
pub mod standard_conditions;
pub mod tool_life;
pub mod tools;

use crate::service::error::{ApiError, Validator};
use crate::service::store::Conn;
use crate::service::store::Row;
use serde::{Deserialize, Serialize};
use sqlx::FromRow;
use std::future::Future;
use std::pin::Pin;
use utoipa::{IntoParams, ToSchema};

/// A value bound into a generated SQL statement.
#[derive(Debug, Clone, PartialEq)]
pub enum SqlValue {
    Int(i64),
    Real(f64),
    Text(String),
    Null,
}

impl From<f64> for SqlValue {
    fn from(v: f64) -> Self {
        SqlValue::Real(v)
    }
}
impl From<i64> for SqlValue {
    fn from(v: i64) -> Self {
        SqlValue::Int(v)
    }
}
impl From<String> for SqlValue {
    fn from(v: String) -> Self {
        SqlValue::Text(v)
    }
}
impl From<&str> for SqlValue {
    fn from(v: &str) -> Self {
        SqlValue::Text(v.to_string())
    }
}
impl<T: Into<SqlValue>> From<Option<T>> for SqlValue {
    fn from(v: Option<T>) -> Self {
        v.map_or(SqlValue::Null, Into::into)
    }
}

/// Where the values of a row come from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, ToSchema)]
#[serde(rename_all = "snake_case")]
pub enum Source {
    /// Taken from one of the papers; `reference` names the file and table.
    Paper,
    /// Extrapolated from paper data by a stated rule.
    Extrapolated,
    /// Our default where the papers are silent: replace it with the shop's value.
    Assumed,
    /// Inferred from other figures of the papers where a printed value contradicts them;
    /// `reference` says from what (e.g. the baseline's feed, MODEL.md §5).
    Inferred,
    /// Fitted to measurements (e.g. `POST /v1/tools/{id}/force-model/fit`).
    Fitted,
    /// Entered or edited by the shop.
    User,
}

impl Source {
    pub fn as_str(self) -> &'static str {
        match self {
            Source::Paper => "paper",
            Source::Extrapolated => "extrapolated",
            Source::Assumed => "assumed",
            Source::Inferred => "inferred",
            Source::Fitted => "fitted",
            Source::User => "user",
        }
    }

    /// The source of a row a client writes without naming one.
    pub fn user() -> Source {
        Source::User
    }
}

/// A `source` column, read as text from either backend.
impl sqlx::Type<sqlx::Any> for Source {
    fn type_info() -> sqlx::any::AnyTypeInfo {
        <String as sqlx::Type<sqlx::Any>>::type_info()
    }
}

impl<'r> sqlx::Decode<'r, sqlx::Any> for Source {
    fn decode(value: sqlx::any::AnyValueRef<'r>) -> Result<Source, sqlx::error::BoxDynError> {
        let text = <&str as sqlx::Decode<sqlx::Any>>::decode(value)?;
        Ok(serde_json::from_value(serde_json::Value::String(text.to_string()))?)
    }
}

/// A row another row points at, checked before a write so that a dangling id is a 422
/// naming the field rather than a constraint failure.
pub struct Reference {
    pub field: &'static str,
    pub table: &'static str,
    pub id: i64,
}

/// What a [`Resource`] hook does inside the write transaction.
pub type Hook<'a> = Pin<Box<dyn Future<Output = Result<(), ApiError>> + Send + 'a>>;

/// The writable part of a table's row.
pub trait Resource:
    Serialize + serde::de::DeserializeOwned + Clone + Send + Sync + Unpin + 'static + for<'r> FromRow<'r, Row>
{
    /// SQL table name.
    const TABLE: &'static str;
    /// What one row is called in messages ("tool").
    const SINGULAR: &'static str;
    /// Column names in the order of [`Resource::values`].
    const COLUMNS: &'static [&'static str];
    /// Tables whose rows reference this one: `(table, column, what they are called)`.
    const REFERENCED_BY: &'static [(&'static str, &'static str, &'static str)] = &[];

    /// Values of [`Resource::COLUMNS`], in order.
    fn values(&self) -> Vec<SqlValue>;
    /// Checks every field; errors name the field.
    fn validate(&self, v: &mut Validator);
    /// Rows this one points at.
    fn references(&self) -> Vec<Reference> {
        Vec::new()
    }
    /// Fields that mark the row among others rather than describe it (a tool's `default`):
    /// a patch of these alone leaves the row's `source` and `edited` mark as they are, and
    /// a patch that does not name one leaves it out of the merged data, so that the hooks
    /// read it as unchanged.
    const FLAGS: &'static [&'static str] = &[];
    /// Keeps what spans rows after the row `id` was inserted (`before`: none) or updated,
    /// inside the same write transaction (e.g. one default tool per type and diameter).
    fn after_write<'a>(_conn: &'a mut Conn, _id: i64, _before: Option<&'a Self>, _data: &'a Self) -> Hook<'a> {
        Box::pin(async { Ok(()) })
    }
    /// Keeps what spans rows after the row `id` (whose data was `deleted`) was deleted,
    /// inside the same write transaction.
    fn after_delete<'a>(_conn: &'a mut Conn, _id: i64, _deleted: &'a Self) -> Hook<'a> {
        Box::pin(async { Ok(()) })
    }
}

/// A full row as the API shows it: id, data, provenance and timestamps.
pub trait Record: Serialize + Send + Unpin + 'static + for<'r> FromRow<'r, Row> {
    type Data: Resource;
    fn data(&self) -> &Self::Data;
}

/// Filters of a list request, turned into SQL conditions.
pub trait ListFilter: serde::de::DeserializeOwned + Send {
    /// `(condition with ? placeholders, values)` pairs, ANDed together.
    fn conditions(&self) -> Vec<(String, Vec<SqlValue>)>;
    fn page(&self) -> PageRequest;
    /// Checks the filter values (e.g. finiteness); errors name the parameter.
    fn validate(&self, _v: &mut Validator) {}
}

/// Default number of rows in one page of a list.
pub const DEFAULT_PAGE_LIMIT: i64 = 50;
/// Largest page a client may ask for.
pub const MAX_PAGE_LIMIT: i64 = 500;
/// Tolerance when filtering by diameter, mm.
pub const DIAMETER_FILTER_TOLERANCE_MM: f64 = 1e-6;

/// Paging of a list request.
#[derive(Debug, Clone, Copy, Deserialize, IntoParams)]
pub struct PageRequest {
    /// Rows to return, 1 to 500 (default 50).
    pub limit: Option<i64>,
    /// Rows to skip (default 0).
    pub offset: Option<i64>,
}

/// One page of a list.
#[derive(Debug, Serialize, ToSchema)]
pub struct Page<T> {
    pub items: Vec<T>,
    /// Rows matching the filters, over all pages.
    pub total: i64,
    pub limit: i64,
    pub offset: i64,
}

/// Declares the full-row type of a resource: its data plus id, provenance and timestamps,
/// with one flat OpenAPI schema ([`record_schema`]) that every row validates against.
#[macro_export]
macro_rules! record {
    ($(#[doc = $doc:literal])* $record:ident, $data:ident) => {
        $(#[doc = $doc])*
        #[derive(Debug, Clone, serde::Serialize, sqlx::FromRow)]
        pub struct $record {
            pub id: i64,
            #[serde(flatten)]
            #[sqlx(flatten)]
            pub data: $data,
            /// Stable key of a row seeded by a migration; null for the shop's own rows.
            pub seed_key: Option<String>,
            /// True once the shop changed the row: later migrations leave it alone.
            #[sqlx(try_from = "crate::service::store::Flag")]
            pub edited: bool,
            pub created_at: String,
            pub updated_at: String,
        }

        impl utoipa::PartialSchema for $record {
            fn schema() -> utoipa::openapi::RefOr<utoipa::openapi::schema::Schema> {
                $crate::service::resources::record_schema::record_schema(
                    <$data as utoipa::PartialSchema>::schema(),
                    concat!($($doc),*).trim(),
                )
            }
        }

        impl utoipa::ToSchema for $record {
            fn name() -> std::borrow::Cow<'static, str> {
                std::borrow::Cow::Borrowed(stringify!($record))
            }

            fn schemas(schemas: &mut Vec<(String, utoipa::openapi::RefOr<utoipa::openapi::schema::Schema>)>) {
                <$data as utoipa::ToSchema>::schemas(schemas);
            }
        }

        impl $crate::service::resources::Record for $record {
            type Data = $data;
            fn data(&self) -> &$data {
                &self.data
            }
        }
    };
}

/// Filters of the lists of per-tool data (`/v1/force-models`, `/v1/tool-life`).
#[derive(Debug, Deserialize, IntoParams)]
#[serde(deny_unknown_fields)]
#[into_params(parameter_in = Query)]
pub struct ToolMaterialFilter {
    /// Only rows of this tool.
    pub tool_id: Option<i64>,
    /// Only rows of this material.
    pub material_id: Option<i64>,
    /// Only rows of this source.
    pub source: Option<Source>,
    pub limit: Option<i64>,
    pub offset: Option<i64>,
}

impl ListFilter for ToolMaterialFilter {
    fn conditions(&self) -> Vec<(String, Vec<SqlValue>)> {
        [
            routes::eq("tool_id", self.tool_id),
            routes::eq("material_id", self.material_id),
            routes::eq("source", self.source.map(Source::as_str)),
        ]
        .into_iter()
        .flatten()
        .collect()
    }

    fn page(&self) -> PageRequest {
        PageRequest { limit: self.limit, offset: self.offset }
    }
}

/// Filters of the lists of named rows (`/v1/materials`, `/v1/machines`, `/v1/cost-rates`).
#[derive(Debug, Deserialize, IntoParams)]
#[serde(deny_unknown_fields)]
#[into_params(parameter_in = Query)]
pub struct NameFilter {
    /// Only the row of this name.
    pub name: Option<String>,
    /// Only rows of this source.
    pub source: Option<Source>,
    pub limit: Option<i64>,
    pub offset: Option<i64>,
}

impl ListFilter for NameFilter {
    fn conditions(&self) -> Vec<(String, Vec<SqlValue>)> {
        [routes::eq("name", self.name.clone()), routes::eq("source", self.source.map(Source::as_str))]
            .into_iter()
            .flatten()
            .collect()
    }

    fn page(&self) -> PageRequest {
        PageRequest { limit: self.limit, offset: self.offset }
    }
}
