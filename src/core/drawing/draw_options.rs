//! What a plan view shows ([`DrawOptions`]) and why a request for one is refused
//! ([`DrawError`]), with the checks that resolve the options against a scene.

use super::display_units::LengthUnit;
use super::frame::Extent;
use super::scene::{Quantity, Scene, ScenePath};

/// Default drawing width, px.
pub const DEFAULT_WIDTH_PX: u32 = 1000;
/// Narrowest drawing, px.
pub const MIN_WIDTH_PX: u32 = 200;
/// Widest drawing, px.
pub const MAX_WIDTH_PX: u32 = 4000;

/// What to draw.
#[derive(Debug, Clone, PartialEq)]
pub struct DrawOptions {
    /// The path to draw; `None`: the scene's last path.
    pub path: Option<String>,
    /// The quantity colouring the path; `None`: α if the path has it, else the first it
    /// has (none: plain lines).
    pub color_by: Option<Quantity>,
    /// Index of the layer to draw; `None`: all layers.
    pub layer: Option<usize>,
    pub rapids: bool,
    pub medial: bool,
    pub regions: bool,
    pub trochoids: bool,
    /// Width of the drawing, px ([`MIN_WIDTH_PX`]..=[`MAX_WIDTH_PX`]).
    pub width_px: u32,
    /// The part of the plane to draw, mm (a zoomed view: drawn anew at this scale, its
    /// labels and strokes at their usual size); `None`: the whole scene.
    pub window: Option<Extent>,
    /// The unit the frame's coordinates, the scale bar, the feed legend and the length
    /// labels are written in (the `frame` element stays in mm).
    pub unit: LengthUnit,
}

impl Default for DrawOptions {
    fn default() -> DrawOptions {
        DrawOptions {
            path: None,
            color_by: None,
            layer: None,
            rapids: true,
            medial: true,
            regions: true,
            trochoids: true,
            width_px: DEFAULT_WIDTH_PX,
            window: None,
            unit: LengthUnit::Mm,
        }
    }
}

/// Why a drawing cannot be made as asked.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum DrawError {
    #[error("unknown path '{name}'; available: {}", list(available))]
    UnknownPath { name: String, available: Vec<String> },
    #[error("layer {layer} is out of range: the job has {count} layer{}{}", plural(*count), layer_range(*count))]
    LayerOutOfRange { layer: usize, count: usize },
    #[error("path '{path}' has no values of '{quantity}'; available: {}", list(available))]
    QuantityUnavailable { quantity: String, path: String, available: Vec<String> },
    #[error("width {width} px is out of bounds: {min}..={max} px")]
    WidthOutOfBounds { width: u32, min: u32, max: u32 },
    #[error(
        "the window must have x_min < x_max and y_min < y_max, be at least {MIN_WINDOW_MM} mm wide and high, and lie within ±{MAX_WINDOW_COORD_MM} mm"
    )]
    BadWindow,
}

/// The smallest window a drawing shows, mm (a micrometre: below it the simplified path
/// shows nothing more).
pub const MIN_WINDOW_MM: f64 = 1e-3;
/// The farthest a window's bounds may lie from the origin, mm (a kilometre: beyond any
/// machine, and far from where the drawing's arithmetic loses its precision).
pub const MAX_WINDOW_COORD_MM: f64 = 1e6;

impl DrawError {
    /// The query parameter at fault: `path`, `layer`, `color` or `width`.
    pub fn field(&self) -> &'static str {
        match self {
            DrawError::UnknownPath { .. } => "path",
            DrawError::LayerOutOfRange { .. } => "layer",
            DrawError::QuantityUnavailable { .. } => "color",
            DrawError::WidthOutOfBounds { .. } => "width",
            DrawError::BadWindow => "x_min",
        }
    }
}

fn list(names: &[String]) -> String {
    if names.is_empty() {
        "none".into()
    } else {
        names.join(", ")
    }
}

fn plural(count: usize) -> &'static str {
    if count == 1 {
        ""
    } else {
        "s"
    }
}

fn layer_range(count: usize) -> String {
    match count {
        0 => String::new(),
        1 => " (0)".into(),
        n => format!(" (0–{})", n - 1),
    }
}

/// The options checked against a scene.
#[derive(Debug, Clone, Copy)]
pub struct Resolved<'a> {
    /// The path to draw (none when the scene has no path and none was asked for).
    pub path: Option<&'a ScenePath>,
    pub color_by: Option<Quantity>,
    pub layer: Option<usize>,
}

