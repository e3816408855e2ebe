//! The circles of a path's arcs in XY: a chunk of samples along one of them is applied to
//! the rasters as the area swept along the arc (see [`super::chunk`]), however tight the
//! arc, instead of as short chords.

use crate::core::stock::MAX_ARC_SWEEP_RAD;
use crate::core::toolpath::{Motion, Plane, Toolpath};

/// An arc move in XY (G17): the circle its tool centre follows.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ArcGuide {
    /// The move it is (a chunk follows one move's arc).
    pub move_index: usize,
    pub center: (f64, f64),
    pub radius_mm: f64,
    pub ccw: bool,
}

/// An arc is followed when a quarter turn of it holds at least this many sample steps
/// (on tighter ones the samples are as far apart as the arc is long).
const MIN_STEPS_PER_QUARTER_TURN: f64 = 4.0;

/// The circle of every move that is an arc in XY wide enough to be followed at samples
/// `spacing_mm` apart (None for other moves).
pub fn arc_guides(path: &Toolpath, spacing_mm: f64) -> Vec<Option<ArcGuide>> {
    let min_radius_mm = MIN_STEPS_PER_QUARTER_TURN * spacing_mm / MAX_ARC_SWEEP_RAD;
    path.moves
        .iter()
        .enumerate()
        .map(|(move_index, m)| match m.motion {
            Motion::Arc { center, clockwise, plane: Plane::Xy, .. } => {
                let radius_mm = (m.start.x - center.x).hypot(m.start.y - center.y);
                (radius_mm >= min_radius_mm).then_some(ArcGuide {
                    move_index,
                    center: (center.x, center.y),
                    radius_mm,
                    ccw: !clockwise,
                })
            }
            _ => None,
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use crate::core::analysis::recent::{intruders, Corridor};
    use proptest::prelude::*;

    proptest! {
        #[test]
        fn along_an_arc_the_discs_swept_behind_reach_the_leading_half_exactly_when_it_is_tighter_than_the_tool(
            radius in 0.5..8.0f64,
            ratio in 0.05..6.0f64,
            start in 0.0..std::f64::consts::TAU,
            ccw in any::<bool>(),
        ) {
            // What `Chunk::swept` relies on: centres on the circle up to a quarter turn
            // behind the tool, which moves along it.
            let rho = radius * ratio;
            prop_assume!((rho - radius).abs() > 1e-6 * radius);
            let sign = if ccw { 1.0 } else { -1.0 };
            let at = |t: f64| (rho * t.cos(), rho * t.sin());
            let center = at(start);
            let ahead = (-sign * start.sin(), sign * start.cos());
            let behind: Vec<(f64, f64)> =
                (1..=40).map(|k| at(start - sign * std::f64::consts::FRAC_PI_2 * f64::from(k) / 40.0)).collect();
            let mut out = Vec::new();
            intruders(&behind, &Corridor::UNKNOWN, center, radius, ahead, &mut out);
            if rho < radius {
                prop_assert_eq!(out.len(), behind.len());
            } else {
                prop_assert!(out.is_empty(), "{} of {} reach", out.len(), behind.len());
            }
        }
    }
}
