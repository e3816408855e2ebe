//! The `trochoids` job (seed 004 §2; MODEL.md §7–8): a pocket contour (and optionally a path
//! to modify) in, the medial axis with its radius-ratio classes, the path with trochoid
//! cycles and z-cut division inserted where the engagement exceeds the limit, its G-code, and
//! the report of which region got which treatment out.

use super::inputs::{read_contour, read_dxf, ContourInput};
use super::kind::off_runtime_with;
use super::output::{OutputOptions, DEFAULT_SAFE_HEIGHT_ABOVE_TOP_MM};
use super::program_input::{read_program, ProgramContext, ProgramInput};
use super::setup::{machine_limits, path_job_refs, resolve, resolve_cost, CostSetup, PathSetup, Resolved};
use super::trochoids_result::{ChangeFigures, TrochoidsResult, WearObserver};
use crate::core::analysis::kept::{keep, Floor, KeptStock};
use crate::core::conditions::{feed_mm_min, CuttingConditions};
use crate::core::cycles::trochoid::default_loop_radius_mm;
use crate::core::cycles::CutDirection;
use crate::core::drawing::insertion_scene::insertion_scene;
use crate::core::drawing::paths::with_lines;
use crate::core::drawing::scene::Scene;
use crate::core::geometry::Pocket;
use crate::core::insertion::{analysis_spec, check_plan, plan_insertion_kept, InsertionPlan, InsertionSpec, LoopSize};
use crate::core::kinematics::MachineLimits;
use crate::core::medial::{CLASS_A_RATIO_MAX, CLASS_A_RATIO_MIN};
use crate::core::nc::{write_program_mapped, WriterOptions};
use crate::core::operation::Operation;
use crate::core::progress::Progress;
use crate::core::toolpath::Toolpath;
use crate::core::CoreError;
use crate::service::error::{ApiError, Validator};
use crate::service::jobs::kind::{JobKindSpec, Produced, Submission};
use crate::service::jobs::model::JobKind;
use crate::service::lookup;
use crate::service::store::Pool;
use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

/// Cutting conditions given in a request.
#[derive(Debug, Clone, Copy, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct ConditionsInput {
    /// Spindle speed S, min⁻¹.
    pub spindle_rpm: f64,
    /// Feed per tooth fz, mm.
    pub fz_mm: f64,
    /// Radial depth of cut Rd, mm.
    pub rd_mm: f64,
    /// Axial depth of cut Ad, mm.
    pub ad_mm: f64,
}

impl From<ConditionsInput> for CuttingConditions {
    fn from(c: ConditionsInput) -> Self {
        CuttingConditions { spindle_rpm: c.spindle_rpm, fz_mm: c.fz_mm, rd_mm: c.rd_mm, ad_mm: c.ad_mm }
    }
}

