//! Tool wear along a whole path (MODEL.md §9): the stock simulation gives every sample's
//! engagement, arc length, cutting-point feed per tooth and force; the wear model weighs
//! them; the result says how much of a tool the path uses and where.

use crate::core::analysis::engine::SampleResult;
use crate::core::analysis::kept::KeptStock;
use crate::core::analysis::report::HISTOGRAM_BIN_DEG;
use crate::core::analysis::samples::{PathSamples, SampleCollector, DRAWING_SAMPLE_BINS};
use crate::core::analysis::{analyze_from, Analysis, AnalysisSpec, Stack};
use crate::core::progress::Progress;
use crate::core::tool_life::{machined_surface_mm, Consumption, ToolLifeModel, WearCut};
use crate::core::CoreError;
use rustc_hash::FxHashMap;
use serde::Serialize;
use utoipa::ToSchema;

/// The lines that wear the tool most are listed, at most this many.
pub const MAX_WEAR_LINES: usize = 20;
/// Largest engagement angle, deg.
const MAX_ALPHA_DEG: f64 = 180.0;

/// Wear spent on one NC line.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, ToSchema)]
pub struct LineWear {
    pub line: u32,
    /// Share of the path's wear, 0..1.
    pub share: f64,
    /// Cutting length on that line, mm.
    pub cutting_length_mm: f64,
    pub max_alpha_deg: f64,
}

/// Wear spent at engagement angles in [from, to).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, ToSchema)]
pub struct AlphaWear {
    pub from_deg: f64,
    pub to_deg: f64,
    /// Share of the path's wear, 0..1.
    pub share: f64,
    pub cutting_length_mm: f64,
}

/// How much of a tool a path uses, and where.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct WearReport {
    pub consumption: Consumption,
    /// Share of the wear on samples whose force rests on the force model outside its
    /// experiments (MODEL.md §3), 0–1: that much of the consumption is an extrapolation.
    pub extrapolated_share: f64,
    /// The lines with the largest shares, largest first.
    pub by_line: Vec<LineWear>,
    pub by_alpha: Vec<AlphaWear>,
    /// Per move (by index): the share of one tool's life it uses.
    #[serde(skip)]
    pub move_consumption: Vec<f64>,
    /// The samples kept for drawing.
    #[serde(skip)]
    pub samples: PathSamples,
}

/// Accumulates the wear of samples.
pub struct WearCounter<'a> {
    model: &'a ToolLifeModel,
    flutes: f64,
    default_rpm: Option<f64>,
    worn_mm: f64,
    /// Wear on samples whose force rests on the model outside its experiments.
    extrapolated_mm: f64,
    cutting_mm: f64,
    /// The cutting length along the machined surface.
    surface_mm: f64,
    /// (Looked up at every sample: hashed by the fast hash of the compiler; the keys are
    /// the program's line numbers.)
    lines: FxHashMap<u32, (f64, f64, f64)>,
    bins: Vec<(f64, f64)>,
    moves: Vec<f64>,
}

impl<'a> WearCounter<'a> {
    pub fn new(model: &'a ToolLifeModel, flutes: u32, default_rpm: Option<f64>) -> Self {
        let bins = (MAX_ALPHA_DEG / HISTOGRAM_BIN_DEG).ceil() as usize;
        WearCounter {
            model,
            flutes: f64::from(flutes),
            default_rpm,
            worn_mm: 0.0,
            extrapolated_mm: 0.0,
            cutting_mm: 0.0,
            surface_mm: 0.0,
            lines: FxHashMap::default(),
            bins: vec![(0.0, 0.0); bins],
            moves: Vec::new(),
        }
    }

