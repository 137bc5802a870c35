//! Mitsuba 3's `principledthin` BSDF: the principled model of a thin sheet
//! (Burley 2015, "Extending the Disney BRDF to a BSDF", thin surfaces), term by
//! term as Mitsuba's `src/bsdfs/principledthin.cpp` defines it.
//!
//! The sheet has the same medium on both sides and scatters the same from both:
//! with `v` (towards the viewer) turned to `+z` and `l` the other direction,
//! `l_r = (l.x, l.y, |l.z|)`, `h = normalize(v + l_r)`, `F` the dielectric Fresnel
//! of `v.h` at the sheet's `eta`, `st = spec_trans`, `dt = diff_trans / 2`, GGX
//! of `alpha = max(0.001, roughness^2)` and of the scaled
//! `alpha_t = max(0.001, ((0.65 eta - 0.35) roughness)^2)` for transmission (Burley's
//! Figure 15; each a pair along and across `dp/du` when `anisotropic > 0`,
//! `principled/ggx.rs`), the value `f |cos_l|` is the sum of:
//!
//! - glossy reflection (`l.z > 0`): `st F_thin D G / (4 cos_v)`, with
//!   `F_thin = lerp(F, S(C_tint R0(eta)), spec_tint)` (Mitsuba's Schlick `S`,
//!   [`super::principled`]);
//! - glossy transmission (`l.z < 0`, the reflection through `h` turned to the far
//!   side, no bending): `st C (1 - F) D_t G_t / (4 cos_v)`;
//! - diffuse reflection: `(1 - st)(1 - dt) C / pi cos_l` times Burley's shape
//!   ([`super::principled::burley_diffuse`], with `flatness`), plus the sheen
//!   `sheen (1 - st)(1 - dt) sw(h.l) lerp(1, C_tint, sheen_tint) cos_l`;
//! - diffuse transmission: `(1 - st) dt C / pi |cos_l|`.
//!
//! Sampling chooses glossy reflection, glossy transmission, cosine reflection and
//! cosine transmission with weights `st r_sr / 2`, `st r_st / 2`,
//! `r_dr (1 - st)(1 - dt)` and `r_dt (1 - st) dt` (the sampling rates `r`).

use std::f64::consts::FRAC_1_PI;

use super::principled::ggx::{self, smith_g1, visible_pdf};
use super::principled::{burley_diffuse, compatible, fresnel, luminance, schlick, schlick_r0, schlick_weight};
use super::{lambertian, Sampled, Scatter};
use crate::math::{Rgb, Vec3};

/// The parameters of a thin principled sheet besides its base colour.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ThinParams {
    /// `roughness`, 0 to 1.
    pub roughness: f64,
    /// `anisotropic`, 0 to 1 (`principled::ggx::alphas`); 0 is isotropic.
    pub anisotropic: f64,
    /// `spec_trans`, 0 to 1: the glossy share.
    pub spec_trans: f64,
    /// Half of Mitsuba's `diff_trans` (0 to 2): the diffuse share that transmits.
    pub diff_trans: f64,
    /// The sheet's relative index `eta`.
    pub eta: f64,
    /// `spec_tint`, 0 to 1.
    pub spec_tint: f64,
    /// `sheen`, 0 to 1.
    pub sheen: f64,
    /// `sheen_tint`, 0 to 1.
    pub sheen_tint: f64,
    /// `flatness`, 0 to 1.
    pub flatness: f64,
    /// Sampling rates of glossy reflection, glossy transmission, diffuse reflection
    /// and diffuse transmission.
    pub rates: [f64; 4],
}

impl Default for ThinParams {
    /// Mitsuba's defaults: roughness 0.5, `eta` 1.5, every weight 0, rates 1.
    fn default() -> ThinParams {
        ThinParams {
            roughness: 0.5,
            anisotropic: 0.0,
            spec_trans: 0.0,
            diff_trans: 0.0,
            eta: 1.5,
            spec_tint: 0.0,
            sheen: 0.0,
            sheen_tint: 0.0,
            flatness: 0.0,
            rates: [1.0; 4],
        }
    }
}

/// The thin principled lobe at a shading point (the same from both sides, so
/// lamplight's local frame is its own).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PrincipledThin {
    base: Rgb,
    p: ThinParams,
}

impl PrincipledThin {
    /// The lobe of base colour `base` and `params`.
    pub fn new(base: Rgb, params: ThinParams) -> PrincipledThin {
        PrincipledThin { base, p: params }
    }

    /// The GGX roughness of reflection and of transmission (each `(a_u, a_v)`).
    fn alphas(&self) -> ((f64, f64), (f64, f64)) {
        let r = self.p.roughness;
        let rt = (0.65 * self.p.eta - 0.35) * r;
        (ggx::alphas(r, self.p.anisotropic), ggx::alphas(rt, self.p.anisotropic))
    }

    /// The probabilities of glossy reflection, glossy transmission, diffuse
    /// reflection and diffuse transmission.
    fn probabilities(&self) -> [f64; 4] {
        let (st, dt, r) = (self.p.spec_trans, self.p.diff_trans, self.p.rates);
        let p = [st * r[0] / 2.0, st * r[1] / 2.0, r[2] * (1.0 - st) * (1.0 - dt), r[3] * (1.0 - st) * dt];
        let total: f64 = p.iter().sum();
        if !(total > 0.0) {
            return [0.0; 4];
        }
        p.map(|x| x / total)
    }

    fn half(v: Vec3, l: Vec3) -> Option<Vec3> {
        (v + Vec3::new(l.x, l.y, l.z.abs())).try_normalize()
    }

