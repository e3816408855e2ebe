//! `GET /v1/jobs/{id}/trace`: the vertices of a drawn path with where each is (x, y, z,
//! NC line, path distance) and its values (α, feed, force, wear), as the drawing draws
//! them: what the page reads under the pointer, marks for selected NC lines, and maps a
//! chart's path distance to a line with.

use super::drawings::scene_of;
use super::model::JobId;
use crate::core::drawing::palette::{self, quantity_bin_color, BINS, COOL_BINS};
use crate::core::drawing::plan_view::value_scale;
use crate::core::drawing::scene::{Quantity, Run, Scene};
use crate::service::auth::Caller;
use crate::service::error::{excerpt, ApiError, Problem};
use crate::service::extract::{ApiPath, ApiQuery};
use crate::service::state::AppState;
use axum::extract::State;
use axum::response::{IntoResponse, Response};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use utoipa::{IntoParams, ToSchema};
use utoipa_axum::{router::OpenApiRouter, routes};

/// Which path `GET /v1/jobs/{id}/trace` gives.
#[derive(Debug, Deserialize, IntoParams)]
#[serde(deny_unknown_fields)]
#[into_params(parameter_in = Query)]
pub struct TraceQuery {
    /// A path the job's views list (default: the last, as the drawing).
    pub path: Option<String>,
}

/// One stretch of a path drawn in one style (feed or rapid, one layer): its vertices
/// and, per vertex, where it is and its values. Every list has one item per vertex.
#[derive(Debug, Serialize, ToSchema)]
pub struct TraceRun {
    /// Index into the job's layers (null: not in one layer).
    pub layer: Option<usize>,
    pub rapid: bool,
    /// x, y, mm.
    pub points: Vec<[f64; 2]>,
    /// The tool's height, mm (empty for jobs drawn before it was kept).
    pub z: Vec<f32>,
    /// The NC line (or move number) of the move the vertex ends: a line of the program
    /// the path refers to (empty for jobs drawn before it was kept).
    pub lines: Vec<u32>,
    /// Path distance, mm: the x axis of the job's charts (empty likewise).
    pub s_mm: Vec<f64>,
    /// Per quantity (`alpha` °, `feed` mm/min, `force` N, `wear` % of a tool per m), the
    /// largest value of the stretch that ends at the vertex; null where there is none
    /// (air, rapids).
    pub values: BTreeMap<String, Vec<Option<f32>>>,
}

impl From<Run> for TraceRun {
    fn from(run: Run) -> TraceRun {
        TraceRun {
            layer: run.layer,
            rapid: run.rapid,
            points: run.points,
            z: run.z,
            lines: run.lines,
            s_mm: run.s_mm,
            values: run.values.into_iter().map(|(q, v)| (q.as_str().to_string(), v)).collect(),
        }
    }
}

/// How the plan view colours a quantity, for a client that draws the path itself (the
/// page's 3-D view): the same range and colours. A value's bin: without a limit,
/// `floor(32·(v − min)/(max − min))`; with one (α), values up to the limit fall in the
/// first `cool_bins` bins over `min..limit` and values above it in the rest over
/// `limit..max`; each clamped to its bins (an empty range: its first bin).
#[derive(Debug, Serialize, ToSchema)]
pub struct ColorScale {
    pub min: f64,
    pub max: f64,
    /// Values above it are hot (α's limit, deg); null for the other quantities.
    pub limit: Option<f64>,
    /// A few values lie above `max` (outliers left out of the range): they take the top colour.
    pub top_clipped: bool,
    /// Bins over `min..=limit` when there is a limit.
    pub cool_bins: usize,
    /// The colour of each bin, `#rrggbb`, lowest first.
    pub colors: Vec<String>,
    /// The legend's caption, with the unit.
    pub caption: String,
}

impl ColorScale {
    fn of(scene: &Scene, q: Quantity) -> ColorScale {
        let scale = value_scale(scene, q);
        ColorScale {
            min: scale.min,
            max: scale.max,
            limit: scale.limit,
            top_clipped: scale.top_clipped,
            cool_bins: COOL_BINS,
            colors: (0..BINS).map(|b| quantity_bin_color(q, b).to_string()).collect(),
            caption: q.caption().to_string(),
        }
    }
}

/// A drawn path of a job, vertex by vertex.
#[derive(Debug, Serialize, ToSchema)]
pub struct PathTrace {
    pub path: String,
    pub runs: Vec<TraceRun>,
    /// Per quantity the path can be coloured by, the plan view's colour scale (the same
    /// over every path of the job).
    pub scales: BTreeMap<String, ColorScale>,
    /// The plan view's colour of rapids (drawn dashed), `#rrggbb`.
    pub rapid_color: String,
    /// Its colour of a vertex without a value (air), `#rrggbb`.
    pub no_value_color: String,
}

/// The vertices of one drawn path of a finished job, with their height, NC line, path
/// distance and values (simplified as the drawing is, within a fraction of a pixel at
/// its full view).
#[utoipa::path(get, path = "/v1/jobs/{id}/trace", tag = "jobs", operation_id = "getJobTrace",
    params(("id" = JobId, Path, description = "Job id (a UUID)"), TraceQuery),
    responses(
        (status = 200, description = "The path, vertex by vertex", body = PathTrace),
        (status = 400, description = "A malformed job id or query parameter", body = Problem, content_type = "application/problem+json"),
        (status = 404, description = "No such job, or no such path", body = Problem, content_type = "application/problem+json"),
        (status = 409, description = "Not finished, or a kind of job without drawings", body = Problem, content_type = "application/problem+json")))]
pub async fn get_trace(
    State(state): State<AppState>,
    caller: Caller,
    ApiPath(id): ApiPath<JobId>,
    ApiQuery(query): ApiQuery<TraceQuery>,
) -> Result<Response, ApiError> {
    let mut scene = scene_of(&state, &caller, &id).await?;
    let found = match query.path.as_deref() {
        Some(name) => scene.paths.iter().position(|p| p.name == name),
        None => scene.paths.len().checked_sub(1),
    };
    let Some(index) = found else {
        let name = query.path.as_deref().map(excerpt).unwrap_or_default();
        return Err(ApiError::not_found(format!("job {id} has no path {name:?} to trace")));
    };
    let scales = scene
        .quantities(&scene.paths[index].name)
        .into_iter()
        .map(|q| (q.as_str().to_string(), ColorScale::of(&scene, q)))
        .collect();
    let path = scene.paths.swap_remove(index);
    let trace = PathTrace {
        path: path.name,
        runs: path.runs.into_iter().map(TraceRun::from).collect(),
        scales,
        rapid_color: palette::RAPID.to_string(),
        no_value_color: palette::NO_VALUE.to_string(),
    };
    let body = tokio::task::spawn_blocking(move || serde_json::to_vec(&trace))
        .await
        .map_err(|e| ApiError::Internal(format!("trace: {e}")))?
        .map_err(|e| ApiError::Internal(format!("trace: {e}")))?;
    Ok(([(axum::http::header::CONTENT_TYPE, "application/json")], body).into_response())
}

/// The trace route.
pub fn router() -> OpenApiRouter<AppState> {
    OpenApiRouter::new().routes(routes!(get_trace))
}
