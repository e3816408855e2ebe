//! NC programs in: a fast, strict G-code parser (the RS274/NGC that CAM post-processors
//! write for LinuxCNC and Fanuc/ISO controls) and the equivalent JSON move list, both read
//! into a [`Toolpath`](crate::core::toolpath::Toolpath) in mm. NC programs out: the writer
//! ([`write_program`]) turns a tool path back into a Fanuc or LinuxCNC program that this
//! parser reads to the same moves; see `writer.rs`.
//!
//! Strict means: a word the parser does not understand, or a feature the planner cannot
//! follow (cutter compensation, offsets, subprograms, parameters, rotary axes…), is an
//! error naming its line, column and word, never silently skipped. All errors are
//! collected (up to [`MAX_NC_ERRORS`]); a line with an error produces nothing.
//!
//! Choices worth knowing:
//! - Rapid and linear moves of zero length are dropped (arcs never are: end = start is a
//!   full circle); see `motion.rs`.
//! - Canned cycles G81/G82/G83 are expanded into moves ([`CannedCycles::Expand`]) in the
//!   XY plane with G90, as LinuxCNC runs them; see `canned.rs`.
//! - Lengths are stored in mm whatever the units (G20 × [`MM_PER_INCH`]).
//! - A Fanuc program number line (`O1234 (TITLE)`) before the first line with words is
//!   ignored; other O words (subprograms) are refused. Fanuc's `G4 X<seconds>` dwell is
//!   read as `G4 P<seconds>`.
//! - The scanner is a single pass over the bytes with reused buffers and a correctly
//!   rounded fast decimal reader; see `lexer.rs`.

mod arcs;
mod block;
mod canned;
mod error;
mod json;
mod lexer;
mod motion;
mod parse;
mod report;
mod writer;

pub use arcs::{arc_radius_tolerance_mm, ARC_RADIUS_TOLERANCE_MM, ARC_RADIUS_TOLERANCE_RATIO};
pub use canned::{G83_PECK_CLEARANCE_MM, MAX_PECKS_PER_HOLE};
pub use error::{NcError, NcErrors, MAX_NC_ERRORS, MAX_NC_WARNINGS};
pub use json::{toolpath_from_json, toolpath_to_json, JsonCenter, JsonMove, JsonProgram};
pub use parse::parse_gcode;
pub use report::MAX_QUOTED_WORD_CHARS;
pub use writer::{
    write_program, Dialect, LineNumbers, WriterOptions, DEFAULT_DECIMALS, DEFAULT_FEED_DECIMALS, MAX_DECIMALS,
    MAX_SEQUENCE_NUMBER,
};

use crate::core::toolpath::P3;

/// mm in one inch (G20 programs are converted to mm).
pub const MM_PER_INCH: f64 = 25.4;

/// What to do with canned drilling cycles (G81, G82, G83).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum CannedCycles {
    /// Turn each cycle into its rapid and feed moves (and G82's dwell).
    #[default]
    Expand,
    /// Refuse them: an error on each line that programs one.
    Refuse,
}

/// What to do with G/M codes, letters and characters the parser does not know.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum UnknownWords {
    /// An error naming the line, column and word.
    #[default]
    Reject,
    /// A warning ("line 12: unknown word Q3 ignored"); the rest of the line is read.
    /// Refused features (cutter compensation, offsets…) stay errors.
    Warn,
}

/// Most moves one program may make (canned cycles expanded) unless [`ParseOptions`] says
/// otherwise: more than a 64 MB program of CAM output holds, so only a program that
/// expands its cycles beyond reason reaches it (a few hundred MB of moves).
pub const MAX_MOVES: usize = 4_000_000;

/// How to read a G-code program.
#[derive(Debug, Clone, Copy, PartialEq)]
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
}

impl Default for ParseOptions {
    fn default() -> Self {
        ParseOptions {
            canned_cycles: CannedCycles::default(),
            unknown_words: UnknownWords::default(),
            initial_position: P3::default(),
            max_moves: MAX_MOVES,
        }
    }
}

#[cfg(test)]
mod tests;
