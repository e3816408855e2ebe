//! Engagement of the tool's leading half at one position (MODEL.md §6): the angle of
//! the tool circle, within ±90° of the feed direction, that lies in material.

use crate::core::stock::Raster;
use std::f64::consts::PI;

/// Angular resolution of the probe: positions on the tool circle every 0.05°.
pub const PROBE_STEPS_PER_TURN: usize = 7200;
/// Coarse scan step, in probe steps (2°): finer features are found by bisection only
/// where the coarse scan sees a change.
pub const COARSE_STEP: usize = 40;

/// Precomputed unit vectors of the probe directions.
pub struct AngleTable {
    cos: Vec<f64>,
    sin: Vec<f64>,
}

impl Default for AngleTable {
    fn default() -> Self {
        // Two turns, so a half-turn scan starting anywhere needs no wrap-around.
        let (cos, sin) = (0..2 * PROBE_STEPS_PER_TURN)
            .map(|k| {
                let a = k as f64 * 2.0 * PI / PROBE_STEPS_PER_TURN as f64;
                (a.cos(), a.sin())
            })
            .unzip();
        AngleTable { cos, sin }
    }
}

/// The engaged part of the leading half.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Contact {
    /// Engagement angle α, rad (sum of the engaged arcs).
    pub alpha_rad: f64,
    /// First and last engaged angle from the feed direction, rad, positive to the left.
    pub entry_rad: f64,
    pub exit_rad: f64,
}

/// Where the tool is and what else has just removed material.
pub struct ProbeSite<'a> {
    pub center: (f64, f64),
    pub radius: f64,
    pub heading: (f64, f64),
    /// Tool centres swept since the raster was last updated: a probe within the radius
    /// of one of them is not material.
    pub recent: &'a [(f64, f64)],
    /// A circle (x, y, radius) holding every recent centre: probes farther than the tool
    /// radius from it need no check against them.
    pub recent_bound: (f64, f64, f64),
}

impl AngleTable {
    #[inline]
    fn material(&self, raster: &Raster, site: &ProbeSite, k: usize) -> bool {
        let x = site.center.0 + site.radius * self.cos[k];
        let y = site.center.1 + site.radius * self.sin[k];
        if !raster.is_material(x, y) {
            return false;
        }
        let (bx, by, reach) = site.recent_bound;
        let far = site.radius + reach;
        if (x - bx) * (x - bx) + (y - by) * (y - by) >= far * far {
            return true;
        }
        let r2 = site.radius * site.radius;
        site.recent.iter().all(|c| (x - c.0) * (x - c.0) + (y - c.1) * (y - c.1) >= r2)
    }

    /// First probe index in (a, b] whose state differs from index `a`'s.
    fn boundary(&self, raster: &Raster, site: &ProbeSite, a: usize, b: usize, state_a: bool) -> usize {
        let (mut lo, mut hi) = (a, b);
        while hi - lo > 1 {
            let mid = (lo + hi) / 2;
            if self.material(raster, site, mid) == state_a {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        hi
    }

    /// Measures the engagement of the leading half at `site`.
    pub fn contact(&self, raster: &Raster, site: &ProbeSite) -> Contact {
        let step = 2.0 * PI / PROBE_STEPS_PER_TURN as f64;
        let heading = site.heading.1.atan2(site.heading.0);
        let h = (heading / step).round() as i64;
        let quarter = (PROBE_STEPS_PER_TURN / 4) as i64;
        let first = (h - quarter).rem_euclid(PROBE_STEPS_PER_TURN as i64) as usize;
        let span = 2 * PROBE_STEPS_PER_TURN / 4;

        let mut engaged = 0usize;
        let mut entry: Option<usize> = None;
        let mut exit = 0usize;
        let mut prev_k = 0usize;
        let mut prev = self.material(raster, site, first);
        let mut offset = COARSE_STEP;
        loop {
            let k = offset.min(span);
            let now = self.material(raster, site, first + k);
            let (a, b) = (prev_k, k);
            if prev == now {
                if now {
                    engaged += b - a;
                    entry.get_or_insert(a);
                    exit = b;
                }
            } else {
                let at = self.boundary(raster, site, first + a, first + b, prev) - first;
                // A run narrower than one coarse step at an edge of the leading half is a
                // wall the tool circle touches tangentially (a pass along cut ground), not
                // engagement.
                let tangent_wall = (prev && a == 0) || (now && b == span);
                let run = if prev { (a, at) } else { (at, b) };
                if !tangent_wall {
                    engaged += run.1 - run.0;
                    entry.get_or_insert(run.0);
                    exit = run.1;
                }
            }
            prev = now;
            prev_k = k;
            if k == span {
                break;
            }
            offset += COARSE_STEP;
        }
        let to_rad = |k: usize| k as f64 * step - PI / 2.0;
        Contact {
            alpha_rad: engaged as f64 * step,
            entry_rad: entry.map_or(0.0, to_rad),
            exit_rad: if entry.is_some() { to_rad(exit) } else { 0.0 },
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::core::stock::Rect;

    fn block() -> Raster {
        let rect = Rect { x_min: -20.0, y_min: -20.0, x_max: 20.0, y_max: 20.0 };
        let mut r = Raster::new(rect, 0.02);
        r.paint(
            true,
            |y, out| {
                if (-20.0..20.0).contains(&y) {
                    out.push((-20.0, 20.0))
                }
            },
            |x, y| crate::core::stock::rect_signed_distance(&rect, x, y),
        );
        r
    }

    #[test]
    fn a_tool_buried_in_material_engages_its_whole_leading_half() {
        let table = AngleTable::default();
        let site = ProbeSite {
            center: (0.0, 0.0),
            radius: 5.0,
            heading: (1.0, 0.0),
            recent: &[],
            recent_bound: (0.0, 0.0, 0.0),
        };
        let c = table.contact(&block(), &site);
        assert!((c.alpha_rad - PI).abs() < 1e-9);
        assert!((c.entry_rad + PI / 2.0).abs() < 1e-9 && (c.exit_rad - PI / 2.0).abs() < 1e-9);
    }

    #[test]
    fn the_recent_centres_remove_what_they_swept() {
        let table = AngleTable::default();
        // A disc about (1, 0) covers the circle where cos θ > 0.1: what stays engaged is
        // 2 × (90° − acos 0.1).
        let recent = [(1.0, 0.0)];
        let site = ProbeSite {
            center: (0.0, 0.0),
            radius: 5.0,
            heading: (1.0, 0.0),
            recent: &recent,
            recent_bound: (0.0, 0.0, 2.0),
        };
        let c = table.contact(&block(), &site);
        let expected = 2.0 * (PI / 2.0 - 0.1f64.acos());
        assert!((c.alpha_rad - expected).abs() < 0.2f64.to_radians(), "{} vs {expected}", c.alpha_rad);
    }

    #[test]
    fn a_tool_in_the_air_engages_nothing() {
        let table = AngleTable::default();
        let site = ProbeSite {
            center: (100.0, 0.0),
            radius: 5.0,
            heading: (0.0, 1.0),
            recent: &[],
            recent_bound: (0.0, 0.0, 0.0),
        };
        assert_eq!(table.contact(&block(), &site).alpha_rad, 0.0);
    }
}
