//! The service: configuration, HTTP routes, the store and the job queue. Handlers are
//! thin: parse, call the core or the store, map the answer.

pub mod app;
pub mod auth;
pub mod config;
pub mod error;
pub mod etag;
pub mod examples;
pub mod extract;
pub mod force_fit;
pub mod health;
pub mod hosts;
pub mod job_schema;
pub mod jobs;
pub mod keys;
pub mod lookup;
pub mod openapi;
pub mod parameter_docs;
pub mod rate_limit;
pub mod reasons;
pub mod request_fields;
pub mod resources;
pub mod retention;
pub mod schemas;
pub mod security_docs;
pub mod state;
pub mod status_docs;
pub mod store;
pub mod web;
