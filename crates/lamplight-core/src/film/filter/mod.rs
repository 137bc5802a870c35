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
//!
//! # Filters with negative lobes
//!
//! Mitsuba's `mitchell` (the Mitchell-Netravali cubic with `B`, `C`, 1/3 by
//! default; radius 2), `catmullrom` (the cubic with `B = 0`, `C = 1/2`) and
//! `lanczos` (`sinc(x) sinc(x / L)` for `|x| < L`, `L` = `lobes`, 3 by
//! default) are negative in places, so no density is proportional to them.
//! They follow pbrt-v4's `FilterSampler`: each axis's offset is drawn from a
//! table of `|f|` (piecewise constant in cells of 1/64 pixel,
//! [`FilterSampler`]) restricted to the same interval as above, and weighted
//! `f(x) / (p(x) M)`, `p` that restricted density and `M` the integral of `f`
//! over the interval. The weight's expectation is 1 and the weighted
//! radiance's the filter-weighted mean of the radiance over the part of the
//! filter inside the image: Mitsuba's expected image, where Mitsuba gets it
//! as the ratio of two sums (splatting, weighted sum over the sum of
//! weights). Splatting would make a pixel the sum of its neighbours' samples
//! (a cross-pixel, order-dependent sum, and a division by a sum of signed
//! weights that can come near zero with few samples); the weights here are
//! bounded (about `(integral of |f|) / M`: 1.07 for Mitchell's cubic, 1.17 for
//! Catmull-Rom and 1.36 for the Lanczos sinc of 3 lobes, more only in cells where
//! `f` crosses 0) and no division by a random sum happens, so every pixel
//! stays finite and each keeps its own fixed-order sum. The price: a constant
//! image comes out as that constant only on average (a pixel's samples
//! weigh `1 +- a few %` at a few samples), where Mitsuba's ratio gives it
//! exactly; the noise is of that size, the expectation the same. A pixel
//! whose `M` is not clearly positive (only a filter with extreme `B`, `C`
//! could have one) takes the pixel square instead, finite but not Mitsuba's.

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
    /// The Mitchell-Netravali cubic of parameters `b` and `c` (Mitsuba's
    /// `mitchell`, `B` and `C`, both 1/3 by default; radius 2). Its lobes
    /// beyond about 1 pixel are negative.
    Mitchell {
        /// The cubic's `B` (blur).
        b: f64,
        /// The cubic's `C` (ringing).
        c: f64,
    },
    /// The Catmull-Rom spline, the Mitchell-Netravali cubic with `B = 0`, `C = 1/2`
    /// (Mitsuba's `catmullrom`; radius 2).
    CatmullRom,
    /// The Lanczos windowed sinc `sinc(x) sinc(x / lobes)` on `|x| < lobes`
    /// (Mitsuba's `lanczos`, `lobes` 3 by default; radius `lobes`).
    Lanczos {
        /// Lobes on each side, the radius in pixels (1 to [`MAX_LOBES`]).
        lobes: u32,
    },
}

/// The most lobes a [`Filter::Lanczos`] takes (a radius of 32 pixels).
pub const MAX_LOBES: u32 = 32;

impl Filter {
    /// Half the width of the filter's support in pixels: 1/2, 1, `4 sigma`, 2
    /// (Mitchell-Netravali, Catmull-Rom) or `lobes` (Lanczos).
    pub fn radius(&self) -> f64 {
        match *self {
            Filter::Box => 0.5,
            Filter::Tent => 1.0,
            Filter::Gaussian { sigma } => 4.0 * sigma,
            Filter::Mitchell { .. } | Filter::CatmullRom => 2.0,
            Filter::Lanczos { lobes } => lobes as f64,
        }
    }

