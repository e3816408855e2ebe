//! The frame of a plan view: the scene's extent in mm fitted into the drawing area in
//! px, y up.

/// An axis-aligned box in mm.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Extent {
    pub x_min: f64,
    pub y_min: f64,
    pub x_max: f64,
    pub y_max: f64,
}

/// Half-size of the extent of a scene without geometry, mm.
const EMPTY_HALF_SIZE_MM: f64 = 1.0;
/// Smallest side of an extent, mm (a point or a straight line gets some width).
const MIN_SIDE_MM: f64 = 1e-3;

impl Extent {
    /// The box around `points` (finite ones); a unit box around the origin when empty.
    pub fn of_points<'a>(points: impl IntoIterator<Item = &'a [f64; 2]>) -> Extent {
        let mut e =
            Extent { x_min: f64::INFINITY, y_min: f64::INFINITY, x_max: f64::NEG_INFINITY, y_max: f64::NEG_INFINITY };
        for p in points.into_iter().filter(|p| p[0].is_finite() && p[1].is_finite()) {
            e.x_min = e.x_min.min(p[0]);
            e.y_min = e.y_min.min(p[1]);
            e.x_max = e.x_max.max(p[0]);
            e.y_max = e.y_max.max(p[1]);
        }
        if !e.x_min.is_finite() {
            return Extent {
                x_min: -EMPTY_HALF_SIZE_MM,
                y_min: -EMPTY_HALF_SIZE_MM,
                x_max: EMPTY_HALF_SIZE_MM,
                y_max: EMPTY_HALF_SIZE_MM,
            };
        }
        let side = e.width().max(e.height()).max(MIN_SIDE_MM);
        // A thin box gets at least 1 % of its long side across (a straight cut).
        let min_side = side * 0.01;
        let widen = |lo: &mut f64, hi: &mut f64| {
            let pad = (min_side - (*hi - *lo)).max(0.0) / 2.0;
            *lo -= pad;
            *hi += pad;
        };
        widen(&mut e.x_min, &mut e.x_max);
        widen(&mut e.y_min, &mut e.y_max);
        e
    }

    pub fn width(&self) -> f64 {
        self.x_max - self.x_min
    }

    pub fn height(&self) -> f64 {
        self.y_max - self.y_min
    }
}

/// Maps mm (y up) to px (y down) in a box of the drawing.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Frame {
    extent: Extent,
    /// px per mm.
    pub scale: f64,
    /// px position of (x_min, y_max).
    origin: (f64, f64),
    /// Size of the drawn area, px.
    pub width_px: f64,
    pub height_px: f64,
}

impl Frame {
    /// Fits `extent` into a box `width_px` wide, at most `max_height_px` high, its top
    /// left at `top_left`: the scale is the largest that fits both, the content centred
    /// horizontally; the box's height is the content's.
    pub fn fit(extent: Extent, top_left: (f64, f64), width_px: f64, max_height_px: f64) -> Frame {
        let scale = (width_px / extent.width()).min(max_height_px / extent.height());
        let content_w = extent.width() * scale;
        let height_px = extent.height() * scale;
        Frame { extent, scale, origin: (top_left.0 + (width_px - content_w) / 2.0, top_left.1), width_px, height_px }
    }

    /// px of a point in mm.
    pub fn px(&self, p: [f64; 2]) -> (f64, f64) {
        (
            self.origin.0 + (p[0] - self.extent.x_min) * self.scale,
            self.origin.1 + (self.extent.y_max - p[1]) * self.scale,
        )
    }

    /// The extent drawn, mm.
    pub fn extent(&self) -> Extent {
        self.extent
    }

    /// A length in mm as px.
    pub fn len_px(&self, mm: f64) -> f64 {
        mm * self.scale
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn y_points_up_and_the_extent_fills_the_width() {
        let e = Extent::of_points(&[[0.0, 0.0], [100.0, 50.0]]);
        let f = Frame::fit(e, (10.0, 20.0), 200.0, 1000.0);
        assert!((f.scale - 2.0).abs() < 1e-12);
        let (x, y) = f.px([0.0, 0.0]);
        assert!((x - 10.0).abs() < 1e-12 && (y - 120.0).abs() < 1e-12);
        let (x, y) = f.px([100.0, 50.0]);
        assert!((x - 210.0).abs() < 1e-12 && (y - 20.0).abs() < 1e-12);
    }

    #[test]
    fn a_tall_extent_is_limited_by_the_height_and_centred() {
        let e = Extent::of_points(&[[0.0, 0.0], [10.0, 100.0]]);
        let f = Frame::fit(e, (0.0, 0.0), 200.0, 100.0);
        assert!((f.scale - 1.0).abs() < 1e-12);
        let (x, _) = f.px([0.0, 0.0]);
        assert!((x - 95.0).abs() < 1e-12);
    }

    #[test]
    fn an_empty_or_flat_extent_still_has_an_area() {
        let empty = Extent::of_points(&[]);
        assert!(empty.width() > 0.0 && empty.height() > 0.0);
        let flat = Extent::of_points(&[[0.0, 5.0], [100.0, 5.0]]);
        assert!(flat.height() > 0.5);
    }
}
