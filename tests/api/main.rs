//! API tests: each starts the real application on port 0 with a temporary database.
//! One test binary, so CI links once.

mod analysis;
mod architecture;
mod ball_tools;
mod browser;
mod common;
mod concurrency;
mod conditions;
mod costing;
mod curl_examples;
mod database;
mod drawings;
mod errors;
mod fair_queue;
mod feeds;
mod fit;
mod job_blobs;
mod jobs;
mod keys;
mod nc_programs;
mod openapi;
mod plans;
mod postgres;
mod postgres_backend;
mod postgres_seed;
mod programs;
mod rate_limits;
mod recalibration;
mod replicas;
mod restarts;
mod retention;
mod schemathesis;
mod tool_defaults;
mod trochoids;
mod validation;
mod web;
