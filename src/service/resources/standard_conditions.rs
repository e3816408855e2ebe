//! Standard cutting conditions per tool, material and operation: `/v1/conditions/standard`.

use super::routes::eq;
use super::{ListFilter, PageRequest, Reference, Resource, Source, SqlValue};
use crate::core::conditions::CuttingConditions;
use crate::core::operation::Operation;
use crate::service::error::Validator;
use serde::{Deserialize, Serialize};
use utoipa::{IntoParams, ToSchema};

/// The range of spindle speeds a row may give, min⁻¹ (assumed: the fastest spindles turn
/// about 150 000 min⁻¹; below 1 min⁻¹ no time or feed stays finite).
const SPINDLE_RPM_RANGE: (f64, f64) = (1.0, 200_000.0);
/// The range of feeds per tooth, mm (assumed: 0.1 µm to 10 mm).
const FEED_PER_TOOTH_RANGE_MM: (f64, f64) = (1e-4, 10.0);
/// The range of radial and axial depths, mm (assumed: 1 µm to 1 m).
const DEPTH_RANGE_MM: (f64, f64) = (1e-3, 1000.0);

/// One operation's standard conditions for one tool in one material.
#[derive(Debug, Clone, Serialize, Deserialize, sqlx::FromRow, ToSchema)]
#[serde(deny_unknown_fields)]
#[schema(example = json!({"tool_id": 3, "material_id": 1, "operation": "rough_side_cutting", "spindle_rpm": 4800.0, "fz_mm": 0.1, "fz_min_mm": 0.005, "rd_mm": 0.5, "ad_mm": 10.0, "ad_last_layer_mm": 5.0}))]
pub struct StandardConditionsData {
    pub tool_id: i64,
    pub material_id: i64,
    #[sqlx(try_from = "String")]
    pub operation: Operation,
    /// Spindle speed S, min⁻¹.
    #[schema(minimum = 1, maximum = 200000)]
    pub spindle_rpm: f64,
    /// Feed per tooth fz, mm/tooth.
    #[schema(minimum = 0.0001, maximum = 10)]
    pub fz_mm: f64,
    /// Smallest feed per tooth a feed optimisation may command, mm/tooth.
    #[schema(minimum = 0.0001, maximum = 10)]
    pub fz_min_mm: f64,
    /// Largest feed per tooth, mm/tooth (none: 2 × standard feed, MODEL.md §3).
    #[serde(default)]
    #[schema(minimum = 0.0001, maximum = 10)]
    pub fz_max_mm: Option<f64>,
    /// Radial depth of cut Rd, mm (for trochoids: the pitch).
    #[schema(minimum = 0.001, maximum = 1000)]
    pub rd_mm: f64,
    /// Axial depth of cut Ad, mm (helical boring: per turn).
    #[schema(minimum = 0.001, maximum = 1000)]
    pub ad_mm: f64,
    /// Axial depth on the last (intermediate-rough) layer, mm.
    #[serde(default)]
    #[schema(minimum = 0.001, maximum = 1000)]
    pub ad_last_layer_mm: Option<f64>,
    #[serde(default)]
    pub notes: String,
    #[serde(default = "Source::user")]
    pub source: Source,
    #[serde(default)]
    pub reference: String,
}

impl StandardConditionsData {
    pub fn conditions(&self) -> CuttingConditions {
        CuttingConditions { spindle_rpm: self.spindle_rpm, fz_mm: self.fz_mm, rd_mm: self.rd_mm, ad_mm: self.ad_mm }
    }
}

