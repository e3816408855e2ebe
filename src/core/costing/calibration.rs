//! The calibration of the tool-life model (MODEL.md §9; seed 003; seed 002 §2.4): the
//! engagement factor γ(α) and the force exponent k of φ = (F/F*)^k are fitted so that the
//! model reproduces seed 003's measurements on the 10 mm straight end mill, read as lengths
//! of the tool-centre path (seed 003 §3.3 measures "the total length of the machined workpiece
//! surface", which on a concave arc is `R/(R − r)` times the centre path):
//!
//! | case | seed 003 (machined surface) | tool-centre path |
//! |---|---|---|
//! | straight, standard conditions | 320 m | 320 m |
//! | concave R/r = 2, fixed F4320 | 30 m | 15 m |
//! | the same arc at constant force | 110 m | 55 m |
//! | wave paths (A) / (B), constant force over fixed F4320 | life × 5 / × 2 (Fig. 9) | same ratios |
//!
//! # The model fitted
//!
//! γ is 1 up to the tool's standard engagement α0 (25.8° at Rd = 0.05 D, every flat tool of
//! the database), rises linearly to γ40 at 40°, and above 40° keeps the steep shape of seed
//! 002 §2.4, MODEL.md §9's table (40°, 1)(50°, 2)(60°, 4)(90°, 8)(180°, 12) scaled by γ40
//! ([`gamma_table`]). Two parameters, γ40 and k; the straight row holds by construction
//! (γ(α0) = 1 and F = F* there).
//!
//! Wear is counted as the costing counts it ([`ToolLifeModel::wear_mm`]): `L / fz_p · γ · φ`
//! per millimetre of the tool-centre path, with the feed per tooth at the cutting point. On a
//! concave arc that counts `Rc / R` of the tooth passes a millimetre of the centre path sees;
//! the fitted γ absorbs it, as it absorbs the heat and chip jamming seed 003 names.
//!
//! # The cuts
//!
//! Each case is a path of steady cuts ([`Piece`]) whose engagement is analytic (MODEL.md §2):
//! α, L and `fz_p/fz_c` of a straight or concave cut at its radial depth, the force of the
//! seed 001 model at the resulting chip. "Constant force" is the feed-forward of MODEL.md §3
//! ([`constant_force_feed`]) at F*, capped at F12124 (seed 003 Table 2's highest feed).
//!
//! The wave paths are built from seed 003 Table 2, which lists one wave of each path: the
//! length of each block and its feed under constant-force control. Each wave is a run (the
//! first row) and an inner arc (the other rows, down to a lowest feed and back), cut at the
//! pitch Rd 0.5 of Table 1. The run is the straight cut whose constant-force feed is row 1's (the
//! sloped flank of a wave stepped over in X is cut at less than the pitch: (A) at the cap,
//! Rd ≈ 0.26 mm; (B) F8689.9, Rd ≈ 0.35 mm); the arc is the concave arc whose constant-force
//! feed is the lowest of the table ((A) F547.9: R/r ≈ 1.6, as MODEL.md §3 notes; (B)
//! F1583.6: R/r ≈ 2.3), over the length of the other rows. Both are then cut at the
//! constant-force feed and at the fixed F4320 of Table 2 (ii), and the ratio of the lives is
//! the case.
//!
//! # The fit
//!
//! [`fit`] minimises the sum of `ln(predicted / measured)²` over the rows by nested
//! golden-section searches (k inside γ40). [`FITTED_GAMMA_AT_40`] and
//! [`FITTED_FORCE_EXPONENT`] are its result to two decimals, the values migration 0006
//! stores (source `fitted`); a test reruns the fit and checks every row within 20 %.

use crate::core::engagement::{engagement, max_chip_thickness_mm, Contour, ToothCut};
use crate::core::feed::constant_force::{constant_force_feed, Cut, FeedLimits};
use crate::core::force_model::ForceModel;
use crate::core::tool_life::{machined_surface_mm, table_value, CutLength, ToolLifeModel, WearCut};
use crate::core::CoreError;

