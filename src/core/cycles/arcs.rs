//! The move builder shared by the cycles: rapids, feed lines, arcs and helices in the XY
//! plane (G17), each move starting where the last ended, numbered by its 1-based index
//! (the JSON form's `line`), with the cycle's feed, spindle speed and tool.

use super::setup::CycleSetup;
use crate::core::error::require_positive;
use crate::core::geometry::Point;
use crate::core::tolerance::LENGTH_EPS_MM;
use crate::core::toolpath::{Motion, Move, Plane, P3};
use crate::core::CoreError;

/// The point of the circle (`center`, `radius_mm`) in the unit direction `dir`.
pub fn on_circle(center: Point, radius_mm: f64, dir: (f64, f64)) -> Point {
    center.offset(radius_mm * dir.0, radius_mm * dir.1)
}

/// Most turns one helix may have.
pub const MAX_HELIX_TURNS: f64 = 1_000_000.0;

/// Whole turns of a helix going down `depth_mm` at most `pitch_mm` per turn: `⌈depth / pitch⌉`,
/// at least 1; `field` names the pitch in the error when there would be too many.
pub fn helix_turns(field: &str, depth_mm: f64, pitch_mm: f64) -> Result<u32, CoreError> {
    let pitch = require_positive(field, pitch_mm)?;
    let n = ((depth_mm - LENGTH_EPS_MM) / pitch).ceil().max(1.0);
    if n > MAX_HELIX_TURNS {
        return Err(CoreError::invalid(field, format!("gives more than {MAX_HELIX_TURNS} helix turns")));
    }
    Ok(n as u32)
}

/// Appends moves to a tool path, keeping it continuous.
pub struct PathBuilder {
    moves: Vec<Move>,
    at: P3,
    spindle_rpm: f64,
    tool: Option<u32>,
}

impl PathBuilder {
    /// A path whose first move starts at `start`, with the setup's spindle speed and tool.
    pub fn starting_at(start: P3, setup: &CycleSetup) -> PathBuilder {
        PathBuilder { moves: Vec::new(), at: start, spindle_rpm: setup.conditions.spindle_rpm, tool: setup.tool }
    }

    /// Moves written so far.
    pub fn len(&self) -> usize {
        self.moves.len()
    }

    /// `true` before the first move.
    pub fn is_empty(&self) -> bool {
        self.moves.is_empty()
    }

    /// Where the tool is.
    pub fn position(&self) -> P3 {
        self.at
    }

    fn push(&mut self, motion: Motion, end: P3, feed_mm_min: Option<f64>) {
        let line = u32::try_from(self.moves.len() + 1).unwrap_or(u32::MAX);
        self.moves.push(Move {
            motion,
            start: self.at,
            end,
            feed_mm_min,
            spindle_rpm: Some(self.spindle_rpm),
            tool: self.tool,
            line,
        });
        self.at = end;
    }

    fn is_here(&self, p: P3) -> bool {
        let a = self.at;
        ((a.x - p.x).powi(2) + (a.y - p.y).powi(2) + (a.z - p.z).powi(2)).sqrt() <= LENGTH_EPS_MM
    }

    /// G0 to `to` (nothing when the tool is already there).
    pub fn rapid(&mut self, to: P3) {
        if !self.is_here(to) {
            self.push(Motion::Rapid, to, None);
        }
    }

    /// G0 straight up or down to height `z_mm`.
    pub fn rapid_z(&mut self, z_mm: f64) {
        let to = P3 { z: z_mm, ..self.at };
        self.rapid(to);
    }

    /// G1 to `to` at `feed_mm_min` (nothing when the tool is already there).
    pub fn line(&mut self, to: P3, feed_mm_min: f64) {
        if !self.is_here(to) {
            self.push(Motion::Linear, to, Some(feed_mm_min));
        }
    }

    /// G2/G3 in XY about `center` to `end` (a full circle when `end` is the start in XY),
    /// with `turns` extra full turns; a helix when `end.z` differs from the start's.
    pub fn arc(&mut self, end: P3, center: Point, clockwise: bool, turns: u32, feed_mm_min: f64) {
        let center = P3::new(center.x, center.y, self.at.z);
        self.push(Motion::Arc { center, clockwise, plane: Plane::Xy, turns }, end, Some(feed_mm_min));
    }

