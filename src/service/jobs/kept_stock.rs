//! The stock a finished job's simulation left, kept compressed in `job_stocks`
//! (migration 0017), and read back for a job that starts from it
//! (`"stock": {"from_job": "<id>"}`, issue 32 item 3).
//!
//! **Format 2** (the `format` column), written by this version: a zlib stream of,
//! little-endian: the grid's origin x and y and its cell (3 × f64, mm), its columns and
//! rows (2 × u32), whether the stock was a pocket's (u8, 0 or 1), the number of slices and
//! of rasters (2 × u32); then per slice, top first, its z_top and z_bottom (2 × f64, mm)
//! and the index of its raster (u32); then each raster's cells, row by row from the bottom
//! (columns × rows i8 each); then what lies under the layer (see
//! [`crate::core::analysis::kept`]): a u8, 0 when it is not known, else 1 for a floor at a
//! z or 2 for one without end, the floor's z (f64, mm; 0 without end) and the footprint's
//! cells (columns × rows i8). Slices still alike at the end of the simulation share one
//! raster, stored once.
//!
//! **Format 1**, written before, is format 2 without what lies under the layer: it is
//! still read, as a stock under which nothing is known. A stock of another format is
//! refused (a 422 naming `stock.from_job`), never guessed at.

use super::model::{JobId, JobStatus};
use super::store;
use crate::core::analysis::kept::{deepest_feed_mm, layer_bottom, Below, Floor, KeptSlice, KeptStock};
use crate::core::stock::{Grid, Rect};
use crate::service::auth::Caller;
use crate::service::error::ApiError;
use crate::service::jobs::kind::Submission;
use crate::service::store::Pool;
use base64::Engine;

/// zlib's fastest level: the rasters are long runs of a few values. On tiger.nc's 37.9 MB of
/// cells it stores 683 kB (the default level: 434 kB), and the analysis with its encoding took
/// 2.06–2.25 s where the default level's took 2.83–2.98 s and the analysis before stocks were
/// kept 2.17–2.68 s (`cargo bench --bench plans -- tiger`, the three binaries in turn).
const KEPT_STOCK_COMPRESSION: flate2::Compression = flate2::Compression::fast();
use flate2::read::ZlibDecoder;
use flate2::write::ZlibEncoder;
use serde::{Deserialize, Serialize};
use std::io::{Read, Write};

/// The format this version writes (it reads [`FORMAT_1`] too).
pub const FORMAT: i64 = 2;
/// The format of stocks kept before what lies under the layer was: read still.
pub const FORMAT_1: i64 = 1;
/// What lies under the layer, in format 2: not known, a floor at a z, or one without end.
const BELOW_UNKNOWN: u8 = 0;
const BELOW_AT: u8 = 1;
const BELOW_UNBOUNDED: u8 = 2;
/// Most slices a kept stock may have (above what an analysis makes,
/// [`crate::core::analysis::budget::MOST_SLICES`] and the kept stock's bottom).
const MAX_KEPT_SLICES: usize = 4096;
/// The field the faults of a `from_job` name.
pub const FIELD: &str = "stock.from_job";

/// A kept stock, encoded and compressed: what is stored.
pub struct EncodedStock {
    pub format: i64,
    /// Size before compression, bytes.
    pub raw_bytes: usize,
    pub body: Vec<u8>,
}

