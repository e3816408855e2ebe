//! What the trochoid-insertion planner is asked to do: the tool, its conditions, the layer,
//! the limits and the strategy choices, with their defaults (seed 004 §2, MODEL.md §7–8).

use crate::core::conditions::CuttingConditions;
use crate::core::cycles::arcs::helix_turns;
use crate::core::cycles::levels::{level_count, MAX_LEVELS};
use crate::core::cycles::{CutDirection, DEFAULT_ZCUT_AD_MM};
use crate::core::error::{require_finite, require_positive};
use crate::core::insertion::pitch::MIN_PITCH_MM;
use crate::core::medial::{CLASS_A_RATIO_DEFAULT, CLASS_A_RATIO_MAX, CLASS_A_RATIO_MIN};
use crate::core::tolerance::LENGTH_EPS_MM;
use crate::core::tool::{EndMill, ToolType};
use crate::core::toolpath::Step;
use crate::core::CoreError;

/// Default engagement limit, deg: a critical cutting region is where α exceeds it
/// (MODEL.md §6; seed 004 Figure 10).
pub const DEFAULT_INSERTION_ALPHA_LIMIT_DEG: f64 = 40.0;

/// The trochoid pitch is designed for the limit less this margin, deg, so that the
/// simulation (which differs from the design model by the sampling) stays under the limit.
pub const PITCH_DESIGN_MARGIN_DEG: f64 = 1.0;

/// Default gap left between a trochoid loop's reach and the wall beyond the allowance, mm:
/// keeps the loops off the finished surface, which the contour-parallel path finishes.
pub const DEFAULT_WALL_GAP_MM: f64 = 0.05;

/// Angle of the helical entries when no pitch is given, deg (**assumed**: a shallow ramp, the
/// common recommendation for solid carbide in hardened steel; the papers enter by helical
/// boring with a ball end mill).
pub const DEFAULT_RAMP_ANGLE_DEG: f64 = 3.0;

/// The air feed, when none is given, as a multiple of the grooving feed (**assumed**: the
/// largest feed the plans' and the feeds jobs' optimisers allow by default, twice the
/// standard feed; the papers move through cleared space at the cutting feed).
pub const DEFAULT_AIR_FEED_PER_GROOVING_FEED: f64 = 2.0;

/// Smallest default helix pitch, mm: a small circle would otherwise take hundreds of turns.
pub const MIN_DEFAULT_RAMP_PITCH_MM: f64 = 0.1;

/// How large the trochoid loops are.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub enum LoopSize {
    /// Variable radius `ρ(s) = R(s) − r − allowance − gap` (seed 004 Figure 5), at most
    /// `(a − 1)·r` with `a` the class-A ratio, so that a loop always sweeps its whole disc.
    #[default]
    Variable,
    /// A fixed radius (seed 004 Figure 4: `(ρ + r)/r = 1.2`), reduced where the clearance
    /// does not leave room for it.
    Fixed { rho_mm: f64 },
}

/// The planner's input besides the pocket and the path.
#[derive(Debug, Clone, PartialEq)]
pub struct InsertionSpec {
    /// A flat end mill (square, or radius: simulated as its cylinder).
    pub tool: EndMill,
    /// Rough side cutting (MODEL.md §8 step 4): S, fz, Rd (the step-over of the generated
    /// contour-parallel path) and Ad (the layer depth).
    pub roughing: CuttingConditions,
    /// Trochoidal grooving (seed 004 Table 1): S, fz and Rd (the default pitch).
    pub grooving: CuttingConditions,
    /// Top and bottom of the material to remove, mm.
    pub z_top_mm: f64,
    pub z_bottom_mm: f64,
    /// Height for moves over the material, mm (above `z_top_mm`).
    pub safe_z_mm: f64,
    /// Stock left on walls and islands, mm.
    pub allowance_mm: f64,
    /// Engagement limit, deg.
    pub alpha_limit_deg: f64,
    /// Lower bound of class A's R/r (2–3).
    pub class_a_ratio: f64,
    pub loop_size: LoopSize,
    /// Largest trochoid pitch, mm; default none but the engagement limit's (see
    /// [`InsertionSpec::max_pitch_mm`]).
    pub pitch_mm: Option<f64>,
    /// Feed of the moves that cut nothing (the return halves of the trochoid loops, links
    /// through cleared space), mm/min; default [`DEFAULT_AIR_FEED_PER_GROOVING_FEED`] × the
    /// grooving feed.
    pub air_feed_mm_min: Option<f64>,
    /// Axial depth of the z-cut division passes, mm.
    pub zcut_ad_mm: f64,
    /// Depth per turn of the helical entry of a trochoid, mm; default a
    /// [`DEFAULT_RAMP_ANGLE_DEG`] ramp.
    pub ramp_pitch_mm: Option<f64>,
    pub direction: CutDirection,
    /// Rapid rate (for the choice between feeding through cleared material and hopping).
    pub rapid_mm_min: f64,
    /// Spacing of the simulation samples, mm (default the analysis's).
    pub sample_spacing_mm: Option<f64>,
    /// Raster cell of the simulation, mm (default the analysis's).
    pub cell_mm: Option<f64>,
    /// Gap between the trochoids' reach and the wall beyond the allowance, mm.
    pub wall_gap_mm: f64,
    /// The step the contour-parallel path makes, for the program's section labels: rough
    /// side cutting, or intermediate-rough on the last layer of a process plan.
    pub base_step: Step,
    /// Memory each simulation of the stock may take, bytes (default the analysis's).
    pub stock_memory_bytes: usize,
}