/// A pocket to rough with trochoids inserted where the tool would be overloaded. Name the
/// tool by `tool_id` or by `tool_type` and `diameter_mm` (a flat end mill).
#[derive(Debug, Clone, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
#[schema(example = json!({
    "contour": {"outer": [[0, 0], [80, 0], [80, 24], [120, 24], [120, 36], [80, 36], [80, 60], [0, 60]]},
    "z_top": 0, "z_bottom": -10,
    "tool_type": "square", "diameter_mm": 10
}))]
pub struct TrochoidsRequest {
    /// The pocket: outer loop and islands (give `contour` or `dxf`).
    pub contour: Option<ContourInput>,
    /// The pocket as DXF text: the outermost loop is the pocket, loops inside it islands.
    pub dxf: Option<String>,
    /// Top and bottom of the material to remove, mm.
    pub z_top: f64,
    pub z_bottom: f64,
    /// A path to modify instead of the generated contour-parallel path.
    pub program: Option<ProgramInput>,
    pub tool_id: Option<i64>,
    pub tool_type: Option<crate::core::tool::ToolType>,
    pub diameter_mm: Option<f64>,
    pub material_id: Option<i64>,
    /// Material name (default SKD61).
    pub material: Option<String>,
    pub machine_id: Option<i64>,
    /// Rough side cutting (the generated path's step-over Rd and layer depth Ad); default
    /// the tool's `rough_side_cutting` conditions, else its standard side-cutting ones.
    pub roughing: Option<ConditionsInput>,
    /// Trochoidal grooving (S, fz, and Rd: the largest pitch); default the tool's
    /// `trochoidal_grooving` conditions, else the roughing ones.
    pub grooving: Option<ConditionsInput>,
    /// Stock left on walls and islands, mm (default 0).
    pub allowance_mm: Option<f64>,
    /// Height for moves over the material, mm (default z_top + 5).
    pub safe_z: Option<f64>,
    /// Engagement limit, deg (default 40).
    pub alpha_limit_deg: Option<f64>,
    /// Lower bound of class A's R/r, 2–3 (default 2).
    pub class_a_ratio: Option<f64>,
    /// `variable` (default: ρ = R − r − allowance, at most (a − 1)·r; seed 004 Figure 5) or
    /// `fixed` (seed 004 Figure 4: ρ = `loop_radius_mm`, default (1.2 − 1)·r, smaller where
    /// the clearance does not leave room).
    pub loop_size: Option<LoopSizeInput>,
    /// The fixed loop radius ρ, mm (with `loop_size: fixed`).
    pub loop_radius_mm: Option<f64>,
    /// Largest trochoid pitch, mm (default a straight cut's depth at the engagement limit,
    /// `r·(1 − cos α_limit)`, and the grooving Rd for loops larger than the tool); smaller
    /// where the limit needs.
    pub pitch_mm: Option<f64>,
    /// Axial depth of the z-cut division passes, mm (default 2.5).
    pub zcut_ad_mm: Option<f64>,
    /// Depth per turn of the trochoids' helical entries, mm (default a 3° ramp).
    pub ramp_pitch_mm: Option<f64>,
    /// `climb` (default) or `conventional`.
    pub direction: Option<CutDirection>,
    /// Distance between simulation samples, mm (default min(0.05, D/100)).
    pub sample_spacing_mm: Option<f64>,
    /// How to write the program (dialect, numbering, title…).
    #[serde(default)]
    pub output: OutputOptions,
}

/// How large the trochoid loops are.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, ToSchema)]
#[serde(rename_all = "snake_case")]
pub enum LoopSizeInput {
    Variable,
    Fixed,
}

/// What the request resolved to.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct TrochoidsPrepared {
    #[serde(flatten)]
    pub base: PathSetup,
    pub roughing: CuttingConditions,
    /// Where the roughing conditions come from (a standard-conditions row, or the request).
    pub roughing_source: String,
    pub grooving: CuttingConditions,
    pub grooving_source: String,
    /// The machine's kinematic limits, for the figures before and after (absent in jobs
    /// queued before they were kept).
    #[serde(default)]
    pub limits: Option<MachineLimits>,
    /// The tool life, rates and machine the paths before and after are costed with (null
    /// without tool-life data for the tool in the material, and in jobs queued before the
    /// costs were kept: no wear or cost then).
    #[serde(default)]
    pub cost: Option<CostSetup>,
}

