//! Machine tools and their limits: `/v1/machines`.

use super::{NameFilter, Resource, Source, SqlValue};
use crate::core::coolant::Coolant;
use crate::service::error::Validator;
use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

/// The range of every machine limit (speeds in mm/min or min⁻¹, accelerations in mm/s²,
/// jerks in mm/s³; assumed: from 0.001 to 10⁹, so no time computed from them overflows).
const LIMIT_RANGE: (f64, f64) = (1e-3, 1e9);
/// The longest tool change, s (assumed: an hour).
const MAX_TOOL_CHANGE_S: f64 = 3600.0;

/// A machining centre: rapid rate, feed and spindle limits, per-axis acceleration and
/// jerk (for the kinematic time estimate, MODEL.md §10), tool-change time, and the coolant
/// the programs written for it switch on.
#[derive(Debug, Clone, Serialize, Deserialize, sqlx::FromRow, ToSchema)]
#[serde(deny_unknown_fields)]
#[schema(example = json!({"name": "shop VMC", "rapid_mm_min": 30000.0, "max_feed_mm_min": 20000.0, "max_spindle_rpm": 24000.0, "accel_x_mm_s2": 3000.0, "accel_y_mm_s2": 3000.0, "accel_z_mm_s2": 2500.0, "jerk_x_mm_s3": 60000.0, "jerk_y_mm_s3": 60000.0, "jerk_z_mm_s3": 50000.0, "tool_change_s": 5.0}))]
pub struct MachineData {
    #[schema(min_length = 1, pattern = r"\S")]
    pub name: String,
    #[schema(minimum = 0.001, maximum = 1000000000)]
    pub rapid_mm_min: f64,
    #[schema(minimum = 0.001, maximum = 1000000000)]
    pub max_feed_mm_min: f64,
    #[schema(minimum = 0.001, maximum = 1000000000)]
    pub max_spindle_rpm: f64,
    #[schema(minimum = 0.001, maximum = 1000000000)]
    pub accel_x_mm_s2: f64,
    #[schema(minimum = 0.001, maximum = 1000000000)]
    pub accel_y_mm_s2: f64,
    #[schema(minimum = 0.001, maximum = 1000000000)]
    pub accel_z_mm_s2: f64,
    #[schema(minimum = 0.001, maximum = 1000000000)]
    pub jerk_x_mm_s3: f64,
    #[schema(minimum = 0.001, maximum = 1000000000)]
    pub jerk_y_mm_s3: f64,
    #[schema(minimum = 0.001, maximum = 1000000000)]
    pub jerk_z_mm_s3: f64,
    #[schema(minimum = 0, maximum = 3600)]
    pub tool_change_s: f64,
    /// Coolant the programs switch on after the spindle starts: `off` (default: dry, or an
    /// air blast the machine runs by itself), `mist` (M7) or `flood` (M8). A job's
    /// `output.coolant` overrides it.
    #[serde(default)]
    #[sqlx(try_from = "String")]
    pub coolant: Coolant,
    #[serde(default = "Source::user")]
    pub source: Source,
    #[serde(default)]
    pub reference: String,
}

impl MachineData {
    fn limits(&self) -> [(&'static str, f64); 9] {
        [
            ("rapid_mm_min", self.rapid_mm_min),
            ("max_feed_mm_min", self.max_feed_mm_min),
            ("max_spindle_rpm", self.max_spindle_rpm),
            ("accel_x_mm_s2", self.accel_x_mm_s2),
            ("accel_y_mm_s2", self.accel_y_mm_s2),
            ("accel_z_mm_s2", self.accel_z_mm_s2),
            ("jerk_x_mm_s3", self.jerk_x_mm_s3),
            ("jerk_y_mm_s3", self.jerk_y_mm_s3),
            ("jerk_z_mm_s3", self.jerk_z_mm_s3),
        ]
    }
}

impl Resource for MachineData {
    const TABLE: &'static str = "machines";
    const SINGULAR: &'static str = "machine";
    const COLUMNS: &'static [&'static str] = &[
        "name",
        "rapid_mm_min",
        "max_feed_mm_min",
        "max_spindle_rpm",
        "accel_x_mm_s2",
        "accel_y_mm_s2",
        "accel_z_mm_s2",
        "jerk_x_mm_s3",
        "jerk_y_mm_s3",
        "jerk_z_mm_s3",
        "tool_change_s",
        "coolant",
        "source",
        "reference",
    ];

    fn values(&self) -> Vec<SqlValue> {
        let mut values = vec![self.name.clone().into()];
        values.extend(self.limits().iter().map(|(_, v)| SqlValue::Real(*v)));
        values.extend([
            self.tool_change_s.into(),
            self.coolant.as_str().into(),
            self.source.as_str().into(),
            self.reference.clone().into(),
        ]);
        values
    }

    fn validate(&self, v: &mut Validator) {
        v.not_blank("name", &self.name);
        for (field, value) in self.limits() {
            v.within(field, value, LIMIT_RANGE.0, LIMIT_RANGE.1);
        }
        v.within("tool_change_s", self.tool_change_s, 0.0, MAX_TOOL_CHANGE_S);
    }
}

crate::record!(
    /// A machine tool.
    Machine,
    MachineData
);

crate::crud_api!(
    module: api,
    record: Machine,
    data: MachineData,
    filter: NameFilter,
    collection: "/v1/machines",
    item: "/v1/machines/{id}",
    tag: "database",
    ids: ["listMachines", "getMachine", "createMachine", "replaceMachine", "updateMachine", "deleteMachine"],
);
