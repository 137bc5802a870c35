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

/// The width in pixels of a cell of a signed filter's table: 1/64, so that
/// cells end on whole pixels, where the cubics change piece.
const CELL: f64 = 1.0 / 64.0;

/// The integral of `g` over `[a, b]` by 8-point Gauss-Legendre quadrature
/// (exact for polynomials of degree up to 15).
fn gauss_legendre(g: impl Fn(f64) -> f64, a: f64, b: f64) -> f64 {
    const NODES: [f64; 4] = [0.1834346424956498, 0.525532409916329, 0.7966664774136267, 0.9602898564975363];
    const WEIGHTS: [f64; 4] = [0.362683783378362, 0.3137066458778873, 0.2223810344533745, 0.1012285362903763];
    if !(b > a) {
        return 0.0;
    }
    let (mid, half) = (0.5 * (a + b), 0.5 * (b - a));
    let sum: f64 = NODES.iter().zip(WEIGHTS).map(|(&t, w)| w * (g(mid - half * t) + g(mid + half * t))).sum();
    sum * half
}

/// Draws film offsets for a [`Filter`] many times: the box, the tent and the
/// Gaussian as [`Filter::sample_in`] does, a filter with negative lobes from
/// its table, built once here (see the module doc).
#[derive(Clone, Debug)]
pub struct FilterSampler {
    filter: Filter,
    table: Option<Box<SignedTable>>,
}

impl FilterSampler {
    /// The sampler of `filter` (for a signed filter, its table: 128 cells a pixel of radius).
    pub fn new(filter: Filter) -> FilterSampler {
        FilterSampler { filter, table: filter.is_signed().then(|| Box::new(SignedTable::new(filter))) }
    }

    /// The filter drawn from.
    pub fn filter(&self) -> Filter {
        self.filter
    }

    /// [`Filter::sample_in`]: the offset for `u` inside the bounds `lo..hi`
    /// and its weight; the pixel is the mean of its samples' weighted radiance.
    #[inline(always)]
    pub fn sample_in(&self, u: (f64, f64), lo: (f64, f64), hi: (f64, f64)) -> ((f64, f64), f64) {
        match &self.table {
            None => self.filter.sample_unsigned(u, lo, hi),
            Some(table) => {
                let (x, wx) = table.sample_axis(u.0, lo.0, hi.0);
                let (y, wy) = table.sample_axis(u.1, lo.1, hi.1);
                ((x, y), wx * wy)
            }
        }
    }
}

/// A signed filter's table on `[-r, r]` in cells of width [`CELL`]: at the
/// cells' ends the cumulative weight `signed` (Gauss-Legendre on each cell,
/// see [`Filter::cumulative`]) and the cumulative `magnitude` of the
/// piecewise-constant density the offsets are drawn from, each cell's
/// integral of `|f|` (by the same quadrature, kinks and all: it need only be
/// close to `|f|`, the weights correct the rest) plus `1e-9` times its width,
/// so that no cell where `f` is not zero has zero density.
#[derive(Clone, Debug)]
struct SignedTable {
    filter: Filter,
    radius: f64,
    signed: Vec<f64>,
    magnitude: Vec<f64>,
}

impl SignedTable {
    fn new(filter: Filter) -> SignedTable {
        let radius = filter.radius();
        let cells = (2.0 * radius / CELL).round() as usize;
        let (mut signed, mut magnitude) = (vec![0.0; cells + 1], vec![0.0; cells + 1]);
        for k in 0..cells {
            let x0 = -radius + k as f64 * CELL;
            signed[k + 1] = signed[k] + filter.cell_integral(k);
            magnitude[k + 1] = magnitude[k] + gauss_legendre(|t| filter.weight(t).abs(), x0, x0 + CELL) + 1e-9 * CELL;
        }
        SignedTable { filter, radius, signed, magnitude }
    }

    /// The cell holding `x` (clamped to the support) and the cell's start.
    fn cell(&self, x: f64) -> (usize, f64) {
        let k = (((x + self.radius) / CELL).floor().max(0.0) as usize).min(self.signed.len() - 2);
        (k, -self.radius + k as f64 * CELL)
    }

