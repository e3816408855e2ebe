//! The material-removal simulation (MODEL.md §6, seed 004 §2.1): the in-process stock
//! is updated move by move and, at every sample, the engagement of the leading half,
//! the arc length, the chip thickness at the programmed feed and the force are found.

use super::arcs::arc_guides;
use super::chunk::Chunk;
use super::lines::straight_runs;
use super::probe::Contact;
use super::profile::{Profile, SAME_RADIUS_MM};
use super::sampling::{for_each_sample, has_heading, move_curvatures, Sample};
use super::scan_memory::Line;
use super::slice_probes::{Site, SliceProbes};
use super::slice_radii::SliceRadii;
use super::stack::{Slice, Stack};
use crate::core::engagement::{pivot_bounded_centre_radius_mm, tooth_chip_thickness_mm, ToothCut};
use crate::core::force_model::{Coded, ForceModel};
use crate::core::progress::Progress;
use crate::core::toolpath::Toolpath;
use crate::core::CoreError;

/// The raster is brought up to date every this many samples …
pub const CHUNK_SAMPLES: usize = 64;
/// … or sooner when the direction has turned by more than this since the last update,
/// so one straight capsule stands for the swept area.
pub const CHUNK_TURN_DEG: f64 = 5.0;
/// Micrometres per millimetre.
const UM_PER_MM: f64 = 1000.0;
/// Smallest feed ratio at the cutting point (a convex path tighter than the tool).
const MIN_CUTTING_POINT_RATIO: f64 = 0.05;
/// Engagement this close to a full slot has no side: the feed ratio is 1.
const SLOT_ALPHA_RAD: f64 = 0.99 * std::f64::consts::PI;
/// Engagement angles closer than this are the same (they are whole probe steps), rad.
const SAME_ALPHA_RAD: f64 = 1e-12;
/// Samples between progress reports and cancellation checks.
const PROGRESS_EVERY: usize = 4096;

/// What the tool and the cut are, and how finely to sample.
#[derive(Debug, Clone, Copy)]
pub struct Cutter {
    /// The tool's radius by height above its tip.
    pub profile: Profile,
    pub flutes: u32,
    /// Used where the program has no S word.
    pub default_spindle_rpm: Option<f64>,
    pub force_model: Option<ForceModel>,
    pub spacing_mm: f64,
    /// Samples expected (for progress).
    pub total_samples: usize,
}

/// The engagement and its consequences at one sample.
#[derive(Debug, Clone, Copy)]
pub struct SampleResult {
    pub sample: Sample,
    /// Path distance from the start, mm.
    pub s_mm: f64,
    /// Largest engagement over the slices cut.
    pub contact: Contact,
    /// Engagement arc length L = r·α, mm.
    pub arc_length_mm: f64,
    /// Axial depth of cut in material, mm.
    pub ad_mm: f64,
    /// Maximum undeformed chip thickness at the programmed feed, µm.
    pub t_m_um: f64,
    /// The radius the slice of the largest engagement takes the tool at (the tool's radius
    /// but in the corner of a radius or ball end mill, see [`super::profile`]), mm.
    pub contact_radius_mm: f64,
    /// Predicted XY force, N, when a force model is given.
    pub force_n: Option<f64>,
    /// A move straight down (no XY motion) into material: no leading half to measure.
    pub plunge: bool,
    /// The force model was evaluated outside its experiments' design region.
    pub force_extrapolated: bool,
    /// The coded point (MODEL.md §3) of the engaged slice furthest from the design
    /// centre, when a force model is given and the tool cuts.
    pub coded: Option<Coded>,
    /// Feed at the cutting point over the feed at the tool centre (MODEL.md §2, seed 000
    /// Eq. 1), pivot-bounded; 1 where the tool does not cut.
    pub cutting_point_ratio: f64,
    /// The centre-path radius the ratio was computed at (pivot-bounded), mm; infinite
    /// where there is no correction.
    pub centre_radius_mm: f64,
}

