//! Feed optimisation building blocks (seed 000; seeds 001–003; MODEL.md §3 and §4): the
//! feed at the tool centre that holds the feed at the cutting point constant, the feed
//! that holds the cutting force constant, and the limit on how fast the feed may change.

pub mod constant_force;
pub mod cutting_point;
pub mod rate_limit;
