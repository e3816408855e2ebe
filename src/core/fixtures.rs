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
        corner_radius_mm: 0.0,
    }
}

/// The 10 mm tool's life of seed 003 with γ and k as fitted to MODEL.md §9's table
/// (`crate::core::costing::calibration`, stored by migration 0006).
pub fn ten_mm_life() -> crate::core::tool_life::ToolLifeModel {
    use crate::core::costing::calibration::{gamma_table, FITTED_FORCE_EXPONENT, FITTED_GAMMA_AT_40};
    use crate::core::engagement::{engagement, Contour};
    let standard = engagement(Contour::Straight, 5.0, 0.5).unwrap();
    crate::core::tool_life::ToolLifeModel {
        life_m: 320.0,
        gamma_table: gamma_table(standard.angle_rad.to_degrees(), FITTED_GAMMA_AT_40),
        force_exponent: FITTED_FORCE_EXPONENT,
        standard_arc_length_mm: standard.arc_length_mm,
        standard_fz_mm: 0.1,
        standard_force_n: Some(269.1),
    }
}

/// A `w × h` box pocket with corners of radius `r` (mm), its lower-left corner at the origin.
pub fn rounded_box(w: f64, h: f64, r: f64) -> crate::core::geometry::Pocket {
    use crate::core::geometry::{Loop, Pocket, Vertex};
    let b = (std::f64::consts::PI / 8.0).tan();
    let outer = Loop::new(vec![
        Vertex::new(r, 0.0, 0.0),
        Vertex::new(w - r, 0.0, b),
        Vertex::new(w, r, 0.0),
        Vertex::new(w, h - r, b),
        Vertex::new(w - r, h, 0.0),
        Vertex::new(r, h, b),
        Vertex::new(0.0, h - r, 0.0),
        Vertex::new(0.0, r, b),
    ]);
    Pocket::new(outer, vec![]).unwrap()
}

/// Seed 004 case study I (MODEL.md §11) as the README draws it: a 90 × 70 mm box with
/// corners of radius 8 mm and a 12 mm wide slot with a round end, 24 mm long, out of its
/// right wall (cut 35 mm deep in the case study).
pub fn case_study_pocket() -> crate::core::geometry::Pocket {
    use crate::core::geometry::{Loop, Pocket, Vertex};
    let b = (std::f64::consts::PI / 8.0).tan();
    let outer = Loop::new(vec![
        Vertex::new(8.0, 0.0, 0.0),
        Vertex::new(82.0, 0.0, b),
        Vertex::new(90.0, 8.0, 0.0),
        Vertex::new(90.0, 29.0, 0.0),
        Vertex::new(114.0, 29.0, 1.0),
        Vertex::new(114.0, 41.0, 0.0),
        Vertex::new(90.0, 41.0, 0.0),
        Vertex::new(90.0, 62.0, b),
        Vertex::new(82.0, 70.0, 0.0),
        Vertex::new(8.0, 70.0, b),
        Vertex::new(0.0, 62.0, 0.0),
        Vertex::new(0.0, 8.0, b),
    ]);
    Pocket::new(outer, vec![]).unwrap()
}
