//! Tracing a tool path into a simplified [`ScenePath`]: arcs tessellated to a chord
//! tolerance, vertices assigned to layers, values attached per vertex, then a streaming
//! simplification that keeps the drawing within a tolerance and every value in its colour
//! bin.
//!
//! Path distance `s` is measured as the analysis measures it (`engine.rs` sums
//! `Sample::step_mm` from 0, `sampling::for_each_sample` visits every move, rapids
//! included, and a move's steps add up to `crate::core::toolpath::move_length`, its 3-D length, helices
//! included): the cumulative 3-D length over all moves of the path, starting at 0. So the
//! `s_mm` of `Series` or of the per-sample results can be passed as they are.
//!
//! The simplification is a sleeve (cone-intersection) test: from the last kept vertex
//! (the anchor), every skipped vertex farther than the tolerance narrows the wedge of
//! directions a chord may take so that it passes within the tolerance of it; a vertex is
//! skipped while its direction stays inside the wedge, it is the farthest from the anchor
//! so far, and every quantity stays in the same colour bin. One pass, O(1) per vertex,
//! no recursion.

use super::scene::{LayerInfo, Quantity, Run, ScenePath};
use crate::core::analysis::sampling::MovePoints;
use crate::core::toolpath::move_length;
use crate::core::toolpath::{Motion, Move, Plane, Toolpath, P3};
use std::collections::BTreeMap;
use std::f64::consts::PI;

/// Default tolerance as a fraction of the path's XY extent: 0.05 px of a 1000 px drawing
/// of the whole, so that a window zoomed in 10 times and more still shows the path
/// within half a pixel (a drawing leaves out what its pixels cannot show).
pub const DEFAULT_TOLERANCE_FRACTION: f64 = 1.0 / 20000.0;
/// Default number of colour bins per quantity.
pub const DEFAULT_VALUE_BINS: usize = 32;
/// Smallest tolerance, mm: a micrometre, below any machine's resolution (and the
/// smallest window a drawing shows).
pub const MIN_TOLERANCE_MM: f64 = 1e-3;
/// A vertex is in a layer when its z is within the layer's range widened by this, mm.
pub const LAYER_Z_TOLERANCE_MM: f64 = 1e-6;
/// Moves shorter than this draw nothing, mm.
const MIN_MOVE_MM: f64 = 1e-9;
/// Samples within this of a vertex's distance count as at it, mm.
const S_TOLERANCE_MM: f64 = 1e-6;
/// Upper bound of segments per arc (a huge helix with a tiny tolerance).
const MAX_ARC_SEGMENTS: usize = 1 << 20;
/// Number of quantities (slots of a value array).
const QUANTITIES: usize = Quantity::ALL.len();

/// Values of one quantity along a path.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum QuantityValues<'a> {
    /// One value per move, indexed like `path.moves` (missing entries count as `None`).
    PerMove(&'a [Option<f64>]),
    /// Values at path distances `s_mm` (ascending, see the module doc), e.g. the
    /// analysis's per-sample results.
    PerSample { s_mm: &'a [f64], v: &'a [Option<f64>] },
}

/// The values to attach to a traced path, per quantity.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct TraceValues<'a> {
    pub quantities: BTreeMap<Quantity, QuantityValues<'a>>,
}

impl<'a> TraceValues<'a> {
    pub fn new() -> TraceValues<'a> {
        TraceValues::default()
    }

    /// Adds one value per move for `quantity`.
    pub fn per_move(mut self, quantity: Quantity, values: &'a [Option<f64>]) -> TraceValues<'a> {
        self.quantities.insert(quantity, QuantityValues::PerMove(values));
        self
    }

    /// Adds per-sample values for `quantity` at path distances `s_mm` (ascending).
    pub fn per_sample(mut self, quantity: Quantity, s_mm: &'a [f64], v: &'a [Option<f64>]) -> TraceValues<'a> {
        self.quantities.insert(quantity, QuantityValues::PerSample { s_mm, v });
        self
    }
}

/// How a path is traced.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TraceOptions {
    /// Simplification (and arc chord) tolerance, mm; `None`: the path's XY extent ×
    /// [`DEFAULT_TOLERANCE_FRACTION`].
    pub tolerance_mm: Option<f64>,
    /// Colour bins per quantity over its min..max along the path; merged vertices stay in
    /// one bin.
    pub value_bins: usize,
}

