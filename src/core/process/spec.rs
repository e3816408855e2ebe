//! What the process planner is given: the candidate tools with their data from the
//! cutting-condition database, and the job's options (seed 002 §2.6, MODEL.md §8–10).

use crate::core::conditions::CuttingConditions;
use crate::core::error::{require_finite, require_positive};
use crate::core::force_model::ForceModel;
use crate::core::kinematics::MachineLimits;
use crate::core::tool::{EndMill, ToolType};
use crate::core::tool_life::ToolLifeModel;
use crate::core::CoreError;

/// The share of one tool's life the tuned conditions aim to use over the job (seed 002 §2.6:
/// "about 90 %").
pub const DEFAULT_TARGET_CONSUMPTION: f64 = 0.9;

/// The tuning stops within this much of the target consumption.
pub const CONSUMPTION_TOLERANCE: f64 = 0.02;

/// Highest target force of the tuned conditions, as a multiple of the standard force F*
/// (**assumed**: twice the standard force, as the feed is limited to twice the standard feed).
pub const DEFAULT_MAX_FORCE_FACTOR: f64 = 2.0;

/// One end mill the planner may choose, with everything the database knows of it.
#[derive(Debug, Clone, PartialEq)]
pub struct ToolCandidate {
    /// How the tool is called in the reports (e.g. the database's name).
    pub name: String,
    pub tool: EndMill,
    /// Rough side cutting (seed 004 Table 2, step 4): S, fz, Rd and the layer depth Ad.
    pub roughing: CuttingConditions,
    /// Intermediate-rough side cutting of the last layer (step 9).
    pub intermediate: CuttingConditions,
    /// Trochoidal grooving, spiral hole expansion and the helical entries (steps 1–3).
    pub grooving: CuttingConditions,
    /// The cutting-force model for the constant-force feeds (MODEL.md §3).
    pub force_model: ForceModel,
    /// F*: the force at the standard straight cut, N.
    pub standard_force_n: f64,
    /// Tool life (MODEL.md §9).
    pub life: ToolLifeModel,
    /// Feed limits of the constant-force optimisation, mm/min.
    pub min_feed_mm_min: f64,
    pub max_feed_mm_min: f64,
    /// c_t: the price of one tool.
    pub tool_price: f64,
}

impl ToolCandidate {
    /// Checks every value, and that the tool is a flat end mill; errors name the candidate.
    pub fn validate(&self) -> Result<(), CoreError> {
        self.validate_in(&format!("candidates.{}", self.name), true)
    }

    /// Checks every value (with `flat`, also that the tool is a flat end mill); errors name
    /// their field under `prefix`.
    pub fn validate_in(&self, prefix: &str, flat: bool) -> Result<(), CoreError> {
        let named = |e: CoreError| match e {
            CoreError::InvalidInput { field, reason } => CoreError::invalid(format!("{prefix}.{field}"), reason),
            other => other,
        };
        (|| {
            if flat && matches!(self.tool.tool_type, ToolType::Ball) {
                return Err(CoreError::invalid("tool", "the proposed strategy needs a flat end mill, not a ball"));
            }
            require_positive("diameter_mm", self.tool.diameter_mm)?;
            self.roughing.validate()?;
            self.intermediate.validate()?;
            self.grooving.validate()?;
            require_positive("standard_force_n", self.standard_force_n)?;
            self.life.validate()?;
            require_positive("min_feed_mm_min", self.min_feed_mm_min)?;
            if require_positive("max_feed_mm_min", self.max_feed_mm_min)? < self.min_feed_mm_min {
                return Err(CoreError::invalid("max_feed_mm_min", "must be at least the minimum feed"));
            }
            if !(self.tool_price.is_finite() && self.tool_price >= 0.0) {
                return Err(CoreError::invalid("tool_price", "must be a finite number ≥ 0"));
            }
            Ok(())
        })()
        .map_err(named)
    }
}

/// The job's options besides the cavity and the candidates.
#[derive(Debug, Clone, PartialEq)]
pub struct ProcessOptions {
    /// Engagement limit of the critical regions, deg.
    pub alpha_limit_deg: f64,
    /// Stock left on the walls for finishing, mm.
    pub allowance_mm: f64,
    /// Height of the moves over the workpiece, mm.
    pub safe_z_mm: f64,
    /// Simulation sample spacing, mm (`None`: the analysis's default).
    pub sample_spacing_mm: Option<f64>,
    /// The machine's rapid rate and kinematic limits.
    pub machine: MachineLimits,
    /// c_m: machine and operator per hour.
    pub machine_rate_per_hour: f64,
    pub currency: String,
    /// Tune the chosen tool's conditions to use this share of its life (0 < x ≤ 1).
    pub target_consumption: f64,
    /// `false`: keep the chosen tool at the standard force.
    pub tune: bool,
    /// Highest target force of the tuning, times F*.
    pub max_force_factor: f64,
    /// Limit on the change of feed along the path, mm/min per mm (`None`: no limit).
    pub max_feed_change_per_mm: Option<f64>,
    /// Memory each simulation of the plan's stock may take, bytes (see
    /// [`crate::core::analysis::budget`]).
    pub stock_memory_bytes: usize,
}

impl ProcessOptions {
    pub fn validate(&self) -> Result<(), CoreError> {
        require_positive("alpha_limit_deg", self.alpha_limit_deg)?;
        if require_finite("allowance_mm", self.allowance_mm)? < 0.0 {
            return Err(CoreError::invalid("allowance_mm", "must be ≥ 0"));
        }
        require_finite("safe_z", self.safe_z_mm)?;
        if let Some(s) = self.sample_spacing_mm {
            require_positive("sample_spacing_mm", s)?;
        }
        self.machine.validate()?;
        if !(self.machine_rate_per_hour.is_finite() && self.machine_rate_per_hour >= 0.0) {
            return Err(CoreError::invalid("machine_rate_per_hour", "must be a finite number ≥ 0"));
        }
        let t = require_positive("target_consumption", self.target_consumption)?;
        if t > 1.0 {
            return Err(CoreError::invalid("target_consumption", format!("must be at most 1 (one tool), got {t}")));
        }
        if require_positive("max_force_factor", self.max_force_factor)? < 1.0 {
            return Err(CoreError::invalid("max_force_factor", "must be at least 1 (the standard force)"));
        }
        if let Some(r) = self.max_feed_change_per_mm {
            require_positive("max_feed_change_per_mm", r)?;
        }
        Ok(())
    }
}
