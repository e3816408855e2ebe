//! The parameters that describe the machine's state, read and written by a program:
//! positions, modal codes, work offsets and tool offsets (LinuxCNC's `#5220`–`#5422` and
//! `#<_x>`-style names; Fanuc's `#4001`–`#4120`, `#5001`–`#5043`, `#5221`–`#5343`, tool
//! offsets `#2001`–`#2200` and `#10001`–`#13400`), and Fanuc's alarm and stop variables.
//! Everything else is an ordinary parameter of the store.

use super::eval::Parameters;
use super::machine::{LengthOffset, Machine};
use super::map::FeedMode;
use super::params::ParamStore;
use crate::core::toolpath::{Plane, Units};

/// Work offsets: `#5221 + 20·k + axis` for G54 (k = 0) … G59.3 (k = 8).
const WORK_OFFSETS_FIRST: u32 = 5221;
const WORK_OFFSET_STRIDE: u32 = 20;
const WORK_OFFSET_SYSTEMS: u32 = 9;

/// Fanuc tool offsets, memory C: H wear, H geometry, D wear, D geometry (offset 1 first).
const FANUC_H_WEAR: u32 = 10_001;
const FANUC_H_GEOMETRY: u32 = 11_001;
const FANUC_D_WEAR: u32 = 12_001;
const FANUC_D_GEOMETRY: u32 = 13_001;
const FANUC_OFFSETS_PER_KIND: u32 = 400;
/// Fanuc tool offsets, memory A: one value per offset number (read as a length).
const FANUC_OFFSET_A: u32 = 2001;
const FANUC_OFFSETS_A: u32 = 200;

/// What a write to a system parameter does.
pub(crate) enum Written {
    /// An ordinary parameter: store it.
    Store,
    /// Done (an offset was set, or the variable is ignored).
    Done,
    /// Fanuc `#3006`: stop with a message.
    Stop,
}

/// The store, with the machine's state behind the system parameters.
pub(crate) struct Env<'a> {
    pub store: &'a ParamStore,
    pub machine: &'a Machine,
}

fn unit(m: &Machine) -> f64 {
    m.scale()
}

impl Parameters for Env<'_> {
    fn numbered(&self, n: u32) -> Result<Option<f64>, String> {
        match read(self.machine, n)? {
            Some(v) => Ok(v),
            None => Ok(self.store.get(n)),
        }
    }

    fn named(&self, name: &str) -> Option<f64> {
        predefined(self.machine, name).or_else(|| self.store.named(name))
    }
}

/// The value of system parameter `n`, if `n` is one: `Some(None)` is vacant.
fn read(m: &Machine, n: u32) -> Result<Option<Option<f64>>, String> {
    let here = m.frame.to_program(m.modal.position);
    let position = [here.x, here.y, here.z].map(|v| v / unit(m));
    if let Some((k, a)) = work_offset(n) {
        return Ok(m.frame.machine_offset(k as u16, a).map(|v| Some(v / unit(m))));
    }
    if let Some((number, kind)) = fanuc_tool_offset(m, n) {
        let value = match kind {
            OffsetKind::Length => m.tools.length_mm(number),
            OffsetKind::Radius => m.tools.radius_mm(number),
        };
        return match value {
            Some(v) => Ok(Some(Some(v / unit(m)))),
            None => Err(format!("#{n}: tool offset {number} is not in the tool table")),
        };
    }
    let modal = &m.modal;
    let fanuc = m.settings.fanuc;
    let v = match (n, fanuc) {
        (5220, false) => f64::from(m.frame.active.min(8)) + 1.0,
        (5211..=5213, false) => m.frame.axis_offset()[(n - 5211) as usize] / unit(m),
        (5400, false) => f64::from(modal.tool.unwrap_or(0)),
        (5403, false) => modal.tool.and_then(|t| m.tools.length_mm(t)).unwrap_or(0.0) / unit(m),
        (5410, false) => modal.tool.and_then(|t| m.tools.radius_mm(t)).unwrap_or(0.0) * 2.0 / unit(m),
        (5420..=5422, false) => position[(n - 5420) as usize],
        (5001..=5003 | 5041..=5043, true) => position[(n % 10 - 1) as usize],
        (5021..=5023, true) => return Err(format!("#{n} is a machine position, which the planner cannot know")),
        (1000..=1999, true) => return Err(format!("#{n} is an interface signal, which the planner cannot know")),
        (4001..=4130, true) => return Ok(Some(fanuc_modal(m, n))),
        (3001..=3012, true) => 0.0,
        _ => return Ok(None),
    };
    Ok(Some(Some(v)))
}

