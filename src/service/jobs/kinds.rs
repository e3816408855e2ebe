//! The job kinds: how each one's input is checked and resolved at submission, and how
//! its prepared input is run by a worker.

use super::analysis::{self, AnalysisRequest};
use super::conditions::{self, ConditionsRequest};
use super::costing::{self, CostingRequest};
use super::feeds::{self, FeedsRequest};
use super::model::JobKind;
use super::plans::{self, PlanRequest};
use super::trochoids::{self, TrochoidsRequest};
use crate::core::drawing::scene::Scene;
use crate::core::progress::Progress;
use crate::core::CoreError;
use crate::service::error::{ApiError, FieldError};
use crate::service::extract::from_value;
use crate::service::store::Pool;
use serde::Serialize;
use utoipa::ToSchema;

/// The input of a job, by kind (the `input` of `POST /v1/jobs`).
#[derive(Debug, Serialize, ToSchema)]
#[serde(untagged)]
pub enum JobInput {
    Conditions(ConditionsRequest),
    Analysis(Box<AnalysisRequest>),
    Feeds(Box<FeedsRequest>),
    Costing(Box<CostingRequest>),
    Trochoids(Box<TrochoidsRequest>),
    Plan(Box<PlanRequest>),
}

/// What a finished job hands back.
pub struct JobOutput {
    pub result: serde_json::Value,
    pub program: Option<String>,
    /// A plan's baseline program (`GET /v1/jobs/{id}/program?part=baseline`).
    pub baseline_program: Option<String>,
    /// The drawing scene as JSON.
    pub scene: Option<String>,
}

/// Prefixes the field paths of a validation error (e.g. `input.` for `POST /v1/jobs`).
fn prefixed(err: ApiError, prefix: &str) -> ApiError {
    match err {
        ApiError::Validation(errors) if !prefix.is_empty() => ApiError::Validation(
            errors
                .into_iter()
                .map(|e| FieldError {
                    field: if e.field == "body" {
                        prefix.trim_end_matches('.').to_string()
                    } else {
                        format!("{prefix}{}", e.field)
                    },
                    reason: e.reason,
                })
                .collect(),
        ),
        other => other,
    }
}

/// Checks a submission and resolves it against the database; the answer is stored
/// with the job and is all a worker needs. Field paths in errors start with `prefix`.
pub async fn prepare(
    pool: &Pool,
    kind: JobKind,
    input: serde_json::Value,
    prefix: &str,
) -> Result<serde_json::Value, ApiError> {
    let prepared = async {
        match kind {
            JobKind::Conditions => {
                let request: ConditionsRequest = from_value(input)?;
                to_json(&conditions::prepare(pool, request).await?)
            }
            JobKind::Analysis => {
                let request: AnalysisRequest = from_value(input)?;
                to_json(&analysis::prepare(pool, request).await?)
            }
            JobKind::Feeds => {
                let request: FeedsRequest = from_value(input)?;
                to_json(&feeds::prepare(pool, request).await?)
            }
            JobKind::Costing => {
                let request: CostingRequest = from_value(input)?;
                to_json(&costing::prepare(pool, request).await?)
            }
            JobKind::Trochoids => {
                let request: TrochoidsRequest = from_value(input)?;
                to_json(&trochoids::prepare(pool, request).await?)
            }
            JobKind::Plan => {
                let request: PlanRequest = from_value(input)?;
                to_json(&plans::prepare(pool, request).await?)
            }
        }
    }
    .await;
    prepared.map_err(|e| prefixed(e, prefix))
}

fn to_json<T: Serialize>(value: &T) -> Result<serde_json::Value, ApiError> {
    serde_json::to_value(value).map_err(|e| ApiError::Internal(format!("serializing a job: {e}")))
}

/// Runs a prepared job from its input as submitted and what `prepare` resolved.
/// CPU-bound: call it on a blocking thread.
pub fn run(kind: JobKind, input: &str, prepared: &str, progress: &dyn Progress) -> Result<JobOutput, CoreError> {
    let unreadable = |e: serde_json::Error| CoreError::invalid("prepared", format!("stored job input unreadable: {e}"));
    progress.checkpoint()?;
    let (mut program, mut baseline_program) = (None, None);
    let mut scene: Option<Scene> = None;
    let result = match kind {
        JobKind::Conditions => {
            let prepared = serde_json::from_str(prepared).map_err(unreadable)?;
            serde_json::to_value(conditions::run(prepared)?).map_err(unreadable)?
        }
        JobKind::Analysis => {
            let request = serde_json::from_str(input).map_err(unreadable)?;
            let prepared = serde_json::from_str(prepared).map_err(unreadable)?;
            let (result, drawn) = analysis::run(request, prepared, progress)?;
            scene = Some(drawn);
            serde_json::to_value(result).map_err(unreadable)?
        }
        JobKind::Feeds => {
            let request = serde_json::from_str(input).map_err(unreadable)?;
            let prepared = serde_json::from_str(prepared).map_err(unreadable)?;
            let (result, text, drawn) = feeds::run(request, prepared, progress)?;
            program = Some(text);
            scene = Some(drawn);
            serde_json::to_value(result).map_err(unreadable)?
        }
        JobKind::Costing => {
            let request = serde_json::from_str(input).map_err(unreadable)?;
            let prepared = serde_json::from_str(prepared).map_err(unreadable)?;
            let (result, drawn) = costing::run(request, prepared, progress)?;
            scene = Some(drawn);
            serde_json::to_value(result).map_err(unreadable)?
        }
        JobKind::Trochoids => {
            let request = serde_json::from_str(input).map_err(unreadable)?;
            let prepared = serde_json::from_str(prepared).map_err(unreadable)?;
            let (result, text, drawn) = trochoids::run(request, prepared, progress)?;
            program = Some(text);
            scene = Some(drawn);
            serde_json::to_value(result).map_err(unreadable)?
        }
        JobKind::Plan => {
            let request = serde_json::from_str(input).map_err(unreadable)?;
            let prepared = serde_json::from_str(prepared).map_err(unreadable)?;
            let out = plans::run(request, prepared, progress)?;
            program = Some(out.program);
            baseline_program = out.baseline_program;
            scene = Some(out.scene);
            serde_json::to_value(out.result).map_err(unreadable)?
        }
    };
    let scene = scene
        .map(|s| serde_json::to_string(&s))
        .transpose()
        .map_err(|e| CoreError::invalid("scene", format!("drawing scene unserialisable: {e}")))?;
    progress.report(1.0);
    Ok(JobOutput { result, program, baseline_program, scene })
}
