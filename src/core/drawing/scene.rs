//! What a finished job leaves to be drawn: outlines, tool paths with values along them,
//! the medial axis, critical regions, trochoid spans and chart data. Built once when a
//! job finishes (already simplified for drawing), stored with the job, and rendered to
//! SVG on request by [`super::plan_view`] and [`super::chart`].

use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// A quantity a tool path can be coloured by.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Quantity {
    /// Engagement angle α, deg.
    Alpha,
    /// Feed, mm/min.
    Feed,
    /// Predicted force F_xy, N.
    Force,
    /// Tool-life consumption per metre of path, % of one tool's life per m.
    Wear,
}

impl Quantity {
    pub const ALL: [Quantity; 4] = [Quantity::Alpha, Quantity::Feed, Quantity::Force, Quantity::Wear];

    /// The name used in URLs and JSON.
    pub fn as_str(self) -> &'static str {
        match self {
            Quantity::Alpha => "alpha",
            Quantity::Feed => "feed",
            Quantity::Force => "force",
            Quantity::Wear => "wear",
        }
    }

    pub fn parse(text: &str) -> Option<Quantity> {
        Quantity::ALL.into_iter().find(|q| q.as_str() == text)
    }

    /// Legend caption with the unit.
    pub fn caption(self) -> &'static str {
        match self {
            Quantity::Alpha => "engagement α, deg",
            Quantity::Feed => "feed, mm/min",
            Quantity::Force => "predicted force F_xy, N",
            Quantity::Wear => "tool-life consumption, % of a tool per m",
        }
    }
}

/// What a closed outline is.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum OutlineRole {
    /// The stock's boundary (material at the start).
    Stock,
    /// A pocket's boundary: the wall the tool must not cross.
    Pocket,
    /// An island inside a pocket.
    Island,
    /// A region already open at the start (a pre-drilled hole, a previous layer).
    Open,
}

/// A closed polygon (the last point joins the first), mm.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Outline {
    pub role: OutlineRole,
    pub points: Vec<[f64; 2]>,
}

/// A layer (z range) of the job.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct LayerInfo {
    pub name: String,
    pub z_top: f64,
    pub z_bottom: f64,
}

/// A stretch of path drawn in one style: rapid or feed, in one layer.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Run {
    /// Index into [`Scene::layers`]; `None` when the run is not in one layer (a rapid
    /// between layers, or a job without layers).
    pub layer: Option<usize>,
    pub rapid: bool,
    /// Vertices, mm.
    pub points: Vec<[f64; 2]>,
    /// Per quantity, one value per vertex (the value of the stretch that ends there;
    /// the first vertex repeats the second's). `NaN` never appears: a vertex without a
    /// value (air, rapid) is stored as `null` and drawn in the "no value" colour.
    pub values: BTreeMap<Quantity, Vec<Option<f32>>>,
    /// Per vertex, the tool's height, mm (empty in scenes stored before it was kept).
    #[serde(default)]
    pub z: Vec<f32>,
    /// Per vertex, the NC line (or move number) of the move it ends (empty likewise).
    #[serde(default)]
    pub lines: Vec<u32>,
    /// Per vertex, its path distance, mm: the x of the job's charts (empty likewise).
    #[serde(default)]
    pub s_mm: Vec<f64>,
}

/// A named tool path ("input", "planned", …).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ScenePath {
    pub name: String,
    pub runs: Vec<Run>,
    /// The finest detail the runs keep, mm: the tolerance they were traced to (the path
    /// is within it everywhere). A drawing can be zoomed until it spans a few px, no
    /// further. `None` in scenes stored before it was kept.
    #[serde(default)]
    pub detail_mm: Option<f64>,
}

/// The class of a medial-axis stretch by R/r (seed 004 §2.3, Figure 6).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum MedialClass {
    /// R/r ≥ a: contour-parallel paths.
    A,
    /// 1.1 ≤ R/r < a: trochoidal grooving.
    B,
    /// R/r < 1.1: z-cut division.
    C,
}

/// A stretch of the medial axis in one class: a polyline with its clearance radius
/// range R, mm.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct MedialEdge {
    pub class: MedialClass,
    pub layer: Option<usize>,
    pub points: Vec<[f64; 2]>,
    pub min_radius_mm: f64,
    pub max_radius_mm: f64,
}