/// Fanuc's modal information `#4001`… of the block before.
fn fanuc_modal(m: &Machine, n: u32) -> Option<f64> {
    use super::codes::MotionCode as M;
    let modal = &m.modal;
    let v = match n {
        4001 => match modal.motion {
            Some(M::Rapid) => 0.0,
            Some(M::Linear) => 1.0,
            Some(M::Arc { clockwise: true }) => 2.0,
            Some(M::Arc { clockwise: false }) => 3.0,
            Some(M::Cycle(_)) | None => 80.0,
        },
        4002 => match modal.plane {
            Plane::Xy => 17.0,
            Plane::Zx => 18.0,
            Plane::Yz => 19.0,
        },
        4003 => {
            if modal.absolute {
                90.0
            } else {
                91.0
            }
        }
        4005 => match modal.feed_mode {
            FeedMode::PerRevolution => 95.0,
            FeedMode::InverseTime => 93.0,
            FeedMode::PerMinute => 94.0,
        },
        4006 => match modal.units {
            Units::Inch => 20.0,
            Units::Mm => 21.0,
        },
        4007 => match &m.comp {
            None => 40.0,
            Some(_) => 41.0,
        },
        4008 => match modal.length_offset {
            None => 49.0,
            Some(_) => 43.0,
        },
        4010 => {
            if modal.retract_to_r {
                99.0
            } else {
                98.0
            }
        }
        4014 => 54.0 + f64::from(m.frame.active.min(5)),
        4109 => modal.feed_mm_min? / unit(m),
        4111 => match modal.length_offset {
            Some(LengthOffset::Table(h)) => f64::from(h),
            _ => 0.0,
        },
        4119 => modal.spindle_rpm?,
        4120 => f64::from(modal.tool?),
        _ => return None,
    };
    Some(v)
}

/// LinuxCNC's predefined named parameters (upper case, as the line is compacted).
fn predefined(m: &Machine, name: &str) -> Option<f64> {
    let modal = &m.modal;
    let here = m.frame.to_program(modal.position);
    let flag = |b: bool| f64::from(u8::from(b));
    Some(match name {
        "_X" => here.x / unit(m),
        "_Y" => here.y / unit(m),
        "_Z" => here.z / unit(m),
        "_FEED" => modal.feed_mm_min.unwrap_or(0.0) / unit(m),
        "_RPM" => modal.spindle_rpm.unwrap_or(0.0),
        "_CURRENT_TOOL" => f64::from(modal.tool.unwrap_or(0)),
        "_SELECTED_TOOL" => modal.selected_tool.map_or(-1.0, f64::from),
        "_METRIC" => flag(modal.units == Units::Mm),
        "_IMPERIAL" => flag(modal.units == Units::Inch),
        "_ABSOLUTE" => flag(modal.absolute),
        "_INCREMENTAL" => flag(!modal.absolute),
        "_TOOL_OFFSET" => flag(modal.length_offset.is_some()),
        _ => return None,
    })
}

/// `(system, axis)` of a work-offset parameter.
fn work_offset(n: u32) -> Option<(u32, usize)> {
    let k = n.checked_sub(WORK_OFFSETS_FIRST)?;
    let (system, axis) = (k / WORK_OFFSET_STRIDE, k % WORK_OFFSET_STRIDE);
    (system < WORK_OFFSET_SYSTEMS && axis < 3).then_some((system, axis as usize))
}

#[derive(Clone, Copy)]
enum OffsetKind {
    Length,
    Radius,
}

/// `(offset number, kind)` of a Fanuc tool-offset variable (geometry; wear counts too).
fn fanuc_tool_offset(m: &Machine, n: u32) -> Option<(u32, OffsetKind)> {
    if !m.settings.fanuc {
        return None;
    }
    let within = |first: u32, count: u32| (first..first + count).contains(&n).then_some(n - first + 1);
    if let Some(k) = within(FANUC_OFFSET_A, FANUC_OFFSETS_A) {
        return Some((k, OffsetKind::Length));
    }
    for (first, kind) in [
        (FANUC_H_GEOMETRY, OffsetKind::Length),
        (FANUC_H_WEAR, OffsetKind::Length),
        (FANUC_D_GEOMETRY, OffsetKind::Radius),
        (FANUC_D_WEAR, OffsetKind::Radius),
    ] {
        if let Some(k) = within(first, FANUC_OFFSETS_PER_KIND) {
            return Some((k, kind));
        }
    }
    None
}

/// Writes system parameter `n` (a value in program units); ordinary ones are left to the
/// store.
pub(crate) fn write(m: &mut Machine, n: u32, value: Option<f64>) -> Result<Written, String> {
    let scale = unit(m);
    if let Some((k, a)) = work_offset(n) {
        let mut values = [None; 3];
        values[a] = Some(value.unwrap_or(0.0) * scale);
        m.frame.set_machine_offset(k as u16, values, None);
        return Ok(Written::Done);
    }
    if let Some((number, kind)) = fanuc_tool_offset(m, n) {
        let v = value.unwrap_or(0.0) * scale;
        let wear = (FANUC_H_WEAR..FANUC_H_WEAR + FANUC_OFFSETS_PER_KIND).contains(&n)
            || (FANUC_D_WEAR..FANUC_D_WEAR + FANUC_OFFSETS_PER_KIND).contains(&n);
        match kind {
            OffsetKind::Length => m.tools.set_length(number, v, wear),
            OffsetKind::Radius => m.tools.set_radius(number, v, wear),
        }
        return Ok(Written::Done);
    }
    if !m.settings.fanuc {
        return Ok(Written::Store);
    }
    match n {
        3000 => Err(format!("the program raises alarm #3000 = {}: it stops here", value.unwrap_or(0.0))),
        3006 => Ok(Written::Stop),
        3001..=3005 | 3901 | 3902 => Ok(Written::Done),
        1000..=1999 | 4001..=4130 | 5001..=5100 => Err(format!("#{n} is a system variable the program cannot set")),
        _ => Ok(Written::Store),
    }
}
