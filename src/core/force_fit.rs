//! Least-squares fit of the response-surface force model to measured forces, as the
//! papers identified their coefficients (seed 002 §2.3: "identified by conducting a set
//! of straight cutting experiments using the least-squares method"; seed 001 Table 4).

use crate::core::error::{require_finite, require_positive};
use crate::core::force_model::{Coefficients, ForceModel};
use crate::core::CoreError;
use nalgebra::{DMatrix, DVector};
use serde::{Deserialize, Serialize};

/// Smallest singular value, relative to the largest, below which the design matrix is
/// taken as rank-deficient: the points do not determine every coefficient.
pub const RANK_TOLERANCE: f64 = 1e-9;

/// One measured cutting test: chip thickness, arc length, force.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct ForceSample {
    pub t_m_um: f64,
    pub l_mm: f64,
    pub fxy_n: f64,
}

/// How the coded variables are centred and scaled, and which terms to fit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FitSpec {
    pub t0_um: f64,
    pub dt_um: f64,
    pub l0_mm: f64,
    pub dl_mm: f64,
    pub ad_ref_mm: f64,
    /// Fit β11 as well; the papers' tables omit it (β11 = 0).
    pub include_x1_squared: bool,
}

/// The fitted model and how well it fits.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ForceFit {
    pub model: ForceModel,
    /// Coefficient of determination R².
    pub r_squared: f64,
    /// R² adjusted for the number of fitted terms.
    pub adjusted_r_squared: f64,
    /// Root-mean-square residual, N.
    pub rms_residual_n: f64,
    /// Measured − predicted force for every sample, N, in input order.
    pub residuals_n: Vec<f64>,
}

impl FitSpec {
    fn terms(&self) -> usize {
        if self.include_x1_squared {
            6
        } else {
            5
        }
    }

    /// The smallest number of samples that leaves one residual degree of freedom.
    pub fn min_samples(&self) -> usize {
        self.terms() + 1
    }
}

