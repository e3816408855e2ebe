//! The `feeds` job (seed 002 subsystem (d); seeds 000–003): the feeds of a tool path
//! optimised for a constant feed at the cutting point, a constant cutting force, or
//! both, written back as an NC program.

use super::feed_limits;
use super::feeds_result::FeedsResult;
use super::inputs::{check_from_job, Stock, StockInput};
use super::kept_stock;
use super::kind::off_runtime_with;
use super::output::OutputOptions;
use super::program_input::{ProgramInput, ReadProgram};
use super::setup::{path_job_refs, read_inputs, reread_inputs, resolve, CostSetup, PathSetup};
use crate::core::analysis::kept::{keep, Floor, KeptStock};
use crate::core::analysis::{
    check, sample_count, AnalysisSpec, DEFAULT_ALPHA_LIMIT_DEG, DEFAULT_STOCK_MEMORY_BYTES, MAX_ALPHA_LIMIT_DEG,
};
use crate::core::drawing::feeds_scene::feeds_scene;
use crate::core::drawing::paths::edited_move_lines;
use crate::core::drawing::scene::Scene;
use crate::core::feed::blocks::{BlockOptions, DEFAULT_FEED_STEP_MM_MIN, DEFAULT_FEED_TOLERANCE, DEFAULT_MIN_BLOCK_MM};
use crate::core::feed::costed::{optimize_costed, Costed, Optimised};
use crate::core::feed::edit::edit_feeds;
use crate::core::feed::objective::{Objective, ObjectiveSpec};
use crate::core::feed::plan::{check_sample_count, check_spec, FeedPlan, FeedSpec};
use crate::core::feed::rule::{FeedRule, FeedStrategy};
use crate::core::feed::surface::{
    self, optimize_surface_finishing, ContactNormal, SurfaceSpec, DEFAULT_SURFACE_FIT_HALF_WIDTH_MM,
};
use crate::core::kinematics::{machining_time, MachineLimits, TimeOptions};
use crate::core::nc::{write_program_mapped, ProgramMap};
use crate::core::progress::Progress;
use crate::core::tool::ToolType;
use crate::core::toolpath::Toolpath;
use crate::core::CoreError;
use crate::service::error::{ApiError, Validator};
use crate::service::jobs::kind::{JobKindSpec, Produced, Submission};
use crate::service::jobs::model::JobKind;
use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

/// Surface finishing samples at most this far apart by default, mm.
pub const DEFAULT_SURFACE_SPACING_MM: f64 = 0.05;

/// What is being cut.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, ToSchema)]
#[serde(rename_all = "snake_case")]
pub enum CutMode {
    /// 2.5-D side milling: the stock is simulated to find the engagement.
    #[default]
    SideMilling,
    /// 3-D finishing with a ball end mill: the feed is held at the cutting point.
    SurfaceFinishing,
}

/// Where the ball touches the surface (surface finishing).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, ToSchema)]
#[serde(rename_all = "snake_case")]
pub enum ContactInput {
    /// Straight down, perpendicular to the path (raster finishing from above).
    #[default]
    Down,
    /// The path's principal normal, turned downwards.
    PrincipalNormal,
}

