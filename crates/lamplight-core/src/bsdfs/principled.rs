//! Mitsuba 3's `principled` BSDF (Burley 2012, "Physically Based Shading at
//! Disney", and 2015, "Extending the Disney BRDF to a BSDF"), term by term as
//! Mitsuba's `src/bsdfs/principled.cpp` and `principledhelpers.h` define it, so
//! that images match Mitsuba's.
//!
//! Written in Mitsuba's frame: `v` is the direction towards the viewer
//! (Mitsuba's `si.wi`, lamplight's `wo`), `l` the other one (Mitsuba's `wo`),
//! `z` the outward shading normal, so `v.z < 0` when the ray arrived from
//! inside. With `brdf = (1 - metallic)(1 - spec_trans)`,
//! `bsdf = (1 - metallic) spec_trans`, GGX of `alpha = max(0.001, roughness^2)`
//! (a pair along and across `dp/du` when `anisotropic > 0`, `principled/ggx.rs`)
//! (`D`, and the separable Smith `G = G1(v) G1(l)` with Mitsuba's orientation
//! checks), `eta_p` the index across the boundary along the path (`eta` from
//! outside, `1 / eta` from inside), `h` the half vector `v + l` (reflection) or
//! `v + eta_p l` (refraction) turned to `+z`, `F` the exact dielectric Fresnel
//! of `v.h`, `sw(c) = (1 - c)^5` and `R0(e) = ((e - 1) / (e + 1))^2`, the value
//! `f |cos_l|` is the sum of:
//!
//! - main reflection: `F_p D G / (4 |cos_v|)`, with
//!   `F_p = (1 - m)(1 - spec_tint) F + m S(C) + (1 - m) spec_tint S(C_tint R0(eta))`
//!   from outside and `bsdf F` from inside; `S(R0)` is Mitsuba's Schlick
//!   (`R0 + (1 - R0) sw(cos)`, the cosine of the refracted direction when the
//!   index falls), `C` the base colour, `C_tint = C / lum(C)`;
//! - transmission: `sqrt(C) bsdf |(1 - F) D G (v.h)(l.h) / (cos_v (v.h + eta_p l.h)^2)|`
//!   (radiance transport: the `eta_p^2` of the Jacobian cancels the `1 / eta_p^2`
//!   compression);
//! - clearcoat (outside only): `clearcoat / 4 S(0.04) D_gtr1(h) G_cc |cos_l|`, with
//!   GTR1 of `alpha = lerp(0.1, 0.001, clearcoat_gloss)` and
//!   `G_cc = g(v) g(l)`, `g = 2 / (1 + sqrt(1 + 0.25^2 tan^2))`;
//! - diffuse (outside only): `brdf C / pi |cos_l| (f_d + f_r)`, Burley's
//!   `f_d = (1 - sw(cos_v) / 2)(1 - sw(cos_l) / 2)` and retro-reflection
//!   `f_r = R_r (F_l + F_v + F_l F_v (R_r - 1))`, `R_r = 2 roughness (h.l)^2`,
//!   blended by `flatness` towards Burley's fake subsurface ([`burley_diffuse`]);
//! - sheen (outside, where the diffuse is): `sheen (1 - m) sw(h.l) lerp(1, C_tint, sheen_tint) |cos_l|`.
//!
//! Sampling (the same densities as Mitsuba's `sample` and `pdf`): from outside a
//! lobe is chosen with weights `diffuse_rate brdf` (cosine hemisphere),
//! `clearcoat_rate clearcoat / 4` (GTR1 normals) and `specular_rate` (GGX visible
//! normals), the last reflecting with probability `1 - bsdf (1 - F)` and refracting
//! otherwise; from inside only the GGX normals, reflecting with probability `F`.
//! Mitsuba's white principled reflects more than it receives at grazing angles
//! (the retro-reflection term), and so does this one.

use std::f64::consts::{FRAC_1_PI, PI};

use super::fresnel::fresnel_dielectric;
use super::{lambertian, Sampled, Scatter};
use crate::math::{Rgb, Vec3};