    /// The cumulative weight at `x` in the support: the table's cells before
    /// `x`'s, and the quadrature over the part of its cell before `x`.
    fn signed_at(&self, x: f64) -> f64 {
        if x >= self.radius {
            return self.signed[self.signed.len() - 1];
        }
        let (k, x0) = self.cell(x);
        self.signed[k] + gauss_legendre(|t| self.filter.weight(t), x0, x)
    }

    /// The cumulative density at `x` in the support (linear in each cell).
    fn magnitude_at(&self, x: f64) -> f64 {
        let (k, x0) = self.cell(x);
        self.magnitude[k] + ((x - x0) / CELL).min(1.0) * (self.magnitude[k + 1] - self.magnitude[k])
    }

    /// One axis: the offset for `u` drawn from the tabulated `|f|` restricted
    /// to `[lo, hi]` and the support, with weight `f(x) / (p(x) M)`: `p` the
    /// restricted density and `M` the weight's integral over the same interval.
    /// Its mean over `u` is 1 and of `g(x)` times it the `f`-weighted mean of `g`.
    fn sample_axis(&self, u: f64, lo: f64, hi: f64) -> (f64, f64) {
        let r = self.radius;
        let (a, b) = (lo.max(-r), hi.min(r));
        if !(a < b) {
            // As the unsigned filters: a pixel outside the bounds takes its square.
            return (u - 0.5, 1.0);
        }
        let (ma, mb) = (self.magnitude_at(a), self.magnitude_at(b));
        let mass = self.signed_at(b) - self.signed_at(a);
        if !(mass > 1e-3 * (mb - ma)) {
            // The filter's weight over the interval is (nearly) zero or
            // negative, so its weighted mean is not defined (Mitsuba would
            // divide by about zero): the pixel square keeps the pixel finite.
            // No pixel inside the image gets here with Mitsuba's cubics and
            // sincs (their middle lobe dominates).
            return (u - 0.5, 1.0);
        }
        let target = ma + u * (mb - ma);
        let (ka, _) = self.cell(a);
        let (kb, _) = self.cell(b);
        let k = (self.magnitude.partition_point(|&m| m <= target).max(1) - 1).clamp(ka, kb);
        let cell_mass = self.magnitude[k + 1] - self.magnitude[k];
        let x0 = -r + k as f64 * CELL;
        let x = (x0 + (target - self.magnitude[k]) / cell_mass * CELL).clamp(a, b);
        let density = cell_mass / CELL / (mb - ma);
        (x, self.filter.weight(x) / (density * mass))
    }
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
                    format!("filter {s:?}: unknown parameter \"{k}\" (\"{name}\" takes {})", allowed.join(", "))
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

    const MITCHELL: Filter = Filter::Mitchell { b: 1.0 / 3.0, c: 1.0 / 3.0 };
    const LANCZOS: Filter = Filter::Lanczos { lobes: 3 };
    const SIGNED: [Filter; 5] = [MITCHELL, Filter::CatmullRom, LANCZOS, Filter::Lanczos { lobes: 2 }, Filter::Mitchell { b: 0.8, c: 0.1 }];

