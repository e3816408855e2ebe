//! Request extractors whose rejections are problem documents naming the field.

use crate::service::error::{excerpt, ApiError, FieldError};
use crate::service::reasons::{parameter_reason, reason};
use axum::extract::{FromRequest, FromRequestParts, Request};
use axum::http::{header, request::Parts};
use serde::de::DeserializeOwned;

/// A JSON body. Malformed JSON is a 400; a well-formed body whose values do not fit the
/// schema is a 422 naming the field path (e.g. `points[2].l_mm`).
pub struct ApiJson<T>(pub T);

impl<S, T> FromRequest<S> for ApiJson<T>
where
    S: Send + Sync,
    T: DeserializeOwned,
{
    type Rejection = ApiError;

    async fn from_request(req: Request, state: &S) -> Result<Self, Self::Rejection> {
        let JsonBytes(bytes) = JsonBytes::from_request(req, state).await?;
        parse_json(&bytes).map(ApiJson)
    }
}

/// A JSON body, not yet parsed: for bodies that may be large, which are parsed off the
/// async runtime ([`parse_json`] on a blocking thread). A body that is not JSON is a 415.
pub struct JsonBytes(pub axum::body::Bytes);

impl<S: Send + Sync> FromRequest<S> for JsonBytes {
    type Rejection = ApiError;

    async fn from_request(req: Request, state: &S) -> Result<Self, Self::Rejection> {
        let content_type =
            req.headers().get(header::CONTENT_TYPE).and_then(|v| v.to_str().ok()).unwrap_or("").to_string();
        let is_json = content_type
            .parse::<mime::Mime>()
            .map(|m| m.subtype() == mime::JSON || m.suffix() == Some(mime::JSON))
            .unwrap_or(false);
        if !is_json {
            return Err(ApiError::UnsupportedMediaType(format!(
                "the body must be JSON (Content-Type: application/json), got '{content_type}'"
            )));
        }
        axum::body::Bytes::from_request(req, state)
            .await
            .map(JsonBytes)
            .map_err(|rejection| ApiError::Status { status: rejection.status(), detail: rejection.body_text() })
    }
}

/// Parses JSON bytes into `T`, mapping syntax errors to 400 and data errors to 422
/// with the path of the offending field (the reason never carries a JSON position).
pub fn parse_json<T: DeserializeOwned>(bytes: &[u8]) -> Result<T, ApiError> {
    let value: serde_json::Value =
        serde_json::from_slice(bytes).map_err(|e| ApiError::BadRequest(format!("malformed JSON: {e}")))?;
    from_value(value)
}

/// Most field errors one problem lists.
pub const MAX_FIELD_ERRORS: usize = 50;

/// Converts an already-parsed JSON value into `T` with path-aware errors (422), listing
/// every refused field at once: after each refusal the field is set aside and the rest read
/// again, until the value reads, a required field is missing, a refusal repeats or is
/// inside a list (whose later items would be misnamed), or [`MAX_FIELD_ERRORS`] are found.
pub fn from_value<T: DeserializeOwned>(value: serde_json::Value) -> Result<T, ApiError> {
    match read_all(value) {
        Read { value: Some(read), refused } if refused.is_empty() => Ok(read),
        Read { refused, .. } => Err(ApiError::Validation(refused)),
    }
}

/// What [`read_all`] made of a document.
pub struct Read<T> {
    /// The document as read, with every refused member set aside (`None` when it does not
    /// read even so: a required field is missing or refused, or the reading stopped).
    pub value: Option<T>,
    /// Every refused field.
    pub refused: Vec<FieldError>,
}

/// Reads `value` as a `T` like [`from_value`], and also returns what the rest of the
/// document reads as once the refused members are set aside, so that the values of the
/// fields that did read can be checked as well and every fault reported at once.
pub fn read_all<T: DeserializeOwned>(mut value: serde_json::Value) -> Read<T> {
    whole_numbers_as_integers(&mut value);
    let mut refused: Vec<FieldError> = Vec::new();
    loop {
        let refusal = match serde_path_to_error::deserialize::<_, T>(&value) {
            Ok(read) => return Read { value: Some(read), refused },
            Err(e) => e,
        };
        let error = field_error(refusal.path().to_string(), &refusal.inner().to_string());
        if refused.iter().any(|e| e.field == error.field) {
            break;
        }
        let missing = error.reason == REQUIRED;
        refused.push(error);
        if missing || refused.len() >= MAX_FIELD_ERRORS || !set_aside(&mut value, refusal.path()) {
            break;
        }
    }
    Read { value: None, refused }
}

