//! Errors of a G-code or JSON move program, and the collector that gathers them (and the
//! warnings) while a program is read.

use std::fmt;

use crate::core::error::CoreError;

/// At most this many errors are reported for one program; reading stops when it is reached.
pub const MAX_NC_ERRORS: usize = 100;

/// At most this many warnings are kept for one program; a last warning counts the others.
pub const MAX_NC_WARNINGS: usize = 100;

/// One problem in a program, pointing at the word that causes it.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct NcError {
    /// 1-based line of the source (the JSON form: 1-based index of the move, 0 for the
    /// program's own fields).
    pub line: u32,
    /// 1-based column (in characters) of the offending word; 0 when there is no column
    /// (the JSON form).
    pub column: u32,
    /// The word as written (e.g. `Q3`, `G41`); the JSON form: the field name; `""` when no
    /// single word is at fault.
    pub word: String,
    /// Why the word is refused, in words a CAM user can act on.
    pub reason: String,
}

impl fmt::Display for NcError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "line {}", self.line)?;
        if self.column > 0 {
            write!(f, ", column {}", self.column)?;
        }
        if !self.word.is_empty() {
            write!(f, " ({})", self.word)?;
        }
        write!(f, ": {}", self.reason)
    }
}

impl std::error::Error for NcError {}

/// All the errors found in a program (at most [`MAX_NC_ERRORS`]), in source order.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct NcErrors(pub Vec<NcError>);

impl fmt::Display for NcErrors {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for (i, error) in self.0.iter().enumerate() {
            if i > 0 {
                writeln!(f)?;
            }
            write!(f, "{error}")?;
        }
        Ok(())
    }
}

impl std::error::Error for NcErrors {}

impl NcErrors {
    /// The errors as one [`CoreError::InvalidInput`] on `field`: the first error, and how
    /// many others there are.
    pub fn to_core_error(&self, field: &str) -> CoreError {
        let first = self.0.first().map_or_else(|| "invalid program".to_string(), ToString::to_string);
        let reason = match self.0.len() {
            0 | 1 => first,
            2 => format!("{first} (and 1 more error)"),
            n => format!("{first} (and {} more errors)", n - 1),
        };
        CoreError::invalid(field, reason)
    }
}

impl From<NcErrors> for CoreError {
    fn from(errors: NcErrors) -> Self {
        errors.to_core_error("gcode")
    }
}

/// Errors and warnings gathered while a program is read.
#[derive(Debug, Default)]
pub(crate) struct Diagnostics {
    pub errors: Vec<NcError>,
    warnings: Vec<String>,
    warnings_not_kept: usize,
}

impl Diagnostics {
    /// Records an error (dropped once [`MAX_NC_ERRORS`] are recorded).
    pub fn error(&mut self, error: NcError) {
        // A line in a loop or a subprogram fails the same way each time it runs: once.
        if self.errors.len() < MAX_NC_ERRORS && !self.errors.contains(&error) {
            self.errors.push(error);
        }
    }

    /// `true` once no more errors can be recorded: reading can stop.
    pub fn full(&self) -> bool {
        self.errors.len() >= MAX_NC_ERRORS
    }

    /// Records a warning (counted but not kept past [`MAX_NC_WARNINGS`]).
    pub fn warn(&mut self, message: String) {
        if self.warnings.len() < MAX_NC_WARNINGS {
            self.warnings.push(message);
        } else {
            self.warnings_not_kept += 1;
        }
    }

    /// The result: the errors if there are any, else the warnings.
    pub fn finish(mut self) -> Result<Vec<String>, NcErrors> {
        if !self.errors.is_empty() {
            return Err(NcErrors(self.errors));
        }
        if self.warnings_not_kept > 0 {
            let n = self.warnings_not_kept;
            self.warnings.push(format!("{n} more warnings not shown"));
        }
        Ok(self.warnings)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn error(line: u32, word: &str) -> NcError {
        NcError { line, column: 5, word: word.to_string(), reason: "no good".to_string() }
    }

    #[test]
    fn errors_are_listed_one_a_line_with_line_column_and_word() {
        let errors = NcErrors(vec![error(12, "Q3"), error(13, "")]);
        assert_eq!(errors.to_string(), "line 12, column 5 (Q3): no good\nline 13, column 5: no good");
    }

    #[test]
    fn the_core_error_names_the_first_error_and_counts_the_others() {
        let errors = NcErrors(vec![error(1, "X"), error(2, "Y"), error(3, "Z")]);
        assert_eq!(
            CoreError::from(errors),
            CoreError::invalid("gcode", "line 1, column 5 (X): no good (and 2 more errors)")
        );
    }

    #[test]
    fn the_collector_keeps_at_most_the_maximum_of_errors_and_warnings() {
        let mut diagnostics = Diagnostics::default();
        for i in 0..MAX_NC_WARNINGS + 3 {
            diagnostics.warn(format!("w{i}"));
        }
        let warnings = diagnostics.finish().unwrap();
        assert_eq!(warnings.len(), MAX_NC_WARNINGS + 1);
        assert_eq!(warnings.last().unwrap(), "3 more warnings not shown");

        let mut diagnostics = Diagnostics::default();
        for i in 0..MAX_NC_ERRORS + 3 {
            assert_eq!(diagnostics.full(), i >= MAX_NC_ERRORS);
            diagnostics.error(error(i as u32, ""));
        }
        assert_eq!(diagnostics.finish().unwrap_err().0.len(), MAX_NC_ERRORS);
    }
}
