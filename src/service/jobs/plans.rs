//! The `plan` job (seed 002 Fig. 1 and Fig. 7, §2.6; seed 004 Table 1; MODEL.md §8–11): a
//! cavity in, the cheapest complete roughing program out, with the table of candidate tools,
//! a breakdown per layer and step, the tuning to about 90 % of one tool, and the comparison
//! with the conventional ball-end baseline.

use super::inputs::{read_contour, read_dxf, ContourInput};
use super::kind::off_runtime_with;
use super::output::{OutputOptions, DEFAULT_SAFE_HEIGHT_ABOVE_TOP_MM};
use super::plan_rows;
use super::plan_stair_step::StairStepInput;
use super::plans_result::PlanResult;
use super::setup::NamedRef;
use crate::core::analysis::kept::KeptStock;
use crate::core::analysis::DEFAULT_STOCK_MEMORY_BYTES;
use crate::core::conditions::CuttingConditions;
use crate::core::drawing::process_scene::{process_scene, WrittenLines};
use crate::core::drawing::scene::Scene;
use crate::core::insertion::DEFAULT_INSERTION_ALPHA_LIMIT_DEG;
use crate::core::kinematics::MachineLimits;
use crate::core::nc::{write_program_mapped, DEFAULT_TOOL_NUMBER};
use crate::core::process::{
    check_process, joined_program, plan_process, BaselineSpec, Cavity, CavityInput, CavityLayer, ProcessOptions,
    StairStepSpec, ToolCandidate, DEFAULT_MAX_FORCE_FACTOR, DEFAULT_TARGET_CONSUMPTION, MAX_CAVITY_LAYERS,
};
use crate::core::progress::Progress;
use crate::core::standard_cut::standard_cut;
use crate::core::tool::{EndMill, ToolType};
use crate::core::tool_life::ToolLifeModel;
use crate::core::CoreError;
use crate::service::error::{ApiError, Validator};
use crate::service::jobs::kind::{JobKindSpec, Produced, Submission};
use crate::service::jobs::model::JobKind;
use crate::service::resources::Source;
use crate::service::store::Pool;
use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

/// The candidate diameters of seed 002 §2.6 (a), mm.
pub const CANDIDATE_DIAMETER_RANGE_MM: (f64, f64) = (6.0, 16.0);
/// The baseline's ball end mill: R5 (seed 004 §3.3), mm.
pub const BASELINE_BALL_DIAMETER_MM: f64 = 10.0;

/// One layer of the cavity.
#[derive(Debug, Clone, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct LayerInput {
    pub contour: ContourInput,
    pub z_top: f64,
    pub z_bottom: f64,
}

