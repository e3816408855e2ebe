//! The NC program of a request: G-code text or the JSON move list, and how a control
//! reads it (whose rules, the arc tolerance, the tool table, the retract height of
//! G53/G28/G30, the limits on loops and calls), turned into the core's tool path with
//! field-named errors.

use crate::core::nc::{
    interpret, toolpath_from_json, ArcTolerance, CannedCycles, Control, JsonProgram, ParseOptions, ProgramMap,
    ToolEntry, UnknownWords, DEFAULT_MAX_CALL_DEPTH, DEFAULT_MAX_LOOP_ITERATIONS, RETRACT_CLEARANCE_MM,
};
use crate::core::toolpath::Toolpath;
use crate::service::error::{ApiError, FieldError, Validator};
use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

/// Most entries a request's tool table may have.
pub const MAX_TOOL_TABLE_ENTRIES: usize = 1000;
/// Most loop iterations a request may allow (a loop of a billion rounds would run for
/// hours).
pub const MAX_LOOP_ITERATIONS_LIMIT: u64 = 100_000_000;
/// Deepest call nesting a request may allow.
pub const MAX_CALL_DEPTH_LIMIT: u32 = 1000;

/// A tool path: G-code text or the JSON move list (exactly one), and how to read it.
#[derive(Debug, Clone, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct ProgramInput {
    /// G-code as LinuxCNC and Fanuc controls run it in 3-axis milling: parameters and
    /// expressions, O-word subroutines and loops, Fanuc macros and `M98`/`M99`
    /// subprograms in the same text, work offsets, tool length and cutter radius
    /// compensation, canned cycles, inch or mm (see the README's "G-code" section).
    pub gcode: Option<String>,
    /// The same moves as JSON: `{"start": {"x","y","z"}, "moves": [{"type": "rapid"|"linear"|"arc", "x", "y", "z", "f", "center": {"x","y"}, "clockwise"}]}`.
    #[schema(value_type = Option<Object>)]
    pub moves: Option<JsonProgram>,
    /// `reject` (default) or `warn` about G codes, letters and characters the interpreter
    /// does not know.
    #[serde(default)]
    pub unknown_words: UnknownWordsInput,
    /// `expand` (default) or `refuse` canned cycles (G73, G74, G76, G81–G86, G89).
    #[serde(default)]
    pub canned_cycles: CannedCyclesInput,
    /// Whose rules apply where LinuxCNC and Fanuc differ (an unset parameter, the cutter
    /// compensation lead-in, `G10 L20`, `G76`): `auto` (default: Fanuc's for a program with
    /// a program number, `%` marks, `M98`/`M99`/`G65` or macro statements), `linux_cnc` or
    /// `fanuc`.
    #[serde(default)]
    pub control: ControlInput,
    /// How far an arc's end may be off its circle (default LinuxCNC's).
    pub arc_tolerance: Option<ArcToleranceInput>,
    /// The height G53, G28 and G30 retract to, mm: their moves are in machine coordinates,
    /// which the planner cannot place, so they are read as a rapid straight up to here
    /// (default: 5 mm above the stock, or the highest the tool has been).
    pub safe_z_mm: Option<f64>,
    /// The radii (G41/G42 by D) and lengths (G43 by H) of the tool, D and H numbers the
    /// program names. G41/G42 with a D number not in the table compensate by the job's
    /// tool radius, with a warning.
    #[serde(default)]
    pub tool_table: Vec<ToolTableEntry>,
    /// Most times the program's loops may repeat, all together (default 1 000 000).
    pub max_loop_iterations: Option<u64>,
    /// Deepest nesting of subroutine and macro calls (default 32).
    pub max_call_depth: Option<u32>,
}

#[derive(Debug, Clone, Copy, Default, Serialize, Deserialize, ToSchema)]
#[serde(rename_all = "snake_case")]
pub enum UnknownWordsInput {
    #[default]
    Reject,
    Warn,
}

