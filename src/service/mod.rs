//! The service: configuration, HTTP routes, the store and the job queue. Handlers are
//! thin: parse, call the core or the store, map the answer.

pub mod app;
pub mod config;
pub mod error;
pub mod examples;
pub mod extract;
pub mod force_fit;
pub mod health;
pub mod jobs;
pub mod lookup;
pub mod openapi;
pub mod resources;
pub mod schemas;
pub mod state;
pub mod store;
pub mod web;
