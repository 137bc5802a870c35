//! Pixel reconstruction filters, applied by filter importance sampling: each
//! sample's film position is drawn from (nearly) the filter's own distribution
//! around the pixel centre, with weight 1 or close to it (Ernst et al. 2006). The
//! pixel value is then the average of its own weighted samples, a fixed-order
//! sum that no other pixel touches, so images stay identical for any thread count.
//!
//! The filters are separable, `f(dx, dy) = f(dx) f(dy)`, with Mitsuba 3's 1D
//! weights (`src/rfilters/`): the box `1` on `|x| <= 1/2`, the tent
//! `max(0, 1 - |x|)` (radius 1), and the Gaussian of standard deviation `s`
//! cut at `R = 4 s`, `max(0, exp(-x^2 / (2 s^2)) - exp(-R^2 / (2 s^2)))`.
//!
//! Mitsuba's film draws samples only inside the image (`sample_border` off) and
//! divides each pixel by the sum of its filter weights, so a pixel's expected
//! value is the filter-weighted mean of the radiance over the part of the
//! filter's support that lies inside the image. [`Filter::sample_in`] draws the
//! offset from the filter restricted to that part, a rectangle (the support is a
//! square and the image a rectangle), by inverting each axis's cumulative weight
//! over its interval: the same expectation, one 2D sample per offset, no
//! rejection, and the sampler's stratification kept. A pixel whose support lies
//! wholly inside the image draws from the whole filter (the box always does, so
//! its offsets are `u - 1/2` as before). The Gaussian mixes in a uniform share
//! and weights its samples ([`Filter::sample_in`]), so that its long, faint
//! tail is sampled too.

/// A reconstruction filter.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub enum Filter {
    /// The pixel square (width 1).
    #[default]
    Box,
    /// The tent `max(0, 1 - |x|)` on each axis (radius 1 pixel, Mitsuba's `tent`).
    Tent,
    /// A Gaussian of standard deviation `sigma` pixels cut at `4 sigma` (Mitsuba's
    /// `gaussian`; its default and lamplight's is `sigma = 0.5`, radius 2).
    Gaussian {
        /// Standard deviation in pixels.
        sigma: f64,
    },
}

impl Filter {
    /// Half the width of the filter's support in pixels: 1/2, 1 or `4 sigma`.
    pub fn radius(&self) -> f64 {
        match *self {
            Filter::Box => 0.5,
            Filter::Tent => 1.0,
            Filter::Gaussian { sigma } => 4.0 * sigma,
        }
    }

    /// The 1D weight at offset `x` (see the module doc; 0 outside the support).
    pub fn weight(&self, x: f64) -> f64 {
        let r = self.radius();
        if !(x.abs() <= r) {
            return 0.0;
        }
        match *self {
            Filter::Box => 1.0,
            Filter::Tent => 1.0 - x.abs(),
            Filter::Gaussian { sigma } => ((-x * x / (2.0 * sigma * sigma)).exp() - GAUSSIAN_BIAS).max(0.0),
        }
    }

    /// The cumulative weight `W(x) = integral of weight(t) dt from -radius to x`,
    /// `x` clamped to the support: `x + 1/2` for the box, `(x + 1)^2 / 2` and
    /// `1 - (1 - x)^2 / 2` for the tent, and for the Gaussian
    /// `s sqrt(pi / 2) (erf(x / (s sqrt 2)) + erf(2 sqrt 2)) - b (x + R)` with `b` the cut's bias.
    pub fn cumulative(&self, x: f64) -> f64 {
        let r = self.radius();
        let x = x.clamp(-r, r);
        match *self {
            Filter::Box => x + 0.5,
            Filter::Tent => {
                if x <= 0.0 {
                    0.5 * (x + 1.0) * (x + 1.0)
                } else {
                    1.0 - 0.5 * (1.0 - x) * (1.0 - x)
                }
            }
            Filter::Gaussian { sigma } => {
                if x <= -r {
                    return 0.0;
                }
                let erf = if x >= r { ERF_AT_CUT } else { libm::erf(x / (sigma * std::f64::consts::SQRT_2)) };
                sigma * (std::f64::consts::PI / 2.0).sqrt() * (erf + ERF_AT_CUT) - GAUSSIAN_BIAS * (x + r)
            }
        }
    }