/// Checks `options` against `scene` and fills in the defaults.
pub fn resolve<'a>(scene: &'a Scene, options: &DrawOptions) -> Result<Resolved<'a>, DrawError> {
    if !(MIN_WIDTH_PX..=MAX_WIDTH_PX).contains(&options.width_px) {
        return Err(DrawError::WidthOutOfBounds { width: options.width_px, min: MIN_WIDTH_PX, max: MAX_WIDTH_PX });
    }
    let path = match &options.path {
        Some(name) => Some(scene.paths.iter().find(|p| &p.name == name).ok_or_else(|| DrawError::UnknownPath {
            name: name.clone(),
            available: scene.paths.iter().map(|p| p.name.clone()).collect(),
        })?),
        None => scene.paths.last(),
    };
    if let Some(w) = options.window {
        let within = [w.x_min, w.y_min, w.x_max, w.y_max].iter().all(|v| v.abs() <= MAX_WINDOW_COORD_MM);
        if !within || w.width() < MIN_WINDOW_MM || w.height() < MIN_WINDOW_MM {
            return Err(DrawError::BadWindow);
        }
    }
    if let Some(layer) = options.layer {
        if layer >= scene.layers.len() {
            return Err(DrawError::LayerOutOfRange { layer, count: scene.layers.len() });
        }
    }
    let available = path.map(|p| scene.quantities(&p.name)).unwrap_or_default();
    let color_by = match options.color_by {
        Some(q) if available.contains(&q) => Some(q),
        Some(q) => {
            return Err(DrawError::QuantityUnavailable {
                quantity: q.as_str().into(),
                path: path.map(|p| p.name.clone()).unwrap_or_default(),
                available: available.iter().map(|q| q.as_str().to_string()).collect(),
            })
        }
        None if available.contains(&Quantity::Alpha) => Some(Quantity::Alpha),
        None => available.first().copied(),
    };
    Ok(Resolved { path, color_by, layer: options.layer })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::core::drawing::scene::{LayerInfo, Run};
    use std::collections::BTreeMap;

    fn scene() -> Scene {
        let run = |q: Quantity| Run {
            layer: Some(0),
            rapid: false,
            points: vec![[0.0, 0.0], [1.0, 0.0]],
            values: BTreeMap::from([(q, vec![Some(1.0), Some(2.0)])]),
            z: Vec::new(),
            lines: Vec::new(),
            s_mm: Vec::new(),
        };
        Scene {
            layers: vec![LayerInfo { name: "L1".into(), z_top: 0.0, z_bottom: -1.0 }],
            paths: vec![
                ScenePath { name: "input".into(), runs: vec![run(Quantity::Alpha)], detail_mm: None },
                ScenePath {
                    name: "planned".into(),
                    runs: vec![run(Quantity::Feed), run(Quantity::Force)],
                    detail_mm: None,
                },
            ],
            ..Scene::default()
        }
    }

    #[test]
    fn defaults_draw_the_last_path_coloured_by_alpha_or_its_first_quantity() {
        let s = scene();
        let r = resolve(&s, &DrawOptions::default()).unwrap();
        assert_eq!(r.path.unwrap().name, "planned");
        assert_eq!(r.color_by, Some(Quantity::Feed));
        let input = DrawOptions { path: Some("input".into()), ..DrawOptions::default() };
        assert_eq!(resolve(&s, &input).unwrap().color_by, Some(Quantity::Alpha));
    }

    #[test]
    fn an_unknown_path_lists_the_available_ones() {
        let e = resolve(&scene(), &DrawOptions { path: Some("x".into()), ..DrawOptions::default() }).unwrap_err();
        assert_eq!(e.field(), "path");
        assert_eq!(e.to_string(), "unknown path 'x'; available: input, planned");
    }

    #[test]
    fn a_layer_out_of_range_says_how_many_there_are() {
        let e = resolve(&scene(), &DrawOptions { layer: Some(3), ..DrawOptions::default() }).unwrap_err();
        assert_eq!(e.field(), "layer");
        assert_eq!(e.to_string(), "layer 3 is out of range: the job has 1 layer (0)");
    }

    #[test]
    fn a_quantity_the_path_lacks_lists_the_available_ones() {
        let options = DrawOptions { color_by: Some(Quantity::Wear), ..DrawOptions::default() };
        let e = resolve(&scene(), &options).unwrap_err();
        assert_eq!(e.field(), "color");
        assert_eq!(e.to_string(), "path 'planned' has no values of 'wear'; available: feed, force");
    }

    #[test]
    fn a_width_out_of_bounds_is_refused() {
        let e = resolve(&scene(), &DrawOptions { width_px: 100, ..DrawOptions::default() }).unwrap_err();
        assert_eq!(e.field(), "width");
        assert_eq!(e.to_string(), "width 100 px is out of bounds: 200..=4000 px");
    }
}