/// What a missing field is said to be.
const REQUIRED: &str = "is required";

/// Removes the object member at `path` from `value`; `false` when the path does not end at
/// a member of an object (the document itself, an item of a list).
fn set_aside(value: &mut serde_json::Value, path: &serde_path_to_error::Path) -> bool {
    use serde_path_to_error::Segment;
    let segments: Vec<&Segment> = path.iter().collect();
    let Some((Segment::Map { key } | Segment::Enum { variant: key }, parents)) = segments.split_last() else {
        return false;
    };
    let mut at = value;
    for segment in parents {
        let next = match segment {
            Segment::Map { key } | Segment::Enum { variant: key } => at.get_mut(key.as_str()),
            Segment::Seq { index } => at.get_mut(*index),
            Segment::Unknown => None,
        };
        match next {
            Some(next) => at = next,
            None => return false,
        }
    }
    at.as_object_mut().is_some_and(|object| object.shift_remove(key.as_str()).is_some())
}

/// Largest magnitude a whole number written with a fraction or exponent (`10.0`, `1e3`)
/// is read as an integer up to: 2^53, where every whole number is exact in a double.
const EXACT_INTEGER_LIMIT: f64 = 9_007_199_254_740_992.0;

/// Whole numbers written as `10.0` or `1e3` become integers, as JSON (and JSON Schema's
/// `integer`) counts them: a count or an id sent as `4.0` is read as 4. Fields of type
/// number read integers as well, so nothing else changes.
fn whole_numbers_as_integers(value: &mut serde_json::Value) {
    use serde_json::Value;
    match value {
        Value::Number(n) if !n.is_i64() && !n.is_u64() => {
            if let Some(x) = n.as_f64().filter(|x| x.fract() == 0.0 && x.abs() <= EXACT_INTEGER_LIMIT) {
                *value = Value::from(x as i64);
            }
        }
        Value::Array(items) => items.iter_mut().for_each(whole_numbers_as_integers),
        Value::Object(map) => map.values_mut().for_each(whole_numbers_as_integers),
        _ => {}
    }
}

/// `message` with every stretch between backticks or double quotes (serde quotes the
/// input it refuses) longer than [`MAX_QUOTED_INPUT_CHARS`] cut to its first characters
/// and an ellipsis ([`excerpt`]).
fn shorten_quoted(message: &str) -> String {
    let mut out = String::with_capacity(message.len().min(256));
    let mut rest = message;
    while let Some(open) = rest.find(['`', '"']) {
        let quote = rest[open..].chars().next().unwrap_or('"');
        let inner_start = open + quote.len_utf8();
        let Some(len) = rest[inner_start..].find(quote) else {
            break;
        };
        let inner = &rest[inner_start..inner_start + len];
        out.push_str(&rest[..inner_start]);
        out.push_str(&excerpt(inner));
        out.push(quote);
        rest = &rest[inner_start + len + quote.len_utf8()..];
    }
    out.push_str(rest);
    out
}

/// The field a deserialisation error at `path` is about, and why: a missing field is named
/// itself ("diameter_mm: is required"), not its parent object.
fn field_error(path: String, message: &str) -> FieldError {
    let missing = message.strip_prefix("missing field `").and_then(|rest| rest.split_once('`')).map(|(name, _)| name);
    match missing {
        Some(name) if path == "." || path.is_empty() => FieldError { field: name.to_string(), reason: REQUIRED.into() },
        Some(name) => FieldError { field: format!("{path}.{name}"), reason: REQUIRED.into() },
        None => FieldError { field: field_of(path), reason: shorten_quoted(&reason(message)) },
    }
}

fn field_of(path: String) -> String {
    if path == "." || path.is_empty() {
        "body".to_string()
    } else {
        path
    }
}

/// Query parameters; a bad parameter is a 400 naming it. With `LISTS`, a parameter may
/// repeat into a list (`tag=a&tag=b`), and an empty value is refused (a list's reader
/// would read `limit=` as no limit).
pub struct ApiQuery<T, const LISTS: bool = false>(pub T);

