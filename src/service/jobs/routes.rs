//! `/v1/jobs` and the named job endpoints.

use super::kind::Submission;
use super::kinds::{self, off_runtime, JobInput, Registered, REGISTRY};
use super::labels::{self, tag_fault, JobLabels, Tag, MAX_NAME_CHARS, MAX_TAGS};
use super::lane::Lane;
use super::model::{Job, JobId, JobKind, JobStatus, JobSummary, ProgramPart};
use super::store;
use super::upload;
use crate::service::auth::Caller;
use crate::service::error::{excerpt, ApiError, FieldError, Problem};
use crate::service::extract::{parse_json, ApiPath, ApiQuery, JsonBytes};
use crate::service::resources::{Page, DEFAULT_PAGE_LIMIT, MAX_PAGE_LIMIT};
use crate::service::state::AppState;
use axum::extract::{FromRequest, Request, State};
use axum::http::{header, HeaderMap, HeaderValue, StatusCode};
use axum::response::{IntoResponse, Response};
use serde::{Deserialize, Serialize};
use std::time::Duration;
use utoipa::openapi::path::{HttpMethod, Operation};
use utoipa::openapi::request_body::RequestBodyBuilder;
use utoipa::openapi::{ContentBuilder, Ref, RefOr, Required};
use utoipa::{IntoParams, ToSchema};
use utoipa_axum::{router::OpenApiRouter, routes};

/// Seconds a client is told to wait before polling a job again.
const RETRY_AFTER_S: &str = "1";

/// A job to run.
#[derive(Debug, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
#[schema(example = json!({"kind": "conditions", "input": {"tool_type": "square", "diameter_mm": 10.0}}))]
pub struct JobRequest {
    pub kind: JobKind,
    /// The input of that kind of job.
    #[schema(value_type = JobInput)]
    pub input: serde_json::Value,
    /// What to call the job (1 to 200 characters, no control characters).
    #[schema(min_length = 1, max_length = 200, pattern = r"^[^\u0000-\u001F\u007F]*$")]
    pub name: Option<String>,
    /// Up to 20 distinct tags, each 1 to 64 ASCII letters, digits and `-_.:/`.
    #[serde(default)]
    #[schema(max_items = 20, value_type = Vec<Tag>)]
    pub tags: Vec<String>,
}

/// The `wait=N` preference of RFC 7240, if any, in seconds.
fn preferred_wait(headers: &HeaderMap) -> Option<u64> {
    headers
        .get_all("prefer")
        .iter()
        .filter_map(|v| v.to_str().ok())
        .flat_map(|v| v.split([',', ';']))
        .filter_map(|pref| {
            let (name, value) = pref.split_once('=')?;
            (name.trim().eq_ignore_ascii_case("wait")).then(|| value.trim().trim_matches('"').parse::<u64>().ok())?
        })
        .next()
}

