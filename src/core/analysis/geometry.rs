//! The geometry of a simulated path, kept sample by sample: what the material removal
//! decides (α, L, Ad, the tooth's path at the cutting point, the NC line) and not what the
//! feeds decide. The material a path removes does not depend on its feeds, so feeds, wear,
//! time and cost at any feed are arithmetic over these samples, without simulating again
//! (MODEL.md §2–3, §9).
//!
//! A sample takes 64 bytes (f32 values): the 1 M samples of the case study's chosen program
//! take about 64 MB.

use super::engine::SampleResult;
use super::report::PathPoint;
use super::sampling::has_heading;
use crate::core::engagement::ToothCut;

/// One sample of a simulated path.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SampleGeometry {
    /// The move (0-based index into the path) and its NC line.
    pub move_index: u32,
    pub line: u32,
    /// Path distance from the start and from the previous sample, mm.
    pub s_mm: f32,
    pub step_mm: f32,
    /// Tool tip, mm.
    pub x: f32,
    pub y: f32,
    pub z: f32,
    /// Engagement angle, rad (0: in air).
    pub alpha_rad: f32,
    /// The radius the engagement is measured at: the tool's, but in the corner of a radius
    /// or ball end mill (see [`super::profile`]), mm.
    pub contact_radius_mm: f32,
    /// Axial depth of cut in material, mm.
    pub ad_mm: f32,
    /// Feed at the cutting point over feed at the tool centre, and the centre-path radius it
    /// was computed at (infinite: straight): with α they give the chip thickness `t_m` of
    /// any feed per tooth ([`crate::core::engagement::tooth_chip_thickness_mm`]).
    pub cutting_point_ratio: f32,
    pub centre_radius_mm: f32,
    /// Spindle speed (the program's, or the default), min⁻¹; 0 when none is known.
    pub spindle_rpm: f32,
    /// The programmed feed, mm/min.
    pub programmed_mm_min: f32,
    /// Predicted force at the programmed feed, summed over the slices cut, N; NaN when the
    /// simulation had no force model or the tool is in air.
    pub force_n: f32,
    flags: u8,
}

const RAPID: u8 = 1;
/// A move straight down into material (no leading half).
const PLUNGE: u8 = 2;
/// No XY motion (a move straight down, in material or not).
const VERTICAL: u8 = 4;

impl SampleGeometry {
    /// The geometry of a simulated sample; `default_rpm` where the program has no S word.
    pub fn of(r: &SampleResult, default_rpm: Option<f64>) -> Self {
        let s = &r.sample;
        let in_material = r.contact.alpha_rad > 0.0;
        let flags = u8::from(s.rapid) * RAPID
            + u8::from(r.plunge) * PLUNGE
            + u8::from(!s.rapid && !has_heading(s.heading)) * VERTICAL;
        SampleGeometry {
            move_index: u32::try_from(s.move_index).unwrap_or(u32::MAX),
            line: s.line,
            s_mm: r.s_mm as f32,
            step_mm: s.step_mm as f32,
            x: s.p.x as f32,
            y: s.p.y as f32,
            z: s.p.z as f32,
            alpha_rad: r.contact.alpha_rad as f32,
            contact_radius_mm: r.contact_radius_mm as f32,
            ad_mm: r.ad_mm as f32,
            cutting_point_ratio: r.cutting_point_ratio as f32,
            centre_radius_mm: r.centre_radius_mm as f32,
            spindle_rpm: s.spindle_rpm.or(default_rpm).unwrap_or(0.0) as f32,
            programmed_mm_min: s.feed_mm_min as f32,
            force_n: r.force_n.filter(|_| in_material).map_or(f32::NAN, |f| f as f32),
            flags,
        }
    }

    pub fn rapid(&self) -> bool {
        self.flags & RAPID != 0
    }

    /// A move straight down into material.
    pub fn plunge(&self) -> bool {
        self.flags & PLUNGE != 0
    }

    /// A feed move with no XY motion (straight down or up), in material or not.
    pub fn vertical(&self) -> bool {
        self.flags & VERTICAL != 0
    }

    pub fn in_material(&self) -> bool {
        self.alpha_rad > 0.0
    }

    /// Engagement arc length `L = ρ·α` at the contact radius ρ, mm.
    pub fn arc_length_mm(&self) -> f64 {
        f64::from(self.contact_radius_mm) * f64::from(self.alpha_rad)
    }

    /// The spindle speed, when known, min⁻¹.
    pub fn spindle(&self) -> Option<f64> {
        (self.spindle_rpm > 0.0).then_some(f64::from(self.spindle_rpm))
    }

