//! Response-surface force models: `/v1/force-models`.

use super::{Reference, Resource, Source, SqlValue, ToolMaterialFilter};
use crate::core::force_model::{Coefficients, ForceModel};
use crate::service::error::Validator;
use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

/// The range of the coding centres and steps of chip thickness, µm (assumed: 1 nm to 1 cm).
const CHIP_THICKNESS_RANGE_UM: (f64, f64) = (1e-3, 1e4);
/// The range of the coding centres and steps of contact length, and of the reference
/// axial depth, mm (assumed: 0.1 µm to 1 m).
const LENGTH_RANGE_MM: (f64, f64) = (1e-4, 1e3);
/// The largest magnitude of a coefficient, N (assumed: a thousand times the papers').
const MAX_COEFFICIENT_N: f64 = 1e6;

/// A second-order response-surface model of the XY cutting force (seed 002 Eq. 1) in
/// coded variables `X1 = (t_m − t0)/δt`, `X2 = (L − L0)/δL`.
#[derive(Debug, Clone, Serialize, Deserialize, sqlx::FromRow, ToSchema)]
#[serde(deny_unknown_fields)]
#[schema(example = json!({"tool_id": 7, "material_id": 1, "t0_um": 43.589, "dt_um": 15.0, "l0_mm": 2.2551, "dl_mm": 0.436, "b0": 269.1, "b1": 65.84, "b2": 53.66, "b11": 0.0, "b22": 3.763, "b12": 15.45, "r_squared": 0.9998, "ad_ref_mm": 10.0}))]
pub struct ForceModelData {
    pub tool_id: i64,
    pub material_id: i64,
    /// Centre of the chip-thickness variable, µm.
    #[schema(minimum = 0.001, maximum = 10000)]
    pub t0_um: f64,
    /// Step of the chip-thickness variable, µm.
    #[schema(minimum = 0.001, maximum = 10000)]
    pub dt_um: f64,
    /// Centre of the arc-length variable, mm.
    #[schema(minimum = 0.0001, maximum = 1000)]
    pub l0_mm: f64,
    /// Step of the arc-length variable, mm.
    #[schema(minimum = 0.0001, maximum = 1000)]
    pub dl_mm: f64,
    #[schema(minimum = -1000000, maximum = 1000000)]
    pub b0: f64,
    #[schema(minimum = -1000000, maximum = 1000000)]
    pub b1: f64,
    #[schema(minimum = -1000000, maximum = 1000000)]
    pub b2: f64,
    #[serde(default)]
    #[schema(minimum = -1000000, maximum = 1000000)]
    pub b11: f64,
    #[schema(minimum = -1000000, maximum = 1000000)]
    pub b22: f64,
    #[schema(minimum = -1000000, maximum = 1000000)]
    pub b12: f64,
    /// Coefficient of determination of the fit.
    #[serde(default)]
    #[schema(maximum = 1)]
    pub r_squared: Option<f64>,
    /// Axial depth of cut of the experiments, mm: forces scale with the tool's engaged
    /// cutting-edge length at Ad over that at Ad_ref: Ad / Ad_ref for a square end mill, the
    /// corner arc and then the flank for radius and ball end mills (whose corner radius the
    /// tool row gives).
    #[schema(minimum = 0.0001, maximum = 1000)]
    pub ad_ref_mm: f64,
    #[serde(default = "Source::user")]
    pub source: Source,
    #[serde(default)]
    pub reference: String,
}

impl ForceModelData {
    /// The model for a tool whose cutting edge has corner radius `corner_radius_mm` (the
    /// tool's): its forces scale with that edge's engaged length at the axial depth.
    pub fn model(&self, corner_radius_mm: f64) -> ForceModel {
        ForceModel {
            t0_um: self.t0_um,
            dt_um: self.dt_um,
            l0_mm: self.l0_mm,
            dl_mm: self.dl_mm,
            coefficients: Coefficients {
                b0: self.b0,
                b1: self.b1,
                b2: self.b2,
                b11: self.b11,
                b22: self.b22,
                b12: self.b12,
            },
            ad_ref_mm: self.ad_ref_mm,
            corner_radius_mm,
        }
    }
}

impl Resource for ForceModelData {
    const TABLE: &'static str = "force_models";
    const SINGULAR: &'static str = "force model";
    const COLUMNS: &'static [&'static str] = &[
        "tool_id",
        "material_id",
        "t0_um",
        "dt_um",
        "l0_mm",
        "dl_mm",
        "b0",
        "b1",
        "b2",
        "b11",
        "b22",
        "b12",
        "r_squared",
        "ad_ref_mm",
        "source",
        "reference",
    ];

    fn values(&self) -> Vec<SqlValue> {
        vec![
            self.tool_id.into(),
            self.material_id.into(),
            self.t0_um.into(),
            self.dt_um.into(),
            self.l0_mm.into(),
            self.dl_mm.into(),
            self.b0.into(),
            self.b1.into(),
            self.b2.into(),
            self.b11.into(),
            self.b22.into(),
            self.b12.into(),
            self.r_squared.into(),
            self.ad_ref_mm.into(),
            self.source.as_str().into(),
            self.reference.clone().into(),
        ]
    }

    fn validate(&self, v: &mut Validator) {
        let (t, l) = (CHIP_THICKNESS_RANGE_UM, LENGTH_RANGE_MM);
        v.within("t0_um", self.t0_um, t.0, t.1);
        v.within("dt_um", self.dt_um, t.0, t.1);
        for (field, value) in [("l0_mm", self.l0_mm), ("dl_mm", self.dl_mm), ("ad_ref_mm", self.ad_ref_mm)] {
            v.within(field, value, l.0, l.1);
        }
        for (field, value) in
            [("b0", self.b0), ("b1", self.b1), ("b2", self.b2), ("b11", self.b11), ("b22", self.b22), ("b12", self.b12)]
        {
            v.within(field, value, -MAX_COEFFICIENT_N, MAX_COEFFICIENT_N);
        }
        if let Some(r2) = self.r_squared {
            v.within("r_squared", r2, f64::NEG_INFINITY, 1.0);
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
    /// A force model. The newest model of a tool and material is the one in use.
    ForceModelRecord,
    ForceModelData
);

crate::crud_api!(
    module: api,
    record: ForceModelRecord,
    data: ForceModelData,
    filter: ToolMaterialFilter,
    collection: "/v1/force-models",
    item: "/v1/force-models/{id}",
    tag: "database",
    ids: ["listForceModels", "getForceModel", "createForceModel", "replaceForceModel", "updateForceModel", "deleteForceModel"],
);