impl Resource for StandardConditionsData {
    const TABLE: &'static str = "standard_conditions";
    const SINGULAR: &'static str = "standard conditions row";
    const COLUMNS: &'static [&'static str] = &[
        "tool_id",
        "material_id",
        "operation",
        "spindle_rpm",
        "fz_mm",
        "fz_min_mm",
        "fz_max_mm",
        "rd_mm",
        "ad_mm",
        "ad_last_layer_mm",
        "notes",
        "source",
        "reference",
    ];

    fn values(&self) -> Vec<SqlValue> {
        vec![
            self.tool_id.into(),
            self.material_id.into(),
            self.operation.as_str().into(),
            self.spindle_rpm.into(),
            self.fz_mm.into(),
            self.fz_min_mm.into(),
            self.fz_max_mm.into(),
            self.rd_mm.into(),
            self.ad_mm.into(),
            self.ad_last_layer_mm.into(),
            self.notes.clone().into(),
            self.source.as_str().into(),
            self.reference.clone().into(),
        ]
    }

    fn validate(&self, v: &mut Validator) {
        let (rpm, fz, depth) = (SPINDLE_RPM_RANGE, FEED_PER_TOOTH_RANGE_MM, DEPTH_RANGE_MM);
        v.within("spindle_rpm", self.spindle_rpm, rpm.0, rpm.1);
        v.within("fz_mm", self.fz_mm, fz.0, fz.1);
        v.within("fz_min_mm", self.fz_min_mm, fz.0, fz.1);
        v.within("rd_mm", self.rd_mm, depth.0, depth.1);
        v.within("ad_mm", self.ad_mm, depth.0, depth.1);
        if let Some(max) = self.fz_max_mm {
            v.within("fz_max_mm", max, fz.0, fz.1);
            v.check(max >= self.fz_mm, "fz_max_mm", format!("must be at least fz_mm = {}", self.fz_mm));
        }
        v.check(self.fz_min_mm <= self.fz_mm, "fz_min_mm", format!("must not exceed fz_mm = {}", self.fz_mm));
        if let Some(last) = self.ad_last_layer_mm {
            v.within("ad_last_layer_mm", last, depth.0, depth.1);
        }
    }

    fn references(&self) -> Vec<Reference> {
        vec![
            Reference { field: "tool_id", table: "tools", id: self.tool_id },
            Reference { field: "material_id", table: "materials", id: self.material_id },
        ]
    }
}

crate::record!(
    /// Standard conditions of one operation.
    StandardConditions,
    StandardConditionsData
);

/// Filters of `GET /v1/conditions/standard`.
#[derive(Debug, Deserialize, IntoParams)]
#[serde(deny_unknown_fields)]
#[into_params(parameter_in = Query)]
pub struct StandardConditionsFilter {
    pub tool_id: Option<i64>,
    pub material_id: Option<i64>,
    #[param(value_type = Option<Operation>)]
    pub operation: Option<String>,
    pub source: Option<Source>,
    pub limit: Option<i64>,
    pub offset: Option<i64>,
}

impl ListFilter for StandardConditionsFilter {
    fn conditions(&self) -> Vec<(String, Vec<SqlValue>)> {
        [
            eq("tool_id", self.tool_id),
            eq("material_id", self.material_id),
            eq("operation", self.operation.clone()),
            eq("source", self.source.map(Source::as_str)),
        ]
        .into_iter()
        .flatten()
        .collect()
    }

    fn page(&self) -> PageRequest {
        PageRequest { limit: self.limit, offset: self.offset }
    }

    fn validate(&self, v: &mut Validator) {
        if let Some(operation) = &self.operation {
            let names: Vec<&str> = Operation::ALL.iter().map(|o| o.as_str()).collect();
            v.check(Operation::parse(operation).is_some(), "operation", format!("must be one of {}", names.join(", ")));
        }
    }
}

crate::crud_api!(
    module: api,
    record: StandardConditions,
    data: StandardConditionsData,
    filter: StandardConditionsFilter,
    collection: "/v1/conditions/standard",
    item: "/v1/conditions/standard/{id}",
    tag: "database",
    ids: ["listStandardConditions", "getStandardConditions", "createStandardConditions", "replaceStandardConditions", "updateStandardConditions", "deleteStandardConditions"],
);
