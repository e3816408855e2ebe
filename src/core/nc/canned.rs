//! Canned cycles (drilling, tapping and boring), expanded into rapid and feed moves the
//! way LinuxCNC and Fanuc controls execute them in the XY plane. Each hole, in absolute
//! coordinates (the interpreter turns G91 values into these):
//!
//! 1. if the tool is below the R plane, rapid up to it (the clearance height becomes R);
//! 2. rapid to the hole's XY at the clearance height, then rapid down to the R plane;
//! 3. the cycle's own work:
//!    - G81 drill: feed to the bottom. G82: the same, then dwell (P).
//!    - G83 peck: feed down one peck (Q), rapid out to R, rapid back down to
//!      [`G83_PECK_CLEARANCE_MM`] above the last depth, and again until the bottom.
//!    - G73 chip break: feed down one peck (Q), rapid back [`G73_CHIP_BREAK_MM`], and feed
//!      on from there, until the bottom.
//!    - G84/G74 tapping, G85 boring, G89 boring with a dwell: feed to the bottom, (dwell,)
//!      feed back out to R.
//!    - G86 boring (spindle stop) and Fanuc's G76 fine boring: feed to the bottom, (dwell,)
//!      rapid out;
//! 4. rapid up to R (G99) or to the clearance height (G98, the default).

use crate::core::tolerance::LENGTH_EPS_MM;
use crate::core::toolpath::P3;

/// How far above the last peck depth G83 comes back down at the rapid rate, mm
/// (LinuxCNC 2.9: 0.010 in).
pub const G83_PECK_CLEARANCE_MM: f64 = 0.254;

/// How far G73 backs off to break the chip, mm (LinuxCNC: 0.010 in).
pub const G73_CHIP_BREAK_MM: f64 = 0.254;

/// Most pecks G83 may make for one hole; more is surely a mistaken Q.
pub const MAX_PECKS_PER_HOLE: u32 = 10_000;

/// Which canned cycle.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum CycleKind {
    /// G81.
    Drill,
    /// G82.
    DwellAtBottom,
    /// G83.
    Peck,
    /// G73.
    ChipBreak,
    /// G84.
    Tap,
    /// G74 (left-hand tapping, Fanuc).
    LeftTap,
    /// G85.
    Bore,
    /// G86.
    BoreSpindleStop,
    /// G89.
    BoreDwell,
    /// G76 (Fanuc fine boring; LinuxCNC's G76 is a lathe threading cycle).
    FineBore,
}

impl CycleKind {
    /// The G code that names the cycle.
    pub fn code(self) -> &'static str {
        match self {
            CycleKind::Drill => "G81",
            CycleKind::DwellAtBottom => "G82",
            CycleKind::Peck => "G83",
            CycleKind::ChipBreak => "G73",
            CycleKind::Tap => "G84",
            CycleKind::LeftTap => "G74",
            CycleKind::Bore => "G85",
            CycleKind::BoreSpindleStop => "G86",
            CycleKind::BoreDwell => "G89",
            CycleKind::FineBore => "G76",
        }
    }

    /// Whether the cycle reads a peck depth Q.
    pub fn pecks(self) -> bool {
        matches!(self, CycleKind::Peck | CycleKind::ChipBreak)
    }

    /// Whether the cycle must have a dwell P (others may have one).
    pub fn needs_dwell(self) -> bool {
        matches!(self, CycleKind::DwellAtBottom | CycleKind::BoreDwell)
    }

    /// Whether the cycle reads a dwell P at all.
    pub fn dwells(self) -> bool {
        !matches!(self, CycleKind::Drill | CycleKind::Peck | CycleKind::ChipBreak)
    }

    /// Whether the tool feeds back out to R (tapping and G85/G89 boring).
    fn feeds_out(self) -> bool {
        matches!(self, CycleKind::Tap | CycleKind::LeftTap | CycleKind::Bore | CycleKind::BoreDwell)
    }
}

