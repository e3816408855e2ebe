//! The G and M codes the interpreter reads, in their modal groups (LinuxCNC's groups,
//! with the Fanuc codes of 3-axis milling added), and the ones it refuses with a reason.

use super::canned::CycleKind;
use super::map::FeedMode;
use crate::core::toolpath::{Plane, Units};

/// Which way a motion-group code moves the tool.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum MotionCode {
    Rapid,
    Linear,
    Arc { clockwise: bool },
    Cycle(CycleKind),
}

/// Cutter radius compensation codes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum CompCode {
    /// G40.
    Off,
    /// G41 (`left`) / G42: D names a tool-table entry (or the current tool).
    Table { left: bool },
    /// G41.1 / G42.1 (LinuxCNC): D is the tool diameter.
    Diameter { left: bool },
}

/// Tool length offset codes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum LengthCode {
    /// G43 (H, or the current tool).
    Offset,
    /// G44 (Fanuc): the offset subtracted.
    Negative,
    /// G43.1 (LinuxCNC): the offset given in Z.
    Dynamic,
    /// G49.
    Off,
}

/// G92 and G52: an offset added to every work coordinate system.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum AxisOffsetCode {
    /// G92: the current position gets the given coordinates.
    Set,
    /// G92.1: the offset is cleared.
    Clear,
    /// G92.2: the offset is suspended (kept for G92.3).
    Suspend,
    /// G92.3: the suspended offset applies again.
    Restore,
    /// G52: the offset is the given values.
    Local,
}

/// A G code this interpreter knows.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum GCode {
    Motion(MotionCode),
    /// G80.
    CancelCycle,
    /// G4.
    Dwell,
    Plane(Plane),
    Units(Units),
    /// G90 / G91.
    Distance {
        absolute: bool,
    },
    /// G90.1 / G91.1.
    ArcDistance {
        absolute: bool,
    },
    /// G98 (false) / G99 (true).
    RetractToR(bool),
    FeedMode(FeedMode),
    CutterComp(CompCode),
    ToolLength(LengthCode),
    /// G54 (0) … G59.3 (8).
    CoordinateSystem(u8),
    /// Fanuc G54.1 P1…P300: an extended work coordinate system.
    ExtendedCoordinates,
    /// G53: this line's motion is in machine coordinates.
    MachineCoordinates,
    /// G28 (false) / G30 (true): go home through an intermediate point.
    Home {
        secondary: bool,
    },
    /// G28.1 / G30.1: the home position is stored.
    SetHome,
    /// G10: tool table or work offsets.
    SetOffsets,
    AxisOffset(AxisOffsetCode),
    /// G64: reads P and Q (ignored, with a warning).
    Blending,
    /// Fanuc high-speed and look-ahead modes (G5 P, G5.1 Q, G8 P): they change how the
    /// control follows the path, not the path. In LinuxCNC, G5 and G5.1 are splines.
    HighSpeed {
        /// Ten times the code.
        code: u32,
    },
    /// G65: a Fanuc macro call (handled by the control flow).
    MacroCall,
    /// G96 (true) / G97.
    SpindleMode {
        surface_speed: bool,
    },
    /// Read, no effect on the path.
    NoOp,
}

/// An M code this interpreter knows.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum MCode {
    /// M0, M1, M60.
    Stop,
    /// M2, M30.
    End,
    /// M3 (`Some(true)`), M4 (`Some(false)`), M5 (`None`).
    Spindle(Option<bool>),
    /// M6.
    ToolChange,
    /// M7, M8 (on) or M9 (off).
    Coolant { on: bool },
    /// M98: call a subprogram (handled by the control flow).
    SubCall,
    /// M99: return from a subprogram (handled by the control flow).
    SubReturn,
    /// M70 save, M71 invalidate, M72 restore, M73 save and restore at return (LinuxCNC).
    ModalState(u8),
    /// Known auxiliary functions that move nothing (M19 orient, M48–M53 overrides, M61
    /// tool number, M62–M68 I/O, M100–M199 user codes).
    Auxiliary,
}

/// Modal groups: two codes of one group cannot share a line.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Group {
    /// G4, G10, G28, G30, G52, G53, G65, G92.
    NonModal,
    Motion,
    Plane,
    Distance,
    ArcDistance,
    FeedMode,
    Units,
    CutterCompensation,
    ToolLength,
    Retract,
    Coordinates,
    PathControl,
    /// G80 (its own group, so that `G80 G0 …` is accepted as Fanuc posts write it).
    CancelCycle,
    /// G15 (polar coordinates off).
    Polar,
    /// G69 (rotation off), G50 (scaling off), G50.1 (mirror off).
    Transform,
    SpindleMode,
    HighSpeed,
    Stop,
    ToolChange,
    Spindle,
    Coolant,
    SubProgram,
    ModalState,
    Auxiliary,
}

