//! Colours of the drawings: one ramp per quantity, so that a colour means the same thing
//! wherever it is drawn: engagement α from safe to danger (green → yellow up to the limit,
//! then orange → dark red above it), feed sequential in one hue (light → dark blue: faster
//! is darker, never "hot"), tool wear as heat (pale yellow → orange → dark red) and force
//! in purples; a distinct grey for "no value", and fixed colours for outlines, medial
//! classes, critical regions, trochoids and chart series.
//!
//! Values are drawn in [`BINS`] colour bins so that consecutive segments of one bin can be
//! grouped into one SVG element. When a limit is given (the α limit), the cool part of the
//! ramp covers `min..=limit` and the hot part (orange → red) covers `limit..max`: anything
//! above the limit is visibly hot, whatever the range.

use super::scene::{MedialClass, OutlineRole, Quantity};
use std::fmt;

/// An sRGB colour, written `#rrggbb`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Rgb(pub u8, pub u8, pub u8);

impl fmt::Display for Rgb {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "#{:02x}{:02x}{:02x}", self.0, self.1, self.2)
    }
}

/// Number of colour bins of the value ramp (a multiple of 4: the hot part starts on a bin
/// boundary).
pub const BINS: usize = 32;
/// Where the hot part of the ramp starts (a fraction of the ramp).
pub const HOT_START: f64 = 0.75;
/// Bins of the cool part (`min..=limit`).
pub const COOL_BINS: usize = 24;
/// Bins of the hot part (`limit..max`).
pub const HOT_BINS: usize = BINS - COOL_BINS;
/// Values within this of the limit count as at the limit (not above).
const LIMIT_TOLERANCE: f64 = 1e-6;

/// The safest engagement: deep green.
pub const RAMP_COLD: Rgb = Rgb(0x1a, 0x7f, 0x4b);
/// Green.
pub const RAMP_TEAL: Rgb = Rgb(0x4c, 0xa8, 0x4f);
/// Yellow-green.
pub const RAMP_GREEN: Rgb = Rgb(0xa6, 0xc9, 0x3a);
/// The most engagement still safe (at the limit): yellow.
pub const RAMP_YELLOW: Rgb = Rgb(0xe8, 0xd2, 0x2e);
/// Just above the limit: orange.
pub const RAMP_ORANGE: Rgb = Rgb(0xf3, 0x8b, 0x1c);
/// The hottest value: dark red.
pub const RAMP_HOT: Rgb = Rgb(0xb3, 0x12, 0x1f);

/// Stops of α's ramp, safe → danger: (position 0..1, colour). The jump from yellow to
/// orange at [`HOT_START`] marks the limit.
pub const RAMP_STOPS: [(f64, Rgb); 6] = [
    (0.0, RAMP_COLD),
    (0.3, RAMP_TEAL),
    (0.55, RAMP_GREEN),
    (HOT_START, RAMP_YELLOW),
    (HOT_START, RAMP_ORANGE),
    (1.0, RAMP_HOT),
];

/// Feed, sequential in one hue (ColorBrewer Blues, its palest stops left out so that the
/// slowest feed still shows on white): slow light, fast dark.
pub const FEED_STOPS: [(f64, Rgb); 3] =
    [(0.0, Rgb(0x9e, 0xca, 0xe1)), (0.5, Rgb(0x31, 0x82, 0xbd)), (1.0, Rgb(0x08, 0x30, 0x6b))];
/// Tool wear as heat (ColorBrewer YlOrRd): little wear pale yellow, much dark red.
pub const WEAR_STOPS: [(f64, Rgb); 3] =
    [(0.0, Rgb(0xfe, 0xd9, 0x76)), (0.5, Rgb(0xfd, 0x8d, 0x3c)), (1.0, Rgb(0x80, 0x00, 0x26))];
/// Cutting force (ColorBrewer Purples): small light, large deep purple.
pub const FORCE_STOPS: [(f64, Rgb); 3] =
    [(0.0, Rgb(0xbc, 0xbd, 0xdc)), (0.5, Rgb(0x80, 0x7d, 0xba)), (1.0, Rgb(0x3f, 0x00, 0x7d))];

