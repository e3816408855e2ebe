//! One candidate's whole job at one force level: the feeds of every layer optimised for a
//! constant cutting force (MODEL.md §3), the tool wear of every move simulated (MODEL.md §9),
//! the layers joined into one program, its nominal and kinematic time, and the cost (seed
//! 002 Eq. 4), broken down per layer and step.

use super::feeds::force_at_feed;
use super::layer::{moved_down, LayerPlan, Step};
use super::parallel::{self, Shares};
use super::spec::{ProcessOptions, ToolCandidate};
use crate::core::analysis::geometry::PathGeometry;
use crate::core::costing::cost::{cost, Cost, Rates};
use crate::core::feed::blocks::BlockOptions;
use crate::core::feed::plan::{FeedPlan, FeedSpec};
use crate::core::feed::rule::{FeedRule, FeedStrategy};
use crate::core::insertion::{append_over, labelled_program};
use crate::core::kinematics::{machining_time, MachiningTime, TimeOptions};
use crate::core::progress::Progress;
use crate::core::tool_life::{machined_surface_mm, Consumption, WearCut};
use crate::core::toolpath::move_length;
use crate::core::toolpath::{labels_of, Motion, Move, Section, Toolpath};
use crate::core::CoreError;
use serde::Serialize;

/// Seconds per minute.
const S_PER_MIN: f64 = 60.0;
/// Share of an evaluation's progress taken by the layers' feed optimisation (the rest is the
/// program's time and cost).
const OPTIMISATION_SHARE: f64 = 0.95;

/// Lengths, times and tool consumption of a part of the job (a step of a layer, a layer,
/// or the whole).
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, utoipa::ToSchema)]
#[schema(as = PlanFigures)]
pub struct Figures {
    /// Length of the feed moves, mm.
    pub feed_length_mm: f64,
    /// Length of the feed moves that cut material, mm.
    pub cutting_length_mm: f64,
    pub rapid_length_mm: f64,
    /// Feed moves at their feeds and rapids at the rapid rate, min.
    pub nominal_time_min: f64,
    /// With the machine's acceleration and jerk limits, min.
    pub kinematic_time_min: f64,
    /// Share of one tool's life used (L_t / L_f).
    pub consumption: f64,
}

impl Figures {
    /// Adds `o`'s lengths, times and consumption.
    pub fn add(&mut self, o: &Figures) {
        self.feed_length_mm += o.feed_length_mm;
        self.cutting_length_mm += o.cutting_length_mm;
        self.rapid_length_mm += o.rapid_length_mm;
        self.nominal_time_min += o.nominal_time_min;
        self.kinematic_time_min += o.kinematic_time_min;
        self.consumption += o.consumption;
    }
}

/// The figures of one step of one layer.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, utoipa::ToSchema)]
pub struct StepFigures {
    pub step: Step,
    #[serde(flatten)]
    pub figures: Figures,
}

/// One layer's figures.
#[derive(Debug, Clone, PartialEq, Serialize, utoipa::ToSchema)]
pub struct LayerFigures {
    /// The layer's index (reported by its [`super::LayerReport`]).
    #[serde(skip)]
    pub index: usize,
    #[serde(flatten)]
    pub figures: Figures,
    /// Material removed, mm³.
    pub removed_volume_mm3: f64,
    pub steps: Vec<StepFigures>,
}

/// A candidate's job at one force level.
#[derive(Debug, Clone)]
pub struct Evaluation {
    /// Target force over F*.
    pub force_factor: f64,
    pub target_force_n: f64,
    pub program: Toolpath,
    /// Per move of the program: the cavity layer it belongs to (links to a layer included).
    pub move_layer: Vec<usize>,
    /// Per move of the program: the share of one tool's life it uses.
    pub move_consumption: Vec<f64>,
    pub layers: Vec<LayerFigures>,
    pub total: Figures,
    pub consumption: Consumption,
    pub time: MachiningTime,
    pub cost: Cost,
    pub removed_volume_mm3: f64,
    /// Mean removal rate over the kinematic time, cm³/min.
    pub removal_rate_cm3_min: f64,
    /// Where the feed optimisation could not reach the target force (the worst per layer).
    pub warnings: Vec<String>,
}

