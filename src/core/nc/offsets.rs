//! G10: the program sets its own tool table and work offsets.
//!
//! - `G10 L1 P<tool> R<radius> Z<length>` (LinuxCNC): the tool table.
//! - `G10 L2 P<system> X Y Z [R<rotation>]`: the machine coordinates of a work coordinate
//!   system's origin (LinuxCNC P0 is the active system, 1–9 G54–G59.3; Fanuc P1–P6 are
//!   G54–G59, P0 its external offset).
//! - `G10 L20 P<system> X Y Z` (LinuxCNC): the system's origin is set so that the tool's
//!   current position has the given coordinates. Fanuc's `G10 L20 P<n>` sets the machine
//!   coordinates of the extended system G54.1 Pn.
//! - `G10 L10/L11 P<H> R<length>` and `G10 L12/L13 P<D> R<radius>` (Fanuc): tool offset
//!   geometry and wear.

use super::block::{bit, Block, AXES};
use super::frame::{SystemId, EXTENDED_BASE};
use super::machine::{whole_number, Machine};
use super::report::{Failed, Line};

/// Work coordinate systems LinuxCNC numbers with P (G54–G59.3).
const LINUXCNC_SYSTEMS: u32 = 9;
/// Work coordinate systems Fanuc numbers with P in `G10 L2` (G54–G59).
const FANUC_SYSTEMS: u32 = 6;
/// Extended systems Fanuc numbers with P in `G10 L20` (G54.1 P1–P300).
const FANUC_EXTENDED_SYSTEMS: u32 = 300;

/// Runs a G10 line; returns the letters it read.
pub(crate) fn g10(m: &mut Machine, b: &Block, line: &mut Line, i: usize) -> Result<u32, Failed> {
    if b.value(b'L').is_none() {
        let reason = "G10 needs L: L1 (tool table), L2 or L20 (work offsets), L10–L13 (Fanuc tool offsets)";
        return Err(line.error_at(i, reason));
    }
    let l = whole_number(b, line, b'L', "G10 L")?;
    m.claim(b, line, b'P', "G10")?;
    let p = match b.value(b'P') {
        Some(_) => Some(whole_number(b, line, b'P', "G10 P")?),
        None => None,
    };
    let scale = m.scale();
    let values = m.axis_values(b);
    let fanuc = m.settings.fanuc;
    let read = bit(b'L') | bit(b'P') | bit(b'R') | AXES | bit(b'I') | bit(b'J') | bit(b'Q');
    let need_p = |line: &mut Line, what: &str| line.error_at(i, format!("G10 L{l} needs P, {what}"));
    match l {
        1 if !fanuc => {
            let Some(tool) = p else { return Err(need_p(line, "the tool number")) };
            if let Some(r) = b.value(b'R') {
                m.tools.set_radius(tool, r * scale, false);
            }
            if let Some(z) = values[2] {
                m.tools.set_length(tool, z, false);
            }
        }
        10..=13 if fanuc => {
            let Some(number) = p else { return Err(need_p(line, "the offset number")) };
            let Some(r) = b.value(b'R') else {
                return Err(line.error_at(i, format!("G10 L{l} needs R, the offset value")));
            };
            let wear = l == 11 || l == 13;
            if l <= 11 {
                m.tools.set_length(number, r * scale, wear);
            } else {
                m.tools.set_radius(number, r * scale, wear);
            }
        }
        10 | 11 => line.warn(format!("G10 L{l} (tool touch-off) is not followed: the tool table keeps its lengths")),
        2 | 20 => {
            if m.comp.is_some() {
                return Err(line.error_at(i, "G10 while cutter compensation is on: turn it off (G40) first"));
            }
            let Some(p) = p else { return Err(need_p(line, "the work coordinate system")) };
            if fanuc && l == 2 && p == 0 {
                line.warn("G10 L2 P0 sets Fanuc's external work offset, which shifts every system: not followed");
                return Ok(read);
            }
            let id = system(m, b, line, p, fanuc && l == 20)?;
            if l == 20 && !fanuc {
                m.frame.set_current_as(id, m.modal.position, values);
            } else {
                let rotation = if fanuc { None } else { b.value(b'R') };
                m.frame.set_machine_offset(id, values, rotation);
            }
        }
        _ => return Err(line.error_at(b.word(b'L'), format!("G10 L{l} is not a form this interpreter knows"))),
    }
    Ok(read)
}

/// The system a G10 P word names.
fn system(m: &Machine, b: &Block, line: &mut Line, p: u32, extended: bool) -> Result<SystemId, Failed> {
    let (count, first) = match (m.settings.fanuc, extended) {
        (true, true) => (FANUC_EXTENDED_SYSTEMS, EXTENDED_BASE + 1),
        (true, false) => (FANUC_SYSTEMS, 0),
        (false, _) => (LINUXCNC_SYSTEMS, 0),
    };
    if p == 0 && !m.settings.fanuc {
        return Ok(m.frame.active);
    }
    if !(1..=count).contains(&p) {
        return Err(line.error_at(b.word(b'P'), format!("G10 P must be 1 to {count} here")));
    }
    Ok(first + (p - 1) as SystemId)
}