/// Encodes and compresses `kept` in [`FORMAT`].
pub fn encode(kept: &KeptStock) -> EncodedStock {
    let below = kept.below.as_ref().map_or(0, |b| b.footprint.len());
    let cells: usize = kept.rasters.iter().map(Vec::len).sum::<usize>() + below;
    let mut raw = Vec::with_capacity(64 + 20 * kept.slices.len() + cells);
    let g = kept.grid;
    for v in [g.x0_mm, g.y0_mm, g.cell_mm] {
        raw.extend_from_slice(&v.to_le_bytes());
    }
    for n in [g.nx, g.ny] {
        raw.extend_from_slice(&(n as u32).to_le_bytes());
    }
    raw.push(u8::from(kept.cavity));
    for n in [kept.slices.len(), kept.rasters.len()] {
        raw.extend_from_slice(&(n as u32).to_le_bytes());
    }
    for s in &kept.slices {
        raw.extend_from_slice(&s.z_top.to_le_bytes());
        raw.extend_from_slice(&s.z_bottom.to_le_bytes());
        raw.extend_from_slice(&(s.raster as u32).to_le_bytes());
    }
    for r in &kept.rasters {
        raw.extend(r.iter().map(|&v| v as u8));
    }
    match &kept.below {
        None => raw.push(BELOW_UNKNOWN),
        Some(below) => {
            let (tag, z) = match below.floor {
                Floor::At(z) => (BELOW_AT, z),
                Floor::Unbounded => (BELOW_UNBOUNDED, 0.0),
            };
            raw.push(tag);
            raw.extend_from_slice(&z.to_le_bytes());
            raw.extend(below.footprint.iter().map(|&v| v as u8));
        }
    }
    let mut z = ZlibEncoder::new(Vec::new(), KEPT_STOCK_COMPRESSION);
    // Writing to a Vec cannot fail.
    let body = z.write_all(&raw).and_then(|()| z.finish()).unwrap_or_default();
    EncodedStock { format: FORMAT, raw_bytes: raw.len(), body }
}

/// Reads the fields of an encoded stock in order.
struct Reader<'a>(&'a [u8]);

impl Reader<'_> {
    fn take<const N: usize>(&mut self) -> Result<[u8; N], String> {
        let (head, rest) = self.0.split_first_chunk::<N>().ok_or("the stock ends early")?;
        self.0 = rest;
        Ok(*head)
    }
    fn f64(&mut self) -> Result<f64, String> {
        self.take::<8>().map(f64::from_le_bytes)
    }
    fn u32(&mut self) -> Result<usize, String> {
        self.take::<4>().map(|b| u32::from_le_bytes(b) as usize)
    }
}

/// Decodes a stored stock of `format` (2, or 1: nothing known under the layer) for a
/// service whose analyses may take `stock_memory_bytes`; `Err` says why it cannot be read.
pub fn decode(format: i64, body: &[u8], stock_memory_bytes: usize) -> Result<KeptStock, String> {
    if format != FORMAT && format != FORMAT_1 {
        return Err(format!(
            "it is stored in format {format}, and this version of dieplan reads formats {FORMAT_1} and {FORMAT}"
        ));
    }
    // Never more than the largest stock an analysis within the budget makes (its slices'
    // headers, and a footprint as large as its rasters, which take at least a byte a cell).
    let limit = 2 * stock_memory_bytes as u64 + 64 + 20 * MAX_KEPT_SLICES as u64;
    let mut raw = Vec::new();
    ZlibDecoder::new(body).take(limit + 1).read_to_end(&mut raw).map_err(|e| format!("it is not readable: {e}"))?;
    if raw.len() as u64 > limit {
        return Err("it is larger than the stock memory budget of this service lets a job keep".to_string());
    }
    let mut r = Reader(&raw);
    let (x0_mm, y0_mm, cell_mm) = (r.f64()?, r.f64()?, r.f64()?);
    let (nx, ny) = (r.u32()?, r.u32()?);
    let cavity = match r.take::<1>()? {
        [0] => false,
        [1] => true,
        _ => return Err("its pocket flag is neither 0 nor 1".to_string()),
    };
    let (n_slices, n_rasters) = (r.u32()?, r.u32()?);
    if n_slices > MAX_KEPT_SLICES || n_rasters > n_slices {
        return Err(format!("{n_slices} slices and {n_rasters} rasters"));
    }
    let slices = (0..n_slices)
        .map(|_| Ok(KeptSlice { z_top: r.f64()?, z_bottom: r.f64()?, raster: r.u32()? }))
        .collect::<Result<Vec<_>, String>>()?;
    let grid = Grid { x0_mm, y0_mm, cell_mm, nx, ny };
    let cells = grid.cells();
    let raster_bytes = cells.checked_mul(n_rasters).filter(|&n| n <= r.0.len());
    let Some(raster_bytes) = raster_bytes else {
        return Err(format!("its cells are not {n_rasters} rasters of {nx} × {ny}"));
    };
    let (raster_cells, rest) = r.0.split_at(raster_bytes);
    let rasters = raster_cells.chunks_exact(cells.max(1)).map(signed).collect();
    let mut r = Reader(rest);
    let below = match format {
        FORMAT_1 => None,
        _ => read_below(&mut r, cells)?,
    };
    if !r.0.is_empty() {
        return Err(format!("{} bytes follow its cells", r.0.len()));
    }
    let kept = KeptStock { grid, slices, rasters, cavity, below };
    kept.validate()?;
    // Every raster must rebuild (finite grid, values within the clamp).
    for cells in kept.rasters.iter().chain(kept.below.as_ref().map(|b| &b.footprint)) {
        crate::core::stock::Raster::from_cells(grid, cells.clone())?;
    }
    Ok(kept)
}