    #[test]
    fn signed_weights_are_mitsubas_formulas() {
        // Mitchell-Netravali, B = C = 1/3: (6 - 2B) / 6 = 8/9 at 0; at 1 both
        // pieces give (12 - 9B - 6C - 18 + 12B + 6C + 6 - 2B) / 6 = B / 6 = 1/18;
        // at 1.5 ((-7/3) 27/8 + 12 (9/4) - 20 (3/2) + 32/3) / 6 = -5/144.
        let close = |a: f64, b: f64| (a - b).abs() < 1e-14;
        assert!(close(MITCHELL.weight(0.0), 8.0 / 9.0));
        assert!(close(MITCHELL.weight(1.0), 1.0 / 18.0) && (MITCHELL.weight(1.0 - 1e-12) - 1.0 / 18.0).abs() < 1e-11);
        assert!(close(MITCHELL.weight(-1.5), -5.0 / 144.0) && close(MITCHELL.weight(1.5), -5.0 / 144.0));
        assert_eq!((MITCHELL.weight(2.0), MITCHELL.weight(-2.5)), (0.0, 0.0));
        // Another B, C: at 0.5, (12 - 9B - 6C) / 8 + (-18 + 12B + 6C) / 4 + 6 - 2B, over 6.
        let (b, c) = (0.8, 0.1);
        let f = Filter::Mitchell { b, c };
        let at_half = ((12.0 - 9.0 * b - 6.0 * c) / 8.0 + (-18.0 + 12.0 * b + 6.0 * c) / 4.0 + 6.0 - 2.0 * b) / 6.0;
        assert!(close(f.weight(0.5), at_half));
        // Catmull-Rom (B = 0, C = 1/2): 1 at 0, 0 at 1, (9/8 - 15/4 + 6) / 6 = 9/16
        // at 1/2, (-3 (27/8) + 15 (9/4) - 24 (3/2) + 12) / 6 = -1/16 at 3/2.
        let cr = Filter::CatmullRom;
        assert!(close(cr.weight(0.0), 1.0) && close(cr.weight(1.0), 0.0));
        assert!(close(cr.weight(0.5), 9.0 / 16.0) && close(cr.weight(-1.5), -1.0 / 16.0));
        // Lanczos, 3 lobes: sin(pi x) sin(pi x / 3) / (pi^2 x^2 / 3): 1 at 0,
        // 6 / pi^2 at 1/2, -4 / (3 pi^2) at 3/2, 0 at the whole pixels and beyond 3.
        let pi2 = std::f64::consts::PI * std::f64::consts::PI;
        assert_eq!(LANCZOS.weight(0.0), 1.0);
        assert!(close(LANCZOS.weight(0.5), 6.0 / pi2) && close(LANCZOS.weight(-1.5), -4.0 / (3.0 * pi2)));
        assert!(LANCZOS.weight(1.0).abs() < 1e-15 && LANCZOS.weight(2.0).abs() < 1e-15);
        assert!((LANCZOS.weight(1e-6) - 1.0).abs() < 1e-11 && LANCZOS.weight(3.5) == 0.0);
        // Two lobes at 1/2: sin(pi/2) sin(pi/4) / (pi^2 / 8).
        assert!(close(Filter::Lanczos { lobes: 2 }.weight(0.5), std::f64::consts::FRAC_1_SQRT_2 * 8.0 / pi2));
    }

    #[test]
    fn signed_filters_are_normalised_as_mitsubas() {
        // The Mitchell-Netravali family has area 1 for every B, C (0.5 + (C/2 - B/4) / 6
        // below 1 on each side, (B/4 - C/2) / 6 between 1 and 2); the sinc's area
        // is left to quadrature: Mitsuba divides by the sum of weights, so the
        // area scales nothing.
        for f in [MITCHELL, Filter::CatmullRom, Filter::Mitchell { b: 0.8, c: 0.1 }] {
            assert!((f.cumulative(2.0) - 1.0).abs() < 1e-13, "{f:?}: {}", f.cumulative(2.0));
            assert!((f.cumulative(0.0) - 0.5).abs() < 1e-13 && (f.cumulative(1.0) - (1.0 - f.cumulative(-1.0))).abs() < 1e-13);
        }
        for f in SIGNED {
            let r = f.radius();
            assert_eq!(f.cumulative(-r), 0.0);
            for x in [-0.9 * r, -1.3, -0.3, 0.0, 0.2, 1.0, 1.7, r] {
                let exact = integral(|t| f.weight(t), -r, x);
                assert!((f.cumulative(x) - exact).abs() < 1e-8, "{f:?} at {x}: {} vs {exact}", f.cumulative(x));
            }
            let table = SignedTable::new(f);
            for x in [-0.77 * r, -0.5, 0.013, 0.5, 1.5, r] {
                assert!((table.signed_at(x) - f.cumulative(x)).abs() < 1e-13, "{f:?} at {x}");
            }
        }
    }

