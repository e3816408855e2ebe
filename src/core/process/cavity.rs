//! The cavity a process plan machines: layers, each a pocket contour between two heights
//! (seed 002 §2.2, seed 004 Table 1), and what limits the tools that can cut it.

use crate::core::error::{require_finite, require_positive};
use crate::core::geometry::Pocket;
use crate::core::tolerance::LENGTH_EPS_MM;
use crate::core::CoreError;
use serde::Serialize;

/// Two turns closer than this (cross product of unit tangents) are tangent: no corner.
const TANGENT_EPS: f64 = 1e-6;

/// One layer of the cavity: the region to remove between `z_top_mm` and `z_bottom_mm`.
#[derive(Debug, Clone, PartialEq)]
pub struct CavityLayer {
    pub pocket: Pocket,
    pub z_top_mm: f64,
    pub z_bottom_mm: f64,
}

impl CavityLayer {
    pub fn thickness_mm(&self) -> f64 {
        self.z_top_mm - self.z_bottom_mm
    }
}

/// How a layer is cut (seed 004 Table 1, MODEL.md §8).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, utoipa::ToSchema)]
#[serde(rename_all = "snake_case")]
pub enum LayerRole {
    /// Rough side cutting at the full axial depth.
    Rough,
    /// The last layer: intermediate-rough side cutting (smaller Ad, higher speed).
    IntermediateRough,
}

/// The layers, top first; the last is cut intermediate-rough.
#[derive(Debug, Clone, PartialEq)]
pub struct Cavity {
    pub layers: Vec<CavityLayer>,
}

impl Cavity {
    /// Checks that the layers are finite, each below the one before and not overlapping.
    pub fn validate(&self) -> Result<(), CoreError> {
        if self.layers.is_empty() {
            return Err(CoreError::invalid("layers", "needs at least one layer"));
        }
        let mut above: Option<f64> = None;
        for (i, l) in self.layers.iter().enumerate() {
            let top = require_finite(&format!("layers[{i}].z_top"), l.z_top_mm)?;
            let bottom = require_finite(&format!("layers[{i}].z_bottom"), l.z_bottom_mm)?;
            if bottom >= top - LENGTH_EPS_MM {
                return Err(CoreError::invalid(
                    format!("layers[{i}].z_bottom"),
                    format!("must be below its z_top ({top} mm), got {bottom} mm"),
                ));
            }
            if let Some(prev) = above {
                if top > prev + LENGTH_EPS_MM {
                    return Err(CoreError::invalid(
                        format!("layers[{i}].z_top"),
                        format!("must be at or below the bottom of the layer above ({prev} mm), got {top} mm"),
                    ));
                }
            }
            above = Some(bottom);
        }
        Ok(())
    }

    /// Top of the first layer, mm.
    pub fn top_mm(&self) -> f64 {
        self.layers.first().map_or(0.0, |l| l.z_top_mm)
    }

    /// Depth from the top of the first layer to the bottom of the last, mm.
    pub fn depth_mm(&self) -> f64 {
        self.top_mm() - self.layers.last().map_or(0.0, |l| l.z_bottom_mm)
    }

    /// Volume of the material the layers hold, mm³.
    pub fn volume_mm3(&self) -> f64 {
        self.layers.iter().map(|l| l.pocket.area() * l.thickness_mm()).sum()
    }

    /// The role of layer `index`: the last one is intermediate-rough.
    pub fn role(&self, index: usize) -> LayerRole {
        if index + 1 == self.layers.len() {
            LayerRole::IntermediateRough
        } else {
            LayerRole::Rough
        }
    }

    /// The smallest concave radius of the walls over all layers, mm (see
    /// [`min_concave_radius_mm`]); `None` when no wall is concave.
    pub fn min_concave_radius_mm(&self) -> Option<f64> {
        self.layers.iter().filter_map(|l| min_concave_radius_mm(&l.pocket)).reduce(f64::min)
    }
}

/// What the job is asked to cut: fixed layers, or one contour to a depth, which each
/// candidate cuts in layers of its own axial depths ([`layers_by_depth`]).
#[derive(Debug, Clone, PartialEq)]
pub enum CavityInput {
    Layers(Cavity),
    Depth { pocket: Pocket, z_top_mm: f64, z_bottom_mm: f64 },
}

/// Most layers one cavity may have, given or cut to a depth: a die's process has a
/// handful, and each layer is planned for every candidate tool.
pub const MAX_CAVITY_LAYERS: usize = 100;