/// A critical region of a path (engagement above the limit).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RegionMark {
    /// `full_slotting`, `inner_corner`, `narrow_region`.
    pub kind: String,
    /// Name of the path it belongs to.
    pub path: String,
    pub layer: Option<usize>,
    /// The stretch of path, simplified, mm.
    pub points: Vec<[f64; 2]>,
    pub max_alpha_deg: f64,
    pub start_line: u32,
    pub end_line: u32,
}

/// Where trochoid cycles were inserted.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct TrochoidMark {
    pub layer: Option<usize>,
    /// The base path the loops follow, mm.
    pub points: Vec<[f64; 2]>,
    /// Loop radius ρ, mm.
    pub loop_radius_mm: f64,
    /// Smallest pitch of the loops, mm (null in scenes stored before it was kept).
    #[serde(default)]
    pub pitch_mm: Option<f64>,
    /// The path whose moves make the loops: only its drawing clusters dense spans (the
    /// others show the spans under their own path).
    #[serde(default)]
    pub path: Option<String>,
}

/// One line of a line chart.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct LineSeries {
    pub name: String,
    pub x: Vec<f64>,
    /// `None`: a gap.
    pub y: Vec<Option<f64>>,
}

/// A quantity against path distance (or anything against anything).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct LineChart {
    pub x_label: String,
    pub y_label: String,
    pub series: Vec<LineSeries>,
    /// Horizontal reference lines (e.g. the α limit), with captions.
    pub limits: Vec<(String, f64)>,
}

/// One group of bars (one colour), a value per category.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct BarGroup {
    pub name: String,
    pub values: Vec<Option<f64>>,
}

/// Categories (operations, candidate tools) with one bar per group.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct BarChart {
    pub y_label: String,
    pub categories: Vec<String>,
    pub groups: Vec<BarGroup>,
    /// A note under each category (e.g. "chosen", "cannot reach"); may be empty.
    pub notes: Vec<String>,
    /// Index of the category to highlight (e.g. the chosen tool).
    pub highlight: Option<usize>,
}

/// What a chart shows.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case", tag = "type")]
pub enum ChartBody {
    Lines(LineChart),
    Bars(BarChart),
}

/// A chart of a job.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ChartData {
    /// URL name, e.g. `alpha`, `force`, `feed`, `time`, `cost`, `candidates`.
    pub id: String,
    pub title: String,
    pub body: ChartBody,
}

/// Everything a job leaves to be drawn.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct Scene {
    pub title: String,
    pub tool_diameter_mm: Option<f64>,
    pub alpha_limit_deg: Option<f64>,
    pub outlines: Vec<Outline>,
    pub layers: Vec<LayerInfo>,
    pub paths: Vec<ScenePath>,
    pub medial: Vec<MedialEdge>,
    pub regions: Vec<RegionMark>,
    pub trochoids: Vec<TrochoidMark>,
    pub charts: Vec<ChartData>,
}

impl Scene {
    /// Quantities some run of `path` carries.
    pub fn quantities(&self, path: &str) -> Vec<Quantity> {
        let mut found: Vec<Quantity> = self
            .paths
            .iter()
            .filter(|p| p.name == path)
            .flat_map(|p| p.runs.iter().flat_map(|r| r.values.keys().copied()))
            .collect();
        found.sort();
        found.dedup();
        found
    }

    /// The finest detail any path keeps, mm (`None`: no path says).
    pub fn detail_mm(&self) -> Option<f64> {
        self.paths.iter().filter_map(|p| p.detail_mm).reduce(f64::min)
    }

    /// Renames the NC lines of the critical regions of path `name`: `to` maps a line they
    /// were found on (a line of the program the path was edited from) to the line of the
    /// program that is served for the path.
    pub fn relabel_regions(&mut self, name: &str, to: impl Fn(u32) -> u32) {
        for region in self.regions.iter_mut().filter(|r| r.path == name) {
            region.start_line = to(region.start_line);
            region.end_line = to(region.end_line);
        }
    }

    pub fn chart(&self, id: &str) -> Option<&ChartData> {
        self.charts.iter().find(|c| c.id == id)
    }
}
