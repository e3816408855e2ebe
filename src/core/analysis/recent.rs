//! Which recently swept tool centres can reach the leading half at a sample. The probe
//! checks those centres' discs exactly (the rasters do not hold them yet); behind a
//! straight or gently curved move none can, and a chunk laid out along a line lets the
//! search stop after the newest few.

/// A centre is dropped only when its disc misses the leading half by more than this, mm
/// (rounding of the probe positions).
const INTRUSION_MARGIN_MM: f64 = 1e-9;
/// A search along a corridor stops early only while the feed direction is within this
/// distance (between unit vectors) of the corridor's.
const MAX_TURN_FROM_CORRIDOR: f64 = 0.5;

/// Where a list of centres lies: within `half_width` of the line through `start` along
/// the unit vector `dir`; with `ordered`, at nondecreasing distances along it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Corridor {
    pub start: (f64, f64),
    pub dir: (f64, f64),
    pub half_width: f64,
    pub ordered: bool,
}

impl Corridor {
    /// Nothing known about the centres: all are tested.
    pub const UNKNOWN: Corridor = Corridor { start: (0.0, 0.0), dir: (1.0, 0.0), half_width: 0.0, ordered: false };
}

/// Sets `out` to the centres of `recent` (laid out along `corridor`) whose disc of
/// radius `radius` can reach the closed half circle of that radius about `center` that
/// faces the unit vector `ahead`.
pub fn intruders(
    recent: &[(f64, f64)],
    corridor: &Corridor,
    center: (f64, f64),
    radius: f64,
    ahead: (f64, f64),
    out: &mut Vec<(f64, f64)>,
) {
    out.clear();
    // A disc about center + v reaches the half circle where u·v > |v|²/2r for one of
    // its unit vectors u: the largest u·v there is |v| when v points forward, else
    // |v × ahead|.
    let (hx, hy) = ahead;
    let reaches = |c: &(f64, f64)| {
        let (vx, vy) = (c.0 - center.0, c.1 - center.1);
        let d2 = vx * vx + vy * vy;
        let best = if vx * hx + vy * hy > -INTRUSION_MARGIN_MM { d2.sqrt() } else { (vy * hx - vx * hy).abs() };
        best > d2 / (2.0 * radius) - INTRUSION_MARGIN_MM
    };
    let (dx, dy) = corridor.dir;
    let turn = (hx - dx).hypot(hy - dy);
    if !corridor.ordered || turn >= MAX_TURN_FROM_CORRIDOR {
        out.extend(recent.iter().copied().filter(reaches));
        return;
    }
    // A centre c = center + v of the corridor, g behind the tool along it, has
    // |v × ahead| ≤ w + |v|·turn (w: the corridor's half width plus the tool's offset
    // from its line) and v·ahead ≤ −g + (g + w)·turn; so beyond `stop` it lies behind
    // and too far from the half circle (|v|²/2r − |v|·turn > w + margin), and so do
    // all older ones.
    let rel = (center.0 - corridor.start.0, center.1 - corridor.start.1);
    let along = rel.0 * dx + rel.1 * dy;
    let w = corridor.half_width + (rel.0 * dy - rel.1 * dx).abs();
    let m = INTRUSION_MARGIN_MM;
    let far = radius * turn + ((radius * turn).powi(2) + 2.0 * radius * (w + m)).sqrt();
    let stop = far.max((w * turn + m) / (1.0 - turn));
    for c in recent.iter().rev() {
        let behind = along - ((c.0 - corridor.start.0) * dx + (c.1 - corridor.start.1) * dy);
        if behind >= stop {
            break;
        }
        if reaches(c) {
            out.push(*c);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn all(recent: &[(f64, f64)], center: (f64, f64), radius: f64, ahead: (f64, f64)) -> Vec<(f64, f64)> {
        let mut out = Vec::new();
        intruders(recent, &Corridor::UNKNOWN, center, radius, ahead, &mut out);
        out
    }

    #[test]
    fn centres_behind_a_straight_move_cannot_reach_the_leading_half() {
        let recent: Vec<(f64, f64)> = (1..=16).map(|k| (-0.05 * f64::from(k), 0.0)).collect();
        assert!(all(&recent, (0.0, 0.0), 5.0, (1.0, 0.0)).is_empty());
        // Behind a turn tighter than the tool they can.
        let turned: Vec<(f64, f64)> = (1..=16).map(|k| (-0.05 * f64::from(k), -0.02 * f64::from(k * k))).collect();
        assert!(!all(&turned, (0.0, 0.0), 5.0, (1.0, 0.0)).is_empty());
    }

    proptest! {
        #[test]
        fn a_corridor_only_spares_tests_of_centres_that_cannot_reach(
            steps in prop::collection::vec((0.0..0.3f64, -0.02..0.02f64), 1..80),
            angle in 0.0..std::f64::consts::TAU,
            turn in -0.6..0.6f64,
            radius in 0.5..8.0f64,
        ) {
            // A wavy path along `dir`, the tool one more step ahead, facing `turn` off it.
            let dir = (angle.cos(), angle.sin());
            let normal = (-dir.1, dir.0);
            let start = (3.0, -2.0);
            let mut along = 0.0;
            let mut recent = vec![start];
            let mut half_width: f64 = 0.0;
            for (advance, side) in &steps {
                along += advance;
                half_width = half_width.max(side.abs());
                recent.push((start.0 + along * dir.0 + side * normal.0, start.1 + along * dir.1 + side * normal.1));
            }
            let center = (start.0 + (along + 0.05) * dir.0, start.1 + (along + 0.05) * dir.1);
            let ahead = ((angle + turn).cos(), (angle + turn).sin());
            let corridor = Corridor { start, dir, half_width, ordered: true };
            let mut fast = Vec::new();
            intruders(&recent, &corridor, center, radius, ahead, &mut fast);
            let bits = |v: Vec<(f64, f64)>| {
                let mut b: Vec<(u64, u64)> = v.iter().map(|c| (c.0.to_bits(), c.1.to_bits())).collect();
                b.sort_unstable();
                b
            };
            prop_assert_eq!(bits(fast), bits(all(&recent, center, radius, ahead)));
        }
    }
}