    #[test]
    fn signed_sampling_gives_the_filter_weighted_mean() {
        // For a constant image the mean weight is 1, for a ramp g the mean of
        // g(x) times the weight the f-weighted mean of g over the interval
        // (by quadrature), on each axis and in 2D, to 1e-4 at 200 000 (1D) and
        // 1e-3 at 40 000 (2D) stratified samples (the Lanczos sinc's 1D mean is
        // off by 1.2e-4 at 20 000: stratification, not bias).
        let g = |x: f64| 0.3 + 0.7 * x;
        for f in SIGNED {
            let sampler = FilterSampler::new(f);
            let table = sampler.table.as_ref().unwrap();
            let r = f.radius();
            for (lo, hi) in [(-f64::INFINITY, f64::INFINITY), (-0.5, f64::INFINITY), (-0.5, 0.5), (-1.5, 0.6), (-r, 1.25)] {
                let (a, b) = (f64::max(lo, -r), f64::min(hi, r));
                let mass = integral(|t| f.weight(t), a, b);
                let ramp = integral(|t| g(t) * f.weight(t), a, b) / mass;
                let bound = 4.0 * integral(|t| f.weight(t).abs(), a, b) / mass;
                let n = 200_000;
                let xs: Vec<(f64, f64)> = (0..n).map(|i| table.sample_axis((i as f64 + 0.5) / n as f64, lo, hi)).collect();
                assert!(xs.iter().all(|&(x, w)| x >= a && x <= b && w.abs() <= bound), "{f:?} [{lo}, {hi}]");
                let m0 = xs.iter().map(|(_, w)| w).sum::<f64>() / n as f64;
                let m1 = xs.iter().map(|(x, w)| g(*x) * w).sum::<f64>() / n as f64;
                assert!((m0 - 1.0).abs() < 1e-4, "{f:?} [{lo}, {hi}]: weights average {m0}");
                assert!((m1 - ramp).abs() < 1e-4, "{f:?} [{lo}, {hi}]: {m1} vs {ramp}");
                // 2D: a Fibonacci-like lattice of 40 000 points (both projections
                // well stratified), the ramp g(x) + g(y) / 2.
                let (mut w2, mut g2) = (0.0, 0.0);
                for i in 0..40_000 {
                    let t = i as f64 + 0.5;
                    let u = (t / 40_000.0, (t * 0.618_033_988_749_894_8).fract());
                    let ((x, y), w) = sampler.sample_in(u, (lo, -f64::INFINITY), (hi, 0.5));
                    assert!(w.is_finite());
                    w2 += w;
                    g2 += w * (g(x) + 0.5 * g(y));
                }
                let ramp_y = integral(|t| g(t) * f.weight(t), -r, 0.5) / integral(|t| f.weight(t), -r, 0.5);
                assert!((w2 / 40_000.0 - 1.0).abs() < 1e-3, "{f:?} [{lo}, {hi}] 2D: {}", w2 / 40_000.0);
                assert!((g2 / 40_000.0 - ramp - 0.5 * ramp_y).abs() < 1e-3, "{f:?} [{lo}, {hi}] 2D ramp: {}", g2 / 40_000.0);
            }
        }
    }

