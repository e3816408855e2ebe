//! `GET /v1/examples`: a few complete job inputs built into the binary, for the web page's
//! "built-in example" source and for trying the API without data of one's own.

use crate::service::jobs::model::JobKind;
use crate::service::state::AppState;
use serde::Serialize;
use serde_json::{json, Value};
use utoipa::ToSchema;
use utoipa_axum::{router::OpenApiRouter, routes};

/// A built-in example job.
#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct Example {
    /// Stable identifier, e.g. `pocket-slot-trochoids`.
    pub id: String,
    pub title: String,
    /// What the example shows and roughly how long it runs.
    pub description: String,
    /// The job kind; submit `input` to its endpoint (or `POST /v1/jobs {kind, input}`).
    pub kind: JobKind,
    /// The complete job input.
    #[schema(value_type = Object)]
    pub input: Value,
}

/// The built-in examples.
#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct ExampleList {
    pub items: Vec<Example>,
}

/// An 80 × 60 mm box pocket with a 12 mm wide, 40 mm long slot out of its right wall.
fn box_with_slot() -> Value {
    json!({"outer": [[0, 0], [80, 0], [80, 24], [120, 24], [120, 36], [80, 36], [80, 60], [0, 60]]})
}

/// A slot through a 60 × 40 × 5 mm block, then four 1 mm side steps that widen it.
const SLOT_AND_STEPS: &str = "(slot through the block, then widen it by 1 mm steps)
G21 G90 G17
S9600 M3
G0 X-10 Y20 Z5
G1 Z-5 F1000
G1 X70 F1200
G0 Z5
G0 X-10 Y21
G1 Z-5 F1000
G1 X70 F5760
G0 Z5
G0 X-10 Y22
G1 Z-5 F1000
G1 X70 F5760
G0 Z5
G0 X70 Y19
G1 Z-5 F1000
G1 X-10 F5760
G0 Z5
G0 X70 Y18
G1 Z-5 F1000
G1 X-10 F5760
G0 Z5
M30
";

/// One pass round the walls of a pre-roughed 40 × 40 mm pocket, 0.5 mm into the wall.
const WALL_PASS: &str = "(finish the walls of a pre-roughed 40 x 40 pocket, 0.5 mm radial)
G21 G90 G17
S9600 M3
G0 X0 Y0 Z5
G1 Z-10 F1000
G1 X15.5 F5760
G1 Y15.5
G1 X-15.5
G1 Y-15.5
G1 X15.5
G1 Y0
G0 Z5
M30
";

/// The stock of [`WALL_PASS`]: a 60 × 60 × 10 mm block with the 40 × 40 pocket open.
fn pre_roughed_pocket() -> Value {
    json!({"box": {"x_min": -30, "y_min": -30, "z_min": -10, "x_max": 30, "y_max": 30, "z_max": 0},
           "open": [{"contour": [[-20, -20], [20, -20], [20, 20], [-20, 20]]}]})
}

/// Every built-in example, in the order the page lists them.
pub fn all() -> Vec<Example> {
    let example = |id: &str, title: &str, description: &str, kind: JobKind, input: Value| Example {
        id: id.into(),
        title: title.into(),
        description: description.into(),
        kind,
        input,
    };
    vec![
        example(
            "pocket-slot-trochoids",
            "Pocket with a narrow slot: trochoids",
            "An 80 × 60 mm box pocket, 10 mm deep, with a 12 mm slot out of its right wall, roughed with the \
             10 mm square end mill. The contour-parallel path slots (α up to 180°) in the narrow slot and \
             where the loops close; trochoid cycles are inserted there and the result is simulated again. \
             Takes a few seconds.",
            JobKind::Trochoids,
            json!({"contour": box_with_slot(), "z_top": 0, "z_bottom": -10, "tool_type": "square", "diameter_mm": 10}),
        ),
        example(
            "slot-analysis",
            "Slot and side steps: where the tool overloads",
            "A 10 mm square end mill slots through a 60 × 40 × 5 mm block (full slot: α 180°, a critical \
             region) and then widens the slot by 1 mm side steps (α 36.9°, below the 40° limit). Takes a \
             second or two.",
            JobKind::Analysis,
            json!({"program": {"gcode": SLOT_AND_STEPS}, "tool_type": "square", "diameter_mm": 10,
                   "stock": {"box": {"x_min": 0, "y_min": 0, "z_min": -5, "x_max": 60, "y_max": 40, "z_max": 0}},
                   "series_points": 400}),
        ),
        example(
            "pocket-wall-feeds",
            "Pocket walls: constant-force feeds",
            "One pass round the walls of a pre-roughed 40 × 40 mm pocket, 10 mm deep and 0.5 mm into the \
             wall, at the programmed 5760 mm/min. In the corners the engagement rises far above the \
             straight walls' 25.8°; the feed of every block is set so the cutting force stays at the \
             tool's standard force, slowing down into each corner. Takes a few seconds.",
            JobKind::Feeds,
            json!({"program": {"gcode": WALL_PASS}, "tool_type": "square", "diameter_mm": 10,
                   "strategy": "constant_force", "stock": pre_roughed_pocket()}),
        ),
        example(
            "pocket-wall-costing",
            "Pocket walls: time, tool wear and cost",
            "The same wall pass at its programmed feed: machining time (nominal and with the machine's \
             acceleration limits), tool-life consumption with the lines where the tool wears (the \
             corners), and the cost. Takes a few seconds.",
            JobKind::Costing,
            json!({"program": {"gcode": WALL_PASS}, "tool_type": "square", "diameter_mm": 10,
                   "stock": pre_roughed_pocket()}),
        ),
        example(
            "cavity-plan",
            "Small die cavity: complete process plan",
            "A 90 × 70 mm cavity with rounded corners and a 12 mm slot, 35 mm deep, planned with the \
             10 mm square end mill: layers, helical entries, trochoids where the tool would overload, \
             constant-force feeds, time, tool life and cost, compared with the conventional ball-end \
             roughing. Takes about a minute (longer while other jobs run).",
            JobKind::Plan,
            json!({"contour": {"outer": [[8, 0], [82, 0, 0.414214], [90, 8], [90, 29], [114, 29, 1], [114, 41],
                                         [90, 41], [90, 62, 0.414214], [82, 70], [8, 70, 0.414214], [0, 62],
                                         [0, 8, 0.414214]]},
                   "z_top": 0, "z_bottom": -35, "diameters_mm": [10], "sample_spacing_mm": 0.1}),
        ),
    ]
}

/// Lists the built-in examples: complete job inputs to submit as they are or to edit.
#[utoipa::path(get, path = "/v1/examples", tag = "jobs", operation_id = "listExamples",
    responses((status = 200, description = "The built-in examples", body = ExampleList)))]
pub async fn list_examples() -> axum::Json<ExampleList> {
    axum::Json(ExampleList { items: all() })
}

pub fn router() -> OpenApiRouter<AppState> {
    OpenApiRouter::new().routes(routes!(list_examples))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn examples_have_unique_ids_and_object_inputs() {
        let examples = all();
        let mut ids: Vec<&str> = examples.iter().map(|e| e.id.as_str()).collect();
        ids.sort_unstable();
        ids.dedup();
        assert_eq!(ids.len(), examples.len());
        assert!(examples.iter().all(|e| e.input.is_object()));
    }
}
