//! The service's one error type, mapped to HTTP in one place: `application/problem+json`
//! (RFC 9457) naming the field and the reason. 5xx details are logged, never sent.

use crate::core::CoreError;
use crate::service::request_fields::request_field;
use axum::http::{header, HeaderValue, StatusCode};
use axum::response::{IntoResponse, Response};
use serde::{Deserialize, Serialize};
use thiserror::Error;
use utoipa::ToSchema;

/// Content type of every error body.
pub const PROBLEM_JSON: &str = "application/problem+json";

/// Input quoted in an error message is cut to this many characters, so a 10 000-character
/// value is named, not echoed.
pub const MAX_QUOTED_INPUT_CHARS: usize = 32;

/// `text` as quoted in an error message: its first [`MAX_QUOTED_INPUT_CHARS`] characters,
/// and an ellipsis when there are more.
pub fn excerpt(text: &str) -> String {
    match text.char_indices().nth(MAX_QUOTED_INPUT_CHARS) {
        Some((cut, _)) => format!("{}…", &text[..cut]),
        None => text.to_string(),
    }
}

/// One field that failed validation.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
pub struct FieldError {
    /// JSON path of the field, e.g. `points[3].fxy_n`; `body` for the document as a whole.
    pub field: String,
    /// Why the value was refused.
    pub reason: String,
}

/// An RFC 9457 problem document.
#[derive(Debug, Clone, Serialize, Deserialize, ToSchema)]
pub struct Problem {
    /// A URI reference naming the problem type.
    #[serde(rename = "type")]
    pub kind: String,
    /// A short summary of the problem type.
    pub title: String,
    /// The HTTP status code.
    pub status: u16,
    /// What went wrong with this request.
    pub detail: String,
    /// For validation problems: every refused field.
    #[serde(skip_serializing_if = "Vec::is_empty", default)]
    pub errors: Vec<FieldError>,
}

/// Everything a request can fail with.
#[derive(Debug, Error)]
pub enum ApiError {
    /// The body or query could not be read at all (malformed JSON, bad encoding).
    #[error("{0}")]
    BadRequest(String),
    /// Well-formed input with values that are refused.
    #[error("{}", summarize(.0))]
    Validation(Vec<FieldError>),
    #[error("{0}")]
    NotFound(String),
    #[error("{0}")]
    Conflict(String),
    #[error("{0}")]
    UnsupportedMediaType(String),
    /// A status produced outside the handlers (body limit, timeout, unknown route).
    #[error("{detail}")]
    Status { status: StatusCode, detail: String },
    /// Something failed on our side; the detail is logged, not sent.
    #[error("internal error: {0}")]
    Internal(String),
}

fn summarize(errors: &[FieldError]) -> String {
    match errors {
        [] => "the request is invalid".to_string(),
        [one] => format!("{}: {}", one.field, one.reason),
        [first, rest @ ..] => format!("{}: {} (and {} more)", first.field, first.reason, rest.len()),
    }
}

impl ApiError {
    pub fn field(field: impl Into<String>, reason: impl Into<String>) -> Self {
        ApiError::Validation(vec![FieldError { field: field.into(), reason: reason.into() }])
    }

    pub fn not_found(what: impl Into<String>) -> Self {
        ApiError::NotFound(what.into())
    }

    pub fn status(&self) -> StatusCode {
        match self {
            ApiError::BadRequest(_) => StatusCode::BAD_REQUEST,
            ApiError::Validation(_) => StatusCode::UNPROCESSABLE_ENTITY,
            ApiError::NotFound(_) => StatusCode::NOT_FOUND,
            ApiError::Conflict(_) => StatusCode::CONFLICT,
            ApiError::UnsupportedMediaType(_) => StatusCode::UNSUPPORTED_MEDIA_TYPE,
            ApiError::Status { status, .. } => *status,
            ApiError::Internal(_) => StatusCode::INTERNAL_SERVER_ERROR,
        }
    }

    /// The problem document sent to the client.
    pub fn problem(&self) -> Problem {
        let status = self.status();
        let (slug, detail, errors) = match self {
            ApiError::Validation(errors) => ("validation", self.to_string(), errors.clone()),
            ApiError::Internal(_) => {
                ("internal", "the server failed to handle the request; it has been logged".to_string(), vec![])
            }
            ApiError::BadRequest(_) => ("bad-request", self.to_string(), vec![]),
            ApiError::NotFound(_) => ("not-found", self.to_string(), vec![]),
            ApiError::Conflict(_) => ("conflict", self.to_string(), vec![]),
            ApiError::UnsupportedMediaType(_) => ("unsupported-media-type", self.to_string(), vec![]),
            ApiError::Status { .. } => ("http", self.to_string(), vec![]),
        };
        Problem {
            kind: format!("urn:dieplan:problem:{slug}"),
            title: status.canonical_reason().unwrap_or("Error").to_string(),
            status: status.as_u16(),
            detail,
            errors,
        }
    }
}