impl Default for TraceOptions {
    fn default() -> TraceOptions {
        TraceOptions { tolerance_mm: None, value_bins: DEFAULT_VALUE_BINS }
    }
}

/// Traces `path` into a simplified [`ScenePath`] named `name`. See the module doc.
pub fn trace_path(
    name: &str,
    path: &Toolpath,
    values: &TraceValues,
    layers: &[LayerInfo],
    options: &TraceOptions,
) -> ScenePath {
    let tolerance = options
        .tolerance_mm
        .filter(|t| t.is_finite() && *t > 0.0)
        .unwrap_or_else(|| xy_extent(&path.moves) * DEFAULT_TOLERANCE_FRACTION)
        .max(MIN_TOLERANCE_MM);
    let slots: Vec<(usize, Quantity, QuantityValues)> =
        values.quantities.iter().map(|(&q, &v)| (slot(q), q, v)).collect();
    let bins = Bins::new(path, &slots, options.value_bins.max(1));
    let mut tracer = Tracer {
        runs: Vec::new(),
        current: None,
        cursors: [0; QUANTITIES],
        tolerance,
        bins,
        present: slots.iter().map(|s| s.1).collect(),
    };
    let mut s = 0.0;
    for (index, m) in path.moves.iter().enumerate() {
        let length = move_length(m);
        if length > MIN_MOVE_MM {
            tracer.trace_move(index, m, s, length, &slots, layers);
        }
        s += length;
    }
    tracer.finish_run();
    ScenePath { name: name.to_string(), runs: tracer.runs, detail_mm: Some(tolerance) }
}

/// The index of `q` in a value array.
fn slot(q: Quantity) -> usize {
    Quantity::ALL.iter().position(|&a| a == q).unwrap_or(0)
}

/// The larger of the XY bounding box's sides, over move ends and arc circles.
fn xy_extent(moves: &[Move]) -> f64 {
    let mut lo = [f64::INFINITY; 2];
    let mut hi = [f64::NEG_INFINITY; 2];
    let mut add = |x: f64, y: f64| {
        lo = [lo[0].min(x), lo[1].min(y)];
        hi = [hi[0].max(x), hi[1].max(y)];
    };
    for m in moves {
        add(m.start.x, m.start.y);
        add(m.end.x, m.end.y);
        if let Motion::Arc { center, .. } = m.motion {
            let r = (m.start.x - center.x).hypot(m.start.y - center.y);
            add(center.x - r, center.y - r);
            add(center.x + r, center.y + r);
        }
    }
    if lo[0].is_finite() {
        (hi[0] - lo[0]).max(hi[1] - lo[1])
    } else {
        0.0
    }
}

/// The layer containing `z` (the lowest index when several do).
pub fn layer_of(z: f64, layers: &[LayerInfo]) -> Option<usize> {
    layers.iter().position(|l| {
        let (lo, hi) = (l.z_bottom.min(l.z_top), l.z_bottom.max(l.z_top));
        z >= lo - LAYER_Z_TOLERANCE_MM && z <= hi + LAYER_Z_TOLERANCE_MM
    })
}

/// Per-vertex values, by quantity slot.
type Values = [Option<f64>; QUANTITIES];
/// Colour bins of the values, by quantity slot (`u32::MAX`: no value).
type BinKey = [u32; QUANTITIES];
const NO_BIN: u32 = u32::MAX;

/// The colour bins of each quantity over its range along the path (first pass).
struct Bins {
    ranges: [Option<(f64, f64)>; QUANTITIES],
    count: usize,
}

impl Bins {
    fn new(path: &Toolpath, slots: &[(usize, Quantity, QuantityValues)], count: usize) -> Bins {
        let mut ranges = [None; QUANTITIES];
        for &(slot, _, values) in slots {
            let feed_values: Box<dyn Iterator<Item = f64>> = match values {
                QuantityValues::PerMove(v) => Box::new(
                    v.iter()
                        .zip(&path.moves)
                        .filter(|(_, m)| !matches!(m.motion, Motion::Rapid))
                        .filter_map(|(v, _)| *v),
                ),
                QuantityValues::PerSample { v, .. } => Box::new(v.iter().filter_map(|v| *v)),
            };
            ranges[slot] = feed_values
                .filter(|v| v.is_finite())
                .fold(None, |r: Option<(f64, f64)>, v| Some(r.map_or((v, v), |(lo, hi)| (lo.min(v), hi.max(v)))));
        }
        Bins { ranges, count }
    }

