//! Builds the HTTP application, starts it and stops it gracefully.

use crate::service::auth::{authenticate, AuthState, RouteRoles};
use crate::service::config::{Config, LogFormat};
use crate::service::error::{problem_response, ApiError, PROBLEM_JSON};
use crate::service::hosts::{check_host, AllowedHosts};
use crate::service::jobs::queue::JobQueue;
use crate::service::keys::store::{self as keys, EnvironmentKeyError};
use crate::service::openapi::api_parts;
use crate::service::rate_limit::RateLimits;
use crate::service::state::AppState;
use axum::body::Body;
use axum::extract::{DefaultBodyLimit, State};
use axum::http::{header, HeaderName, HeaderValue, Method, Request, Response, StatusCode};
use axum::Router;
use std::net::SocketAddr;
use std::sync::Arc;
use std::time::Duration;
use thiserror::Error;
use tokio::net::TcpListener;
use tokio::sync::oneshot;
use tokio::task::JoinHandle;
use tower_http::catch_panic::CatchPanicLayer;
use tower_http::compression::CompressionLayer;
use tower_http::cors::{AllowOrigin, CorsLayer};
use tower_http::limit::RequestBodyLimitLayer;
use tower_http::request_id::{MakeRequestUuid, PropagateRequestIdLayer, SetRequestIdLayer};
use tower_http::timeout::TimeoutLayer;
use tower_http::trace::TraceLayer;
use utoipa_swagger_ui::SwaggerUi;

/// The header carrying the request id, echoed in every response.
pub const REQUEST_ID: &str = "x-request-id";

