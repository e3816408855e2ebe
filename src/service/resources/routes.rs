//! The six routes of a database resource (list, get, create, replace, patch, delete),
//! generated for each table with its own OpenAPI operation ids and schemas.

use super::SqlValue;

/// `column = ?` when the filter value is present.
pub fn eq<V: Into<SqlValue>>(column: &str, value: Option<V>) -> Option<(String, Vec<SqlValue>)> {
    value.map(|v| (format!("{column} = ?"), vec![v.into()]))
}

/// Generates `pub mod $module` with the six handlers of one resource.
#[macro_export]
macro_rules! crud_api {
    (
        module: $m:ident,
        record: $rec:ident,
        data: $data:ident,
        filter: $filter:ident,
        collection: $coll:literal,
        item: $item:literal,
        tag: $tag:literal,
        ids: [$list:literal, $get:literal, $create:literal, $replace:literal, $patch:literal, $delete:literal] $(,)?
    ) => {
        pub mod $m {
            use super::*;
            use axum::extract::State;
            use axum::http::{header, HeaderMap, StatusCode};
            use axum::response::IntoResponse;
            use $crate::service::error::{ApiError, Problem};
            use $crate::service::etag;
            use $crate::service::extract::{ApiJson, ApiPath, ApiQuery};
            use $crate::service::resources::{crud, Page};
            use $crate::service::state::AppState;

            /// Lists rows, filtered and paged.
            #[utoipa::path(get, path = $coll, tag = $tag, operation_id = $list, params($filter),
                responses(
                    (status = 200, description = "One page of rows", body = Page<$rec>),
                    (status = 400, description = "A bad query parameter", body = Problem, content_type = "application/problem+json")))]
            pub async fn list(
                State(state): State<AppState>,
                ApiQuery(filter): ApiQuery<$filter>,
            ) -> Result<axum::Json<Page<$rec>>, ApiError> {
                Ok(axum::Json(crud::list::<$rec, _>(&state.pool, &filter).await?))
            }

            /// Reads one row, with its entity tag in `ETag` (send it back in `If-Match`
            /// to write only if nobody changed the row meanwhile).
            #[utoipa::path(get, path = $item, tag = $tag, operation_id = $get,
                params(("id" = i64, Path, description = "Row id")),
                responses(
                    (status = 200, description = "The row", body = $rec,
                        headers(("ETag" = String, description = "The row's entity tag"))),
                    (status = 404, description = "No such row", body = Problem, content_type = "application/problem+json")))]
            pub async fn get(
                State(state): State<AppState>,
                ApiPath(id): ApiPath<i64>,
            ) -> Result<impl IntoResponse, ApiError> {
                let record = crud::get::<$rec>(&state.pool, id).await?;
                Ok(([etag::header(&record)], axum::Json(record)))
            }

            /// Creates a row (`source` defaults to `user`).
            #[utoipa::path(post, path = $coll, tag = $tag, operation_id = $create, request_body = $data,
                responses(
                    (status = 201, description = "Created; Location names the new row", body = $rec,
                        headers(("Location" = String, description = "The new row"), ("ETag" = String, description = "The row's entity tag"))),
                    (status = 400, description = "Malformed JSON", body = Problem, content_type = "application/problem+json"),
                    (status = 409, description = "A row with the same unique key exists", body = Problem, content_type = "application/problem+json"),
                    (status = 422, description = "A refused field", body = Problem, content_type = "application/problem+json")))]
            pub async fn create(
                State(state): State<AppState>,
                ApiJson(data): ApiJson<$data>,
            ) -> Result<impl IntoResponse, ApiError> {
                let record = crud::create::<$rec>(&state.pool, data).await?;
                let location = format!("{}/{}", $coll, record.id);
                Ok((StatusCode::CREATED, [(header::LOCATION, location)], [etag::header(&record)], axum::Json(record)))
            }

            /// Replaces a row's data (`source` defaults to `user`); the row is marked edited.
            /// With `If-Match`, only if the row still has that entity tag (else 412).
            #[utoipa::path(put, path = $item, tag = $tag, operation_id = $replace, request_body = $data,
                params(("id" = i64, Path, description = "Row id"),
                    ("If-Match" = Option<String>, Header, description = "The row's entity tag as read (`ETag`), or `*`: write only if it is still so")),
                responses(
                    (status = 200, description = "The updated row", body = $rec,
                        headers(("ETag" = String, description = "The row's new entity tag"))),
                    (status = 404, description = "No such row", body = Problem, content_type = "application/problem+json"),
                    (status = 409, description = "A row with the same unique key exists", body = Problem, content_type = "application/problem+json"),
                    (status = 412, description = "The row changed since it was read (If-Match)", body = Problem, content_type = "application/problem+json"),
                    (status = 422, description = "A refused field", body = Problem, content_type = "application/problem+json")))]
            pub async fn replace(
                State(state): State<AppState>,
                ApiPath(id): ApiPath<i64>,
                headers: HeaderMap,
                ApiJson(data): ApiJson<$data>,
            ) -> Result<impl IntoResponse, ApiError> {
                let record = crud::replace::<$rec>(&state.pool, id, data, etag::if_match(&headers).as_deref()).await?;
                Ok(([etag::header(&record)], axum::Json(record)))
            }

            /// Changes some fields (JSON merge patch, RFC 7396); unless the patch names
            /// `source`, the row becomes the shop's (`source = user`). Two patches of
            /// different fields both land. With `If-Match`, only if the row still has that
            /// entity tag (else 412).
            #[utoipa::path(patch, path = $item, tag = $tag, operation_id = $patch,
                request_body(content = Object, content_type = "application/merge-patch+json", description = "The fields to change"),
                params(("id" = i64, Path, description = "Row id"),
                    ("If-Match" = Option<String>, Header, description = "The row's entity tag as read (`ETag`), or `*`: write only if it is still so")),
                responses(
                    (status = 200, description = "The updated row", body = $rec,
                        headers(("ETag" = String, description = "The row's new entity tag"))),
                    (status = 404, description = "No such row", body = Problem, content_type = "application/problem+json"),
                    (status = 409, description = "A row with the same unique key exists", body = Problem, content_type = "application/problem+json"),
                    (status = 412, description = "The row changed since it was read (If-Match)", body = Problem, content_type = "application/problem+json"),
                    (status = 422, description = "A refused field", body = Problem, content_type = "application/problem+json")))]
            pub async fn patch(
                State(state): State<AppState>,
                ApiPath(id): ApiPath<i64>,
                headers: HeaderMap,
                ApiJson(patch): ApiJson<serde_json::Value>,
            ) -> Result<impl IntoResponse, ApiError> {
                let record = crud::patch::<$rec>(&state.pool, id, patch, etag::if_match(&headers).as_deref()).await?;
                Ok(([etag::header(&record)], axum::Json(record)))
            }

            /// Deletes a row that nothing references. With `If-Match`, only if the row
            /// still has that entity tag (else 412).
            #[utoipa::path(delete, path = $item, tag = $tag, operation_id = $delete,
                params(("id" = i64, Path, description = "Row id"),
                    ("If-Match" = Option<String>, Header, description = "The row's entity tag as read (`ETag`), or `*`: delete only if it is still so")),
                responses(
                    (status = 204, description = "Deleted"),
                    (status = 404, description = "No such row", body = Problem, content_type = "application/problem+json"),
                    (status = 409, description = "Other rows still reference it", body = Problem, content_type = "application/problem+json"),
                    (status = 412, description = "The row changed since it was read (If-Match)", body = Problem, content_type = "application/problem+json")))]
            pub async fn delete(
                State(state): State<AppState>,
                ApiPath(id): ApiPath<i64>,
                headers: HeaderMap,
            ) -> Result<StatusCode, ApiError> {
                crud::delete::<$rec>(&state.pool, id, etag::if_match(&headers).as_deref()).await?;
                Ok(StatusCode::NO_CONTENT)
            }

            /// The routes of this resource with their OpenAPI operations.
            pub fn router() -> utoipa_axum::router::OpenApiRouter<AppState> {
                utoipa_axum::router::OpenApiRouter::new()
                    .routes(utoipa_axum::routes!(list, create))
                    .routes(utoipa_axum::routes!(get, replace, patch, delete))
            }
        }
    };
}