/// The stops of `quantity`'s ramp.
pub fn stops(quantity: Quantity) -> &'static [(f64, Rgb)] {
    match quantity {
        Quantity::Alpha => &RAMP_STOPS,
        Quantity::Feed => &FEED_STOPS,
        Quantity::Wear => &WEAR_STOPS,
        Quantity::Force => &FORCE_STOPS,
    }
}

/// A vertex or segment without a value (air, rapid): neutral grey.
pub const NO_VALUE: Rgb = Rgb(0xa8, 0xa8, 0xa8);
/// Rapid moves (drawn dashed and thin).
pub const RAPID: Rgb = Rgb(0x80, 0x80, 0x80);
/// Feed moves when the path carries no values.
pub const PLAIN_FEED: Rgb = Rgb(0x33, 0x33, 0x33);

/// Stock outline and fill.
pub const STOCK_STROKE: Rgb = Rgb(0x9e, 0x9e, 0x9e);
pub const STOCK_FILL: Rgb = Rgb(0xee, 0xee, 0xee);
/// Pocket wall and the cleared area.
pub const POCKET_STROKE: Rgb = Rgb(0x21, 0x21, 0x21);
pub const POCKET_FILL: Rgb = Rgb(0xff, 0xff, 0xff);
/// Islands.
pub const ISLAND_STROKE: Rgb = Rgb(0x6d, 0x4c, 0x41);
pub const ISLAND_FILL: Rgb = Rgb(0xd7, 0xcc, 0xc8);
/// Regions open at the start.
pub const OPEN_STROKE: Rgb = Rgb(0x64, 0x95, 0xc8);
pub const OPEN_FILL: Rgb = Rgb(0xe3, 0xf2, 0xfd);

/// Medial classes: A (contour-parallel) purple, B (trochoidal) magenta, C (z-cut) brown.
pub const MEDIAL_A: Rgb = Rgb(0x6a, 0x3d, 0x9a);
pub const MEDIAL_B: Rgb = Rgb(0xe7, 0x29, 0x8a);
pub const MEDIAL_C: Rgb = Rgb(0xa6, 0x76, 0x1d);

/// Critical regions.
pub const REGION: Rgb = Rgb(0xe0, 0x1b, 0x24);
/// Opacity of the region band.
pub const REGION_OPACITY: f64 = 0.35;
/// Trochoid spans.
pub const TROCHOID: Rgb = Rgb(0x17, 0xbe, 0xcf);
/// Opacity of the trochoid band.
pub const TROCHOID_OPACITY: f64 = 0.3;

/// Text and axes.
pub const INK: Rgb = Rgb(0x21, 0x21, 0x21);
/// Grid lines of charts.
pub const GRID: Rgb = Rgb(0xe0, 0xe0, 0xe0);

/// Series and bar-group colours of charts (Tableau 10), in order.
pub const SERIES: [Rgb; 10] = [
    Rgb(0x4e, 0x79, 0xa7),
    Rgb(0xf2, 0x8e, 0x2b),
    Rgb(0xe1, 0x57, 0x59),
    Rgb(0x76, 0xb7, 0xb2),
    Rgb(0x59, 0xa1, 0x4f),
    Rgb(0xed, 0xc9, 0x48),
    Rgb(0xb0, 0x7a, 0xa1),
    Rgb(0xff, 0x9d, 0xa7),
    Rgb(0x9c, 0x75, 0x5f),
    Rgb(0xba, 0xb0, 0xac),
];

/// The colour of chart series `index` (wrapping).
pub fn series_color(index: usize) -> Rgb {
    SERIES[index % SERIES.len()]
}

/// Stroke and fill of an outline.
pub fn outline_colors(role: OutlineRole) -> (Rgb, Rgb) {
    match role {
        OutlineRole::Stock => (STOCK_STROKE, STOCK_FILL),
        OutlineRole::Pocket => (POCKET_STROKE, POCKET_FILL),
        OutlineRole::Island => (ISLAND_STROKE, ISLAND_FILL),
        OutlineRole::Open => (OPEN_STROKE, OPEN_FILL),
    }
}

