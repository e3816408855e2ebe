//! Screening the candidates before planning them in full: each candidate that can reach the
//! cavity is planned and costed at a coarse sample spacing (a few times the default), and
//! only those whose estimate can still beat the best complete plan are planned at the
//! requested spacing. The chosen plan, its figures and its verification are always those of
//! the full spacing; a candidate screened out is reported with its estimate.

use super::evaluate::evaluate;
use super::layer::plan_layers_on_cells;
use super::spec::{ProcessOptions, ToolCandidate};
use crate::core::analysis::{CELL_PER_DIAMETER, DEFAULT_MAX_SPACING_MM, MAX_CELL_MM, SPACING_PER_DIAMETER};
use crate::core::progress::Progress;
use crate::core::CoreError;

/// The screening samples this many times more coarsely than the plan (**assumed**: 0.2 mm at
/// the default 0.05 mm, still finer than a tenth of the smallest candidate's radius). In the
/// case study its estimates stray 0.3–1.6 % from the full plans' costs (D6 200.83 against
/// 198.46, D8 115.40 against 113.70, D10 80.34 against 80.13, D12 3995 against 4058: `cargo
/// bench --bench plans -- case`); at 8 × the D10 estimate strays 20 %, and D8 must then be
/// planned in full too, which costs more than the coarser screening saves.
pub const SCREEN_SPACING_FACTOR: f64 = 4.0;

/// The screening's simulations take raster cells this many times the default
/// ([`CELL_PER_DIAMETER`] of the diameter) (**assumed**: the raster work of a plan goes with
/// the number of rows a tool sweeps, not with the sample spacing).
pub const SCREEN_CELL_FACTOR: f64 = 4.0;

/// A candidate can still win while its estimate, less this share, is below the cost of the
/// best complete plan (**assumed**: a fifth; in the case study the next-cheapest candidate,
/// D8, costs 42 % more than the chosen D10 in full).
pub const SCREEN_MARGIN: f64 = 0.2;

/// What the screening of one candidate found.
#[derive(Debug, Clone, PartialEq)]
pub struct Estimate {
    /// The cost at the standard force, at the coarse spacing.
    pub cost: f64,
    /// Every layer passed its verification at the coarse spacing.
    pub passes: bool,
    /// The coarse spacing, mm.
    pub spacing_mm: f64,
}

/// The sample spacing of `candidate`'s plan under `options`, mm.
pub fn plan_spacing_mm(candidate: &ToolCandidate, options: &ProcessOptions) -> f64 {
    options.sample_spacing_mm.unwrap_or((SPACING_PER_DIAMETER * candidate.tool.diameter_mm).min(DEFAULT_MAX_SPACING_MM))
}

/// Plans and costs `candidate` for the layers `cavity` at the coarse spacing; `Ok(Err(reason))`
/// when it cannot be planned so.
pub fn estimate(
    cavity: &super::cavity::Cavity,
    candidate: &ToolCandidate,
    options: &ProcessOptions,
    progress: &dyn Progress,
) -> Result<Result<Estimate, String>, CoreError> {
    let spacing_mm = SCREEN_SPACING_FACTOR * plan_spacing_mm(candidate, options);
    let cell_mm = (SCREEN_CELL_FACTOR * CELL_PER_DIAMETER * candidate.tool.diameter_mm).min(MAX_CELL_MM);
    let coarse = ProcessOptions { sample_spacing_mm: Some(spacing_mm), ..options.clone() };
    let stage = crate::core::progress::Stage { inner: progress, from: 0.0, span: 0.9 };
    let layers = match super::unplannable_unless_cancelled(plan_layers_on_cells(
        cavity,
        candidate,
        &coarse,
        Some(cell_mm),
        &stage,
    ))? {
        Ok(l) => l,
        Err(reason) => return Ok(Err(reason)),
    };
    let passes = layers.iter().all(|l| l.insertion.verification.passed);
    let rest = crate::core::progress::Stage { inner: progress, from: stage.span, span: 1.0 - stage.span };
    let evaluation = evaluate(&layers, candidate, &coarse, 1.0, &rest);
    Ok(super::unplannable_unless_cancelled(evaluation)?.map(|e| Estimate { cost: e.cost.total, passes, spacing_mm }))
}

/// Whether a candidate of estimate `e` can still beat the best complete plan so far (its
/// cost, and whether it passed its verification): a plan that fails verification is beaten
/// by any that passes, so against one every candidate can still win.
pub fn can_still_win(e: &Estimate, best: Option<(f64, bool)>) -> bool {
    match best {
        None | Some((_, false)) => true,
        Some((cost, true)) => e.cost * (1.0 - SCREEN_MARGIN) < cost,
    }
}
