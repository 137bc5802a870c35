//! Filters with negative lobes drawn from a table of `|f|` (see the parent
//! module doc): [`FilterSampler`] and its per-filter table.

use super::Filter;

/// The width in pixels of a cell of a signed filter's table: 1/64, so that
/// cells end on whole pixels, where the cubics change piece.
pub(super) const CELL: f64 = 1.0 / 64.0;

/// The integral of `g` over `[a, b]` by 8-point Gauss-Legendre quadrature
/// (exact for polynomials of degree up to 15).
pub(super) fn gauss_legendre(g: impl Fn(f64) -> f64, a: f64, b: f64) -> f64 {
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
    pub(super) filter: Filter,
    pub(super) table: Option<Box<SignedTable>>,
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
pub(super) struct SignedTable {
    pub(super) filter: Filter,
    pub(super) radius: f64,
    pub(super) signed: Vec<f64>,
    pub(super) magnitude: Vec<f64>,
}

impl SignedTable {
    pub(super) fn new(filter: Filter) -> SignedTable {
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
    pub(super) fn cell(&self, x: f64) -> (usize, f64) {
        let k = (((x + self.radius) / CELL).floor().max(0.0) as usize).min(self.signed.len() - 2);
        (k, -self.radius + k as f64 * CELL)
    }

    /// The cumulative weight at `x` in the support: the table's cells before
    /// `x`'s, and the quadrature over the part of its cell before `x`.
    pub(super) fn signed_at(&self, x: f64) -> f64 {
        if x >= self.radius {
            return self.signed[self.signed.len() - 1];
        }
        let (k, x0) = self.cell(x);
        self.signed[k] + gauss_legendre(|t| self.filter.weight(t), x0, x)
    }

    /// The cumulative density at `x` in the support (linear in each cell).
    pub(super) fn magnitude_at(&self, x: f64) -> f64 {
        let (k, x0) = self.cell(x);
        self.magnitude[k] + ((x - x0) / CELL).min(1.0) * (self.magnitude[k + 1] - self.magnitude[k])
    }

    /// One axis: the offset for `u` drawn from the tabulated `|f|` restricted
    /// to `[lo, hi]` and the support, with weight `f(x) / (p(x) M)`: `p` the
    /// restricted density and `M` the weight's integral over the same interval.
    /// Its mean over `u` is 1 and of `g(x)` times it the `f`-weighted mean of `g`.
    pub(super) fn sample_axis(&self, u: f64, lo: f64, hi: f64) -> (f64, f64) {
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
