//! Entity tags of database rows: the SHA-256 of the row as the API shows it, so any change
//! (including `updated_at`) changes it. `If-Match` makes a write conditional on it: a
//! client that read a row, changed it and writes it back learns (412) when someone else
//! wrote in between, instead of silently undoing their change.

use crate::service::error::ApiError;
use axum::http::{header, HeaderMap, HeaderValue, StatusCode};
use serde::Serialize;
use sha2::{Digest, Sha256};

/// Bytes of the digest in a tag: 128 bits, no collision in any shop's lifetime.
const TAG_BYTES: usize = 16;

/// The strong entity tag of `value` (quoted, as the `ETag` header carries it).
pub fn of<T: Serialize>(value: &T) -> String {
    let json = serde_json::to_vec(value).unwrap_or_default();
    format!("\"{}\"", hex::encode(&Sha256::digest(&json)[..TAG_BYTES]))
}

/// The `ETag` header of `value`.
pub fn header<T: Serialize>(value: &T) -> (header::HeaderName, HeaderValue) {
    (header::ETAG, HeaderValue::from_str(&of(value)).unwrap_or_else(|_| HeaderValue::from_static("\"\"")))
}

/// The `If-Match` header of a request, if any (joined when repeated).
pub fn if_match(headers: &HeaderMap) -> Option<String> {
    let values: Vec<&str> = headers.get_all(header::IF_MATCH).iter().filter_map(|v| v.to_str().ok()).collect();
    (!values.is_empty()).then(|| values.join(","))
}

/// Refuses (412) a write whose `If-Match` names none of the row's current tag (`*`
/// matches any existing row; weak tags never match, as RFC 9110 §13.1.1 asks).
pub fn check<T: Serialize>(if_match: Option<&str>, current: &T) -> Result<(), ApiError> {
    let Some(condition) = if_match else {
        return Ok(());
    };
    let tag = of(current);
    if condition.split(',').map(str::trim).any(|t| t == "*" || t == tag) {
        return Ok(());
    }
    Err(ApiError::Status {
        status: StatusCode::PRECONDITION_FAILED,
        detail: format!(
            "the row has changed since it was read (If-Match {}, now {tag}): read it again and reapply the change",
            crate::service::error::excerpt(condition)
        ),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;

    #[test]
    fn the_tag_changes_with_any_field_and_only_then() {
        let a = of(&json!({"id": 1, "name": "x", "updated_at": "t1"}));
        assert_eq!(a, of(&json!({"id": 1, "name": "x", "updated_at": "t1"})));
        assert_ne!(a, of(&json!({"id": 1, "name": "x", "updated_at": "t2"})));
        assert_eq!(a.len(), 2 + 2 * TAG_BYTES);
    }

    #[test]
    fn if_match_passes_the_current_tag_or_a_star_and_refuses_a_stale_or_weak_one() {
        let row = json!({"id": 1});
        let tag = of(&row);
        assert!(check(None, &row).is_ok());
        assert!(check(Some(&tag), &row).is_ok());
        assert!(check(Some("*"), &row).is_ok());
        assert!(check(Some(&format!("\"00\", {tag}")), &row).is_ok());
        let stale = check(Some("\"0123\""), &row).unwrap_err();
        assert_eq!(stale.status(), StatusCode::PRECONDITION_FAILED);
        assert!(check(Some(&format!("W/{tag}")), &row).is_err());
    }
}
