//! NC programs in: an interpreter of the G-code that LinuxCNC and Fanuc controls run in
//! 3-axis milling, and the equivalent JSON move list, both read into a
//! [`Toolpath`](crate::core::toolpath::Toolpath) of the tool tip in mm. NC programs out:
//! the writer ([`write_program`]) turns a tool path back into a Fanuc or LinuxCNC program
//! that this interpreter reads to the same moves; see `writer.rs`.
//!
//! The interpreter runs the program as the control would: parameters and expressions
//! (`#1`, `#<name>`, `[#1*2+SIN[30]]`), LinuxCNC O-words (subroutines, `if`, `while`,
//! `do`, `repeat`, `break`, `continue`) and Fanuc Custom Macro B (`IF [..] GOTO n`,
//! `WHILE [..] DO m`, `M98`/`M99` subprograms in the same text, `G65` macro calls), work
//! coordinate systems and offsets (G54–G59.3, G10 L2/L20, G92, G52), tool length offsets
//! (G43/G49), cutter radius compensation (G41/G42) on the tool table, feed modes (G93,
//! G94, G95), polar words (`@`, `^`), canned drilling, tapping and boring cycles. Moves in
//! machine coordinates or to the home position (G53, G28, G30) cannot be placed without
//! the machine's offsets: they are read as a straight retract up to a safe height, with a
//! warning. Whatever it refuses names the line, the column and the word, one error per
//! bad word, all of them at once (up to [`MAX_NC_ERRORS`]); a line with an error changes
//! nothing.
//!
//! Choices worth knowing:
//! - Rapid and linear moves of zero length are dropped (arcs never are: end = start is a
//!   full circle); see `motion.rs`.
//! - Arcs whose end is off the circle by no more than the [`ArcTolerance`] are accepted
//!   and their centre moved onto the bisector of the chord, so the arc is exact.
//! - Lengths are stored in mm whatever the units (G20 × [`MM_PER_INCH`]).
//! - Where the two controls differ (an unset parameter, the cutter compensation lead-in,
//!   `G10 L20`, `G76`), [`Control::Auto`] reads a program by Fanuc's rules when it has a
//!   Fanuc program number, `%` tape marks, `M98`/`M99`/`G65` or macro statements, and by
//!   LinuxCNC's otherwise.
//! - The scanner of plain lines is a single pass over the bytes with reused buffers and a
//!   correctly rounded fast decimal reader (`lexer.rs`); lines with parameters, expressions
//!   or control flow are read in full (`line.rs`) and kept for loops.

mod arcs;
mod block;
mod canned;
mod codes;
mod compensation;
mod control;
mod error;
mod eval;
mod expr;
mod flow;
mod frame;
mod json;
mod lexer;
mod line;
mod machine;
mod map;
mod motion;
mod offsets;
mod options;
mod owords;
mod params;
mod parse;
mod report;
mod setup;
mod subprograms;
mod system;
mod tools;
pub(crate) mod words;
mod writer;

pub use arcs::{arc_radius_tolerance_mm, ARC_RADIUS_TOLERANCE_MM, ARC_RADIUS_TOLERANCE_RATIO};
pub use canned::{G83_PECK_CLEARANCE_MM, MAX_PECKS_PER_HOLE};
pub use error::{NcError, NcErrors, MAX_NC_ERRORS, MAX_NC_WARNINGS};
pub use json::{toolpath_from_json, toolpath_to_json, JsonCenter, JsonMove, JsonProgram};
pub use map::{Affine, ArcFormat, FeedMode, LineMotion, LineRecord, MotionContext, ProgramMap};
pub use options::{
    ArcTolerance, Control, ToolEntry, ARC_TOLERANCE_ABSOLUTE_INCH, ARC_TOLERANCE_ABSOLUTE_MM,
    ARC_TOLERANCE_MAXIMUM_INCH, ARC_TOLERANCE_MAXIMUM_MM, ARC_TOLERANCE_RELATIVE, DEFAULT_MAX_CALL_DEPTH,
    DEFAULT_MAX_LOOP_ITERATIONS, RETRACT_CLEARANCE_MM,
};
pub use parse::{interpret, parse_gcode, Interpreted};
pub use report::MAX_QUOTED_WORD_CHARS;
pub use writer::{
    write_program, write_program_mapped, Dialect, LineNumbers, WriterOptions, WrittenProgram, DEFAULT_DECIMALS,
    DEFAULT_FEED_DECIMALS, DEFAULT_TOOL_NUMBER, MAX_DECIMALS, MAX_SEQUENCE_NUMBER,
};