/// What a code is: known (with its modal group), refused (with the reason) or unknown.
pub(crate) enum Class<T> {
    Known(T, Group),
    Refused(&'static str),
    Unknown,
}

const PROBING: &str = "probing (G38.x) stops where the probe touches: the planner cannot know where";
const LATHE: &str = "lathe codes (G7, G8, G33, G76 threading) are not milling moves";
const TRANSFORMS: &str = "scaling, mirroring and coordinate rotation (G51, G51.1, G68) are not supported: send the \
     program with the transformation applied";
const FIVE_AXIS: &str = "tilted planes and tool-centre-point control (G43.4, G68.2) are 5-axis functions: dieplan \
     plans 3-axis milling";
const POLAR_FANUC: &str = "Fanuc polar coordinates (G16) are not supported: send X and Y, or LinuxCNC's @ and ^ words";
const OTHER_PLANES: &str = "the UVW planes (G17.1, G18.1, G19.1) need secondary axes: dieplan plans 3-axis milling";
pub(crate) const SPLINES: &str = "splines and NURBS (G5, G5.1, G5.2) are not supported: send them as lines and arcs";
const OTHER_CYCLES: &str = "back boring (G87) and manual-retract boring (G88) need an operator: they cannot be planned";

/// The class of G code `code` (ten times its number).
pub(crate) fn classify_g(code: u32) -> Class<GCode> {
    use Class::{Known, Refused};
    use GCode as G;
    use Group as K;
    let cycle = |kind| Known(G::Motion(MotionCode::Cycle(kind)), K::Motion);
    match code {
        0 => Known(G::Motion(MotionCode::Rapid), K::Motion),
        10 => Known(G::Motion(MotionCode::Linear), K::Motion),
        20 => Known(G::Motion(MotionCode::Arc { clockwise: true }), K::Motion),
        30 => Known(G::Motion(MotionCode::Arc { clockwise: false }), K::Motion),
        730 => cycle(CycleKind::ChipBreak),
        740 => cycle(CycleKind::LeftTap),
        760 => cycle(CycleKind::FineBore),
        810 => cycle(CycleKind::Drill),
        820 => cycle(CycleKind::DwellAtBottom),
        830 => cycle(CycleKind::Peck),
        840 => cycle(CycleKind::Tap),
        850 => cycle(CycleKind::Bore),
        860 => cycle(CycleKind::BoreSpindleStop),
        890 => cycle(CycleKind::BoreDwell),
        870 | 880 => Refused(OTHER_CYCLES),
        40 => Known(G::Dwell, K::NonModal),
        50 | 51 | 80 => Known(G::HighSpeed { code }, K::HighSpeed),
        52 | 53 => Refused(SPLINES),
        70 | 71 | 330 | 331 => Refused(LATHE),
        100 => Known(G::SetOffsets, K::NonModal),
        150 => Known(G::NoOp, K::Polar),
        160 => Refused(POLAR_FANUC),
        170 => Known(G::Plane(Plane::Xy), K::Plane),
        180 => Known(G::Plane(Plane::Zx), K::Plane),
        190 => Known(G::Plane(Plane::Yz), K::Plane),
        171 | 181 | 191 => Refused(OTHER_PLANES),
        200 => Known(G::Units(Units::Inch), K::Units),
        210 => Known(G::Units(Units::Mm), K::Units),
        280 => Known(G::Home { secondary: false }, K::NonModal),
        300 => Known(G::Home { secondary: true }, K::NonModal),
        281 | 301 => Known(G::SetHome, K::NonModal),
        382..=385 => Refused(PROBING),
        400 => Known(G::CutterComp(CompCode::Off), K::CutterCompensation),
        410 => Known(G::CutterComp(CompCode::Table { left: true }), K::CutterCompensation),
        420 => Known(G::CutterComp(CompCode::Table { left: false }), K::CutterCompensation),
        411 => Known(G::CutterComp(CompCode::Diameter { left: true }), K::CutterCompensation),
        421 => Known(G::CutterComp(CompCode::Diameter { left: false }), K::CutterCompensation),
        430 => Known(G::ToolLength(LengthCode::Offset), K::ToolLength),
        431 => Known(G::ToolLength(LengthCode::Dynamic), K::ToolLength),
        440 => Known(G::ToolLength(LengthCode::Negative), K::ToolLength),
        490 => Known(G::ToolLength(LengthCode::Off), K::ToolLength),
        434 | 682 => Refused(FIVE_AXIS),
        500 | 690 | 501 => Known(G::NoOp, K::Transform),
        510 | 511 | 680 => Refused(TRANSFORMS),
        520 => Known(G::AxisOffset(AxisOffsetCode::Local), K::NonModal),
        530 => Known(G::MachineCoordinates, K::NonModal),
        540 => Known(G::CoordinateSystem(0), K::Coordinates),
        550 => Known(G::CoordinateSystem(1), K::Coordinates),
        560 => Known(G::CoordinateSystem(2), K::Coordinates),
        570 => Known(G::CoordinateSystem(3), K::Coordinates),
        580 => Known(G::CoordinateSystem(4), K::Coordinates),
        590 => Known(G::CoordinateSystem(5), K::Coordinates),
        591 => Known(G::CoordinateSystem(6), K::Coordinates),
        592 => Known(G::CoordinateSystem(7), K::Coordinates),
        593 => Known(G::CoordinateSystem(8), K::Coordinates),
        541 => Known(G::ExtendedCoordinates, K::Coordinates),
        610 | 611 => Known(G::NoOp, K::PathControl),
        640 => Known(G::Blending, K::PathControl),
        650 => Known(G::MacroCall, K::NonModal),
        800 => Known(G::CancelCycle, K::CancelCycle),
        900 => Known(G::Distance { absolute: true }, K::Distance),
        910 => Known(G::Distance { absolute: false }, K::Distance),
        901 => Known(G::ArcDistance { absolute: true }, K::ArcDistance),
        911 => Known(G::ArcDistance { absolute: false }, K::ArcDistance),
        920 => Known(G::AxisOffset(AxisOffsetCode::Set), K::NonModal),
        921 => Known(G::AxisOffset(AxisOffsetCode::Clear), K::NonModal),
        922 => Known(G::AxisOffset(AxisOffsetCode::Suspend), K::NonModal),
        923 => Known(G::AxisOffset(AxisOffsetCode::Restore), K::NonModal),
        930 => Known(G::FeedMode(FeedMode::InverseTime), K::FeedMode),
        940 => Known(G::FeedMode(FeedMode::PerMinute), K::FeedMode),
        950 => Known(G::FeedMode(FeedMode::PerRevolution), K::FeedMode),
        960 => Known(G::SpindleMode { surface_speed: true }, K::SpindleMode),
        970 => Known(G::SpindleMode { surface_speed: false }, K::SpindleMode),
        980 => Known(G::RetractToR(false), K::Retract),
        990 => Known(G::RetractToR(true), K::Retract),
        _ => Class::Unknown,
    }
}

/// The class of M code `code` (ten times its number).
pub(crate) fn classify_m(code: u32) -> Class<MCode> {
    use Class::Known;
    match code {
        0 | 10 | 600 => Known(MCode::Stop, Group::Stop),
        20 | 300 => Known(MCode::End, Group::Stop),
        30 => Known(MCode::Spindle(Some(true)), Group::Spindle),
        40 => Known(MCode::Spindle(Some(false)), Group::Spindle),
        50 => Known(MCode::Spindle(None), Group::Spindle),
        60 => Known(MCode::ToolChange, Group::ToolChange),
        70 | 80 => Known(MCode::Coolant { on: true }, Group::Coolant),
        90 => Known(MCode::Coolant { on: false }, Group::Coolant),
        980 => Known(MCode::SubCall, Group::SubProgram),
        990 => Known(MCode::SubReturn, Group::SubProgram),
        700 | 710 | 720 | 730 => Known(MCode::ModalState((code / 10 - 70) as u8), Group::ModalState),
        190 | 480..=530 | 610..=680 | 1000..=1990 if code.is_multiple_of(10) => {
            Known(MCode::Auxiliary, Group::Auxiliary)
        }
        _ => Class::Unknown,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn group(code: u32) -> Group {
        match classify_g(code) {
            Class::Known(_, group) => group,
            _ => panic!("G{} is not known", f64::from(code) / 10.0),
        }
    }

    #[test]
    fn g80_has_its_own_group_so_fanuc_style_g80_g0_lines_are_accepted() {
        assert_ne!(group(800), group(0));
        assert_eq!(group(810), group(0));
        assert_eq!(group(901), Group::ArcDistance);
        assert_eq!(group(530), Group::NonModal);
        assert_eq!(group(410), Group::CutterCompensation);
        assert!(matches!(classify_g(382), Class::Refused(_)));
        assert!(matches!(classify_g(1870), Class::Unknown));
    }

    #[test]
    fn m_codes_of_subprograms_modal_state_and_auxiliary_functions_are_known() {
        assert!(matches!(classify_m(980), Class::Known(MCode::SubCall, _)));
        assert!(matches!(classify_m(720), Class::Known(MCode::ModalState(2), _)));
        assert!(matches!(classify_m(1230), Class::Known(MCode::Auxiliary, _)));
        assert!(matches!(classify_m(190), Class::Known(MCode::Auxiliary, _)));
        assert!(matches!(classify_m(880), Class::Unknown));
    }
}