/// A tool path whose feeds to optimise. Name the tool by `tool_id` or by `tool_type` and
/// `diameter_mm`; every limit has a default from the database (see each field).
#[derive(Debug, Clone, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
#[schema(example = json!({
    "program": {"gcode": "G21 G90 G17\nG0 X-10 Y5 Z5\nS9600 M3\nG1 Z-10 F1000\nG1 X50 F5760\nG3 X60 Y15 I0 J10\nG1 Y60\nM30"},
    "tool_type": "square", "diameter_mm": 10,
    "stock": {"box": {"x_min": 0, "y_min": -40, "z_min": -10, "x_max": 55, "y_max": 80, "z_max": 0}},
    "strategy": "constant_force"
}))]
pub struct FeedsRequest {
    pub program: ProgramInput,
    pub tool_id: Option<i64>,
    pub tool_type: Option<ToolType>,
    pub diameter_mm: Option<f64>,
    pub material_id: Option<i64>,
    /// Material name (default SKD61).
    pub material: Option<String>,
    /// The stock of the layer (required for side milling); `from_job` optimises the path
    /// on the stock a finished job left (see the README, "Stock carried between
    /// programs"), and the job keeps the stock the path leaves in turn.
    pub stock: Option<StockInput>,
    /// `side_milling` (default) or `surface_finishing` (a ball end mill only).
    #[serde(default)]
    pub mode: CutMode,
    /// `cutting_point`, `constant_force` or `both` (constant force capped by the
    /// cutting-point rule). Default: `constant_force` for side milling, `cutting_point`
    /// for surface finishing.
    pub strategy: Option<FeedStrategy>,
    /// What the feeds are chosen for, within the strategy: `min_cost` (default for side
    /// milling: the cheapest feed per millimetre under the force limit, and never a
    /// program that costs more than the input), `constant_force` (the papers' rule as
    /// written: hold the target force, the minimum feed where it cannot be held) or
    /// `min_time` (the fastest feed under the force limit). Surface finishing takes
    /// `constant_force` only.
    pub objective: Option<Objective>,
    /// The most force min_cost and min_time may ask of the tool, N (default: the target
    /// force, so both hold the constant force wherever it can be held; raise it to let
    /// them trade force for cost or time).
    pub max_force_n: Option<f64>,
    /// Cost rates of the costs before and after and of min_cost (default: the first).
    pub cost_rates_id: Option<i64>,
    /// Price of one tool (default: the tool's price, else the rates' default).
    pub tool_price: Option<f64>,
    /// Force to hold, N (default: the model's force at the tool's standard straight
    /// conditions, β0).
    pub target_force_n: Option<f64>,
    /// Default: the minimum feed per tooth of the standard conditions × z × S.
    pub min_feed_mm_min: Option<f64>,
    /// Default: 2 × the standard feed, at most the machine's maximum feed.
    pub max_feed_mm_min: Option<f64>,
    /// Feed of feed moves in the air (default: the maximum feed).
    pub air_feed_mm_min: Option<f64>,
    /// Most the feed may change per mm of path, mm/min (default 1000; 0: no limit).
    pub max_feed_change_per_mm: Option<f64>,
    /// Shortest block a move is split into, mm (default 1).
    pub min_block_mm: Option<f64>,
    /// Relative change of the required feed inside a block before it is split (default 0.01).
    pub feed_tolerance: Option<f64>,
    /// Feeds are rounded down to a multiple of this, mm/min (default 1; 0: no rounding).
    pub feed_step_mm_min: Option<f64>,
    /// Spindle speed where the program has no S word (default: the standard one).
    pub spindle_rpm: Option<f64>,
    /// Machine for the rapid rate and the maximum feed (default: the first machine).
    pub machine_id: Option<i64>,
    /// Engagement above this is critical in the analysis of the input (default 40°).
    pub alpha_limit_deg: Option<f64>,
    /// Distance between samples, mm (default min(0.05, D/100)).
    pub sample_spacing_mm: Option<f64>,
    /// Raster cell of the stock simulation, mm.
    pub cell_mm: Option<f64>,
    /// Surface finishing: where the ball touches (default `down`).
    pub contact: Option<ContactInput>,
    /// Surface finishing: one contact normal `[x, y, z]` per move (from the ball centre to
    /// the contact point), instead of `contact`.
    pub contact_normals: Option<Vec<[f64; 3]>>,
    /// How to write the program (dialect, numbering, title…).
    #[serde(default)]
    pub output: OutputOptions,
}

/// What the request resolved to.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct FeedsPrepared {
    #[serde(flatten)]
    pub base: PathSetup,
    pub strategy: FeedStrategy,
    pub target_force_n: Option<f64>,
    pub min_feed_mm_min: f64,
    pub max_feed_mm_min: f64,
    pub air_feed_mm_min: f64,
    pub max_feed_change_per_mm: Option<f64>,
    pub standard_conditions_id: Option<i64>,
    /// Jobs stored before objectives existed ran the papers' rule.
    #[serde(default = "papers_rule")]
    pub objective: Objective,
    #[serde(default)]
    pub max_force_n: Option<f64>,
    /// The costing's tool life, rates and machine (null: the figures before and after
    /// have no wear or cost).
    #[serde(default)]
    pub cost: Option<CostSetup>,
    /// The machine's limits for the nominal and kinematic time.
    #[serde(default)]
    pub limits: Option<MachineLimits>,
    /// What the request resolved to that the user should know.
    #[serde(default)]
    pub notes: Vec<String>,
}

fn papers_rule() -> Objective {
    Objective::ConstantForce
}

