//! The scene of a process plan (seed 002 §2.6, seed 004 Table 1): the cavity's outlines,
//! the chosen tool's program by layer, coloured by feed and tool-life consumption, and
//! charts of the candidates, of time and cost per operation, and of the baseline.

use super::charts::bar_chart;
use super::outlines::pocket_outlines;
use super::paths::{move_feeds, traced, wear_rates, with_lines};
use super::scene::{BarGroup, ChartBody, ChartData, LayerInfo, Quantity, Scene};
use crate::core::process::{CandidateStatus, Cavity, ProcessPlan, Step};

/// The chosen tool's program.
pub const PROGRAM_PATH: &str = "program";
/// The conventional ball-end baseline's program.
pub const BASELINE_PATH: &str = "baseline";
/// The stair-step roughing, the plan's program's last part.
pub const STAIR_STEP_PATH: &str = "stair_step";

/// The lines of the written programs, per move (1-based): the plan's program and its
/// baseline's ([`crate::core::nc::WrittenProgram::move_lines`]), so that the drawing's
/// vertices name the lines of the programs served. The plan's program holds the roughing's
/// moves first and the stair step's last.
#[derive(Debug, Clone, Copy, Default)]
pub struct WrittenLines<'a> {
    pub program: &'a [u32],
    pub baseline: Option<&'a [u32]>,
}

fn status_name(status: CandidateStatus) -> &'static str {
    match status {
        CandidateStatus::Chosen => "chosen",
        CandidateStatus::Planned => "planned",
        CandidateStatus::CannotReach => "cannot reach",
        CandidateStatus::Incomplete => "incomplete",
        CandidateStatus::Unplannable => "unplannable",
        CandidateStatus::ScreenedOut => "screened out",
    }
}

/// Cost of each candidate (machine and tool), the chosen one highlighted.
fn candidates_chart(plan: &ProcessPlan, currency: &str) -> ChartData {
    let c = &plan.candidates;
    let mut chart = bar_chart(
        "candidates",
        "Candidate end mills: cost of the job at the standard force",
        &format!("cost, {currency}"),
        c.iter().map(|c| c.name.clone()).collect(),
        vec![
            BarGroup { name: "machine".to_string(), values: c.iter().map(|c| c.machine_cost).collect() },
            BarGroup { name: "tool".to_string(), values: c.iter().map(|c| c.tool_cost).collect() },
        ],
    );
    if let ChartBody::Bars(b) = &mut chart.body {
        b.notes = c.iter().map(|c| status_name(c.status).to_string()).collect();
        b.highlight = Some(plan.chosen);
    }
    chart
}

/// Time and cost per operation (step), over all layers; a step's cost shares the
/// machine cost by its time and the tool cost by its consumption.
fn step_charts(plan: &ProcessPlan, currency: &str) -> [ChartData; 2] {
    let mut steps: Vec<(Step, f64, f64, f64)> = Vec::new();
    for layer in &plan.evaluation.layers {
        for s in &layer.steps {
            let f = &s.figures;
            match steps.iter_mut().find(|(step, ..)| *step == s.step) {
                Some(acc) => {
                    acc.1 += f.nominal_time_min;
                    acc.2 += f.kinematic_time_min;
                    acc.3 += f.consumption;
                }
                None => steps.push((s.step, f.nominal_time_min, f.kinematic_time_min, f.consumption)),
            }
        }
    }
    steps.sort_by_key(|s| s.0);
    let names: Vec<String> = steps.iter().map(|s| Step::name(s.0).to_string()).collect();
    let time_total: f64 = steps.iter().map(|s| s.2).sum();
    let worn_total: f64 = steps.iter().map(|s| s.3).sum();
    let cost = &plan.evaluation.cost;
    let share = |part: f64, whole: f64| if whole > 0.0 { part / whole } else { 0.0 };
    [
        bar_chart(
            "time",
            "Machining time per operation",
            "time, min",
            names.clone(),
            vec![
                BarGroup { name: "nominal".to_string(), values: steps.iter().map(|s| Some(s.1)).collect() },
                BarGroup { name: "kinematic".to_string(), values: steps.iter().map(|s| Some(s.2)).collect() },
            ],
        ),
        bar_chart(
            "cost",
            "Cost per operation",
            &format!("cost, {currency}"),
            names,
            vec![
                BarGroup {
                    name: "machine".to_string(),
                    values: steps.iter().map(|s| Some(cost.machine * share(s.2, time_total))).collect(),
                },
                BarGroup {
                    name: "tool".to_string(),
                    values: steps.iter().map(|s| Some(cost.tool * share(s.3, worn_total))).collect(),
                },
            ],
        ),
    ]
}

