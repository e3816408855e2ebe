//! `POST /v1/tools/{id}/force-model/fit`: fit the response-surface force model to a
//! shop's measured (t_m, L, F_xy) triples and, when asked, store it.

use crate::core::conditions::standard_centres;
use crate::core::force_fit::{fit_force_model, FitSpec, ForceSample};
use crate::core::force_model::{Coefficients, ForceModel};
use crate::core::operation::Operation;
use crate::service::error::{ApiError, Problem};
use crate::service::extract::{ApiJson, ApiPath};
use crate::service::lookup;
use crate::service::resources::force_models::{ForceModelData, ForceModelRecord};
use crate::service::resources::{crud, Source};
use crate::service::state::AppState;
use axum::extract::State;
use axum::http::{header, StatusCode};
use axum::response::{IntoResponse, Response};
use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

/// δt of the coded chip thickness when no model gives one: 1.5·D µm (MODEL.md §3, assumed).
const DT_UM_PER_MM_DIAMETER: f64 = 1.5;
/// δL of the coded arc length when no model gives one: 0.0436·D mm (MODEL.md §3, assumed).
const DL_PER_MM_DIAMETER: f64 = 0.0436;
/// Most measurements one fit takes (the papers fitted 13-run designs).
pub const MAX_FIT_POINTS: usize = 10_000;

/// One measured cut.
#[derive(Debug, Clone, Copy, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct MeasuredForce {
    /// Maximum undeformed chip thickness, µm.
    pub t_m_um: f64,
    /// Engagement arc length, mm.
    pub l_mm: f64,
    /// Measured average XY force, N.
    pub fxy_n: f64,
}

/// Measurements to fit. The coding (t0, δt, L0, δL) defaults to the tool's current
/// model, else to its standard side-cutting conditions with δt = 1.5·D µm and
/// δL = 0.0436·D mm.
#[derive(Debug, Clone, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct FitRequest {
    /// Default SKD61.
    pub material_id: Option<i64>,
    pub points: Vec<MeasuredForce>,
    pub t0_um: Option<f64>,
    pub dt_um: Option<f64>,
    pub l0_mm: Option<f64>,
    pub dl_mm: Option<f64>,
    /// Axial depth of the measurements, mm (default: the tool diameter).
    pub ad_ref_mm: Option<f64>,
    /// Fit the X1² term too (default true; the papers' tables dropped it).
    #[serde(default = "yes")]
    pub include_x1_squared: bool,
    /// Store the fitted model (source `fitted`); it becomes the tool's model in use.
    #[serde(default)]
    pub store: bool,
    /// Where the measurements come from, kept with a stored model.
    #[serde(default)]
    pub reference: String,
}

fn yes() -> bool {
    true
}

/// One point's fit.
#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct FitResidual {
    pub t_m_um: f64,
    pub l_mm: f64,
    pub measured_n: f64,
    pub predicted_n: f64,
    pub residual_n: f64,
}

/// The fitted model and its quality.
#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct FitResponse {
    pub tool_id: i64,
    pub material_id: i64,
    pub t0_um: f64,
    pub dt_um: f64,
    pub l0_mm: f64,
    pub dl_mm: f64,
    pub b0: f64,
    pub b1: f64,
    pub b2: f64,
    pub b11: f64,
    pub b22: f64,
    pub b12: f64,
    pub ad_ref_mm: f64,
    pub r_squared: f64,
    pub adjusted_r_squared: f64,
    pub rms_residual_n: f64,
    pub residuals: Vec<FitResidual>,
    /// The stored model, when `store` was true.
    pub stored: Option<ForceModelRecord>,
}

/// Fits seed 002 Eq. 1 to measured forces by least squares.
#[utoipa::path(post, path = "/v1/tools/{id}/force-model/fit", tag = "database", operation_id = "fitForceModel",
    request_body = FitRequest,
    params(("id" = i64, Path, description = "Tool id")),
    responses(
        (status = 200, description = "The fit (not stored)", body = FitResponse),
        (status = 201, description = "The fit, stored; Location names the new force model", body = FitResponse),
        (status = 404, description = "No such tool", body = Problem, content_type = "application/problem+json"),
        (status = 422, description = "Too few or degenerate points, or a refused field", body = Problem, content_type = "application/problem+json")))]
