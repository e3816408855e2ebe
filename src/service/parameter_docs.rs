//! Bounds of the parameters every list and every row shares, written into the OpenAPI
//! document from the constants the service checks them against:
//!
//! - `limit`: 1 to [`MAX_PAGE_LIMIT`] rows (default [`DEFAULT_PAGE_LIMIT`]);
//! - `offset`: 0 or more rows (default 0);
//! - an integer `id` in the path: 1 or more (ids start at 1);
//! - a job's `id` in the path: a UUID;
//! - the `Prefer` header of a submission: `wait=N`, cut to the longest wait the service
//!   honours ([`crate::service::config::Config::effective_max_wait_s`], by default).
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
    if matches!(parameter.parameter_in, ParameterIn::Header) && parameter.name.eq_ignore_ascii_case("prefer") {
        return describe_prefer(parameter);
    }
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

/// The longest `Prefer: wait=N` the service honours with its default configuration, s.
pub fn default_max_wait_s() -> u64 {
    crate::service::config::Config::with_database(std::path::PathBuf::new()).effective_max_wait_s()
}

/// The `Prefer` header of a submission, with the bound of its wait.
fn describe_prefer(parameter: &mut Parameter) {
    let max = default_max_wait_s();
    parameter.description = Some(format!(
        "RFC 7240 preferences. `wait=N`, N a whole number of seconds: answer with the finished job (201) if it \
         finishes within N seconds. The wait is at most {max} s (the service's `--max-wait`, {max} by default, \
         and always less than its request timeout): a longer one is cut to it, and `Preference-Applied` names the \
         wait applied. Other preferences are ignored."
    ));
    parameter.schema = Some(ObjectBuilder::new().schema_type(Type::String).examples([format!("wait={max}")]).into());
}

fn is_integer(schema: Option<&RefOr<Schema>>) -> bool {
    matches!(schema, Some(RefOr::T(Schema::Object(o))) if o.schema_type == SchemaType::Type(Type::Integer))
}
