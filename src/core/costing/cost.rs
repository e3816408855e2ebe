//! The cost of a program (seed 002, Eq. 4): `C = c_m · T_m + c_t · L_t / L_f`.

use crate::core::CoreError;
use serde::{Deserialize, Serialize};

/// Minutes per hour.
const MIN_PER_HOUR: f64 = 60.0;

/// The shop's rates.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Rates {
    /// c_m: machine and operator, per hour.
    pub machine_rate_per_hour: f64,
    /// c_t: one tool.
    pub tool_price: f64,
    pub currency: String,
}

/// A cost and its two parts, in the rates' currency.
#[derive(Debug, Clone, PartialEq, Serialize, utoipa::ToSchema)]
pub struct Cost {
    /// c_m · T_m.
    pub machine: f64,
    /// c_t · L_t / L_f.
    pub tool: f64,
    pub total: f64,
    pub currency: String,
}

/// `C = c_m · T_m + c_t · L_t / L_f` (seed 002, Eq. 4) for `time_min` of machining and a
/// tool consumption `L_t / L_f`.
pub fn cost(time_min: f64, consumption_ratio: f64, rates: &Rates) -> Result<Cost, CoreError> {
    for (field, v) in [
        ("machine_rate_per_hour", rates.machine_rate_per_hour),
        ("tool_price", rates.tool_price),
        ("time_min", time_min),
        ("consumption", consumption_ratio),
    ] {
        if !(v.is_finite() && v >= 0.0) {
            return Err(CoreError::invalid(field, format!("must be a finite number ≥ 0, got {v}")));
        }
    }
    let machine = rates.machine_rate_per_hour * time_min / MIN_PER_HOUR;
    let tool = rates.tool_price * consumption_ratio;
    Ok(Cost { machine, tool, total: machine + tool, currency: rates.currency.clone() })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn half_an_hour_and_a_quarter_of_a_tool_cost_their_shares() {
        let rates = Rates { machine_rate_per_hour: 60.0, tool_price: 80.0, currency: "USD".into() };
        let c = cost(30.0, 0.25, &rates).unwrap();
        assert!((c.machine - 30.0).abs() < 1e-12 && (c.tool - 20.0).abs() < 1e-12 && (c.total - 50.0).abs() < 1e-12);
    }

    #[test]
    fn negative_or_infinite_inputs_are_refused() {
        let rates = Rates { machine_rate_per_hour: -1.0, tool_price: 80.0, currency: "USD".into() };
        assert!(cost(1.0, 0.1, &rates).is_err());
        let rates = Rates { machine_rate_per_hour: 60.0, tool_price: 80.0, currency: "USD".into() };
        assert!(cost(f64::INFINITY, 0.1, &rates).is_err());
    }
}