impl<S, T, const LISTS: bool> FromRequestParts<S> for ApiQuery<T, LISTS>
where
    S: Send + Sync,
    T: DeserializeOwned,
{
    type Rejection = ApiError;

    async fn from_request_parts(parts: &mut Parts, _state: &S) -> Result<Self, Self::Rejection> {
        let query = parts.uri.query().unwrap_or("");
        let pairs = form_urlencoded::parse(query.as_bytes());
        if !LISTS {
            let de = serde_urlencoded::Deserializer::new(pairs);
            return serde_path_to_error::deserialize(de).map(ApiQuery).map_err(query_rejection);
        }
        if let Some((key, _)) = pairs.clone().find(|(_, value)| value.is_empty()) {
            return Err(ApiError::BadRequest(format!("query parameter {}: must not be empty", excerpt(&key))));
        }
        let de = serde_html_form::Deserializer::new(pairs);
        serde_path_to_error::deserialize(de).map(ApiQuery).map_err(query_rejection)
    }
}

/// A query parameter that does not read, named.
fn query_rejection<E: std::fmt::Display>(e: serde_path_to_error::Error<E>) -> ApiError {
    let field = field_of(e.path().to_string());
    ApiError::Status {
        status: axum::http::StatusCode::BAD_REQUEST,
        detail: format!("query parameter {field}: {}", shorten_quoted(&reason(&e.inner().to_string()))),
    }
}

/// Path parameters; a malformed one (e.g. `/v1/tools/abc`) is a 400.
pub struct ApiPath<T>(pub T);

impl<S, T> FromRequestParts<S> for ApiPath<T>
where
    S: Send + Sync,
    T: DeserializeOwned + Send,
{
    type Rejection = ApiError;

    async fn from_request_parts(parts: &mut Parts, state: &S) -> Result<Self, Self::Rejection> {
        match axum::extract::Path::<T>::from_request_parts(parts, state).await {
            Ok(axum::extract::Path(v)) => Ok(ApiPath(v)),
            Err(rejection) => {
                let raw = axum::extract::RawPathParams::from_request_parts(parts, state).await.ok();
                let params: Vec<(String, String)> = raw
                    .iter()
                    .flat_map(|raw| raw.iter().map(|(key, value)| (key.to_string(), value.to_string())))
                    .collect();
                Err(path_rejection(rejection, &params))
            }
        }
    }
}

/// The parameter a refusal without a key is about: the only one, or the one whose value
/// the message quotes (a type of ours refusing its value says what it got).
fn refused_parameter<'a>(message: &str, params: &'a [(String, String)]) -> Option<&'a str> {
    match params {
        [(key, _)] => Some(key),
        _ => params.iter().find(|(_, value)| message.contains(&format!("\"{value}\""))).map(|(key, _)| key.as_str()),
    }
}