/// What one distinct layer's feed optimisation and wear simulation give.
struct Optimised {
    path: Toolpath,
    steps: Vec<Step>,
    /// Per move: worn edge arc (mm) and cutting length (mm).
    wear_mm: Vec<f64>,
    cutting_mm: Vec<f64>,
    /// The cutting length along the machined surface, mm.
    surface_mm: f64,
    removed_mm3: f64,
    warnings: Vec<String>,
}

/// The length of `program`'s feed moves and of its rapids, mm.
pub(super) fn feed_and_rapid_mm(program: &Toolpath) -> (f64, f64) {
    program.moves.iter().fold((0.0, 0.0), |(f, r), m| {
        if matches!(m.motion, Motion::Rapid) {
            (f, r + move_length(m))
        } else {
            (f + move_length(m), r)
        }
    })
}

/// The cost rates of `options` for a tool of `tool_price`.
pub(super) fn rates(options: &ProcessOptions, tool_price: f64) -> Rates {
    Rates { machine_rate_per_hour: options.machine_rate_per_hour, tool_price, currency: options.currency.clone() }
}

/// The feed rule of `candidate` at `force_factor` × F*.
pub fn feed_spec(candidate: &ToolCandidate, options: &ProcessOptions, force_factor: f64) -> FeedSpec {
    FeedSpec {
        rule: FeedRule {
            strategy: FeedStrategy::ConstantForce,
            force_model: Some(candidate.force_model),
            target_force_n: force_factor * candidate.standard_force_n,
            flutes: candidate.tool.flutes,
            min_feed_mm_min: candidate.min_feed_mm_min,
            max_feed_mm_min: candidate.max_feed_mm_min,
            air_feed_mm_min: candidate.max_feed_mm_min,
        },
        max_change_per_mm: options.max_feed_change_per_mm,
        blocks: BlockOptions::default(),
        rapid_mm_min: options.machine.rapid_mm_min,
    }
}

fn optimise_layer(
    layer: &LayerPlan,
    candidate: &ToolCandidate,
    spec: &FeedSpec,
    progress: &dyn Progress,
) -> Result<Optimised, CoreError> {
    // The layer's geometry, as its verification simulated it (simulated again only when it
    // was let go).
    let simulated;
    let geometry = match layer.geometry.as_deref() {
        Some(g) => g,
        None => {
            simulated = super::layer::simulate_geometry(&layer.toolpath, &layer.analysis, progress)?;
            &simulated
        }
    };
    let mut plan = super::feeds::optimise(&layer.toolpath, geometry, spec)?;
    // The optimiser splits moves into blocks; each block keeps its source line (move + 1).
    let source = |m: &Move| (m.line as usize).saturating_sub(1).min(layer.steps.len().saturating_sub(1));
    let steps: Vec<Step> = plan.path.moves.iter().map(|m| layer.steps[source(m)]).collect();
    // The approach holes keep their programmed feed: the 2.5-D simulation sees a helix cut
    // its whole slice at every turn (it cannot split a slice by depth), so its forces there are
    // not the helix's, and the force model, fitted to side cutting, does not cover the axial
    // cut of a helix. Their wear counts the engagement (γ) at the centre feed per tooth, with
    // no force factor.
    let mut entry = vec![false; plan.path.moves.len()];
    for (i, m) in plan.path.moves.iter_mut().enumerate() {
        if steps[i] == Step::HelicalBoring {
            m.feed_mm_min = layer.toolpath.moves[source(m)].feed_mm_min;
            entry[i] = true;
        }
    }
    let Worn { wear_mm, cutting_mm, surface_mm } = wear_along(&layer.toolpath, geometry, &plan, candidate, &entry);
    progress.report(1.0);
    let mut warnings = Vec::new();
    if !plan.shortfalls.is_empty() {
        let length: f64 = plan.shortfalls.iter().map(|s| s.length_mm).sum();
        let worst = plan.shortfalls.iter().map(|s| s.max_alpha_deg).fold(0.0, f64::max);
        warnings.push(format!(
            "layer {}: {} stretch(es), {length:.1} mm in all (up to α {worst:.1}°), where no feed within the limits holds the target force",
            layer.index,
            plan.shortfalls.len()
        ));
    }
    Ok(Optimised {
        path: plan.path,
        steps,
        wear_mm,
        cutting_mm,
        surface_mm,
        removed_mm3: geometry.removed_volume_mm3,
        warnings,
    })
}