    /// Whether the filter has negative lobes, so that it is sampled from its
    /// table ([`FilterSampler`]) with signed weights.
    pub fn is_signed(&self) -> bool {
        matches!(self, Filter::Mitchell { .. } | Filter::CatmullRom | Filter::Lanczos { .. })
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
            Filter::Mitchell { b, c } => mitchell(x.abs(), b, c),
            Filter::CatmullRom => mitchell(x.abs(), 0.0, 0.5),
            Filter::Lanczos { lobes } => {
                let x = x.abs();
                if x < 1e-8 {
                    // sinc(x) sinc(x / L) = 1 - O(x^2): 1 to within 1e-15.
                    return 1.0;
                }
                let (x1, lobes) = (std::f64::consts::PI * x, lobes as f64);
                let x2 = x1 / lobes;
                x1.sin() * x2.sin() / (x1 * x2)
            }
        }
    }

    /// The cumulative weight `W(x) = integral of weight(t) dt from -radius to x`,
    /// `x` clamped to the support: `x + 1/2` for the box, `(x + 1)^2 / 2` and
    /// `1 - (1 - x)^2 / 2` for the tent, and for the Gaussian
    /// `s sqrt(pi / 2) (erf(x / (s sqrt 2)) + erf(2 sqrt 2)) - b (x + R)` with `b` the cut's bias.
    /// The filters with negative lobes integrate their weight by Gauss-Legendre
    /// quadrature on the cells of their table (exact for the cubics, to about
    /// 1e-15 for the Lanczos sinc); [`FilterSampler`] keeps the cells' sums.
    pub fn cumulative(&self, x: f64) -> f64 {
        let r = self.radius();
        let x = x.clamp(-r, r);
        if self.is_signed() {
            let cells = ((x + r) / CELL).floor() as usize;
            let whole: f64 = (0..cells).map(|k| self.cell_integral(k)).sum();
            return whole + gauss_legendre(|t| self.weight(t), -r + cells as f64 * CELL, x);
        }
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
            Filter::Mitchell { .. } | Filter::CatmullRom | Filter::Lanczos { .. } => unreachable!("integrated above"),
        }
    }

    /// The integral of the weight over cell `k` of a signed filter's table, `[-r + k CELL, -r + (k + 1) CELL]`.
    fn cell_integral(&self, k: usize) -> f64 {
        let x0 = -self.radius() + k as f64 * CELL;
        gauss_legendre(|t| self.weight(t), x0, x0 + CELL)
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
            Filter::Mitchell { .. } | Filter::CatmullRom | Filter::Lanczos { .. } => {
                unreachable!("filters with negative lobes are sampled by their table")
            }
        };
        x.clamp(lo, hi)
    }

    /// One axis of [`Filter::sample_in`]: the offset for uniform `u` on
    /// `[lo, hi]` intersected with the support, and its weight.
    #[inline(always)]
    fn sample_axis(&self, u: f64, lo: f64, hi: f64) -> (f64, f64) {
        if let Filter::Box = self {
            return box_axis(u, lo, hi);
        }
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
    ///
    /// A filter with negative lobes builds its table on each call here: draw
    /// many offsets through one [`FilterSampler`] instead.
    pub fn sample_in(&self, u: (f64, f64), lo: (f64, f64), hi: (f64, f64)) -> ((f64, f64), f64) {
        if self.is_signed() {
            return FilterSampler::new(*self).sample_in(u, lo, hi);
        }
        self.sample_unsigned(u, lo, hi)
    }

    /// [`Filter::sample_in`] for the box, the tent and the Gaussian.
    #[inline(always)]
    fn sample_unsigned(&self, u: (f64, f64), lo: (f64, f64), hi: (f64, f64)) -> ((f64, f64), f64) {
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

/// [`Filter::sample_axis`] of the box, inlined: the path tracer's default
/// filter draws two of these per sample, and the general route (two calls of
/// [`Filter::cumulative`] and one of `inverse_cumulative`, each matching on
/// the filter) was about 300 instructions a sample, 5 % of a Cornell box
/// (`BENCHMARKS.md`, session 18). The operations are those of the general
/// route, in the same order (`W(x) = x + 1/2` at both bounds, then
/// `W^-1(w) = w - 1/2` clamped to the bounds), so the offsets are the same bits.
#[inline(always)]
fn box_axis(u: f64, lo: f64, hi: f64) -> (f64, f64) {
    let (a, b) = (lo.max(-0.5), hi.min(0.5));
    if !(a < b) {
        return (u - 0.5, 1.0);
    }
    let (wa, wb) = (a + 0.5, b + 0.5);
    (((wa + u * (wb - wa)) - 0.5).clamp(a, b), 1.0)
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

/// The Mitchell-Netravali cubic at `x >= 0` (Mitsuba's `mitchell.cpp`):
/// `((12 - 9B - 6C) x^3 + (-18 + 12B + 6C) x^2 + 6 - 2B) / 6` below 1,
/// `((-B - 6C) x^3 + (6B + 30C) x^2 + (-12B - 48C) x + 8B + 24C) / 6` below 2, 0 beyond.
fn mitchell(x: f64, b: f64, c: f64) -> f64 {
    let (x2, x3) = (x * x, x * x * x);
    let v = if x < 1.0 {
        (12.0 - 9.0 * b - 6.0 * c) * x3 + (-18.0 + 12.0 * b + 6.0 * c) * x2 + (6.0 - 2.0 * b)
    } else if x < 2.0 {
        (-b - 6.0 * c) * x3 + (6.0 * b + 30.0 * c) * x2 + (-12.0 * b - 48.0 * c) * x + (8.0 * b + 24.0 * c)
    } else {
        0.0
    };
    v / 6.0
}

impl std::str::FromStr for Filter {
    type Err = String;

    /// A name, with parameters in parentheses for the filters that take them:
    /// `mitchell(B=0.5, C=0.25)`, `lanczos(lobes=2)` (each optional, defaults
    /// B = C = 1/3 and 3 lobes as Mitsuba's).
    fn from_str(s: &str) -> Result<Filter, String> {
        let (name, args) = match s.split_once('(') {
            Some((name, rest)) if rest.ends_with(')') => (name.trim(), Some(&rest[..rest.len() - 1])),
            _ => (s, None),
        };
        let mut params: Vec<(&str, &str)> = Vec::new();
        for arg in args.unwrap_or("").split(',').map(str::trim).filter(|a| !a.is_empty()) {
            let Some((k, v)) = arg.split_once('=') else {
                return Err(format!("filter {s:?}: parameter {arg:?} must read name=value"));
            };
            params.push((k.trim(), v.trim()));
        }
        let allowed: &[&str] = match name {
            "mitchell" => &["B", "C"],
            "lanczos" => &["lobes"],
            _ => &[],
        };
        for (k, _) in &params {
            if !allowed.contains(k) {
                return Err(if allowed.is_empty() {
                    format!("filter {s:?}: \"{name}\" takes no parameters")
                } else {
                    let hint = crate::params::suggestion(k, allowed.iter().copied())
                        .map(|near| format!("did you mean '{near}'? "))
                        .unwrap_or_default();
                    format!("filter {s:?}: unknown parameter \"{k}\" ({hint}\"{name}\" takes {})", allowed.join(", "))
                });
            }
        }
        let number = |key: &str, default: f64| -> Result<f64, String> {
            match params.iter().find(|(k, _)| *k == key) {
                None => Ok(default),
                Some((_, v)) => match v.parse::<f64>() {
                    Ok(x) if x.is_finite() => Ok(x),
                    _ => Err(format!("filter {s:?}: {key} must be a finite number, got {v:?}")),
                },
            }
        };
        match name {
            "box" => Ok(Filter::Box),
            "tent" => Ok(Filter::Tent),
            "gaussian" => Ok(Filter::Gaussian { sigma: 0.5 }),
            "mitchell" => Ok(Filter::Mitchell { b: number("B", 1.0 / 3.0)?, c: number("C", 1.0 / 3.0)? }),
            "catmullrom" => Ok(Filter::CatmullRom),
            "lanczos" => {
                let lobes = match params.first() {
                    None => 3,
                    Some((_, v)) => match v.parse::<u32>() {
                        Ok(n) if (1..=MAX_LOBES).contains(&n) => n,
                        _ => return Err(format!("filter {s:?}: lobes must be a whole number from 1 to {MAX_LOBES}, got {v}")),
                    },
                };
                Ok(Filter::Lanczos { lobes })
            }
            _ => Err(crate::params::unknown("filter", name, &["box", "tent", "gaussian", "mitchell", "catmullrom", "lanczos"])),
        }
    }
}

impl std::fmt::Display for Filter {
    /// The name [`Filter`]'s `from_str` reads back (parameters only where they
    /// differ from the defaults; the Gaussian's sigma is always 0.5 there).
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match *self {
            Filter::Box => f.write_str("box"),
            Filter::Tent => f.write_str("tent"),
            Filter::Gaussian { .. } => f.write_str("gaussian"),
            Filter::Mitchell { b, c } if b == 1.0 / 3.0 && c == 1.0 / 3.0 => f.write_str("mitchell"),
            Filter::Mitchell { b, c } => write!(f, "mitchell(B={b}, C={c})"),
            Filter::CatmullRom => f.write_str("catmullrom"),
            Filter::Lanczos { lobes: 3 } => f.write_str("lanczos"),
            Filter::Lanczos { lobes } => write!(f, "lanczos(lobes={lobes})"),
        }
    }
}

/// The names [`Filter`] parses, quoted for messages.
pub const FILTER_NAMES: &str = "\"box\", \"tent\", \"gaussian\", \"mitchell\" (B, C), \"catmullrom\" or \"lanczos\" (lobes)";

mod signed;

pub use signed::FilterSampler;
use signed::{gauss_legendre, CELL};

#[cfg(test)]
mod tests;