/// Cells as stored, back to their signed values.
fn signed(cells: &[u8]) -> Vec<i8> {
    cells.iter().map(|&v| v as i8).collect()
}

/// What lies under the layer, in format 2 (see the module's doc).
fn read_below(r: &mut Reader<'_>, cells: usize) -> Result<Option<Below>, String> {
    let [tag] = r.take::<1>()?;
    let floor = match tag {
        BELOW_UNKNOWN => return Ok(None),
        BELOW_AT => Floor::At(r.f64()?),
        BELOW_UNBOUNDED => {
            r.f64()?;
            Floor::Unbounded
        }
        _ => return Err(format!("what lies under it is marked {tag}, neither 0, 1 nor 2")),
    };
    if r.0.len() < cells {
        return Err("its footprint ends early".to_string());
    }
    let (footprint, rest) = r.0.split_at(cells);
    r.0 = rest;
    Ok(Some(Below { footprint: signed(footprint), floor }))
}

/// Stores the stock job `id` left (in a transaction of the caller's).
pub async fn store(conn: &mut crate::service::store::Conn, id: &str, stock: &EncodedStock) -> Result<(), sqlx::Error> {
    sqlx::query(
        "INSERT INTO job_stocks (job_id, format, raw_bytes, body) VALUES ($1, $2, $3, $4)
         ON CONFLICT (job_id) DO UPDATE SET format = excluded.format, raw_bytes = excluded.raw_bytes, body = excluded.body",
    )
    .bind(id)
    .bind(stock.format)
    .bind(i64::try_from(stock.raw_bytes).unwrap_or(i64::MAX))
    .bind(&stock.body)
    .execute(conn)
    .await?;
    Ok(())
}

/// The stock job `id` keeps as stored (its format and compressed body), if it keeps one.
pub async fn stored(pool: &Pool, id: &str) -> Result<Option<(i64, Vec<u8>)>, sqlx::Error> {
    sqlx::query_as("SELECT format, body FROM job_stocks WHERE job_id = $1").bind(id).fetch_optional(pool).await
}

/// The stock a job starts from, as its submission resolved it: the job it came from, the
/// layer and grid it covers, and the stored stock (read again when the job runs, so the
/// job does not depend on the other job being kept).
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct CarriedStock {
    pub from_job: String,
    pub z_top: f64,
    pub z_bottom: f64,
    pub cell_mm: f64,
    /// The grid's extent, mm.
    pub bounds: [f64; 4],
    pub format: i64,
    /// The stored body, base64.
    pub body: String,
    /// How deep the stock under the kept layer goes (null: not known; format 1).
    #[serde(default)]
    pub floor: Option<Floor>,
}

impl CarriedStock {
    /// The extent of the kept grid.
    pub fn rect(&self) -> Rect {
        let [x_min, y_min, x_max, y_max] = self.bounds;
        Rect { x_min, y_min, x_max, y_max }
    }

