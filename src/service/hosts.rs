//! `--allowed-hosts`: requests must name one of the service's own host names in `Host`,
//! so a web page on another name that resolves here (DNS rebinding) cannot use it.

use crate::service::error::ApiError;
use axum::extract::{Request, State};
use axum::http::{header, StatusCode};
use axum::middleware::Next;
use axum::response::{IntoResponse, Response};
use std::sync::Arc;

/// Paths a health probe calls by address, whatever the allowed names.
pub const PROBES: &[&str] = &["/healthz", "/readyz"];

/// The host names (or `name:port`) allowed in `Host`; empty: any.
#[derive(Debug, Clone, Default)]
pub struct AllowedHosts(Arc<Vec<String>>);

impl AllowedHosts {
    pub fn new(hosts: &[String]) -> AllowedHosts {
        AllowedHosts(Arc::new(hosts.iter().map(|h| h.trim().to_ascii_lowercase()).filter(|h| !h.is_empty()).collect()))
    }

    /// `true` when `host` (the `Host` header) is allowed: equal to an entry, or its name
    /// part equal to an entry without a port.
    pub fn allows(&self, host: Option<&str>) -> bool {
        if self.0.is_empty() {
            return true;
        }
        let Some(host) = host.map(str::to_ascii_lowercase) else {
            return false;
        };
        let name = strip_port(&host);
        self.0.iter().any(|allowed| *allowed == host || *allowed == name)
    }
}

/// `host` without its `:port` (an IPv6 literal keeps its brackets).
fn strip_port(host: &str) -> &str {
    match host.rfind(':') {
        Some(colon) if !host[colon..].contains(']') && host[colon + 1..].bytes().all(|b| b.is_ascii_digit()) => {
            &host[..colon]
        }
        _ => host,
    }
}

/// Refuses a request whose `Host` is not allowed (400), except the health probes.
pub async fn check_host(State(allowed): State<AllowedHosts>, request: Request, next: Next) -> Response {
    let host = request.headers().get(header::HOST).and_then(|v| v.to_str().ok()).map(str::to_string);
    if PROBES.contains(&request.uri().path()) || allowed.allows(host.as_deref()) {
        return next.run(request).await;
    }
    ApiError::Status {
        status: StatusCode::BAD_REQUEST,
        detail: "the Host header names a host this service does not answer for (see --allowed-hosts)".to_string(),
    }
    .into_response()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_allowed_name_matches_with_or_without_a_port_and_others_are_refused() {
        let allowed = AllowedHosts::new(&["dieplan.shop.lan".into(), "10.0.0.5:8080".into(), "[::1]".into()]);
        assert!(allowed.allows(Some("dieplan.shop.lan")));
        assert!(allowed.allows(Some("DIEPLAN.shop.lan:8080")));
        assert!(allowed.allows(Some("10.0.0.5:8080")));
        assert!(!allowed.allows(Some("10.0.0.5:9090")));
        assert!(allowed.allows(Some("[::1]:8080")));
        assert!(!allowed.allows(Some("evil.example")));
        assert!(!allowed.allows(None));
    }

    #[test]
    fn no_list_allows_every_host() {
        assert!(AllowedHosts::new(&[]).allows(Some("anything")));
        assert!(AllowedHosts::new(&[" ".into()]).allows(None));
    }
}