/// Renders a problem document with its status and content type.
pub fn problem_response(problem: &Problem) -> Response {
    let status = StatusCode::from_u16(problem.status).unwrap_or(StatusCode::INTERNAL_SERVER_ERROR);
    let body = serde_json::to_vec(problem).unwrap_or_default();
    let mut response = (status, body).into_response();
    response.headers_mut().insert(header::CONTENT_TYPE, HeaderValue::from_static(PROBLEM_JSON));
    response
}

impl IntoResponse for ApiError {
    fn into_response(self) -> Response {
        if self.status().is_server_error() {
            tracing::error!(error = %self, "request failed");
        }
        problem_response(&self.problem())
    }
}

impl From<CoreError> for ApiError {
    /// The core's refusal of a field, named as the request names it
    /// ([`request_field`]).
    fn from(err: CoreError) -> Self {
        match err {
            CoreError::InvalidInput { field, reason } | CoreError::Unsolvable { field, reason } => {
                ApiError::field(request_field(&field), reason)
            }
            CoreError::Cancelled => ApiError::Conflict("the computation was cancelled".to_string()),
        }
    }
}

impl From<crate::core::drawing::plan_view::DrawError> for ApiError {
    fn from(err: crate::core::drawing::plan_view::DrawError) -> Self {
        ApiError::field(err.field(), err.to_string())
    }
}

impl From<sqlx::Error> for ApiError {
    fn from(err: sqlx::Error) -> Self {
        use sqlx::error::ErrorKind;
        if let sqlx::Error::Database(db) = &err {
            let message = db.message().to_string();
            match db.kind() {
                ErrorKind::UniqueViolation => {
                    let columns = message.rsplit(": ").next().unwrap_or("").to_string();
                    return ApiError::Conflict(format!("a row with the same {columns} already exists"));
                }
                ErrorKind::ForeignKeyViolation => {
                    return ApiError::Conflict(
                        "the change would break a reference between rows (a referenced row is missing or still referenced)"
                            .to_string(),
                    );
                }
                ErrorKind::CheckViolation | ErrorKind::NotNullViolation => {
                    return ApiError::field("body", message);
                }
                _ => {}
            }
        }
        if matches!(err, sqlx::Error::RowNotFound) {
            return ApiError::not_found("the row does not exist");
        }
        ApiError::Internal(err.to_string())
    }
}

/// Collects the faults of a request, stage after stage (its schema, the checks that need no
/// database, the look-ups and parsing that resolve it), and turns them into one
/// [`ApiError::Validation`]: every fault of a request comes in one problem, each field
/// named once.
///
/// A later stage sees what earlier ones refused: a fault about a field an earlier stage
/// refused (or about a part of it, or its parent) is no news and is not added, and a stage
/// asks [`Validator::refused`] before a look-up or a check that needs a refused field, so
/// that no field is blamed for another's fault.
#[derive(Debug, Default)]
pub struct Validator {
    errors: Vec<FieldError>,
    /// How many of `errors` earlier stages found.
    earlier: usize,
}

/// Whether two field paths name the same field, or one a part of the other
/// (`stock` and `stock.box.x_min`, `layers` and `layers[2].z_top`).
fn related(a: &str, b: &str) -> bool {
    let within = |inner: &str, outer: &str| {
        inner.strip_prefix(outer).is_some_and(|rest| rest.is_empty() || rest.starts_with(['.', '[']))
    };
    within(a, b) || within(b, a)
}

impl Validator {
    pub fn new() -> Self {
        Self::default()
    }

    /// A validator that goes on after an earlier stage refused `faults`.
    pub fn after(faults: Vec<FieldError>) -> Self {
        Validator { earlier: faults.len(), errors: faults }
    }

    /// Ends a stage: the faults found so far are an earlier stage's.
    pub fn next_stage(&mut self) {
        self.earlier = self.errors.len();
    }

    /// Refuses `field` for `reason`. A field is named once, with its first fault (a
    /// negative cell is not also said to be out of range), and not at all when an earlier
    /// stage refused it, a part of it or its parent.
    pub fn fail(&mut self, field: impl Into<String>, reason: impl Into<String>) {
        let field = field.into();
        let known = self.errors.iter().any(|e| e.field == field)
            || self.errors[..self.earlier].iter().any(|e| related(&e.field, &field));
        if !known {
            self.errors.push(FieldError { field, reason: reason.into() });
        }
    }

