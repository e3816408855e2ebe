//! Where a program's coordinates are. The interpreter's output is the tool tip, in mm, in
//! the frame of the work coordinate system the program starts in (the *base*, G54 unless
//! the program selects another before it moves). The program may move that frame:
//!
//! - other work coordinate systems (G54–G59.3, Fanuc's G54.1 Pn), with the offsets the
//!   program sets itself (`G10 L2` machine values, `G10 L20` "the current position is …",
//!   rotations `G10 L2 R`): a system whose offset from the base is not in the program is
//!   read as having the base's origin, with a warning;
//! - the G92/G52 offset, which shifts every system;
//! - the tool length offset (`G43 H`, `G43.1`): when H names another tool than the one in
//!   the spindle and the tool table gives both lengths, the tip moves by their difference.

use std::collections::{HashMap, HashSet};

use super::map::Affine;
use crate::core::toolpath::P3;

/// Index of a work coordinate system: 0–8 for G54–G59.3, [`EXTENDED_BASE`] + n for
/// Fanuc's G54.1 Pn.
pub(crate) type SystemId = u16;

/// Fanuc's extended systems G54.1 P1… are numbered from here.
pub(crate) const EXTENDED_BASE: SystemId = 100;

/// The name of a work coordinate system, for messages.
pub(crate) fn system_name(id: SystemId) -> String {
    const NAMES: [&str; 9] = ["G54", "G55", "G56", "G57", "G58", "G59", "G59.1", "G59.2", "G59.3"];
    match NAMES.get(usize::from(id)) {
        Some(name) => (*name).to_string(),
        None => format!("G54.1 P{}", id - EXTENDED_BASE),
    }
}

/// What the program said of one work coordinate system's offset.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
struct System {
    /// Machine coordinates of its origin (G10 L2), mm.
    machine: [Option<f64>; 3],
    /// Its origin relative to the output origin (G10 L20, or derived), mm.
    relative: [Option<f64>; 3],
    /// Rotation about its origin in XY (G10 L2 R), degrees.
    rotation_deg: f64,
}

/// Work coordinate systems, the G92/G52 offset and the tool length offset.
#[derive(Debug, Clone)]
pub(crate) struct Frame {
    systems: HashMap<SystemId, System>,
    /// The active system.
    pub active: SystemId,
    /// The base system (the output frame).
    base: SystemId,
    /// Machine coordinates of the output origin, where the program set the base's offset
    /// before its first move.
    anchor: [Option<f64>; 3],
    /// The program has moved: the base is fixed.
    moved: bool,
    /// The G92/G52 offset, mm, and whether it applies (G92.2 suspends it).
    axis_offset: [f64; 3],
    axis_offset_on: bool,
    /// The tip's Z correction of the active length offset, mm.
    tip_dz_mm: f64,
    /// Systems already warned about.
    warned: HashSet<SystemId>,
    /// The map from program to output coordinates, kept up to date by every change.
    current: Affine,
    /// The active system's offset had to be assumed.
    assumed: bool,
}

impl Default for Frame {
    fn default() -> Self {
        Frame {
            systems: HashMap::new(),
            active: 0,
            base: 0,
            anchor: [None; 3],
            moved: false,
            axis_offset: [0.0; 3],
            axis_offset_on: true,
            tip_dz_mm: 0.0,
            warned: HashSet::new(),
            current: Affine::IDENTITY,
            assumed: false,
        }
    }
}

fn axis(p: P3, a: usize) -> f64 {
    [p.x, p.y, p.z][a]
}

fn rotate(x: f64, y: f64, deg: f64) -> (f64, f64) {
    if deg.abs() < f64::EPSILON {
        return (x, y);
    }
    let (s, c) = deg.to_radians().sin_cos();
    (x * c - y * s, x * s + y * c)
}

impl Frame {
    /// Selects a work coordinate system; before the first move it becomes the base.
    pub fn select(&mut self, id: SystemId) {
        self.active = id;
        if !self.moved {
            self.base = id;
        }
        self.refresh();
    }

    /// Sets the tip's Z correction of the active length offset, mm.
    pub fn set_tip_dz(&mut self, dz_mm: f64) {
        if (dz_mm - self.tip_dz_mm).abs() > 0.0 {
            self.tip_dz_mm = dz_mm;
            self.refresh();
        }
    }

