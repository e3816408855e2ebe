//! Tool life along a path (seed 002 Eq. 2–3, seed 003; MODEL.md §9): the edge arc each
//! tooth pass wears, weighted by the engagement angle γ(α) and the force φ(F/F*),
//! against the life measured at the standard straight cut.

use crate::core::error::require_positive;
use crate::core::CoreError;
use serde::Serialize;

/// mm per m.
const MM_PER_M: f64 = 1000.0;

/// A tool's life in a material and what shortens it.
#[derive(Debug, Clone, PartialEq, Serialize, serde::Deserialize)]
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
        table_value(&self.gamma_table, alpha_deg)
    }

    /// φ(F/F*): 1 up to the standard force, `(F/F*)^k` above it (MODEL.md §9).
    pub fn force_factor(&self, force_n: Option<f64>) -> f64 {
        match (force_n, self.standard_force_n) {
            (Some(f), Some(target)) if f > target => (f / target).powf(self.force_exponent),
            _ => 1.0,
        }
    }

    /// Edge arc worn over `ds_mm` of the tool-centre path: `ds · L / fz_p · γ(α) · φ(F/F*)`
    /// (MODEL.md §9, seed 002 Eq. 2), mm. γ and k are fitted with wear counted so
    /// (`crate::core::costing::calibration`).
    pub fn wear_mm(&self, ds_mm: f64, cut: &WearCut) -> f64 {
        if cut.alpha_deg <= 0.0 || cut.fz_p_mm <= 0.0 {
            return 0.0;
        }
        ds_mm * cut.arc_length_mm / cut.fz_p_mm * self.gamma(cut.alpha_deg) * self.force_factor(cut.force_n)
    }
}

/// The value of a table of (α deg, factor) points at `alpha_deg`: linear between points,
/// constant beyond the ends (1 for an empty table).
pub fn table_value(table: &[(f64, f64)], alpha_deg: f64) -> f64 {
    let (Some(first), Some(last)) = (table.first(), table.last()) else { return 1.0 };
    if alpha_deg <= first.0 {
        return first.1;
    }
    for w in table.windows(2) {
        if alpha_deg <= w[1].0 {
            let f = (alpha_deg - w[0].0) / (w[1].0 - w[0].0);
            return w[0].1 + f * (w[1].1 - w[0].1);
        }
    }
    last.1
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

/// A length of cut measured two ways: along the tool-centre path, which the NC program
/// and the simulation step along, and along the machined surface, which seed 003 §3.3
/// measures tool life by ("the total length of the machined workpiece surface"). The
/// surface is traced by the cutting point: on a concave arc it is `R/(R − r)` times the
/// centre path (twice at R/r = 2), on a straight cut equal, on a convex arc shorter
/// (MODEL.md §2 and §9).
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, utoipa::ToSchema)]
pub struct CutLength {
    pub centre_path_m: f64,
    pub machined_surface_m: f64,
}

impl CutLength {
    /// `centre_path_mm` and `machined_surface_mm` in m.
    pub fn from_mm(centre_path_mm: f64, machined_surface_mm: f64) -> CutLength {
        CutLength { centre_path_m: centre_path_mm / MM_PER_M, machined_surface_m: machined_surface_mm / MM_PER_M }
    }
}

/// The machined-surface length of a simulation step `ds_mm` along the tool-centre path
/// whose cutting point moves `cutting_point_ratio = |PO|/Rc` times as far (MODEL.md §2): mm.
pub fn machined_surface_mm(ds_mm: f64, cutting_point_ratio: f64) -> f64 {
    ds_mm * cutting_point_ratio
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
    /// Cutting length of the path along the tool-centre path, mm.
    pub cutting_length_mm: f64,
    /// The same cuts measured along the machined surface, mm.
    pub machined_surface_mm: f64,
    /// The length one tool would last at this path's mix of cuts, both ways (0 when the
    /// path does not cut).
    pub equivalent_life: CutLength,
}

impl Consumption {
    /// The consumption of `worn_edge_arc_mm` against a life of `life_edge_arc_mm`, over a
    /// cut of `cutting_length_mm` along the tool-centre path and `machined_surface_mm`
    /// along the machined surface.
    pub fn new(worn_edge_arc_mm: f64, life_edge_arc_mm: f64, cutting_length_mm: f64, machined_surface_mm: f64) -> Self {
        let ratio = worn_edge_arc_mm / life_edge_arc_mm;
        let equivalent_life = if ratio > 0.0 {
            CutLength::from_mm(cutting_length_mm / ratio, machined_surface_mm / ratio)
        } else {
            CutLength::default()
        };
        Consumption {
            worn_edge_arc_mm,
            life_edge_arc_mm,
            ratio,
            cutting_length_mm,
            machined_surface_mm,
            equivalent_life,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::core::fixtures::ten_mm_life;

    #[test]
    fn the_standard_straight_cut_wears_the_tool_at_the_rate_of_its_320_m_life() {
        let m = ten_mm_life();
        let cut =
            WearCut { alpha_deg: 25.84, arc_length_mm: m.standard_arc_length_mm, fz_p_mm: 0.1, force_n: Some(269.1) };
        let life_m = m.life_edge_arc_mm() / m.wear_mm(1.0, &cut) / MM_PER_M;
        assert!((life_m - 320.0).abs() < 1e-9, "{life_m}");
    }

    #[test]
    fn gamma_interpolates_its_table_and_is_constant_beyond_its_ends() {
        let mut m = ten_mm_life();
        m.gamma_table = vec![(0.0, 1.0), (40.0, 1.0), (50.0, 2.0), (60.0, 4.0), (90.0, 8.0), (180.0, 12.0)];
        assert!((m.gamma(25.8) - 1.0).abs() < 1e-12);
        assert!((m.gamma(45.0) - 1.5).abs() < 1e-12);
        assert!((m.gamma(180.0) - 12.0).abs() < 1e-12);
        assert!((m.gamma(200.0) - 12.0).abs() < 1e-12);
    }

    #[test]
    fn forces_at_or_below_the_standard_do_not_shorten_the_life() {
        let mut m = ten_mm_life();
        m.force_exponent = 2.4;
        assert!((m.force_factor(Some(200.0)) - 1.0).abs() < 1e-12);
        assert!((m.force_factor(Some(2.0 * 269.1)) - 2f64.powf(2.4)).abs() < 1e-9);
        assert!((m.force_factor(None) - 1.0).abs() < 1e-12);
    }

    #[test]
    fn life_is_reported_along_the_centre_path_and_along_the_machined_surface() {
        // Half a tool over 10 m of centre path that machined 20 m of surface (a concave arc
        // of R/r = 2): one tool lasts 20 m of centre path, 40 m of surface.
        let c = Consumption::new(50.0, 100.0, 10_000.0, machined_surface_mm(10_000.0, 2.0));
        assert!((c.ratio - 0.5).abs() < 1e-12);
        assert!((c.equivalent_life.centre_path_m - 20.0).abs() < 1e-9, "{c:?}");
        assert!((c.equivalent_life.machined_surface_m - 40.0).abs() < 1e-9, "{c:?}");
        assert_eq!(Consumption::new(0.0, 100.0, 0.0, 0.0).equivalent_life, CutLength::default());
    }

    #[test]
    fn a_bad_table_is_refused() {
        let mut m = ten_mm_life();
        m.gamma_table = vec![(40.0, 1.0), (30.0, 2.0)];
        assert!(m.validate().is_err());
    }
}
