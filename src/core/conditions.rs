//! Decision of cutting conditions (seed 002 §2.1, subsystem "decision of cutting
//! conditions"): the recommended conditions of an operation and what the models predict
//! for them — engagement angle, maximum chip thickness, engagement arc and XY force.

use crate::core::engagement::{engagement, max_chip_thickness_mm, Contour};
use crate::core::error::require_positive;
use crate::core::force_model::ForceModel;
use crate::core::tool::EndMill;
use crate::core::CoreError;
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

/// Micrometres per millimetre.
const UM_PER_MM: f64 = 1000.0;
/// Millimetres per metre.
const MM_PER_M: f64 = 1000.0;

/// The standard conditions of one operation for one tool.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, utoipa::ToSchema)]
pub struct CuttingConditions {
    /// Spindle speed S, min⁻¹.
    pub spindle_rpm: f64,
    /// Feed per tooth fz, mm/tooth.
    pub fz_mm: f64,
    /// Radial depth of cut Rd, mm.
    pub rd_mm: f64,
    /// Axial depth of cut Ad, mm.
    pub ad_mm: f64,
}

impl CuttingConditions {
    pub fn validate(&self) -> Result<(), CoreError> {
        require_positive("spindle_rpm", self.spindle_rpm)?;
        require_positive("fz_mm", self.fz_mm)?;
        require_positive("rd_mm", self.rd_mm)?;
        require_positive("ad_mm", self.ad_mm)?;
        Ok(())
    }
}

/// Feed rate in the NC program, `F = fz·z·S` (MODEL.md §1), mm/min.
pub fn feed_mm_min(fz_mm: f64, flutes: u32, spindle_rpm: f64) -> f64 {
    fz_mm * f64::from(flutes) * spindle_rpm
}

/// Cutting speed `V = π·D·S / 1000` (MODEL.md §5), m/min.
pub fn cutting_speed_m_min(diameter_mm: f64, spindle_rpm: f64) -> f64 {
    PI * diameter_mm * spindle_rpm / MM_PER_M
}

/// Diameter at which a ball end mill cuts at axial depth `Ad`: the chord of the sphere,
/// `2·sqrt(Ad·(D − Ad))` for `Ad < D/2`, else `D` (standard ball-end geometry).
pub fn ball_effective_diameter_mm(diameter_mm: f64, ad_mm: f64) -> f64 {
    let r = diameter_mm / 2.0;
    if ad_mm >= r {
        diameter_mm
    } else {
        2.0 * (ad_mm * (diameter_mm - ad_mm)).sqrt()
    }
}

/// The centre `(t0 µm, L0 mm)` of a force model's coded variables for a tool of radius
/// `r` at standard straight conditions: the chip thickness and engagement arc of that
/// cut (seed 001 Table 2; MODEL.md §3).
pub fn standard_centres(tool_radius_mm: f64, conditions: CuttingConditions) -> Result<(f64, f64), CoreError> {
    let e = engagement(Contour::Straight, tool_radius_mm, conditions.rd_mm)?;
    Ok((max_chip_thickness_mm(conditions.fz_mm, e.angle_rad) * UM_PER_MM, e.arc_length_mm))
}

/// What the engagement model predicts for a straight cut at the conditions.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct PredictedEngagement {
    pub angle_deg: f64,
    pub max_chip_thickness_um: f64,
    pub arc_length_mm: f64,
}

/// What the force model predicts at the conditions.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct PredictedForce {
    pub fxy_n: f64,
    pub x1: f64,
    pub x2: f64,
    /// `false` when the point lies outside the experiments' design region (|X| > √2).
    pub within_design_region: bool,
}

/// The recommended conditions and the models' predictions for them.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ConditionsReport {
    pub conditions: CuttingConditions,
    pub feed_mm_min: f64,
    pub cutting_speed_m_min: f64,
    /// For a ball end mill, the diameter in contact at the axial depth, and the cutting
    /// speed there.
    pub effective_diameter_mm: f64,
    pub effective_cutting_speed_m_min: f64,
    pub engagement: Option<PredictedEngagement>,
    pub force: Option<PredictedForce>,
    pub warnings: Vec<String>,
}

