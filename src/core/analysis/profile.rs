//! The cutting profile of an end mill as the stock simulation needs it (issue 32 item 1):
//! the tool's radius at each height above its tip, and the radius a z slice of the stock
//! takes it at.
//!
//! A square end mill is a cylinder. A radius (bull-nose) end mill of corner radius `rc` is
//! a flat end of radius `r − rc`, a quarter torus up to `rc` above the tip, then the
//! cylinder; a ball end mill is the radius end mill whose corner radius is `r`. At a height
//! `h ≤ rc` above the tip the radius is `ρ(h) = r − rc + √(2·rc·h − h²)`.
//!
//! A slice of the stock is a prism (MODEL.md §6): it cuts a slice with one disc. The slice
//! takes the tool at its **mean radius** over the slice's height (0 below the tip):
//! `ρ̄ = ∫ρ(h) dh / thickness`. A straight pass across material then removes, slice by
//! slice, exactly the area of the tool's profile below the surface, however the slices
//! lie; the engagement of each slice is that of the tool at its mean height in it.

use crate::core::tool::{EndMill, ToolType};
use std::f64::consts::FRAC_PI_4;

/// Radii closer than this are one, mm (a slice at the cylinder's radius is the cylinder).
pub const SAME_RADIUS_MM: f64 = 1e-9;

/// An end mill's radius by height above its tip.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Profile {
    /// The cylinder's radius r, mm.
    pub radius_mm: f64,
    /// The corner radius rc (0: square; r: ball), mm.
    pub corner_mm: f64,
}

impl Profile {
    /// The profile of `tool`: a ball end mill's corner is its radius, a radius end mill's
    /// its corner radius (at most its radius), a square end mill's none.
    pub fn of(tool: &EndMill) -> Profile {
        let radius_mm = tool.radius_mm();
        let corner_mm = match tool.tool_type {
            ToolType::Square => 0.0,
            ToolType::Radius => tool.corner_radius_mm.max(0.0).min(radius_mm),
            ToolType::Ball => radius_mm,
        };
        Profile { radius_mm, corner_mm }
    }

    /// A cylinder of radius `radius_mm` (a square end mill).
    pub fn cylinder(radius_mm: f64) -> Profile {
        Profile { radius_mm, corner_mm: 0.0 }
    }

    /// `true` for a square end mill: every slice takes the full radius.
    pub fn is_cylinder(&self) -> bool {
        self.corner_mm <= SAME_RADIUS_MM
    }

    /// The tool's radius `h_mm` above its tip (0 below it), mm.
    pub fn radius_at(&self, h_mm: f64) -> f64 {
        if h_mm < 0.0 {
            return 0.0;
        }
        let rc = self.corner_mm;
        if h_mm >= rc {
            return self.radius_mm;
        }
        self.radius_mm - rc + (h_mm * (2.0 * rc - h_mm)).max(0.0).sqrt()
    }

    /// The height of the tool's end above its tip at `rho_mm` from its axis, mm: 0 across
    /// the flat end, the corner's arc beyond it; `None` outside the tool's radius.
    pub fn height_at(&self, rho_mm: f64) -> Option<f64> {
        if rho_mm > self.radius_mm {
            return None;
        }
        let rc = self.corner_mm;
        let into_corner = rho_mm - (self.radius_mm - rc);
        if into_corner <= 0.0 {
            return Some(0.0);
        }
        Some(rc - (rc * rc - into_corner * into_corner).max(0.0).sqrt())
    }

    /// `∫₀^h ρ(t) dt`: half the area of the tool's axial section up to `h_mm` above the
    /// tip, mm² (0 below the tip).
    pub fn half_section_mm2(&self, h_mm: f64) -> f64 {
        if h_mm <= 0.0 {
            return 0.0;
        }
        let rc = self.corner_mm;
        let flat = self.radius_mm - rc;
        let in_corner = h_mm.min(rc);
        // ∫₀^c √(rc² − (t − rc)²) dt with u = t − rc: [u·√(rc² − u²)/2 + rc²·asin(u/rc)/2]
        // from −rc to c − rc.
        let quarter_disc = if rc > 0.0 {
            let u = in_corner - rc;
            u * (rc * rc - u * u).max(0.0).sqrt() / 2.0
                + rc * rc * (u / rc).clamp(-1.0, 1.0).asin() / 2.0
                + rc * rc * FRAC_PI_4
        } else {
            0.0
        };
        flat * in_corner + quarter_disc + self.radius_mm * (h_mm - rc).max(0.0)
    }

    /// The radius a slice from `z_bottom` to `z_top` takes a tool tip at `tip_z` at: the
    /// tool's mean radius over the slice's height, counting 0 below the tip, mm.
    pub fn slice_radius_mm(&self, tip_z: f64, z_bottom: f64, z_top: f64) -> f64 {
        let thickness = z_top - z_bottom;
        if self.is_cylinder() || z_bottom - tip_z >= self.corner_mm {
            return self.radius_mm;
        }
        if thickness <= 0.0 {
            return self.radius_at(z_top - tip_z);
        }
        (self.half_section_mm2(z_top - tip_z) - self.half_section_mm2(z_bottom - tip_z)) / thickness
    }
}