impl CavityInput {
    /// The layers a tool of rough axial depth `rough_ad_mm` and last-layer depth
    /// `last_ad_mm` cuts. A depth that would take more than [`MAX_CAVITY_LAYERS`] layers
    /// is refused before any layer is built.
    pub fn layers_for(&self, rough_ad_mm: f64, last_ad_mm: f64) -> Result<Cavity, CoreError> {
        match self {
            CavityInput::Layers(c) => Ok(c.clone()),
            CavityInput::Depth { pocket, z_top_mm, z_bottom_mm } => {
                let n = layer_count_by_depth(*z_top_mm, *z_bottom_mm, rough_ad_mm, last_ad_mm)?;
                if n > MAX_CAVITY_LAYERS as f64 {
                    return Err(CoreError::invalid(
                        "z_bottom",
                        format!(
                            "{} mm deep at a rough axial depth of {rough_ad_mm} mm is {n} layers; at most {MAX_CAVITY_LAYERS}",
                            z_top_mm - z_bottom_mm
                        ),
                    ));
                }
                layers_by_depth(pocket, *z_top_mm, *z_bottom_mm, rough_ad_mm, last_ad_mm)
            }
        }
    }

    /// The whole cavity as one layer per contour (what the baseline levels run through).
    pub fn whole(&self) -> Cavity {
        match self {
            CavityInput::Layers(c) => c.clone(),
            CavityInput::Depth { pocket, z_top_mm, z_bottom_mm } => Cavity {
                layers: vec![CavityLayer { pocket: pocket.clone(), z_top_mm: *z_top_mm, z_bottom_mm: *z_bottom_mm }],
            },
        }
    }
}

/// How many layers [`layers_by_depth`] makes, without making them (however many that is).
pub fn layer_count_by_depth(
    z_top_mm: f64,
    z_bottom_mm: f64,
    rough_ad_mm: f64,
    last_ad_mm: f64,
) -> Result<f64, CoreError> {
    require_finite("z_top_mm", z_top_mm)?;
    require_finite("z_bottom_mm", z_bottom_mm)?;
    require_positive("rough_ad_mm", rough_ad_mm)?;
    let depth = z_top_mm - z_bottom_mm;
    if depth <= last_ad_mm + LENGTH_EPS_MM {
        return Ok(1.0);
    }
    Ok(crate::core::cycles::levels::step_count(depth - last_ad_mm, rough_ad_mm) + 1.0)
}

/// One contour cut to a depth: layers of the rough axial depth `rough_ad_mm` (equal, at
/// most it) and a last layer of `last_ad_mm`, as seed 004 case study I cuts 35 mm as 3 × 10
/// and 1 × 5. A depth of at most `last_ad_mm` is one (last) layer.
pub fn layers_by_depth(
    pocket: &Pocket,
    z_top_mm: f64,
    z_bottom_mm: f64,
    rough_ad_mm: f64,
    last_ad_mm: f64,
) -> Result<Cavity, CoreError> {
    let depth = z_top_mm - z_bottom_mm;
    let layer = |top: f64, bottom: f64| CavityLayer { pocket: pocket.clone(), z_top_mm: top, z_bottom_mm: bottom };
    if depth <= last_ad_mm + LENGTH_EPS_MM {
        return Ok(Cavity { layers: vec![layer(z_top_mm, z_bottom_mm)] });
    }
    let last_top = z_bottom_mm + last_ad_mm;
    let mut layers: Vec<CavityLayer> = crate::core::cycles::z_levels(z_top_mm, last_top, rough_ad_mm)?
        .into_iter()
        .scan(z_top_mm, |top, bottom| {
            let l = layer(*top, bottom);
            *top = bottom;
            Some(l)
        })
        .collect();
    layers.push(layer(last_top, z_bottom_mm));
    Ok(Cavity { layers })
}

/// The smallest radius of the concave parts of the pocket's walls, mm: the radius of every
/// arc the pocket lies inside, 0 for every sharp concave corner. A flat end mill reaches the
/// whole wall only if its radius is at most this. `None` when no part is concave.
pub fn min_concave_radius_mm(pocket: &Pocket) -> Option<f64> {
    // The pocket keeps its interior on the left of every loop (outer counter-clockwise,
    // islands clockwise): a left-turning arc or corner is concave.
    let mut smallest: Option<f64> = None;
    let mut note = |r: f64| smallest = Some(smallest.map_or(r, |s: f64| s.min(r)));
    for lp in std::iter::once(&pocket.outer).chain(&pocket.islands) {
        let segments: Vec<_> = lp.segments().collect();
        for (k, s) in segments.iter().enumerate() {
            if let Some((_, radius)) = s.circle() {
                if s.sweep_rad() > 0.0 {
                    note(radius);
                }
            }
            let next = &segments[(k + 1) % segments.len()];
            let (out_dir, in_dir) = (tangent(s, 1.0), tangent(next, 0.0));
            if out_dir.0 * in_dir.1 - out_dir.1 * in_dir.0 > TANGENT_EPS {
                note(0.0);
            }
        }
    }
    smallest
}