/// One hole of a cycle, all lengths absolute, mm.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Hole {
    pub kind: CycleKind,
    pub x_mm: f64,
    pub y_mm: f64,
    /// Z of the bottom of the hole (the Z word).
    pub bottom_z_mm: f64,
    /// Z of the retract (R) plane.
    pub r_plane_mm: f64,
    /// The dwell at the bottom, s (0: none).
    pub dwell_s: f64,
    /// G83's and G73's peck depth (Q), > 0.
    pub peck_mm: f64,
    /// G99: retract to R; G98: to the clearance height.
    pub retract_to_r: bool,
}

/// One step of an expanded cycle.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Step {
    Rapid(P3),
    Feed(P3),
    Dwell { seconds: f64 },
}

/// The depths a pecking cycle feeds to before the bottom.
fn peck_depths(hole: &Hole) -> Result<Vec<f64>, String> {
    if !hole.kind.pecks() {
        return Ok(Vec::new());
    }
    let (r, bottom) = (hole.r_plane_mm, hole.bottom_z_mm);
    if hole.peck_mm <= 0.0 {
        return Err("the peck depth Q must be > 0".to_string());
    }
    let pecks = ((r - bottom) / hole.peck_mm).ceil();
    if pecks > f64::from(MAX_PECKS_PER_HOLE) {
        return Err(format!("Q {} mm would make {pecks} pecks (at most {MAX_PECKS_PER_HOLE})", hole.peck_mm));
    }
    Ok((1..pecks as u32)
        .map(|k| r - f64::from(k) * hole.peck_mm)
        .take_while(|&depth| depth > bottom + LENGTH_EPS_MM)
        .collect())
}

