//! Tool life along a path (seed 002 Eq. 2–3, seed 003; MODEL.md §9): the edge arc each
//! tooth pass wears, weighted by the engagement angle γ(α) and the force φ(F/F*),
//! against the life measured at the standard straight cut.

use crate::core::error::require_positive;
use crate::core::CoreError;
use serde::Serialize;

/// mm per m.
const MM_PER_M: f64 = 1000.0;

/// A tool's life in a material and what shortens it.
#[derive(Debug, Clone, PartialEq)]
pub struct ToolLifeModel {
    /// Machined length at the standard straight conditions until worn, m.
    pub life_m: f64,
    /// γ(α) as (α deg, factor) points, angles increasing; linear in between, constant
    /// beyond the ends.
    pub gamma_table: Vec<(f64, f64)>,
    /// k of φ = (F/F*)^k above the target force.
    pub force_exponent: f64,
    /// Engagement arc length of the standard straight cut, mm (L0).
    pub standard_arc_length_mm: f64,
    /// Feed per tooth of the standard straight cut, mm (fz0).
    pub standard_fz_mm: f64,
    /// F*: the force of the standard straight cut, N (`None`: φ = 1).
    pub standard_force_n: Option<f64>,
}

impl ToolLifeModel {
    /// Checks every value.
    pub fn validate(&self) -> Result<(), CoreError> {
        require_positive("life_m", self.life_m)?;
        require_positive("standard_arc_length_mm", self.standard_arc_length_mm)?;
        require_positive("standard_fz_mm", self.standard_fz_mm)?;
        if !(self.force_exponent.is_finite() && self.force_exponent >= 0.0) {
            return Err(CoreError::invalid("force_exponent", "must be a finite number ≥ 0"));
        }
        if let Some(f) = self.standard_force_n {
            require_positive("standard_force_n", f)?;
        }
        if self.gamma_table.is_empty() {
            return Err(CoreError::invalid("gamma_table", "needs at least one point"));
        }
        let increasing = self.gamma_table.windows(2).all(|w| w[1].0 > w[0].0);
        let finite = self.gamma_table.iter().all(|(a, g)| a.is_finite() && g.is_finite() && *g > 0.0);
        if !(increasing && finite) {
            return Err(CoreError::invalid("gamma_table", "angles must increase and every factor be finite and > 0"));
        }
        Ok(())
    }

    /// Life as edge arc length: `L_f = life · L0 / fz0` (MODEL.md §9), mm of edge arc.
    pub fn life_edge_arc_mm(&self) -> f64 {
        self.life_m * MM_PER_M * self.standard_arc_length_mm / self.standard_fz_mm
    }

    /// γ(α): the wear factor of engagement angle `alpha_deg` (seed 002 Eq. 3).
    pub fn gamma(&self, alpha_deg: f64) -> f64 {
        let t = &self.gamma_table;
        if alpha_deg <= t[0].0 {
            return t[0].1;
        }
        for w in t.windows(2) {
            if alpha_deg <= w[1].0 {
                let f = (alpha_deg - w[0].0) / (w[1].0 - w[0].0);
                return w[0].1 + f * (w[1].1 - w[0].1);
            }
        }
        t[t.len() - 1].1
    }

    /// φ(F/F*): 1 up to the standard force, `(F/F*)^k` above it (MODEL.md §9).
    pub fn force_factor(&self, force_n: Option<f64>) -> f64 {
        match (force_n, self.standard_force_n) {
            (Some(f), Some(target)) if f > target => (f / target).powf(self.force_exponent),
            _ => 1.0,
        }
    }

    /// Edge arc worn over `ds_mm` of path: `ds · L / fz_p · γ(α) · φ(F/F*)` (MODEL.md §9,
    /// seed 002 Eq. 2), mm.
    pub fn wear_mm(&self, ds_mm: f64, cut: &WearCut) -> f64 {
        if cut.alpha_deg <= 0.0 || cut.fz_p_mm <= 0.0 {
            return 0.0;
        }
        ds_mm * cut.arc_length_mm / cut.fz_p_mm * self.gamma(cut.alpha_deg) * self.force_factor(cut.force_n)
    }
}

/// The cut at one point, as tool wear needs it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WearCut {
    pub alpha_deg: f64,
    /// Engagement arc length L, mm.
    pub arc_length_mm: f64,
    /// Feed per tooth at the cutting point, mm.
    pub fz_p_mm: f64,
    /// Predicted XY force, N.
    pub force_n: Option<f64>,
}

impl WearCut {
    /// The cut of a simulated sample run at centre feed `feed_mm_min` by `flutes` teeth at
    /// `spindle_rpm`: `fz_p = F / (z·S) · |PO|/Rc` (MODEL.md §2 and §9). The costing and
    /// the feed optimiser both weigh wear through this.
    pub fn at_centre_feed(
        alpha_deg: f64,
        arc_length_mm: f64,
        feed_mm_min: f64,
        flutes: f64,
        spindle_rpm: f64,
        cutting_point_ratio: f64,
        force_n: Option<f64>,
    ) -> WearCut {
        let fz_p_mm = feed_mm_min / (flutes * spindle_rpm) * cutting_point_ratio;
        WearCut { alpha_deg, arc_length_mm, fz_p_mm, force_n }
    }
}

