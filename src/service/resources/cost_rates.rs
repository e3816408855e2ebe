//! Cost rates of seed 002 Eq. 4: `/v1/cost-rates`.

use super::tools::MAX_PRICE;
use super::{NameFilter, Resource, Source, SqlValue};
use crate::service::error::Validator;
use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

/// Machine cost per hour `c_m` and the price of a tool `c_t` (seed 002 Eq. 4).
#[derive(Debug, Clone, Serialize, Deserialize, sqlx::FromRow, ToSchema)]
#[serde(deny_unknown_fields)]
#[schema(example = json!({"name": "night shift", "currency": "EUR", "machine_rate_per_hour": 45.0, "default_tool_price": 70.0}))]
pub struct CostRatesData {
    #[schema(min_length = 1, pattern = r"\S")]
    pub name: String,
    /// Currency code, e.g. USD, EUR, JPY.
    #[schema(min_length = 1, pattern = r"\S")]
    pub currency: String,
    /// Machine cost per hour `c_m`.
    #[schema(minimum = 0, maximum = 10000000)]
    pub machine_rate_per_hour: f64,
    /// Price of a tool `c_t` for tools that have no price of their own.
    #[schema(minimum = 0, maximum = 10000000)]
    pub default_tool_price: f64,
    #[serde(default = "Source::user")]
    pub source: Source,
    #[serde(default)]
    pub reference: String,
}

impl Resource for CostRatesData {
    const TABLE: &'static str = "cost_rates";
    const SINGULAR: &'static str = "cost-rates row";
    const COLUMNS: &'static [&'static str] =
        &["name", "currency", "machine_rate_per_hour", "default_tool_price", "source", "reference"];

    fn values(&self) -> Vec<SqlValue> {
        vec![
            self.name.clone().into(),
            self.currency.clone().into(),
            self.machine_rate_per_hour.into(),
            self.default_tool_price.into(),
            self.source.as_str().into(),
            self.reference.clone().into(),
        ]
    }

    fn validate(&self, v: &mut Validator) {
        v.not_blank("name", &self.name);
        v.not_blank("currency", &self.currency);
        v.within("machine_rate_per_hour", self.machine_rate_per_hour, 0.0, MAX_PRICE);
        v.within("default_tool_price", self.default_tool_price, 0.0, MAX_PRICE);
    }
}

crate::record!(
    /// Cost rates.
    CostRates,
    CostRatesData
);

crate::crud_api!(
    module: api,
    record: CostRates,
    data: CostRatesData,
    filter: NameFilter,
    collection: "/v1/cost-rates",
    item: "/v1/cost-rates/{id}",
    tag: "database",
    ids: ["listCostRates", "getCostRates", "createCostRates", "replaceCostRates", "updateCostRates", "deleteCostRates"],
);
