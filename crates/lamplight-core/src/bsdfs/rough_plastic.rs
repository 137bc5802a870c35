//! Rough plastic: a diffuse base under a rough dielectric coating, Mitsuba 3's
//! `roughplastic`.
//!
//! With `eta = n_int / n_ext`, the microfacet distribution `D` (GGX or Beckmann,
//! [`Microfacet`]) and Smith's separable `G = G1(wo) G1(wi)` (Mitsuba's choice):
//!
//! - the coating reflects `f_s = ks F(wo.h) D(h) G / (4 cos_o cos_i)`,
//!   `h = normalize(wo + wi)`;
//! - the base's light leaves through the coating:
//!   `f_d = d / (1 - R_int) T(cos_o) T(cos_i) / (eta^2 pi)` (`d / (1 - d R_int)` with `nonlinear`).
//!
//! `T(cos)` is the coating's transmittance for light arriving from outside,
//! `E_h[(1 - F(wo.h)) G1(wt)]` over the normals visible from `wo` with `wt` the
//! refracted direction, and `R_int` its internal reflectance, the cosine-weighted
//! hemispherical mean `2 integral R(mu) mu dmu` of the reflectance seen from inside
//! (`eta -> 1 / eta`, reflected direction `wr`, `E_h[F G1(wr)]`). Both are
//! precomputed per `(distribution, alpha, eta)` as Mitsuba does: `T` at 64 cosines
//! `mu_i = max(i / 63, 1e-6)` (linearly interpolated), `R_int` as twice the mean of
//! `R(mu_i) mu_i` over the same 64 cosines; each expectation by a midpoint rule
//! over the normal sampler's unit square ([`CoatTable`]). The tables are made
//! once per process for each distinct coating and kept (a few hundred bytes each).
//!
//! Sampling picks the coating with probability `(1 - T(cos_o)) w / ((1 - T(cos_o)) w + T(cos_o) (1 - w))`,
//! `w` Mitsuba's specular sampling weight ([`Coating`]), else a cosine-weighted direction.

use std::f64::consts::FRAC_1_PI;
use std::sync::Mutex;

use super::distribution::{Distribution, Microfacet};
use super::fresnel::fresnel_dielectric;
use super::lambertian;
use super::plastic::{internal_scattering, specular_probability, Coating};
use super::rough_dielectric::refract;
use super::{Sampled, Scatter};
use crate::math::{Rgb, Vec3};

/// Cosines at which the transmittance is tabulated (Mitsuba's `MI_ROUGH_TRANSMITTANCE_RES`).
pub const RESOLUTION: usize = 64;
/// Midpoint-rule points per axis of each expectation.
const QUADRATURE: usize = 192;

/// A rough coating's transmittance table and internal reflectance.
#[derive(Debug, PartialEq)]
pub struct CoatTable {
    /// `T(mu_i)`.
    pub transmittance: [f64; RESOLUTION],
    /// `R_int`.
    pub internal_reflectance: f64,
}

impl CoatTable {
    /// `T(cos)`, linearly interpolated between the tabulated cosines.
    #[inline]
    pub fn transmittance(&self, cos: f64) -> f64 {
        let x = cos.clamp(0.0, 1.0) * (RESOLUTION - 1) as f64;
        let i = (x as usize).min(RESOLUTION - 2);
        let t = x - i as f64;
        self.transmittance[i] * (1.0 - t) + self.transmittance[i + 1] * t
    }
}

/// `E_h[g(h)]` over the normals visible from `wi`, the normals drawn by `m`'s sampler
/// and reweighted by the visible density over the sampler's density (1 for GGX).
fn visible_expectation(m: Microfacet, wi: Vec3, g: impl Fn(Vec3) -> f64) -> f64 {
    let n = QUADRATURE;
    let g1 = m.g1(wi);
    let mut sum = 0.0;
    for i in 0..n {
        for j in 0..n {
            let u = ((i as f64 + 0.5) / n as f64, (j as f64 + 0.5) / n as f64);
            let h = m.sample_normal(wi, u);
            let wi_h = wi.dot(h);
            let p = m.normal_pdf(wi, h);
            if wi_h <= 0.0 || !(p > 0.0) {
                continue;
            }
            let visible = g1 * wi_h * m.d(h) / wi.z;
            sum += g(h) * visible / p;
        }
    }
    sum / (n * n) as f64
}

