//! How each line of a program ran: what the editor needs to change a line's feed, or to
//! split its move, in the program's own terms (units, distance modes, arc format, feed
//! mode, coordinate frame), and how often it ran.

use serde::Serialize;

use super::options::Control;
use crate::core::toolpath::{Plane, Units, P3};

/// How F is read (G94, G93, G95).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum FeedMode {
    /// G94: length units per minute.
    #[default]
    PerMinute,
    /// G93: the block takes 1/F minutes.
    InverseTime,
    /// G95: length units per spindle revolution.
    PerRevolution,
}

/// How an arc's centre was written.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum ArcFormat {
    /// I/J/K (absolute with G90.1, else incremental).
    Centre,
    /// R.
    Radius,
}

/// The affine map from program coordinates (mm) to output coordinates:
/// `out = R(rotation) · p + translation` (the rotation in XY).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Affine {
    pub rotation_deg: f64,
    pub translation: P3,
}

impl Affine {
    pub const IDENTITY: Affine = Affine { rotation_deg: 0.0, translation: P3::new(0.0, 0.0, 0.0) };

    /// Output coordinates of program point `p` (mm).
    pub fn to_out(&self, p: P3) -> P3 {
        let (x, y) = if self.rotation_deg.abs() < f64::EPSILON {
            (p.x, p.y)
        } else {
            let (s, c) = self.rotation_deg.to_radians().sin_cos();
            (p.x * c - p.y * s, p.x * s + p.y * c)
        };
        P3::new(x + self.translation.x, y + self.translation.y, p.z + self.translation.z)
    }

    /// Program coordinates (mm) of output point `out`.
    pub fn to_program(&self, out: P3) -> P3 {
        let (x, y, z) = (out.x - self.translation.x, out.y - self.translation.y, out.z - self.translation.z);
        if self.rotation_deg.abs() < f64::EPSILON {
            return P3::new(x, y, z);
        }
        let (s, c) = (-self.rotation_deg).to_radians().sin_cos();
        P3::new(x * c - y * s, x * s + y * c, z)
    }
}

/// The state a line's motion was read in.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct MotionContext {
    pub units: Units,
    /// G90 (true) or G91.
    pub absolute: bool,
    /// G90.1 (true) or G91.1.
    pub absolute_centres: bool,
    pub plane: Plane,
    pub feed_mode: FeedMode,
    /// The spindle speed the move ran at (for G95 feeds), min⁻¹.
    pub spindle_rpm: Option<f64>,
    /// How the arc's centre was written (`None`: a line).
    pub arc: Option<ArcFormat>,
    /// The line's turns word P (LinuxCNC arcs), if written.
    pub turns_word: bool,
    /// Where the program's coordinates were.
    pub frame: Affine,
}

/// What a line's motion was, the first time it ran.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum LineMotion {
    /// No move.
    None,
    /// One line or arc, from the line's own words, as written.
    Direct(MotionContext),
    /// Moves the line does not spell out (a canned cycle, cutter compensation, a retract
    /// for G53/G28/G30): its feed can change, the moves cannot be split.
    Derived(MotionContext),
}

/// How a line ran.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct LineRecord {
    /// How many times it ran (in loops and subprograms, more than once).
    pub executions: u32,
    pub motion: LineMotion,
}

/// How each line of a program ran (a few bytes a line: contexts are shared by the lines
/// that run in the same state).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct ProgramMap {
    executions: Vec<u32>,
    /// 0: no move; 2k + 1: derived, `contexts[k]`; 2k + 2: direct, `contexts[k]`.
    motions: Vec<u32>,
    contexts: Vec<MotionContext>,
    /// The lines in the order they ran (1-based), when the program jumps or calls;
    /// `None` when the lines ran in the order of the text.
    pub order: Option<Vec<u32>>,
    /// Whose rules the program was read by.
    pub control: Control,
}

const NO_MOTION: u32 = 0;

impl ProgramMap {
    /// A map of a program of `lines` lines, read by `control`'s rules.
    pub(crate) fn new(lines: usize, control: Control) -> Self {
        ProgramMap { executions: vec![0; lines], motions: vec![0; lines], contexts: Vec::new(), order: None, control }
    }

    /// Records that 0-based line `index` ran, moving as `motion` (kept from its first run).
    pub(crate) fn record(&mut self, index: usize, motion: LineMotion) {
        let Some(runs) = self.executions.get_mut(index) else { return };
        *runs = runs.saturating_add(1);
        if *runs > 1 {
            return;
        }
        let (c, direct) = match motion {
            LineMotion::None => {
                self.motions[index] = NO_MOTION;
                return;
            }
            LineMotion::Derived(c) => (c, false),
            LineMotion::Direct(c) => (c, true),
        };
        if self.contexts.last() != Some(&c) {
            self.contexts.push(c);
        }
        let k = (self.contexts.len() - 1) as u32;
        self.motions[index] = 2 * k + 1 + u32::from(direct);
    }

    /// The record of 1-based line `line`, if it ran.
    pub fn line(&self, line: u32) -> Option<LineRecord> {
        let index = line.checked_sub(1)? as usize;
        let executions = *self.executions.get(index)?;
        if executions == 0 {
            return None;
        }
        let code = self.motions[index];
        let motion = match code {
            NO_MOTION => LineMotion::None,
            _ => {
                let c = self.contexts[((code - 1) / 2) as usize];
                if code.is_multiple_of(2) {
                    LineMotion::Direct(c)
                } else {
                    LineMotion::Derived(c)
                }
            }
        };
        Some(LineRecord { executions, motion })
    }

    /// Lines in the program.
    pub fn lines(&self) -> usize {
        self.executions.len()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lines_keep_their_first_motion_and_count_their_runs() {
        let context = MotionContext {
            units: Units::Inch,
            absolute: true,
            absolute_centres: false,
            plane: Plane::Xy,
            feed_mode: FeedMode::PerMinute,
            spindle_rpm: None,
            arc: Some(ArcFormat::Radius),
            turns_word: false,
            frame: Affine::IDENTITY,
        };
        let mut map = ProgramMap::new(3, Control::LinuxCnc);
        map.record(0, LineMotion::Direct(context));
        map.record(1, LineMotion::Derived(context));
        map.record(1, LineMotion::None);
        assert_eq!(map.line(1).unwrap().motion, LineMotion::Direct(context));
        assert_eq!(map.line(2).unwrap(), LineRecord { executions: 2, motion: LineMotion::Derived(context) });
        assert_eq!(map.line(3), None);
        assert_eq!(map.line(0), None);
        assert_eq!(map.lines(), 3);
    }

    #[test]
    fn the_affine_map_returns_program_coordinates() {
        let a = Affine { rotation_deg: 90.0, translation: P3::new(100.0, 0.0, -2.0) };
        let p = a.to_program(P3::new(100.0, 10.0, 3.0));
        assert!((p.x - 10.0).abs() < 1e-12 && p.y.abs() < 1e-12 && (p.z - 5.0).abs() < 1e-12, "{p:?}");
        assert_eq!(Affine::IDENTITY.to_program(P3::new(1.0, 2.0, 3.0)), P3::new(1.0, 2.0, 3.0));
        let q = a.to_out(p);
        assert!((q.x - 100.0).abs() < 1e-12 && (q.y - 10.0).abs() < 1e-12 && (q.z - 3.0).abs() < 1e-12, "{q:?}");
    }
}
