//! The coolant a program switches on after the spindle starts: what the
//! machine's database row says (`machines.coolant`), unless the request says otherwise.
//! The papers cut the hardened die steel dry with an air blast (seed 001 Table 2, seed 003
//! Table 1) or with oil-air mist at the cutting point and no coolant (seed 004 §3.4, on the
//! OKK VM4-II that the database seeds).

use serde::{Deserialize, Serialize};

/// The coolant a program switches on after the spindle starts (and off at its end).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Coolant {
    /// None: dry cutting, or an air blast the machine controls by itself (seed 001 Table 2,
    /// seed 003 Table 1: "dry air").
    #[default]
    Off,
    /// Oil mist, `M7` (seed 004 §3.4: "no coolant was used, only oil air mist
    /// lubrication").
    Mist,
    /// Flood coolant, `M8`.
    Flood,
}

impl Coolant {
    pub const ALL: [Coolant; 3] = [Coolant::Off, Coolant::Mist, Coolant::Flood];

    pub fn as_str(self) -> &'static str {
        match self {
            Coolant::Off => "off",
            Coolant::Mist => "mist",
            Coolant::Flood => "flood",
        }
    }

    pub fn parse(text: &str) -> Option<Coolant> {
        Coolant::ALL.into_iter().find(|c| c.as_str() == text)
    }
}

impl TryFrom<String> for Coolant {
    type Error = crate::core::CoreError;

    fn try_from(value: String) -> Result<Self, Self::Error> {
        Coolant::parse(&value).ok_or_else(|| {
            crate::core::CoreError::invalid("coolant", format!("unknown coolant '{value}': off, mist or flood"))
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_coolant_name_parses_back_to_itself_and_others_are_refused() {
        for c in Coolant::ALL {
            assert_eq!(Coolant::try_from(c.as_str().to_string()).unwrap(), c);
            assert_eq!(serde_json::to_string(&c).unwrap(), format!("\"{}\"", c.as_str()));
        }
        let e = Coolant::try_from("through_spindle".to_string()).unwrap_err().to_string();
        assert!(e.contains("off, mist or flood"), "{e}");
        assert_eq!(Coolant::default(), Coolant::Off);
    }
}