/// The plan against the conventional ball-end baseline: kinematic time and cost.
fn baseline_chart(plan: &ProcessPlan, currency: &str) -> Option<ChartData> {
    let b = plan.baseline.as_ref()?;
    let chosen = &plan.candidates[plan.chosen].name;
    Some(bar_chart(
        "baseline",
        "The plan against the conventional ball-end roughing",
        &format!("kinematic time, min; cost, {currency}"),
        vec![chosen.clone(), b.tool.clone()],
        vec![
            BarGroup {
                name: "time, min".to_string(),
                values: vec![Some(plan.evaluation.total.kinematic_time_min), Some(b.figures.kinematic_time_min)],
            },
            BarGroup {
                name: format!("cost, {currency}"),
                values: vec![Some(plan.evaluation.cost.total), Some(b.cost.total)],
            },
        ],
    ))
}

/// The scene of `plan` for `cavity`: the baseline's program (when planned), then the
/// chosen tool's program, their vertices named by the lines written (`lines`; every
/// layer of the plan is a part of its one program, so a layer's vertices name lines of it).
pub fn process_scene(cavity: &Cavity, plan: &ProcessPlan, lines: WrittenLines) -> Scene {
    let layers: Vec<LayerInfo> = plan
        .layers
        .iter()
        .map(|l| LayerInfo {
            name: format!("layer {} (z {:.3} to {:.3})", l.index + 1, l.z_bottom_mm, l.z_top_mm),
            z_top: l.z_top_mm,
            z_bottom: l.z_bottom_mm,
        })
        .collect();
    let program = with_lines(&plan.evaluation.program, lines.program);
    let path = traced(
        PROGRAM_PATH,
        &program,
        None,
        vec![
            (Quantity::Feed, move_feeds(&program)),
            (Quantity::Wear, wear_rates(&program, &plan.evaluation.move_consumption)),
        ],
        &layers,
    );
    let baseline = plan.baseline.as_ref().map(|b| {
        let program = with_lines(&b.program, lines.baseline.unwrap_or_default());
        traced(BASELINE_PATH, &program, None, vec![(Quantity::Feed, move_feeds(&program))], &layers)
    });
    // The step's moves are the written program's last.
    let stair_step = plan.stair_step.as_ref().map(|s| {
        let first = lines.program.len().saturating_sub(s.program.moves.len());
        let program = with_lines(&s.program, &lines.program[first..]);
        traced(STAIR_STEP_PATH, &program, None, vec![(Quantity::Feed, move_feeds(&program))], &layers)
    });
    let mut outlines = Vec::new();
    for (k, layer) in cavity.layers.iter().enumerate() {
        if k == 0 || cavity.layers[k - 1].pocket != layer.pocket {
            outlines.extend(pocket_outlines(&layer.pocket));
        }
    }
    let currency = plan.evaluation.cost.currency.clone();
    let mut charts = vec![candidates_chart(plan, &currency)];
    charts.extend(step_charts(plan, &currency));
    charts.extend(baseline_chart(plan, &currency));
    let chosen = &plan.candidates[plan.chosen];
    Scene {
        title: format!(
            "Process plan: {} chosen, {} layers, {:.1} min, {:.2} {currency}",
            chosen.name,
            plan.layers.len(),
            plan.whole.figures.kinematic_time_min,
            plan.whole.cost.total
        ),
        tool_diameter_mm: Some(chosen.diameter_mm),
        alpha_limit_deg: None,
        outlines,
        layers,
        paths: baseline.into_iter().chain([path]).chain(stair_step).collect(),
        medial: Vec::new(),
        regions: Vec::new(),
        trochoids: Vec::new(),
        charts,
    }
}