/// Checks the values of the request that need no database.
pub fn check_request(request: &FeedsRequest, v: &mut Validator) {
    if let Some(stock) = &request.stock {
        check_from_job(stock, v);
        if stock.from_job.is_some() && request.cell_mm.is_some() {
            v.fail("cell_mm", "not with stock.from_job: the stock keeps the cell of the job that left it");
        }
        if stock.from_job.is_some() && request.mode == CutMode::SurfaceFinishing {
            v.fail(kept_stock::FIELD, "surface finishing simulates no stock: only side milling starts from a kept one");
        }
    }
    for (field, value) in [
        ("target_force_n", request.target_force_n),
        ("min_feed_mm_min", request.min_feed_mm_min),
        ("max_feed_mm_min", request.max_feed_mm_min),
        ("air_feed_mm_min", request.air_feed_mm_min),
        ("spindle_rpm", request.spindle_rpm),
        ("max_force_n", request.max_force_n),
    ] {
        if let Some(x) = value {
            v.positive(field, x);
        }
    }
    if let Some(p) = request.tool_price {
        v.within("tool_price", p, 0.0, crate::service::resources::tools::MAX_PRICE);
    }
    for (field, value) in [
        ("max_feed_change_per_mm", request.max_feed_change_per_mm),
        ("min_block_mm", request.min_block_mm),
        ("feed_tolerance", request.feed_tolerance),
        ("feed_step_mm_min", request.feed_step_mm_min),
    ] {
        if let Some(x) = value {
            v.non_negative(field, x);
        }
    }
    if let Some(a) = request.alpha_limit_deg {
        v.above_and_at_most("alpha_limit_deg", a, 0.0, MAX_ALPHA_LIMIT_DEG);
    }
    if let Some(s) = request.sample_spacing_mm {
        v.within("sample_spacing_mm", s, 1e-4, 5.0);
    }
    if let Some(c) = request.cell_mm {
        v.within("cell_mm", c, 1e-3, 5.0);
    }
    if let Some(t) = request.feed_tolerance {
        v.within("feed_tolerance", t, 0.0, 1.0);
    }
    if let Some(b) = request.min_block_mm {
        v.within("min_block_mm", b, 0.0, 1000.0);
    }
    match request.mode {
        CutMode::SideMilling => {
            v.check(request.stock.is_some(), "stock", "required for side milling");
            v.check(request.contact.is_none(), "contact", "only for surface_finishing");
            v.check(request.contact_normals.is_none(), "contact_normals", "only for surface_finishing");
        }
        CutMode::SurfaceFinishing => {
            v.check(
                !(request.contact.is_some() && request.contact_normals.is_some()),
                "contact",
                "give contact or contact_normals, not both",
            );
            v.check(
                request.objective.is_none_or(|o| o == Objective::ConstantForce),
                "objective",
                "surface finishing holds the programmed feed at the cutting point (seed 000): only constant_force applies; min_cost and min_time need the stock simulation of side milling",
            );
        }
    }
    request.output.validate(v);
}

/// Resolves the request and reads its program and stock, adding every fault to `faults`;
/// then, when it has none, checks the optimisation as the core will run it.
pub async fn prepare(
    submission: &Submission<'_>,
    request: FeedsRequest,
    faults: &mut Validator,
) -> Result<Option<FeedsPrepared>, ApiError> {
    let pool = submission.pool;
    let carried = match request.stock.as_ref().and_then(|s| s.from_job.as_ref()) {
        Some(id) if !faults.refused(kept_stock::FIELD) => faults.take(kept_stock::carried(submission, id).await)?,
        _ => None,
    };
    let refs = path_job_refs!(request, request.machine_id, request.spindle_rpm);
    let resolved = resolve(pool, &refs, faults).await?.map(|mut r| {
        r.prepared.carried_stock = carried;
        r
    });
    let base = resolved.as_ref().map(|r| r.prepared.clone());
    let prepared = match resolved {
        Some(resolved) => feed_limits::resolve(pool, &request, resolved, faults).await?,
        None => None,
    };
    // Parse and check everything now, off the async runtime: bad input is a 4xx here.
    let checked = prepared.clone();
    off_runtime_with(faults, move |faults| {
        let stock = request.stock.as_ref().filter(|_| request.mode == CutMode::SideMilling);
        let inputs = read_inputs(base.as_ref(), Some(&request.program), stock, faults)?;
        let (Some(prepared), Some(read)) = (checked, inputs.program) else {
            return Ok(());
        };
        if faults.has_errors() {
            return Ok(());
        }
        let Some(job) = faults.take(build(&request, &prepared, inputs.stock, read))? else {
            return Ok(());
        };
        faults.take(check_spec(&job.spec))?;
        if let Some(analysis) = &job.analysis {
            faults.take(check(&job.path, analysis))?;
            faults.take(check_sample_count(sample_count(&job.path, analysis)))?;
        }
        if let Some(surface) = &job.surface {
            faults.take(surface::check_surface(&job.path, surface, &job.spec))?;
        }
        Ok(())
    })
    .await?;
    Ok(prepared)
}

