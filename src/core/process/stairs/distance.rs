//! Exact Euclidean distance transform of a grid (Felzenszwalb and Huttenlocher, "Distance
//! transforms of sampled functions", 2012): for every cell, the distance from its centre to
//! the centre of the nearest feature cell, in two passes of the lower envelope of parabolas
//! (rows, then columns), linear in the number of cells.

use crate::core::stock::Grid;

/// A squared distance no grid reaches, standing for "no feature in this row or column"
/// (finite, so that the envelope's intersections stay finite), cells².
const FAR_CELLS2: f64 = 1e20;

/// The distance from every cell of `grid` to the nearest cell where `feature` holds, mm
/// (`f64::INFINITY` everywhere when no cell holds).
pub fn distance_to_mm(grid: &Grid, feature: &[bool]) -> Vec<f64> {
    nearest_feature(grid, feature).into_iter().map(|(d, _)| d).collect()
}

/// For every cell of `grid`: the distance to the nearest cell where `feature` holds, mm,
/// and that cell's index (`(f64::INFINITY, 0)` everywhere when no cell holds).
pub fn nearest_feature(grid: &Grid, feature: &[bool]) -> Vec<(f64, usize)> {
    let (nx, ny) = (grid.nx, grid.ny);
    debug_assert_eq!(feature.len(), nx * ny);
    if !feature.iter().any(|&f| f) {
        return vec![(f64::INFINITY, 0); nx * ny];
    }
    let mut d2: Vec<f64> = feature.iter().map(|&f| if f { 0.0 } else { FAR_CELLS2 }).collect();
    // Per cell, the column of the nearest feature in its row.
    let mut nearest_column = vec![0usize; nx * ny];
    let mut envelope = Envelope::with_capacity(nx.max(ny));
    let mut line = vec![0.0; nx.max(ny)];
    let mut roots = vec![0usize; nx.max(ny)];
    for row in 0..ny {
        let cells = &mut d2[row * nx..(row + 1) * nx];
        line[..nx].copy_from_slice(cells);
        envelope.transform(&line[..nx], cells, &mut roots[..nx]);
        nearest_column[row * nx..(row + 1) * nx].copy_from_slice(&roots[..nx]);
    }
    let mut column = vec![0.0; ny];
    let mut out = vec![(f64::INFINITY, 0usize); nx * ny];
    for col in 0..nx {
        for row in 0..ny {
            line[row] = d2[row * nx + col];
        }
        envelope.transform(&line[..ny], &mut column, &mut roots[..ny]);
        for row in 0..ny {
            let r = roots[row];
            let c2 = column[row];
            let d = if c2 >= FAR_CELLS2 { f64::INFINITY } else { c2.sqrt() * grid.cell_mm };
            out[row * nx + col] = (d, r * nx + nearest_column[r * nx + col]);
        }
    }
    out
}

/// The lower envelope of the parabolas `f(q) + (p − q)²` of one row or column.
struct Envelope {
    /// Where each parabola of the envelope is rooted.
    roots: Vec<usize>,
    /// Where each parabola of the envelope begins to be the lowest.
    starts: Vec<f64>,
}

impl Envelope {
    fn with_capacity(n: usize) -> Envelope {
        Envelope { roots: Vec::with_capacity(n), starts: Vec::with_capacity(n + 1) }
    }

    /// `out[p] = min_q f[q] + (p − q)²`, and `root[p]` the `q` it is taken at.
    fn transform(&mut self, f: &[f64], out: &mut [f64], root: &mut [usize]) {
        self.roots.clear();
        self.starts.clear();
        self.roots.push(0);
        self.starts.push(f64::NEG_INFINITY);
        for q in 1..f.len() {
            loop {
                let v = *self.roots.last().unwrap_or(&0);
                let s = ((f[q] + (q * q) as f64) - (f[v] + (v * v) as f64)) / (2.0 * (q as f64 - v as f64));
                if self.roots.len() > 1 && s <= *self.starts.last().unwrap_or(&f64::NEG_INFINITY) {
                    self.roots.pop();
                    self.starts.pop();
                    continue;
                }
                self.roots.push(q);
                self.starts.push(s);
                break;
            }
        }
        let mut k = 0;
        for (p, (o, r)) in out.iter_mut().zip(root.iter_mut()).enumerate() {
            while k + 1 < self.roots.len() && self.starts[k + 1] < p as f64 {
                k += 1;
            }
            let q = self.roots[k];
            let d = p as f64 - q as f64;
            *o = f[q] + d * d;
            *r = q;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn grid(nx: usize, ny: usize, cell_mm: f64) -> Grid {
        Grid { x0_mm: 0.0, y0_mm: 0.0, cell_mm, nx, ny }
    }

    #[test]
    fn every_cell_gets_its_exact_distance_to_the_nearest_feature_cell() {
        let g = grid(23, 17, 0.5);
        let features = [(3usize, 4usize), (20, 15), (11, 2)];
        let mut feature = vec![false; g.cells()];
        for &(c, r) in &features {
            feature[r * g.nx + c] = true;
        }
        let d = distance_to_mm(&g, &feature);
        let nearest = nearest_feature(&g, &feature);
        for r in 0..g.ny {
            for c in 0..g.nx {
                let brute = features
                    .iter()
                    .map(|&(fc, fr)| ((c as f64 - fc as f64).powi(2) + (r as f64 - fr as f64).powi(2)).sqrt())
                    .fold(f64::INFINITY, f64::min)
                    * g.cell_mm;
                assert!((d[r * g.nx + c] - brute).abs() < 1e-9, "cell ({c}, {r}): {} against {brute}", d[r * g.nx + c]);
                // The nearest feature named is one at that distance.
                let (_, k) = nearest[r * g.nx + c];
                assert!(feature[k]);
                let (fc, fr) = (k % g.nx, k / g.nx);
                let to_it = ((c as f64 - fc as f64).powi(2) + (r as f64 - fr as f64).powi(2)).sqrt() * g.cell_mm;
                assert!((to_it - brute).abs() < 1e-9);
            }
        }
    }

    #[test]
    fn a_grid_without_features_is_infinitely_far_from_them() {
        let g = grid(4, 3, 1.0);
        assert!(distance_to_mm(&g, &[false; 12]).iter().all(|d| d.is_infinite()));
    }
}