/// A cavity to rough: `layers` (z range and contour each, top first), or one `contour` (or
/// `dxf`) from `z_top` to `z_bottom`, which is cut in layers of the rough axial depth and a
/// last intermediate-rough layer. At most 100 layers, given or made for any candidate.
#[derive(Debug, Clone, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
#[schema(example = json!({
    "contour": {"outer": [[8, 0, 0.414214], [90, 0], [90, 62, 0.414214], [82, 70], [0, 70], [0, 8, 0.414214]]},
    "z_top": 0, "z_bottom": -12, "diameters_mm": [8, 10]
}))]
pub struct PlanRequest {
    pub contour: Option<ContourInput>,
    pub dxf: Option<String>,
    pub z_top: Option<f64>,
    pub z_bottom: Option<f64>,
    pub layers: Option<Vec<LayerInput>>,
    /// `square` (default) or `radius`: the flat end mills of `diameters_mm` and of the
    /// default range.
    pub tool_type: Option<ToolType>,
    /// Candidate diameters: the default tool of `tool_type` of each (default, when neither
    /// this nor `tool_ids` is given: the default tool of every diameter from 6 to 16 mm).
    pub diameters_mm: Option<Vec<f64>>,
    /// Candidate tools by id (flat end mills, square or radius), beside or instead of
    /// `diameters_mm`; a tool both name is one candidate.
    pub tool_ids: Option<Vec<i64>>,
    pub material_id: Option<i64>,
    /// Material name (default SKD61).
    pub material: Option<String>,
    pub machine_id: Option<i64>,
    pub cost_rates_id: Option<i64>,
    /// Engagement limit of the critical regions, deg (default 40).
    pub alpha_limit_deg: Option<f64>,
    /// Stock left on the walls, mm (default 0).
    pub allowance_mm: Option<f64>,
    /// Height of the moves over the workpiece, mm (default the top + 5).
    pub safe_z: Option<f64>,
    /// Simulation sample spacing, mm (default min(0.05, D/100)).
    pub sample_spacing_mm: Option<f64>,
    /// Tune the chosen tool to use `target_consumption` of its life (default true).
    pub tune: Option<bool>,
    /// Share of one tool's life to use, 0–1 (default 0.9, seed 002 §2.6).
    pub target_consumption: Option<f64>,
    /// Highest tuned force, times the standard force (default 2).
    pub max_force_factor: Option<f64>,
    /// Plan the conventional baseline (R5 ball, Ad 0.6) for the comparison (default true).
    pub baseline: Option<bool>,
    /// The stair-step roughing after the chosen tool's, where the layers are sections of a
    /// sloped wall or floor (`{}`: the R5 ball at its standard side cut; default none).
    pub stair_step: Option<StairStepInput>,
    #[serde(default)]
    pub output: OutputOptions,
}

/// One candidate as resolved from the database.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct CandidatePrepared {
    pub tool_id: i64,
    pub name: String,
    pub tool: EndMill,
    pub roughing: CuttingConditions,
    pub intermediate: CuttingConditions,
    pub grooving: CuttingConditions,
    pub force_model: crate::core::force_model::ForceModel,
    pub standard_force_n: f64,
    pub life_m: f64,
    pub gamma_table: Vec<(f64, f64)>,
    pub force_exponent: f64,
    pub standard_arc_length_mm: f64,
    pub standard_fz_mm: f64,
    pub min_feed_mm_min: f64,
    pub max_feed_mm_min: f64,
    pub tool_price: f64,
}

/// The baseline tool as resolved.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct BaselinePrepared {
    pub tool_id: i64,
    pub name: String,
    pub tool: EndMill,
    pub conditions: CuttingConditions,
    /// The `conventional_ball_roughing` row the conditions come from (absent in jobs stored
    /// before it was kept).
    #[serde(default)]
    pub conditions_row: Option<RowRef>,
    pub life_m: f64,
    pub gamma_table: Vec<(f64, f64)>,
    pub force_exponent: f64,
    pub tool_price: f64,
}

/// A database row a job's values come from: its id, and where its values come from.
#[derive(Debug, Clone, Serialize, Deserialize, ToSchema)]
pub struct RowRef {
    pub id: i64,
    pub source: Source,
    pub reference: String,
}

/// What the request resolved to.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct PlanPrepared {
    pub material: NamedRef,
    pub machine: NamedRef,
    pub limits: MachineLimits,
    pub cost_rates: NamedRef,
    pub machine_rate_per_hour: f64,
    pub currency: String,
    pub candidates: Vec<CandidatePrepared>,
    /// Tools of the type in the range the database cannot plan with, and why.
    pub skipped: Vec<String>,
    pub baseline: Option<BaselinePrepared>,
    /// The stair-step roughing's tool with its data (absent when the request asks for none,
    /// and in jobs stored before it was planned).
    #[serde(default)]
    pub stair_step: Option<CandidatePrepared>,
    /// For the program writer (the chosen tool is set at run time).
    pub writer_base: super::setup::PathSetup,
}