/// The unit tangent of `s` at parameter `t` (0 start, 1 end), in the direction of travel.
fn tangent(s: &crate::core::geometry::Segment, t: f64) -> (f64, f64) {
    let (dx, dy) = match s.circle() {
        Some((c, _)) => {
            let p = s.point_at(t);
            let (rx, ry) = (p.x - c.x, p.y - c.y);
            if s.sweep_rad() > 0.0 {
                (-ry, rx)
            } else {
                (ry, -rx)
            }
        }
        None => (s.end.x - s.start.x, s.end.y - s.start.y),
    };
    let n = dx.hypot(dy);
    if n > 0.0 {
        (dx / n, dy / n)
    } else {
        (0.0, 0.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::core::fixtures::rounded_box;
    use crate::core::geometry::Loop;

    #[test]
    fn a_box_with_corners_of_radius_8_has_its_smallest_concave_radius_8() {
        let r = min_concave_radius_mm(&rounded_box(90.0, 70.0, 8.0)).unwrap();
        assert!((r - 8.0).abs() < 1e-9, "{r}");
    }

    #[test]
    fn a_sharp_box_has_concave_corners_of_radius_0_and_a_square_island_none() {
        let sharp = Pocket::new(Loop::rectangle(0.0, 0.0, 50.0, 40.0), vec![]).unwrap();
        assert!(min_concave_radius_mm(&sharp).unwrap().abs() < 1e-12);
        let island = Loop::rectangle(20.0, 15.0, 30.0, 25.0);
        let with_island = Pocket::new(rounded_box(50.0, 40.0, 6.0).outer, vec![island]).unwrap();
        let r = min_concave_radius_mm(&with_island).unwrap();
        assert!((r - 6.0).abs() < 1e-9, "the island's corners are convex for the tool: {r}");
    }

    #[test]
    fn thirty_five_mm_cut_as_seed_004_case_i_is_three_layers_of_10_and_one_of_5() {
        let c = layers_by_depth(&rounded_box(90.0, 70.0, 8.0), 0.0, -35.0, 10.0, 5.0).unwrap();
        let t: Vec<f64> = c.layers.iter().map(CavityLayer::thickness_mm).collect();
        assert_eq!(t.len(), 4);
        assert!(t[..3].iter().all(|x| (x - 10.0).abs() < 1e-9) && (t[3] - 5.0).abs() < 1e-9, "{t:?}");
        assert_eq!(c.role(3), LayerRole::IntermediateRough);
        assert_eq!(c.role(0), LayerRole::Rough);
        c.validate().unwrap();
    }

    #[test]
    fn a_depth_between_whole_layers_is_split_into_equal_rough_layers_and_a_shallow_one_is_one_layer() {
        let c = layers_by_depth(&rounded_box(90.0, 70.0, 8.0), 0.0, -32.0, 10.0, 5.0).unwrap();
        let t: Vec<f64> = c.layers.iter().map(CavityLayer::thickness_mm).collect();
        assert!(t.len() == 4 && t[..3].iter().all(|x| (x - 9.0).abs() < 1e-9), "{t:?}");
        let one = layers_by_depth(&rounded_box(90.0, 70.0, 8.0), 0.0, -4.0, 10.0, 5.0).unwrap();
        assert_eq!(one.layers.len(), 1);
    }

    #[test]
    fn the_layer_count_by_depth_is_the_number_of_layers_made() {
        let pocket = rounded_box(90.0, 70.0, 8.0);
        for depth in [1.0, 5.0, 5.0 + 1e-12, 7.5, 15.0, 32.0, 35.0, 35.1, 250.0] {
            let made = layers_by_depth(&pocket, 0.0, -depth, 10.0, 5.0).unwrap().layers.len();
            assert_eq!(layer_count_by_depth(0.0, -depth, 10.0, 5.0).unwrap() as usize, made, "{depth} mm deep");
        }
    }

    #[test]
    fn a_depth_that_takes_more_than_the_most_layers_is_refused_before_they_are_made() {
        let pocket = rounded_box(90.0, 70.0, 8.0);
        let deepest = 10.0 * (MAX_CAVITY_LAYERS - 1) as f64 + 5.0;
        let fits = CavityInput::Depth { pocket: pocket.clone(), z_top_mm: 0.0, z_bottom_mm: -deepest };
        assert_eq!(fits.layers_for(10.0, 5.0).unwrap().layers.len(), MAX_CAVITY_LAYERS);
        let too_deep = CavityInput::Depth { pocket: pocket.clone(), z_top_mm: 0.0, z_bottom_mm: -1e5 };
        let e = too_deep.layers_for(10.0, 5.0).unwrap_err().to_string();
        assert!(e.starts_with("z_bottom") && e.contains("10001 layers"), "{e}");
        let past_counting = CavityInput::Depth { pocket, z_top_mm: 0.0, z_bottom_mm: -1e9 };
        let e = past_counting.layers_for(10.0, 5.0).unwrap_err().to_string();
        assert!(e.starts_with("z_bottom") && e.contains("100000001 layers"), "{e}");
    }

    #[test]
    fn overlapping_layers_are_refused_naming_the_layer() {
        let p = rounded_box(50.0, 40.0, 6.0);
        let c = Cavity {
            layers: vec![
                CavityLayer { pocket: p.clone(), z_top_mm: 0.0, z_bottom_mm: -10.0 },
                CavityLayer { pocket: p, z_top_mm: -5.0, z_bottom_mm: -15.0 },
            ],
        };
        let e = c.validate().unwrap_err();
        assert!(e.to_string().starts_with("layers[1].z_top"), "{e}");
    }
}
