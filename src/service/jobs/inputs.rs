//! Request parts shared by the planning jobs: the stock of a layer and pocket contours,
//! turned into the core's stock regions with field-named errors (the NC program is in
//! `program_input.rs`).

use crate::core::analysis::StockRegion;
use crate::core::geometry::{loops_from_dxf, pocket_from_loops, Loop, Pocket, Vertex};
use crate::core::stock::Rect;
use crate::service::error::{ApiError, FieldError};
use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

/// An axis-aligned stock box, mm.
#[derive(Debug, Clone, Copy, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct BoxInput {
    pub x_min: f64,
    pub y_min: f64,
    pub z_min: f64,
    pub x_max: f64,
    pub y_max: f64,
    pub z_max: f64,
}

/// A pocket contour: the outer loop and islands, each a list of `[x, y]` or
/// `[x, y, bulge]` vertices (bulge of the segment to the next vertex, as in DXF).
#[derive(Debug, Clone, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct ContourInput {
    pub outer: Vec<Vec<f64>>,
    #[serde(default)]
    pub islands: Vec<Vec<Vec<f64>>>,
}

/// A region already open before the layer is cut: a circle or a closed contour.
#[derive(Debug, Clone, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct OpenRegionInput {
    /// `{"cx", "cy", "r"}`.
    pub circle: Option<CircleInput>,
    /// A closed loop of `[x, y]` or `[x, y, bulge]` vertices.
    pub contour: Option<Vec<Vec<f64>>>,
}

#[derive(Debug, Clone, Copy, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct CircleInput {
    pub cx: f64,
    pub cy: f64,
    pub r: f64,
}

/// The stock of the layer: a box, a pocket contour, or DXF text (exactly one), the
/// layer's z range, and regions already open.
#[derive(Debug, Clone, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct StockInput {
    #[serde(rename = "box")]
    pub stock_box: Option<BoxInput>,
    pub contour: Option<ContourInput>,
    /// DXF text (LINE, ARC, CIRCLE, LWPOLYLINE): the outermost loop is the pocket, loops
    /// inside it are islands.
    pub dxf: Option<String>,
    /// Top of the layer, mm (default: the box's z_max; required otherwise).
    pub z_top: Option<f64>,
    /// Bottom of the layer, mm (default: the box's z_min; required otherwise).
    pub z_bottom: Option<f64>,
    #[serde(default)]
    pub open: Vec<OpenRegionInput>,
}

/// The core's view of the stock.
pub struct Stock {
    pub regions: Vec<StockRegion>,
    pub open: Vec<StockRegion>,
    pub z_top: f64,
    pub z_bottom: f64,
}

/// A loop of `[x, y]` or `[x, y, bulge]` vertices; errors name `field[i]`.
pub(crate) fn vertices(field: &str, raw: &[Vec<f64>]) -> Result<Loop, ApiError> {
    let vertices = raw
        .iter()
        .enumerate()
        .map(|(i, v)| match v.as_slice() {
            [x, y] => Ok(Vertex { x: *x, y: *y, bulge: 0.0 }),
            [x, y, b] => Ok(Vertex { x: *x, y: *y, bulge: *b }),
            _ => Err(ApiError::field(format!("{field}[{i}]"), "a vertex is [x, y] or [x, y, bulge]")),
        })
        .collect::<Result<Vec<_>, _>>()?;
    Ok(Loop::new(vertices))
}

/// Prefixes a core error's field with `prefix`.
pub(crate) fn under(prefix: &str, err: crate::core::CoreError) -> ApiError {
    match ApiError::from(err) {
        ApiError::Validation(errors) => ApiError::Validation(
            errors
                .into_iter()
                .map(|e| FieldError { field: format!("{prefix}.{}", e.field), reason: e.reason })
                .collect(),
        ),
        other => other,
    }
}

