//! The plan's stair-step intermediate roughing (issue 32 item 4, [`super::stairs`]):
//! after the chosen tool has roughed the layers, a ball or radius end mill takes off the
//! steps they leave over a sloped wall or floor. Its path is simulated on the stock the
//! roughing really left (the plan's kept stock), its feeds set for a constant cutting force
//! at the tool's standard force F* (MODEL.md §3), its wear, time and cost estimated by the
//! same models as the roughing's (MODEL.md §9–10), and the stock it leaves is what the plan
//! keeps.

use super::evaluate::{feed_and_rapid_mm, feed_spec, rates, wear_along, Figures, Worn};
use super::spec::{ProcessOptions, ToolCandidate};
use super::stairs::stock::with_steps;
use super::stairs::{plan_stairs, StairLevel, StairSpec};
use super::Cavity;
use crate::core::analysis::geometry::{PathGeometry, SampleGeometry};
use crate::core::analysis::kept::{keep, Floor, KeptStock};
use crate::core::analysis::{analyze_from, AnalysisSpec, StockRegion};
use crate::core::conditions::CuttingConditions;
use crate::core::costing::cost::{cost, Cost};
use crate::core::insertion::append_over;
use crate::core::kinematics::{machining_time, MachiningTime, TimeOptions};
use crate::core::progress::{Progress, Stage};
use crate::core::tool::{EndMill, ToolType};
use crate::core::tool_life::{Consumption, CutLength};
use crate::core::toolpath::{Event, EventKind, Toolpath};
use crate::core::CoreError;
use serde::Serialize;

/// The request field errors of the step's values are named under.
pub const STAIR_STEP_FIELD: &str = "stair_step";

/// Share of the step's progress taken by planning its path (the rest is its simulation).
const PATH_SHARE: f64 = 0.3;

/// A radius end mill's default depth between levels, × its diameter (**assumed**: the ratio
/// of the R5 ball's side cut of seed 004 Table 7, Ad 0.6 on D10).
pub const RADIUS_STAIR_AD_PER_DIAMETER: f64 = 0.06;
/// A radius end mill's default depth between rings, × its diameter (**assumed**: as the R5
/// ball's Rd 4 on D10, seed 004 Table 7).
pub const RADIUS_STAIR_RD_PER_DIAMETER: f64 = 0.4;

/// The stair step's conditions for `tool`, whose standard side cut is `standard`: its S and
/// fz; `axial_depth_mm` and `radial_depth_mm` where given, else a ball's own standard Ad and
/// Rd and a radius end mill's shares of its diameter.
pub fn stair_conditions(
    tool: &EndMill,
    standard: CuttingConditions,
    axial_depth_mm: Option<f64>,
    radial_depth_mm: Option<f64>,
) -> CuttingConditions {
    let (ad, rd) = match tool.tool_type {
        ToolType::Ball => (standard.ad_mm, standard.rd_mm),
        _ => (RADIUS_STAIR_AD_PER_DIAMETER * tool.diameter_mm, RADIUS_STAIR_RD_PER_DIAMETER * tool.diameter_mm),
    };
    CuttingConditions { ad_mm: axial_depth_mm.unwrap_or(ad), rd_mm: radial_depth_mm.unwrap_or(rd), ..standard }
}

/// The stair-step roughing's tool, as the plan's candidates are given (its conditions are
/// the step's: S, fz, Rd between rings, Ad between levels), and its number in the program.
#[derive(Debug, Clone)]
pub struct StairStepSpec {
    pub candidate: ToolCandidate,
    pub tool_number: u32,
}

/// The stair-step roughing as planned and estimated.
#[derive(Debug, Clone, Serialize, utoipa::ToSchema)]
pub struct StairStep {
    pub tool: String,
    pub tool_type: ToolType,
    pub diameter_mm: f64,
    pub corner_radius_mm: f64,
    /// Its number in the program (`T.. M6`, `G43 H..`).
    pub tool_number: u32,
    pub spindle_rpm: f64,
    /// Between levels, mm.
    pub axial_depth_mm: f64,
    /// Between rings at a level, mm.
    pub radial_depth_mm: f64,
    /// The constant force the feeds hold (the tool's standard force F*), N.
    pub target_force_n: f64,
    pub levels: Vec<StairLevel>,
    /// The cell of the height field the rings follow, mm.
    pub surface_cell_mm: f64,
    /// The steps over the die's surface (interpolated between the layers' sections) as the
    /// layers' contours leave them, mm³.
    pub step_volume_mm3: f64,
    /// Material the step removes from the stock the roughing left, as simulated, mm³.
    pub removed_volume_mm3: f64,
    #[serde(flatten)]
    pub figures: Figures,
    /// The length one of its tools lasts at this step's mix of cuts, both ways.
    pub equivalent_life: CutLength,
    pub cost: Cost,
    /// Where the feeds cannot hold the target force.
    pub warnings: Vec<String>,
    /// The step's program (its tool change first), labelled by level.
    #[serde(skip)]
    pub consumption: Consumption,
    #[serde(skip)]
    pub program: Toolpath,
    #[serde(skip)]
    pub time: MachiningTime,
}

