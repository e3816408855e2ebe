//! Pockets: an outer loop with islands, validated, and the scanline primitive over them.

use super::contour::{pair_crossings, Loop};
use super::fmt_point;
use super::point::Bounds;
use super::validate::first_contact;
use crate::core::error::CoreError;
use serde::{Deserialize, Serialize};

/// A region to machine: inside `outer` and outside every island. After [`Pocket::new`] the
/// outer loop runs counter-clockwise, the islands clockwise, every loop is simple, and each
/// island lies strictly inside the outer loop, apart from the other islands.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "RawPocket")]
pub struct Pocket {
    /// The boundary (counter-clockwise).
    pub outer: Loop,
    /// Regions inside the boundary that stay (clockwise).
    #[serde(default)]
    pub islands: Vec<Loop>,
}

/// A pocket as sent, before validation.
#[derive(Deserialize)]
struct RawPocket {
    outer: Loop,
    #[serde(default)]
    islands: Vec<Loop>,
}

impl TryFrom<RawPocket> for Pocket {
    type Error = CoreError;

    fn try_from(raw: RawPocket) -> Result<Pocket, CoreError> {
        Pocket::new(raw.outer, raw.islands)
    }
}

impl Pocket {
    /// Validates the loops (see [`Loop::validate`]) and their arrangement, and orients the
    /// outer loop counter-clockwise and the islands clockwise. Errors name `outer…` or
    /// `islands[k]…`.
    pub fn new(outer: Loop, islands: Vec<Loop>) -> Result<Pocket, CoreError> {
        outer.validate("outer")?;
        for (k, island) in islands.iter().enumerate() {
            island.validate(&format!("islands[{k}]"))?;
        }
        arrange(outer, islands, "outer", &|k| format!("islands[{k}]"))
    }

    /// `true` when `(x, y)` lies inside the outer loop and inside no island (boundaries as in
    /// [`Loop::contains`], so it agrees with [`Pocket::row_intervals`]).
    pub fn contains(&self, x: f64, y: f64) -> bool {
        self.outer.contains(x, y) && !self.islands.iter().any(|i| i.contains(x, y))
    }

    /// Area of the region (mm²): the outer area minus the islands'.
    pub fn area(&self) -> f64 {
        self.outer.signed_area().abs() - self.islands.iter().map(|i| i.signed_area().abs()).sum::<f64>()
    }

    /// Exact bounding box (the outer loop's).
    pub fn bounds(&self) -> Bounds {
        self.outer.bounds()
    }

    /// The x-intervals of the horizontal line at `y` that lie inside the pocket (outer minus
    /// islands), sorted and disjoint, as half-open `[a, b)` pairs. `out` is cleared first and
    /// is the only buffer used (no allocation once it has grown to the row's crossing count).
    ///
    /// Arcs are intersected exactly; a row through a vertex counts it once and a row along a
    /// horizontal edge counts as inside exactly when the region lies above that edge (the
    /// half-open rule of [`super::Segment::row_crossings`]).
    pub fn row_intervals(&self, y: f64, out: &mut Vec<(f64, f64)>) {
        out.clear();
        self.outer.for_each_row_crossing(y, |x| out.push((x, x)));
        for island in &self.islands {
            island.for_each_row_crossing(y, |x| out.push((x, x)));
        }
        pair_crossings(out);
    }
}

/// Orients already validated loops and checks that each island lies strictly inside the
/// outer loop without touching it, and apart from the others. `outer_field` and
/// `island_field(k)` name the loops in errors.
fn arrange(
    outer: Loop,
    islands: Vec<Loop>,
    outer_field: &str,
    island_field: &dyn Fn(usize) -> String,
) -> Result<Pocket, CoreError> {
    let outer = if outer.signed_area() < 0.0 { outer.reversed() } else { outer };
    let islands: Vec<Loop> =
        islands.into_iter().map(|i| if i.signed_area() > 0.0 { i.reversed() } else { i }).collect();
    for (k, island) in islands.iter().enumerate() {
        if let Some((i, j, point)) = first_contact(island, &outer) {
            return Err(CoreError::invalid(
                island_field(k),
                format!(
                    "the island touches or crosses the boundary {outer_field}: its segment {i} meets segment {j} of {outer_field} at {}",
                    fmt_point(point)
                ),
            ));
        }
        let v = island.vertices[0];
        if !outer.contains(v.x, v.y) {
            return Err(CoreError::invalid(
                island_field(k),
                format!(
                    "the island lies outside the boundary {outer_field} (its vertex {} is outside)",
                    fmt_point(v.point())
                ),
            ));
        }
    }
    for a in 0..islands.len() {
        for b in a + 1..islands.len() {
            if let Some((i, j, point)) = first_contact(&islands[a], &islands[b]) {
                return Err(CoreError::invalid(
                    island_field(b),
                    format!(
                        "islands must be apart: segment {j} of {} meets segment {i} of {} at {}",
                        island_field(b),
                        island_field(a),
                        fmt_point(point)
                    ),
                ));
            }
            for (inner, outer_island) in [(a, b), (b, a)] {
                let v = islands[inner].vertices[0];
                if islands[outer_island].contains(v.x, v.y) {
                    return Err(CoreError::invalid(
                        island_field(inner),
                        format!(
                            "{} lies inside {}: islands must not contain each other (nesting deeper than one level is not supported)",
                            island_field(inner),
                            island_field(outer_island)
                        ),
                    ));
                }
            }
        }
    }
    Ok(Pocket { outer, islands })
}

/// Builds a pocket from loops in any order and orientation: the loop of largest area is the
/// outer one, all others must lie inside it and become islands. Errors name `loops[k]`.
pub fn pocket_from_loops(loops: Vec<Loop>) -> Result<Pocket, CoreError> {
    if loops.is_empty() {
        return Err(CoreError::invalid("loops", "no closed loop to make a pocket from"));
    }
    for (k, lp) in loops.iter().enumerate() {
        lp.validate(&format!("loops[{k}]"))?;
    }
    let outer_index = (0..loops.len())
        .max_by(|&a, &b| loops[a].signed_area().abs().total_cmp(&loops[b].signed_area().abs()))
        .unwrap_or(0);
    let original: Vec<usize> = (0..loops.len()).filter(|&k| k != outer_index).collect();
    let mut loops = loops;
    let outer = loops.remove(outer_index);
    arrange(outer, loops, &format!("loops[{outer_index}]"), &|k| format!("loops[{}]", original[k]))
}

#[cfg(test)]
#[path = "pocket_tests.rs"]
mod tests;