use crate::core::toolpath::P3;

/// mm in one inch (G20 programs are converted to mm).
pub const MM_PER_INCH: f64 = 25.4;

/// What to do with canned cycles (G73, G74, G76, G81–G86, G89).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum CannedCycles {
    /// Turn each cycle into its rapid and feed moves (and dwells).
    #[default]
    Expand,
    /// Refuse them: an error on each line that programs one.
    Refuse,
}

/// What to do with G codes, letters and characters the interpreter does not know.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum UnknownWords {
    /// An error naming the line, column and word.
    #[default]
    Reject,
    /// A warning ("line 12: unknown word Q3 ignored"); the rest of the line is read.
    /// Refused features (rotary axes, probing…) stay errors.
    Warn,
}

/// Most moves one program may make (canned cycles expanded, loops run) unless
/// [`ParseOptions`] says otherwise: more than a 64 MB program of CAM output holds, so only
/// a program that expands its cycles or loops beyond reason reaches it.
pub const MAX_MOVES: usize = 4_000_000;

/// How to read a G-code program.
#[derive(Debug, Clone, PartialEq)]
pub struct ParseOptions {
    /// Expand or refuse canned cycles (default: expand).
    pub canned_cycles: CannedCycles,
    /// Reject unknown words or warn about them (default: reject).
    pub unknown_words: UnknownWords,
    /// Where the tool is before the first line, mm (default: the origin); the start of the
    /// first move for the axes it does not program.
    pub initial_position: P3,
    /// Most moves the program may make, canned cycles expanded (default [`MAX_MOVES`]);
    /// the line that makes more is an error.
    pub max_moves: usize,
    /// Whose rules apply where LinuxCNC and Fanuc differ (default: recognised).
    pub control: Control,
    /// How far an arc's end may be off its circle.
    pub arc_tolerance: ArcTolerance,
    /// The height G53, G28 and G30 retract to, mm (default: the highest the tool has been).
    pub retract_z_mm: Option<f64>,
    /// Radii and lengths of the tools and offset numbers the program names (D, H, T).
    pub tool_table: Vec<ToolEntry>,
    /// The radius G41/G42 compensate by when the tool table has none for the D number, mm.
    pub tool_radius_mm: Option<f64>,
    /// Most times the program's loops may repeat, all loops together (default
    /// [`DEFAULT_MAX_LOOP_ITERATIONS`]).
    pub max_loop_iterations: u64,
    /// Deepest nesting of subroutine and macro calls (default [`DEFAULT_MAX_CALL_DEPTH`]).
    pub max_call_depth: u32,
}

impl Default for ParseOptions {
    fn default() -> Self {
        ParseOptions {
            canned_cycles: CannedCycles::default(),
            unknown_words: UnknownWords::default(),
            initial_position: P3::default(),
            max_moves: MAX_MOVES,
            control: Control::default(),
            arc_tolerance: ArcTolerance::default(),
            retract_z_mm: None,
            tool_table: Vec::new(),
            tool_radius_mm: None,
            max_loop_iterations: DEFAULT_MAX_LOOP_ITERATIONS,
            max_call_depth: DEFAULT_MAX_CALL_DEPTH,
        }
    }
}

#[cfg(test)]
mod compensation_tests;
#[cfg(test)]
mod expr_tests;
#[cfg(test)]
mod interpreter_tests;
#[cfg(test)]
mod line_tests;
#[cfg(test)]
mod tests;