    #[test]
    fn signed_sampling_stays_finite() {
        // Outside the bounds: the pixel square. A filter whose weight over the
        // interval is not positive (B = 0, C = 8: a negative lobe of area 1.3
        // beyond 1 pixel) falls back to it too, every weight finite.
        let table = SignedTable::new(LANCZOS);
        assert_eq!(table.sample_axis(0.25, 4.0, 5.0), (-0.25, 1.0));
        let wild = SignedTable::new(Filter::Mitchell { b: 0.0, c: 8.0 });
        assert!(wild.signed_at(2.0) - wild.signed_at(0.9) < 0.0);
        assert_eq!(wild.sample_axis(0.75, 0.9, f64::INFINITY), (0.25, 1.0));
        for i in 0..1000 {
            let u = (i as f64 + 0.5) / 1000.0;
            for (lo, hi) in [(-9.0, 9.0), (-0.5, 2.0), (-0.5, 0.5), (0.0, 0.01), (1.999, 2.5)] {
                for t in [&table, &wild] {
                    let (x, w) = t.sample_axis(u, lo, hi);
                    assert!(x.is_finite() && w.is_finite(), "{:?} [{lo}, {hi}] u {u}: {x} {w}", t.filter);
                }
            }
        }
    }

    #[test]
    fn the_sampler_keeps_the_unsigned_filters() {
        for f in [Filter::Box, Filter::Tent, GAUSS] {
            let sampler = FilterSampler::new(f);
            assert!(sampler.table.is_none() && sampler.filter() == f);
            for (u, lo, hi) in [((0.1, 0.8), (-0.5, -1.0), (2.0, 0.7)), ((0.5, 0.33), (-9.0, -9.0), (9.0, 9.0))] {
                assert_eq!(sampler.sample_in(u, lo, hi), f.sample_in(u, lo, hi));
            }
        }
        // Filter::sample_in of a signed filter is its sampler's.
        assert_eq!(
            LANCZOS.sample_in((0.3, 0.6), (-1.0, -2.0), (4.0, 0.5)),
            FilterSampler::new(LANCZOS).sample_in((0.3, 0.6), (-1.0, -2.0), (4.0, 0.5))
        );
    }

    #[test]
    fn names_parse() {
        assert_eq!("tent".parse::<Filter>(), Ok(Filter::Tent));
        assert_eq!("gaussian".parse::<Filter>(), Ok(GAUSS));
        assert_eq!("mitchell".parse::<Filter>(), Ok(MITCHELL));
        assert_eq!("catmullrom".parse::<Filter>(), Ok(Filter::CatmullRom));
        assert_eq!("lanczos".parse::<Filter>(), Ok(LANCZOS));
        assert_eq!("mitchell(B=0.5, C=0.25)".parse::<Filter>(), Ok(Filter::Mitchell { b: 0.5, c: 0.25 }));
        assert_eq!("mitchell(C=0)".parse::<Filter>(), Ok(Filter::Mitchell { b: 1.0 / 3.0, c: 0.0 }));
        assert_eq!("lanczos(lobes=2)".parse::<Filter>(), Ok(Filter::Lanczos { lobes: 2 }));
        for f in [
            Filter::Box,
            Filter::Tent,
            GAUSS,
            MITCHELL,
            Filter::CatmullRom,
            LANCZOS,
            Filter::Mitchell { b: 0.1, c: 0.45 },
            Filter::Lanczos { lobes: 5 },
        ] {
            assert_eq!(f.to_string().parse::<Filter>(), Ok(f), "{f}");
        }
        assert_eq!(Filter::Lanczos { lobes: 5 }.to_string(), "lanczos(lobes=5)");
        assert_eq!(
            "sinc".parse::<Filter>(),
            Err("unknown filter \"sinc\" (filters: box, tent, gaussian, mitchell, catmullrom, lanczos)".into())
        );
        assert_eq!(
            "lanczos(lobes=0)".parse::<Filter>(),
            Err("filter \"lanczos(lobes=0)\": lobes must be a whole number from 1 to 32, got 0".into())
        );
        assert_eq!("mitchell(B=nan)".parse::<Filter>(), Err("filter \"mitchell(B=nan)\": B must be a finite number, got \"nan\"".into()));
        assert_eq!("tent(radius=2)".parse::<Filter>(), Err("filter \"tent(radius=2)\": \"tent\" takes no parameters".into()));
        assert_eq!(
            "lanczos(taps=2)".parse::<Filter>(),
            Err("filter \"lanczos(taps=2)\": unknown parameter \"taps\" (\"lanczos\" takes lobes)".into())
        );
    }
}
