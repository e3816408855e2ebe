//! What the simulation's tests share: feed moves and a relief program to build paths from,
//! its painted slices, and a sample's figures bit for bit, to compare simulations.

use super::engine::{Cutter, SampleResult};
use super::profile::Profile;
use super::region::{paint, StockRegion};
use super::slices::slice_levels;
use super::stack::Stack;
use crate::core::force_model::ForceModel;
use crate::core::progress::NoProgress;
use crate::core::stock::Rect;
use crate::core::toolpath::{Motion, Move, Toolpath, Units, P3};

/// The block the relief program cuts.
pub const RELIEF: Rect = Rect { x_min: 0.0, y_min: 0.0, x_max: 30.0, y_max: 30.0 };

/// Zig-zag passes along x over [`RELIEF`] that step down and across, ramping in z: a
/// relief program in miniature.
pub fn relief_program() -> Toolpath {
    let mut moves = Vec::new();
    let mut at = P3::new(-3.0, 2.0, -0.5);
    for pass in 0..14 {
        let y = 2.0 + 2.0 * f64::from(pass);
        let depth = -0.5 - 0.7 * f64::from(pass % 7);
        let x_end = if pass % 2 == 0 { 33.0 } else { -3.0 };
        for end in [P3::new(at.x, y, at.z), P3::new((at.x + x_end) / 2.0, y, depth), P3::new(x_end, y, -0.5)] {
            moves.push(feed_move(at, end, moves.len()));
            at = end;
        }
    }
    Toolpath { moves, events: vec![], source_units: Units::Mm, warnings: vec![] }
}

/// The 4 mm two-flute square end mill the relief program's tests simulate with, at 9600
/// rpm and 0.05 mm, with `force_model` if any.
pub fn relief_cutter(force_model: Option<ForceModel>) -> Cutter {
    Cutter {
        profile: Profile::cylinder(2.0),
        flutes: 2,
        default_spindle_rpm: Some(9600.0),
        force_model,
        spacing_mm: 0.05,
        total_samples: 1,
    }
}

/// The slices of [`RELIEF`] for `path`, painted.
pub fn relief_slices(path: &Toolpath) -> Stack {
    let levels = slice_levels(path, -6.0, 0.0);
    Stack::build(&levels, RELIEF, 0.1, |raster| paint(raster, &[StockRegion::Rect(RELIEF)], &[], &NoProgress))
        .expect("nothing cancels the painting")
}

/// A straight feed move from `start` to `end` at 600 mm/min and 9600 rpm, the `index`-th
/// of its path (its line is one more).
pub fn feed_move(start: P3, end: P3, index: usize) -> Move {
    Move {
        motion: Motion::Linear,
        start,
        end,
        feed_mm_min: Some(600.0),
        spindle_rpm: Some(9600.0),
        tool: None,
        line: u32::try_from(index + 1).unwrap_or(u32::MAX),
    }
}

/// The figures of a sample that the simulation computes, bit for bit: where it is along
/// the path, its contact, Ad, t_m, the force, the feed ratio, and its move and plunge.
pub fn sample_bits(r: &SampleResult) -> [u64; 9] {
    [
        r.s_mm.to_bits(),
        r.contact.alpha_rad.to_bits(),
        r.contact.entry_rad.to_bits(),
        r.contact.exit_rad.to_bits(),
        r.ad_mm.to_bits(),
        r.t_m_um.to_bits(),
        r.force_n.map_or(0, f64::to_bits),
        r.cutting_point_ratio.to_bits(),
        u64::from(r.plunge) | (r.sample.move_index as u64) << 1,
    ]
}
