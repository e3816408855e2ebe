//! Who is calling, and may they: the `Authorization: Bearer <key>` of every `/v1` request
//! is looked up, its role checked against the route's, and its rate limit applied. While
//! no key exists the service runs open (see [`crate::service::app::start`] for when it may).

use crate::service::error::ApiError;
use crate::service::keys::model::Role;
use crate::service::keys::store::{self as keys, KeyRow};
use crate::service::rate_limit::{retry_after_s, RateLimits};
use crate::service::state::AppState;
use axum::extract::{FromRequestParts, MatchedPath, Request, State};
use axum::http::{header, request::Parts, HeaderValue, Method, StatusCode};
use axum::middleware::Next;
use axum::response::{IntoResponse, Response};
use std::collections::HashMap;
use std::sync::Arc;
use std::time::Duration;

/// How stale a key's `last_used_at` may get before a request refreshes it: one write a
/// minute per key at most, not one per request.
const LAST_USED_RESOLUTION: Duration = Duration::from_secs(60);
/// Where the page and clients are told to look in a 401.
const WWW_AUTHENTICATE: &str = "Bearer realm=\"dieplan\"";

/// The caller of a request, as handlers see it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Caller {
    /// No key exists: the service runs open and every caller may do everything.
    Open,
    /// A request with a valid key.
    Key { id: i64, role: Role },
}

impl Caller {
    /// The key to record on the jobs this caller creates.
    pub fn key_id(&self) -> Option<i64> {
        match self {
            Caller::Open => None,
            Caller::Key { id, .. } => Some(*id),
        }
    }

    /// The key whose jobs alone this caller may see, if it is limited so (a planner).
    pub fn own_jobs_only(&self) -> Option<i64> {
        match self {
            Caller::Key { id, role: Role::Planner } => Some(*id),
            _ => None,
        }
    }

    /// `true` when this caller may see (and, with a role that may cancel, cancel) a job
    /// made by `owner`.
    pub fn may_see_job(&self, owner: Option<i64>) -> bool {
        self.own_jobs_only().is_none_or(|own| owner == Some(own))
    }
}

impl<S: Send + Sync> FromRequestParts<S> for Caller {
    type Rejection = ApiError;

    async fn from_request_parts(parts: &mut Parts, _: &S) -> Result<Self, Self::Rejection> {
        parts
            .extensions
            .get::<Caller>()
            .cloned()
            .ok_or_else(|| ApiError::Internal("a /v1 route was reached without authentication".into()))
    }
}

/// The role each route needs, by method and path template, taken from the OpenAPI
/// document (see [`required_role`]).
#[derive(Debug, Clone, Default)]
pub struct RouteRoles(Arc<HashMap<(Method, String), Role>>);

impl RouteRoles {
    pub fn from_openapi(doc: &utoipa::openapi::OpenApi) -> RouteRoles {
        let mut roles = HashMap::new();
        for (path, item) in &doc.paths.paths {
            for (method, op) in operations(item) {
                let tag = op.tags.as_ref().and_then(|t| t.first()).map(String::as_str);
                if let Some(role) = required_role(&method, path, tag) {
                    roles.insert((method, path.clone()), role);
                }
            }
        }
        RouteRoles(Arc::new(roles))
    }

    /// The role `method` on `path` needs; `HEAD` needs what `GET` does (axum answers it
    /// with the `GET` handler).
    fn get(&self, method: &Method, path: &str) -> Option<Role> {
        let method = if method == Method::HEAD { Method::GET } else { method.clone() };
        self.0.get(&(method, path.to_string())).copied()
    }
}

/// The operations of a path item with their methods.
pub fn operations(item: &utoipa::openapi::PathItem) -> Vec<(Method, &utoipa::openapi::path::Operation)> {
    [
        (Method::GET, &item.get),
        (Method::POST, &item.post),
        (Method::PUT, &item.put),
        (Method::PATCH, &item.patch),
        (Method::DELETE, &item.delete),
        (Method::HEAD, &item.head),
    ]
    .into_iter()
    .filter_map(|(method, op)| op.as_ref().map(|op| (method, op)))
    .collect()
}

/// The role a route needs: none outside `/v1` (health); admin for the keys; reader to
/// read; planner to create and cancel jobs (the `jobs` tag); admin for every other write
/// (the database).
pub fn required_role(method: &Method, path: &str, tag: Option<&str>) -> Option<Role> {
    if !path.starts_with("/v1/") {
        None
    } else if path == "/v1/keys" || path.starts_with("/v1/keys/") {
        Some(Role::Admin)
    } else if method == Method::GET || method == Method::HEAD {
        Some(Role::Reader)
    } else if tag == Some("jobs") {
        Some(Role::Planner)
    } else {
        Some(Role::Admin)
    }
}

/// What the authentication middleware needs.
#[derive(Clone)]
pub struct AuthState {
    pub app: AppState,
    pub roles: RouteRoles,
    pub limits: Arc<RateLimits>,
}

/// Authenticates a request to a documented route and puts its [`Caller`] in the request's
/// extensions; answers 401, 403 or 429 (with `Retry-After`) instead when it may not pass.
pub async fn authenticate(
    State(auth): State<AuthState>,
    matched: Option<MatchedPath>,
    mut request: Request,
    next: Next,
) -> Response {
    let needed = matched.and_then(|m| auth.roles.get(request.method(), m.as_str()));
    let Some(needed) = needed else {
        return next.run(request).await;
    };
    let caller = match identify(&auth, request.headers().get(header::AUTHORIZATION)).await {
        Ok(caller) => caller,
        Err(response) => return response,
    };
    if let Caller::Key { role, .. } = caller {
        if !role.covers(needed) {
            let detail =
                format!("this needs a key of role {} or above; this key is a {} key", needed.as_str(), role.as_str());
            return ApiError::Status { status: StatusCode::FORBIDDEN, detail }.into_response();
        }
    }
    request.extensions_mut().insert(caller);
    next.run(request).await
}