    /// Recomputes the map from program to output coordinates after a change.
    fn refresh(&mut self) {
        let rotation_deg = self.rotation(self.active) - self.rotation(self.base);
        let g = self.axis_offset();
        let (gx, gy) = rotate(g[0], g[1], rotation_deg);
        let (o, assumed) = self.origin(self.active);
        self.current =
            Affine { rotation_deg, translation: P3::new(gx + o[0], gy + o[1], g[2] + o[2] + self.tip_dz_mm) };
        self.assumed = assumed;
    }

    /// Marks that the program moves: the base is fixed from now on.
    pub fn start_moving(&mut self) {
        self.moved = true;
    }

    /// The active system's origin relative to the output origin, per axis, and whether
    /// any axis had to be assumed.
    fn origin(&self, id: SystemId) -> ([f64; 3], bool) {
        let sys = self.systems.get(&id).copied().unwrap_or_default();
        let mut out = [0.0; 3];
        let mut assumed = false;
        for (a, o) in out.iter_mut().enumerate() {
            *o = match (sys.relative[a], sys.machine[a], self.anchor[a]) {
                (Some(r), _, _) => r,
                (None, Some(m), Some(anchor)) => m - anchor,
                _ => {
                    assumed |= id != self.base || sys.machine[a].is_some();
                    0.0
                }
            };
        }
        (out, assumed)
    }

    fn rotation(&self, id: SystemId) -> f64 {
        self.systems.get(&id).map_or(0.0, |s| s.rotation_deg)
    }

    /// A warning the first time a system whose offset had to be assumed is used.
    pub fn assumption_warning(&mut self) -> Option<String> {
        if !self.assumed || !self.warned.insert(self.active) {
            return None;
        }
        Some(format!(
            "{}: its offset from {} is not in the program; read as the same origin",
            system_name(self.active),
            system_name(self.base)
        ))
    }

    /// Program coordinates (mm, active system, before G92) to output coordinates.
    pub fn to_out(&self, p: P3) -> P3 {
        self.current.to_out(p)
    }

    /// Output coordinates to program coordinates (the inverse of [`to_out`](Self::to_out)).
    pub fn to_program(&self, p: P3) -> P3 {
        self.current.to_program(p)
    }

    /// The map from program to output coordinates as it is now.
    pub fn affine(&self) -> Affine {
        self.current
    }

    /// `G10 L2 P…`: the machine coordinates of system `id`'s origin on the given axes, and
    /// its rotation.
    pub fn set_machine_offset(&mut self, id: SystemId, values: [Option<f64>; 3], rotation_deg: Option<f64>) {
        let before_moving = !self.moved && id == self.base;
        let sys = self.systems.entry(id).or_default();
        for (a, value) in values.iter().enumerate() {
            if let Some(v) = *value {
                sys.machine[a] = Some(v);
                sys.relative[a] = None;
                if before_moving {
                    self.anchor[a] = Some(v);
                }
            }
        }
        if let Some(r) = rotation_deg {
            sys.rotation_deg = r;
        }
        self.refresh();
    }

    /// `G10 L20 P…`: system `id`'s origin is set so that the tool at `current_out`
    /// (output coordinates) has the given program coordinates (mm) on the given axes.
    pub fn set_current_as(&mut self, id: SystemId, current_out: P3, values: [Option<f64>; 3]) {
        let g = if self.axis_offset_on { self.axis_offset } else { [0.0; 3] };
        let anchor = self.anchor;
        let tip = self.tip_dz_mm;
        let sys = self.systems.entry(id).or_default();
        for a in 0..3 {
            if let Some(v) = values[a] {
                let dz = if a == 2 { tip } else { 0.0 };
                let relative = axis(current_out, a) - v - g[a] - dz;
                sys.relative[a] = Some(relative);
                sys.machine[a] = anchor[a].map(|m| m + relative);
            }
        }
        self.refresh();
    }

    /// `G92`: the G92 offset changes so that `current_out` has the given program
    /// coordinates (mm) on the given axes.
    pub fn set_axis_offset_to(&mut self, current_out: P3, values: [Option<f64>; 3]) {
        let program = self.to_program(current_out);
        for (a, value) in values.iter().enumerate() {
            if let Some(v) = *value {
                let old = if self.axis_offset_on { self.axis_offset[a] } else { 0.0 };
                self.axis_offset[a] = old + axis(program, a) - v;
            }
        }
        self.axis_offset_on = true;
        self.refresh();
    }