/// The steep shape of γ above 40° (seed 002 §2.4), as multiples of γ at 40°: MODEL.md §9's
/// table, (α deg, factor).
pub const SEED_002_GAMMA_SHAPE: [(f64, f64); 5] = [(40.0, 1.0), (50.0, 2.0), (60.0, 4.0), (90.0, 8.0), (180.0, 12.0)];

/// γ at 40° as [`fit`] finds it on the seed 003 bench (to two decimals), stored by migration
/// 0006.
pub const FITTED_GAMMA_AT_40: f64 = 2.03;
/// k of φ = (F/F*)^k as [`fit`] finds it (to two decimals), stored by migration 0006.
pub const FITTED_FORCE_EXPONENT: f64 = 2.61;

/// Seed 003 Table 1: the wear tests' 10 mm six-flute end mill at S 9600, fz 0.1 (F5760),
/// Rd 0.5, Ad 10; its life on the standard straight cut, 320 m (seed 003 abstract).
const SEED_003_TOOL_RADIUS_MM: f64 = 5.0;
const SEED_003_FLUTES: u32 = 6;
const SEED_003_SPINDLE_RPM: f64 = 9600.0;
const SEED_003_FZ_MM: f64 = 0.1;
const SEED_003_RD_MM: f64 = 0.5;
const SEED_003_AD_MM: f64 = 10.0;
const SEED_003_LIFE_M: f64 = 320.0;

/// The fixed feed of seed 003's comparison runs, Table 2 (ii), mm/min.
pub const SEED_003_FIXED_FEED_MM_MIN: f64 = 4320.0;
/// The highest feed of the constant-force control, seed 003 Table 2 (A) rows 1 and 20–22
/// (≈ 2.1 × the standard feed; MODEL.md §3), mm/min.
pub const SEED_003_FEED_CAP_MM_MIN: f64 = 12124.0;
/// The lowest constant-force feed, as a share of the standard feed (the database's
/// `fz_min = 0.05 fz`, assumed): never reached by the cases.
const MIN_FEED_SHARE: f64 = 0.05;

/// mm per m.
const MM_PER_M: f64 = 1000.0;
/// µm per mm.
const UM_PER_MM: f64 = 1000.0;

/// Where the searches for a wave's radial depth and arc radius look: Rd from this share of
/// the pitch up to the pitch, R/r from 1.2 (seed 003's smallest) to 5.
const RD_SEARCH_FROM_SHARE: f64 = 0.02;
const RATIO_SEARCH: (f64, f64) = (1.2, 5.0);
/// Bisection steps of those searches (the interval shrinks 2⁻⁶⁰).
const BISECTION_STEPS: usize = 60;
/// Where the fit looks for γ40 and k, and its golden-section steps (0.618⁶⁰ of the range).
const GAMMA_SEARCH: (f64, f64) = (1.0, 8.0);
const EXPONENT_SEARCH: (f64, f64) = (0.0, 6.0);
const GOLDEN_STEPS: usize = 60;

/// The γ table of a flat end mill whose standard cut engages `standard_alpha_deg` (< 40°):
/// 1 up to it, linear to `gamma_at_40` at 40°, then [`SEED_002_GAMMA_SHAPE`] × `gamma_at_40`.
pub fn gamma_table(standard_alpha_deg: f64, gamma_at_40: f64) -> Vec<(f64, f64)> {
    let mut table = vec![(0.0, 1.0), (standard_alpha_deg, 1.0)];
    table.extend(SEED_002_GAMMA_SHAPE.iter().map(|&(a, g)| (a, g * gamma_at_40)));
    table
}

/// `table` moved along α so that its knee at `from_deg` lies at `to_deg`, cut at 180° (its
/// value there interpolated): the rule that gives a tool whose standard cut engages more
/// (the ball of migration 0004, 78.5°) the flat tools' shape, 1 at its own standard cut.
pub fn moved_gamma_table(table: &[(f64, f64)], from_deg: f64, to_deg: f64) -> Vec<(f64, f64)> {
    const FULL_DEG: f64 = 180.0;
    let shift = to_deg - from_deg;
    let mut moved = vec![(0.0, table.first().map_or(1.0, |p| p.1))];
    moved.extend(table.iter().filter(|p| p.0 > 0.0 && p.0 + shift < FULL_DEG).map(|&(a, g)| (a + shift, g)));
    moved.push((FULL_DEG, table_value(table, FULL_DEG - shift)));
    moved
}