/// What a path's cuts take of the tool: per move of the optimised path, the edge arc worn
/// and the cutting length (mm), and the cutting length along the machined surface (mm).
pub(super) struct Worn {
    pub wear_mm: Vec<f64>,
    pub cutting_mm: Vec<f64>,
    pub surface_mm: f64,
}

/// The wear of `candidate` along `plan` (the feeds optimised for `path`, whose samples are
/// `geometry`), MODEL.md §9: every sample's edge arc at its feed per tooth at the cutting
/// point and its force. Moves marked in `programmed` keep their programmed feed and count
/// their engagement (γ) at the centre feed per tooth, with no force factor.
pub(super) fn wear_along(
    path: &Toolpath,
    geometry: &PathGeometry,
    plan: &FeedPlan,
    candidate: &ToolCandidate,
    programmed: &[bool],
) -> Worn {
    let n = plan.path.moves.len();
    let (mut wear_mm, mut cutting_mm, mut surface_mm) = (vec![0.0; n], vec![0.0; n], 0.0);
    let model = &candidate.life;
    let flutes = f64::from(candidate.tool.flutes);
    super::feeds::for_each_sample_in_plan(path, geometry, plan, |g, i| {
        let alpha_deg = f64::from(g.alpha_rad).to_degrees();
        let rpm = g.spindle().unwrap_or(0.0);
        if alpha_deg <= 0.0 || rpm <= 0.0 || g.rapid() {
            return;
        }
        let feed_mm_min = plan.path.moves[i].feed_mm_min.unwrap_or(0.0);
        let fz_c_mm = feed_mm_min / (flutes * rpm);
        let arc_length_mm = g.arc_length_mm();
        let cut = if programmed.get(i).copied().unwrap_or(false) {
            WearCut { alpha_deg, arc_length_mm, fz_p_mm: fz_c_mm, force_n: None }
        } else {
            WearCut {
                alpha_deg,
                arc_length_mm,
                fz_p_mm: fz_c_mm * f64::from(g.cutting_point_ratio),
                force_n: force_at_feed(candidate.force_model, g, candidate.tool.flutes, feed_mm_min),
            }
        };
        let step_mm = f64::from(g.step_mm);
        wear_mm[i] += model.wear_mm(step_mm, &cut);
        cutting_mm[i] += step_mm;
        surface_mm += machined_surface_mm(step_mm, f64::from(g.cutting_point_ratio));
    });
    Worn { wear_mm, cutting_mm, surface_mm }
}

