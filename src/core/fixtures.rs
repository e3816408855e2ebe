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

/// The 10 mm tool's life of seed 003 with the assumed tables of MODEL.md §9.
pub fn ten_mm_life() -> crate::core::tool_life::ToolLifeModel {
    crate::core::tool_life::ToolLifeModel {
        life_m: 320.0,
        gamma_table: vec![(0.0, 1.0), (40.0, 1.0), (50.0, 2.0), (60.0, 4.0), (90.0, 8.0), (180.0, 12.0)],
        force_exponent: 2.4,
        standard_arc_length_mm: crate::core::engagement::engagement(
            crate::core::engagement::Contour::Straight,
            5.0,
            0.5,
        )
        .unwrap()
        .arc_length_mm,
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