/// A pocket from a contour; errors name `{field}.outer[i]`, `{field}.islands[k][i]`, or the
/// loop and its problem under `field`.
pub(crate) fn read_contour(field: &str, c: &ContourInput) -> Result<Pocket, ApiError> {
    let outer = vertices(&format!("{field}.outer"), &c.outer)?;
    let islands = c
        .islands
        .iter()
        .enumerate()
        .map(|(i, island)| vertices(&format!("{field}.islands[{i}]"), island))
        .collect::<Result<Vec<_>, _>>()?;
    Pocket::new(outer, islands).map_err(|e| under(field, e))
}

/// A pocket from DXF text sent as `dxf` (under `parent`, if any): the outermost loop, the
/// loops inside it islands. Errors name `{parent.}dxf…`.
pub(crate) fn read_dxf(parent: Option<&str>, text: &str) -> Result<Pocket, ApiError> {
    let field = parent.map_or_else(|| "dxf".to_string(), |p| format!("{p}.dxf"));
    // The reader's errors already name `dxf`.
    let loops = loops_from_dxf(text).map_err(|e| match parent {
        Some(p) => under(p, e),
        None => ApiError::from(e),
    })?;
    pocket_from_loops(loops).map_err(|e| under(&field, e))
}

fn finite(field: &str, values: &[f64]) -> Result<(), ApiError> {
    if values.iter().all(|v| v.is_finite()) {
        Ok(())
    } else {
        Err(ApiError::field(field, "every value must be a finite number"))
    }
}

/// Checks the stock and turns it into regions.
pub fn read_stock(input: &StockInput) -> Result<Stock, ApiError> {
    let (regions, default_z) = match (&input.stock_box, &input.contour, &input.dxf) {
        (Some(b), None, None) => {
            finite("stock.box", &[b.x_min, b.y_min, b.z_min, b.x_max, b.y_max, b.z_max])?;
            if !(b.x_max > b.x_min && b.y_max > b.y_min && b.z_max > b.z_min) {
                return Err(ApiError::field("stock.box", "every max must be above its min"));
            }
            let rect = Rect { x_min: b.x_min, y_min: b.y_min, x_max: b.x_max, y_max: b.y_max };
            (vec![StockRegion::Rect(rect)], Some((b.z_max, b.z_min)))
        }
        (None, Some(c), None) => (vec![StockRegion::Pocket(read_contour("stock.contour", c)?)], None),
        (None, None, Some(text)) => (vec![StockRegion::Pocket(read_dxf(Some("stock"), text)?)], None),
        _ => return Err(ApiError::field("stock", "give exactly one of box, contour and dxf")),
    };
    let z_top = input
        .z_top
        .or(default_z.map(|z| z.0))
        .ok_or_else(|| ApiError::field("stock.z_top", "required for a contour"))?;
    let z_bottom = input
        .z_bottom
        .or(default_z.map(|z| z.1))
        .ok_or_else(|| ApiError::field("stock.z_bottom", "required for a contour"))?;
    finite("stock.z_top", &[z_top])?;
    finite("stock.z_bottom", &[z_bottom])?;
    if z_top <= z_bottom {
        return Err(ApiError::field("stock.z_top", "must be above z_bottom"));
    }
    let open = input
        .open
        .iter()
        .enumerate()
        .map(|(i, o)| {
            let field = format!("stock.open[{i}]");
            match (&o.circle, &o.contour) {
                (Some(c), None) => {
                    finite(&field, &[c.cx, c.cy, c.r])?;
                    if c.r <= 0.0 {
                        return Err(ApiError::field(format!("{field}.circle.r"), "must be > 0"));
                    }
                    Ok(StockRegion::Circle { cx: c.cx, cy: c.cy, r: c.r })
                }
                (None, Some(raw)) => {
                    let lp = vertices(&format!("{field}.contour"), raw)?;
                    Pocket::new(lp, vec![]).map(StockRegion::Pocket).map_err(|e| under(&field, e))
                }
                _ => Err(ApiError::field(field, "give exactly one of circle and contour")),
            }
        })
        .collect::<Result<Vec<_>, _>>()?;
    Ok(Stock { regions, open, z_top, z_bottom })
}
