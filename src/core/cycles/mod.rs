//! Fixed cycles as move generators (seed 002 §2.2.3 and Fig. 2–3; seed 004 §2.2–2.3 and
//! Table 1; MODEL.md §7–8): trochoids along a guide, trochoidal slot grooving, helical
//! boring, spiral hole expansion, corner milling and z-cut division.
//!
//! Every generator is a pure function returning a [`Cycle`]: continuous moves with true arcs
//! in XY (helices with z motion and `turns`), feeds `F = fz·z·S` from the operation's
//! cutting conditions, `line` = the 1-based index of the move, and a [`CycleReport`].
//! Cuts are climb cuts with an M3 spindle unless the request says otherwise (see
//! [`CutDirection`]).

pub mod arcs;
pub mod corner;
pub mod guide;
pub mod helical_boring;
pub mod levels;
pub mod report;
pub mod setup;
pub mod slot;
pub mod spiral;
pub mod trochoid;

#[cfg(test)]
pub(crate) mod test_support;

pub use corner::{corner_milling, corner_step_radii, max_concave_rd_mm, CornerParams};
pub use guide::Guide;
pub use helical_boring::{helical_boring, HelicalBoringParams};
pub use levels::{z_levels, DEFAULT_ZCUT_AD_MM};
pub use report::{Cycle, CycleReport};
pub use setup::{CutDirection, CycleSetup};
pub use slot::{trochoidal_slot, SlotParams};
pub use spiral::{spiral_hole_expansion, SpiralParams};
pub use trochoid::{trochoid_along, Entry, LoopRadius, TrochoidParams, DEFAULT_RADIUS_RATIO};