#[derive(Debug, Clone, Copy, Default, Serialize, Deserialize, ToSchema)]
#[serde(rename_all = "snake_case")]
pub enum CannedCyclesInput {
    #[default]
    Expand,
    Refuse,
}

#[derive(Debug, Clone, Copy, Default, Serialize, Deserialize, ToSchema)]
#[serde(rename_all = "snake_case")]
pub enum ControlInput {
    #[default]
    Auto,
    #[serde(alias = "linuxcnc")]
    LinuxCnc,
    Fanuc,
}

/// An arc's end may miss the circle through its start by at most `absolute`, or by up to
/// `maximum` if that is within `relative` of the radius (LinuxCNC's rule). Lengths are in
/// the program's own units (mm or inch).
#[derive(Debug, Clone, Copy, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct ArcToleranceInput {
    /// Always accepted, program units (default 0.005 mm or 0.0005 in).
    pub absolute: Option<f64>,
    /// Accepted up to this fraction of the radius (default 0.001).
    pub relative: Option<f64>,
    /// Never accepted beyond, program units (default 0.5 mm or 0.05 in).
    pub maximum: Option<f64>,
}

/// One entry of the tool table.
#[derive(Debug, Clone, Copy, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct ToolTableEntry {
    /// The tool, D or H number.
    pub number: u32,
    /// The radius G41/G42 compensate by, mm (0 for a program of tool-centre moves with
    /// wear compensation).
    pub radius_mm: Option<f64>,
    /// The length G43 offsets by, mm.
    pub length_mm: Option<f64>,
}

/// What the job knows that the program may need.
#[derive(Debug, Clone, Copy, Default)]
pub struct ProgramContext {
    /// The job's tool radius: what G41/G42 compensate by without a tool-table entry, mm.
    pub tool_radius_mm: Option<f64>,
    /// The top of the stock, mm: retracts go 5 mm above it by default.
    pub stock_top_mm: Option<f64>,
}

/// A program read: its tool path, and for G-code how each line ran (what the feed editor
/// needs to write it back).
#[derive(Debug, Clone)]
pub struct ReadProgram {
    pub path: Toolpath,
    pub map: Option<ProgramMap>,
}

impl ProgramInput {
    /// G-code text read with `options`' reading options (or the defaults).
    pub fn of_text(text: String, options: Option<&ProgramInput>) -> ProgramInput {
        let template = options.cloned().unwrap_or(ProgramInput {
            gcode: None,
            moves: None,
            unknown_words: UnknownWordsInput::default(),
            canned_cycles: CannedCyclesInput::default(),
            control: ControlInput::default(),
            arc_tolerance: None,
            safe_z_mm: None,
            tool_table: Vec::new(),
            max_loop_iterations: None,
            max_call_depth: None,
        });
        ProgramInput { gcode: Some(text), moves: None, ..template }
    }

    /// The reading options of the `program` of a stored job's input, if it has one.
    pub fn options_of_job_input(input: &str) -> Option<ProgramInput> {
        let value: serde_json::Value = serde_json::from_str(input).ok()?;
        let program: ProgramInput = serde_json::from_value(value.get("program")?.clone()).ok()?;
        Some(ProgramInput { gcode: None, moves: None, ..program })
    }