/// Checks the values of the request that need no database.
pub fn check_request(request: &TrochoidsRequest, v: &mut Validator) {
    v.finite("z_top", request.z_top);
    v.finite("z_bottom", request.z_bottom);
    v.check(request.z_bottom < request.z_top, "z_bottom", "must be below z_top");
    v.check(request.contour.is_some() != request.dxf.is_some(), "contour", "give exactly one of contour and dxf");
    for (field, value) in [
        ("loop_radius_mm", request.loop_radius_mm),
        ("pitch_mm", request.pitch_mm),
        ("zcut_ad_mm", request.zcut_ad_mm),
        ("ramp_pitch_mm", request.ramp_pitch_mm),
    ] {
        if let Some(x) = value {
            v.positive(field, x);
        }
    }
    if let Some(a) = request.allowance_mm {
        v.non_negative("allowance_mm", a);
    }
    v.check(
        request.loop_radius_mm.is_none() || request.loop_size == Some(LoopSizeInput::Fixed),
        "loop_radius_mm",
        "only with loop_size: fixed",
    );
    if let Some(z) = request.safe_z {
        v.finite("safe_z", z);
        v.check(z > request.z_top, "safe_z", "must be above z_top");
    }
    if let Some(a) = request.alpha_limit_deg {
        v.within("alpha_limit_deg", a, 5.0, 179.0);
    }
    if let Some(a) = request.class_a_ratio {
        v.within("class_a_ratio", a, CLASS_A_RATIO_MIN, CLASS_A_RATIO_MAX);
    }
    if let Some(s) = request.sample_spacing_mm {
        v.within("sample_spacing_mm", s, 1e-3, 1.0);
    }
    for (name, c) in [("roughing", request.roughing), ("grooving", request.grooving)] {
        if let Some(c) = c {
            for (field, x) in
                [("spindle_rpm", c.spindle_rpm), ("fz_mm", c.fz_mm), ("rd_mm", c.rd_mm), ("ad_mm", c.ad_mm)]
            {
                v.positive(&format!("{name}.{field}"), x);
            }
        }
    }
    request.output.validate(v);
}

/// Reads the pocket; errors name `contour.outer[i]`, `contour.islands[k][i]` or `dxf`.
fn read_pocket(request: &TrochoidsRequest) -> Result<Pocket, ApiError> {
    match (&request.contour, &request.dxf) {
        (Some(c), None) => read_contour("contour", c),
        (None, Some(text)) => read_dxf(None, text),
        _ => Err(ApiError::field("contour", "give exactly one of contour and dxf")),
    }
}

/// Resolves the request (the tool, material, machine and conditions) and reads its pocket
/// and program, adding every fault to `faults`; then, when it has none, checks the plan as
/// the core will make it.
pub async fn prepare(
    pool: &Pool,
    request: TrochoidsRequest,
    faults: &mut Validator,
) -> Result<Option<TrochoidsPrepared>, ApiError> {
    let refs = path_job_refs!(request, request.machine_id, None);
    let resolved = resolve(pool, &refs, faults).await?;
    // An unknown tool's radius is not the program's fault: it is read by radius 0.
    let radius_mm = resolved.as_ref().map_or(0.0, |r| r.prepared.tool.geometry.diameter_mm / 2.0);
    let prepared = match resolved {
        Some(resolved) => resolve_conditions(pool, &request, resolved, faults).await?,
        None => None,
    };
    let checked = prepared.clone();
    off_runtime_with(faults, move |faults| {
        let read = read_inputs(&request, radius_mm, faults)?;
        if let (Some(prepared), Some((pocket, path))) = (&checked, read) {
            if !faults.has_errors() {
                faults.take(check_plan(&pocket, &spec(&request, prepared), path.as_ref()))?;
            }
        }
        Ok(())
    })
    .await?;
    Ok(prepared)
}