/// Creates a job for `caller`; with `Prefer: wait=N` waits up to N seconds for it to
/// finish, or until the service begins to stop (the job goes on: 202 with `Location`).
async fn submit(
    state: &AppState,
    caller: &Caller,
    kind: JobKind,
    input: serde_json::Value,
    prefix: &str,
    labels: (JobLabels, Vec<FieldError>),
    headers: &HeaderMap,
) -> Result<Response, ApiError> {
    let submission = Submission { pool: &state.pool, caller, stock_memory_bytes: state.config.stock_memory_bytes() };
    let (labels, mut faults) = labels;
    faults.extend(labels.faults(""));
    // The faults of the input and of the labels come in one problem.
    let accepted = match kinds::accept(&submission, kind, input, prefix).await {
        Ok(accepted) if faults.is_empty() => accepted,
        Ok(_) => return Err(ApiError::Validation(faults)),
        Err(ApiError::Validation(input_faults)) => {
            return Err(ApiError::Validation(input_faults.into_iter().chain(faults).collect()))
        }
        Err(other) => return Err(other),
    };
    let id = uuid::Uuid::new_v4().to_string();
    let mut finished = state.jobs.subscribe();
    let mut stopping = state.jobs.stopping();
    let lane = Lane::of(kind, accepted.input.len());
    let new = store::NewJob {
        id: &id,
        kind,
        input: &accepted.input,
        prepared: &accepted.prepared,
        key_id: caller.key_id(),
        lane,
        labels: &labels,
    };
    store::insert(&state.pool, new).await?;
    state.jobs.wake();
    tracing::info!(job = %id, kind = kind.as_str(), "job queued");

    let location = format!("/v1/jobs/{id}");
    let wait = preferred_wait(headers).map(|n| n.min(state.config.effective_max_wait_s()));
    if let Some(seconds) = wait {
        let deadline = tokio::time::Instant::now() + Duration::from_secs(seconds);
        // The job is read again only when it is the one announced as finished, or when
        // announcements were missed: with many clients waiting, every finished job would
        // otherwise cost each of them a read.
        let mut look = true;
        loop {
            if look {
                let row = store::get(&state.pool, &id).await?;
                if row.status()?.is_terminal() {
                    let mut response = job_response(&state.pool, StatusCode::CREATED, &row).await?;
                    let h = response.headers_mut();
                    h.insert(header::LOCATION, header_value(&location));
                    h.insert("preference-applied", header_value(&format!("wait={seconds}")));
                    return Ok(response);
                }
            }
            if *stopping.borrow_and_update() {
                break;
            }
            tokio::select! {
                received = tokio::time::timeout_at(deadline, finished.recv()) => match received {
                    Err(_) => break,
                    Ok(Ok(done)) => look = done == id,
                    Ok(Err(tokio::sync::broadcast::error::RecvError::Lagged(_))) => look = true,
                    Ok(Err(tokio::sync::broadcast::error::RecvError::Closed)) => break,
                },
                _ = stopping.changed() => break,
            }
        }
    }
    let row = store::get(&state.pool, &id).await?;
    let mut response = job_response(&state.pool, StatusCode::ACCEPTED, &row).await?;
    let h = response.headers_mut();
    h.insert(header::LOCATION, header_value(&location));
    h.insert(header::RETRY_AFTER, HeaderValue::from_static(RETRY_AFTER_S));
    Ok(response)
}

/// A job as JSON with `status`: its row, and its result spliced in as stored, never parsed
/// (a result may be tens of megabytes).
pub(super) async fn job_response(
    pool: &crate::service::store::Pool,
    status: StatusCode,
    row: &store::JobRow,
) -> Result<Response, ApiError> {
    let job = row.to_job()?;
    let mut body = serde_json::to_vec(&job).map_err(|e| ApiError::Internal(format!("serializing a job: {e}")))?;
    let result = match row.status()? {
        JobStatus::Succeeded => store::result(pool, &row.id).await?,
        _ => None,
    };
    if let Some(result) = result {
        // `job` serializes as an object without `result`: close it with the stored one.
        body.pop();
        body.reserve(result.len() + RESULT_KEY.len() + 1);
        body.extend_from_slice(RESULT_KEY.as_bytes());
        body.extend_from_slice(result.as_bytes());
        body.push(b'}');
    }
    Ok((status, [(header::CONTENT_TYPE, HeaderValue::from_static(JSON))], body).into_response())
}

/// The key that [`job_response`] appends the stored result under.
const RESULT_KEY: &str = ",\"result\":";
/// The OpenAPI tag of the job routes (the role a route needs follows its tag).
const JOBS_TAG: &str = "jobs";
/// The content type of JSON answers.
const JSON: &str = "application/json";

fn header_value(text: &str) -> HeaderValue {
    HeaderValue::from_str(text).unwrap_or_else(|_| HeaderValue::from_static(""))
}

