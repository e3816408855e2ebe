//! Cutter radius compensation (G41 left, G42 right of the direction of travel): the
//! programmed contour in, the tool-centre path out, as the controls make it.
//!
//! - **Lead-in.** The first XY move after G41/G42 must be a straight line (both controls
//!   refuse an arc there). LinuxCNC ends it where the tool, coming straight from where it
//!   is, first touches the circle of the tool radius about the programmed end (the line is
//!   tangent to the tool there; it must be longer than the radius). Fanuc (start-up type
//!   A) ends it one tool radius from the programmed end, square to the *next* move.
//! - **Corners.** Each move is offset by the radius (lines parallel, arcs concentric, a
//!   concave arc smaller than the tool is refused). Where two moves meet at a convex
//!   corner the tool goes round it on an arc about the corner; at a concave corner both
//!   offset moves are cut back to where they meet, and a move too short for that gouges:
//!   an error naming its line, as the controls stop there.
//! - **Lead-out.** The last compensated move ends one radius square to its end; the move
//!   after G40 goes straight from there (it must be a line).
//! - Moves in Z alone keep the tool where it is; a rapid goes straight from corner to
//!   corner (no arc), as LinuxCNC does.
//!
//! One move is held back until the next shows how its corner is cut, so moves come out one
//! move late; [`Compensation::finish`] lets the last one go.

use crate::core::toolpath::arc_sweep;
use crate::core::toolpath::{Motion, Move, Plane, P3};
use std::f64::consts::PI;

/// Corners whose directions differ by less than this are tangent: no arc, no trimming,
/// rad.
const TANGENT_RAD: f64 = 1e-6;

/// A move shorter than this in XY moves in Z alone, mm.
const XY_EPS_MM: f64 = 1e-9;

/// Slack of the gouging checks, mm (rounding of the programmed coordinates).
const GOUGE_SLACK_MM: f64 = 1e-6;

/// Which side of the contour the tool runs on.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Side {
    Left,
    Right,
}

/// How the lead-in move ends.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum StartUp {
    /// LinuxCNC: tangent to the tool circle about the programmed end.
    LinuxCnc,
    /// Fanuc start-up type A: square to the next move at its start.
    Fanuc,
}

type V2 = (f64, f64);

fn sub(a: V2, b: V2) -> V2 {
    (a.0 - b.0, a.1 - b.1)
}

fn add(a: V2, b: V2) -> V2 {
    (a.0 + b.0, a.1 + b.1)
}

fn scale(a: V2, k: f64) -> V2 {
    (a.0 * k, a.1 * k)
}

fn dot(a: V2, b: V2) -> f64 {
    a.0 * b.0 + a.1 * b.1
}

fn cross(a: V2, b: V2) -> f64 {
    a.0 * b.1 - a.1 * b.0
}

fn norm(a: V2) -> f64 {
    a.0.hypot(a.1)
}

fn unit(a: V2) -> V2 {
    let n = norm(a);
    (a.0 / n, a.1 / n)
}

fn xy(p: P3) -> V2 {
    (p.x, p.y)
}

fn at(v: V2, z: f64) -> P3 {
    P3::new(v.0, v.1, z)
}

/// The curve a move's tool centre follows.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Curve {
    Line,
    /// About `centre`, at `radius` (the offset radius).
    Arc {
        centre: V2,
        radius: f64,
        clockwise: bool,
        turns: u32,
    },
}

/// A contour move and its offset, waiting for its end corner.
#[derive(Debug, Clone, Copy)]
struct Pending {
    contour: Move,
    curve: Curve,
    /// Its end tangent (unit).
    end_dir: V2,
    /// The tool centre square to its end.
    end: V2,
    /// A Fanuc lead-in, which ends square to the next move.
    fanuc_lead_in: bool,
}

