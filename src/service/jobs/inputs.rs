//! Request parts shared by the planning jobs: the stock of a layer and pocket contours,
//! turned into the core's stock regions with field-named errors (the NC program is in
//! `program_input.rs`).

use crate::core::analysis::kept::Floor;
use crate::core::analysis::StockRegion;
use crate::core::geometry::{loops_from_dxf, pocket_from_loops, Loop, Pocket, Vertex};
use crate::core::stock::Rect;
use crate::service::error::{ApiError, FieldError, Validator};
use crate::service::jobs::kept_stock::{CarriedStock, FIELD};
use crate::service::jobs::model::JobId;
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
/// layer's z range, and regions already open; or the stock a finished job left
/// (`from_job`, alone).
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
    /// A finished job (analysis, costing, feeds in side milling, or trochoids: the stock
    /// its verified program leaves) whose simulated stock
    /// the layer starts from, given alone: the layer, its z range, its grid and the
    /// material left in each of its slices are that job's (the program's own z levels
    /// take, each, the material the kept stock has anywhere over their z range). Where the
    /// program cuts deeper, the layer reaches down to its deepest feed move into the
    /// stock as that job was given it: a box down to its `z_min`, a pocket's cavity on
    /// down in its outline (see the README, "Stock carried between programs"). A
    /// planner's key may name only its own jobs.
    pub from_job: Option<JobId>,
}

/// The fields a stock from a job (`from_job`) takes from that job, and may not be given.
const TAKEN_FROM_THE_JOB: [&str; 6] = ["box", "contour", "dxf", "z_top", "z_bottom", "open"];

impl StockInput {
    /// The fields given besides `from_job` that it takes from its job.
    fn given_with_from_job(&self) -> Vec<&'static str> {
        if self.from_job.is_none() {
            return vec![];
        }
        let given = [
            self.stock_box.is_some(),
            self.contour.is_some(),
            self.dxf.is_some(),
            self.z_top.is_some(),
            self.z_bottom.is_some(),
            !self.open.is_empty(),
        ];
        TAKEN_FROM_THE_JOB.iter().zip(given).filter(|(_, g)| *g).map(|(f, _)| *f).collect()
    }
}

impl StockInput {
    /// How deep the stock goes under the layer, for a job that starts from the stock this
    /// one leaves: a box is solid down to its `z_min`; a pocket's cavity (a contour or a
    /// DXF) runs on down in its outline. (A stock from a job passes on what lay under it.)
    pub fn floor(&self) -> Floor {
        match &self.stock_box {
            Some(b) => Floor::At(b.z_min),
            None => Floor::Unbounded,
        }
    }
}

/// Checks, without the database, that a stock from a job gives nothing its job decides:
/// each such field is refused, naming it (`stock.box`…).
pub fn check_from_job(stock: &StockInput, v: &mut Validator) {
    for field in stock.given_with_from_job() {
        let reason = "not with from_job: a layer that starts from a job's stock takes its shape, z range and open regions from that job";
        v.fail(format!("stock.{field}"), reason);
    }
}

/// The core's view of the stock.
pub struct Stock {
    pub regions: Vec<StockRegion>,
    pub open: Vec<StockRegion>,
    pub z_top: f64,
    pub z_bottom: f64,
    /// Starts from the stock a job left (then `regions` is its grid's extent).
    pub carried: bool,
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

/// Checks the stock and turns it into regions; a stock from a job (`from_job`) is the one
/// its submission resolved (`carried`).
pub fn read_stock(input: &StockInput, carried: Option<&CarriedStock>) -> Result<Stock, ApiError> {
    if input.from_job.is_some() {
        if let Some(field) = input.given_with_from_job().first() {
            return Err(ApiError::field(format!("stock.{field}"), "not with from_job"));
        }
        let carried = carried.ok_or_else(|| ApiError::field(FIELD, "the job's stock is not known"))?;
        let regions = vec![StockRegion::Rect(carried.rect())];
        return Ok(Stock { regions, open: vec![], z_top: carried.z_top, z_bottom: carried.z_bottom, carried: true });
    }
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
    Ok(Stock { regions, open, z_top, z_bottom, carried: false })
}
