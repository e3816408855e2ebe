//! The parts of [`ParseOptions`](super::ParseOptions) that say how a control reads a
//! program: whose rules, how far an arc may miss its circle, and the tool table.

use serde::{Deserialize, Serialize};

use crate::core::toolpath::Units;

/// Whose rules apply where LinuxCNC and Fanuc read a program differently.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Control {
    /// Fanuc's if the program looks like a Fanuc program (a program number, `%` tape
    /// marks, `M98`/`M99`/`G65`, macro statements), LinuxCNC's otherwise.
    #[default]
    Auto,
    #[serde(alias = "linuxcnc")]
    LinuxCnc,
    Fanuc,
}

/// An arc's end may miss the circle through its start by at most `absolute`, or by up to
/// `maximum` if that is within `relative` of the radius (LinuxCNC's rule for centre-format
/// arcs: "more than 0.5 mm, or more than 0.005 mm and 0.1 % of the radius, is an error").
/// Lengths are in the program's units; `None` takes the control's default for them.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct ArcTolerance {
    /// Always accepted, program units (default 0.005 mm or 0.0005 in).
    pub absolute: Option<f64>,
    /// Accepted up to this fraction of the radius (default 0.001).
    pub relative: f64,
    /// Never accepted beyond, program units (default 0.5 mm or 0.05 in).
    pub maximum: Option<f64>,
}

/// LinuxCNC's arc tolerances (its G-code manual, "Center Format Arcs").
pub const ARC_TOLERANCE_ABSOLUTE_MM: f64 = 0.005;
pub const ARC_TOLERANCE_ABSOLUTE_INCH: f64 = 0.0005;
pub const ARC_TOLERANCE_MAXIMUM_MM: f64 = 0.5;
pub const ARC_TOLERANCE_MAXIMUM_INCH: f64 = 0.05;
pub const ARC_TOLERANCE_RELATIVE: f64 = 0.001;

impl Default for ArcTolerance {
    fn default() -> Self {
        ArcTolerance { absolute: None, relative: ARC_TOLERANCE_RELATIVE, maximum: None }
    }
}

impl ArcTolerance {
    /// The absolute and maximum tolerances in `units`, program units.
    pub fn in_units(&self, units: Units) -> (f64, f64) {
        let (absolute, maximum) = match units {
            Units::Mm => (ARC_TOLERANCE_ABSOLUTE_MM, ARC_TOLERANCE_MAXIMUM_MM),
            Units::Inch => (ARC_TOLERANCE_ABSOLUTE_INCH, ARC_TOLERANCE_MAXIMUM_INCH),
        };
        (self.absolute.unwrap_or(absolute), self.maximum.unwrap_or(maximum))
    }

    /// Whether a miss of `miss` on an arc of `radius` (both in program units) is accepted.
    pub fn accepts(&self, units: Units, miss: f64, radius: f64) -> bool {
        let (absolute, maximum) = self.in_units(units);
        miss <= absolute || (miss <= maximum && miss <= self.relative * radius)
    }

    /// The fault in a tolerance given by a request, if any.
    pub fn check(&self) -> Result<(), String> {
        for (name, value) in [("absolute", self.absolute), ("maximum", self.maximum), ("relative", Some(self.relative))]
        {
            if let Some(v) = value {
                if !(v.is_finite() && v >= 0.0) {
                    return Err(format!("{name} must be a finite number ≥ 0"));
                }
            }
        }
        Ok(())
    }
}

/// How far above the stock G53, G28 and G30 retract by default, mm (**assumed**: the
/// clearance the planners keep above the stock).
pub const RETRACT_CLEARANCE_MM: f64 = 5.0;

/// Most times a program's loops may repeat, all loops together, by default.
pub const DEFAULT_MAX_LOOP_ITERATIONS: u64 = 1_000_000;

/// Deepest nesting of subroutine and macro calls by default (LinuxCNC allows more; a
/// program nesting deeper than this recurses without end).
pub const DEFAULT_MAX_CALL_DEPTH: u32 = 32;

/// One entry of the tool table: what a T, D or H number stands for.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ToolEntry {
    /// The tool, D or H number.
    pub number: u32,
    /// The radius G41/G42 compensate by, mm.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub radius_mm: Option<f64>,
    /// The tool length G43 offsets by, mm.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub length_mm: Option<f64>,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_linuxcnc_arc_rule_accepts_rounding_and_refuses_real_misses() {
        let t = ArcTolerance::default();
        // A 4-decimal inch program misses by 0.004 mm = 0.000157 in.
        assert!(t.accepts(Units::Inch, 0.000_157, 0.05));
        assert!(t.accepts(Units::Mm, 0.004, 1.0));
        // 0.02 mm on a 100 mm radius is 0.02 %: accepted; on a 5 mm radius 0.4 %: not.
        assert!(t.accepts(Units::Mm, 0.02, 100.0));
        assert!(!t.accepts(Units::Mm, 0.02, 5.0));
        // Never more than 0.5 mm.
        assert!(!t.accepts(Units::Mm, 0.6, 10_000.0));
        let loose = ArcTolerance { absolute: Some(0.05), ..ArcTolerance::default() };
        assert!(loose.accepts(Units::Mm, 0.02, 5.0));
        assert!(ArcTolerance { relative: f64::NAN, ..ArcTolerance::default() }.check().is_err());
    }
}
