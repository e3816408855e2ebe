//! Writes the stair-step program move by move: each ring at its level, reached by a
//! straight feed move where the tip may stand all along it, otherwise over the safe height
//! and down to a clearance above the stock the roughing may have left there (the top of the
//! layer over it), then plunged at the plunge feed.

use super::levels::Level;
use super::rings::Ring;
use crate::core::geometry::Point;
use crate::core::tolerance::LENGTH_EPS_MM;
use crate::core::toolpath::{Motion, Move, Section, P3};

/// A plunge starts this far above the highest stock the roughing may have left within the
/// tool's reach, mm (**assumed**: a common shop clearance, as the trochoids' ramps start).
pub const PLUNGE_CLEARANCE_MM: f64 = 1.0;

/// Points along a link are checked this many times per cell.
const LINK_CHECKS_PER_CELL: f64 = 2.0;

/// The feeds, speed and heights moves are written with.
#[derive(Debug, Clone, Copy)]
pub struct Feeds {
    pub feed_mm_min: f64,
    pub plunge_feed_mm_min: f64,
    pub spindle_rpm: f64,
    pub safe_z_mm: f64,
    pub tool: u32,
}

/// The moves written so far and the label of each.
pub struct Writer {
    feeds: Feeds,
    pub moves: Vec<Move>,
    pub labels: Vec<Option<Section>>,
    position: Option<P3>,
    label: Option<Section>,
    modal_feed_mm_min: Option<f64>,
}

impl Writer {
    pub fn new(feeds: Feeds) -> Writer {
        Writer { feeds, moves: Vec::new(), labels: Vec::new(), position: None, label: None, modal_feed_mm_min: None }
    }

    /// The label of the moves written from now on.
    pub fn label(&mut self, section: Section) {
        self.label = Some(section);
    }

    /// Cuts `ring` at `z_mm`, from its point nearest the tool, reached as the module says;
    /// `level` says where the tip may stand, `reach_mm` how far the tool's end reaches.
    pub fn cut_ring(&mut self, ring: &Ring, z_mm: f64, level: &Level<'_>, reach_mm: f64) {
        let here = self.position.map(|p| Point::new(p.x, p.y));
        let start = here.map_or(0, |h| nearest(ring, h));
        let first = ring[start];
        match self.position {
            Some(p)
                if (p.z - z_mm).abs() <= LENGTH_EPS_MM && straight_link_allowed(level, Point::new(p.x, p.y), first) =>
            {
                self.feed_to(first, z_mm);
            }
            _ => self.enter(first, z_mm, level, reach_mm),
        }
        for k in 1..=ring.len() {
            self.feed_to(ring[(start + k) % ring.len()], z_mm);
        }
    }

    /// Z alone up to the safe height, if below it.
    pub fn retract(&mut self) {
        if let Some(p) = self.position.filter(|p| p.z < self.feeds.safe_z_mm) {
            self.push(Motion::Rapid, P3::new(p.x, p.y, self.feeds.safe_z_mm), None);
        }
    }

    /// Goes to `p` at `z_mm` from above: up to the safe height, over, down at the rapid
    /// rate to the clearance over the material within reach, then the plunge.
    fn enter(&mut self, p: Point, z_mm: f64, level: &Level<'_>, reach_mm: f64) {
        let safe = self.feeds.safe_z_mm;
        match self.position {
            None => {
                let above = P3::new(p.x, p.y, safe);
                self.position = Some(above);
                self.push(Motion::Rapid, above, None);
            }
            Some(_) => {
                self.retract();
                self.push(Motion::Rapid, P3::new(p.x, p.y, safe), None);
            }
        }
        let clear = (highest_material_mm(level, p, reach_mm).max(z_mm) + PLUNGE_CLEARANCE_MM).min(safe);
        if clear < safe {
            self.push(Motion::Rapid, P3::new(p.x, p.y, clear), None);
        }
        self.push(Motion::Linear, P3::new(p.x, p.y, z_mm), Some(self.feeds.plunge_feed_mm_min));
    }

    fn feed_to(&mut self, p: Point, z_mm: f64) {
        self.push(Motion::Linear, P3::new(p.x, p.y, z_mm), Some(self.feeds.feed_mm_min));
    }

    fn push(&mut self, motion: Motion, end: P3, feed: Option<f64>) {
        if feed.is_some() {
            self.modal_feed_mm_min = feed;
        }
        let start = self.position.unwrap_or(end);
        self.moves.push(Move {
            motion,
            start,
            end,
            feed_mm_min: self.modal_feed_mm_min,
            spindle_rpm: Some(self.feeds.spindle_rpm),
            tool: Some(self.feeds.tool),
            line: 0,
        });
        self.labels.push(self.label);
        self.position = Some(end);
    }
}

/// The index of the point of `ring` nearest `p`.
fn nearest(ring: &Ring, p: Point) -> usize {
    (0..ring.len()).min_by(|&a, &b| ring[a].distance_mm(p).total_cmp(&ring[b].distance_mm(p))).unwrap_or(0)
}

/// Whether the tip may stand at every point of the straight line from `a` to `b`.
fn straight_link_allowed(level: &Level<'_>, a: Point, b: Point) -> bool {
    let step = level.surface.grid.cell_mm / LINK_CHECKS_PER_CELL;
    let n = (a.distance_mm(b) / step).ceil().max(1.0) as usize;
    (0..=n).all(|k| {
        let t = k as f64 / n as f64;
        level.allows(a.x + (b.x - a.x) * t, a.y + (b.y - a.y) * t)
    })
}

/// The highest the roughing may have left stock in the cavity within `reach_mm` of `p`, mm:
/// the top of the layer over each cell, since its tool leaves rest material up to there in
/// corners and necks (the die's own material outside the cavity is not stock: where the tip
/// may stand the tool clears it on the way down). `NEG_INFINITY` where none lies within reach.
fn highest_material_mm(level: &Level<'_>, p: Point, reach_mm: f64) -> f64 {
    let s = level.surface;
    let g = &s.grid;
    let cells = (reach_mm / g.cell_mm).ceil() as isize + 1;
    let Some(centre) = s.cell_at(p.x, p.y) else {
        return s.top_mm;
    };
    let (col, row) = ((centre % g.nx) as isize, (centre / g.nx) as isize);
    let mut highest = f64::NEG_INFINITY;
    for dr in -cells..=cells {
        for dc in -cells..=cells {
            let (x, y) = (col + dc, row + dr);
            if x < 0 || y < 0 || x >= g.nx as isize || y >= g.ny as isize {
                continue;
            }
            let c = (y * g.nx as isize + x) as usize;
            if s.height_mm[c] < s.top_mm {
                highest = highest.max(s.rest_top_mm[c]);
            }
        }
    }
    highest
}