/// The compensation of one G41/G42 stretch.
#[derive(Debug, Clone)]
pub(crate) struct Compensation {
    side: Side,
    radius: f64,
    startup: StartUp,
    /// Where the tool centre is (the end of the last move let go).
    tool: P3,
    pending: Option<Pending>,
    /// Z moves behind `pending`.
    held: Vec<Move>,
}

impl Compensation {
    /// Compensation by `radius_mm` on `side`, the tool centre now at `tool`.
    pub fn new(side: Side, radius_mm: f64, startup: StartUp, tool: P3) -> Self {
        Compensation { side, radius: radius_mm, startup, tool, pending: None, held: Vec::new() }
    }

    /// The unit normal towards the tool side of direction `t`.
    fn normal(&self, t: V2) -> V2 {
        match self.side {
            Side::Left => (-t.1, t.0),
            Side::Right => (t.1, -t.0),
        }
    }

    /// Takes the next contour move (XY plane); finished moves go to `out`.
    pub fn push(&mut self, m: Move, out: &mut Vec<Move>) -> Result<(), String> {
        let arc = matches!(m.motion, Motion::Arc { .. });
        if let Motion::Arc { plane, .. } = m.motion {
            if plane != Plane::Xy {
                return Err("cutter compensation works in the XY plane (G17) only".to_string());
            }
        }
        if !arc && norm(sub(xy(m.end), xy(m.start))) < XY_EPS_MM {
            match self.pending {
                Some(_) => self.held.push(m),
                None => self.emit(m, xy(self.tool), out),
            }
            return Ok(());
        }
        let (curve, start_dir, end_dir) = self.offset_curve(&m)?;
        let start = add(xy(m.start), scale(self.normal(start_dir), self.radius));
        let end = add(xy(m.end), scale(self.normal(end_dir), self.radius));
        let Some(prev) = self.pending.take() else {
            return self.lead_in(m, curve, end_dir, end);
        };
        if prev.fanuc_lead_in {
            // Fanuc type A: the lead-in ends square to this move, where it starts.
            self.let_go(&prev, start, out)?;
        } else {
            self.corner(&prev, &m, curve, start_dir, start, out)?;
        }
        self.pending = Some(Pending { contour: m, curve, end_dir, end, fanuc_lead_in: false });
        Ok(())
    }

    /// The offset curve of a contour move, with its start and end tangents.
    fn offset_curve(&self, m: &Move) -> Result<(Curve, V2, V2), String> {
        match m.motion {
            Motion::Rapid | Motion::Linear => {
                let t = unit(sub(xy(m.end), xy(m.start)));
                Ok((Curve::Line, t, t))
            }
            Motion::Arc { center, clockwise, turns, .. } => {
                let c = xy(center);
                let r = norm(sub(xy(m.start), c));
                let tangent = |p: V2| {
                    let u = unit(sub(p, c));
                    if clockwise {
                        (u.1, -u.0)
                    } else {
                        (-u.1, u.0)
                    }
                };
                let (ts, te) = (tangent(xy(m.start)), tangent(xy(m.end)));
                // The tool side's normal points at the centre: the tool runs inside.
                let inside = dot(self.normal(ts), sub(c, xy(m.start))) > 0.0;
                let radius = if inside { r - self.radius } else { r + self.radius };
                if radius <= GOUGE_SLACK_MM {
                    return Err(format!(
                        "the arc's radius ({r:.4} mm) is not larger than the tool radius ({:.4} mm): the tool cannot follow it",
                        self.radius
                    ));
                }
                Ok((Curve::Arc { centre: c, radius, clockwise, turns }, ts, te))
            }
        }
    }

