//! Checks shared by the lobes' and the materials' tests: the white furnace
//! (stratified albedo, of one lobe or of a whole BSDF), a
//! chi-square test of sampled directions against the stated pdf, and reciprocity.

use std::f64::consts::PI;

use super::Bsdf;
use crate::math::{Rgb, Vec3};
use crate::sampling::Rng;

/// Calls `visit(u_choice, u)` for the centres `u` of an `n x n` grid over the
/// unit square, with a one-dimensional choice (of a lobe or a branch) from a
/// golden-ratio sequence: the stratified pattern every furnace test samples with.
pub fn stratified_grid(n: usize, mut visit: impl FnMut(f64, (f64, f64))) {
    for i in 0..n {
        for j in 0..n {
            let u = ((i as f64 + 0.5) / n as f64, (j as f64 + 0.5) / n as f64);
            visit(((i * n + j) as f64 * 0.618_033_988_749_895).fract(), u);
        }
    }
}

/// `integral of d(h) cos(theta_h) d(omega)` over the upper hemisphere for a
/// distribution `d` symmetric about the normal, by the midpoint rule in
/// `c = cos theta` over `n` cells (`d(omega) = 2 pi dc` around the axis): 1
/// for a normalised microfacet distribution.
pub fn projected_area(n: usize, d: impl Fn(Vec3) -> f64) -> f64 {
    (0..n)
        .map(|i| {
            let c = (i as f64 + 0.5) / n as f64;
            d(Vec3::new((1.0 - c * c).sqrt(), 0.0, c)) * c * 2.0 * PI / n as f64
        })
        .sum()
}

/// Directional albedo (reflected and transmitted power over incident power,
/// `E[weight * eta^2]`) of `bsdf` for `wo`, estimated with stratified samples.
pub fn albedo(bsdf: &Bsdf, wo: Vec3) -> Rgb {
    let n = 128;
    let mut sum = Rgb::ZERO;
    stratified_grid(n, |u_lobe, u| {
        if let Some(s) = bsdf.sample(wo, u_lobe, u) {
            sum += s.weight * (s.eta * s.eta);
        }
    });
    sum / (n * n) as f64
}

/// One sample of a lobe, in one channel: direction and weight `f |cos| / pdf`
/// (for a delta branch, the branch's weight over its probability).
#[derive(Clone, Copy, Debug)]
pub enum Sampled {
    /// The weight of a delta branch's sample (not counted by the chi-square test).
    Delta(f64),
    /// From the part with a density.
    Smooth(Vec3, f64),
}

/// Directional albedo `E[weight]` over 256^2 stratified samples (the lobe choice
/// from a golden-ratio sequence), and the fraction that came from a delta branch.
pub fn furnace(mut sample: impl FnMut(f64, (f64, f64)) -> Option<Sampled>) -> (f64, f64) {
    let n = 256;
    let (mut sum, mut delta) = (0.0, 0.0);
    stratified_grid(n, |u_choice, u| match sample(u_choice, u) {
        Some(Sampled::Delta(w)) => {
            sum += w;
            delta += 1.0;
        }
        Some(Sampled::Smooth(_, w)) => sum += w,
        None => {}
    });
    let count = (n * n) as f64;
    (sum / count, delta / count)
}

const NX: usize = 40;
const NP: usize = 80;
const SUB: usize = 4;

/// The direction at fractions `(xf, pf)` of a grid over the sphere uniform in `x` and
/// in the angle around the x axis (equal solid angle per cell); the poles lie on
/// the x axis, away from the normal where the lobes peak.
fn cell_dir(xf: f64, pf: f64) -> Vec3 {
    let x = -1.0 + 2.0 * xf;
    let s = (1.0 - x * x).max(0.0).sqrt();
    let phi = 2.0 * PI * pf;
    Vec3::new(x, s * phi.cos(), s * phi.sin())
}

fn cell_of(v: Vec3) -> usize {
    let xf = (((v.x + 1.0) / 2.0 * NX as f64) as usize).min(NX - 1);
    let phi = v.z.atan2(v.y).rem_euclid(2.0 * PI);
    let pf = ((phi / (2.0 * PI) * NP as f64) as usize).min(NP - 1);
    xf * NP + pf
}