    /// Every fault of the reading options, named by field.
    fn check(&self, v: &mut Validator) {
        if let Some(t) = &self.arc_tolerance {
            for (field, value) in [("absolute", t.absolute), ("relative", t.relative), ("maximum", t.maximum)] {
                if let Some(x) = value {
                    v.non_negative(&format!("program.arc_tolerance.{field}"), x);
                }
            }
        }
        if let Some(z) = self.safe_z_mm {
            v.finite("program.safe_z_mm", z);
        }
        v.check(
            self.tool_table.len() <= MAX_TOOL_TABLE_ENTRIES,
            "program.tool_table",
            format!("at most {MAX_TOOL_TABLE_ENTRIES} entries"),
        );
        for (i, e) in self.tool_table.iter().enumerate() {
            if let Some(r) = e.radius_mm {
                v.non_negative(&format!("program.tool_table[{i}].radius_mm"), r);
            }
            if let Some(l) = e.length_mm {
                v.finite(&format!("program.tool_table[{i}].length_mm"), l);
            }
        }
        if let Some(n) = self.max_loop_iterations {
            v.check(
                (1..=MAX_LOOP_ITERATIONS_LIMIT).contains(&n),
                "program.max_loop_iterations",
                format!("1 to {MAX_LOOP_ITERATIONS_LIMIT}"),
            );
        }
        if let Some(n) = self.max_call_depth {
            v.check(
                (1..=MAX_CALL_DEPTH_LIMIT).contains(&n),
                "program.max_call_depth",
                format!("1 to {MAX_CALL_DEPTH_LIMIT}"),
            );
        }
    }

    /// How the interpreter reads this program in `context`.
    fn options(&self, context: ProgramContext) -> ParseOptions {
        let defaults = ArcTolerance::default();
        ParseOptions {
            unknown_words: match self.unknown_words {
                UnknownWordsInput::Reject => UnknownWords::Reject,
                UnknownWordsInput::Warn => UnknownWords::Warn,
            },
            canned_cycles: match self.canned_cycles {
                CannedCyclesInput::Expand => CannedCycles::Expand,
                CannedCyclesInput::Refuse => CannedCycles::Refuse,
            },
            control: match self.control {
                ControlInput::Auto => Control::Auto,
                ControlInput::LinuxCnc => Control::LinuxCnc,
                ControlInput::Fanuc => Control::Fanuc,
            },
            arc_tolerance: self.arc_tolerance.map_or(defaults, |t| ArcTolerance {
                absolute: t.absolute,
                relative: t.relative.unwrap_or(defaults.relative),
                maximum: t.maximum,
            }),
            retract_z_mm: self.safe_z_mm.or(context.stock_top_mm.map(|top| top + RETRACT_CLEARANCE_MM)),
            tool_table: self
                .tool_table
                .iter()
                .map(|e| ToolEntry { number: e.number, radius_mm: e.radius_mm, length_mm: e.length_mm })
                .collect(),
            tool_radius_mm: context.tool_radius_mm,
            max_loop_iterations: self.max_loop_iterations.unwrap_or(DEFAULT_MAX_LOOP_ITERATIONS),
            max_call_depth: self.max_call_depth.unwrap_or(DEFAULT_MAX_CALL_DEPTH),
            ..ParseOptions::default()
        }
    }
}

/// Reads the program; errors name `program.gcode` with the line, or `program.moves[i]`.
pub fn read_program(input: &ProgramInput, context: ProgramContext) -> Result<ReadProgram, ApiError> {
    let mut v = Validator::new();
    input.check(&mut v);
    v.finish()?;
    let options = input.options(context);
    let (read, field) = match (&input.gcode, &input.moves) {
        (Some(text), None) => {
            (interpret(text, &options).map(|i| ReadProgram { path: i.path, map: Some(i.map) }), "program.gcode")
        }
        (None, Some(moves)) => (toolpath_from_json(moves).map(|path| ReadProgram { path, map: None }), "program.moves"),
        _ => return Err(ApiError::field("program", "give exactly one of gcode and moves")),
    };
    let read = read.map_err(|errors| {
        ApiError::Validation(
            errors
                .0
                .iter()
                .map(|e| FieldError {
                    field: if field == "program.moves" {
                        format!("program.moves[{}]", e.line.saturating_sub(1))
                    } else {
                        field.to_string()
                    },
                    reason: if e.word.is_empty() {
                        format!("line {}, column {}: {}", e.line, e.column, e.reason)
                    } else {
                        format!("line {}, column {} ({}): {}", e.line, e.column, e.word, e.reason)
                    },
                })
                .collect(),
        )
    })?;
    if read.path.moves.is_empty() {
        return Err(ApiError::field(field, "the program has no moves"));
    }
    Ok(read)
}
