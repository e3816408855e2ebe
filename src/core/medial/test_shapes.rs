//! Shapes with known medial axes for the tests, and the measures the tests compare with.

use super::boundary::Boundary;
use super::MedialAxis;
use crate::core::geometry::{Loop, Pocket, Point, Vertex};

/// Points per parabola when an analytic axis is drawn as a polyline.
const PARABOLA_POINTS: usize = 2000;

/// The 60 × 40 rectangle with its corner at the origin, and its axis: the middle segment
/// (20, 20)–(40, 20) and the four diagonals into the corners.
pub fn rectangle() -> (Pocket, Vec<Vec<Point>>) {
    let pocket = Pocket::new(Loop::rectangle(0.0, 0.0, 60.0, 40.0), vec![]).unwrap();
    let (a, b) = (Point::new(20.0, 20.0), Point::new(40.0, 20.0));
    let axis = vec![
        vec![a, b],
        vec![a, Point::new(0.0, 0.0)],
        vec![a, Point::new(0.0, 40.0)],
        vec![b, Point::new(60.0, 0.0)],
        vec![b, Point::new(60.0, 40.0)],
    ];
    (pocket, axis)
}

/// A stadium `length` long and `width` wide along x from the origin (semicircular ends), and
/// its axis: the segment between the two ends' centres.
pub fn stadium(length: f64, width: f64) -> (Pocket, Vec<Vec<Point>>) {
    turned_stadium(length, width, 0.0, Point::new(0.0, 0.0))
}

/// The stadium of [`stadium`] turned by `angle_rad` about the origin, then moved by `shift`.
pub fn turned_stadium(length: f64, width: f64, angle_rad: f64, shift: Point) -> (Pocket, Vec<Vec<Point>>) {
    let r = 0.5 * width;
    let (sin, cos) = angle_rad.sin_cos();
    let place = |x: f64, y: f64| Point::new(shift.x + x * cos - y * sin, shift.y + x * sin + y * cos);
    let vertex = |x: f64, y: f64, bulge: f64| {
        let p = place(x, y);
        Vertex::new(p.x, p.y, bulge)
    };
    let outer = Loop::new(vec![
        vertex(r, 0.0, 0.0),
        vertex(length - r, 0.0, 1.0),
        vertex(length - r, width, 0.0),
        vertex(r, width, 1.0),
    ]);
    let pocket = Pocket::new(outer, vec![]).unwrap();
    (pocket, vec![vec![place(r, r), place(length - r, r)]])
}

/// The rounded rectangle of `border.dxf` (102 × 137, corner arcs of radius 10) and its axis:
/// the middle segment (51, 51)–(51, 86) and the diagonals to the arcs' centres.
pub fn border_dxf() -> (Pocket, Vec<Vec<Point>>) {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../shared/data/border.dxf");
    let text = std::fs::read_to_string(path).unwrap();
    let pocket =
        crate::core::geometry::pocket_from_loops(crate::core::geometry::loops_from_dxf(&text).unwrap()).unwrap();
    let (a, b) = (Point::new(51.0, 51.0), Point::new(51.0, 86.0));
    let axis = vec![
        vec![a, b],
        vec![a, Point::new(10.0, 10.0)],
        vec![a, Point::new(92.0, 10.0)],
        vec![b, Point::new(10.0, 127.0)],
        vec![b, Point::new(92.0, 127.0)],
    ];
    (pocket, axis)
}

/// The junction of the axis where a 90° corner's diagonal meets the parabola of a reflex
/// corner at distance `w` (leg width) along both sides: `t = w·√2 / (1 + √2)`.
fn elbow_junction(w: f64) -> f64 {
    w * 2f64.sqrt() / (1.0 + 2f64.sqrt())
}

/// The parabola of points equidistant from the line `y = 0` and the point `(w, w)`, for x from
/// `x0` to `w`, mapped through `map` (mm).
fn parabola(w: f64, x0: f64, map: impl Fn(Point) -> Point) -> Vec<Point> {
    (0..=PARABOLA_POINTS)
        .map(|k| {
            let x = x0 + (w - x0) * k as f64 / PARABOLA_POINTS as f64;
            map(Point::new(x, 0.5 * w + (x - w).powi(2) / (2.0 * w)))
        })
        .collect()
}

