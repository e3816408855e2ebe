//! The job kinds, registered once: [`REGISTRY`] lists every [`JobKindSpec`], and the
//! submission, the worker, the routes and the OpenAPI document all find a kind there.

use super::analysis::Analysis;
use super::conditions::Conditions;
use super::costing::Costing;
use super::feeds::Feeds;
use super::kind::{JobKindSpec, Produced, Submission};
use super::model::JobKind;
use super::plans::Plan;
use super::trochoids::Trochoids;
use crate::core::progress::Progress;
use crate::core::CoreError;
use crate::service::error::{ApiError, FieldError, Validator};
use crate::service::extract::{read_all, Read};
use std::borrow::Cow;
use std::future::Future;
use std::pin::Pin;
use utoipa::openapi::schema::{AnyOfBuilder, Schema};
use utoipa::openapi::{Ref, RefOr};
use utoipa::{PartialSchema, ToSchema};

/// A future of a submission, boxed so that every kind's fits one table.
pub type Pending<'a, T> = Pin<Box<dyn Future<Output = Result<T, ApiError>> + Send + 'a>>;

/// What a finished job hands back, serialised for the store.
pub struct JobOutput {
    pub result: serde_json::Value,
    pub program: Option<String>,
    /// A plan's baseline program (`GET /v1/jobs/{id}/program?part=baseline`).
    pub baseline_program: Option<String>,
    /// A trochoids job's base program (`?part=base`).
    pub base_program: Option<String>,
    /// The drawing scene as JSON.
    pub scene: Option<String>,
    /// The stock the simulation left, encoded and compressed.
    pub stock: Option<super::kept_stock::EncodedStock>,
}

/// A submission checked and resolved: what the store keeps for the worker.
pub struct Accepted {
    /// The input as submitted (JSON text).
    pub input: String,
    /// What it resolved to (JSON text).
    pub prepared: String,
}

/// A kind as the rest of the service sees it: its [`JobKindSpec`] behind plain functions.
pub struct Registered {
    pub kind: JobKind,
    pub path: &'static str,
    pub operation_id: &'static str,
    pub summary: &'static str,
    pub description: &'static str,
    pub refuses: &'static str,
    accept: for<'a> fn(&'a Submission<'a>, serde_json::Value) -> Pending<'a, Accepted>,
    run: fn(&str, &str, &dyn Progress, usize) -> Result<JobOutput, CoreError>,
    /// The names of the schemas of its request and result.
    pub request_schema: fn() -> Cow<'static, str>,
    pub result_schema: fn() -> Cow<'static, str>,
    /// Its request's and result's schemas with every schema they refer to.
    pub schemas: fn() -> Vec<(String, RefOr<Schema>)>,
}

/// Registers `K`.
const fn register<K: JobKindSpec>() -> Registered {
    Registered {
        kind: K::KIND,
        path: K::PATH,
        operation_id: K::OPERATION_ID,
        summary: K::SUMMARY,
        description: K::DESCRIPTION,
        refuses: K::REFUSES,
        accept: accept_kind::<K>,
        run: run_kind::<K>,
        request_schema: <K::Request as ToSchema>::name,
        result_schema: <K::Output as ToSchema>::name,
        schemas: schemas::<K>,
    }
}

/// Every kind of job, in the order the document lists them.
pub static REGISTRY: [Registered; 6] = [
    register::<Conditions>(),
    register::<Analysis>(),
    register::<Feeds>(),
    register::<Costing>(),
    register::<Trochoids>(),
    register::<Plan>(),
];

/// The registration of `kind` (every kind has one: a test checks).
pub fn of(kind: JobKind) -> Option<&'static Registered> {
    REGISTRY.iter().find(|r| r.kind == kind)
}

/// The input of a job as submitted, whichever its kind (`GET /v1/jobs/{id}/input`, and
/// the `input` of `POST /v1/jobs`): an `anyOf` of the kinds' inputs, since a small input
/// can satisfy more than one kind's schema (the job's `kind` says which it is).
pub struct JobInput;

impl PartialSchema for JobInput {
    fn schema() -> RefOr<Schema> {
        REGISTRY
            .iter()
            .fold(AnyOfBuilder::new(), |any, r| any.item(Ref::from_schema_name((r.request_schema)())))
            .description(Some("The input of a job, by kind (the `input` of `POST /v1/jobs`)."))
            .into()
    }
}

impl ToSchema for JobInput {
    fn schemas(schemas: &mut Vec<(String, RefOr<Schema>)>) {
        for r in &REGISTRY {
            schemas.extend((r.schemas)());
        }
    }
}

/// Runs `work` on a blocking thread: reading and writing big JSON is CPU work.
pub async fn off_runtime<T: Send + 'static>(
    work: impl FnOnce() -> Result<T, ApiError> + Send + 'static,
) -> Result<T, ApiError> {
    tokio::task::spawn_blocking(work).await.map_err(|e| ApiError::Internal(format!("a blocking task failed: {e}")))?
}

/// `value` as JSON text, through a JSON value: a key written twice (a flattened part and
/// its container naming the same field) is kept once, as readers expect.
fn to_json<T: serde::Serialize>(value: &T) -> Result<String, ApiError> {
    serde_json::to_value(value)
        .map(|v| v.to_string())
        .map_err(|e| ApiError::Internal(format!("serializing a job: {e}")))
}

/// Reads `input` as a `K` request and checks it: the fields its schema refuses and the
/// values [`JobKindSpec::check`] refuses in the rest. The request is `None` when it does
/// not read even with the refused fields set aside (a required field is missing).
fn read_request<K: JobKindSpec>(input: serde_json::Value) -> (Option<K::Request>, Validator) {
    let Read { value, refused } = read_all::<K::Request>(input);
    // A check of a field the schema refused sees it missing, which is no news: the
    // validator drops it.
    let mut faults = Validator::after(refused);
    if let Some(request) = &value {
        K::check(request, &mut faults);
    }
    (value, faults)
}