    /// The offset `x` in `[lo, hi]` with `cumulative(x) = w`, for `w` between
    /// `cumulative(lo)` and `cumulative(hi)`: in closed form for the box and the
    /// tent, for the Gaussian by Newton's method from a table's chord, kept
    /// inside a shrinking bracket, until a step is below `1e-12 sigma` (two
    /// steps as a rule, at most 64; the same inputs always take the same steps).
    fn inverse_cumulative(&self, w: f64, lo: f64, hi: f64) -> f64 {
        let x = match *self {
            Filter::Box => w - 0.5,
            Filter::Tent => {
                if w <= 0.5 {
                    (2.0 * w).sqrt() - 1.0
                } else {
                    1.0 - (2.0 * (1.0 - w)).sqrt()
                }
            }
            Filter::Gaussian { sigma } => {
                // Start from the table of the standard cut Gaussian (W(x) = sigma G(x / sigma)):
                // its cell brackets the root and its chord is the first guess.
                let table = standard_gaussian_table();
                let target = w / sigma;
                let k = table.partition_point(|&g| g <= target).clamp(1, TABLE_CELLS) - 1;
                let cell = |i: usize| sigma * (-4.0 + 8.0 * i as f64 / TABLE_CELLS as f64);
                let (g0, g1) = (table[k], table[k + 1]);
                let (mut a, mut b) = (lo.max(cell(k)), hi.min(cell(k + 1)));
                if !(a < b) {
                    (a, b) = (lo, hi);
                }
                let chord = if g1 > g0 { cell(k) + (target - g0) / (g1 - g0) * (cell(k + 1) - cell(k)) } else { cell(k) };
                let mut x = chord.clamp(a, b);
                for _ in 0..64 {
                    let g = self.cumulative(x) - w;
                    if g == 0.0 {
                        break;
                    }
                    if g > 0.0 {
                        b = x;
                    } else {
                        a = x;
                    }
                    let step = x - g / self.weight(x);
                    // Newton where it stays in the bracket, else bisection.
                    let next = if step > a && step < b { step } else { 0.5 * (a + b) };
                    if (next - x).abs() <= 1e-12 * sigma || b - a <= 1e-15 {
                        x = next;
                        break;
                    }
                    x = next;
                }
                x
            }
        };
        x.clamp(lo, hi)
    }

    /// One axis of [`Filter::sample_in`]: the offset for uniform `u` on
    /// `[lo, hi]` intersected with the support, and its weight.
    fn sample_axis(&self, u: f64, lo: f64, hi: f64) -> (f64, f64) {
        let r = self.radius();
        let (a, b) = (lo.max(-r), hi.min(r));
        if !(a < b) {
            // No part of the support is inside the bounds: only a pixel outside
            // them (the border an adaptive render probes) gets here.
            return (u - 0.5, 1.0);
        }
        let (wa, wb) = (self.cumulative(a), self.cumulative(b));
        if !matches!(self, Filter::Gaussian { .. }) {
            return (self.inverse_cumulative(wa + u * (wb - wa), a, b), 1.0);
        }
        // The Gaussian's mixture with the uniform density (see `sample_in`).
        let (mass, len) = (wb - wa, b - a);
        let x = if u < UNIFORM_SHARE {
            (a + u / UNIFORM_SHARE * len).min(b)
        } else {
            self.inverse_cumulative(wa + (u - UNIFORM_SHARE) / (1.0 - UNIFORM_SHARE) * mass, a, b)
        };
        let filter_density = self.weight(x) / mass;
        (x, filter_density / ((1.0 - UNIFORM_SHARE) * filter_density + UNIFORM_SHARE / len))
    }

    /// The offset from a pixel's centre for a uniform point `u`, drawn from the
    /// filter restricted to the offsets `lo..hi` (per axis) whose positions lie
    /// inside the image (see the module doc), and the sample's weight: the
    /// pixel is the mean of its samples' weighted radiance. The box and the
    /// tent draw from the filter itself (weight 1). The Gaussian draws each
    /// axis from the mixture `q = 0.75 f / W + 0.25 / (hi - lo)` of the filter's
    /// density and the uniform one, with weight `(f / W) / q` (at most 4/3),
    /// so that a pixel whose light reaches it only through the filter's tail
    /// gets samples there (one in 32 per axis in each outer quarter) and
    /// its noise is measured rather than hidden by samples that all miss.
    /// With infinite bounds this is the whole filter.
    pub fn sample_in(&self, u: (f64, f64), lo: (f64, f64), hi: (f64, f64)) -> ((f64, f64), f64) {
        let (x, wx) = self.sample_axis(u.0, lo.0, hi.0);
        let (y, wy) = self.sample_axis(u.1, lo.1, hi.1);
        ((x, y), wx * wy)
    }

    /// [`Filter::sample_in`] without bounds: the whole filter.
    pub fn sample(&self, u: (f64, f64)) -> ((f64, f64), f64) {
        let inf = f64::INFINITY;
        self.sample_in(u, (-inf, -inf), (inf, inf))
    }
}

