//! The web page at `/`: plain HTML, CSS and JavaScript modules embedded in the binary (no
//! build step, nothing from a CDN). Each asset carries an `ETag` of its content and
//! `Cache-Control: no-cache`, so a browser revalidates cheaply and never runs a stale page
//! after an upgrade.

use crate::service::state::AppState;
use axum::http::{header, HeaderMap, HeaderValue, StatusCode};
use axum::response::{IntoResponse, Response};
use axum::routing::get;
use axum::Router;
use std::hash::{Hash, Hasher};

/// One embedded asset: URL path, content type, content.
struct Asset {
    path: &'static str,
    content_type: &'static str,
    body: &'static str,
}

const JS: &str = "text/javascript; charset=utf-8";
const TEXT: &str = "text/plain; charset=utf-8";

static ASSETS: &[Asset] = &[
    Asset { path: "/", content_type: "text/html; charset=utf-8", body: include_str!("web/index.html") },
    Asset { path: "/app.css", content_type: "text/css; charset=utf-8", body: include_str!("web/app.css") },
    Asset { path: "/favicon.svg", content_type: "image/svg+xml", body: include_str!("web/favicon.svg") },
    Asset { path: "/app.js", content_type: JS, body: include_str!("web/app.js") },
    Asset { path: "/ui.js", content_type: JS, body: include_str!("web/ui.js") },
    Asset { path: "/key.js", content_type: JS, body: include_str!("web/key.js") },
    Asset { path: "/new-job.js", content_type: JS, body: include_str!("web/new-job.js") },
    Asset { path: "/job-view.js", content_type: JS, body: include_str!("web/job-view.js") },
    Asset { path: "/drawing.js", content_type: JS, body: include_str!("web/drawing.js") },
    Asset { path: "/jobs.js", content_type: JS, body: include_str!("web/jobs.js") },
    Asset { path: "/database.js", content_type: JS, body: include_str!("web/database.js") },
    Asset { path: "/savings.js", content_type: JS, body: include_str!("web/savings.js") },
    Asset { path: "/units.js", content_type: JS, body: include_str!("web/units.js") },
    Asset { path: "/program-view.js", content_type: JS, body: include_str!("web/program-view.js") },
    Asset { path: "/zoom.js", content_type: JS, body: include_str!("web/zoom.js") },
    Asset { path: "/trace.js", content_type: JS, body: include_str!("web/trace.js") },
    Asset { path: "/view3d-panel.js", content_type: JS, body: include_str!("web/view3d-panel.js") },
    Asset { path: "/view3d.js", content_type: JS, body: include_str!("web/view3d.js") },
    Asset { path: "/scene3d.js", content_type: JS, body: include_str!("web/scene3d.js") },
    Asset { path: "/levels3d.js", content_type: JS, body: include_str!("web/levels3d.js") },
    Asset { path: "/tool3d.js", content_type: JS, body: include_str!("web/tool3d.js") },
    // three.js, vendored unchanged (see web/vendor/three/README.md for the version).
    Asset {
        path: "/vendor/three/three.module.js",
        content_type: JS,
        body: include_str!("web/vendor/three/three.module.js"),
    },
    Asset {
        path: "/vendor/three/three.core.js",
        content_type: JS,
        body: include_str!("web/vendor/three/three.core.js"),
    },
    Asset {
        path: "/vendor/three/OrbitControls.js",
        content_type: JS,
        body: include_str!("web/vendor/three/OrbitControls.js"),
    },
    Asset { path: "/vendor/three/LICENSE", content_type: TEXT, body: include_str!("web/vendor/three/LICENSE") },
];

/// The version of three.js the page's 3-D view is vendored with.
pub const THREE_JS_VERSION: &str = "0.187.0";

fn etag(body: &str) -> String {
    let mut hasher = std::collections::hash_map::DefaultHasher::new();
    body.hash(&mut hasher);
    env!("CARGO_PKG_VERSION").hash(&mut hasher);
    format!("\"{:016x}\"", hasher.finish())
}

fn serve(asset: &'static Asset, headers: &HeaderMap) -> Response {
    let tag = etag(asset.body);
    let matches = headers
        .get(header::IF_NONE_MATCH)
        .and_then(|v| v.to_str().ok())
        .is_some_and(|v| v.split(',').any(|t| t.trim() == tag || t.trim() == "*"));
    let etag_value = HeaderValue::from_str(&tag).unwrap_or_else(|_| HeaderValue::from_static("\"0\""));
    let cache = HeaderValue::from_static("no-cache");
    if matches {
        return (StatusCode::NOT_MODIFIED, [(header::ETAG, etag_value), (header::CACHE_CONTROL, cache)])
            .into_response();
    }
    (
        [
            (header::CONTENT_TYPE, HeaderValue::from_static(asset.content_type)),
            (header::ETAG, etag_value),
            (header::CACHE_CONTROL, cache),
            (header::X_CONTENT_TYPE_OPTIONS, HeaderValue::from_static("nosniff")),
        ],
        asset.body,
    )
        .into_response()
}

/// The page's routes (not part of the OpenAPI document).
pub fn router() -> Router<AppState> {
    ASSETS.iter().fold(Router::new(), |router, asset| {
        router.route(asset.path, get(move |headers: HeaderMap| async move { serve(asset, &headers) }))
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_asset_has_a_distinct_path_and_content() {
        let mut paths: Vec<&str> = ASSETS.iter().map(|a| a.path).collect();
        paths.sort_unstable();
        paths.dedup();
        assert_eq!(paths.len(), ASSETS.len());
        assert!(ASSETS.iter().all(|a| !a.body.trim().is_empty()));
    }

    #[test]
    fn three_js_is_served_with_its_licence_at_the_version_its_note_names() {
        let three = ASSETS.iter().find(|a| a.path == "/vendor/three/three.core.js").expect("three.js");
        assert!(three.body.contains(&format!("REVISION = '{}'", THREE_JS_VERSION.split('.').nth(1).unwrap())));
        let note = include_str!("web/vendor/three/README.md");
        assert!(note.contains(&format!("three@{THREE_JS_VERSION}")));
        let licence = ASSETS.iter().find(|a| a.path == "/vendor/three/LICENSE").expect("the licence");
        assert!(licence.body.contains("MIT License") && licence.body.contains("three.js authors"));
    }

    #[test]
    fn an_unchanged_asset_answers_304() {
        let asset = &ASSETS[0];
        let mut headers = HeaderMap::new();
        headers.insert(header::IF_NONE_MATCH, HeaderValue::from_str(&etag(asset.body)).unwrap());
        assert_eq!(serve(asset, &headers).status(), StatusCode::NOT_MODIFIED);
        assert_eq!(serve(asset, &HeaderMap::new()).status(), StatusCode::OK);
    }
}