    /// The first XY move after G41/G42.
    fn lead_in(&mut self, m: Move, curve: Curve, end_dir: V2, square_end: V2) -> Result<(), String> {
        if curve != Curve::Line {
            return Err(
                "the move that starts cutter compensation must be a straight line (a lead-in), not an arc".into()
            );
        }
        let from = xy(self.tool);
        let to = xy(m.end);
        let d = norm(sub(to, from));
        if self.startup == StartUp::Fanuc {
            let pending = Pending { contour: m, curve, end_dir, end: square_end, fanuc_lead_in: true };
            self.pending = Some(pending);
            return Ok(());
        }
        if d <= self.radius + GOUGE_SLACK_MM {
            return Err(format!(
                "the lead-in move is not longer than the tool radius ({:.4} mm): the tool would gouge the contour",
                self.radius
            ));
        }
        // The tangent from `from` to the circle of the tool radius about `to`.
        let theta = (self.radius / d).acos();
        let back = sub(from, to);
        let base = back.1.atan2(back.0);
        let alpha = if self.side == Side::Left { base - theta } else { base + theta };
        let end = add(to, (self.radius * alpha.cos(), self.radius * alpha.sin()));
        let dir = unit(sub(end, from));
        self.pending = Some(Pending { contour: m, curve, end_dir: dir, end, fanuc_lead_in: false });
        Ok(())
    }

    /// Cuts the corner between `prev` and the contour move `m`: the tool ends where `m`'s
    /// tool centre starts.
    fn corner(
        &mut self,
        prev: &Pending,
        m: &Move,
        curve: Curve,
        start_dir: V2,
        start: V2,
        out: &mut Vec<Move>,
    ) -> Result<(), String> {
        let (t1, t2) = (prev.end_dir, start_dir);
        let turn = cross(t1, t2);
        let angle = turn.atan2(dot(t1, t2));
        let towards_tool = match self.side {
            Side::Left => angle,
            Side::Right => -angle,
        };
        if towards_tool.abs() < TANGENT_RAD {
            return self.let_go(prev, prev.end, out);
        }
        let convex = towards_tool < 0.0 || (PI - towards_tool.abs()).abs() < TANGENT_RAD;
        if convex {
            self.let_go(prev, prev.end, out)?;
            let corner = xy(m.start);
            let z = self.tool.z;
            let rapid = matches!(m.motion, Motion::Rapid);
            let motion = if rapid {
                Motion::Rapid
            } else {
                let clockwise = self.side == Side::Left;
                Motion::Arc { center: at(corner, z), clockwise, plane: Plane::Xy, turns: 0 }
            };
            let arc = Move { motion, start: self.tool, end: at(start, z), ..*m };
            self.tool = arc.end;
            out.push(arc);
            return Ok(());
        }
        let prev_geom = Geom::of(prev.curve, prev.end, prev.end_dir);
        let hit = meet(prev_geom, Geom::of(curve, start, start_dir), xy(m.start)).ok_or_else(|| {
            format!(
                "the tool (radius {:.4} mm) does not fit the concave corner where this move starts: its offset never meets the one before",
                self.radius
            )
        })?;
        self.let_go(prev, hit, out)
    }

    /// Emits `p`'s offset move ending at `end`, then the Z moves held behind it.
    fn let_go(&mut self, p: &Pending, end: V2, out: &mut Vec<Move>) -> Result<(), String> {
        let start = xy(self.tool);
        let motion = match p.curve {
            Curve::Line => {
                // Cut back past its own start, the move would run backwards.
                if !p.fanuc_lead_in && dot(sub(end, start), p.end_dir) < -GOUGE_SLACK_MM {
                    return Err(self.gouge(&p.contour));
                }
                p.contour.motion
            }
            Curve::Arc { centre, radius, clockwise, turns } => {
                let (cs, ce) = (xy(p.contour.start), xy(p.contour.end));
                let full = arc_sweep((cs.0, cs.1, 0.0), (ce.0, ce.1, 0.0), (centre.0, centre.1, 0.0), clockwise, turns);
                let trimmed = arc_sweep(
                    (start.0, start.1, 0.0),
                    (end.0, end.1, 0.0),
                    (centre.0, centre.1, 0.0),
                    clockwise,
                    turns,
                );
                if trimmed.abs() > full.abs() + GOUGE_SLACK_MM / radius {
                    return Err(self.gouge(&p.contour));
                }
                Motion::Arc { center: at(centre, self.tool.z), clockwise, plane: Plane::Xy, turns }
            }
        };
        let m = Move { motion, start: self.tool, end: at(end, p.contour.end.z), ..p.contour };
        self.tool = m.end;
        out.push(m);
        for held in std::mem::take(&mut self.held) {
            self.emit(held, end, out);
        }
        Ok(())
    }

