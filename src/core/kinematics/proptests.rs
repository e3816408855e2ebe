//! Random tool paths: the kinematic time is finite and never below the nominal one.

use super::tests::vm4;
use super::*;
use crate::core::toolpath::{Event, EventKind, Motion, Move, Plane, Toolpath, Units, P3};
use proptest::prelude::*;

/// One random move relative to the current point: kind (0 rapid, 1 line, 2 arc), offsets,
/// feed, arc turn angle.
type Step = (u8, (f64, f64, f64), f64, f64);

fn build(steps: &[Step], tool_change_at: Option<usize>) -> Toolpath {
    let mut at = P3::new(0.0, 0.0, 0.0);
    let mut moves = Vec::new();
    for (i, &(kind, (dx, dy, dz), feed, turn)) in steps.iter().enumerate() {
        let line = i as u32 + 1;
        let m = match kind {
            0 => Move {
                motion: Motion::Rapid,
                start: at,
                end: P3::new(at.x + dx, at.y + dy, at.z + dz),
                feed_mm_min: None,
                spindle_rpm: None,
                tool: None,
                line,
            },
            1 => Move {
                motion: Motion::Linear,
                start: at,
                end: P3::new(at.x + dx, at.y + dy, at.z + dz),
                feed_mm_min: Some(feed),
                spindle_rpm: None,
                tool: None,
                line,
            },
            _ => {
                let center = P3::new(at.x + dx, at.y + dy, at.z);
                let (r, a0) = ((at.x - center.x).hypot(at.y - center.y), (at.y - center.y).atan2(at.x - center.x));
                Move {
                    motion: Motion::Arc { center, clockwise: turn < 0.0, plane: Plane::Xy, turns: 0 },
                    start: at,
                    end: P3::new(center.x + r * (a0 + turn).cos(), center.y + r * (a0 + turn).sin(), at.z + dz),
                    feed_mm_min: Some(feed),
                    spindle_rpm: None,
                    tool: None,
                    line,
                }
            }
        };
        at = m.end;
        moves.push(m);
    }
    let events = tool_change_at
        .filter(|&k| k <= moves.len())
        .map(|k| Event { kind: EventKind::ToolChange { tool: 1 }, before_move: k, line: 1 })
        .into_iter()
        .collect();
    Toolpath { moves, events, source_units: Units::Mm, warnings: vec![] }
}

fn step() -> impl Strategy<Value = Step> {
    let offset = prop_oneof![-50.0..50.0f64, -0.05..0.05f64];
    (0u8..3, (offset.clone(), offset, -5.0..5.0f64), 10.0..30000.0f64, -6.0..6.0f64)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    #[test]
    fn the_kinematic_time_is_finite_and_never_below_the_nominal_time(
        steps in prop::collection::vec(step(), 0..40),
        tool_change_at in prop::option::of(0usize..40),
        scale in 0.05..5.0f64,
        look_ahead in prop::option::of(1usize..50),
        deviation in 0.0..0.1f64,
        exact_stop_at_rapids in any::<bool>(),
    ) {
        let mut machine = vm4();
        machine.accel_mm_s2.iter_mut().for_each(|a| *a *= scale);
        machine.jerk_mm_s3.iter_mut().for_each(|j| *j *= scale * scale);
        let options = TimeOptions { look_ahead_blocks: look_ahead, junction_deviation_mm: deviation, exact_stop_at_rapids, per_move: true };
        let t = machining_time(&build(&steps, tool_change_at), &machine, &options).unwrap();
        prop_assert!(t.nominal_min.is_finite() && t.kinematic_min.is_finite(), "{:?}", t);
        prop_assert!(t.kinematic_min >= t.nominal_min - 1e-9, "{:?}", t);
        prop_assert!(t.feed_kinematic_min >= t.feed_nominal_min - 1e-9);
        prop_assert!(t.rapid_kinematic_min >= t.rapid_nominal_min - 1e-9);
        prop_assert!(t.breakdown.jerk_min >= 0.0 && t.breakdown.acceleration_min >= -1e-12);
        prop_assert!(t.per_move_s.unwrap().iter().all(|s| s.is_finite() && *s >= 0.0));
    }
}