/// Creates a job of any kind.
///
/// Answers 202 with `Location` at once, or, with `Prefer: wait=N`, 201 with the
/// finished job when it finishes within N seconds. Invalid input is refused here with
/// a 4xx, never accepted as a job that fails later.
#[utoipa::path(post, path = "/v1/jobs", tag = "jobs", operation_id = "createJob", request_body = JobRequest,
    params(("Prefer" = Option<String>, Header, description = "wait=N: return the finished job if it finishes within N seconds")),
    responses(
        (status = 201, description = "Finished within the preferred wait", body = Job,
            headers(("Location" = String, description = "The job"), ("Preference-Applied" = String, description = "wait=N"))),
        (status = 202, description = "Queued (or the service is stopping: the job goes on); poll Location", body = Job,
            headers(("Location" = String, description = "The job"), ("Retry-After" = u64, description = "Seconds to wait before polling"))),
        (status = 400, description = "Malformed JSON", body = Problem, content_type = "application/problem+json"),
        (status = 422, description = "Every fault of the input, in one problem (its fields under `input`): refused fields, rows it names that are not in the database, the faults of its NC program or pocket", body = Problem, content_type = "application/problem+json")))]
pub async fn create_job(
    State(state): State<AppState>,
    caller: Caller,
    headers: HeaderMap,
    JsonBytes(body): JsonBytes,
) -> Result<Response, ApiError> {
    let request: JobRequest = off_runtime(move || parse_json(&body)).await?;
    submit(
        &state,
        &caller,
        request.kind,
        request.input,
        "input.",
        (JobLabels { name: request.name, tags: request.tags }, Vec::new()),
        &headers,
    )
    .await
}

/// Reads a job: status, progress, timestamps, result or error (the input is at
/// `links.input`).
#[utoipa::path(get, path = "/v1/jobs/{id}", tag = "jobs", operation_id = "getJob",
    params(("id" = JobId, Path, description = "Job id (a UUID)")),
    responses(
        (status = 200, description = "The job", body = Job),
        (status = 400, description = "A malformed job id", body = Problem, content_type = "application/problem+json"),
        (status = 404, description = "No such job", body = Problem, content_type = "application/problem+json")))]
pub async fn get_job(
    State(state): State<AppState>,
    caller: Caller,
    ApiPath(id): ApiPath<JobId>,
) -> Result<Response, ApiError> {
    let row = store::get_visible(&state.pool, &caller, &id).await?;
    job_response(&state.pool, StatusCode::OK, &row).await
}

/// A job's input as submitted (JSON), as stored.
#[utoipa::path(get, path = "/v1/jobs/{id}/input", tag = "jobs", operation_id = "getJobInput",
    params(("id" = JobId, Path, description = "Job id (a UUID)")),
    responses(
        (status = 200, description = "The input as submitted", body = JobInput),
        (status = 400, description = "A malformed job id", body = Problem, content_type = "application/problem+json"),
        (status = 404, description = "No such job", body = Problem, content_type = "application/problem+json")))]
pub async fn get_input(
    State(state): State<AppState>,
    caller: Caller,
    ApiPath(id): ApiPath<JobId>,
) -> Result<Response, ApiError> {
    let row = store::get_visible(&state.pool, &caller, &id).await?;
    let input = store::input(&state.pool, &row.id)
        .await?
        .ok_or_else(|| ApiError::Internal(format!("job {id} has no stored input")))?;
    Ok(([(header::CONTENT_TYPE, HeaderValue::from_static(JSON))], input).into_response())
}

