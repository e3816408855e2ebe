//! OpenAPI schemas of the core's plain enums that requests name (tool type, operation,
//! strategy, objective, cut direction, coolant) and of the shortfall kind: each lists its
//! values with what they mean, in one description written for the API. The core's report
//! types derive theirs (`utoipa::ToSchema`, descriptions from their doc comments).

use crate::core::feed::collect::ShortfallKind;
use crate::core::feed::objective::Objective;
use crate::core::feed::rule::FeedStrategy;
use crate::core::operation::Operation;
use crate::core::tool::ToolType;
use std::borrow::Cow;
use utoipa::openapi::schema::{ObjectBuilder, Schema, Type};
use utoipa::openapi::RefOr;

fn string_enum(values: Vec<&'static str>, description: &str) -> RefOr<Schema> {
    ObjectBuilder::new().schema_type(Type::String).enum_values(Some(values)).description(Some(description)).into()
}

impl utoipa::PartialSchema for ToolType {
    fn schema() -> RefOr<Schema> {
        string_enum(
            ToolType::ALL.iter().map(|t| t.as_str()).collect(),
            "End-mill shape: square (straight, flat end), radius (flat end with corner radius), ball.",
        )
    }
}

impl utoipa::ToSchema for ToolType {
    fn name() -> Cow<'static, str> {
        Cow::Borrowed("ToolType")
    }
}

impl utoipa::PartialSchema for Operation {
    fn schema() -> RefOr<Schema> {
        string_enum(
            Operation::ALL.iter().map(|o| o.as_str()).collect(),
            "Machining operation with its own standard conditions (MODEL.md §5). standard_side_cutting is the reference straight cut of the force model and tool-life test.",
        )
    }
}

impl utoipa::ToSchema for Operation {
    fn name() -> Cow<'static, str> {
        Cow::Borrowed("Operation")
    }
}

impl utoipa::PartialSchema for FeedStrategy {
    fn schema() -> RefOr<Schema> {
        string_enum(
            vec!["cutting_point", "constant_force", "both"],
            "How feeds are chosen: cutting_point holds the programmed feed at the cutting point (seed 000, Eq. 1); constant_force holds the cutting force at the target (MODEL.md §3); both takes the lower of the two.",
        )
    }
}

impl utoipa::ToSchema for FeedStrategy {
    fn name() -> Cow<'static, str> {
        Cow::Borrowed("FeedStrategy")
    }
}

impl utoipa::PartialSchema for Objective {
    fn schema() -> RefOr<Schema> {
        string_enum(
            vec!["min_cost", "constant_force", "min_time"],
            "What the feeds are chosen for: min_cost, the cheapest feed per millimetre (machine time and tool wear, seed 002 Eq. 4 and MODEL.md §9) under the force limit, never a program that costs more than the input; constant_force, the papers' rule as written (MODEL.md §3: the target force, the minimum feed where it cannot be held); min_time, the fastest feed under the force limit.",
        )
    }
}

impl utoipa::ToSchema for Objective {
    fn name() -> Cow<'static, str> {
        Cow::Borrowed("Objective")
    }
}

impl utoipa::PartialSchema for ShortfallKind {
    fn schema() -> RefOr<Schema> {
        string_enum(
            vec!["infeasible", "below_minimum_feed"],
            "Why the target force is not held: infeasible (no feed reaches it: a trochoid or a z-cut division is needed) or below_minimum_feed (the feed is held at the minimum and the force stays above the target).",
        )
    }
}

impl utoipa::ToSchema for ShortfallKind {
    fn name() -> Cow<'static, str> {
        Cow::Borrowed("ShortfallKind")
    }
}

impl utoipa::PartialSchema for crate::core::cycles::CutDirection {
    fn schema() -> RefOr<Schema> {
        string_enum(
            vec!["climb", "conventional"],
            "Milling direction with an M3 spindle: climb (down cut, the material on the right of travel; default, MODEL.md §1) or conventional (up cut).",
        )
    }
}

impl utoipa::ToSchema for crate::core::cycles::CutDirection {
    fn name() -> Cow<'static, str> {
        Cow::Borrowed("CutDirection")
    }
}

impl utoipa::PartialSchema for crate::core::coolant::Coolant {
    fn schema() -> RefOr<Schema> {
        string_enum(
            crate::core::coolant::Coolant::ALL.iter().map(|c| c.as_str()).collect(),
            "Coolant a program switches on after the spindle starts and off (M9) at its end: off (dry, or an air blast the machine runs by itself; seed 001 and 003 cut dry with air), mist (M7: seed 004 §3.4 used oil air mist) or flood (M8).",
        )
    }
}

impl utoipa::ToSchema for crate::core::coolant::Coolant {
    fn name() -> Cow<'static, str> {
        Cow::Borrowed("Coolant")
    }
}