    /// Adds one sample of the simulation.
    pub fn add(&mut self, r: &SampleResult) {
        let alpha_deg = r.contact.alpha_rad.to_degrees();
        let rpm = r.sample.spindle_rpm.or(self.default_rpm).unwrap_or(0.0);
        if alpha_deg <= 0.0 || rpm <= 0.0 || r.sample.rapid {
            return;
        }
        let cut = WearCut::at_centre_feed(
            alpha_deg,
            r.arc_length_mm,
            r.sample.feed_mm_min,
            self.flutes,
            rpm,
            r.cutting_point_ratio,
            r.force_n,
        );
        let ds = r.sample.step_mm;
        let wear = self.model.wear_mm(ds, &cut);
        self.worn_mm += wear;
        if r.force_extrapolated {
            self.extrapolated_mm += wear;
        }
        self.cutting_mm += ds;
        self.surface_mm += machined_surface_mm(ds, r.cutting_point_ratio);
        let line = self.lines.entry(r.sample.line).or_insert((0.0, 0.0, 0.0));
        line.0 += wear;
        line.1 += ds;
        line.2 = line.2.max(alpha_deg);
        let bin = ((alpha_deg / HISTOGRAM_BIN_DEG) as usize).min(self.bins.len() - 1);
        self.bins[bin].0 += wear;
        self.bins[bin].1 += ds;
        let i = r.sample.move_index;
        if self.moves.len() <= i {
            self.moves.resize(i + 1, 0.0);
        }
        self.moves[i] += wear;
    }

    pub fn finish(self) -> WearReport {
        let total = self.worn_mm;
        let share = |w: f64| if total > 0.0 { w / total } else { 0.0 };
        let mut by_line: Vec<LineWear> = self
            .lines
            .iter()
            .map(|(&line, &(w, len, alpha))| LineWear {
                line,
                share: share(w),
                cutting_length_mm: len,
                max_alpha_deg: alpha,
            })
            .collect();
        by_line.sort_by(|a, b| b.share.total_cmp(&a.share).then(a.line.cmp(&b.line)));
        by_line.truncate(MAX_WEAR_LINES);
        let by_alpha = self
            .bins
            .iter()
            .enumerate()
            .filter(|(_, (_, len))| *len > 0.0)
            .map(|(i, &(w, len))| AlphaWear {
                from_deg: i as f64 * HISTOGRAM_BIN_DEG,
                to_deg: (i + 1) as f64 * HISTOGRAM_BIN_DEG,
                share: share(w),
                cutting_length_mm: len,
            })
            .collect();
        let life = self.model.life_edge_arc_mm();
        WearReport {
            consumption: Consumption::new(total, life, self.cutting_mm, self.surface_mm),
            extrapolated_share: share(self.extrapolated_mm),
            by_line,
            by_alpha,
            move_consumption: self.moves.iter().map(|w| if life > 0.0 { w / life } else { 0.0 }).collect(),
            samples: PathSamples::default(),
        }
    }
}

/// Analyses `path` and counts its tool wear.
pub fn path_wear(
    path: &crate::core::toolpath::Toolpath,
    spec: &AnalysisSpec,
    model: &ToolLifeModel,
    progress: &dyn Progress,
) -> Result<(Analysis, WearReport), CoreError> {
    path_wear_from(path, spec, None, model, progress).map(|(analysis, report, _)| (analysis, report))
}

