//! Drawings and charts of a job as SVG: the scene a finished job leaves
//! ([`scene::Scene`]), how a tool path is traced and simplified into it
//! ([`trace::trace_path`]), and how it is rendered ([`plan_view::render_drawing`],
//! [`chart::render_chart`]). Pure: strings out, no I/O.

pub mod analysis_scene;
mod bar_chart;
pub mod chart;
pub mod charts;
pub mod costing_scene;
pub mod display_units;
pub mod downsample;
pub mod draw_options;
pub mod feeds_scene;
pub mod frame;
pub mod frame_axes;
pub mod insertion_scene;
pub mod labels;
pub mod legend;
pub mod medial;
pub mod outlines;
pub mod palette;
pub mod paths;
pub mod plan_view;
pub mod process_scene;
pub mod regions;
pub mod scene;
pub mod svg;
pub mod synthetic;
pub mod ticks;
pub mod trace;
pub mod trochoid_marks;

#[cfg(test)]
mod golden_tests;
