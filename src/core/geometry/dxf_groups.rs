//! Reading an ASCII DXF file as group-code/value pairs, its sections, entities and units.

use super::chain::Source;
use crate::core::error::CoreError;

/// An extrusion direction whose x and y components are below this is ±Z.
const EXTRUSION_EPS: f64 = 1e-9;

/// Millimetres per drawing unit for the `$INSUNITS` codes this reader accepts
/// (0 = unitless, read as mm; 1 in; 2 ft; 4 mm; 5 cm; 6 m).
const MM_PER_UNIT: [(i64, f64); 6] = [(0, 1.0), (1, 25.4), (2, 304.8), (4, 1.0), (5, 10.0), (6, 1000.0)];

/// One group: code and value, with the 1-based line of the value.
#[derive(Debug, Clone, Copy)]
pub(super) struct Group<'a> {
    /// Group code.
    pub code: i32,
    /// Value, trimmed.
    pub value: &'a str,
    /// 1-based line of the value in the file.
    pub line: usize,
}

/// The file's groups in order; an error names the line that is not a group code.
pub(super) fn read_groups(text: &str) -> Result<Vec<Group<'_>>, CoreError> {
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    if text.starts_with("AutoCAD Binary DXF") {
        return Err(CoreError::invalid("dxf", "binary DXF is not supported: save as ASCII DXF"));
    }
    let mut lines = text.lines().enumerate();
    let mut groups = Vec::new();
    while let Some((index, code_line)) = lines.next() {
        let code_text = code_line.trim();
        if code_text.is_empty() && lines.clone().all(|(_, l)| l.trim().is_empty()) {
            break;
        }
        let code = code_text.parse::<i32>().map_err(|_| {
            CoreError::invalid("dxf", format!("line {}: expected a group code, got '{code_text}'", index + 1))
        })?;
        let (value_index, value) = lines
            .next()
            .ok_or_else(|| CoreError::invalid("dxf", format!("line {}: group code {code} has no value", index + 1)))?;
        groups.push(Group { code, value: value.trim(), line: value_index + 1 });
    }
    Ok(groups)
}

/// The groups between `0 SECTION / 2 ENTITIES` and its `0 ENDSEC`.
pub(super) fn entities_section<'g, 'a>(groups: &'g [Group<'a>]) -> Result<&'g [Group<'a>], CoreError> {
    for (k, pair) in groups.windows(2).enumerate() {
        if pair[0].code == 0 && pair[0].value == "SECTION" && pair[1].code == 2 && pair[1].value == "ENTITIES" {
            let body = &groups[k + 2..];
            let end = body.iter().position(|g| g.code == 0 && g.value == "ENDSEC").unwrap_or(body.len());
            return Ok(&body[..end]);
        }
    }
    Err(CoreError::invalid("dxf", "the file has no ENTITIES section"))
}

/// One entity: its type group and the groups up to the next entity.
pub(super) struct Entity<'g, 'a> {
    /// The entity type, line and handle.
    pub source: Source,
    /// The groups after the type group.
    pub groups: &'g [Group<'a>],
}

impl Entity<'_, '_> {
    /// An input error naming this entity.
    pub fn error(&self, reason: impl std::fmt::Display) -> CoreError {
        CoreError::invalid("dxf", format!("{}: {reason}", self.source))
    }

    /// The value of `g` as a finite number.
    pub fn number_of(&self, g: &Group<'_>) -> Result<f64, CoreError> {
        match g.value.parse::<f64>() {
            Ok(v) if v.is_finite() => Ok(v),
            _ => {
                Err(self.error(format!("line {}: group {} must be a finite number, got '{}'", g.line, g.code, g.value)))
            }
        }
    }

    /// The first value of group `code` as a number, if present.
    pub fn optional(&self, code: i32) -> Result<Option<f64>, CoreError> {
        self.groups.iter().find(|g| g.code == code).map(|g| self.number_of(g)).transpose()
    }

    /// The first value of group `code` as a number; an error when absent.
    pub fn required(&self, code: i32) -> Result<f64, CoreError> {
        self.optional(code)?.ok_or_else(|| self.error(format!("group {code} is missing")))
    }

    /// Group 70 (flags), 0 when absent.
    pub fn flags(&self) -> Result<i64, CoreError> {
        Ok(self.optional(70)?.unwrap_or(0.0) as i64)
    }

    /// `true` when the entity's coordinates are in a mirrored OCS (extrusion −Z).
    pub fn mirrored(&self) -> Result<bool, CoreError> {
        let (nx, ny) = (self.optional(210)?.unwrap_or(0.0), self.optional(220)?.unwrap_or(0.0));
        let nz = self.optional(230)?.unwrap_or(1.0);
        if nx.abs() > EXTRUSION_EPS || ny.abs() > EXTRUSION_EPS {
            return Err(
                self.error(format!("extrusion ({nx}, {ny}, {nz}) is not along Z: the entity is not in the XY plane"))
            );
        }
        Ok(nz < 0.0)
    }
}

/// Splits a section's groups into entities at each group 0.
pub(super) fn split_entities<'g, 'a>(groups: &'g [Group<'a>]) -> Vec<Entity<'g, 'a>> {
    let starts: Vec<usize> = (0..groups.len()).filter(|&k| groups[k].code == 0).collect();
    starts
        .iter()
        .enumerate()
        .map(|(n, &s)| {
            let end = starts.get(n + 1).copied().unwrap_or(groups.len());
            let body = &groups[s + 1..end];
            let handle = body.iter().find(|g| g.code == 5).map(|g| g.value.to_string());
            Entity { source: Source { kind: groups[s].value.to_string(), line: groups[s].line, handle }, groups: body }
        })
        .collect()
}

/// Millimetres per drawing unit from the HEADER's `$INSUNITS` (mm when absent).
pub(super) fn mm_per_unit(groups: &[Group<'_>]) -> Result<f64, CoreError> {
    let Some(k) = groups.iter().position(|g| g.code == 9 && g.value == "$INSUNITS") else {
        return Ok(1.0);
    };
    let Some(g) = groups.get(k + 1).filter(|g| g.code == 70) else {
        return Ok(1.0);
    };
    let code = g.value.parse::<i64>().map_err(|_| {
        CoreError::invalid("dxf", format!("line {}: $INSUNITS must be an integer, got '{}'", g.line, g.value))
    })?;
    MM_PER_UNIT.iter().find(|(c, _)| *c == code).map(|(_, mm)| *mm).ok_or_else(|| {
        CoreError::invalid("dxf", format!("line {}: unsupported drawing units $INSUNITS = {code}", g.line))
    })
}