    /// G2/G3 in XY at the current height to the XY point `end`.
    pub fn arc_xy(&mut self, end: Point, center: Point, clockwise: bool, feed_mm_min: f64) {
        let z = self.at.z;
        self.arc(P3::new(end.x, end.y, z), center, clockwise, 0, feed_mm_min);
    }

    /// A full circle about `center` from where the tool is, at its height.
    pub fn full_circle(&mut self, center: Point, clockwise: bool, feed_mm_min: f64) {
        let end = self.at;
        self.arc(end, center, clockwise, 0, feed_mm_min);
    }

    /// A helix of `turns` whole turns about `center` from where the tool is down to `z_mm`,
    /// ending at the same XY point: one G2/G3 block with `turns − 1` extra turns (nothing
    /// when `turns` is 0).
    pub fn helix_down(&mut self, center: Point, z_mm: f64, turns: u32, clockwise: bool, feed_mm_min: f64) {
        if turns > 0 {
            let end = P3 { z: z_mm, ..self.at };
            self.arc(end, center, clockwise, turns - 1, feed_mm_min);
        }
    }

    /// The finished moves.
    pub fn finish(self) -> Vec<Move> {
        self.moves
    }
}

/// The XY part of `p`.
pub fn xy(p: P3) -> Point {
    Point::new(p.x, p.y)
}

/// `p` at height `z_mm`.
pub fn at_z(p: Point, z_mm: f64) -> P3 {
    P3::new(p.x, p.y, z_mm)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::core::conditions::CuttingConditions;

    fn setup() -> CycleSetup {
        CycleSetup::new(CuttingConditions { spindle_rpm: 4800.0, fz_mm: 0.1, rd_mm: 0.5, ad_mm: 10.0 }, 6, 20.0)
    }

    #[test]
    fn moves_are_continuous_numbered_from_one_and_carry_the_speed() {
        let mut b = PathBuilder::starting_at(P3::new(0.0, 0.0, 20.0), &setup());
        b.rapid_z(2.0);
        b.line(P3::new(0.0, 0.0, -5.0), 500.0);
        b.arc_xy(Point::new(10.0, 0.0), Point::new(5.0, 0.0), false, 1000.0);
        b.full_circle(Point::new(5.0, 0.0), false, 1000.0);
        let moves = b.finish();
        assert_eq!(moves.len(), 4);
        for (i, m) in moves.iter().enumerate() {
            assert_eq!(m.line as usize, i + 1);
            assert_eq!(m.spindle_rpm, Some(4800.0));
            if i > 0 {
                assert_eq!(m.start, moves[i - 1].end);
            }
        }
        let Motion::Arc { center, .. } = moves[2].motion else { panic!("not an arc") };
        assert_eq!(center, P3::new(5.0, 0.0, -5.0));
    }

    #[test]
    fn a_helix_takes_whole_turns_no_steeper_than_the_pitch() {
        assert_eq!(helix_turns("pitch_mm", 10.0, 0.6).unwrap(), 17);
        assert_eq!(helix_turns("pitch_mm", 6.0, 0.6).unwrap(), 10);
        assert_eq!(helix_turns("pitch_mm", 0.1, 0.6).unwrap(), 1);
        assert!(helix_turns("pitch_mm", 10.0, 1e-9).unwrap_err().to_string().starts_with("pitch_mm"));
        let mut b = PathBuilder::starting_at(P3::new(5.0, 0.0, 0.0), &setup());
        b.helix_down(Point::new(0.0, 0.0), -10.0, 17, false, 280.0);
        let m = b.finish()[0];
        assert_eq!(m.end, P3::new(5.0, 0.0, -10.0));
        assert!(matches!(m.motion, Motion::Arc { turns: 16, clockwise: false, .. }));
    }

    #[test]
    fn a_move_to_where_the_tool_is_is_left_out() {
        let mut b = PathBuilder::starting_at(P3::new(1.0, 2.0, 3.0), &setup());
        b.rapid_z(3.0);
        b.line(P3::new(1.0, 2.0, 3.0), 100.0);
        assert!(b.finish().is_empty());
    }
}
