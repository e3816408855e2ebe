//! DXF import: the closed contours of an ASCII DXF file's ENTITIES section.
//!
//! Read: LINE, ARC, CIRCLE, LWPOLYLINE (closed flag 70 bit 1, bulges 42) and old-style
//! POLYLINE/VERTEX/SEQEND (3-D polylines projected onto XY; meshes refused). Closed
//! entities are loops by themselves; open ones are chained end to end ([`super::chain`]).
//! Other entity types (TEXT, DIMENSION, INSERT, SPLINE, …) are ignored. Coordinates are
//! converted to mm by the header's `$INSUNITS` (mm when absent); arcs and polylines whose
//! extrusion is −Z are mirrored into the world frame.

use super::chain::{chain_pieces, Piece, Source};
use super::contour::{Loop, Vertex};
use super::dxf_groups::{entities_section, mm_per_unit, read_groups, split_entities, Entity, Group};
use super::point::Bounds;
use crate::core::error::CoreError;

/// Chaining tolerance relative to the drawing's size (the diagonal of its vertices' box).
pub const CHAIN_REL_TOL: f64 = 1e-6;

/// Smallest chaining tolerance (mm): ends closer than the larger of this and
/// `CHAIN_REL_TOL × drawing size` are one point.
pub const CHAIN_MIN_TOL_MM: f64 = 1e-6;

/// An angle within this of a multiple of 90° (deg) gets exact sine and cosine.
const RIGHT_ANGLE_EPS_DEG: f64 = 1e-12;

/// An ARC whose sweep is below this (deg) spans the full circle (start = end angle).
const FULL_CIRCLE_EPS_DEG: f64 = 1e-9;

/// A full turn (deg).
const FULL_TURN_DEG: f64 = 360.0;

/// A half turn (deg): longer ARCs get an extra vertex in their middle.
const HALF_TURN_DEG: f64 = 180.0;

/// A right angle (deg).
const RIGHT_ANGLE_DEG: f64 = 90.0;

/// LWPOLYLINE/POLYLINE flag (group 70): closed.
const FLAG_CLOSED: i64 = 1;

/// POLYLINE flag (group 70): 3-D polyline (world coordinates; read projected onto XY).
const FLAG_3D_POLYLINE: i64 = 8;

/// POLYLINE flags (group 70) of polygon meshes and polyface meshes.
const FLAGS_MESH: i64 = 16 | 64;

/// VERTEX flag (group 70): spline frame control point, not on the curve.
const VERTEX_SPLINE_FRAME: i64 = 16;

/// The closed loops drawn in a DXF file, in the order of their first entity.
///
/// Open LINE, ARC and polyline pieces are chained end to end (tolerance: the larger of
/// [`CHAIN_MIN_TOL_MM`] and [`CHAIN_REL_TOL`] × drawing size). Every loop is validated
/// ([`Loop::validate`]). Errors have field `dxf` and a reason naming the DXF line and
/// handle of the entity at fault.
pub fn loops_from_dxf(text: &str) -> Result<Vec<Loop>, CoreError> {
    let groups = read_groups(text)?;
    let entities = entities_section(&groups)?;
    let (mut closed, mut pieces) = read_entities(entities)?;
    let scale = mm_per_unit(&groups)?;
    for v in closed
        .iter_mut()
        .flat_map(|(_, l)| l.vertices.iter_mut())
        .chain(pieces.iter_mut().flat_map(|p| p.vertices.iter_mut()))
    {
        v.x *= scale;
        v.y *= scale;
    }
    let mut bounds = Bounds::EMPTY;
    for v in closed.iter().flat_map(|(_, l)| &l.vertices).chain(pieces.iter().flat_map(|p| &p.vertices)) {
        bounds.include(v.point());
    }
    let tol_mm = CHAIN_MIN_TOL_MM.max(CHAIN_REL_TOL * bounds.diagonal_mm());
    let mut loops = closed;
    loops.extend(chain_pieces(pieces, tol_mm)?);
    loops.sort_by_key(|(source, _)| source.line);
    loops
        .into_iter()
        .map(|(source, lp)| {
            let lp = without_duplicate_vertices(lp, tol_mm);
            lp.validate("loop").map_err(|e| match e {
                CoreError::InvalidInput { field, reason } => {
                    CoreError::invalid("dxf", format!("the loop starting with {source}: {field}: {reason}"))
                }
                other => other,
            })?;
            Ok(lp)
        })
        .collect()
}

/// Drops vertices within `tol_mm` of the previous one (the wrap-around included); the
/// kept vertex takes the bulge of the segment leaving the dropped one.
fn without_duplicate_vertices(lp: Loop, tol_mm: f64) -> Loop {
    let mut out: Vec<Vertex> = Vec::with_capacity(lp.vertices.len());
    for v in lp.vertices {
        match out.last_mut() {
            Some(prev) if prev.point().near(v.point(), tol_mm) => prev.bulge = v.bulge,
            _ => out.push(v),
        }
    }
    while out.len() > 2 && out[out.len() - 1].point().near(out[0].point(), tol_mm) {
        out.pop();
    }
    Loop::new(out)
}

type Shapes = (Vec<(Source, Loop)>, Vec<Piece>);

