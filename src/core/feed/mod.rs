//! Feed optimisation (seed 000; seeds 001–003; seed 002 subsystem (d); MODEL.md §3 and
//! §4): the feed at the tool centre that holds the feed at the cutting point constant,
//! the feed that holds the cutting force constant, the limit on how fast the feed may
//! change, one feed per NC block, and the whole path's optimisation with its figures.

pub mod blocks;
pub mod collect;
pub mod constant_force;
pub mod costed;
pub mod cutting_point;
pub mod edit;
pub mod guarantee;
pub mod objective;
pub mod plan;
pub mod rate_limit;
pub mod rule;
pub mod settle;
pub mod split;
pub mod surface;

#[cfg(test)]
mod costed_tests;
#[cfg(test)]
mod objective_tests;
#[cfg(test)]
mod plan_tests;
#[cfg(test)]
mod settle_tests;
