//! End-mill geometry as the models need it.

use serde::{Deserialize, Serialize};

/// The shape of an end mill's cutting end.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ToolType {
    /// Square (straight, flat) end mill.
    Square,
    /// Radius (bull-nose) end mill: flat end with a corner radius.
    Radius,
    /// Ball end mill: corner radius = D/2.
    Ball,
}

impl ToolType {
    pub const ALL: [ToolType; 3] = [ToolType::Square, ToolType::Radius, ToolType::Ball];

    pub fn as_str(self) -> &'static str {
        match self {
            ToolType::Square => "square",
            ToolType::Radius => "radius",
            ToolType::Ball => "ball",
        }
    }

    pub fn parse(text: &str) -> Option<ToolType> {
        ToolType::ALL.into_iter().find(|t| t.as_str() == text)
    }

    /// Side milling with the cylindrical flank (the papers' 2.5-D engagement and force
    /// models) applies to flat-ended tools; a ball end mill cuts with its sphere.
    pub fn cuts_with_flank(self) -> bool {
        !matches!(self, ToolType::Ball)
    }
}

/// The geometry of one end mill.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct EndMill {
    pub tool_type: ToolType,
    pub diameter_mm: f64,
    pub flutes: u32,
    pub corner_radius_mm: f64,
}

impl EndMill {
    pub fn radius_mm(&self) -> f64 {
        self.diameter_mm / 2.0
    }
}

impl TryFrom<String> for ToolType {
    type Error = crate::core::CoreError;

    fn try_from(value: String) -> Result<Self, Self::Error> {
        ToolType::parse(&value)
            .ok_or_else(|| crate::core::CoreError::invalid("tool_type", format!("unknown tool type '{value}'")))
    }
}
