//! What a plan resolves to in the database at submission: the material, each candidate
//! tool with its data, the machine, the rates and the conventional baseline, each looked
//! up on its own, with every fault added to the request's problem.

use super::plan_tools;
use super::plans::{BaselinePrepared, PlanPrepared, PlanRequest, RowRef, BASELINE_BALL_DIAMETER_MM};
use super::setup::{machine_limits, NamedRef};
use crate::core::operation::Operation;
use crate::core::tool::{EndMill, ToolType};
use crate::service::error::{ApiError, Validator};
use crate::service::lookup;
use crate::service::store::Pool;

/// The rows a plan needs: the material, each candidate with its data, the machine, the
/// rates and the baseline, each looked up on its own unless a field naming it was
/// refused, adding every fault to `faults`.
pub async fn resolve(
    pool: &Pool,
    request: &PlanRequest,
    faults: &mut Validator,
) -> Result<Option<PlanPrepared>, ApiError> {
    let material = match faults.refused_any(&["material_id", "material"]) {
        true => None,
        false => faults.take(lookup::material(pool, request.material_id, request.material.as_deref()).await)?,
    };
    let tool_type = request.tool_type.unwrap_or(ToolType::Square);
    let picks = match faults.refused("tool_type") {
        true => None,
        false => plan_tools::pick(pool, request, tool_type, faults).await?,
    };
    let machine = match faults.refused("machine_id") {
        true => None,
        false => faults.take(lookup::machine(pool, request.machine_id).await)?,
    };
    let rates = match faults.refused("cost_rates_id") {
        true => None,
        false => faults.take(lookup::cost_rates(pool, request.cost_rates_id).await)?,
    };
    let (Some(material), Some(picks), Some(machine), Some(rates)) = (material, picks, machine, rates) else {
        return Ok(None);
    };
    let (mut candidates, mut skipped, mut writer_base) = (Vec::new(), Vec::new(), None);
    for pick in &picks {
        let resolved = plan_tools::resolve(
            pool,
            pick.tool_id,
            material.id,
            machine.id,
            rates.data.default_tool_price,
            plan_tools::ConditionsFrom::Plan,
        );
        match faults.take(resolved.await)? {
            Some(Ok((c, base))) => {
                writer_base.get_or_insert(base);
                candidates.push(c);
            }
            Some(Err(reason)) => match &pick.field {
                Some(field) => faults.fail(field.clone(), reason),
                None => skipped.push(reason),
            },
            None => {}
        }
    }
    if writer_base.is_none() && !faults.touched("diameters_mm") && !faults.touched("tool_ids") {
        faults.fail(
            "diameters_mm",
            format!(
                "no {} end mill from 6 to 16 mm has the data to plan with in {}",
                tool_type.as_str(),
                material.data.name
            ),
        );
    }
    let limits = faults.take(machine_limits(pool, machine.id).await)?;
    let baseline = match (request.baseline.unwrap_or(true), faults.refused("baseline")) {
        (false, _) => Some(None),
        (true, true) => None,
        (true, false) => {
            let found = resolve_baseline(pool, material.id, &material.data.name, &rates.data).await;
            faults.take(found)?.map(Some)
        }
    };
    let stair_step = super::plan_stair_step::resolve(
        pool,
        request.stair_step.as_ref(),
        material.id,
        machine.id,
        rates.data.default_tool_price,
        faults,
    )
    .await?;
    let (Some(writer_base), Some(limits), Some(baseline)) = (writer_base, limits, baseline) else {
        return Ok(None);
    };
    Ok(Some(PlanPrepared {
        material: NamedRef { id: material.id, name: material.data.name.clone() },
        machine: writer_base.machine.clone(),
        limits,
        cost_rates: NamedRef { id: rates.id, name: rates.data.name.clone() },
        machine_rate_per_hour: rates.data.machine_rate_per_hour,
        currency: rates.data.currency.clone(),
        candidates,
        skipped,
        baseline,
        stair_step,
        writer_base,
    }))
}

async fn resolve_baseline(
    pool: &Pool,
    material_id: i64,
    material: &str,
    rates: &crate::service::resources::cost_rates::CostRatesData,
) -> Result<BaselinePrepared, ApiError> {
    let missing = |what: &str| ApiError::field("baseline", format!("{what}: give baseline: false to plan without it"));
    let ball = lookup::tool(pool, None, Some(ToolType::Ball), Some(BASELINE_BALL_DIAMETER_MM))
        .await
        .map_err(|_| missing("no default R5 ball end mill in the database"))?;
    let row = lookup::standard_conditions(pool, ball.id, material_id, Operation::ConventionalBallRoughing)
        .await?
        .ok_or_else(|| {
            missing(&format!("no conventional_ball_roughing conditions for {} in {material}", ball.data.name))
        })?;
    let life = lookup::tool_life(pool, ball.id, material_id)
        .await?
        .ok_or_else(|| missing(&format!("no tool-life data for {} in {material}", ball.data.name)))?;
    let d = &ball.data;
    let tool = EndMill {
        tool_type: d.tool_type,
        diameter_mm: d.diameter_mm,
        flutes: d.flutes,
        corner_radius_mm: d.resolved_corner_radius_mm(),
    };
    Ok(BaselinePrepared {
        tool_id: ball.id,
        name: ball.data.name.clone(),
        tool,
        conditions: row.data.conditions(),
        conditions_row: Some(RowRef { id: row.id, source: row.data.source, reference: row.data.reference.clone() }),
        life_m: life.data.life_m,
        gamma_table: life.data.gamma_table.iter().map(|g| (g.0, g.1)).collect(),
        force_exponent: life.data.force_exponent,
        tool_price: ball.data.price.unwrap_or(rates.default_tool_price),
    })
}
