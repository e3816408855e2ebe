//! The squared Euclidean distance transform of a grid (Felzenszwalb and Huttenlocher,
//! "Distance Transforms of Sampled Functions"): how far every cell lies from the nearest
//! source cell, in two passes of a one-dimensional transform. The coverage check finds with
//! it what the tool can reach.

/// Squared Euclidean distance (in cells) from every cell to the nearest `true` cell
/// (Felzenszwalb and Huttenlocher's separable transform); infinite when there is none.
pub fn squared_distance_transform(sources: &[bool], w: usize, h: usize) -> Vec<f64> {
    let mut grid: Vec<f64> = sources.iter().map(|s| if *s { 0.0 } else { f64::INFINITY }).collect();
    let mut column = vec![0.0; h];
    for i in 0..w {
        for j in 0..h {
            column[j] = grid[j * w + i];
        }
        let out = transform_1d(&column);
        for j in 0..h {
            grid[j * w + i] = out[j];
        }
    }
    for j in 0..h {
        let out = transform_1d(&grid[j * w..(j + 1) * w]);
        grid[j * w..(j + 1) * w].copy_from_slice(&out);
    }
    grid
}

/// One-dimensional squared distance transform of the sampled function `f` (lower envelope of
/// parabolas).
fn transform_1d(f: &[f64]) -> Vec<f64> {
    let n = f.len();
    let mut out = vec![f64::INFINITY; n];
    let mut v = vec![0usize; n];
    let mut z = vec![0.0f64; n + 1];
    let mut k: usize = 0;
    let Some(first) = (0..n).find(|&q| f[q].is_finite()) else { return out };
    v[0] = first;
    z[0] = f64::NEG_INFINITY;
    z[1] = f64::INFINITY;
    for q in first + 1..n {
        if !f[q].is_finite() {
            continue;
        }
        loop {
            let p = v[k];
            let s = ((f[q] + (q * q) as f64) - (f[p] + (p * p) as f64)) / (2.0 * (q as f64 - p as f64));
            if s <= z[k] && k > 0 {
                k -= 1;
                continue;
            }
            if s <= z[k] {
                v[0] = q;
                z[0] = f64::NEG_INFINITY;
                z[1] = f64::INFINITY;
                break;
            }
            k += 1;
            v[k] = q;
            z[k] = s;
            z[k + 1] = f64::INFINITY;
            break;
        }
    }
    let mut k = 0;
    for (q, o) in out.iter_mut().enumerate() {
        while z[k + 1] < q as f64 {
            k += 1;
        }
        let p = v[k];
        let d = q as f64 - p as f64;
        *o = d * d + f[p];
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_distance_transform_is_the_squared_distance_to_the_nearest_source() {
        let (w, h) = (7, 5);
        let mut s = vec![false; w * h];
        s[2 * w + 1] = true;
        s[4 * w + 6] = true;
        let d = squared_distance_transform(&s, w, h);
        for j in 0..h {
            for i in 0..w {
                let a = ((i as f64 - 1.0).powi(2) + (j as f64 - 2.0).powi(2))
                    .min((i as f64 - 6.0).powi(2) + (j as f64 - 4.0).powi(2));
                assert!((d[j * w + i] - a).abs() < 1e-9, "({i},{j}) {} vs {a}", d[j * w + i]);
            }
        }
    }
}