/// Filters of `GET /v1/jobs`.
#[derive(Debug, Deserialize, IntoParams)]
#[serde(deny_unknown_fields)]
#[into_params(parameter_in = Query)]
pub struct JobFilter {
    pub status: Option<JobStatus>,
    pub kind: Option<JobKind>,
    /// Only jobs whose name contains this text, in any case (at most 200 characters).
    #[param(min_length = 1, max_length = 200)]
    pub name: Option<String>,
    /// Only jobs that have this tag; repeated (`tag=a&tag=b`), only jobs that have every
    /// one of them (at most 20).
    #[serde(default)]
    #[param(max_items = 20, value_type = Option<Vec<Tag>>, explode = true, style = Form)]
    pub tag: Vec<String>,
    /// 1 to 500 (default 50).
    pub limit: Option<i64>,
    pub offset: Option<i64>,
}

/// Lists jobs, newest first (a planner's key: its own jobs only).
#[utoipa::path(get, path = "/v1/jobs", tag = "jobs", operation_id = "listJobs", params(JobFilter),
    responses(
        (status = 200, description = "One page of jobs", body = Page<JobSummary>),
        (status = 400, description = "A bad query parameter", body = Problem, content_type = "application/problem+json")))]
pub async fn list_jobs(
    State(state): State<AppState>,
    caller: Caller,
    ApiQuery(filter): ApiQuery<JobFilter, true>,
) -> Result<axum::Json<Page<JobSummary>>, ApiError> {
    let limit = filter.limit.unwrap_or(DEFAULT_PAGE_LIMIT);
    let offset = filter.offset.unwrap_or(0);
    if !(1..=MAX_PAGE_LIMIT).contains(&limit) || offset < 0 {
        return Err(ApiError::Status {
            status: StatusCode::BAD_REQUEST,
            detail: format!("query parameter limit must be 1..={MAX_PAGE_LIMIT} and offset >= 0"),
        });
    }
    if filter.name.as_ref().is_some_and(|name| name.chars().count() > MAX_NAME_CHARS) {
        return Err(ApiError::BadRequest(format!("query parameter name: must be at most {MAX_NAME_CHARS} characters")));
    }
    if filter.tag.len() > MAX_TAGS {
        return Err(ApiError::BadRequest(format!(
            "query parameter tag: at most {MAX_TAGS} tags, got {}",
            filter.tag.len()
        )));
    }
    let bad_tags: Vec<String> = filter
        .tag
        .iter()
        .filter_map(|tag| tag_fault(tag).map(|reason| format!("tag \"{}\" {reason}", excerpt(tag))))
        .collect();
    if !bad_tags.is_empty() {
        return Err(ApiError::BadRequest(format!("query parameter tag: {}", bad_tags.join("; "))));
    }
    let list = store::ListFilter {
        status: filter.status,
        kind: filter.kind,
        owner: caller.own_jobs_only(),
        name: filter.name.as_deref(),
        tags: &filter.tag,
    };
    let (rows, total) = store::list(&state.pool, &list, limit, offset).await?;
    let items = rows.iter().map(store::JobRow::to_summary).collect::<Result<Vec<_>, _>>()?;
    Ok(axum::Json(Page { items, total, limit, offset }))
}

/// What `DELETE /v1/jobs/{id}` does.
#[derive(Debug, Deserialize, IntoParams)]
#[serde(deny_unknown_fields)]
#[into_params(parameter_in = Query)]
pub struct DeleteJobQuery {
    /// `true`: remove a finished job with its result, program and drawing (204), instead
    /// of cancelling it.
    pub purge: Option<bool>,
}

/// Cancels a job, or with `purge=true` removes a finished one.
///
/// A queued job is cancelled at once (200); a running one is asked to stop (202) and ends
/// `cancelled`; a finished job cannot be cancelled (409). `purge=true` removes a finished
/// job and everything it stored (204); a job still queued or running is refused (409:
/// cancel it first). A planner's key may cancel and remove only its own jobs.
#[utoipa::path(delete, path = "/v1/jobs/{id}", tag = "jobs", operation_id = "cancelJob",
    params(("id" = JobId, Path, description = "Job id (a UUID)"), DeleteJobQuery),
    responses(
        (status = 200, description = "Cancelled", body = Job),
        (status = 202, description = "Cancellation requested; the job stops shortly", body = Job),
        (status = 204, description = "Purged: the job and its data are gone"),
        (status = 400, description = "A malformed job id or a bad query parameter", body = Problem, content_type = "application/problem+json"),
        (status = 404, description = "No such job", body = Problem, content_type = "application/problem+json"),
        (status = 409, description = "Already finished (cancel), or not finished yet (purge)", body = Problem, content_type = "application/problem+json")))]