    fn key(&self, values: &Values) -> BinKey {
        let mut key = [NO_BIN; QUANTITIES];
        for (k, (v, range)) in key.iter_mut().zip(values.iter().zip(&self.ranges)) {
            if let (Some(v), Some((lo, hi))) = (v, range) {
                let span = hi - lo;
                let f = if span > 0.0 { ((v - lo) / span).clamp(0.0, 1.0) } else { 0.0 };
                *k = ((f * self.count as f64) as u32).min(self.count as u32 - 1);
            }
        }
        key
    }
}

/// A vertex before simplification.
#[derive(Debug, Clone, Copy)]
struct Vertex {
    p: [f64; 2],
    /// Height, NC line and path distance of the vertex.
    at: At,
    values: Values,
    bins: BinKey,
}

/// Where a vertex is besides its XY: height (mm), NC line, path distance (mm).
#[derive(Debug, Clone, Copy)]
struct At {
    z: f64,
    line: u32,
    s_mm: f64,
}

/// The run being built and its simplification state.
struct OpenRun {
    layer: Option<usize>,
    rapid: bool,
    /// End of the last vertex fed in, 3-D (continuity check).
    end: P3,
    /// Kept vertices and their values.
    points: Vec<[f64; 2]>,
    values: Vec<Values>,
    at: Vec<At>,
    /// The last vertex fed in and not yet kept (the candidate end of the current chord).
    last: Option<Vertex>,
    /// Bins of the stretch since the anchor.
    stretch_bins: BinKey,
    /// Largest values of the stretch since the anchor (attached to the kept vertex).
    stretch_max: Values,
    /// Wedge of admissible chord directions, relative to `wedge_ref` (rad), if any
    /// skipped vertex constrains it.
    wedge: Option<(f64, f64)>,
    wedge_ref: f64,
    /// Distance from the anchor of the farthest skipped vertex.
    reach: f64,
}

struct Tracer {
    runs: Vec<Run>,
    current: Option<OpenRun>,
    /// Per quantity slot, the first sample not yet consumed.
    cursors: [usize; QUANTITIES],
    tolerance: f64,
    bins: Bins,
    present: Vec<Quantity>,
}

impl Tracer {
    fn trace_move(
        &mut self,
        index: usize,
        m: &Move,
        s_start: f64,
        length: f64,
        slots: &[(usize, Quantity, QuantityValues)],
        layers: &[LayerInfo],
    ) {
        let rapid = matches!(m.motion, Motion::Rapid);
        let segments = match m.motion {
            Motion::Rapid | Motion::Linear => 1,
            Motion::Arc { center, plane, .. } => arc_segments(m, center, plane, length, self.tolerance),
        };
        // Vertices at the arc's chords and at every sample inside the move, so that the
        // colour changes where the values do, not only at the move's ends.
        let mut ts: Vec<f64> = (1..=segments).map(|k| k as f64 / segments as f64).collect();
        if !rapid {
            for (_, _, qv) in slots {
                if let QuantityValues::PerSample { s_mm, .. } = qv {
                    let lo = s_mm.partition_point(|&x| x <= s_start + S_TOLERANCE_MM);
                    let hi = s_mm.partition_point(|&x| x < s_start + length - S_TOLERANCE_MM);
                    ts.extend(s_mm[lo..hi.max(lo)].iter().map(|&x| (x - s_start) / length));
                }
            }
            ts.sort_by(f64::total_cmp);
            ts.dedup_by(|a, b| (*a - *b).abs() * length <= S_TOLERANCE_MM);
        }
        let mut s_prev = s_start;
        let mut from = m.start;
        let points = MovePoints::of(m);
        for (k, &t) in ts.iter().enumerate() {
            let p = if k + 1 == ts.len() { m.end } else { points.at(t).0 };
            let s = s_start + length * t;
            let mut values = [None; QUANTITIES];
            for &(slot, _, ref qv) in slots {
                let v = self.value_at(slot, qv, index, s_prev, s);
                if !rapid {
                    values[slot] = v;
                }
            }
            let layer = if layers.is_empty() { None } else { layer_of(p.z, layers) };
            self.feed(from, p, layer, rapid, values, At { z: p.z, line: m.line, s_mm: s });
            from = p;
            s_prev = s;
        }
    }

