//! Downsampling a series for a chart: per pixel column (bucket of x) keep the smallest
//! and the largest value, in their order, so peaks survive and a line of any length
//! costs at most about two points per column.

/// Downsamples `(x, y)` into `buckets` equal ranges of x: each bucket keeps its minimum
/// and maximum `y` (in x order; one point when they coincide). A gap (`None`) at the start
/// or end of a bucket, or a bucket without values, is kept as one `None` so lines do not
/// bridge it; gaps narrower than a bucket inside it are dropped (they are under a pixel).
/// Points with a non-finite x are skipped. With no more than `2 × buckets` points the
/// series is returned as is. `x` should be ascending; `x` and `y` should have the same
/// length (the extra of the longer is ignored).
pub fn min_max_per_bucket(x: &[f64], y: &[Option<f64>], buckets: usize) -> (Vec<f64>, Vec<Option<f64>>) {
    let n = x.len().min(y.len());
    if buckets == 0 || n <= 2 * buckets {
        return (x[..n].to_vec(), y[..n].to_vec());
    }
    let finite = || (0..n).filter(|&i| x[i].is_finite());
    let lo = finite().map(|i| x[i]).fold(f64::INFINITY, f64::min);
    let hi = finite().map(|i| x[i]).fold(f64::NEG_INFINITY, f64::max);
    let span = hi - lo;
    let bucket_of = |v: f64| {
        if span > 0.0 {
            (((v - lo) / span * buckets as f64) as usize).min(buckets - 1)
        } else {
            0
        }
    };
    let mut out = (Vec::with_capacity(4 * buckets), Vec::with_capacity(4 * buckets));
    let mut current: Option<(usize, Bucket)> = None;
    for i in finite() {
        let b = bucket_of(x[i]);
        match current.as_mut() {
            Some((cb, bucket)) if *cb == b => bucket.add(x[i], y[i]),
            _ => {
                if let Some((_, bucket)) = current.take() {
                    bucket.emit(&mut out);
                }
                let mut bucket = Bucket::default();
                bucket.add(x[i], y[i]);
                current = Some((b, bucket));
            }
        }
    }
    if let Some((_, bucket)) = current {
        bucket.emit(&mut out);
    }
    out
}

/// What one bucket has seen.
#[derive(Debug, Default)]
struct Bucket {
    /// (x, y) of the smallest and of the largest value.
    min: Option<(f64, f64)>,
    max: Option<(f64, f64)>,
    /// x of the first point, when it is a gap.
    leading_gap: Option<f64>,
    /// x of the last point, when it is a gap.
    trailing_gap: Option<f64>,
    seen: bool,
}

impl Bucket {
    fn add(&mut self, x: f64, y: Option<f64>) {
        match y.filter(|v| v.is_finite()) {
            None => {
                if !self.seen {
                    self.leading_gap = Some(x);
                }
                self.trailing_gap = Some(x);
            }
            Some(v) => {
                self.trailing_gap = None;
                if self.min.is_none_or(|(_, m)| v < m) {
                    self.min = Some((x, v));
                }
                if self.max.is_none_or(|(_, m)| v > m) {
                    self.max = Some((x, v));
                }
            }
        }
        self.seen = true;
    }

    fn emit(self, out: &mut (Vec<f64>, Vec<Option<f64>>)) {
        let mut push = |x: f64, y: Option<f64>| {
            out.0.push(x);
            out.1.push(y);
        };
        let (Some(min), Some(max)) = (self.min, self.max) else {
            if let Some(x) = self.leading_gap {
                push(x, None);
            }
            return;
        };
        if let Some(x) = self.leading_gap {
            push(x, None);
        }
        let (first, second) = if min.0 <= max.0 { (min, max) } else { (max, min) };
        push(first.0, Some(first.1));
        if second.0 > first.0 || (second.1 - first.1).abs() > 0.0 {
            push(second.0, Some(second.1));
        }
        if let Some(x) = self.trailing_gap {
            push(x, None);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_short_series_is_kept_as_is() {
        let (x, y) = min_max_per_bucket(&[0.0, 1.0, 2.0], &[Some(1.0), None, Some(3.0)], 10);
        assert_eq!(x, vec![0.0, 1.0, 2.0]);
        assert_eq!(y, vec![Some(1.0), None, Some(3.0)]);
    }

    #[test]
    fn a_long_series_keeps_at_most_two_points_per_bucket_and_its_peaks() {
        let n = 100_000;
        let x: Vec<f64> = (0..n).map(|i| i as f64 * 0.01).collect();
        let mut y: Vec<Option<f64>> = x.iter().map(|v| Some(v.sin())).collect();
        y[54_321] = Some(25.0);
        y[12_345] = Some(-30.0);
        let (dx, dy) = min_max_per_bucket(&x, &y, 500);
        assert!(dx.len() <= 1000, "{} points", dx.len());
        assert_eq!(dx.len(), dy.len());
        let values: Vec<f64> = dy.iter().flatten().copied().collect();
        assert!(values.iter().any(|&v| (v - 25.0).abs() < 1e-12));
        assert!(values.iter().any(|&v| (v + 30.0).abs() < 1e-12));
        assert!(dx.windows(2).all(|w| w[0] <= w[1]), "x stays ascending");
    }

    #[test]
    fn a_gap_longer_than_a_bucket_survives() {
        let n = 10_000;
        let x: Vec<f64> = (0..n).map(f64::from).collect();
        let y: Vec<Option<f64>> = (0..n).map(|i| if (4000..6000).contains(&i) { None } else { Some(1.0) }).collect();
        let (dx, dy) = min_max_per_bucket(&x, &y, 100);
        assert!(dy.iter().any(Option::is_none));
        // No line bridges the gap: every point inside it is a gap.
        for (xv, yv) in dx.iter().zip(&dy) {
            if (4000.0..6000.0).contains(xv) {
                assert!(yv.is_none(), "value at {xv}");
            }
        }
    }

    #[test]
    fn no_buckets_or_no_points_return_the_input() {
        assert_eq!(min_max_per_bucket(&[], &[], 10), (vec![], vec![]));
        assert_eq!(min_max_per_bucket(&[1.0], &[Some(2.0)], 0), (vec![1.0], vec![Some(2.0)]));
    }
}