/// The parameters of a principled surface besides its base colour.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PrincipledParams {
    /// `roughness`, 0 to 1 (GGX `alpha = max(0.001, roughness^2)`).
    pub roughness: f64,
    /// `anisotropic`, 0 to 1: the GGX roughness along `dp/du` and across it
    /// (`ggx::alphas`); 0 is isotropic.
    pub anisotropic: f64,
    /// `metallic`, 0 to 1.
    pub metallic: f64,
    /// `spec_trans`, 0 to 1: the share of the dielectric that transmits.
    pub spec_trans: f64,
    /// Relative index `n_int / n_ext`.
    pub eta: f64,
    /// `spec_tint`, 0 to 1.
    pub spec_tint: f64,
    /// `sheen`, 0 to 1.
    pub sheen: f64,
    /// `sheen_tint`, 0 to 1.
    pub sheen_tint: f64,
    /// `clearcoat`, 0 to 1.
    pub clearcoat: f64,
    /// `clearcoat_gloss`, 0 to 1.
    pub clearcoat_gloss: f64,
    /// `flatness`, 0 to 1: blends the diffuse towards Burley's fake subsurface.
    pub flatness: f64,
    /// `diffuse_reflectance_sampling_rate`.
    pub diffuse_rate: f64,
    /// `main_specular_sampling_rate`.
    pub specular_rate: f64,
    /// `clearcoat_sampling_rate`.
    pub clearcoat_rate: f64,
}

impl Default for PrincipledParams {
    /// Mitsuba's defaults: roughness 0.5, `specular` 0.5 (`eta` 1.5), every other weight 0, rates 1.
    fn default() -> PrincipledParams {
        PrincipledParams {
            roughness: 0.5,
            anisotropic: 0.0,
            metallic: 0.0,
            spec_trans: 0.0,
            eta: eta_from_specular(0.5),
            spec_tint: 0.0,
            sheen: 0.0,
            sheen_tint: 0.0,
            clearcoat: 0.0,
            clearcoat_gloss: 0.0,
            flatness: 0.0,
            diffuse_rate: 1.0,
            specular_rate: 1.0,
            clearcoat_rate: 1.0,
        }
    }
}

/// Mitsuba's index for a `specular` strength `s`: `eta = 2 / (1 - sqrt(0.08 s)) - 1`
/// (the inverse of `R0(eta) = 0.08 s`).
pub fn eta_from_specular(s: f64) -> f64 {
    2.0 / (1.0 - (0.08 * s).sqrt()) - 1.0
}

/// Luminance of a linear sRGB colour (Mitsuba's `luminance`, Rec. 709 weights).
#[inline]
pub fn luminance(c: Rgb) -> f64 {
    0.212671 * c.x + 0.715160 * c.y + 0.072169 * c.z
}

/// Schlick's weight `clamp(1 - c, 0, 1)^5`.
#[inline]
pub(super) fn schlick_weight(c: f64) -> f64 {
    let m = (1.0 - c).clamp(0.0, 1.0);
    let m2 = m * m;
    m2 * m2 * m
}

/// `R0(eta) = ((eta - 1) / (eta + 1))^2`.
#[inline]
pub(super) fn schlick_r0(eta: f64) -> f64 {
    let r = (eta - 1.0) / (eta + 1.0);
    r * r
}

/// Mitsuba's `calc_schlick`: `R0 + (1 - R0) sw(|cos|)` where the index rises along
/// the ray (`cos >= 0` sees `eta`, `cos < 0` sees `1 / eta`), else the same with
/// the refracted direction's cosine (0 under total internal reflection).
#[inline]
pub(super) fn schlick(r0: Rgb, cos: f64, eta: f64) -> Rgb {
    let eta_it = if cos >= 0.0 { eta } else { 1.0 / eta };
    let c = if eta_it > 1.0 {
        cos.abs()
    } else {
        let eta_ti = 1.0 / eta_it;
        (1.0 - (1.0 - cos * cos) * eta_ti * eta_ti).max(0.0).sqrt()
    };
    let w = schlick_weight(c);
    r0 + (Rgb::ONE - r0) * w
}