/// Most candidate diameters one plan may compare.
pub const MAX_PLAN_CANDIDATES: usize = 16;
/// Diameters closer than this are the same candidate, mm.
const DIAMETER_TOLERANCE_MM: f64 = 1e-6;

/// Checks the values of the request that need no database.
pub fn check_request(r: &PlanRequest, v: &mut Validator) {
    let single = r.contour.is_some() || r.dxf.is_some();
    v.check(single != r.layers.is_some(), "layers", "give either layers, or contour (or dxf) with z_top and z_bottom");
    v.check(!(r.contour.is_some() && r.dxf.is_some()), "contour", "give exactly one of contour and dxf");
    if single {
        match (r.z_top, r.z_bottom) {
            (Some(top), Some(bottom)) => {
                v.finite("z_top", top);
                v.finite("z_bottom", bottom);
                v.check(bottom < top, "z_bottom", "must be below z_top");
            }
            _ => v.check(false, "z_bottom", "z_top and z_bottom are needed with contour or dxf"),
        }
    }
    if let Some(layers) = &r.layers {
        v.check(!layers.is_empty(), "layers", "needs at least one layer");
        v.check(
            layers.len() <= MAX_CAVITY_LAYERS,
            "layers",
            format!("at most {MAX_CAVITY_LAYERS} layers, got {}", layers.len()),
        );
        for (i, l) in layers.iter().enumerate() {
            v.finite(&format!("layers[{i}].z_top"), l.z_top);
            v.finite(&format!("layers[{i}].z_bottom"), l.z_bottom);
            v.check(l.z_bottom < l.z_top, &format!("layers[{i}].z_bottom"), "must be below its z_top");
        }
    }
    v.check(
        !matches!(r.tool_type, Some(ToolType::Ball)),
        "tool_type",
        "the proposed strategy needs flat end mills: square or radius",
    );
    if let Some(ds) = &r.diameters_mm {
        v.check(!ds.is_empty(), "diameters_mm", "needs at least one diameter");
        for (i, d) in ds.iter().enumerate() {
            v.positive(&format!("diameters_mm[{i}]"), *d);
            if let Some(k) = ds[..i].iter().position(|e| (e - d).abs() <= DIAMETER_TOLERANCE_MM) {
                v.check(false, &format!("diameters_mm[{i}]"), format!("repeats diameters_mm[{k}]"));
            }
        }
    }
    if let Some(ids) = &r.tool_ids {
        v.check(!ids.is_empty(), "tool_ids", "needs at least one tool id");
        for (i, id) in ids.iter().enumerate() {
            if let Some(k) = ids[..i].iter().position(|e| e == id) {
                v.check(false, &format!("tool_ids[{i}]"), format!("repeats tool_ids[{k}]"));
            }
        }
    }
    let named = r.diameters_mm.as_ref().map_or(0, Vec::len) + r.tool_ids.as_ref().map_or(0, Vec::len);
    v.check(
        named <= MAX_PLAN_CANDIDATES,
        if r.tool_ids.is_some() { "tool_ids" } else { "diameters_mm" },
        format!("at most {MAX_PLAN_CANDIDATES} candidates (diameters_mm and tool_ids together), got {named}"),
    );
    if let Some(a) = r.alpha_limit_deg {
        v.within("alpha_limit_deg", a, 5.0, 179.0);
    }
    if let Some(a) = r.allowance_mm {
        v.non_negative("allowance_mm", a);
    }
    if let Some(z) = r.safe_z {
        v.finite("safe_z", z);
    }
    if let Some(s) = r.sample_spacing_mm {
        v.within("sample_spacing_mm", s, 1e-3, 1.0);
    }
    if let Some(t) = r.target_consumption {
        v.within("target_consumption", t, 0.05, 1.0);
    }
    if let Some(k) = r.max_force_factor {
        v.within("max_force_factor", k, 1.0, 4.0);
    }
    if let Some(step) = &r.stair_step {
        super::plan_stair_step::check(step, v);
        // The step's tool is called as the roughing tool's number + 1.
        if step.enabled != Some(false) {
            v.check(
                r.output.tool_number.is_none_or(|t| t < super::output::MAX_TOOL_NUMBER),
                "output.tool_number",
                format!(
                    "below {} with a stair step, whose tool is called as the next number",
                    super::output::MAX_TOOL_NUMBER
                ),
            );
        }
    }
    r.output.validate(v);
}

