//! A tool path as plain data: the moves of an NC program (or of a JSON move list) with
//! their source line numbers, and the events between them. Paths that dieplan generates
//! also label their parts with [`Section`] events (see `toolpath/section.rs`).

mod length;
mod section;

pub use length::{arc_sweep, in_plane, move_length, PlanePoint};
pub use section::{labels_of, section_events, Section, Step};

use serde::{Deserialize, Serialize};

/// A point, mm.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct P3 {
    pub x: f64,
    pub y: f64,
    pub z: f64,
}

impl P3 {
    pub const fn new(x: f64, y: f64, z: f64) -> P3 {
        P3 { x, y, z }
    }
}

/// The plane of circular interpolation (G17, G18, G19).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Plane {
    /// G17: arcs in XY, helix along Z.
    Xy,
    /// G18: arcs in ZX, helix along Y.
    Zx,
    /// G19: arcs in YZ, helix along X.
    Yz,
}

/// How the tool moves from `start` to `end`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(tag = "type", rename_all = "snake_case")]
pub enum Motion {
    /// G0: positioning at the rapid rate.
    Rapid,
    /// G1: straight feed move.
    Linear,
    /// G2/G3: circular or helical feed move about `center` (absolute coordinates; its
    /// coordinate along the plane's normal equals `start`'s). `clockwise` is G2, seen
    /// looking down the positive normal of the plane (the usual convention). `turns` is
    /// the number of extra full turns (LinuxCNC's P word − 1; 0 for a plain arc). A
    /// move whose `end` equals its `start` in the plane is a full circle.
    Arc { center: P3, clockwise: bool, plane: Plane, turns: u32 },
}

/// One move of a tool path.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Move {
    pub motion: Motion,
    pub start: P3,
    pub end: P3,
    /// The programmed (modal) feed, mm/min; `None` before the first F word.
    pub feed_mm_min: Option<f64>,
    /// The modal spindle speed, min⁻¹; `None` before the first S word.
    pub spindle_rpm: Option<f64>,
    /// The tool in the spindle (after the last M6), if known.
    pub tool: Option<u32>,
    /// 1-based line number in the source (the JSON form: 1-based index of the move).
    pub line: u32,
}

/// Something that happens between moves.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(tag = "type", rename_all = "snake_case")]
pub enum EventKind {
    /// M6 with the T word in effect.
    ToolChange { tool: u32 },
    /// M3 (clockwise = true) or M4.
    SpindleOn { clockwise: bool },
    /// M5.
    SpindleOff,
    /// G4 dwell.
    Dwell { seconds: f64 },
    /// M7/M8 (on) or M9 (off).
    Coolant { on: bool },
    /// M0/M1: program stop.
    Stop,
    /// M2/M30: end of program (moves after it are not read).
    End,
    /// The start of a part of a generated program (an operation of a layer): a label, which
    /// the writer writes as a comment and the machine does not see.
    Section(Section),
}

impl EventKind {
    /// `true` for labels ([`EventKind::Section`]): nothing happens on the machine there, so
    /// the motion does not stop; every other event is an M code or a dwell.
    pub fn is_label(&self) -> bool {
        matches!(self, EventKind::Section(_))
    }
}

/// An event and where it happens: before move `before_move` (= the number of moves
/// read before it).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Event {
    pub kind: EventKind,
    pub before_move: usize,
    pub line: u32,
}

/// Units the source was written in (moves are always stored in mm).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Units {
    Mm,
    Inch,
}

/// A parsed tool path.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Toolpath {
    pub moves: Vec<Move>,
    pub events: Vec<Event>,
    /// Units of the source at its end (moves are in mm whatever the source used).
    pub source_units: Units,
    /// Things read but worth telling the user (e.g. an ignored G64 P tolerance).
    pub warnings: Vec<String>,
}
