//! The answer of a `costing` job, as the API documents it.

use super::analysis_result::{summary, SummaryDto};
use super::conditions::{NamedRef, ToolRef};
use super::costing::CostingPrepared;
use crate::core::analysis::Analysis;
use crate::core::costing::cost::{cost, Cost};
use crate::core::costing::wear::{AlphaWear, LineWear, WearReport};
use crate::core::toolpath::{EventKind, Toolpath};
use crate::core::CoreError;
use serde::Serialize;
use utoipa::ToSchema;

/// Seconds per minute.
const S_PER_MIN: f64 = 60.0;
/// mm³ per cm³.
const MM3_PER_CM3: f64 = 1000.0;

/// Machining time, min.
#[derive(Debug, Clone, Copy, Serialize, ToSchema)]
pub struct TimeDto {
    /// Feed moves at their feeds, rapids at the rapid rate, tool changes and dwells.
    pub nominal_min: f64,
    /// Feed moves and rapids at their programmed rates.
    pub moves_min: f64,
    pub tool_changes: usize,
    pub tool_change_min: f64,
    pub dwell_min: f64,
}

/// Wear on one NC line.
#[derive(Debug, Clone, Copy, Serialize, ToSchema)]
pub struct LineWearDto {
    pub line: u32,
    /// Share of the program's tool wear, 0–1.
    pub share: f64,
    pub cutting_length_mm: f64,
    pub max_alpha_deg: f64,
}

/// Wear at engagement angles in [from_deg, to_deg).
#[derive(Debug, Clone, Copy, Serialize, ToSchema)]
pub struct AlphaWearDto {
    pub from_deg: f64,
    pub to_deg: f64,
    /// Share of the program's tool wear, 0–1.
    pub share: f64,
    pub cutting_length_mm: f64,
}

/// How much of a tool the program uses (MODEL.md §9) and where.
#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct ToolLifeDto {
    pub tool_life_id: i64,
    /// L_t / L_f: 1 is one whole tool.
    pub consumption: f64,
    /// Edge arc worn, mm (L_t).
    pub worn_edge_arc_mm: f64,
    /// The tool's life as edge arc, mm (L_f).
    pub life_edge_arc_mm: f64,
    /// The tool's life at standard straight cutting, m.
    pub standard_life_m: f64,
    /// The machined length one tool lasts at this program's mix of cuts, m.
    pub equivalent_life_m: f64,
    /// The lines that wear the tool most (at most 20), largest share first.
    pub by_line: Vec<LineWearDto>,
    pub by_alpha: Vec<AlphaWearDto>,
}

/// Cost (seed 002, Eq. 4): `C = c_m · T_m + c_t · L_t / L_f`.
#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct CostDto {
    /// c_m · T_m.
    pub machine: f64,
    /// c_t · L_t / L_f.
    pub tool: f64,
    pub total: f64,
    pub currency: String,
    pub machine_rate_per_hour: f64,
    pub tool_price: f64,
}

/// The answer of a `costing` job.
#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct CostingResult {
    pub material: NamedRef,
    pub tool: ToolRef,
    pub machine: NamedRef,
    pub cost_rates: NamedRef,
    pub force_model_id: Option<i64>,
    pub time: TimeDto,
    pub tool_life: ToolLifeDto,
    pub cost: CostDto,
    pub removed_volume_mm3: f64,
    /// Removed volume over the nominal time, cm³/min.
    pub removal_rate_cm3_min: f64,
    /// The analysis of the program (engagement, force, critical regions).
    pub analysis: SummaryDto,
    pub warnings: Vec<String>,
}

impl CostingResult {
    pub fn new(
        prepared: CostingPrepared,
        path: &Toolpath,
        analysis: Analysis,
        wear: WearReport,
    ) -> Result<CostingResult, CoreError> {
        let tool_changes = path.events.iter().filter(|e| matches!(e.kind, EventKind::ToolChange { .. })).count();
        let dwell_s: f64 =
            path.events.iter().map(|e| if let EventKind::Dwell { seconds } = e.kind { seconds } else { 0.0 }).sum();
        let moves_min = analysis.summary.time_at_programmed_feeds_min;
        let tool_change_min = tool_changes as f64 * prepared.tool_change_s / S_PER_MIN;
        let dwell_min = dwell_s / S_PER_MIN;
        let nominal_min = moves_min + tool_change_min + dwell_min;
        let c = wear.consumption;
        let Cost { machine, tool, total, currency } = cost(nominal_min, c.ratio, &prepared.rates())?;
        let mut warnings = analysis.summary.warnings.clone();
        if prepared.standard_force_n.is_none() {
            warnings.push("no force model: tool wear is not increased for forces above the standard".to_string());
        }
        let removed = analysis.summary.removed_volume_mm3;
        let regions = analysis.critical_regions.len();
        let base = prepared.base.clone();
        Ok(CostingResult {
            material: base.material,
            tool: base.tool,
            machine: base.machine,
            cost_rates: prepared.cost_rates.clone(),
            force_model_id: base.force_model.map(|f| f.id),
            time: TimeDto { nominal_min, moves_min, tool_changes, tool_change_min, dwell_min },
            tool_life: ToolLifeDto {
                tool_life_id: prepared.tool_life_id,
                consumption: c.ratio,
                worn_edge_arc_mm: c.worn_edge_arc_mm,
                life_edge_arc_mm: c.life_edge_arc_mm,
                standard_life_m: prepared.life_m,
                equivalent_life_m: c.equivalent_life_m,
                by_line: wear
                    .by_line
                    .iter()
                    .map(|&LineWear { line, share, cutting_length_mm, max_alpha_deg }| LineWearDto {
                        line,
                        share,
                        cutting_length_mm,
                        max_alpha_deg,
                    })
                    .collect(),
                by_alpha: wear
                    .by_alpha
                    .iter()
                    .map(|&AlphaWear { from_deg, to_deg, share, cutting_length_mm }| AlphaWearDto {
                        from_deg,
                        to_deg,
                        share,
                        cutting_length_mm,
                    })
                    .collect(),
            },
            cost: CostDto {
                machine,
                tool,
                total,
                currency,
                machine_rate_per_hour: prepared.machine_rate_per_hour,
                tool_price: prepared.tool_price,
            },
            removed_volume_mm3: removed,
            removal_rate_cm3_min: if nominal_min > 0.0 { removed / MM3_PER_CM3 / nominal_min } else { 0.0 },
            analysis: summary(path.moves.len(), analysis.summary, regions),
            warnings,
        })
    }
}
