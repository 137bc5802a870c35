//! Piecewise-constant distributions in 1D and 2D, sampled by inverting their CDFs
//! (pbrt's `Distribution1D`/`Distribution2D`): used to importance-sample an
//! environment map by its brightness, and an emitting mesh's triangles by area.
//!
//! The inversion finds the cell of `u` through a guide table (Chen and Asau
//! 1974): `guide[k]` is the first CDF entry above `k / G`, `G` a power of two
//! near a quarter of the cell count, so `u` in `[k / G, (k + 1) / G)` has its
//! cell between `guide[k]` and `guide[k + 1]`, a few entries, where a binary
//! search over the whole CDF took `log2 n` dependent loads (17 for the Damaged
//! Helmet's 46 thousand emitting triangles, 17 % of its Whitted render). The
//! cell found is the one the whole search finds, for every `u`.

/// A piecewise-constant density on `[0, 1)` with `n` equal cells.
#[derive(Clone, Debug, PartialEq)]
pub struct Distribution1d {
    func: Vec<f64>,
    cdf: Vec<f64>,
    integral: f64,
    /// `guide[k]`: the number of CDF entries at or below `k / G`, for `k` in
    /// `0..=G`, `G = guide.len() - 1` a power of two (module doc).
    guide: Vec<u32>,
}

impl Distribution1d {
    /// From non-negative cell values (negative or non-finite ones count as 0); an
    /// all-zero function becomes uniform.
    pub fn new(values: &[f64]) -> Distribution1d {
        let n = values.len().max(1);
        let mut func: Vec<f64> = values.iter().map(|&v| if v.is_finite() && v > 0.0 { v } else { 0.0 }).collect();
        func.resize(n, 0.0);
        let mut cdf = vec![0.0; n + 1];
        for i in 0..n {
            cdf[i + 1] = cdf[i] + func[i] / n as f64;
        }
        let mut integral = cdf[n];
        if integral > 0.0 {
            cdf.iter_mut().for_each(|c| *c /= integral);
        } else {
            func.iter_mut().for_each(|f| *f = 1.0);
            cdf.iter_mut().enumerate().for_each(|(i, c)| *c = i as f64 / n as f64);
            integral = 1.0;
        }
        cdf[n] = 1.0;
        let g = (n / 4).next_power_of_two();
        let guide = (0..=g).map(|k| cdf.partition_point(|&c| c <= k as f64 / g as f64) as u32).collect();
        Distribution1d { func, cdf, integral, guide }
    }

    /// The number of CDF entries at or below `u`: through the guide table for
    /// `u` in `[0, 1)` (exact: `G` is a power of two, so `k / G` and `u G` are
    /// exact and `k = floor(u G)` puts `u` in `[k / G, (k + 1) / G)`), over the
    /// whole CDF otherwise (NaN, or out of range).
    #[inline]
    fn entries_at_or_below(&self, u: f64) -> usize {
        if !(0.0..1.0).contains(&u) {
            return self.cdf.partition_point(|&c| c <= u);
        }
        let g = self.guide.len() - 1;
        let k = (u * g as f64) as usize;
        let (lo, hi) = (self.guide[k] as usize, self.guide[k + 1] as usize);
        lo + self.cdf[lo..hi].partition_point(|&c| c <= u)
    }

    /// Integral of the function over `[0, 1)`.
    pub fn integral(&self) -> f64 {
        self.integral
    }

    /// Number of cells.
    pub fn len(&self) -> usize {
        self.func.len()
    }

    /// True when there are no cells (never: an empty input gets one).
    pub fn is_empty(&self) -> bool {
        self.func.is_empty()
    }

    /// Density at cell `i`.
    pub fn pdf_cell(&self, i: usize) -> f64 {
        self.func[i.min(self.func.len() - 1)] / self.integral
    }

    /// `(x, density at x, cell)` for uniform `u`.
    pub fn sample(&self, u: f64) -> (f64, f64, usize) {
        let n = self.func.len();
        let i = self.entries_at_or_below(u).saturating_sub(1).min(n - 1);
        let width = self.cdf[i + 1] - self.cdf[i];
        let du = if width > 0.0 { (u - self.cdf[i]) / width } else { 0.5 };
        let x = ((i as f64 + du) / n as f64).min(1.0 - f64::EPSILON);
        (x, self.pdf_cell(i), i)
    }
}

