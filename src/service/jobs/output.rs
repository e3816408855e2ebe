//! How a job writes its NC program: the request's `output` object, turned into the
//! core writer's options. Where the request is silent: the title is the tool's name, the
//! tool `T1` (or the path's own tool) with its length offset `H` of the same number, the
//! safe height the path's highest point (the planners' `safe_z`), the coolant the
//! machine's row (`/v1/machines`, `coolant`), the spindle speed the conditions'.

use super::setup::PathSetup;
use crate::core::coolant::Coolant;
use crate::core::nc::{
    Dialect, LineNumbers, WriterOptions, DEFAULT_DECIMALS, DEFAULT_FEED_DECIMALS, MAX_DECIMALS, MAX_SEQUENCE_NUMBER,
};
use crate::service::error::Validator;
use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

/// Largest Fanuc program number (`O9999`).
pub const MAX_PROGRAM_NUMBER: u32 = 9999;
/// Longest title, characters.
pub const MAX_TITLE_CHARS: usize = 120;
/// Largest tool number written in the header's `T… M6` and `H…` (four digits, as most
/// controls read).
pub const MAX_TOOL_NUMBER: u32 = 9999;
/// Height of the safe plane above the top of the layer when none is given, mm (**assumed**):
/// the default `safe_z` of the programs trochoids and plans write.
pub const DEFAULT_SAFE_HEIGHT_ABOVE_TOP_MM: f64 = 5.0;
/// Largest safe height, mm, either way from the work zero (**assumed**: beyond the travel of
/// any machining centre, and within the eight digits a Fanuc reads at 0.001 mm).
pub const MAX_SAFE_Z_MM: f64 = 10_000.0;

/// The coolant of a program: a name, or the older `true`/`false`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, ToSchema)]
#[serde(untagged)]
pub enum CoolantInput {
    /// `off`, `mist` (M7) or `flood` (M8).
    Named(Coolant),
    /// The older form: `true` is `flood` (M8), `false` is `off`.
    Switch(bool),
}

impl<'de> Deserialize<'de> for CoolantInput {
    /// A name or a boolean, refused with a message that lists both.
    fn deserialize<D: serde::Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct Visitor;
        impl serde::de::Visitor<'_> for Visitor {
            type Value = CoolantInput;

            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str("off, mist, flood, true or false")
            }

            fn visit_bool<E: serde::de::Error>(self, on: bool) -> Result<CoolantInput, E> {
                Ok(CoolantInput::Switch(on))
            }

            fn visit_str<E: serde::de::Error>(self, name: &str) -> Result<CoolantInput, E> {
                Coolant::parse(name)
                    .map(CoolantInput::Named)
                    .ok_or_else(|| E::invalid_value(serde::de::Unexpected::Str(name), &self))
            }
        }
        deserializer.deserialize_any(Visitor)
    }
}

impl CoolantInput {
    pub fn coolant(self) -> Coolant {
        match self {
            CoolantInput::Named(c) => c,
            CoolantInput::Switch(true) => Coolant::Flood,
            CoolantInput::Switch(false) => Coolant::Off,
        }
    }
}

/// The control a program is written for.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, ToSchema)]
#[serde(rename_all = "snake_case")]
pub enum DialectInput {
    /// Fanuc and ISO controls: `%`, `O0001`, a decimal point on every length, `M30`.
    #[default]
    Fanuc,
    /// LinuxCNC: no `%` or O number, `P` turns on arcs, `M2`.
    #[serde(alias = "linuxcnc")]
    LinuxCnc,
}

/// N numbers on every line.
#[derive(Debug, Clone, Copy, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct LineNumbersInput {
    /// First N number (default 10).
    pub start: Option<u32>,
    /// Step (default 10).
    pub step: Option<u32>,
}