/// A path parameter that does not parse, named with what it must be.
fn path_rejection(rejection: axum::extract::rejection::PathRejection, params: &[(String, String)]) -> ApiError {
    use axum::extract::path::ErrorKind;
    use axum::extract::rejection::PathRejection;
    let detail = match &rejection {
        PathRejection::FailedToDeserializePathParams(e) => match e.kind() {
            ErrorKind::ParseErrorAtKey { key, value, expected_type } => {
                format!("path parameter {key}: {}", parameter_reason(expected_type, value))
            }
            ErrorKind::ParseError { value, expected_type }
            | ErrorKind::ParseErrorAtIndex { value, expected_type, .. } => {
                format!("path parameter: {}", parameter_reason(expected_type, value))
            }
            ErrorKind::InvalidUtf8InPathParam { key } => format!("path parameter {key}: must be UTF-8 text"),
            ErrorKind::Message(message) => match refused_parameter(message, params) {
                Some(key) => format!("path parameter {key}: {}", reason(&shorten_quoted(message))),
                None => format!("path: {}", reason(&shorten_quoted(message))),
            },
            ErrorKind::DeserializeError { key, message, .. } => format!("path parameter {key}: {}", reason(message)),
            other => format!("path: {}", reason(&shorten_quoted(&other.to_string()))),
        },
        other => format!("path: {}", reason(&shorten_quoted(&other.body_text()))),
    };
    ApiError::BadRequest(detail)
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde::Deserialize;

    #[derive(Debug, Deserialize)]
    #[allow(dead_code)]
    struct Tool {
        diameter_mm: f64,
        holder: Holder,
    }

    #[derive(Debug, Deserialize)]
    #[allow(dead_code)]
    struct Holder {
        gauge_mm: f64,
    }

    fn only_error(e: ApiError) -> FieldError {
        match e {
            ApiError::Validation(mut errors) if errors.len() == 1 => errors.remove(0),
            other => panic!("not one field error: {other:?}"),
        }
    }

    #[test]
    fn a_missing_field_is_named_itself_and_said_to_be_required() {
        let e = only_error(from_value::<Tool>(serde_json::json!({"holder": {"gauge_mm": 60}})).unwrap_err());
        assert_eq!((e.field.as_str(), e.reason.as_str()), ("diameter_mm", "is required"));
        let e = only_error(parse_json::<Tool>(br#"{"diameter_mm": 10, "holder": {}}"#).unwrap_err());
        assert_eq!((e.field.as_str(), e.reason.as_str()), ("holder.gauge_mm", "is required"));
    }

    #[test]
    fn every_refused_field_of_a_document_is_listed_at_once() {
        #[derive(Debug, Deserialize)]
        #[serde(deny_unknown_fields)]
        #[allow(dead_code)]
        struct Request {
            diameter_mm: Option<f64>,
            flutes: Option<u32>,
            holder: Option<Holder>,
        }
        let body = br#"{"colour": "red", "diameter_mm": "ten", "flutes": -4, "holder": {"gauge_mm": "long"}}"#;
        let ApiError::Validation(errors) = parse_json::<Request>(body).unwrap_err() else {
            panic!("not a validation error")
        };
        let fields: Vec<&str> = errors.iter().map(|e| e.field.as_str()).collect();
        assert_eq!(fields, ["colour", "diameter_mm", "flutes", "holder.gauge_mm"], "{errors:?}");
    }

    #[test]
    fn a_missing_field_is_named_with_the_faults_read_before_it() {
        let ApiError::Validation(errors) = parse_json::<Tool>(br#"{"diameter_mm": "ten", "holder": {}}"#).unwrap_err()
        else {
            panic!("not a validation error")
        };
        let fields: Vec<&str> = errors.iter().map(|e| e.field.as_str()).collect();
        assert_eq!(fields, ["diameter_mm", "holder.gauge_mm"], "{errors:?}");
    }

    #[test]
    fn a_long_refused_value_is_quoted_by_its_first_characters_not_echoed_whole() {
        let long = "x".repeat(5000);
        let body = format!(r#"{{"diameter_mm": "{long}", "holder": {{"gauge_mm": 60}}}}"#);
        let e = only_error(parse_json::<Tool>(body.as_bytes()).unwrap_err());
        let quoted = format!("\"{}…\"", &long[..crate::service::error::MAX_QUOTED_INPUT_CHARS]);
        assert_eq!(e.field, "diameter_mm");
        assert!(e.reason.contains(&quoted) && e.reason.len() < 200, "{}", e.reason);
        assert_eq!(
            shorten_quoted("unknown variant `squar`, expected one of `square`, `ball`"),
            "unknown variant `squar`, expected one of `square`, `ball`"
        );
        assert_eq!(shorten_quoted("an unpaired ` quote stays"), "an unpaired ` quote stays");
    }

    #[test]
    fn a_whole_number_written_with_a_fraction_is_read_as_an_integer() {
        #[derive(Debug, Deserialize)]
        struct Count {
            flutes: u32,
            id: i64,
        }
        let read = parse_json::<Count>(br#"{"flutes": 4.0, "id": 1e3}"#).unwrap();
        assert_eq!((read.flutes, read.id), (4, 1000));
        let e = only_error(parse_json::<Count>(br#"{"flutes": 4.5, "id": 1}"#).unwrap_err());
        assert_eq!(e.reason, "must be a whole number from 0 to 4294967295, got 4.5");
    }

    #[test]
    fn a_value_of_the_wrong_type_is_named_by_its_path_without_the_json_position() {
        let e = only_error(parse_json::<Tool>(br#"{"diameter_mm": "ten", "holder": {"gauge_mm": 60}}"#).unwrap_err());
        assert_eq!(e.field, "diameter_mm");
        assert_eq!(e.reason, r#"must be a number, got "ten""#);
    }
}