/// The Wilson-Hilferty z score of the chi-square statistic of `n` samples' smooth
/// directions against `pdf` integrated over each cell (cells expecting fewer than
/// 5 pooled). Under the null hypothesis it is a standard normal: a correct sampler
/// stays below 4 (fixed seeds, so no flakiness).
pub fn chi_square_z(pdf: impl Fn(Vec3) -> f64, mut sample: impl FnMut(f64, (f64, f64)) -> Option<Sampled>, n: usize, seed: u64) -> f64 {
    let mut observed = vec![0.0; NX * NP];
    let mut rng = Rng::for_sample(seed, 0, 0);
    for _ in 0..n {
        let (a, b, c) = (rng.uniform(), rng.uniform(), rng.uniform());
        if let Some(Sampled::Smooth(wi, _)) = sample(a, (b, c)) {
            observed[cell_of(wi)] += 1.0;
        }
    }
    let d_omega = 4.0 * PI / (NX * NP * SUB * SUB) as f64;
    let mut expected = vec![0.0; NX * NP];
    for i in 0..NX * SUB {
        for j in 0..NP * SUB {
            let wi = cell_dir((i as f64 + 0.5) / (NX * SUB) as f64, (j as f64 + 0.5) / (NP * SUB) as f64);
            expected[(i / SUB) * NP + j / SUB] += pdf(wi) * d_omega * n as f64;
        }
    }
    let (chi2, dof) = pooled_chi_square(&observed, &expected);
    let k = dof.saturating_sub(1).max(1) as f64;
    ((chi2 / k).cbrt() - (1.0 - 2.0 / (9.0 * k))) / (2.0 / (9.0 * k)).sqrt()
}

/// Pearson's chi-square of `observed` counts against `expected` ones, cell by
/// cell, the cells expecting fewer than 5 pooled into one: `(chi2, cells)`.
pub fn pooled_chi_square(observed: &[f64], expected: &[f64]) -> (f64, usize) {
    let (mut chi2, mut cells, mut pooled_o, mut pooled_e) = (0.0, 0usize, 0.0, 0.0);
    for (o, e) in observed.iter().zip(expected) {
        if *e < 5.0 {
            pooled_o += o;
            pooled_e += e;
        } else {
            chi2 += (o - e) * (o - e) / e;
            cells += 1;
        }
    }
    if pooled_e > 5.0 {
        chi2 += (pooled_o - pooled_e) * (pooled_o - pooled_e) / pooled_e;
        cells += 1;
    }
    (chi2, cells)
}

/// The mean of `g(u)` over an `n x n` grid of cell centres of the unit square:
/// a stratified estimate of `E[g]`.
pub fn stratified_mean(n: usize, mut g: impl FnMut((f64, f64)) -> f64) -> f64 {
    let mut sum = 0.0;
    for i in 0..n {
        for j in 0..n {
            sum += g(((i as f64 + 0.5) / n as f64, (j as f64 + 0.5) / n as f64));
        }
    }
    sum / (n * n) as f64
}

/// `integral of f(wi) cos(wi) d(omega)` over the upper hemisphere, by the
/// midpoint rule in `(cos theta, phi)` on a 2000 x 400 grid.
pub fn hemisphere_quadrature(f: impl Fn(Vec3) -> f64) -> f64 {
    let (nt, np) = (2000, 400);
    let mut sum = 0.0;
    for i in 0..nt {
        let c = (i as f64 + 0.5) / nt as f64;
        for j in 0..np {
            let phi = (j as f64 + 0.5) / np as f64 * 2.0 * PI;
            let s = (1.0 - c * c).sqrt();
            sum += f(Vec3::new(s * phi.cos(), s * phi.sin(), c)) * c * 2.0 * PI / (nt * np) as f64;
        }
    }
    sum
}

/// Largest `|f(a, b) - f(b, a)| / max(f, 1)` over 500 pairs of upper-hemisphere directions.
pub fn reciprocity_error(f: impl Fn(Vec3, Vec3) -> f64) -> f64 {
    let mut rng = Rng::for_sample(17, 0, 0);
    let mut dir = || {
        let c = 0.02 + 0.98 * rng.uniform();
        let phi = 2.0 * PI * rng.uniform();
        let s = (1.0 - c * c).sqrt();
        Vec3::new(s * phi.cos(), s * phi.sin(), c)
    };
    (0..500)
        .map(|_| {
            let (a, b) = (dir(), dir());
            let (x, y) = (f(a, b), f(b, a));
            (x - y).abs() / x.abs().max(y.abs()).max(1.0)
        })
        .fold(0.0, f64::max)
}