/// Tool-life consumption of a path.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize)]
pub struct Consumption {
    /// Edge arc worn, mm (L_t).
    pub worn_edge_arc_mm: f64,
    /// The tool's life as edge arc, mm (L_f).
    pub life_edge_arc_mm: f64,
    /// L_t / L_f: 1 is one whole tool.
    pub ratio: f64,
    /// Cutting length of the path, mm.
    pub cutting_length_mm: f64,
    /// The machined length one tool would last at this path's mix of cuts, m (0 when
    /// the path does not cut).
    pub equivalent_life_m: f64,
}

impl Consumption {
    pub fn new(worn_edge_arc_mm: f64, life_edge_arc_mm: f64, cutting_length_mm: f64) -> Self {
        let ratio = worn_edge_arc_mm / life_edge_arc_mm;
        let equivalent_life_m = if ratio > 0.0 { cutting_length_mm / ratio / MM_PER_M } else { 0.0 };
        Consumption { worn_edge_arc_mm, life_edge_arc_mm, ratio, cutting_length_mm, equivalent_life_m }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::core::engagement::{engagement, max_chip_thickness_mm, Contour};
    use crate::core::fixtures::seed_001_ten_mm;

    /// The 10 mm tool of seed 003 with the assumed tables of MODEL.md §9.
    fn ten_mm() -> ToolLifeModel {
        let standard = engagement(Contour::Straight, 5.0, 0.5).unwrap();
        ToolLifeModel {
            life_m: 320.0,
            gamma_table: vec![(0.0, 1.0), (40.0, 1.0), (50.0, 2.0), (60.0, 4.0), (90.0, 8.0), (180.0, 12.0)],
            force_exponent: 2.4,
            standard_arc_length_mm: standard.arc_length_mm,
            standard_fz_mm: 0.1,
            standard_force_n: Some(269.1),
        }
    }

    /// The life in m of a path that is all `contour` at centre feed `feed_mm_min` (10 mm
    /// tool, 6 flutes, S 9600, Rd 0.5, Ad 10).
    fn life_m(contour: Contour, feed_mm_min: f64) -> f64 {
        let m = ten_mm();
        let e = engagement(contour, 5.0, 0.5).unwrap();
        let fz_p = feed_mm_min / (6.0 * 9600.0) * e.cutting_point_feed_ratio;
        let t_um = max_chip_thickness_mm(fz_p, e.angle_rad) * 1000.0;
        let force = seed_001_ten_mm().force_n(t_um, e.arc_length_mm, 10.0);
        let cut = WearCut {
            alpha_deg: e.angle_rad.to_degrees(),
            arc_length_mm: e.arc_length_mm,
            fz_p_mm: fz_p,
            force_n: Some(force),
        };
        let per_mm = m.wear_mm(1.0, &cut);
        m.life_edge_arc_mm() / per_mm / 1000.0
    }

    #[test]
    fn the_standard_straight_cut_lasts_the_measured_320_m() {
        assert!((life_m(Contour::Straight, 5760.0) - 320.0).abs() < 1e-6);
    }

    #[test]
    fn a_concave_arc_of_r_over_r_2_at_a_fixed_f4320_lasts_about_30_m_as_seed_003_measured() {
        let life = life_m(Contour::Concave { surface_radius_mm: 10.0 }, 4320.0);
        assert!((life - 30.0).abs() / 30.0 < 0.2, "{life} m");
    }

    #[test]
    fn the_same_arc_at_constant_force_lasts_about_110_m_as_seed_003_measured() {
        // MODEL.md §3: R/r 2 at constant force is F ≈ 1160 mm/min.
        let life = life_m(Contour::Concave { surface_radius_mm: 10.0 }, 1160.0);
        assert!((life - 110.0).abs() / 110.0 < 0.2, "{life} m");
    }

    #[test]
    fn gamma_is_one_up_to_40_degrees_and_interpolates_the_table_above() {
        let m = ten_mm();
        assert!((m.gamma(25.8) - 1.0).abs() < 1e-12);
        assert!((m.gamma(45.0) - 1.5).abs() < 1e-12);
        assert!((m.gamma(180.0) - 12.0).abs() < 1e-12);
        assert!((m.gamma(200.0) - 12.0).abs() < 1e-12);
    }

    #[test]
    fn forces_at_or_below_the_standard_do_not_shorten_the_life() {
        let m = ten_mm();
        assert!((m.force_factor(Some(200.0)) - 1.0).abs() < 1e-12);
        assert!((m.force_factor(Some(2.0 * 269.1)) - 2f64.powf(2.4)).abs() < 1e-9);
        assert!((m.force_factor(None) - 1.0).abs() < 1e-12);
    }

    #[test]
    fn a_bad_table_is_refused() {
        let mut m = ten_mm();
        m.gamma_table = vec![(40.0, 1.0), (30.0, 2.0)];
        assert!(m.validate().is_err());
    }
}