/// The caller a request's `Authorization` header names, or the 401 or 429 answer.
async fn identify(auth: &AuthState, header: Option<&HeaderValue>) -> Result<Caller, Response> {
    let pool = &auth.app.pool;
    let Some(header) = header else {
        return match keys::any_active(pool).await {
            Ok(false) => Ok(Caller::Open),
            Ok(true) => Err(unauthorized("this service needs an API key: send `Authorization: Bearer <key>`")),
            Err(e) => Err(ApiError::from(e).into_response()),
        };
    };
    let secret = header
        .to_str()
        .ok()
        .and_then(|v| v.split_once(' '))
        .filter(|(scheme, _)| scheme.eq_ignore_ascii_case("bearer"))
        .map(|(_, secret)| secret.trim())
        .filter(|secret| !secret.is_empty());
    let Some(secret) = secret else {
        return Err(unauthorized("the Authorization header must be `Bearer <key>`"));
    };
    let key = match keys::find_active(pool, secret).await {
        Ok(Some(key)) => key,
        Ok(None) => return Err(unauthorized("this API key is unknown or revoked")),
        Err(e) => return Err(ApiError::from(e).into_response()),
    };
    let role = key.role().map_err(IntoResponse::into_response)?;
    let per_minute = key.rate_limit_per_minute.unwrap_or(auth.app.config.rate_limit_per_minute);
    match auth.limits.check(pool, key.id, per_minute).await {
        Ok(None) => {}
        Ok(Some(wait)) => return Err(too_many_requests(wait, per_minute)),
        Err(e) => return Err(ApiError::from(e).into_response()),
    }
    note_use(pool, &key);
    Ok(Caller::Key { id: key.id, role })
}

/// Refreshes a key's `last_used_at` in the background when it is older than
/// [`LAST_USED_RESOLUTION`].
fn note_use(pool: &crate::service::store::Pool, key: &KeyRow) {
    let stale = key
        .last_used_at
        .as_deref()
        .and_then(|t| time::OffsetDateTime::parse(t, &time::format_description::well_known::Rfc3339).ok())
        .is_none_or(|t| time::OffsetDateTime::now_utc() - t > LAST_USED_RESOLUTION);
    if stale {
        let (pool, id) = (pool.clone(), key.id);
        tokio::spawn(async move {
            if let Err(e) = keys::touch(&pool, id).await {
                tracing::warn!(key = id, error = %e, "could not note the use of a key");
            }
        });
    }
}

fn unauthorized(detail: &str) -> Response {
    let mut response =
        ApiError::Status { status: StatusCode::UNAUTHORIZED, detail: detail.to_string() }.into_response();
    response.headers_mut().insert(header::WWW_AUTHENTICATE, HeaderValue::from_static(WWW_AUTHENTICATE));
    response
}

fn too_many_requests(wait: Duration, per_minute: i64) -> Response {
    let seconds = retry_after_s(wait);
    let detail = format!("this key may make {per_minute} requests a minute: retry in {seconds} s");
    let mut response = ApiError::Status { status: StatusCode::TOO_MANY_REQUESTS, detail }.into_response();
    response.headers_mut().insert(header::RETRY_AFTER, HeaderValue::from(seconds));
    response
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reading_needs_a_reader_jobs_a_planner_and_every_other_write_an_admin() {
        assert_eq!(required_role(&Method::GET, "/healthz", Some("health")), None);
        assert_eq!(required_role(&Method::GET, "/v1/tools", Some("database")), Some(Role::Reader));
        assert_eq!(required_role(&Method::GET, "/v1/jobs/{id}", Some("jobs")), Some(Role::Reader));
        assert_eq!(required_role(&Method::POST, "/v1/plans", Some("jobs")), Some(Role::Planner));
        assert_eq!(required_role(&Method::DELETE, "/v1/jobs/{id}", Some("jobs")), Some(Role::Planner));
        assert_eq!(required_role(&Method::PATCH, "/v1/force-models/{id}", Some("database")), Some(Role::Admin));
        assert_eq!(required_role(&Method::GET, "/v1/keys", Some("keys")), Some(Role::Admin));
    }

    #[test]
    fn a_planner_sees_only_its_own_jobs_and_the_others_see_all() {
        let planner = Caller::Key { id: 4, role: Role::Planner };
        assert!(planner.may_see_job(Some(4)));
        assert!(!planner.may_see_job(Some(5)));
        assert!(!planner.may_see_job(None));
        for caller in
            [Caller::Open, Caller::Key { id: 1, role: Role::Reader }, Caller::Key { id: 2, role: Role::Admin }]
        {
            assert!(caller.may_see_job(Some(4)) && caller.may_see_job(None));
        }
    }

    #[test]
    fn each_role_covers_the_ones_below_it() {
        assert!(Role::Admin.covers(Role::Planner) && Role::Planner.covers(Role::Reader));
        assert!(!Role::Reader.covers(Role::Planner) && !Role::Planner.covers(Role::Admin));
    }
}