/// The program of the whole job: `roughing`, then `step` (which calls its own tool),
/// joined over `safe_z_mm`; `step`'s events move with its moves.
pub fn joined_program(roughing: &Toolpath, step: &Toolpath, safe_z_mm: f64) -> Toolpath {
    let mut moves = roughing.moves.clone();
    let mut events = roughing.events.clone();
    // The roughing's end (if any) is no longer the program's.
    events.retain(|e| e.kind != EventKind::End);
    append_over(&mut moves, &step.moves, safe_z_mm);
    let offset = moves.len() - step.moves.len();
    events.extend(step.events.iter().map(|e| Event { before_move: e.before_move + offset, ..*e }));
    for (i, m) in moves.iter_mut().enumerate() {
        m.line = u32::try_from(i + 1).unwrap_or(u32::MAX);
    }
    let mut warnings = roughing.warnings.clone();
    warnings.extend(step.warnings.iter().cloned());
    Toolpath { moves, events, source_units: roughing.source_units, warnings }
}

/// Plans and estimates the stair-step roughing of `cavity` from the stock `start` the
/// roughing left; `None` when the layers leave no steps. Also hands back the stock it leaves.
pub fn plan_stair_step(
    cavity: &Cavity,
    start: &KeptStock,
    spec: &StairStepSpec,
    options: &ProcessOptions,
    progress: &dyn Progress,
) -> Result<Option<(StairStep, KeptStock)>, CoreError> {
    let c = &spec.candidate;
    c.validate_in(STAIR_STEP_FIELD, false)?;
    let conditions = c.intermediate;
    let stair = StairSpec {
        tool: c.tool,
        conditions,
        allowance_mm: options.allowance_mm,
        safe_z_mm: options.safe_z_mm,
        tool_number: spec.tool_number,
    };
    let planning = Stage { inner: progress, from: 0.0, span: PATH_SHARE };
    let Some(path) = plan_stairs(cavity, &stair, &planning)? else {
        return Ok(None);
    };
    let simulating = Stage { inner: progress, from: PATH_SHARE, span: 1.0 - PATH_SHARE };
    let Some(first) = cavity.layers.first() else {
        return Ok(None);
    };
    let bottom = cavity.layers.last().map_or(first.z_bottom_mm, |l| l.z_bottom_mm);
    let analysis = AnalysisSpec {
        force_model: Some(c.force_model),
        default_spindle_rpm: Some(conditions.spindle_rpm),
        rapid_mm_min: options.machine.rapid_mm_min,
        sample_spacing_mm: options.sample_spacing_mm,
        alpha_limit_deg: options.alpha_limit_deg,
        stock_memory_bytes: options.stock_memory_bytes,
        ..AnalysisSpec::new(c.tool, vec![StockRegion::Pocket(first.pocket.clone())], cavity.top_mm(), bottom)
    };
    // The roughing's stock holds no steps (each layer was simulated on its own contour):
    // they are painted in, on slices cut at the step's levels.
    let levels: Vec<f64> = path.levels.iter().map(|l| l.z_mm).collect();
    let start = with_steps(start, &path.surface, &levels).map_err(|reason| CoreError::unsolvable("stock", reason))?;
    let mut geometry = PathGeometry::new(c.tool.radius_mm());
    let (simulated, stack) = analyze_from(&path.toolpath, &analysis, Some(&start), &simulating, |r| {
        geometry.samples.push(SampleGeometry::of(r, Some(conditions.spindle_rpm)))
    })?;
    geometry.removed_volume_mm3 = simulated.summary.removed_volume_mm3;
    let kept = keep(&stack, &analysis, Some(&start), Floor::Unbounded, true)?;
    let feeds = feed_spec(c, options, 1.0);
    let plan = super::feeds::optimise(&path.toolpath, &geometry, &feeds)?;
    let Worn { wear_mm, cutting_mm, surface_mm } = wear_along(&path.toolpath, &geometry, &plan, c, &[]);
    let program = plan.path;
    let time = machining_time(&program, &options.machine, &TimeOptions::default())?;
    let (feed_length_mm, rapid_length_mm) = feed_and_rapid_mm(&program);
    let worn: f64 = wear_mm.iter().sum();
    let cutting: f64 = cutting_mm.iter().sum();
    let consumption = Consumption::new(worn, c.life.life_edge_arc_mm(), cutting, surface_mm);
    let cost = cost(time.kinematic_min, consumption.ratio, &rates(options, c.tool_price))?;
    let mut warnings = Vec::new();
    if !plan.shortfalls.is_empty() {
        let length: f64 = plan.shortfalls.iter().map(|s| s.length_mm).sum();
        warnings.push(format!(
            "{} stretch(es), {length:.1} mm in all, where no feed within the limits holds the target force",
            plan.shortfalls.len()
        ));
    }
    progress.report(1.0);
    let step = StairStep {
        tool: c.name.clone(),
        tool_type: c.tool.tool_type,
        diameter_mm: c.tool.diameter_mm,
        corner_radius_mm: c.tool.corner_radius_mm,
        tool_number: spec.tool_number,
        spindle_rpm: conditions.spindle_rpm,
        axial_depth_mm: conditions.ad_mm,
        radial_depth_mm: conditions.rd_mm,
        target_force_n: feeds.rule.target_force_n,
        levels: path.levels,
        surface_cell_mm: path.cell_mm,
        step_volume_mm3: path.step_volume_mm3,
        removed_volume_mm3: simulated.summary.removed_volume_mm3,
        figures: Figures {
            feed_length_mm,
            cutting_length_mm: cutting,
            rapid_length_mm,
            nominal_time_min: time.nominal_min,
            kinematic_time_min: time.kinematic_min,
            consumption: consumption.ratio,
        },
        equivalent_life: consumption.equivalent_life,
        consumption,
        cost,
        warnings,
        program,
        time,
    };
    Ok(Some((step, kept)))
}