/// Fits seed 002 Eq. 1 to `samples` by linear least squares (SVD).
///
/// Refuses fewer samples than terms + 1, non-finite values, and samples that do not
/// determine every coefficient (e.g. all at one chip thickness).
pub fn fit_force_model(samples: &[ForceSample], spec: FitSpec) -> Result<ForceFit, CoreError> {
    require_positive("t0_um", spec.t0_um)?;
    require_positive("dt_um", spec.dt_um)?;
    require_positive("l0_mm", spec.l0_mm)?;
    require_positive("dl_mm", spec.dl_mm)?;
    require_positive("ad_ref_mm", spec.ad_ref_mm)?;
    if samples.len() < spec.min_samples() {
        return Err(CoreError::invalid(
            "points",
            format!(
                "{} points given; fitting {} terms needs at least {}",
                samples.len(),
                spec.terms(),
                spec.min_samples()
            ),
        ));
    }
    for (i, s) in samples.iter().enumerate() {
        require_positive(&format!("points[{i}].t_m_um"), s.t_m_um)?;
        require_positive(&format!("points[{i}].l_mm"), s.l_mm)?;
        require_finite(&format!("points[{i}].fxy_n"), s.fxy_n)?;
    }

    let terms = spec.terms();
    let rows: Vec<f64> = samples
        .iter()
        .flat_map(|s| {
            let x1 = (s.t_m_um - spec.t0_um) / spec.dt_um;
            let x2 = (s.l_mm - spec.l0_mm) / spec.dl_mm;
            let mut row = vec![1.0, x1, x2];
            if spec.include_x1_squared {
                row.push(x1 * x1);
            }
            row.extend([x2 * x2, x1 * x2]);
            row
        })
        .collect();
    let design = DMatrix::from_row_slice(samples.len(), terms, &rows);
    let forces = DVector::from_iterator(samples.len(), samples.iter().map(|s| s.fxy_n));

    let svd = design.clone().svd(true, true);
    let max_sv = svd.singular_values.max();
    let min_sv = svd.singular_values.min();
    if max_sv.is_nan() || max_sv <= 0.0 || min_sv / max_sv < RANK_TOLERANCE {
        return Err(CoreError::unsolvable(
            "points",
            "the points do not determine every coefficient: vary both the chip thickness and the arc length (e.g. a central composite design)",
        ));
    }
    let beta =
        svd.solve(&forces, RANK_TOLERANCE * max_sv).map_err(|e| CoreError::unsolvable("points", e.to_string()))?;

    let predicted = &design * &beta;
    let residuals = &forces - &predicted;
    let n = samples.len() as f64;
    let mean = forces.mean();
    let ss_tot: f64 = forces.iter().map(|f| (f - mean).powi(2)).sum();
    let ss_res: f64 = residuals.iter().map(|r| r * r).sum();
    if ss_tot.is_nan() || ss_tot <= 0.0 {
        return Err(CoreError::unsolvable(
            "points",
            "every measured force is the same: R² is undefined and the model cannot be fitted",
        ));
    }
    let r_squared = 1.0 - ss_res / ss_tot;
    let dof = n - terms as f64;
    let adjusted_r_squared = 1.0 - (1.0 - r_squared) * (n - 1.0) / dof;

    let b = beta.as_slice();
    let (b11, rest) = if spec.include_x1_squared { (b[3], &b[4..]) } else { (0.0, &b[3..]) };
    let model = ForceModel {
        t0_um: spec.t0_um,
        dt_um: spec.dt_um,
        l0_mm: spec.l0_mm,
        dl_mm: spec.dl_mm,
        coefficients: Coefficients { b0: b[0], b1: b[1], b2: b[2], b11, b22: rest[0], b12: rest[1] },
        ad_ref_mm: spec.ad_ref_mm,
        // The fit is evaluated at Ad_ref, where every edge profile gives the same force.
        corner_radius_mm: 0.0,
    };
    Ok(ForceFit {
        model,
        r_squared,
        adjusted_r_squared,
        rms_residual_n: (ss_res / n).sqrt(),
        residuals_n: residuals.iter().copied().collect(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::core::fixtures::seed_001_ten_mm;
    use crate::core::tolerance::approx_eq;

    fn spec(include_x1_squared: bool) -> FitSpec {
        let m = seed_001_ten_mm();
        FitSpec {
            t0_um: m.t0_um,
            dt_um: m.dt_um,
            l0_mm: m.l0_mm,
            dl_mm: m.dl_mm,
            ad_ref_mm: m.ad_ref_mm,
            include_x1_squared,
        }
    }

    /// The 13-run central composite design of the papers, in coded units.
    fn central_composite() -> Vec<(f64, f64)> {
        let s = std::f64::consts::SQRT_2;
        let mut pts =
            vec![(-1.0, -1.0), (1.0, -1.0), (-1.0, 1.0), (1.0, 1.0), (-s, 0.0), (s, 0.0), (0.0, -s), (0.0, s)];
        pts.extend(std::iter::repeat_n((0.0, 0.0), 5));
        pts
    }

    fn samples_from(model: &ForceModel, noise: impl Fn(usize) -> f64) -> Vec<ForceSample> {
        central_composite()
            .into_iter()
            .enumerate()
            .map(|(i, (x1, x2))| {
                let t = model.t0_um + x1 * model.dt_um;
                let l = model.l0_mm + x2 * model.dl_mm;
                ForceSample { t_m_um: t, l_mm: l, fxy_n: model.force_n(t, l, model.ad_ref_mm) + noise(i) }
            })
            .collect()
    }

    #[test]
    fn exact_samples_of_the_seed_001_model_give_its_coefficients_back_with_r2_one() {
        let truth = seed_001_ten_mm();
        let fit = fit_force_model(&samples_from(&truth, |_| 0.0), spec(false)).unwrap();
        let (c, t) = (fit.model.coefficients, truth.coefficients);
        for (got, want) in [(c.b0, t.b0), (c.b1, t.b1), (c.b2, t.b2), (c.b22, t.b22), (c.b12, t.b12)] {
            assert!(approx_eq(got, want, 1e-9), "{got} vs {want}");
        }
        assert!(approx_eq(fit.r_squared, 1.0, 1e-12));
        assert!(fit.residuals_n.iter().all(|r| r.abs() < 1e-9));
    }

    #[test]
    fn noisy_samples_give_r2_below_one_and_residuals_that_sum_to_zero() {
        let noise = |i: usize| if i.is_multiple_of(2) { 3.0 } else { -2.5 };
        let fit = fit_force_model(&samples_from(&seed_001_ten_mm(), noise), spec(true)).unwrap();
        assert!(fit.r_squared < 1.0 && fit.r_squared > 0.99);
        assert!(fit.adjusted_r_squared < fit.r_squared);
        assert!(fit.residuals_n.iter().sum::<f64>().abs() < 1e-6);
        assert!(fit.rms_residual_n > 0.0);
    }

    #[test]
    fn too_few_points_are_refused_with_the_number_needed() {
        let samples = samples_from(&seed_001_ten_mm(), |_| 0.0);
        let err = fit_force_model(&samples[..6], spec(true)).unwrap_err();
        assert!(err.to_string().contains("at least 7"), "{err}");
    }

    #[test]
    fn points_at_one_chip_thickness_are_refused_as_degenerate() {
        let samples: Vec<_> = (0..10)
            .map(|i| ForceSample { t_m_um: 43.6, l_mm: 2.0 + 0.1 * i as f64, fxy_n: 250.0 + i as f64 })
            .collect();
        let err = fit_force_model(&samples, spec(false)).unwrap_err();
        assert!(matches!(err, CoreError::Unsolvable { .. }), "{err}");
    }

    #[test]
    fn a_non_finite_measurement_is_refused_naming_its_index() {
        let mut samples = samples_from(&seed_001_ten_mm(), |_| 0.0);
        samples[4].fxy_n = f64::NAN;
        let err = fit_force_model(&samples, spec(false)).unwrap_err();
        assert!(err.to_string().contains("points[4].fxy_n"), "{err}");
    }
}
