//! The machine's limits and the estimator's options (MODEL.md §10: "a kinematic estimate with
//! the machine's acceleration (and jerk) limits, per axis").

use crate::core::error::{require_finite, require_positive, CoreError};
use serde::{Deserialize, Serialize};

/// Blocks the control reads ahead (**assumed**: the 200-block look-ahead of FANUC's AI contour
/// control II; LinuxCNC's default queue is of the same order). Sets [`TimeOptions::look_ahead_blocks`].
pub const DEFAULT_LOOK_AHEAD_BLOCKS: usize = 200;

/// How far the tool may deviate from a sharp corner, mm (**assumed**: GRBL's default
/// `$11 = 0.010 mm`, which Marlin's junction deviation also uses). Sets the corner speed
/// through the junction-deviation formula (see `junction.rs`).
pub const DEFAULT_JUNCTION_DEVIATION_MM: f64 = 0.01;

/// Velocity, acceleration and jerk limits of a machining centre and its tool-change time
/// (the service fills it from a `/v1/machines` row).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct MachineLimits {
    /// G0 rate, mm/min (along the path: see the module's assumptions).
    pub rapid_mm_min: f64,
    /// Highest programmable feed, mm/min; feeds above it are clamped.
    pub max_feed_mm_min: f64,
    /// Acceleration limit of each axis (X, Y, Z), mm/s² (the row's `accel_{x,y,z}_mm_s2`).
    pub accel_mm_s2: [f64; 3],
    /// Jerk limit of each axis (X, Y, Z), mm/s³ (the row's `jerk_{x,y,z}_mm_s3`).
    pub jerk_mm_s3: [f64; 3],
    /// Time of one tool change (M6), s; 0 allowed.
    pub tool_change_s: f64,
}

impl MachineLimits {
    /// The seeded OKK VM-4 row (`migrations/0002_seed.sql`, `assumed` values): the machine
    /// the tests and benchmarks time programs on without a database.
    pub const SEEDED_OKK_VM4: MachineLimits = MachineLimits {
        rapid_mm_min: 20000.0,
        max_feed_mm_min: 15000.0,
        accel_mm_s2: [2000.0, 2000.0, 1500.0],
        jerk_mm_s3: [50000.0, 50000.0, 40000.0],
        tool_change_s: 8.0,
    };

    /// Checks that every limit is finite and positive (the tool-change time may be 0). Field
    /// names are those of the machine row (`accel_x_mm_s2`…), so the service can point at them.
    pub fn validate(&self) -> Result<(), CoreError> {
        require_positive("rapid_mm_min", self.rapid_mm_min)?;
        require_positive("max_feed_mm_min", self.max_feed_mm_min)?;
        for (axis, (&accel, &jerk)) in ["x", "y", "z"].iter().zip(self.accel_mm_s2.iter().zip(&self.jerk_mm_s3)) {
            require_positive(&format!("accel_{axis}_mm_s2"), accel)?;
            require_positive(&format!("jerk_{axis}_mm_s3"), jerk)?;
        }
        require_finite("tool_change_s", self.tool_change_s)?;
        if self.tool_change_s < 0.0 {
            return Err(CoreError::invalid("tool_change_s", format!("must be >= 0, got {}", self.tool_change_s)));
        }
        Ok(())
    }
}

/// How the kinematic estimate models the control.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct TimeOptions {
    /// Moves the control plans ahead: it must always be able to stop at the end of what it
    /// has read. `None`: the whole program (an ideal control). Default
    /// [`DEFAULT_LOOK_AHEAD_BLOCKS`].
    pub look_ahead_blocks: Option<usize>,
    /// Corner tolerance of the junction-deviation rule, mm; 0 stops at every corner.
    /// Default [`DEFAULT_JUNCTION_DEVIATION_MM`].
    pub junction_deviation_mm: f64,
    /// The machine stops before and after every rapid (G0), as FANUC controls do by default
    /// (in-position check at the end of a positioning block). `false`: rapids blend into
    /// neighbouring moves like feed moves do. Default `true`.
    pub exact_stop_at_rapids: bool,
    /// Also return the kinematic time of every move ([`MachiningTime::per_move_s`](super::MachiningTime)).
    pub per_move: bool,
}

impl Default for TimeOptions {
    fn default() -> Self {
        TimeOptions {
            look_ahead_blocks: Some(DEFAULT_LOOK_AHEAD_BLOCKS),
            junction_deviation_mm: DEFAULT_JUNCTION_DEVIATION_MM,
            exact_stop_at_rapids: true,
            per_move: false,
        }
    }
}

impl TimeOptions {
    /// Checks the look-ahead (at least one block) and the corner tolerance (finite, ≥ 0).
    pub fn validate(&self) -> Result<(), CoreError> {
        if self.look_ahead_blocks == Some(0) {
            return Err(CoreError::invalid("look_ahead_blocks", "must be at least 1 (or null for the whole program)"));
        }
        require_finite("junction_deviation_mm", self.junction_deviation_mm)?;
        if self.junction_deviation_mm < 0.0 {
            return Err(CoreError::invalid(
                "junction_deviation_mm",
                format!("must be >= 0, got {}", self.junction_deviation_mm),
            ));
        }
        Ok(())
    }
}