/// Why the service could not start.
#[derive(Debug, Error)]
pub enum StartError {
    #[error("database {path}: {source}")]
    Database { path: String, source: sqlx::Error },
    #[error("cannot listen on {addr}: {source}")]
    Bind { addr: SocketAddr, source: std::io::Error },
    #[error("{0}")]
    AdminKey(#[from] EnvironmentKeyError),
    #[error("refusing to listen on {addr} without API keys: anyone who reaches it could change the database and every job. Set DIEPLAN_ADMIN_KEY, or make a key with `dieplan keys create --role admin --name NAME`, or pass --insecure-no-auth to run open anyway")]
    Unprotected { addr: SocketAddr },
}

/// Sets up `tracing` output as configured. Safe to call more than once.
pub fn init_tracing(config: &Config) {
    let filter = tracing_subscriber::EnvFilter::try_new(&config.log)
        .unwrap_or_else(|_| tracing_subscriber::EnvFilter::new("info"));
    let builder = tracing_subscriber::fmt().with_env_filter(filter);
    let _ = match config.log_format {
        LogFormat::Json => builder.json().try_init(),
        LogFormat::Text => builder.try_init(),
    };
}

/// The application router with every layer.
pub fn router(state: AppState) -> Router {
    let config = state.config.clone();
    let (api, openapi) = api_parts();
    let auth = AuthState {
        app: state.clone(),
        roles: RouteRoles::from_openapi(&openapi),
        limits: Arc::new(RateLimits::default()),
    };
    let api = api.route_layer(axum::middleware::from_fn_with_state(auth, authenticate));
    let request_id = HeaderName::from_static(REQUEST_ID);
    api.merge(SwaggerUi::new("/docs").url("/openapi.json", openapi))
        .merge(crate::service::web::router())
        .fallback(not_found)
        .method_not_allowed_fallback(method_not_allowed)
        .with_state(state)
        .layer(DefaultBodyLimit::disable())
        .layer(RequestBodyLimitLayer::new(config.body_limit))
        .layer(TimeoutLayer::with_status_code(
            StatusCode::SERVICE_UNAVAILABLE,
            Duration::from_secs(config.request_timeout_s),
        ))
        .layer(CatchPanicLayer::custom(panic_response))
        .layer(axum::middleware::from_fn_with_state(config.body_limit, problem_for_bare_errors))
        .layer(CompressionLayer::new().gzip(true))
        .layer(cors(&config.cors_origins))
        .layer(axum::middleware::from_fn_with_state(AllowedHosts::new(&config.allowed_hosts), check_host))
        .layer(PropagateRequestIdLayer::new(request_id.clone()))
        .layer(TraceLayer::new_for_http().make_span_with(|req: &Request<Body>| {
            let id = req.headers().get(REQUEST_ID).and_then(|v| v.to_str().ok()).unwrap_or("-");
            tracing::info_span!("request", method = %req.method(), uri = %req.uri(), request_id = %id)
        }))
        .layer(SetRequestIdLayer::new(request_id, MakeRequestUuid))
}

fn cors(origins: &[String]) -> CorsLayer {
    let origins: Vec<&str> = origins.iter().map(|o| o.trim()).filter(|o| !o.is_empty()).collect();
    if origins.is_empty() {
        return CorsLayer::new();
    }
    let allow = if origins.contains(&"*") {
        AllowOrigin::any()
    } else {
        AllowOrigin::list(origins.iter().filter_map(|o| HeaderValue::from_str(o).ok()))
    };
    CorsLayer::new()
        .allow_origin(allow)
        .allow_methods([Method::GET, Method::POST, Method::PUT, Method::PATCH, Method::DELETE])
        .allow_headers([
            header::CONTENT_TYPE,
            header::AUTHORIZATION,
            header::IF_MATCH,
            HeaderName::from_static("prefer"),
        ])
        .expose_headers([
            header::LOCATION,
            header::ETAG,
            header::RETRY_AFTER,
            header::WWW_AUTHENTICATE,
            HeaderName::from_static(REQUEST_ID),
        ])
}

async fn not_found() -> ApiError {
    ApiError::not_found("no such route: see /openapi.json or /docs")
}

async fn method_not_allowed() -> ApiError {
    ApiError::Status {
        status: StatusCode::METHOD_NOT_ALLOWED,
        detail: "this route does not take that method: see /openapi.json".to_string(),
    }
}

fn panic_response(_: Box<dyn std::any::Any + Send + 'static>) -> Response<Body> {
    tracing::error!("a request handler panicked");
    problem_response(&ApiError::Internal("panic".into()).problem())
}

/// Turns error answers made outside the handlers (405, 408, 413, 503 from layers) into
/// problem documents. A 413 says whether the body was refused up front for the length it
/// declared (before any of it, or any part of an upload, was read) and names the limit and
/// the setting that raises it.
async fn problem_for_bare_errors(
    State(body_limit): State<usize>,
    request: Request<Body>,
    next: axum::middleware::Next,
) -> Response<Body> {
    let declared =
        request.headers().get(header::CONTENT_LENGTH).and_then(|v| v.to_str().ok()).and_then(|v| v.parse::<u64>().ok());
    let response = next.run(request).await;
    let status = response.status();
    let is_problem =
        response.headers().get(header::CONTENT_TYPE).is_some_and(|v| v.as_bytes().starts_with(PROBLEM_JSON.as_bytes()));
    if !status.is_client_error() && !status.is_server_error() || is_problem {
        return response;
    }
    let detail = match status {
        StatusCode::METHOD_NOT_ALLOWED => "this route does not take that method".to_string(),
        StatusCode::PAYLOAD_TOO_LARGE => match declared {
            Some(length) if length > body_limit as u64 => format!(
                "the request declares a body of {length} bytes (Content-Length), more than the limit of {body_limit} bytes, so none of it was read; the service's --body-limit (DIEPLAN_BODY_LIMIT) raises it"
            ),
            _ => format!(
                "the request body grew past the limit of {body_limit} bytes; the service's --body-limit (DIEPLAN_BODY_LIMIT) raises it"
            ),
        },
        StatusCode::SERVICE_UNAVAILABLE | StatusCode::REQUEST_TIMEOUT => {
            "the request took longer than the configured timeout".to_string()
        }
        other => other.canonical_reason().unwrap_or("error").to_string(),
    };
    let mut problem = problem_response(&ApiError::Status { status, detail }.problem());
    for (name, value) in response.headers() {
        if name != header::CONTENT_TYPE && name != header::CONTENT_LENGTH {
            problem.headers_mut().insert(name.clone(), value.clone());
        }
    }
    problem
}

/// A started service.
pub struct RunningServer {
    pub addr: SocketAddr,
    pub state: AppState,
    stop: oneshot::Sender<()>,
    server: JoinHandle<Result<(), std::io::Error>>,
    retention: Option<JoinHandle<()>>,
}

impl RunningServer {
    /// Stops within the grace period: stops accepting requests, answers the clients
    /// waiting for a job at once (202 with `Location`: the job goes on), lets the other
    /// requests in flight finish, and interrupts running jobs, which are queued again
    /// without counting an attempt and resume at the next start.
    pub async fn stop(mut self) {
        let grace = Duration::from_secs(self.state.config.shutdown_grace_s);
        let deadline = tokio::time::Instant::now() + grace;
        self.state.jobs.begin_stop();
        let _ = self.stop.send(());
        if let Some(retention) = self.retention.take() {
            retention.abort();
        }
        let server = async {
            match tokio::time::timeout_at(deadline, &mut self.server).await {
                Ok(Ok(Err(e))) => tracing::error!(error = %e, "server stopped with an error"),
                Ok(Err(e)) => tracing::error!(error = %e, "server task failed"),
                Ok(Ok(Ok(()))) => {}
                Err(_) => {
                    tracing::warn!("requests still in flight at the end of the grace period were dropped");
                    self.server.abort();
                }
            }
        };
        tokio::join!(server, self.state.jobs.shutdown(grace));
        self.state.pool.close().await;
        tracing::info!("stopped");
    }
}

/// Opens the database, starts the workers and serves on the configured address
/// (port 0 picks a free one: see [`RunningServer::addr`]).
pub async fn start(config: Config) -> Result<RunningServer, StartError> {
    let pool = crate::service::store::open(&config.database)
        .await
        .map_err(|source| StartError::Database { path: config.database.to_string(), source })?;
    keys::install_environment_key(&pool, config.admin_key.as_ref().map(|s| s.0.as_str())).await?;
    let protected = keys::any_active(&pool)
        .await
        .map_err(|source| StartError::Database { path: config.database.to_string(), source })?;
    if !protected {
        if config.addr.ip().is_loopback() {
            tracing::warn!("no API key exists: the service is open to every user of this machine until one is made (`dieplan keys create --role admin --name NAME`, or POST /v1/keys)");
        } else if config.insecure_no_auth {
            tracing::warn!(addr = %config.addr, "no API key exists and --insecure-no-auth is set: the service is open to anyone who reaches it");
        } else {
            return Err(StartError::Unprotected { addr: config.addr });
        }
    }
    let retention = crate::service::retention::start(pool.clone(), config.job_retention_days);
    crate::service::jobs::summaries::start(pool.clone());
    let workers = config.worker_count();
    let jobs = JobQueue::start(
        pool.clone(),
        workers,
        config.job_time_limit(),
        config.job_lease(),
        config.stock_memory_bytes(),
    )
    .await
    .map_err(|source| StartError::Database { path: config.database.to_string(), source })?;
    let listener =
        TcpListener::bind(config.addr).await.map_err(|source| StartError::Bind { addr: config.addr, source })?;
    let addr = listener.local_addr().map_err(|source| StartError::Bind { addr: config.addr, source })?;
    let state = AppState { pool, jobs, config: Arc::new(config) };
    let app = router(state.clone());
    let (stop, stopped) = oneshot::channel::<()>();
    let server = tokio::spawn(async move {
        axum::serve(listener, app)
            .with_graceful_shutdown(async {
                let _ = stopped.await;
            })
            .await
    });
    tracing::info!(%addr, workers, "dieplan listening");
    Ok(RunningServer { addr, state, stop, server, retention })
}

/// Resolves on SIGTERM or ctrl-c.
pub async fn shutdown_signal() {
    let ctrl_c = async {
        let _ = tokio::signal::ctrl_c().await;
    };
    #[cfg(unix)]
    let terminate = async {
        match tokio::signal::unix::signal(tokio::signal::unix::SignalKind::terminate()) {
            Ok(mut s) => {
                s.recv().await;
            }
            Err(_) => std::future::pending::<()>().await,
        }
    };
    #[cfg(not(unix))]
    let terminate = std::future::pending::<()>();
    tokio::select! {
        _ = ctrl_c => {},
        _ = terminate => {},
    }
    tracing::info!("shutdown signal received");
}