/// The L of legs 20 wide: (0,0)–(60,0)–(60,20)–(20,20)–(20,60)–(0,60), and its axis: a
/// junction on the diagonal of the outer corner, parabolas around the reflex corner (20, 20)
/// into the legs' centre lines, and two corner branches at each leg's end.
pub fn l_shape() -> (Pocket, Vec<Vec<Point>>) {
    let outer = Loop::new(
        [(0.0, 0.0), (60.0, 0.0), (60.0, 20.0), (20.0, 20.0), (20.0, 60.0), (0.0, 60.0)]
            .iter()
            .map(|&(x, y)| Vertex::new(x, y, 0.0))
            .collect(),
    );
    let pocket = Pocket::new(outer, vec![]).unwrap();
    let w = 20.0;
    let t = elbow_junction(w);
    let axis = vec![
        vec![Point::new(0.0, 0.0), Point::new(t, t)],
        parabola(w, t, |p| p),
        parabola(w, t, |p| Point::new(p.y, p.x)),
        vec![Point::new(20.0, 10.0), Point::new(50.0, 10.0)],
        vec![Point::new(10.0, 20.0), Point::new(10.0, 50.0)],
        vec![Point::new(50.0, 10.0), Point::new(60.0, 0.0)],
        vec![Point::new(50.0, 10.0), Point::new(60.0, 20.0)],
        vec![Point::new(10.0, 50.0), Point::new(0.0, 60.0)],
        vec![Point::new(10.0, 50.0), Point::new(20.0, 60.0)],
    ];
    (pocket, axis)
}

/// The square 60 × 60 with the square island 20 × 20 in its middle, and its axis: a cycle of
/// middle lines and parabolas around the island's corners, and a diagonal into each corner.
pub fn square_ring() -> (Pocket, Vec<Vec<Point>>) {
    let pocket =
        Pocket::new(Loop::rectangle(0.0, 0.0, 60.0, 60.0), vec![Loop::rectangle(20.0, 20.0, 40.0, 40.0)]).unwrap();
    let w = 20.0;
    let t = elbow_junction(w);
    let mut axis = Vec::new();
    // The eight symmetries of the square about its centre (30, 30).
    let maps: [fn(Point) -> Point; 8] = [
        |p| p,
        |p| Point::new(p.y, p.x),
        |p| Point::new(60.0 - p.x, p.y),
        |p| Point::new(p.y, 60.0 - p.x),
        |p| Point::new(p.x, 60.0 - p.y),
        |p| Point::new(60.0 - p.y, p.x),
        |p| Point::new(60.0 - p.x, 60.0 - p.y),
        |p| Point::new(60.0 - p.y, 60.0 - p.x),
    ];
    for map in maps {
        axis.push(vec![map(Point::new(0.0, 0.0)), map(Point::new(t, t))]);
        axis.push(parabola(w, t, map));
        axis.push(vec![map(Point::new(20.0, 10.0)), map(Point::new(30.0, 10.0))]);
    }
    (pocket, axis)
}

/// The disc of radius 30 with a circular island of radius 10 at its centre (the origin), and
/// its axis: the circle of radius 20 (as a fine polygon).
pub fn circle_ring() -> (Pocket, Vec<Vec<Point>>) {
    let pocket = Pocket::new(Loop::circle(0.0, 0.0, 30.0), vec![Loop::circle(0.0, 0.0, 10.0)]).unwrap();
    let n = 20_000;
    let circle = (0..=n)
        .map(|k| {
            let a = std::f64::consts::TAU * k as f64 / n as f64;
            Point::new(20.0 * a.cos(), 20.0 * a.sin())
        })
        .collect();
    (pocket, vec![circle])
}

/// Distance from `p` to the nearest polyline of `axis` (a single point counts as a polyline)
/// (mm), and that nearest point.
pub fn nearest_on(axis: &[Vec<Point>], p: Point) -> (f64, Point) {
    let mut best = (f64::INFINITY, p);
    for line in axis {
        let pieces: Vec<(Point, Point)> = match line.as_slice() {
            [only] => vec![(*only, *only)],
            _ => line.windows(2).map(|w| (w[0], w[1])).collect(),
        };
        for (a, b) in pieces {
            let (dx, dy) = a.vector_to(b);
            let (px, py) = a.vector_to(p);
            let len2 = dx * dx + dy * dy;
            let t = if len2 > 0.0 { ((px * dx + py * dy) / len2).clamp(0.0, 1.0) } else { 0.0 };
            let q = a.offset(t * dx, t * dy);
            if q.distance_mm(p) < best.0 {
                best = (q.distance_mm(p), q);
            }
        }
    }
    best
}

/// The worst deviation of the computed axis from the analytic one: (largest distance of an axis
/// point from the analytic axis, largest difference between its R and the true clearance at the
/// nearest analytic axis point) (mm).
pub fn worst_errors(pocket: &Pocket, axis: &MedialAxis, analytic: &[Vec<Point>]) -> (f64, f64) {
    let boundary = Boundary::of_pocket(pocket);
    let mut worst = (0.0f64, 0.0f64);
    for p in axis.points() {
        let (d, q) = nearest_on(analytic, p.point);
        worst.0 = worst.0.max(d);
        worst.1 = worst.1.max((p.clearance_mm - boundary.clearance_mm(q)).abs());
    }
    worst
}