/// Reads `input` as a `K` request, checks and resolves it, and answers every fault of
/// the three stages in one problem; the reading and writing of JSON run off the async
/// runtime.
fn accept_kind<'a, K: JobKindSpec>(submission: &'a Submission<'a>, input: serde_json::Value) -> Pending<'a, Accepted> {
    Box::pin(async move {
        let (request, text, mut faults) = off_runtime(move || {
            let text = input.to_string();
            let (request, faults) = read_request::<K>(input);
            Ok((request, text, faults))
        })
        .await?;
        // Resolved even when the checks found faults, so that the faults of the look-ups and
        // of the program come in the same problem; `prepare` skips what needs a refused field.
        let prepared = match request {
            Some(request) => {
                faults.next_stage();
                K::prepare(submission, request, &mut faults).await?
            }
            None => None,
        };
        faults.finish()?;
        let prepared =
            prepared.ok_or_else(|| ApiError::Internal(format!("a {} job resolved to nothing", K::KIND.as_str())))?;
        let prepared = off_runtime(move || to_json(&prepared)).await?;
        Ok(Accepted { input: text, prepared })
    })
}

fn schemas<K: JobKindSpec>() -> Vec<(String, RefOr<Schema>)> {
    let mut all = vec![
        (K::Request::name().into_owned(), K::Request::schema()),
        (K::Output::name().into_owned(), K::Output::schema()),
    ];
    K::Request::schemas(&mut all);
    K::Output::schemas(&mut all);
    all
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

/// Checks a submission of `kind` and resolves it against the database. Field paths in
/// errors start with `prefix`.
pub async fn accept(
    submission: &Submission<'_>,
    kind: JobKind,
    input: serde_json::Value,
    prefix: &str,
) -> Result<Accepted, ApiError> {
    let registered =
        of(kind).ok_or_else(|| ApiError::Internal(format!("job kind {} is not registered", kind.as_str())))?;
    registered.accept(submission, input, prefix).await
}

impl Registered {
    /// Checks a submission and resolves it against the database; the answer is stored
    /// with the job and is all a worker needs. Field paths in errors start with `prefix`.
    pub async fn accept(
        &self,
        submission: &Submission<'_>,
        input: serde_json::Value,
        prefix: &str,
    ) -> Result<Accepted, ApiError> {
        (self.accept)(submission, input).await.map_err(|e| prefixed(e, prefix))
    }
}

/// Runs a prepared job of `K` from its input as submitted and what it resolved to, each of
/// its stock simulations within `stock_memory_bytes`.
fn run_kind<K: JobKindSpec>(
    input: &str,
    prepared: &str,
    progress: &dyn Progress,
    stock_memory_bytes: usize,
) -> Result<JobOutput, CoreError> {
    let unreadable = |e: serde_json::Error| CoreError::invalid("prepared", format!("stored job input unreadable: {e}"));
    let request = serde_json::from_str(input).map_err(unreadable)?;
    let prepared = serde_json::from_str(prepared).map_err(unreadable)?;
    let Produced { result, program, baseline_program, base_program, scene, stock } =
        K::run(request, prepared, progress, stock_memory_bytes)?;
    // The kept stock is compressed beside the result's and the scene's serialisation (each
    // a few milliseconds of a trochoids job's last, single-threaded steps).
    let (result, scene, stock) = std::thread::scope(|scope| {
        let stock = stock.as_ref().map(|kept| scope.spawn(|| super::kept_stock::encode(kept)));
        let result = serde_json::to_value(result).map_err(unreadable);
        let scene = scene
            .map(|s| serde_json::to_string(&s))
            .transpose()
            .map_err(|e| CoreError::invalid("scene", format!("drawing scene unserialisable: {e}")));
        let stock = stock.map(|encoding| encoding.join().unwrap_or_else(|panic| std::panic::resume_unwind(panic)));
        (result, scene, stock)
    });
    Ok(JobOutput { result: result?, program, baseline_program, base_program, scene: scene?, stock })
}

/// Runs a prepared job from its input as submitted and what it resolved to, each of its
/// stock simulations within `stock_memory_bytes`. CPU-bound: call it on a blocking thread.
pub fn run(
    kind: JobKind,
    input: &str,
    prepared: &str,
    progress: &dyn Progress,
    stock_memory_bytes: usize,
) -> Result<JobOutput, CoreError> {
    progress.checkpoint()?;
    let registered =
        of(kind).ok_or_else(|| CoreError::invalid("kind", format!("job kind {} is not registered", kind.as_str())))?;
    let output = (registered.run)(input, prepared, progress, stock_memory_bytes)?;
    progress.report(1.0);
    Ok(output)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_kind_is_registered_once_with_its_own_route_and_schemas() {
        for kind in crate::service::jobs::model::JobKind::ALL {
            let found: Vec<_> = REGISTRY.iter().filter(|r| r.kind == kind).collect();
            assert_eq!(found.len(), 1, "{kind:?}");
        }
        let mut paths: Vec<_> = REGISTRY.iter().map(|r| r.path).collect();
        paths.sort_unstable();
        paths.dedup();
        assert_eq!(paths.len(), REGISTRY.len());
        for r in &REGISTRY {
            let names: Vec<String> = (r.schemas)().into_iter().map(|(name, _)| name).collect();
            assert!(names.contains(&(r.request_schema)().into_owned()), "{}", r.path);
            assert!(names.contains(&(r.result_schema)().into_owned()), "{}", r.path);
        }
    }
}
