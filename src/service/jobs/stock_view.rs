//! `GET /v1/jobs/{id}/stock`: the stock a finished job's simulation left, as a height map
//! the page's 3-D view draws (issue 32 item 5), computed from the kept stock
//! ([`super::kept_stock`]) by [`crate::core::analysis::height_map`].
//!
//! **Encoding.** `tops` is base64 (RFC 4648, with padding) of `columns × rows`
//! little-endian IEEE-754 `f32`, mm, row by row from the bottom (y up), column by column
//! from the left (x up): per cell, the top of the material there. A cell with no material
//! anywhere in the layer (cut through, or never stock: outside a pocket's contour) has its
//! top at the layer's bottom `z_bottom_mm`; every cell with material is above it. No NaN,
//! no null. In JavaScript: `new Float32Array(Uint8Array.from(atob(tops), c =>
//! c.charCodeAt(0)).buffer)`.

use super::kept_stock;
use super::model::JobId;
use crate::core::analysis::height_map::{
    height_map, HeightMap, DEFAULT_HEIGHT_MAP_CELLS, MAX_HEIGHT_MAP_CELLS, MIN_HEIGHT_MAP_CELLS,
};
use crate::service::auth::Caller;
use crate::service::error::{ApiError, Problem, Validator};
use crate::service::extract::{ApiPath, ApiQuery};
use crate::service::state::AppState;
use axum::extract::State;
use axum::Json;
use base64::Engine;
use serde::{Deserialize, Serialize};
use utoipa::{IntoParams, ToSchema};
use utoipa_axum::{router::OpenApiRouter, routes};

/// The name of the encoding of [`StockHeightMap::tops`].
pub const TOPS_ENCODING: &str = "base64-f32le";

/// Query of `GET /v1/jobs/{id}/stock`.
#[derive(Debug, Deserialize, IntoParams)]
#[serde(deny_unknown_fields)]
#[into_params(parameter_in = Query)]
pub struct StockQuery {
    /// The most cells the height map may have (default 65536, 256 × 256): the kept grid
    /// is gathered into square blocks, each the highest top in it, the smallest blocks
    /// that fit.
    #[param(minimum = 4, maximum = 1048576)]
    pub max_cells: Option<u32>,
}

/// Where the height map's cells lie, mm.
#[derive(Debug, Serialize, ToSchema)]
pub struct HeightMapGrid {
    /// The corner of the first cell (bottom left), mm.
    pub x0_mm: f64,
    pub y0_mm: f64,
    /// The side of a cell, mm.
    pub cell_mm: f64,
    pub columns: usize,
    pub rows: usize,
}

/// The stock a job left, as the top of the material per cell of a grid.
#[derive(Debug, Serialize, ToSchema)]
pub struct StockHeightMap {
    pub job_id: String,
    pub grid: HeightMapGrid,
    /// The kept stock's own cell, mm, and how many of them a height-map cell gathers per
    /// side (1: the kept grid itself).
    pub kept_cell_mm: f64,
    pub block: usize,
    /// The layer the stock covers: its top and bottom, mm.
    pub z_top_mm: f64,
    pub z_bottom_mm: f64,
    /// The kept stock's slices' levels, top first, mm (each slice from one to the next).
    pub levels_mm: Vec<f64>,
    /// Cells that hold material somewhere in the layer (their top above `z_bottom_mm`).
    pub material_cells: usize,
    /// The stock was a pocket's: its material is what was to be cut in the cavity.
    pub cavity: bool,
    /// How `tops` is encoded: `base64-f32le`.
    #[schema(example = "base64-f32le")]
    pub encoding: String,
    /// Per cell, the top of the material, mm: base64 of little-endian f32, row by row
    /// from the bottom; `z_bottom_mm` where the cell holds no material.
    pub tops: String,
}

impl StockHeightMap {
    fn new(job_id: String, map: &HeightMap, kept: &crate::core::analysis::kept::KeptStock) -> StockHeightMap {
        let bytes: Vec<u8> = map.tops_mm.iter().flat_map(|t| t.to_le_bytes()).collect();
        let g = map.grid;
        let levels_mm = kept.slices.iter().map(|s| s.z_top).chain(kept.slices.last().map(|s| s.z_bottom)).collect();
        StockHeightMap {
            job_id,
            grid: HeightMapGrid { x0_mm: g.x0_mm, y0_mm: g.y0_mm, cell_mm: g.cell_mm, columns: g.nx, rows: g.ny },
            kept_cell_mm: kept.grid.cell_mm,
            block: map.block,
            z_top_mm: map.z_top_mm,
            z_bottom_mm: map.z_bottom_mm,
            levels_mm,
            material_cells: map.material_cells(),
            cavity: kept.cavity,
            encoding: TOPS_ENCODING.to_string(),
            tops: base64::engine::general_purpose::STANDARD.encode(bytes),
        }
    }
}

/// The stock a finished analysis or costing job left, as a height map: per cell, the top
/// of the material (the top of the highest kept slice holding material there), in at most
/// `max_cells` cells.
#[utoipa::path(get, path = "/v1/jobs/{id}/stock", tag = "jobs", operation_id = "getJobStock",
    params(("id" = JobId, Path, description = "Job id (a UUID)"), StockQuery),
    responses(
        (status = 200, description = "The stock as a height map", body = StockHeightMap),
        (status = 400, description = "A malformed job id or query parameter", body = Problem, content_type = "application/problem+json"),
        (status = 404, description = "No such job, or a job that kept no stock (not succeeded, or a kind that keeps none)", body = Problem, content_type = "application/problem+json"),
        (status = 409, description = "A kept stock this version of dieplan cannot read", body = Problem, content_type = "application/problem+json"),
        (status = 422, description = "max_cells out of bounds", body = Problem, content_type = "application/problem+json")))]
pub async fn get_stock(
    State(state): State<AppState>,
    caller: Caller,
    ApiPath(id): ApiPath<JobId>,
    ApiQuery(query): ApiQuery<StockQuery>,
) -> Result<Json<StockHeightMap>, ApiError> {
    let max_cells = query.max_cells.map_or(DEFAULT_HEIGHT_MAP_CELLS, |n| n as usize);
    let mut v = Validator::new();
    v.check(
        (MIN_HEIGHT_MAP_CELLS..=MAX_HEIGHT_MAP_CELLS).contains(&max_cells),
        "max_cells",
        format!("must be from {MIN_HEIGHT_MAP_CELLS} to {MAX_HEIGHT_MAP_CELLS}, got {max_cells}"),
    );
    v.finish()?;
    let (format, body) = kept_stock::find(&state.pool, &caller, &id).await?.map_err(ApiError::not_found)?;
    let (job_id, budget) = (id.to_string(), state.config.stock_memory_bytes());
    let map = tokio::task::spawn_blocking(move || {
        let kept = kept_stock::decode(format, &body, budget)
            .map_err(|e| ApiError::Conflict(format!("the stock job {job_id} kept cannot be read: {e}")))?;
        let map = height_map(&kept, max_cells);
        Ok::<_, ApiError>(StockHeightMap::new(job_id, &map, &kept))
    })
    .await
    .map_err(|e| ApiError::Internal(format!("a blocking task failed: {e}")))??;
    Ok(Json(map))
}

/// The stock route.
pub fn router() -> OpenApiRouter<AppState> {
    OpenApiRouter::new().routes(routes!(get_stock))
}
