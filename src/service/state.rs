//! What every handler can reach.

use crate::service::config::Config;
use crate::service::jobs::queue::JobQueue;
use crate::service::store::Pool;
use std::sync::Arc;

/// Shared application state.
#[derive(Clone)]
pub struct AppState {
    pub pool: Pool,
    pub jobs: JobQueue,
    pub config: Arc<Config>,
}