/// Evaluates `candidate`'s planned `layers` at `force_factor` × F*.
pub fn evaluate(
    layers: &[LayerPlan],
    candidate: &ToolCandidate,
    options: &ProcessOptions,
    force_factor: f64,
    progress: &dyn Progress,
) -> Result<Evaluation, CoreError> {
    let spec = feed_spec(candidate, options, force_factor);
    let originals: Vec<usize> = layers.iter().filter(|l| l.copy_of.is_none()).map(|l| l.index).collect();
    // The distinct layers side by side, one per core.
    let shares = Shares::new(progress, 0.0, OPTIMISATION_SHARE, originals.len());
    let results = parallel::map(progress, &originals, |k, &i| {
        let part = shares.part(k);
        part.checkpoint()?;
        optimise_layer(&layers[i], candidate, &spec, &part)
    });
    let mut optimised: Vec<Option<Optimised>> = (0..layers.len()).map(|_| None).collect();
    for (&i, result) in originals.iter().zip(results) {
        optimised[i] = Some(result?);
    }
    // The program: every layer in order (copies moved down), joined over the safe height,
    // each part labelled with the cavity's layer.
    let mut moves = Vec::new();
    let (mut owner, mut step_of, mut wear_of, mut cut_of) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    let mut labels: Vec<Option<Section>> = Vec::new();
    let mut removed = vec![0.0; layers.len()];
    let mut warnings = Vec::new();
    let mut surface = 0.0;
    for l in layers {
        let source = l.copy_of.unwrap_or(l.index);
        let Some(o) = optimised[source].as_ref() else { continue };
        let path = match l.copy_of {
            Some(_) => moved_down(&o.path, l.z_top_mm - layers[source].z_top_mm, options.safe_z_mm),
            None => o.path.clone(),
        };
        let before = moves.len();
        append_over(&mut moves, &path.moves, options.safe_z_mm);
        let links = moves.len() - before - path.moves.len();
        let first_step = o.steps.first().copied().unwrap_or(Step::RoughSideCutting);
        let layer = u32::try_from(l.index).unwrap_or(u32::MAX);
        let own: Vec<Option<Section>> = labels_of(&path.events, path.moves.len())
            .into_iter()
            .map(|label| label.map(|s| Section { layer, ..s }))
            .collect();
        labels.extend(std::iter::repeat_n(own.first().copied().flatten(), links).chain(own));
        owner.extend(std::iter::repeat_n(l.index, links + path.moves.len()));
        step_of.extend(std::iter::repeat_n(first_step, links).chain(o.steps.iter().copied()));
        wear_of.extend(std::iter::repeat_n(0.0, links).chain(o.wear_mm.iter().copied()));
        cut_of.extend(std::iter::repeat_n(0.0, links).chain(o.cutting_mm.iter().copied()));
        removed[l.index] = o.removed_mm3;
        surface += o.surface_mm;
        if l.copy_of.is_none() {
            warnings.extend(o.warnings.iter().cloned());
        }
    }
    let program = labelled_program(moves, labels);
    debug_assert_eq!(program.moves.len(), owner.len(), "the layers' paths have no moves of no length");
    let time = machining_time(&program, &options.machine, &TimeOptions { per_move: true, ..TimeOptions::default() })?;
    let per_move_s = time.per_move_s.clone().unwrap_or_default();
    let life_arc = candidate.life.life_edge_arc_mm();
    let mut per_layer: Vec<Vec<(Step, Figures)>> = vec![Vec::new(); layers.len()];
    for (i, m) in program.moves.iter().enumerate() {
        let len = move_length(m);
        let rapid = matches!(m.motion, Motion::Rapid);
        let nominal = if rapid {
            len / options.machine.rapid_mm_min
        } else {
            m.feed_mm_min.filter(|f| *f > 0.0).map_or(0.0, |f| len / f)
        };
        let f = Figures {
            feed_length_mm: if rapid { 0.0 } else { len },
            cutting_length_mm: cut_of[i],
            rapid_length_mm: if rapid { len } else { 0.0 },
            nominal_time_min: nominal,
            kinematic_time_min: per_move_s.get(i).map_or(nominal, |s| f64::from(*s) / S_PER_MIN),
            consumption: wear_of[i] / life_arc,
        };
        let steps = &mut per_layer[owner[i]];
        match steps.iter_mut().find(|(s, _)| *s == step_of[i]) {
            Some((_, acc)) => acc.add(&f),
            None => steps.push((step_of[i], f)),
        }
    }
    let mut total = Figures::default();
    let layer_figures: Vec<LayerFigures> = per_layer
        .into_iter()
        .enumerate()
        .map(|(index, mut steps)| {
            steps.sort_by_key(|(s, _)| *s);
            let mut figures = Figures::default();
            steps.iter().for_each(|(_, f)| figures.add(f));
            total.add(&figures);
            LayerFigures {
                index,
                figures,
                removed_volume_mm3: removed[index],
                steps: steps.into_iter().map(|(step, figures)| StepFigures { step, figures }).collect(),
            }
        })
        .collect();
    // The program-level times include tool changes and dwells; the per-move sums do not.
    total.nominal_time_min = time.nominal_min;
    total.kinematic_time_min = time.kinematic_min;
    let worn: f64 = wear_of.iter().sum();
    let cutting: f64 = cut_of.iter().sum();
    let consumption = Consumption::new(worn, life_arc, cutting, surface);
    total.consumption = consumption.ratio;
    let cost = cost(time.kinematic_min, consumption.ratio, &rates(options, candidate.tool_price))?;
    let removed_volume_mm3: f64 = removed.iter().sum();
    let removal_rate_cm3_min =
        if time.kinematic_min > 0.0 { removed_volume_mm3 / 1000.0 / time.kinematic_min } else { 0.0 };
    progress.report(1.0);
    Ok(Evaluation {
        force_factor,
        target_force_n: spec.rule.target_force_n,
        move_consumption: wear_of.iter().map(|w| w / life_arc).collect(),
        program,
        move_layer: owner,
        layers: layer_figures,
        total,
        consumption,
        time,
        cost,
        removed_volume_mm3,
        removal_rate_cm3_min,
        warnings,
    })
}
