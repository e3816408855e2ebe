//! The answers every operation can get from the layers in front of its handler, written
//! into the OpenAPI document from the same rules those layers apply, so the document
//! lists every status and header the service can send:
//!
//! - 400: malformed JSON (any body), a malformed path or query parameter, and a `Host`
//!   the service does not answer for (`--allowed-hosts`; every route but the probes);
//! - 404: an id in the path that names nothing;
//! - 413: a body over `--body-limit` (any body);
//! - 415: a body that is not JSON (any JSON body);
//! - 422: a body whose values are refused (any body);
//! - 503: a request that ran past `--request-timeout-s` (every route);
//! - `Location` on every 201 and 202 (a created row, key or job).
//!
//! A status the route's own attributes describe keeps its description.

use crate::service::hosts::PROBES;
use crate::service::security_docs::problem;
use std::collections::BTreeMap;
use utoipa::openapi::path::{Operation, ParameterIn};
use utoipa::openapi::schema::{ObjectBuilder, Type};
use utoipa::openapi::{HeaderBuilder, OpenApi, RefOr, Response};

/// Adds the layers' answers and the `Location` header to every operation.
pub fn describe(doc: &mut OpenApi) {
    for (path, item) in doc.paths.paths.iter_mut() {
        let probe = PROBES.contains(&path.as_str());
        for op in [&mut item.get, &mut item.post, &mut item.put, &mut item.patch, &mut item.delete, &mut item.head]
            .into_iter()
            .flatten()
        {
            document(op, probe);
        }
    }
}

fn document(op: &mut Operation, probe: bool) {
    let body = op.request_body.as_ref();
    let has_body = body.is_some();
    let json_body = body.is_some_and(|b| b.content.keys().any(|c| c.contains("json")));
    let params = op.parameters.as_deref().unwrap_or_default();
    let in_path = params.iter().any(|p| matches!(p.parameter_in, ParameterIn::Path));
    let in_query = params.iter().any(|p| matches!(p.parameter_in, ParameterIn::Query));

    let mut bad_request = Vec::new();
    if has_body {
        bad_request.push("malformed JSON");
    }
    if in_path || in_query {
        bad_request.push("a malformed path or query parameter");
    }
    if !probe {
        bad_request.push("a Host header the service does not answer for (--allowed-hosts)");
    }
    let responses = &mut op.responses.responses;
    if !bad_request.is_empty() {
        let text = format!("Refused as unreadable: {}", bad_request.join("; "));
        add(responses, "400", &text);
    }
    if in_path {
        add(responses, "404", "Nothing has the id in the path");
    }
    if has_body {
        add(responses, "413", "The body is larger than the service accepts (--body-limit)");
        add(responses, "422", "A refused field: `errors` names each one and why");
    }
    if json_body {
        add(responses, "415", "The body is not JSON (Content-Type: application/json)");
    }
    add(responses, "503", "The request took longer than the service allows (--request-timeout-s)");
    for (code, response) in responses.iter_mut() {
        if let (true, RefOr::T(response)) = (code == "201" || code == "202", response) {
            response.headers.entry("Location".to_string()).or_insert_with(|| {
                HeaderBuilder::new()
                    .schema(ObjectBuilder::new().schema_type(Type::String))
                    .description(Some("What was made, as a path under the service"))
                    .build()
            });
        }
    }
}

/// Adds a problem-document answer unless the route describes that status itself.
fn add(responses: &mut BTreeMap<String, RefOr<Response>>, code: &str, description: &str) {
    responses.entry(code.to_string()).or_insert_with(|| problem(description, None).into());
}