impl InsertionSpec {
    /// A spec with the defaults of seed 004 for `tool` and its conditions.
    pub fn new(
        tool: EndMill,
        roughing: CuttingConditions,
        grooving: CuttingConditions,
        z_top_mm: f64,
        z_bottom_mm: f64,
    ) -> Self {
        InsertionSpec {
            tool,
            roughing,
            grooving,
            z_top_mm,
            z_bottom_mm,
            safe_z_mm: z_top_mm + 5.0,
            allowance_mm: 0.0,
            alpha_limit_deg: DEFAULT_INSERTION_ALPHA_LIMIT_DEG,
            class_a_ratio: CLASS_A_RATIO_DEFAULT,
            loop_size: LoopSize::Variable,
            pitch_mm: None,
            air_feed_mm_min: None,
            zcut_ad_mm: DEFAULT_ZCUT_AD_MM,
            ramp_pitch_mm: None,
            direction: CutDirection::Climb,
            rapid_mm_min: crate::core::cycles::setup::DEFAULT_RAPID_MM_MIN,
            sample_spacing_mm: None,
            cell_mm: None,
            wall_gap_mm: DEFAULT_WALL_GAP_MM,
            base_step: Step::RoughSideCutting,
            stock_memory_bytes: crate::core::analysis::DEFAULT_STOCK_MEMORY_BYTES,
        }
    }

    /// Tool radius r, mm.
    pub fn r_mm(&self) -> f64 {
        self.tool.radius_mm()
    }

    /// The largest trochoid pitch, mm: the request's, else the radial depth of a straight cut
    /// at the engagement limit, `r·(1 − cos α_limit)` (MODEL.md §2, `α = acos(1 − Rd/r)`),
    /// at most the tool diameter. A loop's engagement at a pitch is at least a straight
    /// cut's at that depth, so no pitch above it keeps a loop under the limit; the planner
    /// takes the largest pitch below it that does ([`super::pitch::pitch_for_limit`]).
    pub fn max_pitch_mm(&self) -> f64 {
        self.pitch_mm.unwrap_or_else(|| {
            let limit = self.alpha_limit_deg.to_radians().min(std::f64::consts::PI);
            self.r_mm() * (1.0 - limit.cos())
        })
    }

    /// The largest pitch of a loop of radius `rho_mm`, mm: [`InsertionSpec::max_pitch_mm`],
    /// but for a loop larger than the tool the request's pitch or the grooving Rd. Such a
    /// loop leaves a core of radius `ρ − r` about its centre that the next loops' returns
    /// cut into, which the pitch model (the crescent beyond the previous loop's disc) does
    /// not see; at the grooving Rd they stay under the limit (the papers' pitch).
    pub fn max_pitch_for_loop_mm(&self, rho_mm: f64) -> f64 {
        if rho_mm > self.r_mm() + LENGTH_EPS_MM {
            self.pitch_mm.unwrap_or(self.grooving.rd_mm.max(MIN_PITCH_MM).min(self.max_pitch_mm()))
        } else {
            self.max_pitch_mm()
        }
    }

    /// Feed of the moves in the air, mm/min.
    pub fn air_feed_mm_min(&self) -> f64 {
        self.air_feed_mm_min.unwrap_or_else(|| {
            DEFAULT_AIR_FEED_PER_GROOVING_FEED
                * crate::core::conditions::feed_mm_min(self.grooving.fz_mm, self.tool.flutes, self.grooving.spindle_rpm)
        })
    }

    /// Depth per turn of a helical entry on a circle of radius `radius_mm`: the request's, or
    /// the one of a [`DEFAULT_RAMP_ANGLE_DEG`] ramp (at most the grooving Ad), mm.
    pub fn ramp_pitch_mm(&self, radius_mm: f64) -> f64 {
        self.ramp_pitch_mm.unwrap_or_else(|| {
            (std::f64::consts::TAU * radius_mm * DEFAULT_RAMP_ANGLE_DEG.to_radians().tan())
                .clamp(MIN_DEFAULT_RAMP_PITCH_MM, self.grooving.ad_mm)
        })
    }

    /// The largest loop radius, mm: `(a − 1)·r`.
    pub fn max_loop_radius_mm(&self) -> f64 {
        (self.class_a_ratio - 1.0) * self.r_mm()
    }