/// A feeds job ready to run.
struct Built {
    path: Toolpath,
    /// How each line of G-code input ran (none for JSON moves).
    map: Option<ProgramMap>,
    spec: FeedSpec,
    objective: ObjectiveSpec,
    analysis: Option<AnalysisSpec>,
    surface: Option<SurfaceSpec>,
}

/// The job of a request whose stock (side milling) and program were read.
fn build(
    request: &FeedsRequest,
    prepared: &FeedsPrepared,
    stock: Option<Stock>,
    read: ReadProgram,
) -> Result<Built, ApiError> {
    let base = &prepared.base;
    let (path, map) = (read.path, read.map);
    let tool: crate::core::tool::EndMill = base.tool.geometry.into();
    let spec = FeedSpec {
        rule: FeedRule {
            strategy: prepared.strategy,
            force_model: base.force_model.as_ref().map(|f| f.model),
            target_force_n: prepared.target_force_n.unwrap_or(0.0),
            flutes: tool.flutes,
            min_feed_mm_min: prepared.min_feed_mm_min,
            max_feed_mm_min: prepared.max_feed_mm_min,
            air_feed_mm_min: prepared.air_feed_mm_min,
        },
        max_change_per_mm: prepared.max_feed_change_per_mm,
        blocks: BlockOptions {
            min_block_mm: request.min_block_mm.unwrap_or(DEFAULT_MIN_BLOCK_MM),
            tolerance: request.feed_tolerance.unwrap_or(DEFAULT_FEED_TOLERANCE),
            feed_step_mm_min: request.feed_step_mm_min.unwrap_or(DEFAULT_FEED_STEP_MM_MIN),
        },
        rapid_mm_min: base.rapid_mm_min,
    };
    let (analysis, surface) = match (request.mode, stock) {
        (CutMode::SideMilling, Some(stock)) => {
            let analysis = AnalysisSpec {
                tool,
                stock: stock.regions,
                open: stock.open,
                z_top: stock.z_top,
                z_bottom: stock.z_bottom,
                force_model: spec.rule.force_model,
                default_spindle_rpm: base.default_spindle_rpm,
                rapid_mm_min: base.rapid_mm_min,
                sample_spacing_mm: request.sample_spacing_mm,
                cell_mm: request.cell_mm,
                alpha_limit_deg: request.alpha_limit_deg.unwrap_or(DEFAULT_ALPHA_LIMIT_DEG),
                series_points: 0,
                stock_memory_bytes: DEFAULT_STOCK_MEMORY_BYTES,
            };
            (Some(analysis), None)
        }
        (CutMode::SideMilling, None) => return Err(ApiError::field("stock", "required for side milling")),
        (CutMode::SurfaceFinishing, _) => {
            let contact = match (&request.contact_normals, request.contact.unwrap_or_default()) {
                (Some(normals), _) => ContactNormal::PerMove(normals.clone()),
                (None, ContactInput::Down) => ContactNormal::Down,
                (None, ContactInput::PrincipalNormal) => ContactNormal::PrincipalNormal,
            };
            let surface = SurfaceSpec {
                ball_radius_mm: tool.radius_mm(),
                sample_spacing_mm: request.sample_spacing_mm.unwrap_or(DEFAULT_SURFACE_SPACING_MM),
                fit_half_width_mm: DEFAULT_SURFACE_FIT_HALF_WIDTH_MM,
                contact,
            };
            (None, Some(surface))
        }
    };
    let objective = ObjectiveSpec {
        objective: prepared.objective,
        max_force_n: prepared.max_force_n.unwrap_or(f64::INFINITY),
        cost: prepared.cost.as_ref().map(CostSetup::cost_model),
    };
    Ok(Built { path, map, spec, objective, analysis, surface })
}

