//! What [`machining_time`](super::machining_time) returns.

use serde::Serialize;
use utoipa::ToSchema;

/// Machining time of a tool path, nominal and kinematic (MODEL.md §10, seed 002 §2.6 Eq. 4's
/// `T_m`), min.
#[derive(Debug, Clone, PartialEq, Serialize, ToSchema)]
pub struct MachiningTime {
    /// Feed moves at their programmed feeds, rapids at the rapid rate, tool changes and dwells:
    /// the papers' prediction.
    pub nominal_min: f64,
    /// With the machine's speed, acceleration and jerk limits; never below `nominal_min`.
    pub kinematic_min: f64,
    /// `kinematic_min / nominal_min` (1 for an empty program).
    pub kinematic_ratio: f64,
    pub feed_nominal_min: f64,
    pub rapid_nominal_min: f64,
    /// Feed moves (lines and arcs) with the kinematic model.
    pub feed_kinematic_min: f64,
    /// Rapids with the kinematic model.
    pub rapid_kinematic_min: f64,
    pub feed_length_mm: f64,
    pub rapid_length_mm: f64,
    /// M6 tool changes and their time.
    pub tool_changes: usize,
    pub tool_change_min: f64,
    /// G4 dwells (in both totals).
    pub dwell_min: f64,
    /// Where the kinematic time beyond the nominal goes (`lost_to_…`).
    #[serde(flatten)]
    pub breakdown: KinematicBreakdown,
    /// Kinematic time of every move, s (index = move index; 0 for a move of no length);
    /// only when [`TimeOptions::per_move`](super::TimeOptions) is set.
    #[serde(skip)]
    pub per_move_s: Option<Vec<f32>>,
    /// Reported with the warnings of the job that timed the path.
    #[serde(skip)]
    pub warnings: Vec<String>,
}

/// `kinematic_min − nominal_min`, by cause (min); the four parts add up to it.
#[derive(Debug, Clone, PartialEq, Default, Serialize, ToSchema)]
pub struct KinematicBreakdown {
    /// Feeds programmed above the machine's maximum feed, run at the maximum.
    #[serde(rename = "lost_to_feed_clamp_min")]
    pub feed_clamp_min: f64,
    /// Arcs run below their feed by the centripetal acceleration and jerk limits.
    #[serde(rename = "lost_to_arc_limits_min")]
    pub arc_limit_min: f64,
    /// Speeding up and slowing down at the acceleration limits: stops, corners, dense
    /// polylines and small loops, look-ahead.
    #[serde(rename = "lost_to_acceleration_min")]
    pub acceleration_min: f64,
    /// The jerk limits' lengthening of those speed changes (S-curves).
    #[serde(rename = "lost_to_jerk_min")]
    pub jerk_min: f64,
    /// Junctions whose change of direction forces a speed below both moves' speeds.
    pub slowed_corners: usize,
    /// Junctions where the machine stops: tool changes, dwells, M codes, rapids (with
    /// `exact_stop_at_rapids`), discontinuities.
    pub exact_stops: usize,
}