/// As [`path_wear`], on the stock `start` another simulation left when given (see
/// [`crate::core::analysis::analyze_from`]), handing back the stock this one leaves.
pub fn path_wear_from(
    path: &crate::core::toolpath::Toolpath,
    spec: &AnalysisSpec,
    start: Option<&KeptStock>,
    model: &ToolLifeModel,
    progress: &dyn Progress,
) -> Result<(Analysis, WearReport, Stack), CoreError> {
    model.validate()?;
    let mut counter = WearCounter::new(model, spec.tool.flutes, spec.default_spindle_rpm);
    let total_length_mm: f64 = path.moves.iter().map(crate::core::toolpath::move_length).sum();
    let mut drawing = SampleCollector::new(total_length_mm, DRAWING_SAMPLE_BINS);
    let (analysis, stack) = analyze_from(path, spec, start, progress, |r| {
        counter.add(r);
        drawing.add(r);
    })?;
    let mut report = counter.finish();
    report.samples = drawing.finish();
    Ok((analysis, report, stack))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::core::analysis::{StockRegion, DEFAULT_ALPHA_LIMIT_DEG};
    use crate::core::fixtures::seed_001_ten_mm;
    use crate::core::progress::NoProgress;
    use crate::core::stock::Rect;
    use crate::core::tool::{EndMill, ToolType};
    use crate::core::toolpath::{Motion, Move, Plane, Toolpath, Units, P3};

    fn model() -> ToolLifeModel {
        crate::core::fixtures::ten_mm_life()
    }

    fn spec(stock: Rect, open: Vec<StockRegion>) -> AnalysisSpec {
        AnalysisSpec {
            tool: EndMill { tool_type: ToolType::Square, diameter_mm: 10.0, flutes: 6, corner_radius_mm: 0.0 },
            stock: vec![StockRegion::Rect(stock)],
            open,
            z_top: 0.0,
            z_bottom: -10.0,
            force_model: Some(seed_001_ten_mm()),
            default_spindle_rpm: Some(9600.0),
            rapid_mm_min: 20000.0,
            sample_spacing_mm: None,
            cell_mm: None,
            alpha_limit_deg: DEFAULT_ALPHA_LIMIT_DEG,
            series_points: 0,
            stock_memory_bytes: crate::core::analysis::DEFAULT_STOCK_MEMORY_BYTES,
        }
    }

    fn path(motion: Motion, start: P3, end: P3, feed: f64) -> Toolpath {
        let m = Move { motion, start, end, feed_mm_min: Some(feed), spindle_rpm: Some(9600.0), tool: None, line: 3 };
        Toolpath { moves: vec![m], events: vec![], source_units: Units::Mm, warnings: vec![] }
    }

    #[test]
    fn a_simulated_standard_straight_cut_wears_the_tool_at_the_rate_of_its_320_m_life() {
        let stock = Rect { x_min: 0.0, y_min: -40.0, x_max: 200.0, y_max: 0.0 };
        let p = path(Motion::Linear, P3::new(-10.0, 4.5, -10.0), P3::new(210.0, 4.5, -10.0), 5760.0);
        let (_, report) = path_wear(&p, &spec(stock, vec![]), &model(), &NoProgress).unwrap();
        let life = report.consumption.equivalent_life;
        assert!((life.centre_path_m - 320.0).abs() / 320.0 < 0.05, "{life:?}");
        assert!((life.machined_surface_m - life.centre_path_m).abs() < 1e-9, "a straight cut: {life:?}");
        assert_eq!(report.by_line[0].line, 3);
        assert!((report.by_alpha.iter().map(|b| b.share).sum::<f64>() - 1.0).abs() < 1e-9);
    }

    #[test]
    fn a_simulated_concave_arc_of_r_over_r_2_lasts_about_15_m_of_centre_path_at_f4320_and_about_55_m_at_constant_force()
    {
        let stock = Rect { x_min: -30.0, y_min: -30.0, x_max: 30.0, y_max: 30.0 };
        let open = vec![StockRegion::Circle { cx: 0.0, cy: 0.0, r: 9.5 }];
        // Half a turn, so the tool never comes back to where it started.
        let (s, e) = (P3::new(5.0, 0.0, -10.0), P3::new(-5.0, 0.0, -10.0));
        let arc = Motion::Arc { center: P3::new(0.0, 0.0, -10.0), clockwise: false, plane: Plane::Xy, turns: 0 };
        // MODEL.md §9: 15 and 55 m of centre path, 30 and 110 m of machined surface (seed
        // 003); MODEL.md §3: the constant-force feed of R/r 2 is about F1160.
        for (feed, centre_m, surface_m) in [(4320.0, 15.0, 30.0), (1160.0, 55.0, 110.0)] {
            let (_, report) =
                path_wear(&path(arc, s, e, feed), &spec(stock, open.clone()), &model(), &NoProgress).unwrap();
            let life = report.consumption.equivalent_life;
            assert!((life.centre_path_m - centre_m).abs() / centre_m < 0.2, "F{feed}: {life:?}");
            assert!((life.machined_surface_m - surface_m).abs() / surface_m < 0.2, "F{feed}: {life:?}");
        }
    }
}