/// The wear tests of seed 003 (Table 1) with the force model of their tool.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Bench {
    /// The seed 001 model of the 10 mm tool (MODEL.md §3).
    pub force_model: ForceModel,
    pub tool_radius_mm: f64,
    pub flutes: u32,
    pub spindle_rpm: f64,
    pub standard_fz_mm: f64,
    pub standard_rd_mm: f64,
    pub ad_mm: f64,
    /// Life on the standard straight cut, m.
    pub life_m: f64,
}

/// A steady cut along `length_mm` of the tool-centre path.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Piece {
    pub contour: Contour,
    pub rd_mm: f64,
    pub length_mm: f64,
}

/// How a path is fed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Feed {
    /// One feed throughout, mm/min.
    Fixed(f64),
    /// The constant-force feed at F*, capped at [`SEED_003_FEED_CAP_MM_MIN`].
    ConstantForce,
}

impl Bench {
    /// Seed 003's bench with `force_model` (the 10 mm model of seed 001 Table 4).
    pub fn seed_003(force_model: ForceModel) -> Bench {
        Bench {
            force_model,
            tool_radius_mm: SEED_003_TOOL_RADIUS_MM,
            flutes: SEED_003_FLUTES,
            spindle_rpm: SEED_003_SPINDLE_RPM,
            standard_fz_mm: SEED_003_FZ_MM,
            standard_rd_mm: SEED_003_RD_MM,
            ad_mm: SEED_003_AD_MM,
            life_m: SEED_003_LIFE_M,
        }
    }

    /// The standard straight cut's engagement angle, deg (α0).
    pub fn standard_alpha_deg(&self) -> Result<f64, CoreError> {
        Ok(engagement(Contour::Straight, self.tool_radius_mm, self.standard_rd_mm)?.angle_rad.to_degrees())
    }

    /// F*: the force of the standard straight cut, N.
    pub fn standard_force_n(&self) -> Result<f64, CoreError> {
        self.force_n(Contour::Straight, self.standard_rd_mm, self.standard_feed_mm_min())
    }

    fn standard_feed_mm_min(&self) -> f64 {
        self.standard_fz_mm * f64::from(self.flutes) * self.spindle_rpm
    }

    /// The tool-life model with `gamma_at_40` and `force_exponent`.
    pub fn model(&self, gamma_at_40: f64, force_exponent: f64) -> Result<ToolLifeModel, CoreError> {
        let standard = engagement(Contour::Straight, self.tool_radius_mm, self.standard_rd_mm)?;
        Ok(ToolLifeModel {
            life_m: self.life_m,
            gamma_table: gamma_table(standard.angle_rad.to_degrees(), gamma_at_40),
            force_exponent,
            standard_arc_length_mm: standard.arc_length_mm,
            standard_fz_mm: self.standard_fz_mm,
            standard_force_n: Some(self.standard_force_n()?),
        })
    }

    /// The predicted force of `contour` at `rd_mm` and centre feed `feed_mm_min`, N.
    fn force_n(&self, contour: Contour, rd_mm: f64, feed_mm_min: f64) -> Result<f64, CoreError> {
        let e = engagement(contour, self.tool_radius_mm, rd_mm)?;
        let fz_p = feed_mm_min / (f64::from(self.flutes) * self.spindle_rpm) * e.cutting_point_feed_ratio;
        let t_um = max_chip_thickness_mm(fz_p, e.angle_rad) * UM_PER_MM;
        Ok(self.force_model.force_n(t_um, e.arc_length_mm, self.ad_mm))
    }