    /// Checks that what `path` cuts below the kept layer is known (see
    /// [`crate::core::analysis::kept::layer_bottom`]); the fault names `stock.from_job`.
    pub fn check_reach(&self, path: &crate::core::toolpath::Toolpath) -> Result<(), ApiError> {
        layer_bottom(self.z_bottom, self.floor, deepest_feed_mm(path))
            .map(|_| ())
            .map_err(|e| ApiError::field(FIELD, format!("the stock of job {}: {e}", self.from_job)))
    }

    /// The kept stock, decoded for analyses that may take `stock_memory_bytes`.
    pub fn decode(&self, stock_memory_bytes: usize) -> Result<KeptStock, ApiError> {
        let body = base64::engine::general_purpose::STANDARD
            .decode(&self.body)
            .map_err(|e| ApiError::field(FIELD, format!("the stock of job {} is unreadable: {e}", self.from_job)))?;
        decode(self.format, &body, stock_memory_bytes)
            .map_err(|e| ApiError::field(FIELD, format!("the stock of job {} cannot be used: {e}", self.from_job)))
    }
}

/// What a job the caller may see kept: its stored stock (format and body), or why it has
/// none. An unknown job (or another key's, to a planner) is [`ApiError::NotFound`].
pub async fn find(pool: &Pool, caller: &Caller, id: &JobId) -> Result<Result<(i64, Vec<u8>), String>, ApiError> {
    let row = store::get_visible(pool, caller, id).await?;
    if row.status()? != JobStatus::Succeeded {
        return Ok(Err(format!("job {id} is {}: a job's stock is kept when it has succeeded", row.status)));
    }
    Ok(stored(pool, id.as_str()).await?.ok_or_else(|| {
        format!(
            "job {id} ({}) kept no stock: analysis, costing, side-milling feeds, trochoids and plan jobs keep theirs",
            row.kind
        )
    }))
}