impl SampleResult {
    /// What bounds the chip of one tooth at this sample (at the radius of the slice of the
    /// largest engagement).
    pub fn tooth_cut(&self) -> ToothCut {
        ToothCut {
            alpha_rad: self.contact.alpha_rad,
            cutting_point_ratio: self.cutting_point_ratio,
            centre_radius_mm: self.centre_radius_mm,
            tool_radius_mm: self.contact_radius_mm,
        }
    }
}

/// Feed per tooth at the cutting point over that at the centre, from the path's
/// curvature and the side the material is on (MODEL.md §2, seed 000 Eq. 1), and the
/// centre-path radius it was computed at (infinite where there is no correction). Where
/// the centre path turns tighter than the tool follows (a pivot) the radius is bounded
/// ([`pivot_bounded_centre_radius_mm`]), and so is the ratio.
fn cutting_point_ratio(sample: &Sample, contact: &Contact, radius: f64) -> (f64, f64) {
    let rc = sample.curvature.radius_mm();
    if !rc.is_finite() || rc <= 0.0 || contact.alpha_rad >= SLOT_ALPHA_RAD {
        return (1.0, f64::INFINITY);
    }
    let material_left = (contact.entry_rad + contact.exit_rad) > 0.0;
    let centre_left = sample.curvature.kappa > 0.0;
    if material_left == centre_left {
        (((rc - radius) / rc).max(MIN_CUTTING_POINT_RATIO), rc)
    } else {
        let rc = pivot_bounded_centre_radius_mm(rc, radius);
        ((rc + radius) / rc, rc)
    }
}

/// The samples (by their index along the path) a simulation measures.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SampleRange {
    /// Samples before this one only update the stock (see [`simulate_range`]).
    pub measure_from: usize,
    /// The simulation stops before this sample.
    pub stop_at: usize,
}

impl SampleRange {
    /// Every sample.
    pub const ALL: SampleRange = SampleRange { measure_from: 0, stop_at: usize::MAX };
}

/// Runs the simulation, handing every sample's result to `sink`.
pub fn simulate(
    path: &Toolpath,
    cutter: Cutter,
    slices: &mut Stack,
    progress: &dyn Progress,
    sink: impl FnMut(&SampleResult),
) -> Result<(), CoreError> {
    simulate_range(path, cutter, slices, progress, SampleRange::ALL, sink)
}