/// Levels added above each cutting level within a corner, at most: where the corner's angle
/// from the tip reaches each of this many equal steps of its quarter turn (the last at the
/// top of the corner, where the cylinder begins).
pub const CORNER_LEVELS: usize = 4;

/// `levels` (top first, as [`super::levels`] chooses them) with, above each level but the
/// top, the heights within a radius or ball end mill's corner where its radius changes most
/// ([`CORNER_LEVELS`] of them, or half as many, down to none, until the slices number at
/// most `room`: what the stock memory budget holds, see [`super::budget`]), so a slice cut by
/// the corner takes a radius close to the tool's over all of it. Heights closer than
/// [`super::levels::MIN_SLICE_MM`] to a level are left out. A square end mill's levels are
/// returned as they are. (Without corner levels a straight pass still removes the exact
/// section: each slice takes the tool's mean radius over its height.)
pub fn with_corner_levels(levels: Vec<f64>, profile: &Profile, room: usize) -> Vec<f64> {
    if profile.is_cylinder() {
        return levels;
    }
    let mut n = CORNER_LEVELS;
    while n > 0 {
        let refined = with_levels_in_corner(&levels, profile, n);
        if refined.len().saturating_sub(1) <= room {
            return refined;
        }
        n /= 2;
    }
    levels
}