    /// Whether `field` (or what it is part of) has been refused: a look-up or check that
    /// needs it is skipped, since it would fail for that fault or, worse, blame another
    /// field for it.
    pub fn refused(&self, field: &str) -> bool {
        self.errors.iter().any(|e| {
            field.strip_prefix(e.field.as_str()).is_some_and(|rest| rest.is_empty() || rest.starts_with(['.', '[']))
        })
    }

    /// Whether a fault names `field`, a part of it or its parent.
    pub fn touched(&self, field: &str) -> bool {
        self.errors.iter().any(|e| related(&e.field, field))
    }

    /// Runs `work`, which adds its faults to a new validator: its value when it found
    /// none, else one [`ApiError::Validation`] with all of them.
    pub fn collect<T>(work: impl FnOnce(&mut Validator) -> Result<Option<T>, ApiError>) -> Result<T, ApiError> {
        let mut faults = Validator::new();
        let value = work(&mut faults)?;
        faults.finish()?;
        value.ok_or_else(|| ApiError::Internal("a step found no fault and gave no value".to_string()))
    }

    /// Whether any of `fields` has been refused ([`Validator::refused`]).
    pub fn refused_any(&self, fields: &[&str]) -> bool {
        fields.iter().any(|f| self.refused(f))
    }

    /// The value of a step that resolves part of a request, or `None` with its faults
    /// added: all of them (a program's faults are its lines, under one field), except
    /// those about a field already named, a part of one or its parent. An error that is
    /// not the request's fault (the database failed) is returned.
    pub fn take<T, E: Into<ApiError>>(&mut self, step: Result<T, E>) -> Result<Option<T>, ApiError> {
        match step.map_err(Into::into) {
            Ok(value) => Ok(Some(value)),
            Err(ApiError::Validation(faults)) => {
                let named = self.errors.len();
                for fault in faults {
                    if !self.errors[..named].iter().any(|e| related(&e.field, &fault.field)) {
                        self.errors.push(fault);
                    }
                }
                Ok(None)
            }
            Err(other) => Err(other),
        }
    }

    pub fn check(&mut self, ok: bool, field: &str, reason: impl Into<String>) {
        if !ok {
            self.fail(field, reason);
        }
    }

    /// The value must be finite and > 0.
    pub fn positive(&mut self, field: &str, value: f64) {
        self.check(
            value.is_finite() && value > 0.0,
            field,
            format!("must be a finite number > 0, got {}", shown(value)),
        );
    }

    /// The value must be finite and ≥ 0.
    pub fn non_negative(&mut self, field: &str, value: f64) {
        self.check(
            value.is_finite() && value >= 0.0,
            field,
            format!("must be a finite number >= 0, got {}", shown(value)),
        );
    }

    /// The value must be finite.
    pub fn finite(&mut self, field: &str, value: f64) {
        self.check(value.is_finite(), field, format!("must be a finite number, got {}", shown(value)));
    }

    /// The value must be finite, above `lo` (not equal to it) and at most `hi`.
    pub fn above_and_at_most(&mut self, field: &str, value: f64, lo: f64, hi: f64) {
        self.check(
            value.is_finite() && value > lo && value <= hi,
            field,
            format!("must be above {lo} and at most {hi}, got {}", shown(value)),
        );
    }

    /// The value must lie in `[lo, hi]`.
    pub fn within(&mut self, field: &str, value: f64, lo: f64, hi: f64) {
        self.check(
            value.is_finite() && value >= lo && value <= hi,
            field,
            format!("must be between {lo} and {hi}, got {}", shown(value)),
        );
    }

    /// The text must not be blank.
    pub fn not_blank(&mut self, field: &str, value: &str) {
        self.check(!value.trim().is_empty(), field, "must not be empty");
    }

    pub fn has_errors(&self) -> bool {
        !self.errors.is_empty()
    }

    /// The faults found, in order.
    pub fn into_errors(self) -> Vec<FieldError> {
        self.errors
    }

    pub fn finish(self) -> Result<(), ApiError> {
        if self.errors.is_empty() {
            Ok(())
        } else {
            Err(ApiError::Validation(self.errors))
        }
    }
}

/// Magnitudes from this on, or below the next (but not 0), are shown in scientific notation
/// in error messages.
const SCIENTIFIC_FROM: f64 = 1e9;
const SCIENTIFIC_BELOW: f64 = 1e-6;

