//! The planning core: geometry, cutting models and planners as pure functions on plain data.
//!
//! Nothing in here knows about HTTP, SQL, async runtimes or OpenAPI; a test
//! (`core_is_pure` in `tests/architecture.rs`) fails if a file under `src/core/` names them.

pub mod analysis;
pub mod conditions;
/// The coolant a program switches on.
pub mod coolant;
pub mod costing;
pub mod curvature;
pub mod cycles;
/// Drawings and charts of a job as SVG.
pub mod drawing;
pub mod engagement;
pub mod error;
pub mod feed;
#[cfg(test)]
pub(crate) mod fixtures;
pub mod force_fit;
pub mod force_model;
pub mod geometry;
#[cfg(test)]
pub(crate) mod golden;
/// Trochoid insertion into contour-parallel paths (seed 004 §2).
pub mod insertion;
pub mod kinematics;
/// The medial axis of a pocket and its radius-ratio classes (seed 004 §2.1, §2.3).
pub mod medial;
pub mod nc;
pub mod operation;
pub mod pocketing;
/// Process planning of a cavity: tool choice, layers, feeds, cost, tuning (seed 002 §2.6).
pub mod process;
pub mod progress;
pub mod standard_cut;
pub mod stock;
pub mod tolerance;
pub mod tool;
pub mod tool_life;
pub mod toolpath;
pub mod zero_crossing;

pub use error::CoreError;
