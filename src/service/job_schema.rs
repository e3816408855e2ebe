//! The OpenAPI schema of a job as a `oneOf` by `kind`: one schema per kind
//! (`ConditionsJob`, `AnalysisJob`, …) whose `kind` is that kind alone and whose `result`
//! is that kind's result type, and a discriminator on `kind` naming them. A client
//! generated from the document gets a typed result for every kind instead of `Any`.

use crate::service::jobs::kinds::REGISTRY;
use crate::service::jobs::labels::JobLabels;
use crate::service::jobs::model::JobKind;
use std::collections::BTreeMap;
use utoipa::openapi::schema::{Discriminator, ObjectBuilder, OneOfBuilder, Schema, Type};
use utoipa::openapi::{OpenApi, Ref, RefOr};
use utoipa::{PartialSchema, ToSchema};

/// The name of the schema of a job of one kind: `ConditionsJob`, `PlanJob`, …
pub fn job_schema(kind: JobKind) -> String {
    let name = kind.as_str();
    let mut chars = name.chars();
    let first = chars.next().map(|c| c.to_ascii_uppercase()).unwrap_or_default();
    format!("{first}{}Job", chars.as_str())
}

/// The name of the schema of the body of a kind's named endpoint: its request with the
/// job's name and tags (`AnalysisSubmission`, …).
pub fn submission_schema(kind: JobKind) -> String {
    job_schema(kind).replace("Job", "Submission")
}

/// Replaces the `Job` and `JobRequest` schemas by a `oneOf` of one schema per kind,
/// discriminated by `kind`, and adds the bodies of the named endpoints.
pub fn describe(doc: &mut OpenApi) {
    let Some(components) = doc.components.as_mut() else {
        return;
    };
    describe_requests(&mut components.schemas);
    describe_submissions(&mut components.schemas);
    let Some(RefOr::T(Schema::Object(job))) = components.schemas.get("Job").cloned() else {
        return;
    };
    let mut one_of = OneOfBuilder::new().description(job.description.clone());
    let mut mapping = BTreeMap::new();
    for registered in &REGISTRY {
        let (kind, result_schema) = (registered.kind, (registered.result_schema)());
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
            .item(Ref::from_schema_name(result_schema.clone()))
            .description(Some(format!("The result once the job succeeded (a {result_schema}), else null.")));
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
    for registered in &REGISTRY {
        let kind = registered.kind;
        let name = format!("{}Request", job_schema(kind));
        let mut schema = request.clone();
        schema.description = Some(format!("A job of kind `{}` to run.", kind.as_str()));
        schema.example = None;
        let kind_schema = ObjectBuilder::new().schema_type(Type::String).enum_values(Some([kind.as_str()]));
        schema.properties.insert("kind".to_string(), kind_schema.into());
        schema.properties.insert("input".to_string(), Ref::from_schema_name((registered.request_schema)()).into());
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

/// `AnalysisSubmission`, …: each kind's request with the `name` and `tags` of
/// [`JobLabels`], which its named endpoint takes beside the request's own fields.
fn describe_submissions(schemas: &mut BTreeMap<String, RefOr<Schema>>) {
    let RefOr::T(Schema::Object(labels)) = JobLabels::schema() else {
        return;
    };
    let mut more = Vec::new();
    JobLabels::schemas(&mut more);
    schemas.extend(more);
    for registered in &REGISTRY {
        let Some(RefOr::T(Schema::Object(request))) = schemas.get((registered.request_schema)().as_ref()).cloned()
        else {
            continue;
        };
        let mut schema = request;
        schema.description = Some(format!(
            "{} With the job's `name` and `tags`, which are not part of its input.",
            schema.description.unwrap_or_default()
        ));
        schema.properties.extend(labels.properties.clone());
        schemas.insert(submission_schema(registered.kind), RefOr::T(Schema::Object(schema)));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_kind_has_a_job_schema_named_for_it() {
        let names: Vec<String> = REGISTRY.iter().map(|r| job_schema(r.kind)).collect();
        assert_eq!(names, ["ConditionsJob", "AnalysisJob", "FeedsJob", "CostingJob", "TrochoidsJob", "PlanJob"]);
        for kind in JobKind::ALL {
            assert_eq!(JobKind::parse(kind.as_str()), Some(kind));
        }
    }
}