/// The roughing and grooving conditions of a request whose rows resolved, adding every
/// fault to `faults`.
async fn resolve_conditions(
    pool: &Pool,
    request: &TrochoidsRequest,
    resolved: Resolved,
    faults: &mut Validator,
) -> Result<Option<TrochoidsPrepared>, ApiError> {
    let Resolved { prepared: base, standard, machine_max_feed_mm_min, machine_max_spindle_rpm } = resolved;
    // The grooving conditions default to the roughing ones: a fault in either leaves
    // both unjudged.
    if faults.touched("roughing") || faults.touched("grooving") {
        return Ok(None);
    }
    let (tool_id, material_id) = (base.tool.id, base.material.id);
    let row = |op: Operation| async move { lookup::standard_conditions(pool, tool_id, material_id, op).await };
    let rough_row = row(Operation::RoughSideCutting).await?;
    let (roughing, roughing_source) = match (request.roughing, rough_row, &standard) {
        (Some(c), _, _) => (c.into(), "request".to_string()),
        (None, Some(r), _) => (r.data.conditions(), format!("standard conditions {} (rough_side_cutting)", r.id)),
        (None, None, Some(s)) => (s.data.conditions(), format!("standard conditions {} (standard_side_cutting)", s.id)),
        (None, None, None) => {
            faults.fail(
                "roughing",
                format!(
                    "no rough or standard side-cutting conditions for tool {tool_id} in {}: give roughing",
                    base.material.name
                ),
            );
            return Ok(None);
        }
    };
    let (grooving, grooving_source) = match (request.grooving, row(Operation::TrochoidalGrooving).await?) {
        (Some(c), _) => (c.into(), "request".to_string()),
        (None, Some(r)) => (r.data.conditions(), format!("standard conditions {} (trochoidal_grooving)", r.id)),
        (None, None) => (roughing, roughing_source.clone()),
    };
    let flutes = base.tool.geometry.flutes;
    for (name, c, source) in [("roughing", roughing, &roughing_source), ("grooving", grooving, &grooving_source)] {
        faults.take(within_machine(name, &c, source, flutes, (machine_max_spindle_rpm, machine_max_feed_mm_min)))?;
    }
    let limits = Some(machine_limits(pool, base.machine.id).await?);
    // The costs before and after are figures of the result, not a condition of the job: a
    // tool without tool-life data gets none, and no fault.
    let cost = resolve_cost(pool, Some(&base), standard.as_ref(), None, None, &mut Validator::new()).await?;
    Ok(Some(TrochoidsPrepared { base, roughing, roughing_source, grooving, grooving_source, limits, cost }))
}

/// Refuses conditions (`name`, from `source`) whose spindle speed or feed
/// (fz · flutes · S) is above the machine's `(max rpm, max feed mm/min)`.
fn within_machine(
    name: &str,
    c: &CuttingConditions,
    source: &str,
    flutes: u32,
    (max_rpm, max_feed): (f64, f64),
) -> Result<(), ApiError> {
    let from = if source == "request" { String::new() } else { format!(" (from {source})") };
    if c.spindle_rpm > max_rpm {
        let reason = format!("{} min⁻¹{from} is above the machine's maximum of {max_rpm} min⁻¹", c.spindle_rpm);
        return Err(ApiError::field(format!("{name}.spindle_rpm"), reason));
    }
    let feed = feed_mm_min(c.fz_mm, flutes, c.spindle_rpm);
    if feed > max_feed {
        let reason =
            format!("gives a feed of {feed:.0} mm/min{from}, above the machine's maximum of {max_feed} mm/min");
        return Err(ApiError::field(format!("{name}.fz_mm"), reason));
    }
    Ok(())
}

/// Reads the pocket and the program (if any, by the tool's `radius_mm`), each on its own,
/// adding every fault to `faults`; a pocket or program an earlier stage refused is not
/// read.
fn read_inputs(
    request: &TrochoidsRequest,
    radius_mm: f64,
    faults: &mut Validator,
) -> Result<Option<(Pocket, Option<Toolpath>)>, ApiError> {
    let pocket = match faults.refused_any(&["contour", "dxf"]) {
        true => None,
        false => faults.take(read_pocket(request))?,
    };
    let path = match &request.program {
        None => Some(None),
        Some(_) if faults.refused_any(&["program.gcode", "program.moves"]) => None,
        Some(program) => {
            let context = ProgramContext { tool_radius_mm: Some(radius_mm), stock_top_mm: Some(request.z_top) };
            faults.take(read_program(program, context))?.map(|read| Some(read.path))
        }
    };
    Ok(pocket.zip(path))
}

