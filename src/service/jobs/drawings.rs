//! Drawings and charts of a finished job as SVG: `GET /v1/jobs/{id}/views` lists what can
//! be drawn, `drawing.svg` draws the plan view, `charts/{chart}` one chart.

use super::model::{JobId, JobKind, JobStatus};
use super::store;
use crate::core::drawing::chart::render_chart;
use crate::core::drawing::display_units::{in_unit, LengthUnit};
use crate::core::drawing::frame::Extent;
use crate::core::drawing::plan_view::{render_drawing, DrawOptions};
use crate::core::drawing::scene::{Quantity, Scene};
use crate::service::auth::Caller;
use crate::service::error::{excerpt, ApiError, Problem, Validator};
use crate::service::extract::{ApiPath, ApiQuery};
use crate::service::state::AppState;
use axum::extract::State;
use axum::http::header;
use axum::response::{IntoResponse, Response};
use serde::{Deserialize, Serialize};
use utoipa::{IntoParams, ToSchema};
use utoipa_axum::{router::OpenApiRouter, routes};

/// Default size of a chart, px.
pub const DEFAULT_CHART_WIDTH_PX: u32 = 900;
pub const DEFAULT_CHART_HEIGHT_PX: u32 = 360;
/// Bounds of a chart's size, px.
pub const MIN_CHART_PX: u32 = 200;
pub const MAX_CHART_PX: u32 = 4000;

const SVG: &str = "image/svg+xml; charset=utf-8";

/// Whether jobs of `kind` leave a drawing.
pub fn draws(kind: JobKind) -> bool {
    !matches!(kind, JobKind::Conditions)
}

/// A path of the scene and the quantities it can be coloured by.
#[derive(Debug, Serialize, ToSchema)]
pub struct PathView {
    pub name: String,
    /// `alpha`, `feed`, `force`, `wear`.
    pub quantities: Vec<String>,
}

/// A layer of the scene.
#[derive(Debug, Serialize, ToSchema)]
pub struct LayerView {
    pub index: usize,
    pub name: String,
    pub z_top: f64,
    pub z_bottom: f64,
}

/// A chart of the job.
#[derive(Debug, Serialize, ToSchema)]
pub struct ChartLink {
    pub id: String,
    pub title: String,
    pub href: String,
}

/// What can be drawn of a job.
#[derive(Debug, Serialize, ToSchema)]
pub struct JobViews {
    pub title: String,
    pub paths: Vec<PathView>,
    pub layers: Vec<LayerView>,
    pub charts: Vec<ChartLink>,
    /// The plan view (`GET` it with the query parameters of `getJobDrawing`).
    pub drawing: String,
    pub critical_regions: usize,
    pub trochoids: usize,
    /// The finest detail the drawn paths keep, mm (the tolerance they were traced to): a
    /// window can be drawn down to a few times this, and no smaller than 0.001 mm; null for
    /// a job drawn before it was kept.
    pub detail_mm: Option<f64>,
}

/// Query of `GET /v1/jobs/{id}/drawing.svg`.
#[derive(Debug, Deserialize, IntoParams)]
#[serde(deny_unknown_fields)]
#[into_params(parameter_in = Query)]
pub struct DrawingQuery {
    /// The path to draw (default: the last one, e.g. `planned`); `getJobViews` lists a
    /// job's paths.
    #[param(pattern = "^(input|optimised|base|planned|program|baseline)$")]
    pub path: Option<String>,
    /// Colour the path by `alpha`, `feed`, `force` or `wear` (default: alpha where known).
    #[param(pattern = "^(alpha|feed|force|wear)$")]
    pub color: Option<String>,
    /// One layer by index (default: all).
    #[param(minimum = 0, maximum = 4294967295_u64)]
    pub layer: Option<usize>,
    /// Draw the rapids, dashed (default true).
    pub rapids: Option<bool>,
    /// Draw the medial axis by R/r class (default true).
    pub medial: Option<bool>,
    /// Mark the critical regions (default true).
    pub regions: Option<bool>,
    /// Mark the trochoids (default true).
    pub trochoids: Option<bool>,
    /// Width of the drawing, px (200 to 4000, default 1000).
    #[param(minimum = 200, maximum = 4000)]
    pub width: Option<u32>,
    /// A window to draw, mm: give all four of `x_min`, `y_min`, `x_max`, `y_max` to draw
    /// that part of the plane anew at its own scale (a zoomed view: more detail, labels
    /// and strokes at their usual size); default the whole job. The drawing's `frame`
    /// element says how mm map onto its px.
    pub x_min: Option<f64>,
    pub y_min: Option<f64>,
    pub x_max: Option<f64>,
    pub y_max: Option<f64>,
    /// The unit of the frame's coordinates, the scale bar, the feed legend and the length
    /// labels: `mm` (default) or `inch` (in, in/min). The window and the `frame` element
    /// stay in mm.
    pub units: Option<LengthUnit>,
}