/// A piecewise-constant density on `[0, 1)^2`: rows (`v`) by their sums, then a column (`u`) in the row.
#[derive(Clone, Debug, PartialEq)]
pub struct Distribution2d {
    rows: Vec<Distribution1d>,
    marginal: Distribution1d,
}

impl Distribution2d {
    /// From `width * height` values, row-major from `v = 0`.
    pub fn new(values: &[f64], width: usize, height: usize) -> Distribution2d {
        let rows: Vec<Distribution1d> = (0..height).map(|y| Distribution1d::new(&values[y * width..(y + 1) * width])).collect();
        let sums: Vec<f64> = rows.iter().map(|r| r.integral()).collect();
        Distribution2d { rows, marginal: Distribution1d::new(&sums) }
    }

    /// `((u, v), density)` for a uniform point.
    pub fn sample(&self, u: (f64, f64)) -> ((f64, f64), f64) {
        let (v, pv, row) = self.marginal.sample(u.1);
        let (x, pu, _) = self.rows[row].sample(u.0);
        ((x, v), pu * pv)
    }

    /// Density at `(u, v)`.
    pub fn pdf(&self, u: f64, v: f64) -> f64 {
        let h = self.rows.len();
        let row = ((v * h as f64) as usize).min(h - 1);
        let w = self.rows[row].len();
        let col = ((u * w as f64) as usize).min(w - 1);
        self.marginal.pdf_cell(row) * self.rows[row].pdf_cell(col)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The guide table finds the entry the whole search finds, for values on and
    /// next to every CDF entry and guide boundary, and out of range.
    #[test]
    fn the_guide_table_answers_as_the_whole_search() {
        let mut state = 7u64;
        let mut next = move || {
            state = state.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1_442_695_040_888_963_407);
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        for n in [1usize, 2, 3, 5, 17, 64, 1000, 4099] {
            // Uneven values with runs of zeros, as an emitter's black texels give.
            let values: Vec<f64> = (0..n).map(|i| if i % 7 < 3 { 0.0 } else { next().powi(4) * 1e3 }).collect();
            let d = Distribution1d::new(&values);
            let g = d.guide.len() - 1;
            let mut us: Vec<f64> = d.cdf.iter().flat_map(|&c| [c, c.next_up(), c.next_down()]).collect();
            us.extend((0..=g).flat_map(|k| {
                let b = k as f64 / g as f64;
                [b, b.next_up(), b.next_down()]
            }));
            us.extend((0..2000).map(|_| next()));
            us.extend([f64::NAN, -0.0, -1.0, 1.0, 2.0, f64::INFINITY, f64::NEG_INFINITY, 1.0f64.next_down()]);
            for u in us {
                assert_eq!(d.entries_at_or_below(u), d.cdf.partition_point(|&c| c <= u), "n {n}, u {u}");
            }
        }
    }

    #[test]
    fn sampling_frequencies_follow_the_values() {
        let d = Distribution2d::new(&[1.0, 3.0, 0.0, 4.0], 2, 2);
        let n = 200;
        let mut counts = [0u32; 4];
        for i in 0..n {
            for j in 0..n {
                let ((x, y), p) = d.sample(((i as f64 + 0.5) / n as f64, (j as f64 + 0.5) / n as f64));
                let cell = (y * 2.0) as usize * 2 + (x * 2.0) as usize;
                counts[cell] += 1;
                assert!((p - d.pdf(x, y)).abs() < 1e-12);
            }
        }
        let total = (n * n) as f64;
        for (c, expected) in counts.iter().zip([0.125, 0.375, 0.0, 0.5]) {
            assert!((*c as f64 / total - expected).abs() < 1e-3, "{counts:?}");
        }
        // Densities integrate to 1: mean of the pdf over the cells, times area.
        assert!(((d.pdf(0.25, 0.25) + d.pdf(0.75, 0.25) + d.pdf(0.25, 0.75) + d.pdf(0.75, 0.75)) / 4.0 - 1.0).abs() < 1e-12);
    }
}