/// The colour of a medial class.
pub fn medial_color(class: MedialClass) -> Rgb {
    match class {
        MedialClass::A => MEDIAL_A,
        MedialClass::B => MEDIAL_B,
        MedialClass::C => MEDIAL_C,
    }
}

/// α's ramp at `t` ∈ [0, 1] (clamped). At [`HOT_START`] itself the hot colour.
pub fn ramp(t: f64) -> Rgb {
    ramp_of(Quantity::Alpha, t)
}

/// `quantity`'s ramp at `t` ∈ [0, 1] (clamped).
pub fn ramp_of(quantity: Quantity, t: f64) -> Rgb {
    let t = if t.is_finite() { t.clamp(0.0, 1.0) } else { 0.0 };
    let stops = stops(quantity);
    for pair in stops.windows(2) {
        let ((t0, c0), (t1, c1)) = (pair[0], pair[1]);
        if t < t1 && t1 - t0 > f64::EPSILON {
            return mix(c0, c1, (t - t0) / (t1 - t0));
        }
    }
    stops[stops.len() - 1].1
}

fn mix(a: Rgb, b: Rgb, f: f64) -> Rgb {
    let ch = |x: u8, y: u8| (f64::from(x) + (f64::from(y) - f64::from(x)) * f).round().clamp(0.0, 255.0) as u8;
    Rgb(ch(a.0, b.0), ch(a.1, b.1), ch(a.2, b.2))
}

/// How values map onto the ramp: a range and optionally a limit above which values are hot.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ValueScale {
    pub min: f64,
    pub max: f64,
    /// Values above it fall in the hot part of the ramp.
    pub limit: Option<f64>,
    /// Some values lie above `max` (a few outliers left out of the range): they take the
    /// top colour, and the legend says "≥ max".
    pub top_clipped: bool,
}

impl ValueScale {
    /// A scale over `min..=max` without a limit.
    pub fn new(min: f64, max: f64) -> ValueScale {
        ValueScale { min, max, limit: None, top_clipped: false }
    }

    /// The colour bin (0..[`BINS`]) of `value`.
    pub fn bin(&self, value: f64) -> usize {
        match self.limit {
            None => bin_of(fraction(value, self.min, self.max), BINS),
            Some(limit) if value <= limit + LIMIT_TOLERANCE => {
                bin_of(fraction(value, self.min, limit.max(self.min)), COOL_BINS)
            }
            Some(limit) => COOL_BINS + bin_of(fraction(value, limit, self.max.max(limit)), HOT_BINS),
        }
    }

    /// The colour of `value` on α's ramp: the colour of its bin.
    pub fn color(&self, value: f64) -> Rgb {
        bin_color(self.bin(value))
    }

    /// Position (0..1) of `value` along the drawn ramp, for legend ticks.
    pub fn position(&self, value: f64) -> f64 {
        match self.limit {
            None => fraction(value, self.min, self.max),
            Some(limit) if value <= limit + LIMIT_TOLERANCE => {
                HOT_START * fraction(value, self.min, limit.max(self.min))
            }
            Some(limit) => HOT_START + (1.0 - HOT_START) * fraction(value, limit, self.max.max(limit)),
        }
    }
}

/// Where `value` lies in `lo..=hi`, clamped to [0, 1]; 0 for an empty range.
fn fraction(value: f64, lo: f64, hi: f64) -> f64 {
    let span = hi - lo;
    if !value.is_finite() || span <= f64::EPSILON * hi.abs().max(1.0) {
        return 0.0;
    }
    ((value - lo) / span).clamp(0.0, 1.0)
}

fn bin_of(fraction: f64, bins: usize) -> usize {
    ((fraction * bins as f64) as usize).min(bins - 1)
}

/// The colour of bin `bin` of α's ramp: the ramp at the bin's centre.
pub fn bin_color(bin: usize) -> Rgb {
    quantity_bin_color(Quantity::Alpha, bin)
}