fn compute(m: Microfacet, eta: f64) -> CoatTable {
    let mut transmittance = [0.0; RESOLUTION];
    let mut internal = 0.0;
    for (i, t) in transmittance.iter_mut().enumerate() {
        let mu = (i as f64 / (RESOLUTION - 1) as f64).max(1e-6);
        let wi = Vec3::new((1.0 - mu * mu).max(0.0).sqrt(), 0.0, mu);
        *t = visible_expectation(m, wi, |h| match refract(wi, h, eta) {
            Some(wt) if wt.z < 0.0 => (1.0 - fresnel_dielectric(wi.dot(h), eta)) * m.g1(wt),
            _ => 0.0,
        });
        let reflectance = visible_expectation(m, wi, |h| {
            let wr = h * (2.0 * wi.dot(h)) - wi;
            if wr.z <= 0.0 {
                return 0.0;
            }
            fresnel_dielectric(wi.dot(h), 1.0 / eta) * m.g1(wr)
        });
        internal += reflectance * mu;
    }
    CoatTable { transmittance, internal_reflectance: 2.0 * internal / RESOLUTION as f64 }
}

type Key = (Distribution, u64, u64);
static TABLES: Mutex<Vec<(Key, &'static CoatTable)>> = Mutex::new(Vec::new());

/// The table of the coating `(m, eta)`, computed on first use and kept for the process.
pub fn table(m: Microfacet, eta: f64) -> &'static CoatTable {
    let key = (m.distribution, m.alpha_u.to_bits(), eta.to_bits());
    let mut tables = TABLES.lock().unwrap_or_else(|e| e.into_inner());
    if let Some((_, t)) = tables.iter().find(|(k, _)| *k == key) {
        return t;
    }
    let t: &'static CoatTable = Box::leak(Box::new(compute(m, eta)));
    tables.push((key, t));
    t
}

/// The rough plastic lobe at a shading point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RoughPlastic {
    /// `d / (1 - R_int) / eta^2` (or its nonlinear form).
    diffuse: Rgb,
    specular: Rgb,
    eta: f64,
    specular_weight: f64,
    m: Microfacet,
    table: &'static CoatTable,
}

impl RoughPlastic {
    /// The lobe of base albedo `d` under `coating` of roughness `m`, whose table is `table`.
    pub fn new(d: Rgb, coating: &Coating, m: Microfacet, table: &'static CoatTable) -> RoughPlastic {
        let diffuse = internal_scattering(d, table.internal_reflectance, coating.nonlinear) / (coating.eta * coating.eta);
        RoughPlastic { diffuse, specular: coating.specular, eta: coating.eta, specular_weight: coating.specular_weight, m, table }
    }

    #[inline]
    fn specular_probability(&self, cos_o: f64) -> f64 {
        let t = self.table.transmittance(cos_o);
        specular_probability(1.0 - t, t, self.specular_weight)
    }

    /// `f_s + f_d` for `wo`, `wi` above the surface.
    #[inline]
    pub fn f(&self, wo: Vec3, wi: Vec3) -> Rgb {
        if wo.z <= 0.0 || wi.z <= 0.0 {
            return Rgb::ZERO;
        }
        let h = (wo + wi).normalize();
        let g = self.m.g1(wo) * self.m.g1(wi);
        let specular = fresnel_dielectric(wo.dot(h), self.eta) * self.m.d(h) * g / (4.0 * wo.z * wi.z);
        let diffuse = self.table.transmittance(wo.z) * self.table.transmittance(wi.z) * FRAC_1_PI;
        self.specular * specular + self.diffuse * diffuse
    }

    /// Density of [`RoughPlastic::sample`].
    #[inline]
    pub fn pdf(&self, wo: Vec3, wi: Vec3) -> f64 {
        if wo.z <= 0.0 || wi.z <= 0.0 {
            return 0.0;
        }
        let p = self.specular_probability(wo.z);
        p * self.m.pdf(wo, wi) + (1.0 - p) * lambertian::pdf(wo, wi)
    }

    /// The coating's reflection when `u_choice` falls below its probability, else a
    /// diffuse direction; `None` below the surface.
    pub fn sample(&self, wo: Vec3, u_choice: f64, u: (f64, f64)) -> Option<Vec3> {
        if wo.z <= 0.0 {
            return None;
        }
        if u_choice < self.specular_probability(wo.z) {
            self.m.sample(wo, u)
        } else {
            Some(lambertian::sample(u))
        }
    }
}

// `RoughPlastic::f` and the like name the inherent methods (which come before a trait's).
impl Scatter for RoughPlastic {
    const DELTA: bool = false;

    fn bound(&self) -> Rgb {
        Rgb::ONE
    }

    #[inline]
    fn f(&self, wo: Vec3, wi: Vec3) -> Rgb {
        RoughPlastic::f(self, wo, wi)
    }

    #[inline]
    fn pdf(&self, wo: Vec3, wi: Vec3) -> f64 {
        RoughPlastic::pdf(self, wo, wi)
    }

    #[inline]
    fn sample(&self, wo: Vec3, u_choice: f64, u: (f64, f64)) -> Option<Sampled> {
        RoughPlastic::sample(self, wo, u_choice, u).map(Sampled::Smooth)
    }
}

#[cfg(test)]
mod tests;
