//! `/v1/keys`: make, list, read and revoke API keys (admin).

use super::model::{ApiKey, CreatedKey, KeyOrigin, NewKey, Role};
use super::store;
use crate::service::auth::Caller;
use crate::service::error::{ApiError, Problem};
use crate::service::extract::{ApiJson, ApiPath};
use crate::service::state::AppState;
use axum::extract::State;
use axum::http::{header, StatusCode};
use axum::response::IntoResponse;
use utoipa_axum::{router::OpenApiRouter, routes};

/// Makes a key and answers its secret, in `key`, this once.
///
/// The secret is stored only as its SHA-256: keep it now. While the service runs open (no
/// key yet), the first key must be an admin key: from then on every `/v1` route needs one.
#[utoipa::path(post, path = "/v1/keys", tag = "keys", operation_id = "createKey", request_body = NewKey,
    responses(
        (status = 201, description = "Made; `key` is the secret, shown only now; Location names the key", body = CreatedKey,
            headers(("Location" = String, description = "The new key"))),
        (status = 400, description = "Malformed JSON", body = Problem, content_type = "application/problem+json"),
        (status = 409, description = "The first key must be an admin key", body = Problem, content_type = "application/problem+json"),
        (status = 415, description = "The body is not JSON", body = Problem, content_type = "application/problem+json"),
        (status = 422, description = "A refused field", body = Problem, content_type = "application/problem+json")))]
pub async fn create_key(
    State(state): State<AppState>,
    caller: Caller,
    ApiJson(new): ApiJson<NewKey>,
) -> Result<impl IntoResponse, ApiError> {
    if caller == Caller::Open && new.role != Role::Admin {
        return Err(ApiError::Conflict(
            "the first key must be an admin key: once a key exists every /v1 route needs one, and only an admin key can make more".into(),
        ));
    }
    let created = store::create(&state.pool, &new, KeyOrigin::Api).await?;
    tracing::info!(key = created.key.id, role = created.key.role.as_str(), name = %created.key.name, "API key made");
    let location = format!("/v1/keys/{}", created.key.id);
    Ok((StatusCode::CREATED, [(header::LOCATION, location)], axum::Json(created)))
}

/// Lists every key, revoked ones too, oldest first; never their secrets.
#[utoipa::path(get, path = "/v1/keys", tag = "keys", operation_id = "listKeys",
    responses((status = 200, description = "The keys", body = Vec<ApiKey>)))]
pub async fn list_keys(State(state): State<AppState>) -> Result<axum::Json<Vec<ApiKey>>, ApiError> {
    let rows = store::list(&state.pool).await?;
    Ok(axum::Json(rows.iter().map(store::KeyRow::to_key).collect::<Result<_, _>>()?))
}

/// Reads one key (never its secret).
#[utoipa::path(get, path = "/v1/keys/{id}", tag = "keys", operation_id = "getKey",
    params(("id" = i64, Path, description = "Key id")),
    responses(
        (status = 200, description = "The key", body = ApiKey),
        (status = 404, description = "No such key", body = Problem, content_type = "application/problem+json")))]
pub async fn get_key(State(state): State<AppState>, ApiPath(id): ApiPath<i64>) -> Result<axum::Json<ApiKey>, ApiError> {
    Ok(axum::Json(store::get(&state.pool, id).await?.to_key()?))
}

/// Revokes a key: it is refused from now on. The key stays listed (with `revoked_at`),
/// and the jobs it made still name it.
#[utoipa::path(delete, path = "/v1/keys/{id}", tag = "keys", operation_id = "deleteKey",
    params(("id" = i64, Path, description = "Key id")),
    responses(
        (status = 200, description = "Revoked", body = ApiKey),
        (status = 404, description = "No such key", body = Problem, content_type = "application/problem+json"),
        (status = 409, description = "The key of DIEPLAN_ADMIN_KEY: change the variable instead", body = Problem, content_type = "application/problem+json")))]
pub async fn delete_key(
    State(state): State<AppState>,
    ApiPath(id): ApiPath<i64>,
) -> Result<axum::Json<ApiKey>, ApiError> {
    let row = store::revoke(&state.pool, id).await?;
    tracing::info!(key = id, "API key revoked");
    Ok(axum::Json(row.to_key()?))
}

pub fn router() -> OpenApiRouter<AppState> {
    OpenApiRouter::new().routes(routes!(create_key, list_keys)).routes(routes!(get_key, delete_key))
}
