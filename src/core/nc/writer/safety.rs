//! The writer's safety rules, for every path it writes (generated, or sent as JSON moves):
//! the tool called with its length offset on a move of Z alone to the safe height; the
//! first XY move made at that height; Z up before XY and XY before Z down on every rapid;
//! the footer's retract and stops.

use super::{
    Writer, G_LENGTH_OFFSET, G_RAPID, M_COOLANT_OFF, M_END_FANUC, M_END_LINUXCNC, M_SPINDLE_OFF, M_TOOL_CHANGE,
};
use crate::core::nc::arcs::{coord, plane_axes};
use crate::core::toolpath::{Motion, Move, Plane, Toolpath};

/// The highest the tool goes along `path`, mm: the highest end of any move, or, for an arc
/// in the ZX or YZ plane, the top of its circle (a bound: the arc may not reach it). `None`
/// for a path without moves.
pub fn highest_point_mm(path: &Toolpath) -> Option<f64> {
    path.moves.iter().map(highest_of).reduce(f64::max)
}

fn highest_of(m: &Move) -> f64 {
    let ends = m.start.z.max(m.end.z);
    match m.motion {
        Motion::Arc { center, plane: plane @ (Plane::Zx | Plane::Yz), .. } => {
            let [a, b, _] = plane_axes(plane);
            let radius = (coord(m.start, a) - coord(center, a)).hypot(coord(m.start, b) - coord(center, b));
            ends.max(center.z + radius)
        }
        _ => ends,
    }
}

impl Writer<'_> {
    /// Calls `tool`: Z alone up to the safe height if the tool is below it, `T.. M6`, then
    /// `G0 G43 H.. Z<safe>`. Where the tool is in XY is unknown after it.
    pub(super) fn call_tool(&mut self, tool: u32, length_offset: u32) {
        self.retract();
        self.code('T', tool);
        self.code_line('M', M_TOOL_CHANGE);
        self.position = [None; 3];
        self.motion = None;
        match self.safe_z {
            Some(safe) => {
                self.motion_code(G_RAPID);
                self.code('G', G_LENGTH_OFFSET);
                self.code('H', length_offset);
                self.rapid_axes([None, None, Some(safe)], None);
            }
            // No move, no safe height: the offset applies at the next Z move, if any.
            None => {
                self.code('G', G_LENGTH_OFFSET);
                self.code_line('H', length_offset);
            }
        }
    }

    /// Z alone up to the safe height, if the tool is known to be below it.
    pub(super) fn retract(&mut self) {
        if let (Some(z), Some(safe)) = (self.position[2], self.safe_z) {
            if z < safe {
                self.rapid_axes([None, None, Some(safe)], None);
            }
        }
    }

    /// A rapid to `end`: Z first when it rises (or where the tool is in Z is unknown), XY
    /// first when it descends, so that the tool never moves in XY below either end. S of
    /// `m` if it changes (never F: a rapid's modal feed waits for the next feed move).
    pub(super) fn rapid_to(&mut self, end: [i64; 3], m: Option<&Move>) {
        let [x, y, z] = end.map(Some);
        let moves_xy = self.position[0] != x || self.position[1] != y;
        let rises = self.position[2].is_none_or(|here| end[2] > here);
        if moves_xy && rises {
            self.rapid_axes([None, None, z], m);
        }
        self.rapid_axes([x, y, None], m);
        self.rapid_axes([None, None, z], m);
    }

    /// A G0 line to the given axes (`None`: the axis stays); nothing if none changes.
    fn rapid_axes(&mut self, axes: [Option<i64>; 3], m: Option<&Move>) {
        let changes: Vec<usize> = (0..3).filter(|&a| axes[a].is_some() && axes[a] != self.position[a]).collect();
        if changes.is_empty() {
            // `G43 H..` written before a rapid that turned out to be needless stays on its line.
            self.end_line();
            return;
        }
        self.motion_code(G_RAPID);
        for a in changes {
            let units = axes[a].unwrap_or_default();
            self.number(super::AXIS_LETTERS[a], super::format::Fixed { units, decimals: self.decimals });
            self.position[a] = Some(units);
        }
        if let Some(rpm) = m.and_then(|m| m.spindle_rpm) {
            self.speed(rpm);
        }
        self.end_line();
    }

    /// Z alone to the safe height (if the body has not), the spindle and the coolant stopped
    /// if they run, the end.
    pub(super) fn footer(&mut self) {
        self.retract();
        if self.spindle_running {
            self.spindle_running = false;
            self.code_line('M', M_SPINDLE_OFF);
        }
        if self.coolant_on {
            self.coolant_on = false;
            self.code_line('M', M_COOLANT_OFF);
        }
        self.code_line('M', if self.fanuc { M_END_FANUC } else { M_END_LINUXCNC });
        if self.fanuc {
            self.raw_line("%");
        }
    }
}
