//! The JSON form of a tool path: the same moves as G-code, as a list a program can write
//! without a post-processor. Absolute coordinates in mm, feeds in mm/min, modal like
//! G-code (an omitted axis keeps its value, an omitted feed keeps the last one).
//!
//! ```json
//! {"start": {"x": 0, "y": 0, "z": 5}, "spindle_rpm": 8000, "tool": 3, "moves": [
//!   {"type": "rapid", "x": 10, "y": 0},
//!   {"type": "linear", "z": -1, "f": 300},
//!   {"type": "arc", "x": 0, "y": 10, "center": {"x": 0, "y": 0}, "clockwise": false}
//! ]}
//! ```

use serde::{Deserialize, Serialize};

use super::arcs::{self, coord, plane_axes, with_coord, ARC_RADIUS_TOLERANCE_MM};
use super::error::{NcError, NcErrors, MAX_NC_ERRORS};
use crate::core::tolerance::{approx_eq, LENGTH_EPS_MM};
use crate::core::toolpath::{Motion, Move, Plane, Toolpath, Units, P3};

/// A tool path as JSON moves.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct JsonProgram {
    /// Where the tool is before the first move, mm (default: the origin).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub start: Option<P3>,
    /// Spindle speed for every move, min⁻¹.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub spindle_rpm: Option<f64>,
    /// The tool in the spindle for every move.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tool: Option<u32>,
    /// The moves, in order.
    pub moves: Vec<JsonMove>,
}

/// The centre of a JSON arc, absolute, mm. The two in-plane coordinates are required; the
/// one along the plane's normal may be omitted (it is the start's) and if given must be
/// the start's.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct JsonCenter {
    /// X of the centre, mm.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub x: Option<f64>,
    /// Y of the centre, mm.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub y: Option<f64>,
    /// Z of the centre, mm.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub z: Option<f64>,
}

/// One JSON move. Coordinates are absolute mm; an omitted one keeps its value. `f` is the
/// feed in mm/min, modal: a linear or arc move needs one on it or on an earlier move.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(tag = "type", rename_all = "snake_case", deny_unknown_fields)]
pub enum JsonMove {
    /// Positioning at the rapid rate (G0).
    Rapid {
        /// End X, mm.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        x: Option<f64>,
        /// End Y, mm.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        y: Option<f64>,
        /// End Z, mm.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        z: Option<f64>,
    },
    /// Straight feed move (G1).
    Linear {
        /// End X, mm.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        x: Option<f64>,
        /// End Y, mm.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        y: Option<f64>,
        /// End Z, mm.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        z: Option<f64>,
        /// Feed, mm/min (modal).
        #[serde(default, skip_serializing_if = "Option::is_none")]
        f: Option<f64>,
    },
    /// Circular or helical feed move (G2/G3); end = start in the plane is a full circle.
    Arc {
        /// End X, mm.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        x: Option<f64>,
        /// End Y, mm.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        y: Option<f64>,
        /// End Z, mm.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        z: Option<f64>,
        /// Centre, absolute.
        center: JsonCenter,
        /// G2 (true) or G3, seen looking down the plane's positive normal.
        clockwise: bool,
        /// Plane of the arc (default: xy).
        #[serde(default, skip_serializing_if = "Option::is_none")]
        plane: Option<Plane>,
        /// Extra full turns (LinuxCNC's P − 1; default 0).
        #[serde(default, skip_serializing_if = "Option::is_none")]
        turns: Option<u32>,
        /// Feed, mm/min (modal).
        #[serde(default, skip_serializing_if = "Option::is_none")]
        f: Option<f64>,
    },
}

