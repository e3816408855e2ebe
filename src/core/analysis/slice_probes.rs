//! The probes of a sample's slices (MODEL.md §6): where the tool is, and the contact of
//! each slice it cuts, measured slice by slice from the deepest up, using what the slices'
//! nesting tells of those above (see [`super::slices`]).

use super::chunk::{Chunk, Swept};
use super::engages::interior_points;
use super::probe::{AngleTable, Contact, ProbeSite};
use super::same_below::SameBelow;
use super::scan_memory::{Line, ScanMemory};
use super::slice_radii::SliceRadii;
use super::stack::Stack;

/// Where a sample's tool is: its centre (mm and on the rasters' grid), heading and line.
pub struct Site {
    pub p: (f64, f64),
    pub grid: (f64, f64),
    pub heading: (f64, f64),
    pub line: Option<Line>,
}

/// What the probes of the slices keep from sample to sample.
pub struct SliceProbes {
    site: ProbeSite,
    /// Per slice, its contact at the current sample: from the deepest slice cut up to the
    /// first that does not engage. Above that one none engages (see `engages`), and they
    /// are neither measured nor read.
    pub contacts: Vec<Contact>,
    pub memories: Vec<ScanMemory>,
    /// Per slice, the coarse point where [`AngleTable::engages`] last found material.
    engaged_at: Vec<usize>,
    same_below: SameBelow,
}

impl SliceProbes {
    /// The probes of `slices` slices, knowing nothing yet.
    pub fn new(slices: usize) -> SliceProbes {
        SliceProbes {
            site: ProbeSite::default(),
            contacts: vec![Contact::default(); slices],
            memories: vec![ScanMemory::default(); slices],
            engaged_at: vec![0; slices],
            same_below: SameBelow::new(slices),
        }
    }

    /// Places the probe site of a tool of `table`'s radius at `at`, with what the chunk
    /// swept since the rasters were last updated.
    pub fn place(&mut self, table: &AngleTable, chunk: &Chunk, at: &Site) {
        match chunk.swept(table.radius_mm()) {
            Swept::Arc(arc) => {
                self.site.set(table, at.p, at.grid, at.heading, &[], &chunk.corridor(), at.line);
                self.site.set_swept_arc(arc);
            }
            Swept::Centres => {
                self.site.set(table, at.p, at.grid, at.heading, chunk.recent(), &chunk.corridor(), at.line)
            }
        }
    }

    /// Measures the contact of each of the `cut` slices of a radius or ball end mill at
    /// `at`, each at its radius. Slices at one radius nest as the cylinder's do (see
    /// `slices`): a slice alike with the one below at its radius has its contact, and above
    /// a slice at the full radius with no material near the tool none has any. A slice at a
    /// smaller radius than the one above tells nothing of it: each is measured. Returns the
    /// first slice measured: none above it engages.
    pub fn measure_shaped(
        &mut self,
        radii: &mut SliceRadii,
        chunk: &Chunk,
        at: &Site,
        slices: &mut Stack,
        cut: usize,
    ) -> usize {
        for k in (0..cut).rev() {
            if k + 1 < cut && radii.same(k, k + 1) && slices.alike_below(k) {
                self.contacts[k] = self.contacts[k + 1];
                continue;
            }
            if !slices.stock_mut(k).any_material_near(at.p.0, at.p.1, radii.current()[k]) {
                self.contacts[k] = Contact::default();
                if radii.is_full(k) {
                    return k;
                }
                continue;
            }
            let table = radii.table(k);
            self.place(table, chunk, at);
            let memory = Some(&mut self.memories[k]);
            self.contacts[k] = table.contact_and_states(slices.raster(k), &self.site, memory, 0).0;
        }
        0
    }

    /// Measures the contact of each of the `cut` slices at the site, tool centre `p`
    /// moving along `heading`: a force model needs every slice's α.
    pub fn measure_every_slice(
        &mut self,
        table: &AngleTable,
        slices: &mut Stack,
        cut: usize,
        p: (f64, f64),
        heading: (f64, f64),
        r: f64,
    ) {
        // From the deepest slice cut up. Each slice's material lies inside the material of
        // the one below (see `slices`), and so does each coarse point's state: above a
        // slice with no material near the tool, or none at an interior coarse point (no
        // engagement, see `engages`), none engages, and none is measured; coarse points in
        // air below are in air above; and a slice with the cells of the one below under the
        // tool has its contact.
        let mut below: Option<u128> = None;
        for k in (0..cut).rev() {
            let (contact, states) = match below {
                Some(states) if self.same_below.same(slices, k, p, heading, r) => (self.contacts[k + 1], states),
                _ if !slices.stock_mut(k).any_material_near(p.0, p.1, r) => (Contact::default(), 0),
                _ => {
                    let known_air = below.map_or(0, |states| !states);
                    table.contact_and_states(slices.raster(k), &self.site, Some(&mut self.memories[k]), known_air)
                }
            };
            self.contacts[k] = contact;
            if states & interior_points() == 0 {
                break;
            }
            below = Some(states);
        }
    }

    /// Measures the contact of the deepest of the `cut` slices at the site, tool centre
    /// `p`; each slice above takes it where it engages the tool at all, and none where it
    /// does not. Without a force model that is all a sample needs: the deepest slice's
    /// material holds every upper slice's, so its contact is the largest and the
    /// sample's, and the upper slices count only in Ad, where they engage. (Which slices
    /// engage is exactly what [`measure_every_slice`] finds. The contact could differ from
    /// its largest one only where a coarse interval holds more than one boundary and the
    /// bisections of two slices settle on different ones; on the benchmarks' programs no
    /// sample differs.)
    ///
    /// [`measure_every_slice`]: SliceProbes::measure_every_slice
    pub fn measure_deepest_slice(&mut self, table: &AngleTable, slices: &mut Stack, cut: usize, p: (f64, f64), r: f64) {
        let deepest = cut - 1;
        let (contact, states) = if slices.stock_mut(deepest).any_material_near(p.0, p.1, r) {
            table.contact_and_states(slices.raster(deepest), &self.site, Some(&mut self.memories[deepest]), 0)
        } else {
            (Contact::default(), 0)
        };
        self.contacts[deepest] = contact;
        // Interior points in air below are in air above (see `engages`).
        let mut candidates = states & interior_points();
        for k in (0..deepest).rev() {
            if candidates != 0 && slices.alike_below(k) {
                // The cells of the slice below, which engages: so does this one.
                self.contacts[k] = contact;
                continue;
            }
            if candidates == 0 || !table.engages(slices.raster(k), &self.site, &mut candidates, &mut self.engaged_at[k])
            {
                self.contacts[k] = Contact::default();
                break;
            }
            self.contacts[k] = contact;
        }
    }
}