/// The cavity of the request: its layers (each read on its own), or its contour and
/// depth, adding every fault to `faults`; a part an earlier stage refused is not read.
fn read_cavity(r: &PlanRequest, faults: &mut Validator) -> Result<Option<CavityInput>, ApiError> {
    // A fault of `layers` itself says that the cavity is not given in one of the two ways.
    if faults.refused("layers") {
        return Ok(None);
    }
    if let Some(layers) = &r.layers {
        let mut read = Vec::with_capacity(layers.len());
        for (i, l) in layers.iter().enumerate() {
            let field = format!("layers[{i}].contour");
            let pocket = if faults.refused(&field) { None } else { faults.take(read_contour(&field, &l.contour))? };
            read.push(pocket.map(|pocket| CavityLayer { pocket, z_top_mm: l.z_top, z_bottom_mm: l.z_bottom }));
        }
        let layers = read.into_iter().collect::<Option<Vec<_>>>();
        return Ok(layers.map(|layers| CavityInput::Layers(Cavity { layers })));
    }
    if faults.refused_any(&["contour", "dxf"]) {
        return Ok(None);
    }
    let pocket = match (&r.contour, &r.dxf) {
        (Some(c), None) => read_contour("contour", c),
        (None, Some(text)) => read_dxf(None, text),
        _ => Err(ApiError::field("contour", "give exactly one of contour and dxf")),
    };
    let depth = |pocket| CavityInput::Depth {
        pocket,
        z_top_mm: r.z_top.unwrap_or(0.0),
        z_bottom_mm: r.z_bottom.unwrap_or(0.0),
    };
    Ok(faults.take(pocket)?.map(depth))
}

/// Resolves the request (the candidates, the baseline, the machine and the rates) and
/// reads its cavity, adding every fault to `faults`; then, when it has none, checks the
/// cavity against the candidates as the core will plan it.
pub async fn prepare(
    pool: &Pool,
    request: PlanRequest,
    faults: &mut Validator,
) -> Result<Option<PlanPrepared>, ApiError> {
    let prepared = plan_rows::resolve(pool, &request, faults).await?;
    let checked = prepared.clone();
    off_runtime_with(faults, move |faults| {
        let cavity = read_cavity(&request, faults)?;
        if let (Some(prepared), Some(cavity)) = (&checked, cavity) {
            if !faults.has_errors() {
                let (candidates, options) = build(&request, prepared, &cavity, DEFAULT_STOCK_MEMORY_BYTES);
                faults.take(check_process(&cavity, &candidates, &options))?;
            }
        }
        Ok(())
    })
    .await?;
    Ok(prepared)
}

type Built = (Vec<ToolCandidate>, ProcessOptions);

/// A tool as the core plans with it.
fn candidate(c: &CandidatePrepared) -> ToolCandidate {
    ToolCandidate {
        name: c.name.clone(),
        tool: c.tool,
        roughing: c.roughing,
        intermediate: c.intermediate,
        grooving: c.grooving,
        force_model: c.force_model,
        standard_force_n: c.standard_force_n,
        life: life_model(
            c.life_m,
            &c.gamma_table,
            c.force_exponent,
            c.standard_arc_length_mm,
            c.standard_fz_mm,
            Some(c.standard_force_n),
        ),
        min_feed_mm_min: c.min_feed_mm_min,
        max_feed_mm_min: c.max_feed_mm_min,
        tool_price: c.tool_price,
    }
}

