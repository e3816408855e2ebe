//! One job kind: its request, what the request resolves to against the database at
//! submission (stored with the job, so a job's answer does not change when the database
//! does), how a worker runs it and what it hands back. Each kind implements
//! [`JobKindSpec`] in its own file and is registered once, in [`super::kinds`].

use super::model::JobKind;
use crate::core::analysis::kept::KeptStock;
use crate::core::conditions::CuttingConditions;
use crate::core::drawing::scene::Scene;
use crate::core::force_model::ForceModel;
use crate::core::progress::Progress;
use crate::core::standard_cut::{contour_parallel_cut, standard_cut, StandardCut};
use crate::core::tool::EndMill;
use crate::core::CoreError;
use crate::service::auth::Caller;
use crate::service::error::{ApiError, Validator};
use crate::service::store::Pool;
use serde::de::DeserializeOwned;
use serde::Serialize;
use std::future::Future;
use utoipa::ToSchema;

/// What a submission knows besides its input: the database, and who submits it (a
/// planner may name only its own jobs, e.g. the `job_id` of a costing).
pub struct Submission<'a> {
    pub pool: &'a Pool,
    pub caller: &'a Caller,
    /// Memory a stock simulation of this service may take, bytes (a stock a job starts
    /// from is read within it).
    pub stock_memory_bytes: usize,
}

/// What a run of a job produces: its result, and the NC programs and drawing it made.
pub struct Produced<R> {
    pub result: R,
    /// The job's NC program (`GET /v1/jobs/{id}/program`).
    pub program: Option<String>,
    /// A plan's baseline program (`GET /v1/jobs/{id}/program?part=baseline`).
    pub baseline_program: Option<String>,
    /// The program a job changed: a trochoids job's base path (`?part=base`).
    pub base_program: Option<String>,
    /// What can be drawn of the job.
    pub scene: Option<Scene>,
    /// The stock its simulation left, kept for a job to start from (`stock.from_job`).
    pub stock: Option<KeptStock>,
}

impl<R> Produced<R> {
    /// A result alone.
    pub fn result(result: R) -> Self {
        Produced { result, program: None, baseline_program: None, base_program: None, scene: None, stock: None }
    }

    /// A result with its drawing.
    pub fn drawn(result: R, scene: Scene) -> Self {
        Produced { scene: Some(scene), ..Produced::result(result) }
    }

    /// The same, keeping the stock its simulation left.
    pub fn keeping(self, stock: KeptStock) -> Self {
        Produced { stock: Some(stock), ..self }
    }

    /// A result with its NC program and drawing.
    pub fn programmed(result: R, program: String, scene: Scene) -> Self {
        Produced { program: Some(program), ..Produced::drawn(result, scene) }
    }
}

/// A tool's standard cut ([`standard_cut`], or with `contour_parallel` the same cut beside a
/// previous pass, [`contour_parallel_cut`]), worked out on a blocking thread: a radius or
/// ball end mill's is simulated.
pub async fn standard_cut_off_runtime(
    tool: EndMill,
    conditions: CuttingConditions,
    model: Option<ForceModel>,
    contour_parallel: bool,
) -> Result<StandardCut, ApiError> {
    tokio::task::spawn_blocking(move || match contour_parallel {
        true => contour_parallel_cut(&tool, conditions, model.as_ref()),
        false => standard_cut(&tool, conditions, model.as_ref()),
    })
    .await
    .map_err(|e| ApiError::Internal(format!("a blocking task failed: {e}")))?
    .map_err(ApiError::from)
}

/// Runs `work` on a blocking thread (parsing a program or a pocket is CPU work), adding its
/// faults to `faults`.
pub async fn off_runtime_with<T: Send + 'static>(
    faults: &mut Validator,
    work: impl FnOnce(&mut Validator) -> Result<T, ApiError> + Send + 'static,
) -> Result<T, ApiError> {
    let mut moved = std::mem::take(faults);
    let (value, back) = tokio::task::spawn_blocking(move || (work(&mut moved), moved))
        .await
        .map_err(|e| ApiError::Internal(format!("a blocking task failed: {e}")))?;
    *faults = back;
    value
}

/// A kind of job.
pub trait JobKindSpec: 'static {
    /// Its name in `kind`.
    const KIND: JobKind;
    /// The route that submits it alone, e.g. `/v1/conditions`.
    const PATH: &'static str;
    /// The operation id of that route, e.g. `recommendConditions`.
    const OPERATION_ID: &'static str;
    /// The route's summary (one line).
    const SUMMARY: &'static str;
    /// The route's description: what the job does and what its result holds.
    const DESCRIPTION: &'static str;
    /// What the 422 of a submission refuses (a field, an NC line, a contour vertex…).
    const REFUSES: &'static str;

    /// The input as submitted.
    type Request: DeserializeOwned + Serialize + ToSchema + Send + 'static;
    /// What the request resolved to: checked, with the database rows it names.
    type Prepared: DeserializeOwned + Serialize + Send + 'static;
    /// The finished job's `result`.
    type Output: Serialize + ToSchema + 'static;

    /// Checks the values of a request that need no database, adding every fault to `v`.
    /// It also sees a request some of whose fields were refused by their schema (and set
    /// aside), so that a problem names every fault at once.
    fn check(request: &Self::Request, v: &mut Validator);

    /// Resolves a request against the database, and parses and checks what needs its rows
    /// (the program, the pocket, the tool's reach). CPU work runs off the async runtime.
    ///
    /// `faults` holds what the schema and [`JobKindSpec::check`] refused, and `prepare`
    /// adds every fault it finds there instead of stopping at the first: it resolves every
    /// field it can on its own (an unknown tool does not keep the program from being read),
    /// and skips each look-up or check that needs a field already refused
    /// ([`Validator::refused`]), so that no field is blamed for another's fault. The checks
    /// of the core, which span the whole request, run only on a request without faults.
    /// `None` when a fault keeps it from resolving the request; `Err` only for a failure on
    /// our side.
    fn prepare(
        submission: &Submission<'_>,
        request: Self::Request,
        faults: &mut Validator,
    ) -> impl Future<Output = Result<Option<Self::Prepared>, ApiError>> + Send;

    /// Runs a prepared job, each of its stock simulations within `stock_memory_bytes`.
    /// CPU-bound: called on a blocking thread.
    fn run(
        request: Self::Request,
        prepared: Self::Prepared,
        progress: &dyn Progress,
        stock_memory_bytes: usize,
    ) -> Result<Produced<Self::Output>, CoreError>;
}