/// Evaluates the conditions of a straight cut with `tool`: feed, cutting speed and, for
/// flat-ended tools, the engagement (MODEL.md §2) and the force model's prediction
/// (seed 002 Eq. 1) scaled to the axial depth.
pub fn evaluate_conditions(
    tool: &EndMill,
    conditions: CuttingConditions,
    force_model: Option<&ForceModel>,
) -> Result<ConditionsReport, CoreError> {
    require_positive("diameter_mm", tool.diameter_mm)?;
    if tool.flutes == 0 {
        return Err(CoreError::invalid("flutes", "must be at least 1"));
    }
    conditions.validate()?;
    let mut warnings = Vec::new();
    let effective_diameter_mm = if tool.tool_type.cuts_with_flank() {
        tool.diameter_mm
    } else {
        ball_effective_diameter_mm(tool.diameter_mm, conditions.ad_mm)
    };

    let (engagement_pred, force) = if tool.tool_type.cuts_with_flank() {
        let e = engagement(Contour::Straight, tool.radius_mm(), conditions.rd_mm)?;
        let t_m_um = max_chip_thickness_mm(conditions.fz_mm * e.cutting_point_feed_ratio, e.angle_rad) * UM_PER_MM;
        let pred = PredictedEngagement {
            angle_deg: e.angle_rad.to_degrees(),
            max_chip_thickness_um: t_m_um,
            arc_length_mm: e.arc_length_mm,
        };
        let force = match force_model {
            Some(model) => {
                model.validate()?;
                let coded = model.coded(t_m_um, e.arc_length_mm);
                let within = coded.within_design_region();
                if !within {
                    warnings.push(format!(
                        "the conditions lie outside the force model's design region (X1 = {:.2}, X2 = {:.2}); the force is extrapolated",
                        coded.x1, coded.x2
                    ));
                }
                Some(PredictedForce {
                    fxy_n: model.force_n(t_m_um, e.arc_length_mm, conditions.ad_mm),
                    x1: coded.x1,
                    x2: coded.x2,
                    within_design_region: within,
                })
            }
            None => {
                warnings.push("no force model for this tool and material: no force is predicted".to_string());
                None
            }
        };
        (Some(pred), force)
    } else {
        warnings.push(
            "ball end mill: the side-milling engagement and force models do not apply; only feed and cutting speed are given"
                .to_string(),
        );
        (None, None)
    };

    Ok(ConditionsReport {
        conditions,
        feed_mm_min: feed_mm_min(conditions.fz_mm, tool.flutes, conditions.spindle_rpm),
        cutting_speed_m_min: cutting_speed_m_min(tool.diameter_mm, conditions.spindle_rpm),
        effective_diameter_mm,
        effective_cutting_speed_m_min: cutting_speed_m_min(effective_diameter_mm, conditions.spindle_rpm),
        engagement: engagement_pred,
        force,
        warnings,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::core::fixtures::seed_001_ten_mm;
    use crate::core::tolerance::approx_eq;
    use crate::core::tool::ToolType;

    fn square(d: f64) -> EndMill {
        EndMill { tool_type: ToolType::Square, diameter_mm: d, flutes: 6, corner_radius_mm: 0.0 }
    }

    #[test]
    fn the_10_mm_standard_gives_f5760_v302_and_beta0_as_the_force() {
        let c = CuttingConditions { spindle_rpm: 9600.0, fz_mm: 0.1, rd_mm: 0.5, ad_mm: 10.0 };
        let r = evaluate_conditions(&square(10.0), c, Some(&seed_001_ten_mm())).unwrap();
        assert!(approx_eq(r.feed_mm_min, 5760.0, 1e-9));
        assert!(approx_eq(r.cutting_speed_m_min, 301.6, 0.05));
        let e = r.engagement.unwrap();
        assert!(approx_eq(e.max_chip_thickness_um, 43.6, 0.05));
        assert!(approx_eq(e.arc_length_mm, 2.26, 0.005));
        assert!(approx_eq(r.force.unwrap().fxy_n, 269.1, 1e-9));
        assert!(r.warnings.is_empty());
    }

    #[test]
    fn a_ball_end_mill_gets_feed_and_effective_speed_but_no_force() {
        let ball = EndMill { tool_type: ToolType::Ball, diameter_mm: 10.0, flutes: 2, corner_radius_mm: 5.0 };
        let c = CuttingConditions { spindle_rpm: 4800.0, fz_mm: 0.05, rd_mm: 3.5, ad_mm: 0.6 };
        let r = evaluate_conditions(&ball, c, None).unwrap();
        assert!(approx_eq(r.feed_mm_min, 480.0, 1e-9));
        assert!(approx_eq(r.effective_diameter_mm, 2.0 * (0.6f64 * 9.4).sqrt(), 1e-12));
        assert!(r.effective_cutting_speed_m_min < r.cutting_speed_m_min);
        assert!(r.force.is_none() && r.engagement.is_none());
        assert_eq!(r.warnings.len(), 1);
    }

    #[test]
    fn conditions_outside_the_design_region_are_flagged() {
        let c = CuttingConditions { spindle_rpm: 9600.0, fz_mm: 0.2, rd_mm: 2.0, ad_mm: 10.0 };
        let r = evaluate_conditions(&square(10.0), c, Some(&seed_001_ten_mm())).unwrap();
        assert!(!r.force.unwrap().within_design_region);
        assert!(r.warnings[0].contains("design region"));
    }

    #[test]
    fn the_coded_centres_are_the_standard_cut_of_seed_001_table_2() {
        for (d, rd, fz, t0, l0) in
            [(6.0, 0.3, 0.04, 17.4, 1.35), (8.0, 0.4, 0.07, 30.5, 1.80), (10.0, 0.5, 0.10, 43.6, 2.26)]
        {
            let c = CuttingConditions { spindle_rpm: 9600.0, fz_mm: fz, rd_mm: rd, ad_mm: d };
            let (t, l) = standard_centres(d / 2.0, c).unwrap();
            assert!(approx_eq(t, t0, 0.05) && approx_eq(l, l0, 0.005), "D{d}: {t} {l}");
        }
    }

    #[test]
    fn a_zero_feed_is_refused_naming_the_field() {
        let c = CuttingConditions { spindle_rpm: 9600.0, fz_mm: 0.0, rd_mm: 0.5, ad_mm: 10.0 };
        let err = evaluate_conditions(&square(10.0), c, None).unwrap_err();
        assert!(err.to_string().starts_with("fz_mm"));
    }
}