/// `levels` with `n` levels in the corner above each (see [`with_corner_levels`]).
fn with_levels_in_corner(levels: &[f64], profile: &Profile, n: usize) -> Vec<f64> {
    let Some(&top) = levels.first() else {
        return levels.to_vec();
    };
    // Levels this close are one (as the program's own are, see `levels`).
    let apart = super::levels::MIN_SLICE_MM - super::levels::LEVEL_ROUNDING_MM;
    let rc = profile.corner_mm;
    let heights: Vec<f64> =
        (1..=n).map(|j| rc * (1.0 - (j as f64 * std::f64::consts::FRAC_PI_2 / n as f64).cos())).collect();
    let mut corner: Vec<f64> =
        levels[1..].iter().flat_map(|&z| heights.iter().map(move |h| z + h)).filter(|&c| c < top - apart).collect();
    corner.sort_by(|a, b| a.total_cmp(b));
    // Ascending; the program's levels are all kept, a corner level only clear of every level
    // kept so far.
    let mut out: Vec<f64> = levels.iter().rev().copied().collect();
    for c in corner {
        let at = out.partition_point(|&l| l < c);
        let clear = |i: Option<usize>| i.and_then(|i| out.get(i)).is_none_or(|&l| (l - c).abs() >= apart);
        if clear(Some(at)) && clear(at.checked_sub(1)) {
            out.insert(at, c);
        }
    }
    out.reverse();
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ball(d: f64) -> Profile {
        Profile::of(&EndMill { tool_type: ToolType::Ball, diameter_mm: d, flutes: 2, corner_radius_mm: d / 2.0 })
    }

    fn bull(d: f64, rc: f64) -> Profile {
        Profile::of(&EndMill { tool_type: ToolType::Radius, diameter_mm: d, flutes: 4, corner_radius_mm: rc })
    }

    /// The exact area of a circular segment of radius `r` and height `h`, mm².
    fn segment_mm2(r: f64, h: f64) -> f64 {
        r * r * ((r - h) / r).acos() - (r - h) * (h * (2.0 * r - h)).sqrt()
    }

    #[test]
    fn a_ball_end_mill_is_a_sphere_up_to_its_radius_and_a_cylinder_above() {
        let p = ball(10.0);
        assert!(p.radius_at(-0.1).abs() < 1e-12);
        assert!(p.radius_at(0.0).abs() < 1e-12);
        assert!((p.radius_at(1.0) - 3.0).abs() < 1e-12, "√(2·5·1 − 1) = 3");
        assert!((p.radius_at(5.0) - 5.0).abs() < 1e-12);
        assert!((p.radius_at(12.0) - 5.0).abs() < 1e-12);
    }

    #[test]
    fn a_radius_end_mill_has_a_flat_end_and_a_quarter_torus_corner() {
        let p = bull(10.0, 1.0);
        assert!((p.radius_at(0.0) - 4.0).abs() < 1e-12);
        assert!((p.radius_at(1.0) - 5.0).abs() < 1e-12);
        assert!((p.radius_at(0.5) - (4.0 + 0.75f64.sqrt())).abs() < 1e-12);
        assert!(!p.is_cylinder() && Profile::of(&EndMill { corner_radius_mm: 0.0, ..bull_tool() }).is_cylinder());
    }

    fn bull_tool() -> EndMill {
        EndMill { tool_type: ToolType::Square, diameter_mm: 10.0, flutes: 4, corner_radius_mm: 0.0 }
    }

    #[test]
    fn the_half_section_of_a_ball_is_half_the_circular_segment_below_the_height() {
        let p = ball(10.0);
        for h in [0.05, 0.6, 2.0, 4.9, 5.0] {
            assert!((2.0 * p.half_section_mm2(h) - segment_mm2(5.0, h)).abs() < 1e-9, "h {h}");
        }
        // Above the sphere's equator, the cylinder adds r per mm.
        assert!((p.half_section_mm2(7.0) - (segment_mm2(5.0, 5.0) / 2.0 + 10.0)).abs() < 1e-9);
    }

    #[test]
    fn the_half_section_of_a_radius_end_mill_adds_its_flat_end_to_the_corner() {
        let p = bull(10.0, 1.0);
        // The corner's quarter disc less the square it leaves: rc² (1 − π/4) short of r·rc.
        let full_corner = 5.0 * 1.0 - (1.0 - FRAC_PI_4);
        assert!((p.half_section_mm2(1.0) - full_corner).abs() < 1e-9);
        assert!((p.half_section_mm2(3.0) - (full_corner + 10.0)).abs() < 1e-9);
    }

    #[test]
    fn a_slice_takes_the_mean_radius_so_a_straight_pass_removes_the_exact_section() {
        let p = ball(10.0);
        // A pass 0.6 mm deep, cut in slices of any thickness: the discs' widths times the
        // slices' thicknesses sum to the segment below the surface.
        for levels in [vec![0.0, -0.6], vec![0.0, -0.25, -0.6], vec![0.0, -0.1, -0.2, -0.45, -0.6]] {
            let area: f64 = levels.windows(2).map(|w| 2.0 * p.slice_radius_mm(-0.6, w[1], w[0]) * (w[0] - w[1])).sum();
            assert!((area - segment_mm2(5.0, 0.6)).abs() < 1e-9, "{levels:?}: {area}");
        }
        // A slice the tip reaches into takes the part above the tip only.
        let half = p.slice_radius_mm(-0.3, -0.6, 0.0);
        assert!((half * 0.6 - p.half_section_mm2(0.3)).abs() < 1e-12);
        // Slices wholly above the corner take the cylinder.
        assert!((p.slice_radius_mm(-10.0, -4.0, 0.0) - 5.0).abs() < 1e-12);
    }

    #[test]
    fn a_ball_adds_levels_within_its_corner_above_each_level_and_keeps_the_programs_own() {
        let levels = vec![0.0, -0.6, -1.2, -10.0];
        let out = with_corner_levels(levels.clone(), &ball(2.0), 100);
        for l in &levels {
            assert!(out.iter().any(|o| (o - l).abs() < 1e-12), "{l} lost from {out:?}");
        }
        assert!(out.windows(2).all(|w| w[0] - w[1] >= crate::core::analysis::levels::MIN_SLICE_MM - 1e-12));
        // Above −1.2: 1 − cos 22.5° of the 1 mm corner (0.076), then 0.293, 0.617 and 1.
        assert!(out.iter().any(|o| (o - (-1.2 + 1.0 - std::f64::consts::FRAC_PI_4.cos())).abs() < 1e-9));
        assert!(out.iter().any(|o| (o - (-10.0 + 1.0)).abs() < 1e-9));
        assert_eq!(with_corner_levels(levels.clone(), &Profile::cylinder(5.0), 100), levels);
        // A budget of fewer slices takes fewer corner levels, down to none.
        let fewer = with_corner_levels(levels.clone(), &ball(2.0), 8);
        assert!(fewer.len() - 1 <= 8 && fewer.len() < out.len(), "{fewer:?}");
        assert_eq!(with_corner_levels(levels.clone(), &ball(2.0), 3), levels);
    }

    #[test]
    fn corner_levels_never_drop_a_level_of_the_program_not_even_levels_a_rounding_closer_than_a_slice() {
        // A z-level finish stepping down 0.05 mm: 0.15 − 0.1 is 0.04999999999999999.
        let levels: Vec<f64> = vec![0.0, -0.05, -0.1, -0.15, -0.2, -0.25, -3.0];
        let out = with_corner_levels(levels.clone(), &ball(6.0), 1000);
        for l in &levels {
            assert!(out.iter().any(|o| o == l), "{l} lost from {out:?}");
        }
        assert!(out.windows(2).all(|w| w[0] > w[1]), "{out:?}");
    }

    #[test]
    fn higher_slices_never_take_a_smaller_radius() {
        let p = bull(8.0, 1.5);
        let mut last = 0.0;
        for k in 0..40 {
            let bottom = -4.0 + 0.1 * f64::from(k);
            let rho = p.slice_radius_mm(-4.0, bottom, bottom + 0.1);
            assert!(rho >= last - 1e-12, "slice {k}: {rho} below {last}");
            last = rho;
        }
    }
}