/// The exact dielectric Fresnel reflectance for `cos = v.h`, from either side
/// (Mitsuba's `fresnel`: `cos < 0` meets `1 / eta`).
#[inline]
pub(super) fn fresnel(cos: f64, eta: f64) -> f64 {
    if cos >= 0.0 {
        fresnel_dielectric(cos, eta)
    } else {
        fresnel_dielectric(-cos, 1.0 / eta)
    }
}

/// GTR1 (Burley's clearcoat distribution) of roughness `a`:
/// `D(m) = (a^2 - 1) / (pi ln(a^2) (1 + (a^2 - 1) cos^2))`.
#[inline]
fn gtr1(a: f64, m: Vec3) -> f64 {
    let a2 = a * a;
    let d = (a2 - 1.0) / (PI * a2.ln() * (1.0 + (a2 - 1.0) * m.z * m.z));
    if d * m.z > 1e-20 {
        d
    } else {
        0.0
    }
}

/// A GTR1 normal, density `D(m) cos(theta_m)`: `cos^2 = (1 - a^{2 (1 - u_2)}) / (1 - a^2)`.
fn sample_gtr1(a: f64, u: (f64, f64)) -> Vec3 {
    let a2 = a * a;
    let phi = 2.0 * PI * u.0;
    let cos2 = (1.0 - a2.powf(1.0 - u.1)) / (1.0 - a2);
    let sin = (1.0 - cos2).max(0.0).sqrt();
    let cos = cos2.max(0.0).sqrt();
    Vec3::new(phi.cos() * sin, phi.sin() * sin, cos)
}

/// The clearcoat's separable masking `g(v) g(l)`, `g = 2 / (1 + sqrt(1 + 0.25^2 tan^2))`,
/// 0 for a direction on the other side of `m` (Mitsuba's `clearcoat_G`).
#[inline]
fn clearcoat_g(v: Vec3, l: Vec3, m: Vec3) -> f64 {
    let g = |w: Vec3| {
        if w.dot(m) * w.z <= 0.0 {
            return 0.0;
        }
        if w.z == 1.0 {
            return 1.0;
        }
        let c2 = w.z * w.z;
        2.0 / (1.0 + (1.0 + 0.0625 * (1.0 - c2) / c2).sqrt())
    };
    g(v) * g(l)
}

/// Mitsuba's macro/micro-surface check: `v` and `l` on the sides of `m` a
/// reflection (or refraction) needs, `m` turned to `v`'s side.
#[inline]
pub(super) fn compatible(m: Vec3, v: Vec3, l: Vec3, reflection: bool) -> bool {
    let m = if v.z < 0.0 { -m } else { m };
    v.dot(m) > 0.0 && if reflection { l.dot(m) > 0.0 } else { l.dot(m) < 0.0 }
}

/// The principled lobe at a shading point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Principled {
    base: Rgb,
    p: PrincipledParams,
    /// Whether the ray arrived on the outward side (lamplight's local `+z` is
    /// then Mitsuba's; otherwise `z` is mirrored).
    front: bool,
}

/// The geometry of a pair `(v, l)` in Mitsuba's frame.
struct Pair {
    reflect: bool,
    eta_path: f64,
    h: Vec3,
    f: f64,
}

impl Principled {
    /// The lobe of base colour `base` and `params`, for a ray on the outward side when `front`.
    pub fn new(base: Rgb, params: PrincipledParams, front: bool) -> Principled {
        Principled { base, p: params, front }
    }

    fn alpha(&self) -> (f64, f64) {
        ggx::alphas(self.p.roughness, self.p.anisotropic)
    }

    /// Lamplight's local direction in Mitsuba's frame.
    #[inline]
    fn in_mitsuba_frame(&self, w: Vec3) -> Vec3 {
        if self.front {
            w
        } else {
            Vec3::new(w.x, w.y, -w.z)
        }
    }

    fn weights(&self) -> (f64, f64) {
        let m = self.p.metallic;
        ((1.0 - m) * (1.0 - self.p.spec_trans), (1.0 - m) * self.p.spec_trans)
    }