/// The insertion a request asks for, with the conditions it resolved to.
fn spec(request: &TrochoidsRequest, prepared: &TrochoidsPrepared) -> InsertionSpec {
    let tool: crate::core::tool::EndMill = prepared.base.tool.geometry.into();
    let mut spec = InsertionSpec::new(tool, prepared.roughing, prepared.grooving, request.z_top, request.z_bottom);
    spec.safe_z_mm = request.safe_z.unwrap_or(request.z_top + DEFAULT_SAFE_HEIGHT_ABOVE_TOP_MM);
    spec.rapid_mm_min = prepared.base.rapid_mm_min;
    if let Some(a) = request.allowance_mm {
        spec.allowance_mm = a;
    }
    if let Some(a) = request.alpha_limit_deg {
        spec.alpha_limit_deg = a;
    }
    if let Some(a) = request.class_a_ratio {
        spec.class_a_ratio = a;
    }
    if request.loop_size == Some(LoopSizeInput::Fixed) {
        let rho_mm = request.loop_radius_mm.unwrap_or_else(|| default_loop_radius_mm(tool.radius_mm()));
        spec.loop_size = LoopSize::Fixed { rho_mm };
    }
    spec.pitch_mm = request.pitch_mm;
    if let Some(ad) = request.zcut_ad_mm {
        spec.zcut_ad_mm = ad;
    }
    spec.ramp_pitch_mm = request.ramp_pitch_mm;
    if let Some(d) = request.direction {
        spec.direction = d;
    }
    spec.sample_spacing_mm = request.sample_spacing_mm;
    // The return halves of the loops and the links through cleared space run at the air
    // feed, which the machine's largest feed caps.
    if let Some(max) = prepared.base.max_feed_mm_min {
        spec.air_feed_mm_min = Some(spec.air_feed_mm_min().min(max));
    }
    spec
}

/// Replaces the move numbers (1-based) of `lines` by the lines of the text written from
/// those moves (`move_lines`).
fn to_written_lines(lines: &mut [u32], move_lines: &[u32]) {
    for line in lines {
        if let Some(&written) = (*line as usize).checked_sub(1).and_then(|i| move_lines.get(i)) {
            *line = written;
        }
    }
}

/// The program the insertion changed, with the base path's samples relabelled by its
/// lines (so that the drawing's overloads of the base path name them): the G-code sent,
/// as it was (its moves carry its lines already); else the path sent as moves or
/// generated, written with the job's output options (its samples carry move numbers,
/// which become the written lines).
fn base_program(request: &TrochoidsRequest, plan: &mut InsertionPlan, options: &WriterOptions) -> String {
    if let Some(text) = request.program.as_ref().and_then(|p| p.gcode.clone()) {
        return text;
    }
    let written = write_program_mapped(&plan.drawing.base_path, options);
    to_written_lines(&mut plan.drawing.base_samples.line, &written.move_lines);
    plan.drawing.base_path = with_lines(&plan.drawing.base_path, &written.move_lines);
    written.text
}

/// What a run makes: the result, the program, the base program, the drawing and the stock
/// the finished program leaves.
pub type Run = (TrochoidsResult, String, String, Scene, KeptStock);

