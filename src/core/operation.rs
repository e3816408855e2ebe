//! The machining operations the cutting-condition database keeps conditions for
//! (MODEL.md §5; seed 004 Tables 2 and 6; seed 001 Table 2 for the standard).

use serde::{Deserialize, Serialize};

/// A kind of cut with its own standard conditions.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Operation {
    /// The reference straight side cut of the force and tool-life tests (seed 001 Table 2,
    /// seed 003 Table 1): the conditions at which the force model is centred.
    StandardSideCutting,
    /// Helical boring of an approach hole with a ball end mill (seed 004 Table 2).
    HelicalBoring,
    /// Spiral expansion of the approach hole (seed 004 Table 2).
    SpiralHoleExpansion,
    /// Trochoidal grooving of slots and critical regions (seed 004 Table 2).
    TrochoidalGrooving,
    /// Rough side cutting by contour-parallel paths (seed 004 Table 2).
    RoughSideCutting,
    /// Intermediate-rough side cutting of the last layer (seed 004 Table 2).
    IntermediateRoughSideCutting,
    /// The conventional baseline: ball-end roughing in thin layers (seed 004 Table 3).
    ConventionalBallRoughing,
}

impl Operation {
    pub const ALL: [Operation; 7] = [
        Operation::StandardSideCutting,
        Operation::HelicalBoring,
        Operation::SpiralHoleExpansion,
        Operation::TrochoidalGrooving,
        Operation::RoughSideCutting,
        Operation::IntermediateRoughSideCutting,
        Operation::ConventionalBallRoughing,
    ];

    pub fn as_str(self) -> &'static str {
        match self {
            Operation::StandardSideCutting => "standard_side_cutting",
            Operation::HelicalBoring => "helical_boring",
            Operation::SpiralHoleExpansion => "spiral_hole_expansion",
            Operation::TrochoidalGrooving => "trochoidal_grooving",
            Operation::RoughSideCutting => "rough_side_cutting",
            Operation::IntermediateRoughSideCutting => "intermediate_rough_side_cutting",
            Operation::ConventionalBallRoughing => "conventional_ball_roughing",
        }
    }

    pub fn parse(text: &str) -> Option<Operation> {
        Operation::ALL.into_iter().find(|o| o.as_str() == text)
    }
}

impl TryFrom<String> for Operation {
    type Error = crate::core::CoreError;

    fn try_from(value: String) -> Result<Self, Self::Error> {
        Operation::parse(&value)
            .ok_or_else(|| crate::core::CoreError::invalid("operation", format!("unknown operation '{value}'")))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_operation_name_parses_back_to_itself() {
        for op in Operation::ALL {
            assert_eq!(Operation::parse(op.as_str()), Some(op));
            let json = serde_json::to_string(&op).unwrap();
            assert_eq!(json, format!("\"{}\"", op.as_str()));
        }
    }
}