    /// Half vector (turned to `+z`), index along the path and Fresnel of `(v, l)`.
    fn pair(&self, v: Vec3, l: Vec3) -> Option<Pair> {
        if v.z == 0.0 || l.z == 0.0 {
            return None;
        }
        let reflect = v.z * l.z > 0.0;
        let eta_path = if v.z > 0.0 { self.p.eta } else { 1.0 / self.p.eta };
        let h = (v + l * if reflect { 1.0 } else { eta_path }).try_normalize()?;
        let h = if h.z < 0.0 { -h } else { h };
        Some(Pair { reflect, eta_path, h, f: fresnel(v.dot(h), self.p.eta) })
    }

    /// The lobe probabilities `(diffuse, clearcoat, specular reflection, transmission)`
    /// for Fresnel `f` (Mitsuba's, normalized).
    fn probabilities(&self, front: bool, f: f64) -> [f64; 4] {
        let (brdf, bsdf) = self.weights();
        let p = if front {
            [
                brdf * self.p.diffuse_rate,
                0.25 * self.p.clearcoat * self.p.clearcoat_rate,
                self.p.specular_rate * (1.0 - bsdf * (1.0 - f)),
                self.p.specular_rate * bsdf * (1.0 - f),
            ]
        } else {
            [0.0, 0.0, f, 1.0 - f]
        };
        let total: f64 = p.iter().sum();
        if !(total > 0.0) {
            return [0.0; 4];
        }
        p.map(|x| x / total)
    }

    /// Whether anything scatters for a ray on this side (from inside only the transmitting part).
    fn active(&self, v: Vec3) -> bool {
        v.z > 0.0 || self.weights().1 > 0.0
    }

    /// Mitsuba's `eval`: `f |cos_l|` for `v`, `l` in Mitsuba's frame.
    fn eval(&self, v: Vec3, l: Vec3) -> Rgb {
        if !self.active(v) {
            return Rgb::ZERO;
        }
        let Some(Pair { reflect, eta_path, h, f }) = self.pair(v, l) else { return Rgb::ZERO };
        let (brdf, bsdf) = self.weights();
        let (m, base, front) = (self.p.metallic, self.base, v.z > 0.0);
        let alpha = self.alpha();
        let d = ggx::d(alpha, h);
        let g = ggx::smith_g1(alpha, v, h) * ggx::smith_g1(alpha, l, h);
        let (vh, lh) = (v.dot(h), l.dot(h));
        let lum = luminance(base);
        let tint = if lum > 0.0 { base / lum } else { Rgb::ONE };
        let mut value = Rgb::ZERO;
        if reflect && compatible(h, v, l, true) && f > 0.0 {
            let fp = if front {
                let eta_it = if vh >= 0.0 { self.p.eta } else { 1.0 / self.p.eta };
                Rgb::splat((1.0 - m) * (1.0 - self.p.spec_tint) * f)
                    + schlick(base, vh, self.p.eta) * m
                    + schlick(tint * schlick_r0(eta_it), vh, self.p.eta) * ((1.0 - m) * self.p.spec_tint)
            } else {
                Rgb::splat(bsdf * f)
            };
            value += fp * (d * g / (4.0 * v.z.abs()));
        }
        if !reflect && bsdf > 0.0 && compatible(h, v, l, false) && f < 1.0 {
            let denom = vh + eta_path * lh;
            let t = ((1.0 - f) * d * g * vh * lh / (v.z * denom * denom)).abs();
            value += Rgb::new(base.x.sqrt(), base.y.sqrt(), base.z.sqrt()) * (bsdf * t);
        }
        if !(reflect && front) {
            return value;
        }
        if self.p.clearcoat > 0.0 && compatible(h, v, l, true) {
            let a = lerp(0.1, 0.001, self.p.clearcoat_gloss);
            let fcc = schlick(Rgb::splat(0.04), vh, self.p.eta).x;
            value += Rgb::splat(0.25 * self.p.clearcoat * fcc * gtr1(a, h) * clearcoat_g(v, l, h) * l.z.abs());
        }
        if brdf > 0.0 {
            let (fl, fv) = (schlick_weight(l.z.abs()), schlick_weight(v.z.abs()));
            let rr = 2.0 * self.p.roughness * lh * lh;
            let shape = burley_diffuse(fv, fl, rr, v.z.abs(), l.z.abs(), self.p.flatness);
            value += base * (brdf * l.z.abs() * FRAC_1_PI * shape);
            if self.p.sheen > 0.0 && 1.0 - m > 0.0 {
                let sheen = Rgb::ONE + (tint - Rgb::ONE) * self.p.sheen_tint;
                value += sheen * (self.p.sheen * (1.0 - m) * schlick_weight(lh.abs()) * l.z.abs());
            }
        }
        value
    }