/// Plans the insertion and writes the program (and the base program).
pub fn run(
    request: TrochoidsRequest,
    prepared: TrochoidsPrepared,
    progress: &dyn Progress,
    stock_memory_bytes: usize,
) -> Result<Run, CoreError> {
    let reread = |e: ApiError| CoreError::invalid("input", e.to_string());
    let radius_mm = prepared.base.tool.geometry.diameter_mm / 2.0;
    let (pocket, path) = Validator::collect(|faults| read_inputs(&request, radius_mm, faults)).map_err(reread)?;
    let spec = InsertionSpec { stock_memory_bytes, ..spec(&request, &prepared) };
    // With costs, the wear of the paths before and after is counted on the insertion's own
    // simulations of them.
    let simulation = analysis_spec(&pocket, &spec);
    let (mut plan, counted, stack) = match prepared.cost.as_ref() {
        Some(setup) => {
            setup.life.validate()?;
            let mut observer = WearObserver::new(&setup.life, simulation.tool.flutes, simulation.default_spindle_rpm);
            let (plan, stack) = plan_insertion_kept(&pocket, &spec, path.as_ref(), Some(&mut observer), progress)?;
            let counted = observer.finish(&plan);
            (plan, Some((setup, counted)), stack)
        }
        None => {
            let (plan, stack) = plan_insertion_kept(&pocket, &spec, path.as_ref(), None, progress)?;
            (plan, None, stack)
        }
    };
    let options = request.output.to_writer(&prepared.base);
    let written = write_program_mapped(&plan.toolpath, &options);
    let base = base_program(&request, &mut plan, &options);
    // The planned path's samples carry its move numbers: the drawing names the lines of
    // the job's program.
    to_written_lines(&mut plan.drawing.planned_samples.line, &written.move_lines);
    // The drawing's moves name the lines of the program served too (a copy: the overloads
    // of the result are found by move number).
    let lines = with_lines(&plan.toolpath, &written.move_lines);
    let numbered = std::mem::replace(&mut plan.toolpath, lines);
    // The drawing is made beside the stock the finished program leaves, as its
    // verification simulated it: a pocket's cavity, which runs on down in its outline.
    let (scene, kept) = std::thread::scope(|scope| {
        let scene = scope.spawn(|| insertion_scene(&pocket, &spec, &plan));
        let kept = keep(&stack, &simulation, None, Floor::Unbounded, true);
        (scene.join().unwrap_or_else(|panic| std::panic::resume_unwind(panic)), kept)
    });
    let kept = kept?;
    plan.toolpath = numbered;
    let figures = match prepared.limits.as_ref() {
        Some(limits) => Some(ChangeFigures::of(&plan, limits, counted)?),
        None => None,
    };
    Ok((TrochoidsResult::new(prepared, path.is_some(), &written, plan, figures), written.text, base, scene, kept))
}

/// The `trochoids` job kind.
pub struct Trochoids;

impl JobKindSpec for Trochoids {
    const KIND: JobKind = JobKind::Trochoids;
    const PATH: &'static str = "/v1/trochoids";
    const OPERATION_ID: &'static str = "insertTrochoids";
    const SUMMARY: &'static str =
        "Inserts trochoid cycles where a pocket's path overloads the tool (job kind `trochoids`).";
    const DESCRIPTION: &'static str = "Takes a pocket contour (or DXF) and optionally a path to modify; without one, the contour-parallel roughing path is generated (Rd and Ad of the rough side-cutting conditions). The path is simulated; its samples above the engagement limit are mapped onto the medial axis; each critical stretch gets trochoids (classes A and B, the pitch reduced where the limit needs it, entered by a helix) or z-cut division (class C, seed 004 §2.3); the path is cut where the trochoids cleared and re-linked; and the result is simulated again. The result holds the axis with its classes, the treatments with the area each removes, the checks and the path as JSON moves; the NC program is at `GET /v1/jobs/{id}/program`.";
    const REFUSES: &'static str =
        "Every fault of the request, in one problem: each refused field, each row it names that is not in the database, the NC program's faults (line, column and word) and the pocket's (contour vertex or DXF)";
    type Request = TrochoidsRequest;
    type Prepared = TrochoidsPrepared;
    type Output = TrochoidsResult;

    fn check(request: &TrochoidsRequest, v: &mut Validator) {
        check_request(request, v)
    }

    async fn prepare(
        submission: &Submission<'_>,
        request: TrochoidsRequest,
        faults: &mut Validator,
    ) -> Result<Option<TrochoidsPrepared>, ApiError> {
        prepare(submission.pool, request, faults).await
    }

    fn run(
        request: TrochoidsRequest,
        prepared: TrochoidsPrepared,
        progress: &dyn Progress,
        stock_memory_bytes: usize,
    ) -> Result<Produced<TrochoidsResult>, CoreError> {
        let (result, program, base, scene, kept) = run(request, prepared, progress, stock_memory_bytes)?;
        Ok(Produced { base_program: Some(base), ..Produced::programmed(result, program, scene).keeping(kept) })
    }
}