/// A problem with one move: the field at fault and why.
type Refusal = (&'static str, String);

fn refuse(field: &'static str, reason: impl Into<String>) -> Refusal {
    (field, reason.into())
}

/// Turns JSON moves into a [`Toolpath`] with the same checks as G-code (finite numbers,
/// a feed > 0 before the first feed move, consistent arc radii). Errors name the move by
/// its 1-based index (`line`, 0 for the program's own fields) and the field (`word`).
/// Zero-length rapid and linear moves are dropped as in G-code; there are no events.
pub fn toolpath_from_json(program: &JsonProgram) -> Result<Toolpath, NcErrors> {
    let mut errors = Vec::new();
    let mut report = |line: usize, (field, reason): Refusal| {
        if errors.len() < MAX_NC_ERRORS {
            errors.push(NcError {
                line: u32::try_from(line).unwrap_or(u32::MAX),
                column: 0,
                word: field.to_string(),
                reason,
            });
        }
    };
    let start = program.start.unwrap_or_default();
    if ![start.x, start.y, start.z].iter().all(|v| v.is_finite()) {
        report(0, refuse("start", "the start must be finite"));
    }
    if let Some(s) = program.spindle_rpm {
        if !(s.is_finite() && s >= 0.0) {
            report(0, refuse("spindle_rpm", "the spindle speed must be finite and ≥ 0"));
        }
    }
    let mut position = start;
    let mut feed: Option<f64> = None;
    let mut moves = Vec::with_capacity(program.moves.len());
    for (index, json) in program.moves.iter().enumerate() {
        let line = index + 1;
        let (x, y, z, f) = match *json {
            JsonMove::Rapid { x, y, z } => (x, y, z, None),
            JsonMove::Linear { x, y, z, f } | JsonMove::Arc { x, y, z, f, .. } => (x, y, z, f),
        };
        let end = match target(position, [x, y, z]) {
            Ok(end) => end,
            Err(refusal) => {
                report(line, refusal);
                continue;
            }
        };
        let from = position;
        position = end;
        let motion = match motion(json, from, end, f, &mut feed) {
            Ok(motion) => motion,
            Err(refusal) => {
                report(line, refusal);
                continue;
            }
        };
        let zero_length = ![0, 1, 2].iter().any(|&axis| !approx_eq(coord(from, axis), coord(end, axis), LENGTH_EPS_MM));
        if zero_length && !matches!(motion, Motion::Arc { .. }) {
            continue;
        }
        moves.push(Move {
            motion,
            start: from,
            end,
            feed_mm_min: feed,
            spindle_rpm: program.spindle_rpm,
            tool: program.tool,
            line: u32::try_from(line).unwrap_or(u32::MAX),
        });
    }
    if !errors.is_empty() {
        return Err(NcErrors(errors));
    }
    Ok(Toolpath { moves, events: Vec::new(), source_units: Units::Mm, warnings: Vec::new() })
}

/// The end of a move: the given coordinates, the others kept.
fn target(from: P3, given: [Option<f64>; 3]) -> Result<P3, Refusal> {
    let mut end = from;
    for (axis, (value, name)) in given.into_iter().zip(["x", "y", "z"]).enumerate() {
        if let Some(v) = value {
            if !v.is_finite() {
                return Err(refuse(name, "the coordinate must be finite"));
            }
            end = with_coord(end, axis, v);
        }
    }
    Ok(end)
}

/// The motion of one move, updating the modal feed.
fn motion(json: &JsonMove, from: P3, end: P3, f: Option<f64>, feed: &mut Option<f64>) -> Result<Motion, Refusal> {
    if let Some(f) = f {
        if !(f.is_finite() && f > 0.0) {
            return Err(refuse("f", "the feed must be finite and > 0"));
        }
        *feed = Some(f);
    }
    let JsonMove::Arc { center, clockwise, plane, turns, .. } = *json else {
        return match json {
            JsonMove::Rapid { .. } => Ok(Motion::Rapid),
            _ if feed.is_none() => Err(no_feed()),
            _ => Ok(Motion::Linear),
        };
    };
    if feed.is_none() {
        return Err(no_feed());
    }
    let plane = plane.unwrap_or(Plane::Xy);
    let centre = arc_centre(center, from, plane)?;
    arcs::check_arc(from, centre, end, plane).map_err(|reason| refuse("center", reason))?;
    Ok(Motion::Arc { center: centre, clockwise, plane, turns: turns.unwrap_or(0) })
}

fn no_feed() -> Refusal {
    refuse("f", "a feed move with no feed rate: give f on this move or an earlier one")
}

/// The absolute centre of an arc starting at `from`.
fn arc_centre(center: JsonCenter, from: P3, plane: Plane) -> Result<P3, Refusal> {
    let [a, b, n] = plane_axes(plane);
    let given = [center.x, center.y, center.z];
    let names = ["center.x", "center.y", "center.z"];
    let mut centre = from;
    for axis in [a, b] {
        let Some(v) = given[axis] else {
            return Err(refuse(names[axis], "an arc needs both in-plane centre coordinates"));
        };
        if !v.is_finite() {
            return Err(refuse(names[axis], "the centre must be finite"));
        }
        centre = with_coord(centre, axis, v);
    }
    if let Some(v) = given[n] {
        if !approx_eq(v, coord(from, n), ARC_RADIUS_TOLERANCE_MM) {
            let reason = format!(
                "the centre's coordinate along the plane's normal ({v}) must be the start's \
                 ({}) or be omitted",
                coord(from, n)
            );
            return Err(refuse(names[n], reason));
        }
    }
    Ok(centre)
}

/// The JSON form of `path` (the inverse of [`toolpath_from_json`]): every move with its end
/// coordinates, arcs with their centres, and `f` wherever the feed changes. The spindle speed
/// and tool are the first move's (JSON programs have one of each).
pub fn toolpath_to_json(path: &Toolpath) -> JsonProgram {
    let first = path.moves.first();
    let mut feed: Option<f64> = None;
    let moves = path
        .moves
        .iter()
        .map(|m| {
            let (x, y, z) = (Some(m.end.x), Some(m.end.y), Some(m.end.z));
            let f = match (m.motion, m.feed_mm_min) {
                (Motion::Rapid, _) | (_, None) => None,
                (_, Some(value)) if feed.is_some_and(|f| approx_eq(f, value, 0.0)) => None,
                (_, Some(value)) => {
                    feed = Some(value);
                    Some(value)
                }
            };
            match m.motion {
                Motion::Rapid => JsonMove::Rapid { x, y, z },
                Motion::Linear => JsonMove::Linear { x, y, z, f },
                Motion::Arc { center, clockwise, plane, turns } => JsonMove::Arc {
                    x,
                    y,
                    z,
                    center: JsonCenter { x: Some(center.x), y: Some(center.y), z: Some(center.z) },
                    clockwise,
                    plane: (plane != Plane::Xy).then_some(plane),
                    turns: (turns > 0).then_some(turns),
                    f,
                },
            }
        })
        .collect();
    JsonProgram {
        start: first.map(|m| m.start),
        spindle_rpm: first.and_then(|m| m.spindle_rpm),
        tool: first.and_then(|m| m.tool),
        moves,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::core::nc::{parse_gcode, ParseOptions};

    fn program(json: &str) -> JsonProgram {
        serde_json::from_str(json).unwrap_or_else(|e| panic!("{e}"))
    }

    fn without_lines(mut path: Toolpath) -> Toolpath {
        for m in &mut path.moves {
            m.line = 0;
        }
        path
    }

    #[test]
    fn a_json_program_gives_the_same_toolpath_as_its_gcode() {
        let json = program(
            r#"{"start": {"x": 0, "y": 0, "z": 5}, "spindle_rpm": 8000, "moves": [
                {"type": "rapid", "x": 10, "y": 0},
                {"type": "linear", "z": -1, "f": 300},
                {"type": "linear", "z": -1},
                {"type": "arc", "x": 0, "y": 10, "center": {"x": 0, "y": 0}, "clockwise": false},
                {"type": "arc", "x": 0, "y": 10, "z": -3, "center": {"x": 0, "y": 0, "z": -1},
                 "clockwise": true, "turns": 1, "f": 150},
                {"type": "arc", "x": 10, "center": {"x": 5, "z": -3}, "clockwise": false,
                 "plane": "zx"},
                {"type": "rapid", "z": 5}
            ]}"#,
        );
        let gcode = "S8000\nG0 X10 Y0\nG1 Z-1 F300\nG1 Z-1\nG3 X0 Y10 I-10 J0\n\
                     G2 X0 Y10 Z-3 I0 J-10 P2 F150\nG18 G3 X10 I5 K0\nG0 Z5\n";
        let options = ParseOptions { initial_position: P3::new(0.0, 0.0, 5.0), ..ParseOptions::default() };
        let from_json = toolpath_from_json(&json).unwrap();
        let from_gcode = parse_gcode(gcode, &options).unwrap();
        assert_eq!(from_json.moves.len(), 6);
        assert_eq!(from_json.moves[3].line, 5);
        assert_eq!(without_lines(from_json), without_lines(from_gcode));
    }

    #[test]
    fn a_toolpath_written_as_json_reads_back_the_same() {
        let text = "G21 G90 G17\nS8000 M3\nG0 X10 Y0 Z5\nG1 Z-1 F300\nG3 X0 Y10 I-10 J0\nG2 X0 Y10 Z-3 I0 J-10 P2 F150\nG18 G3 X10 Z-3 I5 K0\nG0 Z5\nM30\n";
        let path = parse_gcode(text, &ParseOptions::default()).unwrap();
        let json = toolpath_to_json(&path);
        let back = toolpath_from_json(&serde_json::from_str(&serde_json::to_string(&json).unwrap()).unwrap()).unwrap();
        assert_eq!(without_lines(back).moves, without_lines(path).moves);
    }

    #[test]
    fn unknown_fields_and_move_types_are_refused_by_the_reader() {
        for json in [
            r#"{"moves": [{"type": "rapid", "x": 1, "w": 2}]}"#,
            r#"{"moves": [{"type": "spline", "x": 1}]}"#,
            r#"{"moves": [], "units": "inch"}"#,
            r#"{"moves": [{"type": "arc", "x": 1, "center": {"x": 0, "y": 0, "k": 1}, "clockwise": true}]}"#,
        ] {
            assert!(serde_json::from_str::<JsonProgram>(json).is_err(), "{json}");
        }
    }

    #[test]
    fn invalid_moves_are_refused_naming_the_move_and_the_field() {
        let mut json = program(
            r#"{"moves": [
                {"type": "linear", "x": 1},
                {"type": "rapid", "x": 1},
                {"type": "linear", "x": 2, "f": 100},
                {"type": "arc", "x": 12, "y": 0.6, "center": {"x": 7, "y": 0}, "clockwise": true},
                {"type": "arc", "x": 12, "center": {"x": 7}, "clockwise": true},
                {"type": "arc", "x": 2, "center": {"x": 7, "y": 0, "z": 4}, "clockwise": true},
                {"type": "linear", "x": 3, "f": -5}
            ]}"#,
        );
        json.moves[1] = JsonMove::Rapid { x: Some(f64::NAN), y: None, z: None };
        let errors = toolpath_from_json(&json).unwrap_err().0;
        let found: Vec<_> = errors.iter().map(|e| (e.line, e.word.as_str())).collect();
        assert_eq!(found, [(1, "f"), (2, "x"), (4, "center"), (5, "center.y"), (6, "center.z"), (7, "f")]);
        assert!(errors[2].reason.contains("5.0000 mm") && errors[2].reason.contains("5.0359 mm"));
        assert_eq!(errors[0].to_string(), format!("line 1 (f): {}", errors[0].reason));
    }

    #[test]
    fn the_program_fields_are_checked_as_line_zero() {
        let json = JsonProgram {
            start: Some(P3::new(f64::INFINITY, 0.0, 0.0)),
            spindle_rpm: Some(-1.0),
            tool: None,
            moves: Vec::new(),
        };
        let errors = toolpath_from_json(&json).unwrap_err().0;
        let found: Vec<_> = errors.iter().map(|e| (e.line, e.word.as_str())).collect();
        assert_eq!(found, [(0, "start"), (0, "spindle_rpm")]);
    }
}
