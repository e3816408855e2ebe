//! The OpenAPI document: every route and schema, generated from the code.

use crate::service::error::{FieldError, Problem};
use crate::service::state::AppState;
use utoipa::OpenApi;
use utoipa_axum::router::OpenApiRouter;

#[derive(OpenApi)]
#[openapi(
    info(
        title = "dieplan",
        description = "Plans the milling of dies and molds in hardened steel (JIS SKD61, HRC53) with coated carbide end mills: finds where the tool would be overloaded, inserts trochoids, sets constant-force feeds, estimates time, tool life and cost. Errors are application/problem+json (RFC 9457).",
        license(name = "MIT")
    ),
    tags(
        (name = "jobs", description = "Planning work as jobs: create, poll, list, cancel"),
        (name = "database", description = "The cutting-condition database"),
        (name = "keys", description = "API keys and their roles (admin)"),
        (name = "health", description = "Liveness and readiness")
    ),
    components(schemas(Problem, FieldError, crate::service::jobs::model::ProgramPart))
)]
pub struct ApiDoc;

/// All routes with their OpenAPI operations, before state is attached.
pub fn api_router() -> OpenApiRouter<AppState> {
    use crate::service::resources::*;
    OpenApiRouter::with_openapi(ApiDoc::openapi())
        .merge(crate::service::health::router())
        .merge(crate::service::jobs::routes::router())
        .merge(crate::service::jobs::drawings::router())
        .merge(crate::service::jobs::path_trace::router())
        .merge(crate::service::jobs::stock_view::router())
        .merge(crate::service::examples::router())
        .merge(materials::api::router())
        .merge(tools::api::router())
        .merge(standard_conditions::api::router())
        .merge(force_models::api::router())
        .merge(tool_life::api::router())
        .merge(machines::api::router())
        .merge(cost_rates::api::router())
        .routes(utoipa_axum::routes!(crate::service::force_fit::fit))
        .merge(crate::service::keys::routes::router())
}

/// The routes and the finished OpenAPI document (with keys, roles and rate limits).
pub fn api_parts() -> (axum::Router<AppState>, utoipa::openapi::OpenApi) {
    let (router, mut doc) = api_router().split_for_parts();
    crate::service::security_docs::describe(&mut doc);
    crate::service::status_docs::describe(&mut doc);
    crate::service::parameter_docs::describe(&mut doc);
    crate::service::resources::record_schema::describe_patches(&mut doc);
    crate::service::job_schema::describe(&mut doc);
    (router, doc)
}

/// The OpenAPI document the service serves at `/openapi.json`.
pub fn document() -> utoipa::openapi::OpenApi {
    api_parts().1
}

/// The document as committed in `openapi/openapi.json`: pretty JSON with a final newline.
pub fn document_json() -> String {
    let mut text = document().to_pretty_json().unwrap_or_default();
    text.push('\n');
    text
}
