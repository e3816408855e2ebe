//! Drawings and charts of a job as SVG: the scene a finished job leaves
//! ([`scene::Scene`]), how a tool path is traced and simplified into it, and how it is
//! rendered. Pure: strings out, no I/O.

pub mod downsample;
pub mod palette;
pub mod scene;
pub mod svg;
pub mod ticks;
pub mod trace;
