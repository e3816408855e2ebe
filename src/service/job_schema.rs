//! The OpenAPI schema of a job as a `oneOf` by `kind`: one schema per kind
//! (`ConditionsJob`, `AnalysisJob`, …) whose `kind` is that kind alone and whose `result`
//! is that kind's result type, and a discriminator on `kind` naming them. A client
//! generated from the document gets a typed result for every kind instead of `Any`.

use crate::service::jobs::analysis::AnalysisRequest;
use crate::service::jobs::analysis_result::AnalysisResult;
use crate::service::jobs::conditions::{ConditionsRequest, ConditionsResult};
use crate::service::jobs::costing::CostingRequest;
use crate::service::jobs::costing_result::CostingResult;
use crate::service::jobs::feeds::FeedsRequest;
use crate::service::jobs::feeds_result::FeedsResult;
use crate::service::jobs::model::JobKind;
use crate::service::jobs::plans::PlanRequest;
use crate::service::jobs::plans_result::PlanResult;
use crate::service::jobs::trochoids::TrochoidsRequest;
use crate::service::jobs::trochoids_result::TrochoidsResult;
use std::borrow::Cow;
use std::collections::BTreeMap;
use utoipa::openapi::schema::{AnyOfBuilder, Discriminator, ObjectBuilder, OneOfBuilder, Schema, Type};
use utoipa::openapi::{OpenApi, Ref, RefOr};
use utoipa::ToSchema;

/// Every job kind, in the order the document lists them.
pub const KINDS: [JobKind; 6] =
    [JobKind::Conditions, JobKind::Analysis, JobKind::Feeds, JobKind::Costing, JobKind::Trochoids, JobKind::Plan];

/// The name of the schema of a kind's result.
pub fn result_schema(kind: JobKind) -> Cow<'static, str> {
    match kind {
        JobKind::Conditions => ConditionsResult::name(),
        JobKind::Analysis => AnalysisResult::name(),
        JobKind::Feeds => FeedsResult::name(),
        JobKind::Costing => CostingResult::name(),
        JobKind::Trochoids => TrochoidsResult::name(),
        JobKind::Plan => PlanResult::name(),
    }
}

/// The name of the schema of a kind's input.
pub fn request_schema(kind: JobKind) -> Cow<'static, str> {
    match kind {
        JobKind::Conditions => ConditionsRequest::name(),
        JobKind::Analysis => AnalysisRequest::name(),
        JobKind::Feeds => FeedsRequest::name(),
        JobKind::Costing => CostingRequest::name(),
        JobKind::Trochoids => TrochoidsRequest::name(),
        JobKind::Plan => PlanRequest::name(),
    }
}

/// The name of the schema of a job of one kind: `ConditionsJob`, `PlanJob`, …
pub fn job_schema(kind: JobKind) -> String {
    let name = kind.as_str();
    let mut chars = name.chars();
    let first = chars.next().map(|c| c.to_ascii_uppercase()).unwrap_or_default();
    format!("{first}{}Job", chars.as_str())
}

/// Replaces the `Job` and `JobRequest` schemas by a `oneOf` of one schema per kind,
/// discriminated by `kind`.
pub fn describe(doc: &mut OpenApi) {
    let Some(components) = doc.components.as_mut() else {
        return;
    };
    describe_requests(&mut components.schemas);
    describe_inputs(&mut components.schemas);
    let Some(RefOr::T(Schema::Object(job))) = components.schemas.get("Job").cloned() else {
        return;
    };
    let mut one_of = OneOfBuilder::new().description(job.description.clone());
    let mut mapping = BTreeMap::new();
    for kind in KINDS {
        let name = job_schema(kind);
        let mut schema = job.clone();
        schema.description = Some(format!("A job of kind `{}`.", kind.as_str()));
        let kind_schema = ObjectBuilder::new()
            .schema_type(Type::String)
            .enum_values(Some([kind.as_str()]))
            .description(Some("What the job computes; it says which schema `result` has."));
        schema.properties.insert("kind".to_string(), kind_schema.into());
        let result = OneOfBuilder::new()
            .item(ObjectBuilder::new().schema_type(Type::Null))
            .item(Ref::from_schema_name(result_schema(kind)))
            .description(Some(format!("The result once the job succeeded (a {}), else null.", result_schema(kind))));
        schema.properties.insert("result".to_string(), result.into());
        components.schemas.insert(name.clone(), RefOr::T(Schema::Object(schema)));
        mapping.insert(kind.as_str().to_string(), format!("#/components/schemas/{name}"));
        one_of = one_of.item(Ref::from_schema_name(name));
    }
    let mut discriminator = Discriminator::new("kind");
    discriminator.mapping = mapping;
    components.schemas.insert("Job".to_string(), one_of.discriminator(Some(discriminator)).into());
}

/// `JobRequest` (`POST /v1/jobs`): `{kind, input}` whose `input` is that kind's input.
fn describe_requests(schemas: &mut BTreeMap<String, RefOr<Schema>>) {
    let Some(RefOr::T(Schema::Object(request))) = schemas.get("JobRequest").cloned() else {
        return;
    };
    let mut one_of = OneOfBuilder::new().description(request.description.clone());
    let mut mapping = BTreeMap::new();
    for kind in KINDS {
        let name = format!("{}Request", job_schema(kind));
        let mut schema = request.clone();
        schema.description = Some(format!("A job of kind `{}` to run.", kind.as_str()));
        schema.example = None;
        let kind_schema = ObjectBuilder::new().schema_type(Type::String).enum_values(Some([kind.as_str()]));
        schema.properties.insert("kind".to_string(), kind_schema.into());
        schema.properties.insert("input".to_string(), Ref::from_schema_name(request_schema(kind)).into());
        schemas.insert(name.clone(), RefOr::T(Schema::Object(schema)));
        mapping.insert(kind.as_str().to_string(), format!("#/components/schemas/{name}"));
        one_of = one_of.item(Ref::from_schema_name(name));
    }
    let mut discriminator = Discriminator::new("kind");
    discriminator.mapping = mapping;
    let mut schema = one_of.discriminator(Some(discriminator)).build();
    schema.example = request.example.clone();
    schemas.insert("JobRequest".to_string(), Schema::OneOf(schema).into());
}

/// `JobInput` (`GET /v1/jobs/{id}/input`): one kind's input, as an `anyOf`, since a small
/// input can satisfy more than one kind's schema (the job's `kind` says which it is).
fn describe_inputs(schemas: &mut BTreeMap<String, RefOr<Schema>>) {
    let Some(RefOr::T(Schema::OneOf(one_of))) = schemas.get("JobInput").cloned() else {
        return;
    };
    let mut any_of = AnyOfBuilder::new().description(one_of.description.clone());
    for item in one_of.items {
        any_of = any_of.item(item);
    }
    schemas.insert("JobInput".to_string(), any_of.into());
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_kind_has_a_job_schema_named_for_it() {
        let names: Vec<String> = KINDS.iter().map(|k| job_schema(*k)).collect();
        assert_eq!(names, ["ConditionsJob", "AnalysisJob", "FeedsJob", "CostingJob", "TrochoidsJob", "PlanJob"]);
        for kind in KINDS {
            assert_eq!(JobKind::parse(kind.as_str()), Some(kind));
        }
    }
}