pub async fn cancel_job(
    State(state): State<AppState>,
    caller: Caller,
    ApiPath(id): ApiPath<JobId>,
    ApiQuery(query): ApiQuery<DeleteJobQuery>,
) -> Result<Response, ApiError> {
    let row = store::get_visible(&state.pool, &caller, &id).await?;
    if query.purge == Some(true) {
        if !store::purge(&state.pool, &id).await? {
            return Err(ApiError::Conflict(format!("job {id} is {}: cancel it before purging it", row.status)));
        }
        tracing::info!(job = %id, "job purged");
        crate::service::retention::vacuum_later(&state.pool);
        return Ok(StatusCode::NO_CONTENT.into_response());
    }
    let status = if store::cancel_queued(&state.pool, &id).await? {
        StatusCode::OK
    } else if store::request_cancel(&state.pool, &id).await? {
        state.jobs.cancel_running(&id);
        StatusCode::ACCEPTED
    } else {
        return Err(ApiError::Conflict(format!("job {id} has already finished ({})", row.status)));
    };
    job_response(&state.pool, status, &store::get(&state.pool, &id).await?).await
}

/// Query of `GET /v1/jobs/{id}/program`.
#[derive(Debug, Deserialize, IntoParams)]
#[serde(deny_unknown_fields)]
#[into_params(parameter_in = Query)]
pub struct ProgramQuery {
    /// Which program: `main` (default), the job's own (a feeds job's edited program, the
    /// trochoids', the plan's chosen tool's); `baseline`, a plan's conventional ball-end
    /// baseline; `base`, the program a trochoids job changed (the program sent, or the
    /// generated contour-parallel path), whose lines its base path's overloads name.
    pub part: Option<ProgramPart>,
}

/// An NC program a finished job produced, as plain text.
///
/// `part=baseline` gives a plan's conventional baseline (the R5 ball in thin levels, at its
/// `conventional_ball_roughing` conditions), written with the plan's output options;
/// `part=base` a trochoids job's base program, before the insertion (the G-code sent, or
/// the path sent or generated written with the job's output options).
#[utoipa::path(get, path = "/v1/jobs/{id}/program", tag = "jobs", operation_id = "getJobProgram",
    params(("id" = JobId, Path, description = "Job id (a UUID)"), ProgramQuery),
    responses(
        (status = 200, description = "The NC program", body = String, content_type = "text/plain"),
        (status = 400, description = "A malformed job id, or an unknown part or query parameter", body = Problem, content_type = "application/problem+json"),
        (status = 404, description = "No such job, or this job makes no such program (a baseline only comes with a plan that has one, a base program with a trochoids job)", body = Problem, content_type = "application/problem+json"),
        (status = 409, description = "Not finished yet", body = Problem, content_type = "application/problem+json")))]
pub async fn get_program(
    State(state): State<AppState>,
    caller: Caller,
    ApiPath(id): ApiPath<JobId>,
    ApiQuery(query): ApiQuery<ProgramQuery>,
) -> Result<Response, ApiError> {
    let row = store::get_visible(&state.pool, &caller, &id).await?;
    let part = query.part.unwrap_or_default();
    let program = store::program_part(&state.pool, &row.id, part).await?;
    match (row.status()?, program) {
        (_, Some(program)) => Ok(([(header::CONTENT_TYPE, "text/plain; charset=utf-8")], program).into_response()),
        (JobStatus::Queued | JobStatus::Running, None) if makes(row.kind()?, part) => {
            Err(ApiError::Conflict(format!("job {id} is {}; its program is not ready", row.status)))
        }
        (_, None) if part == ProgramPart::Main => {
            Err(ApiError::not_found(format!("job {id} ({}) has no NC program", row.kind)))
        }
        (_, None) => Err(ApiError::not_found(format!("job {id} ({}) has no {} program", row.kind, part.as_str()))),
    }
}