/// Runs the optimisation and writes the program; side milling also hands back the stock
/// the path leaves.
pub fn run(
    request: FeedsRequest,
    prepared: FeedsPrepared,
    progress: &dyn Progress,
    stock_memory_bytes: usize,
) -> Result<(FeedsResult, String, Scene, Option<KeptStock>), CoreError> {
    let reread = |e: ApiError| CoreError::invalid("input", e.to_string());
    let stock = request.stock.as_ref().filter(|_| request.mode == CutMode::SideMilling);
    let (stock, read) = reread_inputs(&prepared.base, &request.program, stock).map_err(reread)?;
    let mut job = build(&request, &prepared, stock, read).map_err(reread)?;
    if let Some(analysis) = job.analysis.as_mut() {
        analysis.stock_memory_bytes = stock_memory_bytes;
    }
    let start =
        prepared.base.carried_stock.as_ref().map(|c| c.decode(stock_memory_bytes)).transpose().map_err(reread)?;
    let (plan, costed, kept): (FeedPlan, Option<Costed>, Option<KeptStock>) = match (&job.analysis, &job.surface) {
        (Some(analysis), _) => {
            let Optimised { plan, costed, stock } =
                optimize_costed(&job.path, analysis, start.as_ref(), &job.spec, job.objective.clone(), progress)?;
            let cavity = plan.analysis.as_ref().is_some_and(|a| a.summary.rest_material.is_some());
            let floor = request.stock.as_ref().map_or(Floor::Unbounded, StockInput::floor);
            (plan, costed, Some(keep(&stock, analysis, start.as_ref(), floor, cavity)?))
        }
        (None, Some(surface)) => (optimize_surface_finishing(&job.path, surface, &job.spec, progress)?, None, None),
        (None, None) => return Err(CoreError::invalid("mode", "nothing to optimise")),
    };
    // G-code is edited (only its F words change); JSON moves are written anew. Either way
    // the optimised path's drawing names the lines of the program served.
    let (program, edit, served_lines) = match (&request.program.gcode, &job.map) {
        (Some(text), Some(map)) => {
            let edited = edit_feeds(text, &job.path, map, &plan.pieces);
            let lines = edited_move_lines(&plan.path, &edited.changes);
            (edited.text.clone(), Some(edited), lines)
        }
        _ => {
            let written = write_program_mapped(&plan.path, &request.output.to_writer(&prepared.base));
            (written.text, None, written.move_lines)
        }
    };
    let scene = feeds_scene(&job.path, &plan, job.analysis.as_ref(), &served_lines);
    let times = match (&costed, &prepared.limits) {
        (Some(c), _) => Some((c.before.time.clone(), c.after.time.clone())),
        (None, Some(limits)) => {
            let time = |p: &Toolpath| machining_time(p, limits, &TimeOptions::default());
            Some((time(&job.path)?, time(&plan.path)?))
        }
        (None, None) => None,
    };
    let moves_in = job.path.moves.len();
    let mut result = FeedsResult::new(prepared, request.mode, moves_in, &program, plan, costed, times)?;
    if let Some(edited) = edit {
        if request.output.is_set() {
            result.warnings.push(
                "the output options apply to programs written from JSON moves: the G-code sent keeps its own dialect, numbering and header, only its F words change"
                    .to_string(),
            );
        }
        result.warnings.extend(edited.warnings.iter().cloned());
        result.edit = Some(edited);
    }
    Ok((result, program, scene, kept))
}

/// The `feeds` job kind.
pub struct Feeds;

impl JobKindSpec for Feeds {
    const KIND: JobKind = JobKind::Feeds;
    const PATH: &'static str = "/v1/feeds";
    const OPERATION_ID: &'static str = "optimizeFeeds";
    const SUMMARY: &'static str = "Optimises the feeds of a tool path (job kind `feeds`).";
    const DESCRIPTION: &'static str = "`side_milling` (default) simulates the stock to find the engagement at every sample and sets each block's feed for a constant cutting force (`constant_force`, default), a constant feed at the cutting point (`cutting_point`, seed 000) or both; long blocks are split where the feed must change, the change per mm of path is limited, feeds are clamped to the limits and rounded. `surface_finishing` holds the feed at the cutting point of a ball end mill on a 3-D path. The result holds the before/after figures, the feed of every block and where the target could not be held; the NC program is at `GET /v1/jobs/{id}/program`.";
    const REFUSES: &'static str =
        "Every fault of the request, in one problem: each refused field, each row it names that is not in the database or lacks the data asked for, the NC program's faults (line, column and word) and the stock contour's";
    type Request = FeedsRequest;
    type Prepared = FeedsPrepared;
    type Output = FeedsResult;

    fn check(request: &FeedsRequest, v: &mut Validator) {
        check_request(request, v)
    }

    async fn prepare(
        submission: &Submission<'_>,
        request: FeedsRequest,
        faults: &mut Validator,
    ) -> Result<Option<FeedsPrepared>, ApiError> {
        prepare(submission, request, faults).await
    }

    fn run(
        request: FeedsRequest,
        prepared: FeedsPrepared,
        progress: &dyn Progress,
        stock_memory_bytes: usize,
    ) -> Result<Produced<FeedsResult>, CoreError> {
        let (result, program, scene, kept) = run(request, prepared, progress, stock_memory_bytes)?;
        let produced = Produced::programmed(result, program, scene);
        Ok(match kept {
            Some(kept) => produced.keeping(kept),
            None => produced,
        })
    }
}