/// `exp(-8)`: the Gaussian at its cut `4 sigma`, subtracted from its weights (Mitsuba's bias).
const GAUSSIAN_BIAS: f64 = 3.3546262790251185e-4;

/// `erf(2 sqrt 2)`: `erf(x / (sigma sqrt 2))` at the cut `x = 4 sigma`.
const ERF_AT_CUT: f64 = 0.9999366575163338;

/// Cells of [`standard_gaussian_table`].
const TABLE_CELLS: usize = 4096;

/// `G(t)` at `t = -4 + 8 k / TABLE_CELLS`, `k = 0..=TABLE_CELLS`: the cumulative
/// weight of the Gaussian of standard deviation 1 cut at 4 (built once).
fn standard_gaussian_table() -> &'static [f64; TABLE_CELLS + 1] {
    static TABLE: std::sync::OnceLock<[f64; TABLE_CELLS + 1]> = std::sync::OnceLock::new();
    TABLE.get_or_init(|| {
        let unit = Filter::Gaussian { sigma: 1.0 };
        std::array::from_fn(|k| unit.cumulative(-4.0 + 8.0 * k as f64 / TABLE_CELLS as f64))
    })
}

/// The share of the Gaussian's samples drawn uniformly over its support (see [`Filter::sample_in`]).
const UNIFORM_SHARE: f64 = 0.25;

impl std::str::FromStr for Filter {
    type Err = String;

    fn from_str(s: &str) -> Result<Filter, String> {
        match s {
            "box" => Ok(Filter::Box),
            "tent" => Ok(Filter::Tent),
            "gaussian" => Ok(Filter::Gaussian { sigma: 0.5 }),
            _ => Err(crate::params::unknown("filter", s, &["box", "tent", "gaussian"])),
        }
    }
}

/// The names [`Filter`] parses, quoted for messages: `"box", "tent" or "gaussian"`.
pub const FILTER_NAMES: &str = "\"box\", \"tent\" or \"gaussian\"";

#[cfg(test)]
mod tests {
    use super::*;

    const GAUSS: Filter = Filter::Gaussian { sigma: 0.5 };

    /// The integral of `g` over `[a, b]` by the midpoint rule.
    fn integral(g: impl Fn(f64) -> f64, a: f64, b: f64) -> f64 {
        let n = 20_000;
        let h = (b - a) / n as f64;
        (0..n).map(|i| g(a + (i as f64 + 0.5) * h) * h).sum()
    }

    #[test]
    fn cumulative_weights_integrate_the_weights() {
        for f in [Filter::Box, Filter::Tent, GAUSS, Filter::Gaussian { sigma: 0.3 }] {
            let r = f.radius();
            assert_eq!(f.cumulative(-r), 0.0, "{f:?}");
            for x in [-0.9 * r, -0.3, 0.0, 0.2, 0.7 * r, r] {
                let exact = integral(|t| f.weight(t), -r, x);
                assert!((f.cumulative(x) - exact).abs() < 1e-6, "{f:?} at {x}: {} vs {exact}", f.cumulative(x));
            }
        }
        // Analytic totals: the box and the tent have area 1; the cut Gaussian
        // sqrt(pi/8) erf(2 sqrt 2) 2 - 4 exp(-8).
        assert_eq!(Filter::Tent.cumulative(1.0), 1.0);
        let gauss_total = (std::f64::consts::PI / 8.0).sqrt() * 2.0 * libm::erf(2.0 * std::f64::consts::SQRT_2) - 4.0 * (-8.0f64).exp();
        assert!((GAUSS.cumulative(2.0) - gauss_total).abs() < 1e-15);
        assert!((GAUSS.weight(0.0) - (1.0 - (-8.0f64).exp())).abs() < 1e-15);
        assert_eq!(GAUSS.weight(2.0), 0.0);
    }