    /// The value of a quantity for the stretch (s_prev, s] of move `index`.
    fn value_at(&mut self, slot: usize, values: &QuantityValues, index: usize, s_prev: f64, s: f64) -> Option<f64> {
        match *values {
            QuantityValues::PerMove(v) => v.get(index).copied().flatten().filter(|v| v.is_finite()),
            QuantityValues::PerSample { s_mm, v } => {
                let n = s_mm.len().min(v.len());
                let cursor = &mut self.cursors[slot];
                while *cursor < n && s_mm[*cursor] <= s_prev + S_TOLERANCE_MM {
                    *cursor += 1;
                }
                let first = *cursor;
                let mut max: Option<f64> = None;
                while *cursor < n && s_mm[*cursor] <= s + S_TOLERANCE_MM {
                    if let Some(x) = v[*cursor].filter(|x| x.is_finite()) {
                        max = Some(max.map_or(x, |m| m.max(x)));
                    }
                    *cursor += 1;
                }
                if *cursor > first {
                    return max;
                }
                // No sample inside: interpolate between the neighbours (or take the one
                // that has a value).
                let before = first.checked_sub(1).map(|i| (s_mm[i], v[i]));
                let after = (first < n).then(|| (s_mm[first], v[first]));
                match (before, after) {
                    (Some((s0, Some(v0))), Some((s1, Some(v1)))) if s1 - s0 > 0.0 => {
                        Some(v0 + (v1 - v0) * ((s - s0) / (s1 - s0)).clamp(0.0, 1.0))
                    }
                    (Some((s0, v0)), Some((s1, v1))) => {
                        if (s - s0).abs() <= (s1 - s).abs() {
                            v0.or(v1)
                        } else {
                            v1.or(v0)
                        }
                    }
                    (Some((_, v0)), None) => v0,
                    (None, Some((_, v1))) => v1,
                    (None, None) => None,
                }
                .filter(|x| x.is_finite())
            }
        }
    }

    /// Feeds the segment `from` → `to`, starting a new run when its style changes.
    fn feed(&mut self, from: P3, to: P3, layer: Option<usize>, rapid: bool, values: Values, at: At) {
        let vertex = Vertex { p: [to.x, to.y], at, values, bins: self.bins.key(&values) };
        let continues = self.current.as_ref().is_some_and(|r| {
            r.layer == layer
                && r.rapid == rapid
                && (r.end.x - from.x).abs() <= MIN_MOVE_MM
                && (r.end.y - from.y).abs() <= MIN_MOVE_MM
                && (r.end.z - from.z).abs() <= MIN_MOVE_MM
        });
        if !continues {
            self.finish_run();
            let start = At { z: from.z, line: at.line, s_mm: at.s_mm - dist3(from, to) };
            self.current = Some(OpenRun::new(from, start, layer, rapid));
        }
        if let Some(run) = self.current.as_mut() {
            run.push(vertex, self.tolerance);
            run.end = to;
        }
    }

    fn finish_run(&mut self) {
        if let Some(run) = self.current.take() {
            if let Some(run) = run.finish(&self.present) {
                self.runs.push(run);
            }
        }
    }
}

/// Segments of an arc so that its chords stay within `tolerance` of it (in 3-D, hence
/// also in the XY projection).
fn arc_segments(m: &Move, center: P3, plane: Plane, length: f64, tolerance: f64) -> usize {
    let (du, dv, axial) = match plane {
        Plane::Xy => (m.start.x - center.x, m.start.y - center.y, m.end.z - m.start.z),
        Plane::Zx => (m.start.z - center.z, m.start.x - center.x, m.end.y - m.start.y),
        Plane::Yz => (m.start.y - center.y, m.start.z - center.z, m.end.x - m.start.x),
    };
    let r = du.hypot(dv);
    if r <= MIN_MOVE_MM {
        return 1;
    }
    // A chord of angle θ deviates r(1 − cos θ/2) from its arc.
    let step = 2.0 * (1.0 - (tolerance / r).min(2.0)).acos();
    // The swept angle: the planar part of the (helical) length over the radius.
    let sweep = (length * length - axial * axial).max(0.0).sqrt() / r;
    ((sweep / step.max(f64::EPSILON)).ceil() as usize).clamp(1, MAX_ARC_SEGMENTS)
}