    /// Mitsuba's `pdf` for `v`, `l` in Mitsuba's frame.
    fn density(&self, v: Vec3, l: Vec3) -> f64 {
        if !self.active(v) {
            return 0.0;
        }
        let Some(Pair { reflect, eta_path, h, f }) = self.pair(v, l) else { return 0.0 };
        let [p_diffuse, p_clearcoat, p_reflect, p_transmit] = self.probabilities(v.z > 0.0, f);
        let (vh, lh) = (v.dot(h), l.dot(h));
        let jacobian = if reflect {
            (1.0 / (4.0 * lh)).abs()
        } else {
            let denom = vh + eta_path * lh;
            (eta_path * eta_path * lh / (denom * denom)).abs()
        };
        let v_up = if v.z < 0.0 { -v } else { v };
        let normals = ggx::visible_pdf(self.alpha(), v_up, h) * jacobian;
        let mut pdf = 0.0;
        if reflect {
            if compatible(h, v, l, true) {
                pdf += p_reflect * normals;
                if p_clearcoat > 0.0 {
                    let a = lerp(0.1, 0.001, self.p.clearcoat_gloss);
                    pdf += p_clearcoat * h.z.max(0.0) * gtr1(a, h) * jacobian;
                }
            }
            pdf += p_diffuse * l.z.max(0.0) * FRAC_1_PI;
        } else if compatible(h, v, l, false) {
            pdf += p_transmit * normals;
        }
        pdf
    }

    /// The value `f` (without the cosine) in lamplight's local frame.
    #[inline]
    pub fn f(&self, wo: Vec3, wi: Vec3) -> Rgb {
        if wi.z == 0.0 {
            return Rgb::ZERO;
        }
        self.eval(self.in_mitsuba_frame(wo), self.in_mitsuba_frame(wi)) / wi.z.abs()
    }

    /// The solid-angle density of [`Principled::sample`], lamplight's local frame.
    #[inline]
    pub fn pdf(&self, wo: Vec3, wi: Vec3) -> f64 {
        self.density(self.in_mitsuba_frame(wo), self.in_mitsuba_frame(wi))
    }

    /// A direction for `wo` (lamplight's local frame): `u_choice` picks the lobe, and
    /// reflection or refraction; `None` when the direction fails Mitsuba's checks.
    pub fn sample(&self, wo: Vec3, u_choice: f64, u: (f64, f64)) -> Option<Vec3> {
        let v = self.in_mitsuba_frame(wo);
        if v.z == 0.0 || !self.active(v) {
            return None;
        }
        let front = v.z > 0.0;
        let v_up = if front { v } else { -v };
        // The lobe choice does not depend on F from outside (reflection and
        // transmission share `specular_rate`), so F(v.m) only splits the GGX branch.
        let [p_diffuse, p_clearcoat, _, _] = self.probabilities(front, 0.0);
        let l = if u_choice < p_diffuse {
            lambertian::sample(u)
        } else if u_choice < p_diffuse + p_clearcoat {
            let m = sample_gtr1(lerp(0.1, 0.001, self.p.clearcoat_gloss), u);
            let l = m * (2.0 * v.dot(m)) - v;
            if !(compatible(m, v, l, true) && v.z * l.z > 0.0) {
                return None;
            }
            l
        } else {
            let m = ggx::visible_normal(self.alpha(), v_up, u);
            let vm = v.dot(m);
            let f = fresnel(vm, self.p.eta);
            let [_, _, p_reflect, p_transmit] = self.probabilities(front, f);
            let u_branch = (u_choice - p_diffuse - p_clearcoat) / (1.0 - p_diffuse - p_clearcoat);
            if u_branch * (p_reflect + p_transmit) < p_reflect {
                let l = m * (2.0 * vm) - v;
                if !(compatible(m, v, l, true) && v.z * l.z > 0.0) {
                    return None;
                }
                l
            } else {
                // Refraction through m: l = m (v.m / eta_p - sign(v.m) cos_t) - v / eta_p.
                let eta_it = if vm >= 0.0 { self.p.eta } else { 1.0 / self.p.eta };
                let eta_ti = 1.0 / eta_it;
                let cos_t2 = 1.0 - (1.0 - vm * vm) * eta_ti * eta_ti;
                if cos_t2 <= 0.0 {
                    return None;
                }
                let cos_t = -cos_t2.sqrt().copysign(vm);
                let l = m * (vm * eta_ti + cos_t) - v * eta_ti;
                if !(compatible(m, v, l, false) && v.z * l.z < 0.0) {
                    return None;
                }
                l
            }
        };
        Some(self.in_mitsuba_frame(l))
    }