impl DrawingQuery {
    /// The window asked for: all four bounds, or none.
    fn window(&self) -> Result<Option<Extent>, ApiError> {
        match (self.x_min, self.y_min, self.x_max, self.y_max) {
            (Some(x_min), Some(y_min), Some(x_max), Some(y_max)) => Ok(Some(Extent { x_min, y_min, x_max, y_max })),
            (None, None, None, None) => Ok(None),
            _ => Err(ApiError::field("x_min", "give all four of x_min, y_min, x_max and y_max, or none")),
        }
    }
}

/// Query of `GET /v1/jobs/{id}/charts/{chart}`.
#[derive(Debug, Deserialize, IntoParams)]
#[serde(deny_unknown_fields)]
#[into_params(parameter_in = Query)]
pub struct ChartQuery {
    /// Width, px (200 to 4000, default 900).
    #[param(minimum = 200, maximum = 4000)]
    pub width: Option<u32>,
    /// Height, px (200 to 4000, default 360).
    #[param(minimum = 200, maximum = 4000)]
    pub height: Option<u32>,
    /// The unit of its path distances and feeds: `mm` (default) or `inch` (in, in/min).
    pub units: Option<LengthUnit>,
}

/// The scene of a finished job, or why there is none.
pub(super) async fn scene_of(state: &AppState, caller: &Caller, id: &str) -> Result<Scene, ApiError> {
    let row = store::get_visible(&state.pool, caller, id).await?;
    let kind = row.kind()?;
    if !draws(kind) {
        return Err(ApiError::Conflict(format!("a {} job has nothing to draw", kind.as_str())));
    }
    match row.status()? {
        JobStatus::Succeeded => {}
        status => {
            return Err(ApiError::Conflict(format!(
                "job {id} is {}; only a succeeded job can be drawn",
                status.as_str()
            )))
        }
    }
    let text = store::scene(&state.pool, id).await?.ok_or_else(|| {
        ApiError::Conflict(format!("job {id} finished before drawings were kept: run it again to draw it"))
    })?;
    tokio::task::spawn_blocking(move || serde_json::from_str::<Scene>(&text))
        .await
        .map_err(|e| ApiError::Internal(format!("reading a scene: {e}")))?
        .map_err(|e| ApiError::Internal(format!("job {id}: stored scene unreadable: {e}")))
}

fn svg(body: String) -> Response {
    ([(header::CONTENT_TYPE, SVG), (header::CACHE_CONTROL, "private, max-age=3600")], body).into_response()
}

/// What can be drawn of a finished job: its paths and the quantities each can be
/// coloured by, its layers and its charts.
#[utoipa::path(get, path = "/v1/jobs/{id}/views", tag = "jobs", operation_id = "getJobViews",
    params(("id" = JobId, Path, description = "Job id (a UUID)")),
    responses(
        (status = 200, description = "What can be drawn", body = JobViews),
        (status = 400, description = "A malformed job id", body = Problem, content_type = "application/problem+json"),
        (status = 404, description = "No such job", body = Problem, content_type = "application/problem+json"),
        (status = 409, description = "Not finished, or a kind of job without drawings", body = Problem, content_type = "application/problem+json")))]
pub async fn get_views(
    State(state): State<AppState>,
    caller: Caller,
    ApiPath(id): ApiPath<JobId>,
) -> Result<Response, ApiError> {
    let scene = scene_of(&state, &caller, &id).await?;
    let views = JobViews {
        title: scene.title.clone(),
        paths: scene
            .paths
            .iter()
            .map(|p| PathView {
                name: p.name.clone(),
                quantities: scene.quantities(&p.name).into_iter().map(|q| q.as_str().to_string()).collect(),
            })
            .collect(),
        layers: scene
            .layers
            .iter()
            .enumerate()
            .map(|(index, l)| LayerView { index, name: l.name.clone(), z_top: l.z_top, z_bottom: l.z_bottom })
            .collect(),
        charts: scene
            .charts
            .iter()
            .map(|c| ChartLink {
                id: c.id.clone(),
                title: c.title.clone(),
                href: format!("/v1/jobs/{id}/charts/{}", c.id),
            })
            .collect(),
        drawing: format!("/v1/jobs/{id}/drawing.svg"),
        critical_regions: scene.regions.len(),
        trochoids: scene.trochoids.len(),
        detail_mm: scene.detail_mm(),
    };
    Ok(axum::Json(views).into_response())
}