fn life_model(life_m: f64, gamma: &[(f64, f64)], k: f64, arc_mm: f64, fz_mm: f64, force: Option<f64>) -> ToolLifeModel {
    ToolLifeModel {
        life_m,
        gamma_table: gamma.to_vec(),
        force_exponent: k,
        standard_arc_length_mm: arc_mm,
        standard_fz_mm: fz_mm,
        standard_force_n: force,
    }
}

/// The candidates and options of a plan of `cavity`, its simulations each within
/// `stock_memory_bytes`.
fn build(r: &PlanRequest, p: &PlanPrepared, cavity: &CavityInput, stock_memory_bytes: usize) -> Built {
    let candidates = p.candidates.iter().map(candidate).collect();
    let options = ProcessOptions {
        alpha_limit_deg: r.alpha_limit_deg.unwrap_or(DEFAULT_INSERTION_ALPHA_LIMIT_DEG),
        allowance_mm: r.allowance_mm.unwrap_or(0.0),
        safe_z_mm: r.safe_z.unwrap_or(cavity.whole().top_mm() + DEFAULT_SAFE_HEIGHT_ABOVE_TOP_MM),
        sample_spacing_mm: r.sample_spacing_mm,
        machine: p.limits,
        machine_rate_per_hour: p.machine_rate_per_hour,
        currency: p.currency.clone(),
        target_consumption: r.target_consumption.unwrap_or(DEFAULT_TARGET_CONSUMPTION),
        tune: r.tune.unwrap_or(true),
        max_force_factor: r.max_force_factor.unwrap_or(DEFAULT_MAX_FORCE_FACTOR),
        max_feed_change_per_mm: Some(crate::core::feed::plan::DEFAULT_MAX_FEED_CHANGE_PER_MM),
        stock_memory_bytes,
    };
    (candidates, options)
}

/// Plans the cavity and writes the chosen tool's program.
pub fn run(
    request: PlanRequest,
    prepared: PlanPrepared,
    progress: &dyn Progress,
    stock_memory_bytes: usize,
) -> Result<PlanOutput, CoreError> {
    let reread = |e: ApiError| CoreError::invalid("input", e.to_string());
    let cavity = Validator::collect(|faults| read_cavity(&request, faults)).map_err(reread)?;
    let (candidates, options) = build(&request, &prepared, &cavity, stock_memory_bytes);
    // The ball's life (assumed as the straight tool's, MODEL.md §5) counts against its own
    // conventional roughing cut.
    let baseline = prepared
        .baseline
        .as_ref()
        .map(|b| -> Result<BaselineSpec, CoreError> {
            let conditions = b.conditions;
            let arc = standard_cut(&b.tool, conditions, None)?.arc_length_mm;
            Ok(BaselineSpec {
                name: b.name.clone(),
                tool: b.tool,
                conditions,
                life: life_model(b.life_m, &b.gamma_table, b.force_exponent, arc, conditions.fz_mm, None),
                tool_price: b.tool_price,
            })
        })
        .transpose()?;
    // The stair step's tool follows the roughing tool's number.
    let rough_tool = request.output.tool_number.unwrap_or(DEFAULT_TOOL_NUMBER);
    let stair_step = prepared
        .stair_step
        .as_ref()
        .map(|c| StairStepSpec { candidate: candidate(c), tool_number: rough_tool.saturating_add(1) });
    let plan = plan_process(&cavity, &candidates, &options, baseline.as_ref(), stair_step.as_ref(), progress)?;
    let chosen = &prepared.candidates[plan.chosen];
    let mut writer_base = prepared.writer_base.clone();
    writer_base.tool.id = chosen.tool_id;
    writer_base.tool.name = chosen.name.clone();
    writer_base.tool.geometry = chosen.tool.into();
    let whole = match &plan.stair_step {
        Some(step) => joined_program(&plan.evaluation.program, &step.program, options.safe_z_mm),
        None => plan.evaluation.program.clone(),
    };
    let written = write_program_mapped(&whole, &request.output.to_writer(&writer_base));
    // The baseline's program: the same output options, with the ball, its name and its speed.
    let baseline = plan.baseline.as_ref().zip(prepared.baseline.as_ref()).map(|(b, p)| {
        let mut writer_base = prepared.writer_base.clone();
        writer_base.tool.id = p.tool_id;
        writer_base.tool.name = p.name.clone();
        writer_base.tool.geometry = p.tool.into();
        writer_base.default_spindle_rpm = Some(p.conditions.spindle_rpm);
        write_program_mapped(&b.program, &request.output.to_writer(&writer_base))
    });
    // The drawing's vertices name the lines of the programs served (the plan's, the baseline's).
    let lines =
        WrittenLines { program: &written.move_lines, baseline: baseline.as_ref().map(|b| b.move_lines.as_slice()) };
    let scene = process_scene(&cavity.whole(), &plan, lines);
    let baseline_program = baseline.map(|b| b.text);
    let result = PlanResult::new(&prepared, &plan, &written, baseline_program.as_deref().unwrap_or_default());
    let stock = plan.stock.map(|s| s.stock);
    Ok(PlanOutput { result, program: written.text, baseline_program, scene, stock })
}