    /// The relative index `n_t / n_i` of a refraction into `wi` (1 for a reflection).
    #[inline]
    pub fn eta_towards(&self, wi: Vec3) -> f64 {
        match (wi.z < 0.0, self.front) {
            (false, _) => 1.0,
            (true, true) => self.p.eta,
            (true, false) => 1.0 / self.p.eta,
        }
    }
}

/// Burley's diffuse shape for the Schlick weights `fv`, `fl` of the two cosines and
/// `R_r = 2 roughness (h.l)^2`: `lerp(f_d + f_r, f_ss, flatness)` with
/// `f_d = (1 - fv / 2)(1 - fl / 2)`, `f_r = R_r (fl + fv + fl fv (R_r - 1))` and the
/// Hanrahan-Krueger-like `f_ss = 1.25 (F_ss (1 / (cos_l + cos_v) - 0.5) + 0.5)`,
/// `F_ss = lerp(1, R_r / 2, fl) lerp(1, R_r / 2, fv)`.
#[inline]
pub fn burley_diffuse(fv: f64, fl: f64, rr: f64, cos_v: f64, cos_l: f64, flatness: f64) -> f64 {
    let diffuse = (1.0 - 0.5 * fv) * (1.0 - 0.5 * fl);
    let retro = rr * (fl + fv + fl * fv * (rr - 1.0));
    if flatness == 0.0 {
        return diffuse + retro;
    }
    let fss90 = rr / 2.0;
    let fss = lerp(1.0, fss90, fl) * lerp(1.0, fss90, fv);
    let ss = 1.25 * (fss * (1.0 / (cos_l + cos_v) - 0.5) + 0.5);
    lerp(diffuse + retro, ss, flatness)
}

/// `a (1 - t) + b t` (Dr.Jit's `lerp`).
#[inline]
pub(super) fn lerp(a: f64, b: f64, t: f64) -> f64 {
    a * (1.0 - t) + b * t
}

// `Principled::f` and the like name the inherent methods (which come before a trait's).
impl Scatter for Principled {
    const DELTA: bool = false;

    fn bound(&self) -> Rgb {
        Rgb::ONE
    }

    #[inline]
    fn f(&self, wo: Vec3, wi: Vec3) -> Rgb {
        Principled::f(self, wo, wi)
    }

    #[inline]
    fn pdf(&self, wo: Vec3, wi: Vec3) -> f64 {
        Principled::pdf(self, wo, wi)
    }

    #[inline]
    fn sample(&self, wo: Vec3, u_choice: f64, u: (f64, f64)) -> Option<Sampled> {
        Principled::sample(self, wo, u_choice, u).map(Sampled::Smooth)
    }

    fn eta_towards(&self, wi: Vec3) -> f64 {
        Principled::eta_towards(self, wi)
    }

    fn needs_tangent(&self) -> bool {
        let (u, v) = self.alpha();
        u != v
    }
}

pub(super) mod ggx;
#[cfg(test)]
mod tests;
