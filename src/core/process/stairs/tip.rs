//! Where the tool's tip may go over the die's surface: for every cell the lowest tip
//! height at which no point of the tool's end comes closer to the surface than the
//! allowance (a "drop cutter" over the height field, with the tool's real profile).
//!
//! The allowance is kept along the surface's normal by dropping a tool grown by it (its
//! radius and its corner radius each `+ allowance`) and raising the tip by the allowance:
//! the grown tool touches the surface where the real one stays `allowance` off it. The tool
//! is also widened by half a cell's diagonal (its end keeps its height over that band), since
//! a cell's centre stands for an edge anywhere in the cell: a flat floor is kept at the
//! allowance exactly, a steep wall at the allowance plus up to that half diagonal.

use super::surface::Surface;
use crate::core::analysis::profile::Profile;

/// The lowest tip height of the tool of `profile` over every cell of `surface`, keeping
/// `allowance_mm` from it, mm. Outside the cavity (where the surface is its top) the tip
/// stays at the top plus the allowance.
pub fn tip_heights_mm(surface: &Surface, profile: &Profile, allowance_mm: f64) -> Vec<f64> {
    let grown = Profile { radius_mm: profile.radius_mm + allowance_mm, corner_mm: profile.corner_mm + allowance_mm };
    let g = &surface.grid;
    // An edge of the surface may pass anywhere through a cell, up to half its diagonal from
    // the centre that stands for it: the tool is widened by that much, so that it clears a
    // steep wall wherever in its cells the wall lies.
    let widening = g.cell_mm * std::f64::consts::FRAC_1_SQRT_2;
    let reach = ((grown.radius_mm + widening) / g.cell_mm).floor() as isize;
    // The cells the tool covers around its axis, with the height of its end over each.
    let mut stencil: Vec<(isize, isize, f64)> = Vec::new();
    for dr in -reach..=reach {
        for dc in -reach..=reach {
            let rho = ((dc * dc + dr * dr) as f64).sqrt() * g.cell_mm;
            if let Some(lift) = grown.height_at((rho - widening).max(0.0)) {
                stencil.push((dc, dr, lift));
            }
        }
    }
    let (nx, ny) = (g.nx as isize, g.ny as isize);
    let top = surface.top_mm;
    let mut tip = vec![top + allowance_mm; g.cells()];
    for (c, t) in tip.iter_mut().enumerate() {
        if surface.height_mm[c] >= top {
            // No point of the tool's end lies below its tip: over the top it stays there.
            continue;
        }
        let (col, row) = ((c % g.nx) as isize, (c / g.nx) as isize);
        let mut lowest = f64::NEG_INFINITY;
        for &(dc, dr, lift) in &stencil {
            let (x, y) = (col + dc, row + dr);
            // Off the grid lies the stock's top (the grid reaches past the cavity).
            let h = if x < 0 || y < 0 || x >= nx || y >= ny { top } else { surface.height_mm[(y * nx + x) as usize] };
            lowest = lowest.max(h - lift);
        }
        *t = lowest + allowance_mm;
    }
    tip
}
