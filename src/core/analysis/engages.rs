//! Whether a slice above the deepest one cut engages the tool at all, without measuring
//! how much. Without a force model that is all a sample needs of those slices: its α,
//! entry and exit are the deepest slice's, and the upper slices count only in Ad (see
//! [`super::engine`]).
//!
//! Each slice's material lies inside the material of the slice below it (see
//! [`super::slices`]), and so does every probe's answer: a coarse point in air below is
//! in air above. So only the coarse points still material below are probed, and the
//! first one found in material settles the answer.

use super::probe::{points, AngleTable, ProbeSite, COARSE_POINTS, COARSE_STEP};
use crate::core::stock::Raster;

/// The coarse points whose material engages the tool wherever the others are: a run of
/// material in the leading half reaches the next coarse point, or ends at a boundary
/// inside it, only from these. A run from the first point alone, or to the last alone, is
/// a wall the tool circle touches tangentially (see [`AngleTable::contact`]).
pub fn interior_points() -> u128 {
    points(1, COARSE_POINTS - 1)
}

impl AngleTable {
    /// `true` when [`AngleTable::contact`] at `site` on `raster` would find α > 0.
    /// `candidates` are the interior coarse points that may be material (those in material
    /// in a raster whose material holds this one's); those found in air are removed, so
    /// they serve the slice above in turn. `hint` is the coarse point found in material
    /// last (at the previous sample, say): probed first, as it most likely still is, and
    /// set to the one found this time. (Which point is probed first changes the answer
    /// of none.)
    pub fn engages(&self, raster: &Raster, site: &ProbeSite, candidates: &mut u128, hint: &mut usize) -> bool {
        let mut todo = *candidates;
        let hinted = if *hint < COARSE_POINTS { 1u128 << *hint } else { 0 };
        if todo & hinted != 0 && self.in_material(raster, site, *hint, candidates, &mut todo) {
            return true;
        }
        while todo != 0 {
            let m = todo.trailing_zeros() as usize;
            if self.in_material(raster, site, m, candidates, &mut todo) {
                *hint = m;
                return true;
            }
        }
        false
    }

    /// `true` when coarse point `m` at `site` is in material; otherwise removes it from
    /// `candidates` and `todo`, with the points around it that its probe certifies.
    fn in_material(&self, raster: &Raster, site: &ProbeSite, m: usize, candidates: &mut u128, todo: &mut u128) -> bool {
        let (material, level) = self.certified_material(raster, site, m * COARSE_STEP);
        if !material {
            // A certified probe decides its neighbours too.
            let reach = self.skip(level);
            let air = points(m.saturating_sub(reach), (m + reach).min(COARSE_POINTS));
            *candidates &= !air;
            *todo &= !air;
        }
        material
    }
}

#[cfg(test)]
mod tests {
    use super::super::probe_tests::{point, stock, CELL, RADIUS, SIDE};
    use super::super::recent::Corridor;
    use super::*;
    use proptest::prelude::*;
    use std::f64::consts::PI;

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(64))]

        #[test]
        fn a_slice_engages_exactly_when_its_contact_has_an_engagement_and_its_contact_needs_no_probe_in_air_below(
            discs in prop::collection::vec((0.0..SIDE, 0.0..SIDE, 0.5..12.0f64), 0..6),
            slots in prop::collection::vec((point(), point(), 0.05..6.0f64), 0..4),
            ribs in prop::collection::vec((point(), 0.0..PI, 0.05..0.6f64, 0.5..4.0f64), 0..4),
            above in prop::collection::vec((point(), point(), 0.05..6.0f64), 0..6),
            sites in prop::collection::vec((point(), 0.0..2.0 * PI, prop::collection::vec((-4.0..4.0f64, -4.0..4.0f64), 0..4)), 32),
            hint in 0..COARSE_POINTS,
        ) {
            // The slice below, and one above it that lost more material.
            let below = stock(&discs, &slots, &ribs);
            let mut upper = below.clone();
            for &(a, b, radius) in &above {
                upper.clear_capsule(a, b, radius);
            }
            let table = AngleTable::new(RADIUS, CELL);
            let mut site = ProbeSite::default();
            for (center, angle, offsets) in sites {
                let heading = (angle.cos(), angle.sin());
                let recent: Vec<(f64, f64)> = offsets.iter().map(|o| (center.0 + o.0, center.1 + o.1)).collect();
                site.set(&table, center, below.grid_position(center.0, center.1), heading, &recent, &Corridor::UNKNOWN, None);
                let (_, states_below) = table.contact_and_states(&below, &site, None, 0);
                let (contact, states_upper) = table.contact_and_states(&upper, &site, None, 0);
                prop_assert_eq!(states_upper & !states_below, 0, "the upper slice has material where the one below has none");
                // Not probing the points in air below changes nothing.
                let told = table.contact_and_states(&upper, &site, None, !states_below);
                prop_assert_eq!(told, (contact, states_upper), "at {:?} heading {:?}", center, heading);
                // Whichever point is tried first.
                for mut hint in [0, hint, COARSE_POINTS / 2, COARSE_POINTS] {
                    let mut candidates = states_below & interior_points();
                    let engages = table.engages(&upper, &site, &mut candidates, &mut hint);
                    prop_assert_eq!(engages, contact.alpha_rad > 0.0, "at {:?} heading {:?}: {:?}", center, heading, contact);
                    prop_assert_eq!(states_upper & interior_points() & !candidates, 0, "a material point was dropped");
                    if engages {
                        prop_assert!(states_upper & (1 << hint) != 0, "the hint is not a material point");
                    }
                }
            }
        }
    }
}
