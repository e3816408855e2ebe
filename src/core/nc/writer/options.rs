//! How to write a program: the dialect, numbering, header comments, resolution, and what
//! the header may add (tool and length offset, safe height, spindle speed, coolant). Plain
//! data that the service reads from JSON (`{"dialect": "linux_cnc", "line_numbers":
//! {"start": 100}}`, every field optional, unknown fields refused).

use serde::{Deserialize, Serialize};

pub use crate::core::coolant::Coolant;

/// Default decimals of lengths: 3, a micron in mm.
pub const DEFAULT_DECIMALS: u32 = 3;

/// Default decimals of feeds: 1 (the planner rounds feeds already; `F1234.5` at most).
pub const DEFAULT_FEED_DECIMALS: u32 = 1;

/// The tool called when neither the options nor the path name one: `T1`, the first pocket
/// (**assumed**: dieplan's programs use one tool, and the papers' programs name none).
pub const DEFAULT_TOOL_NUMBER: u32 = 1;

/// Default first N number and step.
const DEFAULT_SEQUENCE_START: u32 = 10;
const DEFAULT_SEQUENCE_STEP: u32 = 10;

/// The control a program is written for.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Dialect {
    /// Fanuc and ISO controls: `%`, `O0001`, decimal points everywhere, `M30`.
    #[default]
    Fanuc,
    /// LinuxCNC (RS274/NGC): no `%` or O number, `P` turns on arcs, `M2`.
    #[serde(alias = "linuxcnc")]
    LinuxCnc,
}

/// N numbers: the first and the step.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct LineNumbers {
    /// First N number (default 10).
    pub start: u32,
    /// Added for each line (default 10).
    pub step: u32,
}

impl Default for LineNumbers {
    fn default() -> Self {
        LineNumbers { start: DEFAULT_SEQUENCE_START, step: DEFAULT_SEQUENCE_STEP }
    }
}

/// How to write a program.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct WriterOptions {
    /// Fanuc (default) or LinuxCNC.
    pub dialect: Dialect,
    /// Fanuc program number, `O0001` for 1 (default 1; not written for LinuxCNC).
    pub program_number: u32,
    /// N numbers on every line (default: none).
    pub line_numbers: Option<LineNumbers>,
    /// A comment in the header.
    pub title: Option<String>,
    /// A comment in the header, written only if given (the output is otherwise the same
    /// for the same input).
    pub timestamp: Option<String>,
    /// Coolant switched on after the spindle starts (`M7` mist, `M8` flood) and off (`M9`)
    /// at the end, unless the path has its own coolant events (default: off).
    pub coolant: Coolant,
    /// Decimals of lengths, mm (default 3, at most [`MAX_DECIMALS`](super::MAX_DECIMALS)).
    pub decimals: u32,
    /// Decimals of feeds, mm/min (default 1, at most [`MAX_DECIMALS`](super::MAX_DECIMALS)).
    pub feed_decimals: u32,
    /// Tool called in the header when the path has no tool change before its first move
    /// (default: the first move's tool, else [`DEFAULT_TOOL_NUMBER`]).
    pub tool_number: Option<u32>,
    /// H number of that tool's length offset (default: its tool number).
    pub length_offset: Option<u32>,
    /// Height of the safe plane, mm: the program goes there with Z alone before its first XY
    /// move and after each tool change, and ends there. Never below the path's highest
    /// point, which is the default.
    pub safe_z_mm: Option<f64>,
    /// Spindle speed for the header's spindle start, used only if no move has one, min⁻¹.
    pub spindle_rpm: Option<f64>,
}

impl Default for WriterOptions {
    fn default() -> Self {
        WriterOptions {
            dialect: Dialect::Fanuc,
            program_number: 1,
            line_numbers: None,
            title: None,
            timestamp: None,
            coolant: Coolant::Off,
            decimals: DEFAULT_DECIMALS,
            feed_decimals: DEFAULT_FEED_DECIMALS,
            tool_number: None,
            length_offset: None,
            safe_z_mm: None,
            spindle_rpm: None,
        }
    }
}