    /// The value `f` (without the cosine) for `wo.z > 0`.
    pub fn f(&self, wo: Vec3, wi: Vec3) -> Rgb {
        let (v, l) = (wo, wi);
        if v.z <= 0.0 || l.z == 0.0 {
            return Rgb::ZERO;
        }
        let Some(h) = Self::half(v, l) else { return Rgb::ZERO };
        let (st, dt, base) = (self.p.spec_trans, self.p.diff_trans, self.base);
        let (alpha, alpha_t) = self.alphas();
        let reflect = l.z > 0.0;
        let vh = v.dot(h);
        let f = fresnel(vh, self.p.eta);
        let lum = luminance(base);
        let tint = if lum > 0.0 { base / lum } else { Rgb::ONE };
        // Each term is `f cos_l`; the cosine is divided out at the end.
        let mut value = Rgb::ZERO;
        if st > 0.0 && reflect && compatible(h, v, l, true) {
            let schlick_tint = schlick(tint * schlick_r0(self.p.eta), vh, self.p.eta);
            let f_thin = Rgb::splat(f) * (1.0 - self.p.spec_tint) + schlick_tint * self.p.spec_tint;
            let g = smith_g1(alpha, v, h) * smith_g1(alpha, l, h);
            value += f_thin * (st * ggx::d(alpha, h) * g / (4.0 * v.z));
        }
        if st > 0.0 && !reflect && compatible(h, v, l, false) {
            let g = smith_g1(alpha_t, v, h) * smith_g1(alpha_t, l, h);
            value += base * (st * (1.0 - f) * ggx::d(alpha_t, h) * g / (4.0 * v.z));
        }
        if reflect && st < 1.0 && dt < 1.0 {
            let lh = l.dot(h);
            let (fl, fv) = (schlick_weight(l.z), schlick_weight(v.z));
            let rr = 2.0 * self.p.roughness * lh * lh;
            let shape = burley_diffuse(fv, fl, rr, v.z, l.z, self.p.flatness);
            value += base * ((1.0 - st) * l.z * FRAC_1_PI * (1.0 - dt) * shape);
            if self.p.sheen > 0.0 {
                let sheen = Rgb::ONE + (tint - Rgb::ONE) * self.p.sheen_tint;
                value += sheen * (self.p.sheen * (1.0 - st) * schlick_weight(lh.abs()) * (1.0 - dt) * l.z);
            }
        }
        if !reflect && st < 1.0 && dt > 0.0 {
            value += base * ((1.0 - st) * dt * FRAC_1_PI * l.z.abs());
        }
        value / l.z.abs()
    }

    /// The solid-angle density of [`PrincipledThin::sample`].
    pub fn pdf(&self, wo: Vec3, wi: Vec3) -> f64 {
        let (v, l) = (wo, wi);
        if v.z <= 0.0 || l.z == 0.0 {
            return 0.0;
        }
        let [p_reflect, p_transmit, p_diffuse, p_diffuse_t] = self.probabilities();
        let (alpha, alpha_t) = self.alphas();
        let mut pdf = 0.0;
        if let Some(h) = Self::half(v, l) {
            let jacobian = (1.0 / (4.0 * Vec3::new(l.x, l.y, l.z.abs()).dot(h))).abs();
            if l.z > 0.0 && compatible(h, v, l, true) {
                pdf += p_reflect * visible_pdf(alpha, v, h) * jacobian;
            }
            if l.z < 0.0 && compatible(h, v, l, false) {
                pdf += p_transmit * visible_pdf(alpha_t, v, h) * jacobian;
            }
        }
        pdf + if l.z > 0.0 { p_diffuse } else { p_diffuse_t } * l.z.abs() * FRAC_1_PI
    }

    /// A direction for `wo` (`wo.z > 0`): `u_choice` picks the lobe.
    pub fn sample(&self, wo: Vec3, u_choice: f64, u: (f64, f64)) -> Option<Vec3> {
        let v = wo;
        if v.z <= 0.0 {
            return None;
        }
        let [p_reflect, p_transmit, p_diffuse, _] = self.probabilities();
        let (alpha, alpha_t) = self.alphas();
        if u_choice < p_reflect + p_transmit {
            let transmit = u_choice >= p_reflect;
            let m = ggx::visible_normal(if transmit { alpha_t } else { alpha }, v, u);
            let mut l = m * (2.0 * v.dot(m)) - v;
            if transmit {
                l.z = -l.z;
            }
            let ok = if transmit { l.z < 0.0 } else { l.z > 0.0 } && compatible(m, v, l, !transmit);
            return ok.then_some(l);
        }
        let l = lambertian::sample(u);
        Some(if u_choice < p_reflect + p_transmit + p_diffuse { l } else { Vec3::new(l.x, l.y, -l.z) })
    }
}

// `PrincipledThin::f` and the like name the inherent methods (which come before a trait's).
impl Scatter for PrincipledThin {
    const DELTA: bool = false;

    fn bound(&self) -> Rgb {
        Rgb::ONE
    }

    #[inline]
    fn f(&self, wo: Vec3, wi: Vec3) -> Rgb {
        PrincipledThin::f(self, wo, wi)
    }

    #[inline]
    fn pdf(&self, wo: Vec3, wi: Vec3) -> f64 {
        PrincipledThin::pdf(self, wo, wi)
    }

    #[inline]
    fn sample(&self, wo: Vec3, u_choice: f64, u: (f64, f64)) -> Option<Sampled> {
        PrincipledThin::sample(self, wo, u_choice, u).map(Sampled::Smooth)
    }

    fn needs_tangent(&self) -> bool {
        let (a, a_t) = self.alphas();
        a.0 != a.1 || a_t.0 != a_t.1
    }
}

#[cfg(test)]
mod tests;
