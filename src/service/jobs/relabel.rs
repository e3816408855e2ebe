//! `PATCH /v1/jobs/{id}`: renames and retags a job, queued, running or finished. The body
//! names what changes: `name` (text; `null` removes it) and `tags` (the new list, `[]`
//! for none); what it leaves out stays. The name and tags follow the rules of a submit
//! (labels.rs), every fault in one 422, and a refused patch changes nothing. `null`
//! removes the name or the tags.

use super::labels::{JobLabels, MAX_TAGS};
use super::model::JobId;
use super::routes::job_response;
use super::store;
use crate::service::auth::Caller;
use crate::service::error::{excerpt, ApiError, FieldError, Problem};
use crate::service::extract::{parse_json, ApiPath, JsonBytes};
use crate::service::state::AppState;
use axum::extract::State;
use axum::http::StatusCode;
use axum::response::Response;
use serde::Deserialize;
use serde_json::Value;
use utoipa::ToSchema;

/// A job's new name and tags: give what changes.
#[derive(Debug, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
#[allow(dead_code)]
pub struct JobLabelsPatch {
    /// The new name (1 to 200 characters, no control characters); `null` removes it.
    #[schema(
        min_length = 1,
        max_length = 200,
        pattern = r"^[^\u0000-\u001F\u007F]*$",
        nullable,
        example = "Die 4711, cavity A, finishing"
    )]
    name: Option<String>,
    /// The new tags (see [`tags_schema`]).
    #[schema(schema_with = tags_schema)]
    tags: Option<Vec<String>>,
}

/// The schema of the new tags: distinct, at most [`MAX_TAGS`], or null.
fn tags_schema() -> utoipa::openapi::schema::Array {
    use utoipa::openapi::schema::{ArrayBuilder, SchemaType, Type};
    ArrayBuilder::new()
        .schema_type(SchemaType::from_iter([Type::Array, Type::Null]))
        .items(utoipa::openapi::Ref::from_schema_name("Tag"))
        .max_items(Some(MAX_TAGS))
        .unique_items(true)
        .description(Some(
            "The new tags, replacing the old (up to 20 distinct, each 1 to 64 ASCII letters, digits and `-_.:/`); `[]` or `null` removes them all.",
        ))
        .examples([serde_json::json!(["die:4711", "finishing"])])
        .build()
}

/// The labels `patch` gives `current`, or every fault of the patch.
pub fn patched(current: JobLabels, patch: &Value) -> Result<JobLabels, Vec<FieldError>> {
    let fault = |field: &str, reason: String| FieldError { field: field.to_string(), reason };
    let Some(object) = patch.as_object() else {
        return Err(vec![fault(
            "body",
            format!("must be an object with name and tags, got {}", excerpt(&patch.to_string())),
        )]);
    };
    let mut faults: Vec<FieldError> = object
        .keys()
        .filter(|k| !matches!(k.as_str(), "name" | "tags"))
        .map(|k| fault(k, "is not a field of a job that can change (name, tags)".to_string()))
        .collect();
    let mut labels = current;
    match object.get("name") {
        None => {}
        Some(Value::Null) => labels.name = None,
        Some(Value::String(name)) => labels.name = Some(name.clone()),
        Some(other) => faults.push(fault("name", format!("must be text or null, got {}", excerpt(&other.to_string())))),
    }
    match object.get("tags") {
        None => {}
        Some(Value::Null) => labels.tags = Vec::new(),
        Some(Value::Array(items)) => {
            labels.tags = Vec::new();
            for (i, item) in items.iter().enumerate() {
                match item {
                    Value::String(tag) => labels.tags.push(tag.clone()),
                    other => faults.push(fault(&format!("tags[{i}]"), format!("must be text, got {other}"))),
                }
            }
        }
        Some(other) => {
            faults.push(fault("tags", format!("must be a list of tags, got {}", excerpt(&other.to_string()))))
        }
    }
    faults.extend(labels.faults(""));
    if faults.is_empty() {
        Ok(labels)
    } else {
        Err(faults)
    }
}

/// Renames and retags a job (whatever its status): `name` (`null` removes it) and
/// `tags` (replacing the old ones); a field left out stays as it is.
///
/// A planner's key may change only its own jobs.
#[utoipa::path(patch, path = "/v1/jobs/{id}", tag = "jobs", operation_id = "relabelJob", request_body = JobLabelsPatch,
    params(("id" = JobId, Path, description = "Job id (a UUID)")),
    responses(
        (status = 200, description = "The job with its new name and tags", body = super::model::Job),
        (status = 400, description = "A malformed job id, or malformed JSON", body = Problem, content_type = "application/problem+json"),
        (status = 404, description = "No such job", body = Problem, content_type = "application/problem+json"),
        (status = 422, description = "Every fault of the name and tags, in one problem; nothing changed", body = Problem, content_type = "application/problem+json")))]
pub async fn relabel_job(
    State(state): State<AppState>,
    caller: Caller,
    ApiPath(id): ApiPath<JobId>,
    JsonBytes(body): JsonBytes,
) -> Result<Response, ApiError> {
    let patch: Value = parse_json(&body)?;
    let row = store::get_visible(&state.pool, &caller, &id).await?;
    store::relabel(&state.pool, &row.id, |current| patched(current, &patch).map_err(ApiError::Validation)).await?;
    job_response(&state.pool, StatusCode::OK, &store::get(&state.pool, &row.id).await?).await
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;

    fn current() -> JobLabels {
        JobLabels { name: Some("old".into()), tags: vec!["a".into(), "b".into()] }
    }

    #[test]
    fn a_patch_changes_what_it_names_and_keeps_the_rest() {
        let renamed = patched(current(), &json!({"name": "new"})).unwrap();
        assert_eq!((renamed.name.as_deref(), renamed.tags.len()), (Some("new"), 2));
        let retagged = patched(current(), &json!({"tags": ["c"]})).unwrap();
        assert_eq!((retagged.name.as_deref(), retagged.tags), (Some("old"), vec!["c".to_string()]));
        let cleared = patched(current(), &json!({"name": null, "tags": []})).unwrap();
        assert_eq!(cleared, JobLabels::default());
        assert_eq!(patched(current(), &json!({"tags": null})).unwrap().tags, Vec::<String>::new());
        assert_eq!(patched(current(), &json!({})).unwrap(), current());
    }

    #[test]
    fn every_fault_of_a_patch_is_named_at_once() {
        let faults =
            patched(current(), &json!({"name": "", "tags": ["ok", "bad tag", 3], "kind": "plan"})).unwrap_err();
        let fields: Vec<&str> = faults.iter().map(|f| f.field.as_str()).collect();
        assert_eq!(fields, ["kind", "tags[2]", "name", "tags[1]"]);
        assert!(patched(current(), &json!(["x"])).is_err());
    }
}