/// Runs the simulation over the samples of `range`, handing each one's result to `sink`.
/// The samples before `range.measure_from` update the stock as they would in a whole
/// simulation, and are neither measured nor handed on: what the rasters hold, and the
/// chunk being swept, never depend on what the probes find, so the samples from there on
/// are those of the whole simulation. (The probes' memories start empty there: they only
/// spare work, and find what a fresh probe finds.)
pub fn simulate_range(
    path: &Toolpath,
    cutter: Cutter,
    slices: &mut Stack,
    progress: &dyn Progress,
    range: SampleRange,
    mut sink: impl FnMut(&SampleResult),
) -> Result<(), CoreError> {
    let Cutter { spacing_mm, force_model, total_samples, .. } = cutter;
    let force_model = force_model.as_ref();
    let curvatures = move_curvatures(path);
    // All slices share one cell size (with none, nothing is probed).
    let cell_mm = if slices.is_empty() { 0.0 } else { slices.raster(0).cell_mm() };
    let mut radii = SliceRadii::new(cutter.profile, slices.len(), cell_mm);
    let mut probes = SliceProbes::new(slices.len());
    let r = cutter.profile.radius_mm;
    let mut chunk = Chunk::new(0, cell_mm);
    let runs = straight_runs(path);
    let arcs = arc_guides(path, spacing_mm);
    let mut s_mm = 0.0;
    let mut n = 0usize;
    let mut failure: Option<CoreError> = None;

    for_each_sample(path, &curvatures, spacing_mm, |sample| {
        if n >= range.stop_at {
            return false;
        }
        let measured = n >= range.measure_from;
        n += 1;
        if n.is_multiple_of(PROGRESS_EVERY) {
            progress.report(n as f64 / total_samples.max(1) as f64);
            if let Err(e) = progress.checkpoint() {
                failure = Some(e);
                return false;
            }
        }
        s_mm += sample.step_mm;
        let p = (sample.p.x, sample.p.y);
        let cut = slices.cut_at(sample.p.z);
        // A radius or ball end mill cuts the slices in its corner at radii that follow the
        // tip: the chunk swept at the old ones is applied first.
        let reshaped = radii.differ_at(slices, cut, sample.p.z);
        if cut != chunk.cut || reshaped {
            chunk.restart(slices, radii.current(), cut);
            radii.adopt(|k| probes.memories[k].forget());
        }
        chunk.follow(slices, radii.current(), arcs[sample.move_index].as_ref());
        if !measured {
            chunk.push(slices, radii.current(), (sample.p.x, sample.p.y), sample.heading, sample.step_mm);
            return true;
        }
        let plunge = !has_heading(sample.heading);
        let mut result = SampleResult {
            sample: *sample,
            s_mm,
            contact: Contact::default(),
            arc_length_mm: 0.0,
            ad_mm: 0.0,
            t_m_um: 0.0,
            contact_radius_mm: r,
            force_n: force_model.map(|_| 0.0),
            // The deepest slice cut holds the material of all above it (see `slices`): near
            // the tool's full radius, it holds all a shaped tool's slices may reach.
            plunge: plunge && cut > 0 && slices.stock_mut(cut - 1).any_material_near(p.0, p.1, r),
            force_extrapolated: false,
            coded: None,
            cutting_point_ratio: 1.0,
            centre_radius_mm: f64::INFINITY,
        };
        if cut > 0 && !plunge {
            // All slices share one grid.
            let grid = slices.raster(0).grid_position(p.0, p.1);
            let line = runs[sample.move_index].map(|run| {
                let to_end = ((run.end.0 - p.0).powi(2) + (run.end.1 - p.1).powi(2)).sqrt();
                Line { id: run.id, dir: sample.heading, ahead_cells: to_end / cell_mm }
            });
            let at = Site { p, grid, heading: sample.heading, line };
            if radii.cylinder() {
                probes.place(radii.full_table(), &chunk, &at);
                if force_model.is_some() {
                    probes.measure_every_slice(radii.full_table(), slices, cut, p, sample.heading, r);
                } else {
                    probes.measure_deepest_slice(radii.full_table(), slices, cut, p, r);
                }
                evaluate(&mut result, &probes.contacts[..cut], slices.slices(), radii.current(), cutter, force_model);
            } else {
                // Above the first slice not measured none engages.
                let from = probes.measure_shaped(&mut radii, &chunk, &at, slices, cut);
                let (contacts, radii) = (&probes.contacts[from..cut], &radii.current()[from..cut]);
                evaluate(&mut result, contacts, &slices.slices()[from..], radii, cutter, force_model);
            }
        }
        chunk.push(slices, radii.current(), p, sample.heading, sample.step_mm);
        sink(&result);
        true
    });
    chunk.flush(slices, radii.current());
    match failure {
        Some(e) => Err(e),
        None => Ok(()),
    }
}

