//! Bounds of the parameters every list and every row shares, written into the OpenAPI
//! document from the constants the service checks them against:
//!
//! - `limit`: 1 to [`MAX_PAGE_LIMIT`] rows (default [`DEFAULT_PAGE_LIMIT`]);
//! - `offset`: 0 or more rows (default 0);
//! - an integer `id` in the path: 1 or more (ids start at 1);
//! - a job's `id` in the path: a UUID.
//!
//! Parameters of one route carry their bounds in their own `#[param]` attributes.

use crate::service::resources::{DEFAULT_PAGE_LIMIT, MAX_PAGE_LIMIT};
use utoipa::openapi::path::{Parameter, ParameterIn};
use utoipa::openapi::schema::{KnownFormat, ObjectBuilder, Schema, SchemaFormat, SchemaType, Type};
use utoipa::openapi::{OpenApi, RefOr};

/// Sets the bounds of the paging parameters and of ids in paths.
pub fn describe(doc: &mut OpenApi) {
    for (path, item) in doc.paths.paths.iter_mut() {
        let is_job = path.starts_with("/v1/jobs/{id}");
        for op in [&mut item.get, &mut item.post, &mut item.put, &mut item.patch, &mut item.delete, &mut item.head]
            .into_iter()
            .flatten()
        {
            for parameter in op.parameters.iter_mut().flatten() {
                bound(parameter, is_job);
            }
        }
    }
}

fn bound(parameter: &mut Parameter, is_job: bool) {
    let int64 =
        || ObjectBuilder::new().schema_type(Type::Integer).format(Some(SchemaFormat::KnownFormat(KnownFormat::Int64)));
    let schema = match (&parameter.parameter_in, parameter.name.as_str()) {
        (ParameterIn::Query, "limit") => {
            int64().minimum(Some(1)).maximum(Some(MAX_PAGE_LIMIT as f64)).default(Some(DEFAULT_PAGE_LIMIT.into()))
        }
        (ParameterIn::Query, "offset") => int64().minimum(Some(0)).default(Some(0.into())),
        (ParameterIn::Path, "id") if is_job => {
            ObjectBuilder::new().schema_type(Type::String).format(Some(SchemaFormat::Custom("uuid".to_string())))
        }
        (ParameterIn::Path, "id") if is_integer(parameter.schema.as_ref()) => int64().minimum(Some(1)),
        _ => return,
    };
    parameter.schema = Some(schema.into());
    if matches!(parameter.parameter_in, ParameterIn::Query) && parameter.description.is_none() {
        parameter.description = Some(match parameter.name.as_str() {
            "limit" => format!("Rows to return, 1 to {MAX_PAGE_LIMIT} (default {DEFAULT_PAGE_LIMIT})."),
            _ => "Rows to skip (default 0).".to_string(),
        });
    }
}

fn is_integer(schema: Option<&RefOr<Schema>>) -> bool {
    matches!(schema, Some(RefOr::T(Schema::Object(o))) if o.schema_type == SchemaType::Type(Type::Integer))
}