    #[test]
    fn offsets_follow_the_filter_restricted_to_the_bounds() {
        // The mean of x^2 (and of x) over stratified u equals that of the
        // weight restricted to [lo, hi], by quadrature.
        for f in [Filter::Tent, GAUSS] {
            let r = f.radius();
            for (lo, hi) in [(-f64::INFINITY, f64::INFINITY), (-0.5, f64::INFINITY), (-0.5, 0.5), (-1.5, 0.25)] {
                let (a, b) = (f64::max(lo, -r), f64::min(hi, r));
                let mass = integral(|t| f.weight(t), a, b);
                let mean = integral(|t| t * f.weight(t), a, b) / mass;
                let second = integral(|t| t * t * f.weight(t), a, b) / mass;
                let n = 20_000;
                let xs: Vec<(f64, f64)> = (0..n).map(|i| f.sample_axis((i as f64 + 0.5) / n as f64, lo, hi)).collect();
                assert!(xs.iter().all(|&(x, w)| x >= a && x <= b && w > 0.0 && w <= 4.0 / 3.0 + 1e-12), "{f:?} [{lo}, {hi}]");
                let m0 = xs.iter().map(|(_, w)| w).sum::<f64>() / n as f64;
                let m1 = xs.iter().map(|(x, w)| x * w).sum::<f64>() / n as f64;
                let m2 = xs.iter().map(|(x, w)| x * x * w).sum::<f64>() / n as f64;
                assert!((m0 - 1.0).abs() < 1e-4, "{f:?} [{lo}, {hi}]: weights average {m0}");
                assert!((m1 - mean).abs() < 1e-4 && (m2 - second).abs() < 1e-4, "{f:?} [{lo}, {hi}]: {m1} {m2} vs {mean} {second}");
            }
        }
    }

    #[test]
    fn offsets_invert_the_cumulative_weight() {
        // The tent in closed form: u = 1/8 gives (x + 1)^2 / 2 = 1/8, x = -1/2.
        assert_eq!(Filter::Tent.sample((0.125, 0.875)), ((-0.5, 0.5), 1.0));
        // The Gaussian's filter part (u from 0.25 on, rescaled) is odd about the
        // centre, with its median at u = 0.625; its uniform part spans the support.
        let ((x, y), _) = GAUSS.sample((0.625, 0.91));
        assert!(x.abs() < 1e-12);
        let ((y2, _), _) = GAUSS.sample((0.34, 0.5));
        assert!((y + y2).abs() < 1e-9, "{y} {y2}");
        assert_eq!(GAUSS.sample_axis(0.125, -1.0, 3.0).0, 0.5, "halfway along [-1, 2]");
        // Restricted to [0, 2], the filter part's middle holds half the right half's weight.
        let (x, w) = GAUSS.sample_axis(0.625, 0.0, f64::INFINITY);
        assert!((GAUSS.cumulative(x) - 0.75 * GAUSS.cumulative(2.0)).abs() < 1e-12, "{x}");
        let density = GAUSS.weight(x) / (0.5 * GAUSS.cumulative(2.0));
        assert!((w - density / (0.75 * density + 0.25 / 2.0)).abs() < 1e-15);
    }

    #[test]
    fn the_gaussians_inverse_is_exact_to_1e_12() {
        for f in [GAUSS, Filter::Gaussian { sigma: 0.3 }, Filter::Gaussian { sigma: 1.7 }] {
            let r = f.radius();
            for (lo, hi) in [(-r, r), (-0.2, r), (0.7 * r, r), (-r, -0.9 * r)] {
                let (wa, wb) = (f.cumulative(lo), f.cumulative(hi));
                for i in 0..=1000 {
                    let w = wa + (wb - wa) * i as f64 / 1000.0;
                    let x = f.inverse_cumulative(w, lo, hi);
                    assert!((lo..=hi).contains(&x) && (f.cumulative(x) - w).abs() < 1e-12, "{f:?} [{lo}, {hi}] w {w}: x {x}");
                }
            }
        }
    }

    #[test]
    fn the_box_keeps_its_offsets() {
        // A pixel centre is at least 1/2 from the image's edge, so the box is never cut.
        for u in [0.0, 0.1, 0.37, 0.5, 0.999] {
            assert_eq!(Filter::Box.sample_in((u, u), (-0.5, -7.5), (0.5, 2.5)), ((u - 0.5, u - 0.5), 1.0));
        }
        assert_eq!(Filter::Box.sample((0.0, 1.0)), ((-0.5, 0.5), 1.0));
        // Bounds that miss the support give the pixel square.
        assert_eq!(GAUSS.sample_in((0.25, 0.75), (3.0, -1.0), (4.0, 1.0)).0 .0, -0.25);
    }

    #[test]
    fn the_gaussians_constants_are_its_cut() {
        assert_eq!(GAUSSIAN_BIAS, (-8.0f64).exp());
        assert!((ERF_AT_CUT - libm::erf(2.0 * std::f64::consts::SQRT_2)).abs() <= f64::EPSILON);
    }

    #[test]
    fn names_parse() {
        assert_eq!("tent".parse::<Filter>(), Ok(Filter::Tent));
        assert_eq!("gaussian".parse::<Filter>(), Ok(GAUSS));
        assert_eq!("mitchell".parse::<Filter>(), Err("unknown filter \"mitchell\" (filters: box, tent, gaussian)".into()));
    }
}