/// `true` when a job of `kind` may make the program `part` once it has finished.
fn makes(kind: JobKind, part: ProgramPart) -> bool {
    match part {
        ProgramPart::Main => true,
        ProgramPart::Baseline => kind == JobKind::Plan,
        ProgramPart::Base => kind == JobKind::Trochoids,
    }
}

/// The job routes.
pub fn router() -> OpenApiRouter<AppState> {
    let router = OpenApiRouter::new()
        .routes(routes!(create_job, list_jobs))
        .routes(routes!(get_job, cancel_job, super::relabel::relabel_job))
        .routes(routes!(get_program))
        .routes(routes!(get_input));
    let template = <__path_create_job as utoipa::Path>::operation();
    REGISTRY.iter().fold(router, |router, registered| {
        let kind = registered.kind;
        let create = move |State(state): State<AppState>, caller: Caller, headers: HeaderMap, request: Request| async move {
            let mut input = if upload::takes_program(kind) && upload::is_multipart(&request) {
                upload::read(request, state.config.body_limit).await?
            } else {
                let JsonBytes(body) = JsonBytes::from_request(request, &state).await?;
                off_runtime(move || parse_json::<serde_json::Value>(&body)).await?
            };
            let labels = labels::take(&mut input);
            submit(&state, &caller, kind, input, "", labels, &headers).await
        };
        let mut paths = utoipa::openapi::Paths::new();
        paths.add_path_operation(registered.path, vec![HttpMethod::Post], operation_of(registered, template.clone()));
        router.routes(((registered.schemas)(), paths, axum::routing::post(create)))
    })
}

/// The operation of the route that submits one kind alone (`POST /v1/conditions`, …):
/// `createJob`'s, with the kind's id, words and request.
fn operation_of(registered: &Registered, mut operation: Operation) -> Operation {
    let result = (registered.result_schema)();
    operation.operation_id = Some(registered.operation_id.to_string());
    operation.tags = Some(vec![JOBS_TAG.to_string()]);
    operation.summary = Some(registered.summary.to_string());
    operation.description = Some(format!(
        "{}\n\nJob kind `{}`; the finished job's `result` is a `{result}`.",
        registered.description,
        registered.kind.as_str()
    ));
    let body = crate::service::job_schema::submission_schema(registered.kind);
    let content = ContentBuilder::new().schema(Some(Ref::from_schema_name(body))).build();
    let mut body = RequestBodyBuilder::new().content(JSON, content).required(Some(Required::True));
    if upload::takes_program(registered.kind) {
        body = body
            .content(upload::MULTIPART, upload::content())
            .description(Some("The request as JSON, or the NC program as a file part `program` with the rest of the request as a JSON part `request` (multipart/form-data)."));
    }
    operation.request_body = Some(body.build());
    for (status, response) in operation.responses.responses.iter_mut() {
        if let RefOr::T(response) = response {
            match status.as_str() {
                "201" => response.description = format!("Finished within the preferred wait; result is a {result}"),
                "422" => response.description = registered.refuses.to_string(),
                _ => {}
            }
        }
    }
    operation
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_wait_preference_is_read_among_others() {
        let mut h = HeaderMap::new();
        h.insert("prefer", HeaderValue::from_static("respond-async, wait=7"));
        assert_eq!(preferred_wait(&h), Some(7));
        h.insert("prefer", HeaderValue::from_static("wait=abc"));
        assert_eq!(preferred_wait(&h), None);
    }
}