    /// The force at the programmed feed, when known, N.
    pub fn force(&self) -> Option<f64> {
        self.force_n.is_finite().then_some(f64::from(self.force_n))
    }

    /// What bounds one tooth's chip here (at the contact radius).
    pub fn tooth(&self) -> ToothCut {
        ToothCut {
            alpha_rad: f64::from(self.alpha_rad),
            cutting_point_ratio: f64::from(self.cutting_point_ratio),
            centre_radius_mm: f64::from(self.centre_radius_mm),
            tool_radius_mm: f64::from(self.contact_radius_mm),
        }
    }

    /// Where the sample is.
    pub fn at(&self) -> PathPoint {
        PathPoint {
            s_mm: f64::from(self.s_mm),
            line: self.line,
            x: f64::from(self.x),
            y: f64::from(self.y),
            z: f64::from(self.z),
        }
    }
}

/// Every sample of one simulated path, in path order, and what the path removed.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct PathGeometry {
    pub samples: Vec<SampleGeometry>,
    pub tool_radius_mm: f64,
    /// Material removed, mm³.
    pub removed_volume_mm3: f64,
}

impl PathGeometry {
    /// An empty record for a tool of radius `tool_radius_mm`.
    pub fn new(tool_radius_mm: f64) -> Self {
        PathGeometry { samples: Vec::new(), tool_radius_mm, removed_volume_mm3: 0.0 }
    }

    /// The samples of move `index` (the samples are in path order).
    pub fn of_move(&self, index: usize) -> &[SampleGeometry] {
        let key = u32::try_from(index).unwrap_or(u32::MAX);
        let from = self.samples.partition_point(|s| s.move_index < key);
        let to = self.samples.partition_point(|s| s.move_index <= key);
        &self.samples[from..to]
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::core::analysis::{analyze_with, AnalysisSpec, StockRegion};
    use crate::core::fixtures::rounded_box;
    use crate::core::pocketing::{contour_parallel, PocketingSpec};
    use crate::core::progress::NoProgress;
    use crate::core::tool::{EndMill, ToolType};

    #[test]
    fn the_geometry_of_a_simulated_pocket_keeps_every_sample_its_engagement_and_its_force() {
        let pocket = rounded_box(30.0, 24.0, 6.0);
        let path = contour_parallel(
            &pocket,
            &PocketingSpec {
                tool_radius_mm: 5.0,
                radial_depth_mm: 3.0,
                allowance_mm: 0.0,
                z_mm: -5.0,
                safe_z_mm: 5.0,
                feed_mm_min: 1000.0,
                plunge_feed_mm_min: 300.0,
                spindle_rpm: 4800.0,
                climb: true,
                corner_loops: false,
            },
        )
        .unwrap()
        .toolpath;
        let spec = AnalysisSpec {
            tool: EndMill { tool_type: ToolType::Square, diameter_mm: 10.0, flutes: 6, corner_radius_mm: 0.0 },
            stock: vec![StockRegion::Pocket(pocket)],
            open: Vec::new(),
            z_top: 0.0,
            z_bottom: -5.0,
            force_model: Some(crate::core::fixtures::seed_001_ten_mm()),
            default_spindle_rpm: Some(4800.0),
            rapid_mm_min: 20000.0,
            sample_spacing_mm: Some(0.1),
            cell_mm: None,
            alpha_limit_deg: 40.0,
            series_points: 0,
            stock_memory_bytes: crate::core::analysis::DEFAULT_STOCK_MEMORY_BYTES,
        };
        let mut results = Vec::new();
        let analysis = analyze_with(&path, &spec, &NoProgress, |r| results.push(*r)).unwrap();
        let geometry: Vec<SampleGeometry> = results.iter().map(|r| SampleGeometry::of(r, Some(4800.0))).collect();
        assert_eq!(geometry.len(), analysis.summary.samples);
        for (g, r) in geometry.iter().zip(&results) {
            assert!((f64::from(g.alpha_rad) - r.contact.alpha_rad).abs() < 1e-6);
            assert!((g.arc_length_mm() - r.arc_length_mm).abs() < 1e-5);
            assert_eq!(g.rapid(), r.sample.rapid);
            assert_eq!(g.force().is_some(), r.contact.alpha_rad > 0.0);
        }
        let record = PathGeometry { samples: geometry, tool_radius_mm: 5.0, removed_volume_mm3: 0.0 };
        let first_cut = record.samples.iter().find(|s| s.in_material()).unwrap().move_index as usize;
        assert!(record.of_move(first_cut).iter().all(|s| s.move_index as usize == first_cut));
        assert!(!record.of_move(first_cut).is_empty());
    }
}
