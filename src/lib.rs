//! dieplan: plans the milling of dies and molds in hardened steel.
//!
//! Two worlds: [`core`] (pure planning code: geometry, models, planners) and
//! [`service`] (HTTP, database, jobs) which calls into it.

pub mod core;
pub mod service;
