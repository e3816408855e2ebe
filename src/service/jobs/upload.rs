//! A program sent as a file: the named endpoints of the kinds that read an NC program
//! (`/v1/analysis`, `/v1/feeds`, `/v1/costing`, `/v1/trochoids`) also take
//! `multipart/form-data`, as `curl -F program=@part.nc` sends it:
//!
//! - `program` (required): the G-code, UTF-8 text, read as the request's `program.gcode`;
//! - `request` (optional): the rest of the submission as JSON, as the JSON body would be
//!   without `program.gcode` (its `program` may still hold how to read the program: the
//!   control, the tool table, …; and the job's `name` and `tags`).
//!
//! A part that is missing, repeated, unknown, not UTF-8 or not JSON is a 422 naming the
//! part; a body that is not multipart at all a 400; one larger than the body limit a 413
//! naming the part it grew past the limit in (a body whose declared `Content-Length` is
//! over the limit is refused before it is read: app.rs says so, with the limit).

use super::model::JobKind;
use crate::service::error::{excerpt, ApiError, FieldError};
use axum::extract::multipart::{Multipart, MultipartError};
use axum::extract::{FromRequest, Request};
use axum::http::header;
use serde_json::{Map, Value};
use utoipa::openapi::content::ContentBuilder;
use utoipa::openapi::encoding::EncodingBuilder;
use utoipa::openapi::schema::{ObjectBuilder, Type};
use utoipa::openapi::Content;

/// The content type of an upload.
pub const MULTIPART: &str = "multipart/form-data";
/// The part holding the program.
pub const PROGRAM_PART: &str = "program";
/// The part holding the rest of the request.
pub const REQUEST_PART: &str = "request";

/// `true` when the named endpoint of `kind` takes a program as a file.
pub fn takes_program(kind: JobKind) -> bool {
    matches!(kind, JobKind::Analysis | JobKind::Feeds | JobKind::Costing | JobKind::Trochoids)
}

/// `true` when `request` is a multipart upload.
pub fn is_multipart(request: &Request) -> bool {
    request
        .headers()
        .get(header::CONTENT_TYPE)
        .and_then(|v| v.to_str().ok())
        .and_then(|v| v.parse::<mime::Mime>().ok())
        .is_some_and(|m| m.type_() == mime::MULTIPART && m.subtype() == mime::FORM_DATA)
}

