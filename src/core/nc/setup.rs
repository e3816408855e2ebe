//! The G codes that set up where and how the tool cuts: cutter radius compensation
//! (G40, G41, G42), tool length offsets (G43, G43.1, G44, G49), work coordinate systems
//! (G54–G59.3, G54.1 P), the G92/G52 offset, G10, and the moves the planner can only read
//! as retracts (G28, G30, G53).

use super::block::{bit, Block, AXES};
use super::codes::{AxisOffsetCode, CompCode, GCode, LengthCode};
use super::compensation::{Compensation, Side, StartUp};
use super::frame::{SystemId, EXTENDED_BASE};
use super::machine::{whole_number, LengthOffset, Machine};
use super::map::LineMotion;
use super::report::{Failed, Line};
use crate::core::toolpath::{Motion, Plane, P3};

impl Machine {
    /// G40, G41, G42 (and LinuxCNC's G41.1, G42.1).
    pub(crate) fn cutter_compensation(
        &mut self,
        b: &Block,
        line: &mut Line,
        code: CompCode,
        i: usize,
    ) -> Result<u32, Failed> {
        self.end_compensation(line, Some(i))?;
        let (left, diameter) = match code {
            CompCode::Off => return Ok(0),
            CompCode::Table { left } => (left, false),
            CompCode::Diameter { left } => (left, true),
        };
        if self.modal.plane != Plane::Xy {
            return Err(line.error_at(i, "cutter compensation works in the XY plane (G17) only"));
        }
        let scale = self.scale();
        let (radius, source) = match (b.value(b'D'), diameter) {
            (Some(d), true) => (d * scale / 2.0, None),
            (None, true) => return Err(line.error_at(i, "G41.1/G42.1 need D, the tool diameter")),
            (d, false) => {
                let number = match d {
                    Some(_) => Some(whole_number(b, line, b'D', "the offset number D")?),
                    None => self.modal.tool,
                };
                match (number.and_then(|n| self.tools.radius_mm(n)), self.settings.tool_radius_mm) {
                    (Some(r), _) => (r, None),
                    (None, Some(r)) => (r, number),
                    (None, None) => {
                        let reason = "G41/G42 need the tool radius: give D with a tool_table entry, or the tool";
                        return Err(line.error_at(i, reason));
                    }
                }
            }
        };
        if !(radius.is_finite() && radius >= 0.0) {
            return Err(line.error_at(b.word(b'D'), "the compensation radius must be ≥ 0"));
        }
        if let Some(n) = source {
            let what = if b.has(b'D') { format!("D{n} is not in the tool table") } else { "no D word".to_string() };
            self.warn_once(
                line,
                "comp-radius",
                format!("{} compensates by the tool's radius, {radius:.4} mm ({what}); a program of tool-centre moves with wear compensation needs a tool_table entry with radius 0", line.word_text(i)),
            );
        }
        let side = if left { Side::Left } else { Side::Right };
        let startup = if self.settings.fanuc { StartUp::Fanuc } else { StartUp::LinuxCnc };
        self.comp = Some(Compensation::new(side, radius, startup, self.modal.position));
        Ok(bit(b'D'))
    }

    /// Ends cutter compensation: its last move comes out, and the tool is where it ends.
    pub fn end_compensation(&mut self, line: &mut Line, anchor: Option<usize>) -> Result<(), Failed> {
        let Some(mut comp) = self.comp.take() else {
            return Ok(());
        };
        let mut out = Vec::new();
        let end = comp.finish(&mut out).map_err(|reason| line.error_near(anchor, reason))?;
        self.moves.extend(out);
        self.modal.position = end;
        Ok(())
    }

    /// G43, G43.1, G44, G49.
    pub(crate) fn tool_length(
        &mut self,
        b: &Block,
        line: &mut Line,
        code: LengthCode,
        i: usize,
    ) -> Result<u32, Failed> {
        match code {
            LengthCode::Off => {
                self.modal.length_offset = None;
                Ok(0)
            }
            LengthCode::Dynamic => {
                let Some(z) = b.value(b'Z') else {
                    return Err(line.error_at(i, "G43.1 needs Z, the tool length offset"));
                };
                self.length_offset_used = true;
                self.modal.length_offset = Some(LengthOffset::Dynamic(z * self.scale()));
                Ok(bit(b'Z'))
            }
            LengthCode::Offset | LengthCode::Negative => {
                if code == LengthCode::Negative {
                    line.warn("G44 (negative length offset) is read as G43");
                }
                let h = match b.value(b'H') {
                    Some(_) => Some(whole_number(b, line, b'H', "the offset number H")?),
                    None => self.modal.tool,
                };
                self.length_offset_used = true;
                self.modal.length_offset = h.filter(|&h| h > 0).map(LengthOffset::Table);
                Ok(bit(b'H'))
            }
        }
    }