/// How to write the program. Every field is optional.
#[derive(Debug, Clone, Default, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct OutputOptions {
    /// `fanuc` (default) or `linux_cnc`.
    #[serde(default)]
    pub dialect: DialectInput,
    /// Fanuc program number, 1–9999 (default 1).
    pub program_number: Option<u32>,
    /// N numbers (default: none).
    pub line_numbers: Option<LineNumbersInput>,
    /// A comment in the header (default: the tool's name).
    pub title: Option<String>,
    /// Write the time the job ran in the header (default false: the same input gives the
    /// same bytes).
    #[serde(default)]
    pub timestamp: bool,
    /// Coolant switched on after the spindle starts and off (M9) at the end: `off`, `mist`
    /// (M7) or `flood` (M8); default the machine's (`coolant` of `/v1/machines`: `mist` on
    /// the seeded OKK VM-4, as seed 004 §3.4 cut). `true` and `false`, the older form, are
    /// `flood` and `off`.
    pub coolant: Option<CoolantInput>,
    /// Decimals of lengths (default 3, at most 6).
    pub decimals: Option<u32>,
    /// Decimals of feeds (default 1, at most 6).
    pub feed_decimals: Option<u32>,
    /// Tool number of the header's `T… M6`, 1–9999, when the path has no tool change before
    /// its first move (default: the path's own tool, if it names one, else 1).
    pub tool_number: Option<u32>,
    /// H number of that tool's length offset (`G43 H…`), 1–9999 (default: the tool number).
    pub length_offset: Option<u32>,
    /// Safe height, mm: the program goes there with Z alone before its first XY move and
    /// after each tool change, and back there before it ends. At least the path's highest
    /// point, which is the default (for trochoids and plans their `safe_z`: the top + 5 mm
    /// unless given).
    pub safe_z: Option<f64>,
}

impl OutputOptions {
    /// Whether the request set any option (they apply to the programs dieplan writes).
    pub fn is_set(&self) -> bool {
        serde_json::to_value(self).ok() != serde_json::to_value(OutputOptions::default()).ok()
    }

    pub fn validate(&self, v: &mut Validator) {
        if let Some(n) = self.program_number {
            v.check(
                (1..=MAX_PROGRAM_NUMBER).contains(&n),
                "output.program_number",
                format!("1 to {MAX_PROGRAM_NUMBER}"),
            );
        }
        if let Some(l) = self.line_numbers {
            for (field, value, least) in
                [("output.line_numbers.start", l.start, 0), ("output.line_numbers.step", l.step, 1)]
            {
                if let Some(n) = value {
                    v.check(
                        (least..=MAX_SEQUENCE_NUMBER).contains(&n),
                        field,
                        format!("{least} to {MAX_SEQUENCE_NUMBER} (N numbers have at most five digits)"),
                    );
                }
            }
        }
        for (field, value) in [("output.tool_number", self.tool_number), ("output.length_offset", self.length_offset)] {
            if let Some(n) = value {
                v.check((1..=MAX_TOOL_NUMBER).contains(&n), field, format!("1 to {MAX_TOOL_NUMBER}"));
            }
        }
        if let Some(z) = self.safe_z {
            v.within("output.safe_z", z, -MAX_SAFE_Z_MM, MAX_SAFE_Z_MM);
        }
        if let Some(t) = &self.title {
            v.check(
                t.chars().count() <= MAX_TITLE_CHARS,
                "output.title",
                format!("at most {MAX_TITLE_CHARS} characters"),
            );
        }
        for (field, value) in [("output.decimals", self.decimals), ("output.feed_decimals", self.feed_decimals)] {
            if let Some(d) = value {
                v.check(d <= MAX_DECIMALS, field, format!("at most {MAX_DECIMALS}"));
            }
        }
        v.check(self.decimals.is_none_or(|d| d >= 1), "output.decimals", "at least 1");
    }

    /// The writer's options, with the job's defaults.
    pub fn to_writer(&self, prepared: &PathSetup) -> WriterOptions {
        let defaults = LineNumbers::default();
        WriterOptions {
            dialect: match self.dialect {
                DialectInput::Fanuc => Dialect::Fanuc,
                DialectInput::LinuxCnc => Dialect::LinuxCnc,
            },
            program_number: self.program_number.unwrap_or(1),
            line_numbers: self.line_numbers.map(|l| LineNumbers {
                start: l.start.unwrap_or(defaults.start),
                step: l.step.unwrap_or(defaults.step),
            }),
            title: Some(self.title.clone().unwrap_or_else(|| prepared.tool.name.clone())),
            timestamp: self.timestamp.then(now),
            coolant: self.coolant.map_or(prepared.coolant, CoolantInput::coolant),
            decimals: self.decimals.unwrap_or(DEFAULT_DECIMALS),
            feed_decimals: self.feed_decimals.unwrap_or(DEFAULT_FEED_DECIMALS),
            tool_number: self.tool_number,
            length_offset: self.length_offset,
            safe_z_mm: self.safe_z,
            spindle_rpm: prepared.default_spindle_rpm,
        }
    }
}

fn now() -> String {
    time::OffsetDateTime::now_utc()
        .format(&time::format_description::well_known::Rfc3339)
        .unwrap_or_else(|_| "unknown time".to_string())
}
