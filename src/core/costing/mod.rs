//! Process costing (seed 002 subsystems (e) tool life and (f) time and cost; MODEL.md §9
//! and §10): the tool life a path consumes and where, and the cost of machining it.

pub mod calibration;
pub mod cost;
pub mod estimate;
pub mod wear;