    /// The constant-force feed of `contour` at `rd_mm`, unclamped (infinite where no feed
    /// reaches F*), mm/min.
    fn constant_force_unclamped(&self, contour: Contour, rd_mm: f64) -> Result<f64, CoreError> {
        let e = engagement(contour, self.tool_radius_mm, rd_mm)?;
        let centre_radius_mm = match contour {
            Contour::Straight => f64::INFINITY,
            Contour::Concave { surface_radius_mm } => surface_radius_mm - self.tool_radius_mm,
            Contour::Convex { surface_radius_mm } => surface_radius_mm + self.tool_radius_mm,
        };
        let tooth = ToothCut {
            alpha_rad: e.angle_rad,
            cutting_point_ratio: e.cutting_point_feed_ratio,
            centre_radius_mm,
            tool_radius_mm: self.tool_radius_mm,
        };
        let cut = Cut { tooth, arc_length_mm: e.arc_length_mm, ad_mm: self.ad_mm };
        let limits = FeedLimits {
            flutes: self.flutes,
            spindle_rpm: self.spindle_rpm,
            min_feed_mm_min: MIN_FEED_SHARE * self.standard_feed_mm_min(),
            max_feed_mm_min: f64::INFINITY,
        };
        let f = constant_force_feed(&self.force_model, self.standard_force_n()?, cut, limits);
        Ok(f.unclamped_mm_min.unwrap_or(limits.min_feed_mm_min))
    }

    fn feed_of(&self, piece: &Piece, feed: Feed) -> Result<f64, CoreError> {
        match feed {
            Feed::Fixed(f) => Ok(f),
            Feed::ConstantForce => {
                Ok(self.constant_force_unclamped(piece.contour, piece.rd_mm)?.min(SEED_003_FEED_CAP_MM_MIN))
            }
        }
    }

    /// How long one tool lasts on a path made of `pieces` repeated, fed by `feed`, measured
    /// along the tool-centre path and along the machined surface.
    pub fn life(&self, model: &ToolLifeModel, pieces: &[Piece], feed: Feed) -> Result<CutLength, CoreError> {
        let (mut worn, mut centre, mut surface) = (0.0, 0.0, 0.0);
        for p in pieces {
            let e = engagement(p.contour, self.tool_radius_mm, p.rd_mm)?;
            let feed_mm_min = self.feed_of(p, feed)?;
            let cut = WearCut::at_centre_feed(
                e.angle_rad.to_degrees(),
                e.arc_length_mm,
                feed_mm_min,
                f64::from(self.flutes),
                self.spindle_rpm,
                e.cutting_point_feed_ratio,
                Some(self.force_n(p.contour, p.rd_mm, feed_mm_min)?),
            );
            worn += model.wear_mm(p.length_mm, &cut);
            centre += p.length_mm;
            surface += machined_surface_mm(p.length_mm, e.cutting_point_feed_ratio);
        }
        if worn <= 0.0 {
            return Err(CoreError::invalid("pieces", "the path does not wear the tool"));
        }
        let tools = worn / model.life_edge_arc_mm();
        Ok(CutLength { centre_path_m: centre / tools / MM_PER_M, machined_surface_m: surface / tools / MM_PER_M })
    }
}

/// One wave of a wave path of seed 003 Table 2 (see the module documentation).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Wave {
    pub name: &'static str,
    /// Row 1: the run's length, mm, and its constant-force feed, mm/min.
    pub run_mm: f64,
    pub run_feed_mm_min: f64,
    /// The other rows: their total length, mm, and their lowest feed, mm/min.
    pub arc_mm: f64,
    pub arc_lowest_feed_mm_min: f64,
    /// Seed 003 Fig. 9: the constant-force life over the fixed-feed life.
    pub measured_gain: f64,
}

/// Seed 003 Table 2 (A): 34.3 mm at F12124, then 3.45 mm down to F547.9 and back; life × 5.
pub const WAVE_A: Wave = Wave {
    name: "wave path (A)",
    run_mm: 34.3,
    run_feed_mm_min: 12124.0,
    arc_mm: 3.45,
    arc_lowest_feed_mm_min: 547.9,
    measured_gain: 5.0,
};
/// Seed 003 Table 2 (B): 24.0 mm at F8689.9, then 7.676 mm down to F1583.6 and back; life × 2.
pub const WAVE_B: Wave = Wave {
    name: "wave path (B)",
    run_mm: 24.0,
    run_feed_mm_min: 8689.9,
    arc_mm: 7.676,
    arc_lowest_feed_mm_min: 1583.6,
    measured_gain: 2.0,
};

