//! What a `feeds` request resolves to once its rows are known: the strategy and the
//! objective, the feed limits, the target force and the costing's data, each judged on its
//! own, with every fault added to the request's problem.

use super::feeds::{CutMode, FeedsPrepared, FeedsRequest};
use super::kind::standard_cut_off_runtime;
use super::setup::{machine_limits, resolve_cost, Resolved, MAX_FEED_PER_STANDARD};
use crate::core::conditions::feed_mm_min;
use crate::core::feed::objective::Objective;
use crate::core::feed::plan::DEFAULT_MAX_FEED_CHANGE_PER_MM;
use crate::core::feed::rule::FeedStrategy;
use crate::core::tool::EndMill;
use crate::core::tool::ToolType;
use crate::service::error::{ApiError, Validator};
use crate::service::lookup;
use crate::service::store::Pool;

/// The strategy, feeds, force and cost of a request whose rows resolved, adding every
/// fault to `faults`; a check of a refused field, or of one whose default stands in for a
/// refused one, is skipped.
pub async fn resolve(
    pool: &Pool,
    request: &FeedsRequest,
    resolved: Resolved,
    faults: &mut Validator,
) -> Result<Option<FeedsPrepared>, ApiError> {
    let Resolved { prepared: base, standard, machine_max_feed_mm_min, .. } = resolved;
    let strategy = request.strategy.unwrap_or(match request.mode {
        CutMode::SideMilling => FeedStrategy::ConstantForce,
        CutMode::SurfaceFinishing => FeedStrategy::CuttingPoint,
    });
    let tool = base.tool.geometry;
    if request.mode == CutMode::SurfaceFinishing && tool.tool_type != ToolType::Ball && !faults.refused("mode") {
        faults.fail(
            if request.tool_id.is_some() { "tool_id" } else { "tool_type" },
            format!(
                "surface finishing holds the feed where a ball touches the surface (seed 000 Eq. 1) and needs a ball end mill; tool {} ({}) is a {} end mill",
                base.tool.id,
                base.tool.name,
                tool.tool_type.as_str()
            ),
        );
    }
    let modelled = !strategy.needs_force_model() || base.force_model.is_some();
    if !modelled && !faults.refused("strategy") {
        faults.fail(
            "strategy",
            format!(
                "constant force needs a force model and tool {} ({}) has none in {}: use cutting_point, or fit one at /v1/tools/{}/force-model/fit",
                base.tool.id, base.tool.name, base.material.name, base.tool.id
            ),
        );
    }
    let standard_feed = standard.as_ref().map(|c| feed_mm_min(c.data.fz_mm, tool.flutes, c.data.spindle_rpm));
    let (tool_id, material) = (base.tool.id, base.material.name.clone());
    let no_standard = |faults: &mut Validator, field: &str| {
        faults
            .fail(field, format!("no standard side-cutting conditions for tool {tool_id} in {material}: give {field}"));
    };
    let min_feed = match (request.min_feed_mm_min, &standard) {
        (Some(f), _) => Some(f),
        (None, Some(c)) => Some(feed_mm_min(c.data.fz_min_mm, tool.flutes, c.data.spindle_rpm)),
        (None, None) => {
            no_standard(faults, "min_feed_mm_min");
            None
        }
    };
    let max_feed = match (request.max_feed_mm_min, standard_feed) {
        (Some(f), _) => Some(f),
        (None, Some(f)) => Some((MAX_FEED_PER_STANDARD * f).min(machine_max_feed_mm_min)),
        (None, None) => {
            no_standard(faults, "max_feed_mm_min");
            None
        }
    };
    let target_force_n = match (strategy.needs_force_model(), request.target_force_n, &standard, &base.force_model) {
        (false, ..) => Some(None),
        (true, Some(f), ..) => Some(Some(f)),
        (true, None, Some(c), Some(model)) => {
            let end_mill: EndMill = tool.into();
            let cut =
                faults.take(standard_cut_off_runtime(end_mill, c.data.conditions(), Some(model.model), false).await)?;
            cut.map(|cut| cut.force_n)
        }
        // Without a model the strategy is refused; without standard conditions, the target.
        (true, None, None, Some(_)) => {
            no_standard(faults, "target_force_n");
            None
        }
        (true, None, _, None) => None,
    };
    let feeds_given = !faults.refused_any(&["min_feed_mm_min", "max_feed_mm_min"]);
    if let (Some(min_feed), Some(max_feed)) = (min_feed, max_feed) {
        if max_feed > machine_max_feed_mm_min && !faults.refused("max_feed_mm_min") {
            let reason = format!("above the machine's maximum feed of {machine_max_feed_mm_min} mm/min");
            faults.fail("max_feed_mm_min", reason);
        }
        if min_feed > max_feed && feeds_given {
            faults.fail("min_feed_mm_min", format!("{min_feed} is above the maximum feed {max_feed}"));
        }
    }
    let side_milling = request.mode == CutMode::SideMilling;
    let costable =
        side_milling && standard.is_some() && lookup::tool_life(pool, base.tool.id, base.material.id).await?.is_some();
    let cost = match costable {
        true => {
            match resolve_cost(pool, Some(&base), standard.as_ref(), request.cost_rates_id, request.tool_price, faults)
                .await?
            {
                Some(cost) => Some(cost),
                // Its faults are added; what depends on the cost is not judged without it.
                None => return Ok(None),
            }
        }
        false => None,
    };
    let mut notes = Vec::new();
    let objective = match (request.objective, &cost) {
        (Some(Objective::MinCost), None) if side_milling => {
            faults.fail(
                "objective",
                format!(
                    "min_cost weighs tool wear and needs tool-life data and standard side-cutting conditions for tool {} in {} (add them at /v1/tool-life and /v1/conditions/standard), or choose constant_force or min_time",
                    base.tool.id, base.material.name
                ),
            );
            Objective::MinCost
        }
        (Some(o), _) => o,
        (None, Some(_)) => Objective::MinCost,
        (None, None) => {
            if side_milling {
                notes.push(format!(
                    "no tool-life data or standard conditions for tool {} in {}: the feeds follow the papers' rule (objective constant_force) and the figures before and after have no wear or cost",
                    base.tool.id, base.material.name
                ));
            }
            Objective::ConstantForce
        }
    };
    let limits = faults.take(machine_limits(pool, base.machine.id).await)?;
    let (Some(min_feed), Some(max_feed), Some(target_force_n), Some(limits)) =
        (min_feed, max_feed, target_force_n, limits)
    else {
        return Ok(None);
    };
    Ok(Some(FeedsPrepared {
        objective,
        max_force_n: request.max_force_n.or(target_force_n),
        cost,
        limits: Some(limits),
        notes,
        standard_conditions_id: standard.as_ref().map(|c| c.id),
        strategy,
        target_force_n,
        min_feed_mm_min: min_feed,
        max_feed_mm_min: max_feed,
        air_feed_mm_min: request.air_feed_mm_min.unwrap_or(max_feed).min(max_feed),
        max_feed_change_per_mm: match request.max_feed_change_per_mm {
            Some(rate) if rate <= 0.0 => None,
            Some(rate) => Some(rate),
            None => Some(DEFAULT_MAX_FEED_CHANGE_PER_MM),
        },
        base,
    }))
}