    fn gouge(&self, m: &Move) -> String {
        format!(
            "the move on line {} is too short for the tool (radius {:.4} mm) at its concave corner: the tool would gouge",
            m.line, self.radius
        )
    }

    /// Emits a move in Z alone at XY `at_xy`.
    fn emit(&mut self, m: Move, at_xy: V2, out: &mut Vec<Move>) {
        let moved = Move { start: self.tool, end: at(at_xy, m.end.z), ..m };
        self.tool = moved.end;
        out.push(moved);
    }

    /// Ends the compensation (G40, or the end of the program): the last move ends square
    /// to its end. Returns where the tool centre is.
    pub fn finish(&mut self, out: &mut Vec<Move>) -> Result<P3, String> {
        if let Some(p) = self.pending.take() {
            self.let_go(&p, p.end, out)?;
        }
        for held in std::mem::take(&mut self.held) {
            let here = xy(self.tool);
            self.emit(held, here, out);
        }
        Ok(self.tool)
    }
}

/// An offset curve, for finding where two meet.
#[derive(Debug, Clone, Copy)]
enum Geom {
    /// Through a point, with a unit direction.
    Line(V2, V2),
    Circle(V2, f64),
}

impl Geom {
    fn of(curve: Curve, point: V2, dir: V2) -> Geom {
        match curve {
            Curve::Line => Geom::Line(point, dir),
            Curve::Arc { centre, radius, .. } => Geom::Circle(centre, radius),
        }
    }
}

/// Where two offset curves meet nearest the contour corner `corner`.
fn meet(a: Geom, b: Geom, corner: V2) -> Option<V2> {
    let candidates = match (a, b) {
        (Geom::Line(p1, d1), Geom::Line(p2, d2)) => {
            let den = cross(d1, d2);
            if den.abs() < f64::EPSILON {
                return None;
            }
            let s = cross(sub(p2, p1), d2) / den;
            vec![add(p1, scale(d1, s))]
        }
        (Geom::Line(p, d), Geom::Circle(c, r)) | (Geom::Circle(c, r), Geom::Line(p, d)) => line_circle(p, d, c, r),
        (Geom::Circle(c1, r1), Geom::Circle(c2, r2)) => circle_circle(c1, r1, c2, r2),
    };
    candidates.into_iter().min_by(|a, b| norm(sub(*a, corner)).total_cmp(&norm(sub(*b, corner))))
}

/// Where the line through `p` along unit `d` meets the circle about `c` of radius `r`.
fn line_circle(p: V2, d: V2, c: V2, r: f64) -> Vec<V2> {
    let f = sub(p, c);
    let b = dot(f, d);
    let disc = b * b - (dot(f, f) - r * r);
    if disc < 0.0 {
        return Vec::new();
    }
    let s = disc.sqrt();
    vec![add(p, scale(d, -b - s)), add(p, scale(d, -b + s))]
}

/// Where two circles meet.
fn circle_circle(c1: V2, r1: f64, c2: V2, r2: f64) -> Vec<V2> {
    let d = norm(sub(c2, c1));
    if d < XY_EPS_MM || d > r1 + r2 || d < (r1 - r2).abs() {
        return Vec::new();
    }
    let a = (r1 * r1 - r2 * r2 + d * d) / (2.0 * d);
    let h = (r1 * r1 - a * a).max(0.0).sqrt();
    let u = unit(sub(c2, c1));
    let m = add(c1, scale(u, a));
    let n = (-u.1, u.0);
    vec![add(m, scale(n, h)), add(m, scale(n, -h))]
}