pub async fn fit(
    State(state): State<AppState>,
    ApiPath(tool_id): ApiPath<i64>,
    ApiJson(request): ApiJson<FitRequest>,
) -> Result<Response, ApiError> {
    if request.points.len() > MAX_FIT_POINTS {
        return Err(ApiError::field(
            "points",
            format!("{} points given; at most {MAX_FIT_POINTS} are fitted at once", request.points.len()),
        ));
    }
    let tool =
        crate::service::resources::crud::get::<crate::service::resources::tools::Tool>(&state.pool, tool_id).await?;
    let material = lookup::material(&state.pool, request.material_id, None).await?;
    let current = lookup::force_model(&state.pool, tool_id, material.id).await?;
    let standard =
        lookup::standard_conditions(&state.pool, tool_id, material.id, Operation::StandardSideCutting).await?;
    let d = tool.data.diameter_mm;

    let (t0, l0) = match (&current, &standard) {
        (Some(m), _) => (Some(m.data.t0_um), Some(m.data.l0_mm)),
        (None, Some(s)) => {
            let (t, l) = standard_centres(d / 2.0, s.data.conditions())?;
            (Some(t), Some(l))
        }
        (None, None) => (None, None),
    };
    let spec = FitSpec {
        t0_um: request.t0_um.or(t0).ok_or_else(|| {
            ApiError::field(
                "t0_um",
                "the tool has no force model or standard conditions to centre on: give t0_um and l0_mm",
            )
        })?,
        dt_um: request.dt_um.or(current.as_ref().map(|m| m.data.dt_um)).unwrap_or(DT_UM_PER_MM_DIAMETER * d),
        l0_mm: request.l0_mm.or(l0).ok_or_else(|| ApiError::field("l0_mm", "give l0_mm"))?,
        dl_mm: request.dl_mm.or(current.as_ref().map(|m| m.data.dl_mm)).unwrap_or(DL_PER_MM_DIAMETER * d),
        ad_ref_mm: request.ad_ref_mm.unwrap_or(d),
        include_x1_squared: request.include_x1_squared,
    };
    let samples: Vec<ForceSample> =
        request.points.iter().map(|p| ForceSample { t_m_um: p.t_m_um, l_mm: p.l_mm, fxy_n: p.fxy_n }).collect();
    let fit = fit_force_model(&samples, spec)?;
    let ForceModel { coefficients: Coefficients { b0, b1, b2, b11, b22, b12 }, .. } = fit.model;

    let stored = if request.store {
        let data = ForceModelData {
            tool_id,
            material_id: material.id,
            t0_um: spec.t0_um,
            dt_um: spec.dt_um,
            l0_mm: spec.l0_mm,
            dl_mm: spec.dl_mm,
            b0,
            b1,
            b2,
            b11,
            b22,
            b12,
            r_squared: Some(fit.r_squared),
            ad_ref_mm: spec.ad_ref_mm,
            source: Source::Fitted,
            reference: if request.reference.trim().is_empty() {
                format!("least-squares fit of {} measured points", samples.len())
            } else {
                request.reference.clone()
            },
        };
        Some(crud::create::<ForceModelRecord>(&state.pool, data).await?)
    } else {
        None
    };

    let residuals = samples
        .iter()
        .zip(&fit.residuals_n)
        .map(|(s, r)| FitResidual {
            t_m_um: s.t_m_um,
            l_mm: s.l_mm,
            measured_n: s.fxy_n,
            predicted_n: s.fxy_n - r,
            residual_n: *r,
        })
        .collect();
    let body = FitResponse {
        tool_id,
        material_id: material.id,
        t0_um: spec.t0_um,
        dt_um: spec.dt_um,
        l0_mm: spec.l0_mm,
        dl_mm: spec.dl_mm,
        b0,
        b1,
        b2,
        b11,
        b22,
        b12,
        ad_ref_mm: spec.ad_ref_mm,
        r_squared: fit.r_squared,
        adjusted_r_squared: fit.adjusted_r_squared,
        rms_residual_n: fit.rms_residual_n,
        residuals,
        stored: stored.clone(),
    };
    Ok(match stored {
        Some(record) => {
            (StatusCode::CREATED, [(header::LOCATION, format!("/v1/force-models/{}", record.id))], axum::Json(body))
                .into_response()
        }
        None => axum::Json(body).into_response(),
    })
}
