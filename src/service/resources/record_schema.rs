//! The OpenAPI schema of a full row: one flat object with the data's fields and the
//! row's own (`id`, `seed_key`, `edited`, `created_at`, `updated_at`), every field
//! required and no other allowed, so that every row the service returns validates
//! against it. (utoipa would write `allOf[data, {id…}]`, which no row validates: the
//! data's schema refuses the row's other fields.)

use utoipa::openapi::schema::{AdditionalProperties, KnownFormat, Object, ObjectBuilder, Schema, SchemaFormat, Type};
use utoipa::openapi::RefOr;

/// The schema of a row whose writable part has the schema `data`.
pub fn record_schema(data: RefOr<Schema>, description: &str) -> RefOr<Schema> {
    let mut row = match data {
        RefOr::T(Schema::Object(object)) => object,
        _ => Object::new(),
    };
    let timestamp = || {
        ObjectBuilder::new().schema_type(Type::String).format(Some(SchemaFormat::KnownFormat(KnownFormat::DateTime)))
    };
    let own: [(&str, RefOr<Schema>); 5] = [
        (
            "id",
            ObjectBuilder::new()
                .schema_type(Type::Integer)
                .format(Some(SchemaFormat::KnownFormat(KnownFormat::Int64)))
                .minimum(Some(1))
                .description(Some("The row's id."))
                .into(),
        ),
        (
            "seed_key",
            ObjectBuilder::new()
                .schema_type(utoipa::openapi::schema::SchemaType::from_iter([Type::String, Type::Null]))
                .description(Some("Stable key of a row seeded by a migration; null for the shop's own rows."))
                .into(),
        ),
        (
            "edited",
            ObjectBuilder::new()
                .schema_type(Type::Boolean)
                .description(Some("True once the shop changed the row: later migrations leave it alone."))
                .into(),
        ),
        ("created_at", timestamp().description(Some("When the row was made (UTC, RFC 3339).")).into()),
        ("updated_at", timestamp().description(Some("When the row was last written (UTC, RFC 3339).")).into()),
    ];
    let data_fields = std::mem::take(&mut row.properties);
    row.properties.insert(own[0].0.to_string(), own[0].1.clone());
    row.properties.extend(data_fields);
    for (name, schema) in own.into_iter().skip(1) {
        row.properties.insert(name.to_string(), schema);
    }
    row.required = row.properties.keys().cloned().collect();
    row.additional_properties = Some(Box::new(AdditionalProperties::FreeForm(false)));
    row.description = Some(description.to_string());
    row.example = None;
    RefOr::T(Schema::Object(row))
}

/// Content type of a JSON merge patch (RFC 7396).
const MERGE_PATCH: &str = "application/merge-patch+json";

/// Gives every merge-patch body (`PATCH` of a row) its own schema, `<Data>Patch`: the
/// fields of the row's data (the `PUT` body of the same path), none required, no other
/// allowed; a field with a default may be `null` (the patch removes it: it takes its
/// default), a required one may not (the patch could not remove it).
pub fn describe_patches(doc: &mut utoipa::openapi::OpenApi) {
    let mut patches = Vec::new();
    for item in doc.paths.paths.values_mut() {
        let data = item.put.as_ref().and_then(|put| put.request_body.as_ref()).and_then(|body| {
            body.content.values().find_map(|c| match &c.schema {
                Some(RefOr::Ref(r)) => r.ref_location.rsplit('/').next().map(str::to_string),
                _ => None,
            })
        });
        let (Some(data), Some(patch)) = (data, item.patch.as_mut()) else {
            continue;
        };
        let Some(content) = patch.request_body.as_mut().and_then(|b| b.content.get_mut(MERGE_PATCH)) else {
            continue;
        };
        let name = format!("{data}Patch");
        content.schema = Some(utoipa::openapi::Ref::from_schema_name(name.clone()).into());
        patches.push((data, name));
    }
    let Some(components) = doc.components.as_mut() else {
        return;
    };
    for (data, name) in patches {
        let Some(RefOr::T(Schema::Object(object))) = components.schemas.get(&data).cloned() else {
            continue;
        };
        components.schemas.insert(name, patch_schema(object).into());
    }
}

fn patch_schema(mut data: Object) -> Schema {
    let required = std::mem::take(&mut data.required);
    for (name, schema) in data.properties.iter_mut() {
        if !required.contains(name) {
            let nullable = utoipa::openapi::schema::AnyOfBuilder::new()
                .item(ObjectBuilder::new().schema_type(Type::Null))
                .item(schema.clone())
                .build();
            *schema = RefOr::T(Schema::AnyOf(nullable));
        }
    }
    data.description = Some(format!(
        "A JSON merge patch (RFC 7396) of {}: the fields to change; null resets a field that has a default.",
        data.description.as_deref().unwrap_or("the row").trim_end_matches('.').to_lowercase()
    ));
    data.example = None;
    data.additional_properties = Some(Box::new(AdditionalProperties::FreeForm(false)));
    Schema::Object(data)
}
