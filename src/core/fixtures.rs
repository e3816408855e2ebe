//! Test fixtures shared by the core's unit tests: the papers' models.

use crate::core::force_model::{Coefficients, ForceModel};

/// seed 001 Table 4, 10 mm new end mill (β11 = 0, MODEL.md §3), centred exactly on the
/// standard conditions (Rd 0.5, fz 0.1; Table 2 prints the centres as 43.6 µm, 2.26 mm).
pub fn seed_001_ten_mm() -> ForceModel {
    let alpha = 0.9f64.acos();
    ForceModel {
        t0_um: 100.0 * alpha.sin(),
        dt_um: 15.0,
        l0_mm: 5.0 * alpha,
        dl_mm: 0.436,
        coefficients: Coefficients { b0: 269.1, b1: 65.84, b2: 53.66, b11: 0.0, b22: 3.763, b12: 15.45 },
        ad_ref_mm: 10.0,
    }
}