/// Fills α, L, Ad, t_m and the force of `result` from the contacts of the cut slices
/// (read from the deepest up to the first that does not engage, see [`SliceProbes`]), each
/// slice cutting at its radius in `radii`. The sample's engagement is the largest, with the
/// radius of its slice; the force sums the slices' (MODEL.md §3: the engaged edge, slice by
/// slice), and is an extrapolation wherever a slice cuts in a radius or ball end mill's
/// corner: the papers' model is the flat end mill's flank.
fn evaluate(
    result: &mut SampleResult,
    contacts: &[Contact],
    slices: &[Slice],
    radii: &[f64],
    cutter: Cutter,
    model: Option<&ForceModel>,
) {
    let r = cutter.profile.radius_mm;
    let tip = result.sample.p.z;
    // A cylinder's slices that engage are a run from the deepest cut up: a slice engages
    // only where the one below does (see `engages`), and those above are not measured. A
    // radius or ball end mill's slices are all measured: its corner may miss what its
    // flank above cuts.
    let first = match cutter.profile.is_cylinder() {
        true => contacts.len() - contacts.iter().rev().take_while(|c| c.alpha_rad > 0.0).count(),
        false => 0,
    };
    let (contacts, slices) = (&contacts[first..], slices.get(first..).unwrap_or_default());
    let radii = radii.get(first..).unwrap_or_default();
    // The sample's engagement is the slice's of the longest contact, L = ρ·α (a cylinder's:
    // the largest α): a sliver at a ball's tip may engage all its leading half over a
    // radius too small to carry the cut.
    let cylinder = cutter.profile.is_cylinder();
    let weight = |c: &Contact, rho: f64| if cylinder { c.alpha_rad } else { rho * c.alpha_rad };
    let Some((best, best_radius)) = contacts
        .iter()
        .copied()
        .zip(radii.iter().copied())
        .max_by(|a, b| weight(&a.0, a.1).total_cmp(&weight(&b.0, b.1)).then(a.1.total_cmp(&b.1)))
    else {
        return;
    };
    let rpm = result.sample.spindle_rpm.or(cutter.default_spindle_rpm).unwrap_or(0.0);
    let fz_c_mm = if rpm > 0.0 { result.sample.feed_mm_min / (f64::from(cutter.flutes) * rpm) } else { 0.0 };
    let (ratio, centre_radius_mm) = cutting_point_ratio(&result.sample, &best, best_radius);
    let tooth = |c: &Contact, radius: f64| ToothCut {
        alpha_rad: c.alpha_rad,
        cutting_point_ratio: ratio,
        centre_radius_mm,
        tool_radius_mm: radius,
    };
    let t_m_best = tooth_chip_thickness_mm(fz_c_mm, &tooth(&best, best_radius)) * UM_PER_MM;
    // Slices engaged like the best one (most often all of them) share its chip thickness.
    let t_m = |c: &Contact, radius: f64| {
        if (c.alpha_rad - best.alpha_rad).abs() < SAME_ALPHA_RAD && (radius - best_radius).abs() <= SAME_RADIUS_MM {
            t_m_best
        } else {
            tooth_chip_thickness_mm(fz_c_mm, &tooth(c, radius)) * UM_PER_MM
        }
    };
    result.contact = best;
    result.contact_radius_mm = best_radius;
    result.cutting_point_ratio = ratio;
    result.centre_radius_mm = centre_radius_mm;
    result.arc_length_mm = best_radius * best.alpha_rad;
    result.t_m_um = t_m_best;
    let mut force = 0.0;
    let mut in_corner = false;
    for ((c, s), &radius) in contacts.iter().zip(slices).zip(radii) {
        if c.alpha_rad <= 0.0 {
            continue;
        }
        let thickness = s.z_top - tip.max(s.z_bottom);
        result.ad_mm += thickness;
        in_corner |= r - radius > SAME_RADIUS_MM;
        if let Some(m) = model {
            let (t, l) = (t_m(c, radius), radius * c.alpha_rad);
            force += m.slice_force_n(t, l, s.z_bottom.max(tip) - tip, thickness);
            let coded = m.coded(t, l);
            if result.coded.is_none_or(|c| coded.radius_squared() > c.radius_squared()) {
                result.coded = Some(coded);
            }
        }
    }
    if let Some(coded) = result.coded {
        result.force_extrapolated = in_corner || !coded.within_design_region();
    }
    if model.is_some() {
        result.force_n = Some(force);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::core::analysis::test_paths::{relief_cutter, relief_program, relief_slices};
    use crate::core::progress::NoProgress;

    #[test]
    fn every_slice_keeps_its_material_inside_the_material_of_the_slice_below() {
        let path = relief_program();
        let mut slices = relief_slices(&path);
        assert!(slices.len() > 4, "{} slices", slices.len());
        simulate(&path, relief_cutter(None), &mut slices, &NoProgress, |_| {}).expect("simulates");
        let mut removed_somewhere = vec![false; slices.len()];
        for i in 0..300 {
            for j in 0..300 {
                let (x, y) = (0.05 + 0.1 * f64::from(i), 0.05 + 0.1 * f64::from(j));
                for (k, removed) in removed_somewhere.iter_mut().enumerate().take(slices.len() - 1) {
                    let (upper, lower) = (slices.raster(k).is_material(x, y), slices.raster(k + 1).is_material(x, y));
                    assert!(!upper || lower, "material at ({x}, {y}) in slice {k} but not below it");
                    *removed |= !upper;
                }
            }
        }
        assert!(removed_somewhere.iter().take(slices.len() - 1).all(|&r| r), "some slice was never cut");
    }

    #[test]
    fn slices_sharing_one_stock_while_alike_simulate_exactly_as_slices_with_a_raster_each() {
        let path = relief_program();
        for model in [None, Some(crate::core::fixtures::seed_001_ten_mm())] {
            let run = |separate: bool| {
                let mut slices = relief_slices(&path);
                if separate {
                    (0..slices.len()).for_each(|k| slices.separate(k));
                    slices.never_rejoin = true;
                }
                let mut results = Vec::new();
                simulate(&path, relief_cutter(model), &mut slices, &NoProgress, |r| {
                    results.push((r.contact, r.ad_mm.to_bits(), r.force_n.map(f64::to_bits)))
                })
                .expect("simulates");
                let areas: Vec<u64> =
                    (0..slices.len()).map(|k| slices.raster(k).material_area_mm2().to_bits()).collect();
                (results, areas, slices.memory_bytes())
            };
            let ((shared, shared_areas, shared_bytes), (apart, apart_areas, apart_bytes)) = (run(false), run(true));
            assert!(shared == apart && shared_areas == apart_areas, "the shared stock changed a result");
            assert!(shared_bytes <= apart_bytes);
        }
    }

    #[test]
    fn without_a_force_model_every_sample_has_the_engagement_and_depth_it_has_with_one() {
        // Without a model only the deepest slice's contact is measured, and the slices
        // above are only asked whether they engage at all.
        let model = crate::core::fixtures::seed_001_ten_mm();
        let path = relief_program();
        let run = |model: Option<ForceModel>| {
            let mut results = Vec::new();
            let mut slices = relief_slices(&path);
            simulate(&path, relief_cutter(model), &mut slices, &NoProgress, |r| results.push(*r)).expect("simulates");
            results
        };
        let (with, without) = (run(Some(model)), run(None));
        assert_eq!(with.len(), without.len());
        let mut upper_slices_engaged = 0;
        for (a, b) in with.iter().zip(&without) {
            assert_eq!(a.contact, b.contact, "at {:?}", a.sample.p);
            assert_eq!(a.ad_mm.to_bits(), b.ad_mm.to_bits(), "Ad at {:?}", a.sample.p);
            assert_eq!(a.t_m_um.to_bits(), b.t_m_um.to_bits(), "t_m at {:?}", a.sample.p);
            assert!(a.force_n.is_some() && b.force_n.is_none());
            // More than one slice engaged: more than the deepest slice's share of Ad.
            if a.ad_mm > 1.0 {
                upper_slices_engaged += 1;
            }
        }
        assert!(upper_slices_engaged > 1000, "only {upper_slices_engaged} samples engage more than one slice");
    }
}