/// The colour of bin `bin` of `quantity`'s ramp: the ramp at the bin's centre.
pub fn quantity_bin_color(quantity: Quantity, bin: usize) -> Rgb {
    ramp_of(quantity, (bin.min(BINS - 1) as f64 + 0.5) / BINS as f64)
}

/// `#rrggbb` of `value` on a plain ramp over `min..=max` (no limit); `None` → the "no
/// value" grey.
pub fn value_color(value: Option<f64>, min: f64, max: f64) -> String {
    match value {
        Some(v) if v.is_finite() => ValueScale::new(min, max).color(v).to_string(),
        _ => NO_VALUE.to_string(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn colours_are_written_as_six_hex_digits() {
        assert_eq!(Rgb(1, 0xab, 255).to_string(), "#01abff");
    }

    #[test]
    fn the_ramp_runs_from_deep_blue_to_dark_red() {
        assert_eq!(ramp(0.0), RAMP_COLD);
        assert_eq!(ramp(1.0), RAMP_HOT);
        assert_eq!(ramp(HOT_START), RAMP_ORANGE);
        assert_eq!(value_color(Some(0.0), 0.0, 10.0), bin_color(0).to_string());
        assert_eq!(value_color(Some(10.0), 0.0, 10.0), bin_color(BINS - 1).to_string());
    }

    #[test]
    fn a_missing_value_is_grey() {
        assert_eq!(value_color(None, 0.0, 1.0), NO_VALUE.to_string());
        assert_eq!(value_color(Some(f64::NAN), 0.0, 1.0), NO_VALUE.to_string());
    }

    #[test]
    fn values_above_the_alpha_limit_fall_in_the_hot_end() {
        let scale = ValueScale { min: 0.0, max: 180.0, limit: Some(40.0), top_clipped: false };
        assert!(scale.bin(40.0) < COOL_BINS);
        assert!(scale.bin(40.5) >= COOL_BINS);
        assert_eq!(scale.bin(180.0), BINS - 1);
        assert!((scale.position(40.0) - HOT_START).abs() < 1e-12);
        // Even a small excess is hot when the range is narrow.
        let narrow = ValueScale { min: 10.0, max: 41.0, limit: Some(40.0), top_clipped: false };
        assert!(narrow.bin(41.0) >= COOL_BINS);
    }

    #[test]
    fn a_range_below_the_limit_stays_cool() {
        let scale = ValueScale { min: 0.0, max: 30.0, limit: Some(40.0), top_clipped: false };
        assert!(scale.bin(30.0) < COOL_BINS);
    }

    #[test]
    fn each_quantity_has_its_own_ramp_and_only_alpha_and_wear_end_in_red() {
        let top = |q| quantity_bin_color(q, BINS - 1);
        let reddish = |c: Rgb| c.0 > c.2 && c.0 > c.1;
        assert!(reddish(top(Quantity::Alpha)) && reddish(top(Quantity::Wear)));
        assert!(!reddish(top(Quantity::Feed)), "fast feed must not look hot");
        assert!(!reddish(top(Quantity::Force)));
        let bottoms: Vec<Rgb> = Quantity::ALL.iter().map(|&q| quantity_bin_color(q, 0)).collect();
        for (i, a) in bottoms.iter().enumerate() {
            assert!(bottoms[i + 1..].iter().all(|b| b != a), "two quantities share their first colour");
        }
    }

    #[test]
    fn a_sequential_ramp_darkens_from_its_first_bin_to_its_last() {
        let lightness = |c: Rgb| u32::from(c.0) + u32::from(c.1) + u32::from(c.2);
        for q in [Quantity::Feed, Quantity::Force] {
            let l: Vec<u32> = (0..BINS).map(|b| lightness(quantity_bin_color(q, b))).collect();
            assert!(l.windows(2).all(|w| w[1] <= w[0]), "{q:?}: {l:?}");
        }
    }

    #[test]
    fn an_empty_range_maps_to_the_first_bin() {
        assert_eq!(ValueScale::new(5.0, 5.0).bin(5.0), 0);
    }
}