    /// The tip's Z correction of the active length offset, mm: the difference of the
    /// offset's length and the spindle tool's, where the tool table gives both.
    pub fn tip_dz(&mut self, line: &mut Line) -> f64 {
        let tool = self.modal.tool;
        let tool_length = tool.and_then(|t| self.tools.length_mm(t));
        let (offset_length, name) = match self.modal.length_offset {
            None => return 0.0,
            Some(LengthOffset::Table(h)) if Some(h) == tool => return 0.0,
            Some(LengthOffset::Table(h)) => (self.tools.length_mm(h), format!("H{h}")),
            Some(LengthOffset::Dynamic(l)) => (Some(l), "G43.1".to_string()),
        };
        match (offset_length, tool_length) {
            (Some(a), Some(b)) => a - b,
            _ => {
                let tool_name = tool.map_or("no tool".to_string(), |t| format!("tool {t}"));
                self.warn_once(
                    line,
                    &format!("tlo-{name}-{tool_name}"),
                    format!("the length offset {name} is for another tool than the spindle's ({tool_name}) and the tool table does not give both lengths: Z is read as the tool tip"),
                );
                0.0
            }
        }
    }

    /// G54–G59.3 and Fanuc's G54.1 P.
    pub(crate) fn coordinate_system(
        &mut self,
        b: &Block,
        line: &mut Line,
        code: GCode,
        i: usize,
    ) -> Result<u32, Failed> {
        match code {
            GCode::CoordinateSystem(k) => {
                self.frame.select(SystemId::from(k));
                Ok(0)
            }
            _ => {
                self.claim(b, line, b'P', "G54.1")?;
                let Some(_) = b.value(b'P') else {
                    return Err(line.error_at(i, "G54.1 needs P, the extended work coordinate system (1–300)"));
                };
                let p = whole_number(b, line, b'P', "G54.1 P")?;
                if !(1..=300).contains(&p) {
                    return Err(line.error_at(b.word(b'P'), "G54.1 P must be 1 to 300"));
                }
                self.frame.select(EXTENDED_BASE + p as SystemId);
                Ok(bit(b'P'))
            }
        }
    }

    /// The axis values of a line, mm (`None` where an axis is not written).
    pub fn axis_values(&self, b: &Block) -> [Option<f64>; 3] {
        let scale = self.scale();
        [b.value(b'X'), b.value(b'Y'), b.value(b'Z')].map(|v| v.map(|v| v * scale))
    }

    /// G10, G28, G30, G28.1, G30.1, G52, G92 and its kin: they take the axis words.
    pub(crate) fn non_modal(&mut self, b: &Block, line: &mut Line, code: GCode, i: usize) -> Result<u32, Failed> {
        let values = self.axis_values(b);
        match code {
            GCode::SetHome => Ok(AXES),
            GCode::Home { secondary } => {
                let what = if secondary { "G30" } else { "G28" };
                self.retract(line, i, what)?;
                Ok(AXES)
            }
            GCode::SetOffsets => super::offsets::g10(self, b, line, i),
            GCode::AxisOffset(kind) => {
                if self.comp.is_some() {
                    return Err(line.error_at(i, "G92/G52 while cutter compensation is on: turn it off (G40) first"));
                }
                match kind {
                    AxisOffsetCode::Set => {
                        if values.iter().all(Option::is_none) {
                            return Err(line.error_at(i, "G92 needs at least one axis word"));
                        }
                        self.frame.set_axis_offset_to(self.modal.position, values);
                    }
                    AxisOffsetCode::Local => self.frame.set_local_offset(values),
                    AxisOffsetCode::Clear => self.frame.axis_offset_state(true, true),
                    AxisOffsetCode::Suspend => self.frame.axis_offset_state(false, false),
                    AxisOffsetCode::Restore => self.frame.axis_offset_state(false, true),
                }
                Ok(AXES)
            }
            _ => Ok(0),
        }
    }

    /// G53, G28 and G30: the machine's offsets are unknown, so the move is read as a rapid
    /// retract straight up to the safe height.
    pub fn retract(&mut self, line: &mut Line, anchor: usize, what: &str) -> Result<(), Failed> {
        if self.comp.is_some() {
            let reason = format!("{what} while cutter compensation is on: turn it off (G40) first");
            return Err(line.error_at(anchor, reason));
        }
        let safe = self.settings.retract_z_mm.unwrap_or(self.highest_z).max(self.modal.position.z);
        line.warn(format!(
            "{what} moves in machine coordinates, which the planner cannot place without the machine's offsets: read as a rapid retract straight up to Z{safe:.3} mm"
        ));
        let here = self.modal.position;
        self.push_move(Motion::Rapid, P3::new(here.x, here.y, safe), line.number);
        self.line_motion = LineMotion::Derived(self.context(None, false));
        Ok(())
    }
}