impl OpenRun {
    fn new(start: P3, at: At, layer: Option<usize>, rapid: bool) -> OpenRun {
        OpenRun {
            layer,
            rapid,
            end: start,
            points: vec![[start.x, start.y]],
            values: vec![[None; QUANTITIES]],
            at: vec![at],
            last: None,
            stretch_bins: [NO_BIN; QUANTITIES],
            stretch_max: [None; QUANTITIES],
            wedge: None,
            wedge_ref: 0.0,
            reach: 0.0,
        }
    }

    fn anchor(&self) -> [f64; 2] {
        self.points[self.points.len() - 1]
    }

    /// Adds a vertex: skips the previous candidate when the chord from the anchor to this
    /// one stays within `tolerance` of it (and of everything skipped before) and the
    /// values stay in their bins; keeps it otherwise.
    fn push(&mut self, v: Vertex, tolerance: f64) {
        let Some(last) = self.last else {
            self.start_stretch(v);
            return;
        };
        let a = self.anchor();
        let (lx, ly) = (last.p[0] - a[0], last.p[1] - a[1]);
        let last_dist = lx.hypot(ly);
        // The wedge with the candidate as a skipped vertex.
        let mut wedge = self.wedge;
        let mut wedge_ref = self.wedge_ref;
        if last_dist > tolerance {
            let angle = ly.atan2(lx);
            if wedge.is_none() {
                wedge_ref = angle;
            }
            let rel = wrap(angle - wedge_ref);
            let half = (tolerance / last_dist).asin();
            let (lo, hi) = wedge.unwrap_or((f64::NEG_INFINITY, f64::INFINITY));
            wedge = Some((lo.max(rel - half), hi.min(rel + half)));
        }
        let reach = self.reach.max(last_dist);
        let (vx, vy) = (v.p[0] - a[0], v.p[1] - a[1]);
        let dist = vx.hypot(vy);
        let inside = match wedge {
            None => true,
            Some((lo, hi)) => {
                let rel = wrap(vy.atan2(vx) - wedge_ref);
                lo <= hi && rel >= lo && rel <= hi
            }
        };
        if inside && (dist >= reach || reach <= tolerance) && v.bins == self.stretch_bins {
            self.wedge = wedge;
            self.wedge_ref = wedge_ref;
            self.reach = reach;
            self.merge_values(&v.values);
            self.last = Some(v);
        } else {
            self.keep(last);
            self.start_stretch(v);
        }
    }

    fn start_stretch(&mut self, v: Vertex) {
        self.wedge = None;
        self.reach = 0.0;
        self.stretch_bins = v.bins;
        self.stretch_max = v.values;
        self.last = Some(v);
    }

    fn merge_values(&mut self, values: &Values) {
        for (m, v) in self.stretch_max.iter_mut().zip(values) {
            if let Some(v) = v {
                *m = Some(m.map_or(*v, |x| x.max(*v)));
            }
        }
    }

    fn keep(&mut self, v: Vertex) {
        self.points.push(v.p);
        self.values.push(self.stretch_max);
        self.at.push(v.at);
    }

    fn finish(mut self, present: &[Quantity]) -> Option<Run> {
        let last = self.last.take()?;
        self.keep(last);
        // The first vertex repeats the second's values.
        self.values[0] = self.values[1];
        let values = present
            .iter()
            .map(|&q| {
                let s = slot(q);
                (q, self.values.iter().map(|v| v[s].map(|x| x as f32)).collect())
            })
            .collect();
        Some(Run {
            layer: self.layer,
            rapid: self.rapid,
            points: self.points,
            values,
            z: self.at.iter().map(|a| a.z as f32).collect(),
            lines: self.at.iter().map(|a| a.line).collect(),
            s_mm: self.at.iter().map(|a| a.s_mm).collect(),
        })
    }
}

/// The straight distance from `a` to `b`, mm.
fn dist3(a: P3, b: P3) -> f64 {
    ((b.x - a.x).powi(2) + (b.y - a.y).powi(2) + (b.z - a.z).powi(2)).sqrt()
}

/// `angle` wrapped into (−π, π].
fn wrap(angle: f64) -> f64 {
    let mut a = angle % (2.0 * PI);
    if a <= -PI {
        a += 2.0 * PI;
    } else if a > PI {
        a -= 2.0 * PI;
    }
    a
}

#[cfg(test)]
#[path = "trace_tests.rs"]
mod tests;