/// What a plan job hands back: its result, the chosen tool's program, the baseline's program
/// (when it has a baseline), the drawing scene and the stock it leaves.
pub struct PlanOutput {
    pub result: PlanResult,
    pub program: String,
    pub baseline_program: Option<String>,
    pub scene: Scene,
    /// The stock the chosen plan leaves in the cavity.
    pub stock: Option<KeptStock>,
}

/// The `plan` job kind.
pub struct Plan;

impl JobKindSpec for Plan {
    const KIND: JobKind = JobKind::Plan;
    const PATH: &'static str = "/v1/plans";
    const OPERATION_ID: &'static str = "planCavity";
    const SUMMARY: &'static str =
        "Plans a cavity from end to end (job kind `plan`; seed 002 Fig. 1 and §2.6, seed 004 Table 1).";
    const DESCRIPTION: &'static str = "For each candidate flat end mill (6–16 mm from the database, or `diameters_mm`) that can reach the whole cavity, every layer is planned (helical entries, spiral hole expansion, trochoidal grooving of the critical regions, z-cut division, contour-parallel rough side cutting; the last layer intermediate-rough), the feeds are optimised for a constant cutting force, and time (nominal and kinematic), tool life and cost are estimated. The cheapest complete candidate is chosen and its force target tuned so the job uses about 90 % of one tool. The conventional ball-end baseline is planned for the comparison. The NC program is at `GET /v1/jobs/{id}/program`. Progress is reported while it runs; `DELETE` cancels it.";
    const REFUSES: &'static str =
        "Every fault of the request, in one problem: each refused field, each diameter, tool id or row it names that is not in the database or cannot be planned with, and the contour's faults";
    type Request = PlanRequest;
    type Prepared = PlanPrepared;
    type Output = PlanResult;

    fn check(request: &PlanRequest, v: &mut Validator) {
        check_request(request, v)
    }

    async fn prepare(
        submission: &Submission<'_>,
        request: PlanRequest,
        faults: &mut Validator,
    ) -> Result<Option<PlanPrepared>, ApiError> {
        prepare(submission.pool, request, faults).await
    }

    fn run(
        request: PlanRequest,
        prepared: PlanPrepared,
        progress: &dyn Progress,
        stock_memory_bytes: usize,
    ) -> Result<Produced<PlanResult>, CoreError> {
        let out = run(request, prepared, progress, stock_memory_bytes)?;
        Ok(Produced {
            result: out.result,
            program: Some(out.program),
            baseline_program: out.baseline_program,
            base_program: None,
            scene: Some(out.scene),
            stock: out.stock,
        })
    }
}