/// Where in an upload the reading stopped: in a part, or between parts (after the last
/// one read, if any).
#[derive(Debug, Clone, Copy)]
enum At<'a> {
    In(&'a str),
    After(Option<&'a str>),
}

/// A multipart error, as a problem naming the part being read when it is known; a body
/// over the limit says the limit and the setting that raises it.
fn refused(e: MultipartError, at: At, body_limit: usize) -> ApiError {
    let status = e.status();
    let (what, reading) = match at {
        At::In(part) => (format!("part {part}: "), format!("while reading part {part}")),
        At::After(Some(part)) => (format!("after part {part}: "), format!("while reading the part after {part}")),
        At::After(None) => (String::new(), "before its first part".to_string()),
    };
    let detail = if status == axum::http::StatusCode::PAYLOAD_TOO_LARGE {
        format!("{what}the request body grew past the limit of {body_limit} bytes {reading}; the service's --body-limit (DIEPLAN_BODY_LIMIT) raises it")
    } else {
        format!("{what}malformed multipart/form-data: {}", excerpt(&e.body_text()))
    };
    ApiError::Status { status, detail }
}

/// Reads an upload into the JSON submission it stands for: the `request` part (or an
/// empty object) with the `program` part as `program.gcode`. `body_limit` is the
/// service's (a body over it is refused naming the part it was in).
pub async fn read(request: Request, body_limit: usize) -> Result<Value, ApiError> {
    let mut multipart = Multipart::from_request(request, &())
        .await
        .map_err(|e| ApiError::BadRequest(format!("malformed multipart/form-data: {}", e.body_text())))?;
    let mut faults = Vec::new();
    let mut fail = |field: &str, reason: String| faults.push(FieldError { field: field.to_string(), reason });
    let (mut program, mut rest): (Option<String>, Option<Value>) = (None, None);
    let mut last: Option<String> = None;
    while let Some(field) =
        multipart.next_field().await.map_err(|e| refused(e, At::After(last.as_deref()), body_limit))?
    {
        let name = field.name().unwrap_or_default().to_string();
        let bytes = field.bytes().await.map_err(|e| refused(e, At::In(&name), body_limit))?;
        last = Some(name.clone());
        match name.as_str() {
            PROGRAM_PART if program.is_some() => fail(PROGRAM_PART, "is sent more than once".into()),
            PROGRAM_PART => match String::from_utf8(bytes.to_vec()) {
                Ok(text) => program = Some(text),
                Err(e) => {
                    fail(
                        PROGRAM_PART,
                        format!("must be UTF-8 text (G-code), byte {} is not", e.utf8_error().valid_up_to()),
                    );
                    program = Some(String::new());
                }
            },
            REQUEST_PART if rest.is_some() => fail(REQUEST_PART, "is sent more than once".into()),
            REQUEST_PART => match serde_json::from_slice::<Value>(&bytes) {
                Ok(value @ Value::Object(_)) => rest = Some(value),
                Ok(other) => {
                    fail(REQUEST_PART, format!("must be a JSON object, got {}", excerpt(&other.to_string())));
                    rest = Some(Value::Null);
                }
                Err(e) => {
                    fail(REQUEST_PART, format!("must be JSON: {e}"));
                    rest = Some(Value::Null);
                }
            },
            other => {
                fail(other, format!("is not a part this endpoint takes (it takes {PROGRAM_PART} and {REQUEST_PART})"))
            }
        }
    }
    let Some(program) = program else {
        fail(PROGRAM_PART, "is required: send the NC program as a file part named program".into());
        return Err(ApiError::Validation(faults));
    };
    let mut body = match rest {
        Some(Value::Object(map)) => map,
        _ => Map::new(),
    };
    let gcode = body.entry("program").or_insert_with(|| Value::Object(Map::new()));
    match gcode.as_object_mut() {
        Some(options) if options.contains_key("gcode") || options.contains_key("moves") => {
            fail("request.program", "must not hold gcode or moves: the program part is the program".into())
        }
        Some(options) => {
            options.insert("gcode".into(), Value::String(program));
        }
        None => fail("request.program", "must be an object (how to read the program)".into()),
    }
    if faults.is_empty() {
        Ok(Value::Object(body))
    } else {
        Err(ApiError::Validation(faults))
    }
}

/// The `multipart/form-data` content of a named endpoint's request body in the document.
pub fn content() -> Content {
    let program = ObjectBuilder::new()
        .schema_type(Type::String)
        .content_media_type("text/plain")
        .description(Some("The NC program (G-code), UTF-8 text: read as the request's `program.gcode`."));
    let rest = ObjectBuilder::new().schema_type(Type::Object).description(Some(
        "The rest of the request as JSON, without `program.gcode` (its `program` may say how to read the program), with the job's `name` and `tags`; default `{}`.",
    ));
    let schema = ObjectBuilder::new()
        .property(PROGRAM_PART, program)
        .property(REQUEST_PART, rest)
        .required(PROGRAM_PART)
        .additional_properties(Some(utoipa::openapi::schema::AdditionalProperties::FreeForm(false)))
        .description(Some("An NC program sent as a file, and the rest of the request."));
    ContentBuilder::new()
        .schema(Some(schema))
        .encoding(PROGRAM_PART, EncodingBuilder::new().content_type(Some("text/plain".to_string())).build())
        .encoding(REQUEST_PART, EncodingBuilder::new().content_type(Some("application/json".to_string())).build())
        .build()
}