    /// Checks every field; errors name it.
    pub fn validate(&self) -> Result<(), CoreError> {
        if matches!(self.tool.tool_type, ToolType::Ball) {
            return Err(CoreError::invalid(
                "tool",
                "trochoidal grooving and contour-parallel roughing need a flat end mill (square or radius), not a ball end mill",
            ));
        }
        require_positive("tool.diameter_mm", self.tool.diameter_mm)?;
        self.roughing.validate().map_err(|e| prefix("roughing", e))?;
        self.grooving.validate().map_err(|e| prefix("grooving", e))?;
        let top = require_finite("z_top_mm", self.z_top_mm)?;
        let bottom = require_finite("z_bottom_mm", self.z_bottom_mm)?;
        if bottom >= top {
            return Err(CoreError::invalid(
                "z_bottom_mm",
                format!("must be below z_top_mm ({top} mm), got {bottom} mm"),
            ));
        }
        if require_finite("safe_z_mm", self.safe_z_mm)? <= top {
            return Err(CoreError::invalid(
                "safe_z_mm",
                format!("must be above z_top_mm ({top} mm), got {} mm", self.safe_z_mm),
            ));
        }
        let a = require_finite("allowance_mm", self.allowance_mm)?;
        if a < 0.0 {
            return Err(CoreError::invalid("allowance_mm", format!("must be ≥ 0, got {a}")));
        }
        let limit = require_positive("alpha_limit_deg", self.alpha_limit_deg)?;
        if limit <= PITCH_DESIGN_MARGIN_DEG || limit >= 180.0 {
            return Err(CoreError::invalid(
                "alpha_limit_deg",
                format!("must be between {PITCH_DESIGN_MARGIN_DEG}° and 180°, got {limit}°"),
            ));
        }
        let ratio = require_finite("class_a_ratio", self.class_a_ratio)?;
        if !(CLASS_A_RATIO_MIN..=CLASS_A_RATIO_MAX).contains(&ratio) {
            return Err(CoreError::invalid(
                "class_a_ratio",
                format!("must be between {CLASS_A_RATIO_MIN} and {CLASS_A_RATIO_MAX} (seed 004 §2.3), got {ratio}"),
            ));
        }
        if let LoopSize::Fixed { rho_mm } = self.loop_size {
            require_positive("loop_radius_mm", rho_mm)?;
        }
        if let Some(p) = self.pitch_mm {
            require_positive("pitch_mm", p)?;
        }
        if let Some(f) = self.air_feed_mm_min {
            require_positive("air_feed_mm_min", f)?;
        }
        if self.pitch_mm.is_none() && self.grooving.rd_mm < MIN_PITCH_MM {
            return Err(CoreError::invalid(
                "grooving.rd_mm",
                format!(
                    "is the pitch of trochoid loops larger than the tool and must be at least {MIN_PITCH_MM} mm, got {} mm",
                    self.grooving.rd_mm
                ),
            ));
        }
        let max_pitch = self.max_pitch_mm();
        if max_pitch < MIN_PITCH_MM {
            let field = if self.pitch_mm.is_some() { "pitch_mm" } else { "alpha_limit_deg" };
            return Err(CoreError::invalid(
                field,
                format!("the largest trochoid pitch must be at least {MIN_PITCH_MM} mm, got {max_pitch} mm"),
            ));
        }
        let depth = top - bottom;
        if depth <= LENGTH_EPS_MM {
            return Err(CoreError::invalid(
                "z_bottom_mm",
                format!("the layer from {top} mm down to {bottom} mm is thinner than {LENGTH_EPS_MM} mm"),
            ));
        }
        for (field, ad) in [("zcut_ad_mm", self.zcut_ad_mm), ("roughing.ad_mm", self.roughing.ad_mm)] {
            level_count(top, bottom, require_positive(field, ad)?).map_err(|_| {
                CoreError::invalid(field, format!("divides the {depth} mm depth into more than {MAX_LEVELS} levels"))
            })?;
        }
        if let Some(p) = self.ramp_pitch_mm {
            helix_turns("ramp_pitch_mm", depth, p)?;
        }
        require_positive("rapid_mm_min", self.rapid_mm_min)?;
        if let Some(s) = self.sample_spacing_mm {
            require_positive("sample_spacing_mm", s)?;
        }
        if let Some(c) = self.cell_mm {
            require_positive("cell_mm", c)?;
        }
        let gap = require_finite("wall_gap_mm", self.wall_gap_mm)?;
        if gap < 0.0 {
            return Err(CoreError::invalid("wall_gap_mm", format!("must be ≥ 0, got {gap}")));
        }
        Ok(())
    }
}

fn prefix(section: &str, e: CoreError) -> CoreError {
    match e {
        CoreError::InvalidInput { field, reason } => CoreError::invalid(format!("{section}.{field}"), reason),
        other => other,
    }
}