/// The plan view of a finished job as SVG: outlines, the tool path coloured by a
/// quantity (rapids dashed), critical regions, the medial axis by class, trochoids, a
/// legend and a scale bar.
#[utoipa::path(get, path = "/v1/jobs/{id}/drawing.svg", tag = "jobs", operation_id = "getJobDrawing",
    params(("id" = JobId, Path, description = "Job id (a UUID)"), DrawingQuery),
    responses(
        (status = 200, description = "The drawing", body = String, content_type = "image/svg+xml"),
        (status = 400, description = "A malformed job id or query parameter", body = Problem, content_type = "application/problem+json"),
        (status = 404, description = "No such job", body = Problem, content_type = "application/problem+json"),
        (status = 409, description = "Not finished, or a kind of job without drawings", body = Problem, content_type = "application/problem+json"),
        (status = 422, description = "An unknown path, layer or quantity, a width out of bounds, or a window that is not a box", body = Problem, content_type = "application/problem+json")))]
pub async fn get_drawing(
    State(state): State<AppState>,
    caller: Caller,
    ApiPath(id): ApiPath<JobId>,
    ApiQuery(query): ApiQuery<DrawingQuery>,
) -> Result<Response, ApiError> {
    let color = match query.color.as_deref() {
        Some(text) => Some(Quantity::parse(text).ok_or_else(|| {
            ApiError::field("color", format!("must be one of alpha, feed, force, wear; got {text:?}"))
        })?),
        None => None,
    };
    let defaults = DrawOptions::default();
    let window = query.window()?;
    let options = DrawOptions {
        path: query.path,
        color_by: color,
        layer: query.layer,
        rapids: query.rapids.unwrap_or(defaults.rapids),
        medial: query.medial.unwrap_or(defaults.medial),
        regions: query.regions.unwrap_or(defaults.regions),
        trochoids: query.trochoids.unwrap_or(defaults.trochoids),
        width_px: query.width.unwrap_or(defaults.width_px),
        window,
        unit: query.units.unwrap_or_default(),
    };
    let scene = scene_of(&state, &caller, &id).await?;
    let body = tokio::task::spawn_blocking(move || render_drawing(&scene, &options))
        .await
        .map_err(|e| ApiError::Internal(format!("drawing: {e}")))??;
    Ok(svg(body))
}

/// One chart of a finished job as SVG (the ids are listed by `getJobViews`).
#[utoipa::path(get, path = "/v1/jobs/{id}/charts/{chart}", tag = "jobs", operation_id = "getJobChart",
    params(("id" = JobId, Path, description = "Job id (a UUID)"), ("chart" = String, Path, description = "Chart id, e.g. alpha"), ChartQuery),
    responses(
        (status = 200, description = "The chart", body = String, content_type = "image/svg+xml"),
        (status = 400, description = "A malformed job id", body = Problem, content_type = "application/problem+json"),
        (status = 404, description = "No such job or chart", body = Problem, content_type = "application/problem+json"),
        (status = 409, description = "Not finished, or a kind of job without drawings", body = Problem, content_type = "application/problem+json"),
        (status = 422, description = "A size out of bounds", body = Problem, content_type = "application/problem+json")))]
pub async fn get_chart(
    State(state): State<AppState>,
    caller: Caller,
    ApiPath((id, chart)): ApiPath<(JobId, String)>,
    ApiQuery(query): ApiQuery<ChartQuery>,
) -> Result<Response, ApiError> {
    let width = query.width.unwrap_or(DEFAULT_CHART_WIDTH_PX);
    let height = query.height.unwrap_or(DEFAULT_CHART_HEIGHT_PX);
    let mut v = Validator::new();
    for (field, value) in [("width", width), ("height", height)] {
        v.check(
            (MIN_CHART_PX..=MAX_CHART_PX).contains(&value),
            field,
            format!("must be from {MIN_CHART_PX} to {MAX_CHART_PX} px, got {value}"),
        );
    }
    v.finish()?;
    let scene = scene_of(&state, &caller, &id).await?;
    let Some(data) = scene.chart(&chart).cloned() else {
        let known: Vec<&str> = scene.charts.iter().map(|c| c.id.as_str()).collect();
        return Err(ApiError::not_found(format!(
            "job {id} has no chart {:?}; it has: {}",
            excerpt(&chart),
            known.join(", ")
        )));
    };
    let unit = query.units.unwrap_or_default();
    let body = tokio::task::spawn_blocking(move || render_chart(&in_unit(&data, unit), width, height))
        .await
        .map_err(|e| ApiError::Internal(format!("chart: {e}")))?;
    Ok(svg(body))
}

/// The drawing routes.
pub fn router() -> OpenApiRouter<AppState> {
    OpenApiRouter::new().routes(routes!(get_views)).routes(routes!(get_drawing)).routes(routes!(get_chart))
}
