//! Piecewise-constant distributions in 1D and 2D, sampled by inverting their CDFs
//! (pbrt's `Distribution1D`/`Distribution2D`): used to importance-sample an
//! environment map by its brightness.

/// A piecewise-constant density on `[0, 1)` with `n` equal cells.
#[derive(Clone, Debug, PartialEq)]
pub struct Distribution1d {
    func: Vec<f64>,
    cdf: Vec<f64>,
    integral: f64,
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
        Distribution1d { func, cdf, integral }
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
        let i = self.cdf.partition_point(|&c| c <= u).saturating_sub(1).min(n - 1);
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
