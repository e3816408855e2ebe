//! Planning work as persistent jobs: a table, a pool of workers that run the core off
//! the async runtime, and the routes that create, poll, list and cancel them.

pub mod analysis;
pub mod analysis_result;
pub mod conditions;
pub mod control;
pub mod costing;
pub mod costing_result;
pub mod drawings;
pub mod execution;
pub mod feed_limits;
pub mod feeds;
pub mod feeds_result;
pub mod inputs;
pub mod kept_stock;
pub mod kind;
pub mod kinds;
pub mod labels;
pub mod lane;
pub mod lease;
pub mod model;
pub mod notify;
pub mod output;
pub mod path_trace;
pub mod plan_rows;
pub mod plan_tools;
pub mod plans;
pub mod plans_result;
pub mod program_input;
pub mod queue;
pub mod routes;
pub mod setup;
pub mod store;
pub mod summaries;
pub mod trochoids;
pub mod trochoids_result;
pub mod upload;