/// Expands one hole drilled from `from` into `steps` (cleared first). Returns the reason
/// if the hole cannot be drilled (R plane below the bottom, Q ≤ 0, too many pecks).
pub(crate) fn expand_hole(from: P3, hole: &Hole, steps: &mut Vec<Step>) -> Result<(), String> {
    steps.clear();
    let (x, y, r, bottom) = (hole.x_mm, hole.y_mm, hole.r_plane_mm, hole.bottom_z_mm);
    if r < bottom {
        return Err(format!("the R plane ({r} mm) is below the bottom of the hole (Z {bottom} mm)"));
    }
    let depths = peck_depths(hole)?;
    let mut clearance = from.z;
    if from.z < r {
        steps.push(Step::Rapid(P3::new(from.x, from.y, r)));
        clearance = r;
    }
    let at = |z: f64| P3::new(x, y, z);
    steps.push(Step::Rapid(at(clearance)));
    steps.push(Step::Rapid(at(r)));
    for &depth in &depths {
        steps.push(Step::Feed(at(depth)));
        if hole.kind == CycleKind::ChipBreak {
            steps.push(Step::Rapid(at(depth + G73_CHIP_BREAK_MM)));
        } else {
            steps.push(Step::Rapid(at(r)));
            steps.push(Step::Rapid(at(depth + G83_PECK_CLEARANCE_MM)));
        }
    }
    steps.push(Step::Feed(at(bottom)));
    if hole.dwell_s > 0.0 {
        steps.push(Step::Dwell { seconds: hole.dwell_s });
    }
    if hole.kind.feeds_out() {
        steps.push(Step::Feed(at(r)));
    }
    let retract = if hole.retract_to_r { r } else { clearance };
    steps.push(Step::Rapid(at(retract)));
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn hole(kind: CycleKind) -> Hole {
        Hole {
            kind,
            x_mm: 10.0,
            y_mm: 20.0,
            bottom_z_mm: -5.0,
            r_plane_mm: 2.0,
            dwell_s: if kind.dwells() { 0.5 } else { 0.0 },
            peck_mm: 3.0,
            retract_to_r: false,
        }
    }

    fn steps(from: P3, hole: &Hole) -> Vec<Step> {
        let mut steps = Vec::new();
        expand_hole(from, hole, &mut steps).unwrap();
        steps
    }

    #[test]
    fn a_drill_from_above_goes_over_down_to_r_feeds_and_returns_to_the_start_height() {
        let s = steps(P3::new(0.0, 0.0, 10.0), &hole(CycleKind::Drill));
        let at = |z| P3::new(10.0, 20.0, z);
        assert_eq!(s, vec![Step::Rapid(at(10.0)), Step::Rapid(at(2.0)), Step::Feed(at(-5.0)), Step::Rapid(at(10.0))]);
    }

    #[test]
    fn a_tool_below_r_first_rises_to_r_which_becomes_the_clearance_height() {
        let s = steps(P3::new(0.0, 0.0, 1.0), &hole(CycleKind::Drill));
        assert_eq!(s[0], Step::Rapid(P3::new(0.0, 0.0, 2.0)));
        assert_eq!(*s.last().unwrap(), Step::Rapid(P3::new(10.0, 20.0, 2.0)));
    }

    #[test]
    fn g82_dwells_at_the_bottom_and_g99_retracts_to_r() {
        let mut h = hole(CycleKind::DwellAtBottom);
        h.retract_to_r = true;
        let s = steps(P3::new(0.0, 0.0, 10.0), &h);
        assert_eq!(s[3], Step::Dwell { seconds: 0.5 });
        assert_eq!(s[4], Step::Rapid(P3::new(10.0, 20.0, 2.0)));
    }

    #[test]
    fn g83_pecks_by_q_with_rapid_retracts_to_r_and_back_above_the_last_depth() {
        // R 2, bottom -5, Q 3: pecks to -1 and -4, then the bottom.
        let s = steps(P3::new(10.0, 20.0, 2.0), &hole(CycleKind::Peck));
        let at = |z| P3::new(10.0, 20.0, z);
        let c = G83_PECK_CLEARANCE_MM;
        assert_eq!(
            s,
            vec![
                Step::Rapid(at(2.0)),
                Step::Rapid(at(2.0)),
                Step::Feed(at(-1.0)),
                Step::Rapid(at(2.0)),
                Step::Rapid(at(-1.0 + c)),
                Step::Feed(at(-4.0)),
                Step::Rapid(at(2.0)),
                Step::Rapid(at(-4.0 + c)),
                Step::Feed(at(-5.0)),
                Step::Rapid(at(2.0)),
            ]
        );
    }

    #[test]
    fn a_bad_r_plane_or_peck_is_refused() {
        let mut steps = Vec::new();
        let mut h = hole(CycleKind::Peck);
        h.peck_mm = 0.0;
        assert!(expand_hole(P3::default(), &h, &mut steps).is_err());
        h.peck_mm = 1e-6;
        assert!(expand_hole(P3::default(), &h, &mut steps).is_err());
        let mut h = hole(CycleKind::Drill);
        h.r_plane_mm = -6.0;
        assert!(expand_hole(P3::default(), &h, &mut steps).is_err());
    }

    mod in_gcode {
        //! Canned cycles as G-code writes them.

        use crate::core::nc::{parse_gcode, CannedCycles, ParseOptions, G83_PECK_CLEARANCE_MM};
        use crate::core::tolerance::approx_eq;
        use crate::core::toolpath::{EventKind, Motion, Toolpath, P3};

        /// Coordinates here are short decimals: results match to rounding.
        const TOL_MM: f64 = 1e-9;

        fn parse(text: &str) -> Toolpath {
            parse_gcode(text, &ParseOptions::default()).unwrap_or_else(|e| panic!("{e}"))
        }

        /// (rapid?, end) of each move.
        fn path_of(path: &Toolpath) -> Vec<(bool, P3)> {
            path.moves.iter().map(|m| (m.motion == Motion::Rapid, m.end)).collect()
        }

        fn same(a: &[(bool, P3)], b: &[(bool, P3)]) -> bool {
            a.len() == b.len()
                && a.iter().zip(b).all(|((ra, pa), (rb, pb))| {
                    ra == rb
                        && approx_eq(pa.x, pb.x, TOL_MM)
                        && approx_eq(pa.y, pb.y, TOL_MM)
                        && approx_eq(pa.z, pb.z, TOL_MM)
                })
        }

        const RAPID: bool = true;
        const FEED: bool = false;

        #[test]
        fn g81_is_expanded_and_repeats_at_each_following_xy_until_g80() {
            let path = parse("G0 X0 Y0 Z10\nG81 X10 Y20 Z-5 R2 F100\nX30\nG80\nG0 Z20");
            let p = |x, y, z| P3::new(x, y, z);
            let expected = [
                (RAPID, p(0.0, 0.0, 10.0)),
                (RAPID, p(10.0, 20.0, 10.0)),
                (RAPID, p(10.0, 20.0, 2.0)),
                (FEED, p(10.0, 20.0, -5.0)),
                (RAPID, p(10.0, 20.0, 10.0)),
                (RAPID, p(30.0, 20.0, 10.0)),
                (RAPID, p(30.0, 20.0, 2.0)),
                (FEED, p(30.0, 20.0, -5.0)),
                (RAPID, p(30.0, 20.0, 10.0)),
                (RAPID, p(30.0, 20.0, 20.0)),
            ];
            assert!(same(&path_of(&path), &expected), "{:?}", path_of(&path));
            assert_eq!(path.moves[3].line, 2);
            assert_eq!(path.moves[7].line, 3);
        }

        #[test]
        fn g99_retracts_to_r_and_g98_to_the_starting_height() {
            let path = parse("G0 Z10\nG99 G81 X1 Y1 Z-5 R2 F100\nX2");
            // G99: the second hole starts from R and the tool stays at R.
            let last = path.moves.last().unwrap();
            assert!(approx_eq(last.end.z, 2.0, TOL_MM) && approx_eq(last.end.x, 2.0, TOL_MM));
            let path = parse("G0 Z10\nG98 G81 X1 Y1 Z-5 R2 F100\nX2");
            assert!(approx_eq(path.moves.last().unwrap().end.z, 10.0, TOL_MM));
        }

        #[test]
        fn g82_dwells_at_the_bottom_of_each_hole() {
            let path = parse("G0 Z10\nG82 X1 Y1 Z-5 R2 P0.25 F100\nX2");
            let dwells: Vec<_> = path.events.iter().map(|e| (e.kind, e.before_move)).collect();
            let dwell = EventKind::Dwell { seconds: 0.25 };
            // Moves: Z10, hole 1 (over, down to R, feed, up), hole 2 (over, R, feed, up).
            assert_eq!(dwells, [(dwell, 4), (dwell, 8)]);
            assert!(approx_eq(path.moves[3].end.z, -5.0, TOL_MM));
        }

        #[test]
        fn g83_pecks_by_q_and_keeps_q_for_the_next_hole() {
            let path = parse("G0 Z10\nG83 X1 Y1 Z-5 R2 Q3 F100\nX2");
            let feeds: Vec<f64> = path.moves.iter().filter(|m| m.motion == Motion::Linear).map(|m| m.end.z).collect();
            let expected = [-1.0, -4.0, -5.0, -1.0, -4.0, -5.0];
            assert_eq!(feeds.len(), expected.len());
            assert!(feeds.iter().zip(expected).all(|(a, b)| approx_eq(*a, b, TOL_MM)));
            let back_down = path.moves[5].end.z;
            assert!(approx_eq(back_down, -1.0 + G83_PECK_CLEARANCE_MM, TOL_MM));
        }

        #[test]
        fn cycles_are_refused_when_asked_naming_the_line() {
            let options = ParseOptions { canned_cycles: CannedCycles::Refuse, ..ParseOptions::default() };
            let e = parse_gcode("G0 Z10\nG81 X1 Y1 Z-5 R2 F100", &options).unwrap_err().0;
            assert_eq!((e[0].line, e[0].word.as_str()), (2, "G81"));
            assert_eq!(e[0].reason, "canned cycles are not expanded: send the moves, or let the service expand them");
        }

        #[test]
        fn bad_cycles_are_errors() {
            let error = |text: &str| parse_gcode(text, &ParseOptions::default()).unwrap_err().to_string();
            assert!(error("G81 X1 Y1 Z-5 F100").contains("needs R"));
            assert!(error("G81 X1 Y1 R2 F100").contains("needs Z"));
            assert!(error("G83 X1 Y1 Z-5 R2 F100").contains("needs Q"));
            assert!(error("G82 X1 Y1 Z-5 R2 F100").contains("needs P"));
            assert!(error("G81 X1 Y1 Z-5 R-6 F100").contains("below the bottom"));
            assert!(error("G18 G81 X1 Y1 Z-5 R2 F100").contains("XY plane"));
        }
    }
}