/// The stock job `id` left, for a job of the caller's to start from; faults name
/// `stock.from_job`: an unknown job (or another key's, to a planner), a job not succeeded,
/// a job that kept no stock, a stock this version cannot read.
pub async fn carried(submission: &Submission<'_>, id: &JobId) -> Result<CarriedStock, ApiError> {
    let found = find(submission.pool, submission.caller, id).await.map_err(|e| match e {
        ApiError::NotFound(_) => ApiError::field(FIELD, format!("no job with id {id}")),
        other => other,
    })?;
    let (format, body) = found.map_err(|reason| ApiError::field(FIELD, reason))?;
    let (from_job, budget) = (id.to_string(), submission.stock_memory_bytes);
    tokio::task::spawn_blocking(move || {
        let kept = decode(format, &body, budget)
            .map_err(|e| ApiError::field(FIELD, format!("the stock of job {from_job} cannot be used: {e}")))?;
        let g = kept.grid;
        let bounds = [g.x0_mm, g.y0_mm, g.x0_mm + g.nx as f64 * g.cell_mm, g.y0_mm + g.ny as f64 * g.cell_mm];
        Ok(CarriedStock {
            from_job,
            z_top: kept.z_top(),
            z_bottom: kept.z_bottom(),
            cell_mm: g.cell_mm,
            bounds,
            format,
            body: base64::engine::general_purpose::STANDARD.encode(&body),
            floor: kept.floor(),
        })
    })
    .await
    .map_err(|e| ApiError::Internal(format!("a blocking task failed: {e}")))?
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::core::analysis::DEFAULT_STOCK_MEMORY_BYTES;

    fn kept() -> KeptStock {
        let grid = Grid { x0_mm: -1.0, y0_mm: 2.0, cell_mm: 0.5, nx: 40, ny: 30 };
        let slice = |z_top: f64, z_bottom: f64, raster: usize| KeptSlice { z_top, z_bottom, raster };
        let raster = |v: i8| (0..grid.cells()).map(|k| if k % 7 == 0 { v } else { -v }).collect();
        KeptStock {
            grid,
            slices: vec![slice(0.0, -10.0, 0), slice(-10.0, -20.0, 1), slice(-20.0, -30.0, 1)],
            rasters: vec![raster(126), raster(3)],
            cavity: true,
            below: Some(Below { footprint: raster(5), floor: Floor::At(-35.0) }),
        }
    }

    /// `kept` as format 1 stored it: format 2 without what lies under the layer.
    fn format_1(kept: &KeptStock) -> Vec<u8> {
        let unknown = KeptStock { below: None, ..kept.clone() };
        let mut raw = Vec::new();
        ZlibDecoder::new(encode(&unknown).body.as_slice()).read_to_end(&mut raw).expect("inflates");
        assert_eq!(raw.pop(), Some(BELOW_UNKNOWN));
        let mut z = ZlibEncoder::new(Vec::new(), KEPT_STOCK_COMPRESSION);
        z.write_all(&raw).expect("deflates");
        z.finish().expect("deflates")
    }

    #[test]
    fn a_kept_stock_reads_back_as_it_was_and_shared_rasters_are_stored_once() {
        let encoded = encode(&kept());
        assert_eq!(encoded.format, 2);
        assert_eq!(encoded.raw_bytes, 24 + 8 + 1 + 8 + 3 * 20 + 2 * 40 * 30 + 1 + 8 + 40 * 30);
        assert!(encoded.body.len() < encoded.raw_bytes / 4, "{} bytes compressed", encoded.body.len());
        assert_eq!(decode(FORMAT, &encoded.body, DEFAULT_STOCK_MEMORY_BYTES), Ok(kept()));
        let unbounded = KeptStock { below: kept().below.map(|b| Below { floor: Floor::Unbounded, ..b }), ..kept() };
        assert_eq!(decode(FORMAT, &encode(&unbounded).body, DEFAULT_STOCK_MEMORY_BYTES), Ok(unbounded));
        let unknown = KeptStock { below: None, ..kept() };
        assert_eq!(decode(FORMAT, &encode(&unknown).body, DEFAULT_STOCK_MEMORY_BYTES), Ok(unknown));
    }

    #[test]
    fn a_stock_kept_in_format_1_reads_as_one_under_which_nothing_is_known() {
        let read = decode(FORMAT_1, &format_1(&kept()), DEFAULT_STOCK_MEMORY_BYTES).expect("format 1 is read");
        assert_eq!(read, KeptStock { below: None, ..kept() });
        // Format 1 read as format 2 lacks what lies under the layer.
        assert!(decode(FORMAT, &format_1(&kept()), DEFAULT_STOCK_MEMORY_BYTES).is_err());
    }

    #[test]
    fn a_stock_of_another_format_or_damaged_is_refused_saying_why() {
        let encoded = encode(&kept());
        assert!(decode(3, &encoded.body, DEFAULT_STOCK_MEMORY_BYTES).unwrap_err().contains("format 3"));
        assert!(decode(FORMAT, &encoded.body[..encoded.body.len() / 2], DEFAULT_STOCK_MEMORY_BYTES).is_err());
        assert!(decode(FORMAT, b"not a stock", DEFAULT_STOCK_MEMORY_BYTES).is_err());
        let mut bad = kept();
        bad.rasters[0][0] = i8::MIN;
        assert!(decode(FORMAT, &encode(&bad).body, DEFAULT_STOCK_MEMORY_BYTES).is_err());
        let mut bad_footprint = kept();
        if let Some(b) = &mut bad_footprint.below {
            b.footprint[3] = i8::MIN;
        }
        assert!(decode(FORMAT, &encode(&bad_footprint).body, DEFAULT_STOCK_MEMORY_BYTES).is_err());
        let mut floating = kept();
        floating.below = Some(Below { footprint: vec![0; 1200], floor: Floor::At(-10.0) });
        assert!(decode(FORMAT, &encode(&floating).body, DEFAULT_STOCK_MEMORY_BYTES).unwrap_err().contains("floor"));
    }
}