/// The `x` in `[lo, hi]` where the monotone `f` crosses `target` (bisection).
fn crossing(
    mut lo: f64,
    mut hi: f64,
    target: f64,
    f: impl Fn(f64) -> Result<f64, CoreError>,
) -> Result<f64, CoreError> {
    let rising = f(hi)? > f(lo)?;
    for _ in 0..BISECTION_STEPS {
        let mid = 0.5 * (lo + hi);
        if (f(mid)? < target) == rising {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    Ok(0.5 * (lo + hi))
}

impl Wave {
    /// The run and the arc of this wave on `bench`.
    pub fn pieces(&self, bench: &Bench) -> Result<[Piece; 2], CoreError> {
        let r = bench.tool_radius_mm;
        let pitch = bench.standard_rd_mm;
        let run_rd = crossing(RD_SEARCH_FROM_SHARE * pitch, pitch, self.run_feed_mm_min, |rd| {
            bench.constant_force_unclamped(Contour::Straight, rd)
        })?;
        let arc_ratio = crossing(RATIO_SEARCH.0, RATIO_SEARCH.1, self.arc_lowest_feed_mm_min, |k| {
            bench.constant_force_unclamped(Contour::Concave { surface_radius_mm: k * r }, pitch)
        })?;
        Ok([
            Piece { contour: Contour::Straight, rd_mm: run_rd, length_mm: self.run_mm },
            Piece {
                contour: Contour::Concave { surface_radius_mm: arc_ratio * r },
                rd_mm: pitch,
                length_mm: self.arc_mm,
            },
        ])
    }
}

/// What a calibration row measures.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Measure {
    /// The tool-centre path one tool lasts at `feed`, m.
    Life { feed: Feed },
    /// The life at constant force over the life at the fixed F4320.
    ConstantForceGain,
}

/// One row of MODEL.md §9's calibration table.
#[derive(Debug, Clone, PartialEq)]
pub struct CalibrationRow {
    pub case: &'static str,
    pub pieces: Vec<Piece>,
    pub measure: Measure,
    /// Seed 003's value in tool-centre path terms (m, or the ratio).
    pub measured: f64,
}

impl CalibrationRow {
    /// The model's value of this row.
    pub fn predicted(&self, bench: &Bench, model: &ToolLifeModel) -> Result<f64, CoreError> {
        match self.measure {
            Measure::Life { feed } => Ok(bench.life(model, &self.pieces, feed)?.centre_path_m),
            Measure::ConstantForceGain => {
                let controlled = bench.life(model, &self.pieces, Feed::ConstantForce)?.centre_path_m;
                let fixed = bench.life(model, &self.pieces, Feed::Fixed(SEED_003_FIXED_FEED_MM_MIN))?.centre_path_m;
                Ok(controlled / fixed)
            }
        }
    }
}

/// The rows of MODEL.md §9's calibration table on `bench`.
pub fn calibration_rows(bench: &Bench) -> Result<Vec<CalibrationRow>, CoreError> {
    let standard = Piece { contour: Contour::Straight, rd_mm: bench.standard_rd_mm, length_mm: 1.0 };
    let arc = Piece {
        contour: Contour::Concave { surface_radius_mm: 2.0 * bench.tool_radius_mm },
        rd_mm: bench.standard_rd_mm,
        length_mm: 1.0,
    };
    let mut rows = vec![
        CalibrationRow {
            case: "straight at standard conditions: 320 m",
            pieces: vec![standard],
            measure: Measure::Life { feed: Feed::Fixed(bench.standard_feed_mm_min()) },
            measured: bench.life_m,
        },
        CalibrationRow {
            case: "concave R/r = 2 at fixed F4320: 15 m (30 m of surface)",
            pieces: vec![arc],
            measure: Measure::Life { feed: Feed::Fixed(SEED_003_FIXED_FEED_MM_MIN) },
            measured: 15.0,
        },
        CalibrationRow {
            case: "concave R/r = 2 at constant force: 55 m (110 m of surface)",
            pieces: vec![arc],
            measure: Measure::Life { feed: Feed::ConstantForce },
            measured: 55.0,
        },
    ];
    for (wave, case) in [
        (WAVE_A, "wave path (A), constant force over fixed F4320: life x 5"),
        (WAVE_B, "wave path (B), constant force over fixed F4320: life x 2"),
    ] {
        rows.push(CalibrationRow {
            case,
            pieces: wave.pieces(bench)?.to_vec(),
            measure: Measure::ConstantForceGain,
            measured: wave.measured_gain,
        });
    }
    Ok(rows)
}

/// A row as a model reproduces it.
#[derive(Debug, Clone, PartialEq)]
pub struct RowCheck {
    pub case: &'static str,
    pub measured: f64,
    pub predicted: f64,
}

impl RowCheck {
    /// `predicted / measured − 1`.
    pub fn relative_error(&self) -> f64 {
        self.predicted / self.measured - 1.0
    }
}

/// The fitted parameters and how they reproduce each row.
#[derive(Debug, Clone, PartialEq)]
pub struct Fit {
    pub gamma_at_40: f64,
    pub force_exponent: f64,
    pub rows: Vec<RowCheck>,
}

/// Every row of `rows` as the model with `gamma_at_40` and `force_exponent` predicts it.
pub fn check(
    bench: &Bench,
    rows: &[CalibrationRow],
    gamma_at_40: f64,
    force_exponent: f64,
) -> Result<Vec<RowCheck>, CoreError> {
    let model = bench.model(gamma_at_40, force_exponent)?;
    rows.iter()
        .map(|row| Ok(RowCheck { case: row.case, measured: row.measured, predicted: row.predicted(bench, &model)? }))
        .collect()
}

/// The minimum of the unimodal `f` on `[lo, hi]` (golden-section search).
fn golden_min(lo: f64, hi: f64, f: &mut impl FnMut(f64) -> f64) -> f64 {
    let inv_phi = (5f64.sqrt() - 1.0) / 2.0;
    let (mut a, mut b) = (lo, hi);
    let (mut c, mut d) = (b - inv_phi * (b - a), a + inv_phi * (b - a));
    let (mut fc, mut fd) = (f(c), f(d));
    for _ in 0..GOLDEN_STEPS {
        if fc < fd {
            (b, d, fd) = (d, c, fc);
            c = b - inv_phi * (b - a);
            fc = f(c);
        } else {
            (a, c, fc) = (c, d, fd);
            d = a + inv_phi * (b - a);
            fd = f(d);
        }
    }
    0.5 * (a + b)
}

/// Fits γ40 and k to MODEL.md §9's table on `bench` (see the module documentation).
pub fn fit(bench: &Bench) -> Result<Fit, CoreError> {
    let rows = calibration_rows(bench)?;
    let mut failure = None;
    let mut misfit = |gamma_at_40: f64, k: f64| -> f64 {
        match check(bench, &rows, gamma_at_40, k) {
            Ok(checks) => checks.iter().map(|c| (c.predicted / c.measured).ln().powi(2)).sum(),
            Err(e) => {
                failure.get_or_insert(e);
                f64::INFINITY
            }
        }
    };
    let best_k = |g: f64, misfit: &mut dyn FnMut(f64, f64) -> f64| {
        golden_min(EXPONENT_SEARCH.0, EXPONENT_SEARCH.1, &mut |k| misfit(g, k))
    };
    let gamma_at_40 = golden_min(GAMMA_SEARCH.0, GAMMA_SEARCH.1, &mut |g| {
        let k = best_k(g, &mut misfit);
        misfit(g, k)
    });
    let force_exponent = best_k(gamma_at_40, &mut misfit);
    if let Some(e) = failure {
        return Err(e);
    }
    Ok(Fit { gamma_at_40, force_exponent, rows: check(bench, &rows, gamma_at_40, force_exponent)? })
}

#[cfg(test)]
#[path = "calibration_tests.rs"]
mod tests;