fn read_entities(groups: &[Group<'_>]) -> Result<Shapes, CoreError> {
    let entities = split_entities(groups);
    let mut closed = Vec::new();
    let mut pieces = Vec::new();
    let mut k = 0;
    while k < entities.len() {
        let e = &entities[k];
        k += 1;
        let mut shape = |vertices: Vec<Vertex>, is_closed: bool| {
            if is_closed {
                closed.push((e.source.clone(), Loop::new(vertices)));
            } else {
                pieces.push(Piece { vertices, source: e.source.clone() });
            }
        };
        match e.source.kind.as_str() {
            "LINE" => shape(
                vec![
                    Vertex::new(e.required(10)?, e.required(20)?, 0.0),
                    Vertex::new(e.required(11)?, e.required(21)?, 0.0),
                ],
                false,
            ),
            "ARC" | "CIRCLE" => {
                let (cx, cy, r) = (e.required(10)?, e.required(20)?, e.required(40)?);
                if r <= 0.0 {
                    return Err(e.error(format!("radius (group 40) must be > 0, got {r}")));
                }
                let (from, to) = if e.source.kind == "ARC" { (e.required(50)?, e.required(51)?) } else { (0.0, 0.0) };
                let (vertices, is_closed) = arc_vertices(cx, cy, r, from, to);
                shape(mirror(vertices, e.mirrored()?), is_closed);
            }
            "LWPOLYLINE" => {
                let mut vertices: Vec<Vertex> = Vec::new();
                for g in e.groups {
                    match g.code {
                        10 => vertices.push(Vertex::new(e.number_of(g)?, 0.0, 0.0)),
                        20 | 42 => {
                            let v = vertices.last_mut().ok_or_else(|| {
                                e.error(format!("line {}: group {} before the first vertex", g.line, g.code))
                            })?;
                            let value = e.number_of(g)?;
                            if g.code == 20 {
                                v.y = value
                            } else {
                                v.bulge = value
                            }
                        }
                        _ => {}
                    }
                }
                polyline_shape(e, vertices, e.flags()?, e.mirrored()?, &mut shape)?;
            }
            "POLYLINE" => {
                let flags = e.flags()?;
                if flags & FLAGS_MESH != 0 {
                    return Err(e.error(format!("flags {flags}: polygon and polyface meshes are not contours")));
                }
                let mirrored = flags & FLAG_3D_POLYLINE == 0 && e.mirrored()?;
                let mut vertices = Vec::new();
                while k < entities.len() && entities[k].source.kind == "VERTEX" {
                    let v = &entities[k];
                    k += 1;
                    if v.flags()? & VERTEX_SPLINE_FRAME == 0 {
                        vertices.push(Vertex::new(v.required(10)?, v.required(20)?, v.optional(42)?.unwrap_or(0.0)));
                    }
                }
                if k < entities.len() && entities[k].source.kind == "SEQEND" {
                    k += 1;
                }
                polyline_shape(e, vertices, flags, mirrored, &mut shape)?;
            }
            _ => {}
        }
    }
    Ok((closed, pieces))
}

fn polyline_shape(
    e: &Entity<'_, '_>,
    vertices: Vec<Vertex>,
    flags: i64,
    mirrored: bool,
    shape: &mut impl FnMut(Vec<Vertex>, bool),
) -> Result<(), CoreError> {
    if vertices.len() < 2 {
        return Err(e.error(format!("a polyline needs at least 2 vertices, got {}", vertices.len())));
    }
    shape(mirror(vertices, mirrored), flags & FLAG_CLOSED != 0);
    Ok(())
}

/// Maps OCS vertices of a −Z extrusion to world coordinates: x mirrored, bulges negated.
fn mirror(vertices: Vec<Vertex>, mirrored: bool) -> Vec<Vertex> {
    if !mirrored {
        return vertices;
    }
    vertices.into_iter().map(|v| Vertex::new(-v.x, v.y, -v.bulge)).collect()
}

/// Vertices of the counter-clockwise arc from `from_deg` to `to_deg` (DXF ARC), with a middle
/// vertex when it spans more than a half turn; a full circle is closed (second value `true`).
fn arc_vertices(cx: f64, cy: f64, r: f64, from_deg: f64, to_deg: f64) -> (Vec<Vertex>, bool) {
    let mut sweep = (to_deg - from_deg).rem_euclid(FULL_TURN_DEG);
    if sweep < FULL_CIRCLE_EPS_DEG {
        sweep = FULL_TURN_DEG;
    }
    let at = |deg: f64, bulge: f64| {
        let (c, s) = cos_sin_deg(deg);
        Vertex::new(cx + r * c, cy + r * s, bulge)
    };
    let closed = sweep > FULL_TURN_DEG - FULL_CIRCLE_EPS_DEG;
    if sweep > HALF_TURN_DEG {
        // A full circle is two exact half circles.
        let bulge = if closed { 1.0 } else { (sweep / 8.0).to_radians().tan() };
        let mut v = vec![at(from_deg, bulge), at(from_deg + sweep / 2.0, bulge)];
        if !closed {
            v.push(at(from_deg + sweep, 0.0));
        }
        (v, closed)
    } else {
        (vec![at(from_deg, (sweep / 4.0).to_radians().tan()), at(from_deg + sweep, 0.0)], false)
    }
}

/// Cosine and sine of an angle in degrees, exact at multiples of 90°.
fn cos_sin_deg(deg: f64) -> (f64, f64) {
    let quarter = (deg / RIGHT_ANGLE_DEG).round();
    if (deg - RIGHT_ANGLE_DEG * quarter).abs() < RIGHT_ANGLE_EPS_DEG {
        return match (quarter as i64).rem_euclid(4) {
            0 => (1.0, 0.0),
            1 => (0.0, 1.0),
            2 => (-1.0, 0.0),
            _ => (0.0, -1.0),
        };
    }
    let rad = deg.to_radians();
    (rad.cos(), rad.sin())
}

#[cfg(test)]
#[path = "dxf_tests.rs"]
mod tests;
