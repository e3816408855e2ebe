//! Workpiece materials: `/v1/materials`.

use super::{NameFilter, Resource, Source, SqlValue};
use crate::service::error::Validator;
use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

/// Hardness range accepted, HRC.
const HRC_RANGE: (f64, f64) = (0.0, 80.0);

/// A workpiece material's data.
#[derive(Debug, Clone, Serialize, Deserialize, sqlx::FromRow, ToSchema)]
#[serde(deny_unknown_fields)]
#[schema(example = json!({"name": "NAK80", "designation": "Daido NAK80", "hardness_hrc": 40.0, "description": "pre-hardened mould steel"}))]
pub struct MaterialData {
    /// Unique short name, e.g. SKD61.
    #[schema(min_length = 1, pattern = r"\S")]
    pub name: String,
    /// Standard designation, e.g. JIS G 4404 SKD61.
    #[serde(default)]
    pub designation: String,
    /// Hardness, HRC.
    #[serde(default)]
    #[schema(minimum = 0, maximum = 80)]
    pub hardness_hrc: Option<f64>,
    #[serde(default)]
    pub description: String,
    #[serde(default = "Source::user")]
    pub source: Source,
    #[serde(default)]
    pub reference: String,
}

impl Resource for MaterialData {
    const TABLE: &'static str = "materials";
    const SINGULAR: &'static str = "material";
    const COLUMNS: &'static [&'static str] =
        &["name", "designation", "hardness_hrc", "description", "source", "reference"];
    const REFERENCED_BY: &'static [(&'static str, &'static str, &'static str)] = &[
        ("standard_conditions", "material_id", "standard conditions"),
        ("force_models", "material_id", "force models"),
        ("tool_life", "material_id", "tool-life rows"),
    ];

    fn values(&self) -> Vec<SqlValue> {
        vec![
            self.name.clone().into(),
            self.designation.clone().into(),
            self.hardness_hrc.into(),
            self.description.clone().into(),
            self.source.as_str().into(),
            self.reference.clone().into(),
        ]
    }

    fn validate(&self, v: &mut Validator) {
        v.not_blank("name", &self.name);
        if let Some(h) = self.hardness_hrc {
            v.within("hardness_hrc", h, HRC_RANGE.0, HRC_RANGE.1);
        }
    }
}

crate::record!(
    /// A workpiece material.
    Material,
    MaterialData
);

crate::crud_api!(
    module: api,
    record: Material,
    data: MaterialData,
    filter: NameFilter,
    collection: "/v1/materials",
    item: "/v1/materials/{id}",
    tag: "database",
    ids: ["listMaterials", "getMaterial", "createMaterial", "replaceMaterial", "updateMaterial", "deleteMaterial"],
);