    /// `G52`: the G92/G52 offset is the given values (mm) on the given axes.
    pub fn set_local_offset(&mut self, values: [Option<f64>; 3]) {
        for (offset, value) in self.axis_offset.iter_mut().zip(values) {
            if let Some(v) = value {
                *offset = v;
            }
        }
        self.axis_offset_on = true;
        self.refresh();
    }

    /// `G92.1` (`clear`) or `G92.2`/`G92.3` (suspend, restore).
    pub fn axis_offset_state(&mut self, clear: bool, on: bool) {
        if clear {
            self.axis_offset = [0.0; 3];
        }
        self.axis_offset_on = on;
        self.refresh();
    }

    /// The G92/G52 offset, mm, as it applies now.
    pub fn axis_offset(&self) -> [f64; 3] {
        if self.axis_offset_on {
            self.axis_offset
        } else {
            [0.0; 3]
        }
    }

    /// The machine coordinates of a system's origin, if the program gave them.
    pub fn machine_offset(&self, id: SystemId, a: usize) -> Option<f64> {
        let sys = self.systems.get(&id)?;
        sys.machine[a].or_else(|| Some(sys.relative[a]? + self.anchor[a]?))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(p: P3, x: f64, y: f64, z: f64) -> bool {
        (p.x - x).abs() < 1e-9 && (p.y - y).abs() < 1e-9 && (p.z - z).abs() < 1e-9
    }

    #[test]
    fn offsets_the_program_sets_before_moving_place_other_systems_exactly() {
        let mut f = Frame::default();
        f.set_machine_offset(0, [Some(-400.0), Some(-200.0), Some(-300.0)], None);
        f.set_machine_offset(1, [Some(-250.0), Some(-200.0), Some(-300.0)], None);
        f.start_moving();
        assert!(close(f.to_out(P3::new(10.0, 0.0, 0.0)), 10.0, 0.0, 0.0));
        f.select(1);
        assert!(close(f.to_out(P3::new(10.0, 0.0, 0.0)), 160.0, 0.0, 0.0));
        assert!(close(f.to_program(P3::new(160.0, 0.0, 0.0)), 10.0, 0.0, 0.0));
        assert_eq!(f.assumption_warning(), None);
    }

    #[test]
    fn an_unknown_system_is_read_as_the_base_origin_with_one_warning() {
        let mut f = Frame::default();
        f.start_moving();
        f.select(2);
        assert!(close(f.to_out(P3::new(1.0, 2.0, 3.0)), 1.0, 2.0, 3.0));
        assert!(f.assumption_warning().unwrap().starts_with("G56: its offset from G54"));
        assert_eq!(f.assumption_warning(), None);
    }

    #[test]
    fn g92_g52_and_g10_l20_shift_the_program_origin_by_what_they_say() {
        let mut f = Frame::default();
        f.start_moving();
        // The tool at (50, 20, 5) is made X0 Y0.
        f.set_axis_offset_to(P3::new(50.0, 20.0, 5.0), [Some(0.0), Some(0.0), None]);
        assert!(close(f.to_out(P3::new(10.0, 0.0, 5.0)), 60.0, 20.0, 5.0));
        f.axis_offset_state(false, false);
        assert!(close(f.to_out(P3::new(10.0, 0.0, 5.0)), 10.0, 0.0, 5.0));
        f.axis_offset_state(true, true);
        f.set_local_offset([Some(5.0), None, None]);
        assert!(close(f.to_out(P3::default()), 5.0, 0.0, 0.0));
        f.axis_offset_state(true, true);
        f.set_current_as(3, P3::new(30.0, 40.0, 0.0), [Some(0.0), Some(0.0), None]);
        f.select(3);
        assert!(close(f.to_out(P3::new(1.0, 1.0, 0.0)), 31.0, 41.0, 0.0));
        assert_eq!(f.assumption_warning().as_deref().map(|w| w.starts_with("G57")), Some(true));
    }

    #[test]
    fn a_rotated_system_turns_program_coordinates_about_its_origin() {
        let mut f = Frame::default();
        f.set_machine_offset(0, [Some(0.0), Some(0.0), Some(0.0)], None);
        f.set_machine_offset(1, [Some(100.0), Some(0.0), Some(0.0)], Some(90.0));
        f.start_moving();
        f.select(1);
        let out = f.to_out(P3::new(10.0, 0.0, 0.0));
        assert!(close(out, 100.0, 10.0, 0.0), "{out:?}");
        assert!(close(f.to_program(out), 10.0, 0.0, 0.0));
        assert_eq!(system_name(EXTENDED_BASE + 7), "G54.1 P7");
    }
}