/// A number as an error message shows it: as written when short, else in scientific
/// notation (`1e308` and `1e-300`, not 300 digits).
pub fn shown(value: f64) -> String {
    let magnitude = value.abs();
    if value.is_finite() && (magnitude >= SCIENTIFIC_FROM || (magnitude > 0.0 && magnitude < SCIENTIFIC_BELOW)) {
        format!("{value:e}")
    } else {
        value.to_string()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn huge_numbers_are_shown_short_in_the_reasons() {
        let mut v = Validator::new();
        v.within("price", 1e308, 0.0, 1e6);
        v.positive("diameter_mm", -2.5);
        v.within("life_m", 1e-300, 1e-3, 1e7);
        let Err(ApiError::Validation(errors)) = v.finish() else { panic!("no errors") };
        assert_eq!(errors[0].reason, "must be between 0 and 1000000, got 1e308");
        assert_eq!(errors[1].reason, "must be a finite number > 0, got -2.5");
        assert_eq!(errors[2].reason, "must be between 0.001 and 10000000, got 1e-300");
    }

    #[test]
    fn a_validation_problem_names_every_field_and_summarizes_the_first() {
        let mut v = Validator::new();
        v.positive("diameter_mm", -1.0);
        v.not_blank("name", " ");
        let err = v.finish().unwrap_err();
        let p = err.problem();
        assert_eq!(p.status, 422);
        assert_eq!(p.errors.len(), 2);
        assert!(p.detail.starts_with("diameter_mm: must be"));
        assert!(p.detail.ends_with("(and 1 more)"));
    }

    #[test]
    fn a_field_is_named_once_with_its_first_fault() {
        let mut v = Validator::new();
        v.positive("cell_mm", -1.0);
        v.within("cell_mm", -1.0, 1e-3, 5.0);
        let Err(ApiError::Validation(errors)) = v.finish() else { panic!("no errors") };
        assert_eq!(errors.len(), 1);
        assert_eq!(errors[0].reason, "must be a finite number > 0, got -1");
    }

    fn fault(field: &str, reason: &str) -> FieldError {
        FieldError { field: field.into(), reason: reason.into() }
    }

    #[test]
    fn a_later_stage_names_no_field_an_earlier_one_refused_nor_a_part_or_parent_of_it() {
        let mut v = Validator::after(vec![fault("program", "must be an object"), fault("stock.z_top", "not a number")]);
        v.fail("program", "give exactly one of program and job_id");
        v.fail("program.gcode", "line 3: bad word");
        v.fail("stock", "give exactly one of box, contour and dxf");
        v.fail("programs", "a field of its own");
        v.fail("tool_price", "must be between 0 and 1000000, got -5");
        let fields: Vec<String> = v.into_errors().into_iter().map(|e| e.field).collect();
        assert_eq!(fields, ["program", "stock.z_top", "programs", "tool_price"]);
    }

    #[test]
    fn a_resolving_step_keeps_every_line_of_its_program_and_not_a_field_already_named() {
        let mut v = Validator::after(vec![fault("diameter_mm", "must be a number")]);
        v.next_stage();
        let lines = vec![fault("program.gcode", "line 3: bad word"), fault("program.gcode", "line 9: bad word")];
        assert_eq!(v.take::<(), _>(Err(ApiError::Validation(lines))).unwrap(), None);
        assert_eq!(v.take::<(), _>(Err(ApiError::field("diameter_mm", "no such tool"))).unwrap(), None);
        assert_eq!(v.take::<(), _>(Err(ApiError::field("program", "has no moves"))).unwrap(), None);
        assert_eq!(v.take(Ok::<_, ApiError>(7)).unwrap(), Some(7));
        assert!(v.take::<(), _>(Err(ApiError::Internal("the disk failed".into()))).is_err());
        let reasons: Vec<String> = v.into_errors().into_iter().map(|e| e.reason).collect();
        assert_eq!(reasons, ["must be a number", "line 3: bad word", "line 9: bad word"]);
    }

    #[test]
    fn a_field_is_refused_when_it_or_what_it_is_part_of_has_a_fault() {
        let v = Validator::after(vec![fault("stock", "required"), fault("layers[1].contour", "not a list")]);
        assert!(v.refused("stock") && v.refused("stock.box"));
        assert!(v.refused("layers[1].contour.outer"));
        assert!(!v.refused("layers") && !v.refused("layers[10].contour") && !v.refused("stocks"));
        assert!(v.refused_any(&["tool_id", "stock"]) && !v.refused_any(&["tool_id", "diameter_mm"]));
        assert!(v.touched("layers") && !v.touched("layer"));
    }

    #[test]
    fn internal_errors_do_not_leak_their_detail() {
        let p = ApiError::Internal("disk I/O error at /secret/path".into()).problem();
        assert_eq!(p.status, 500);
        assert!(!p.detail.contains("secret"));
    }
}
