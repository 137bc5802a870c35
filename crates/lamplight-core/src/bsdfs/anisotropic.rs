//! Anisotropic GGX and Beckmann: a roughness `a_u` along the shading frame's
//! first tangent (local `x`, the surface's `dp/du`, [`super::Frame::from_tangent`])
//! and `a_v` along the second (local `y`), as Mitsuba's `alpha_u`, `alpha_v`.
//! [`super::Microfacet`] calls these only when `a_u != a_v`: its isotropic forms
//! stay the ones every image was made with.
//!
//! Both distributions are their isotropic unit-roughness form stretched by
//! `(a_u, a_v)` in the slopes (Heitz 2014, "Understanding the Masking-Shadowing
//! Function in Microfacet-Based BRDFs", section 5.3). With `x = h_x / a_u`,
//! `y = h_y / a_v`:
//!
//! - GGX: `D(h) = 1 / (pi a_u a_v (x^2 + y^2 + h_z^2)^2)`;
//! - Beckmann: `D(h) = exp(-(x^2 + y^2) / h_z^2) / (pi a_u a_v h_z^4)`;
//!
//! and Smith's `Lambda(v)` is the isotropic one with `a^2 tan^2(theta_v)` replaced by
//! `t = (a_u^2 v_x^2 + a_v^2 v_y^2) / v_z^2`: GGX `(sqrt(1 + t) - 1) / 2`, Beckmann
//! Walter's rational fit in `b = 1 / sqrt(t)`.
//!
//! Sampling: GGX's visible normals by Heitz 2018 (stretch `wo` by `(a_u, a_v)`,
//! sample the unit-roughness visible hemisphere, unstretch the normal:
//! [`super::microfacet::visible_normal_stretched`]); Beckmann's normals from
//! `D(h) cos(theta_h)`, whose slopes `(-h_x / h_z, -h_y / h_z)` are a Gaussian of
//! deviations `a_u / sqrt(2)`, `a_v / sqrt(2)`: `r = sqrt(-ln(1 - u_1))`,
//! `phi = 2 pi u_2`, slopes `(a_u r cos(phi), a_v r sin(phi))` (for `a_u = a_v` the
//! isotropic `tan^2(theta_h) = -a^2 ln(1 - u_1)`).

use std::f64::consts::PI;

use crate::math::Vec3;

/// `t = (a_u^2 v_x^2 + a_v^2 v_y^2) / v_z^2`, the stretched `a^2 tan^2(theta_v)`.
#[inline]
fn stretched_tan2(au: f64, av: f64, v: Vec3) -> f64 {
    let (x, y) = (au * v.x, av * v.y);
    (x * x + y * y) / (v.z * v.z)
}

/// Anisotropic GGX `D(h)` (0 below the surface).
#[inline]
pub fn ggx_d(au: f64, av: f64, h: Vec3) -> f64 {
    if h.z <= 0.0 {
        return 0.0;
    }
    let (x, y) = (h.x / au, h.y / av);
    let s = x * x + y * y + h.z * h.z;
    1.0 / (PI * au * av * s * s)
}

/// Anisotropic GGX Smith `Lambda(v)`, even in `v.z`.
#[inline]
pub fn ggx_lambda(au: f64, av: f64, v: Vec3) -> f64 {
    if v.z == 0.0 {
        return f64::INFINITY;
    }
    0.5 * ((1.0 + stretched_tan2(au, av, v)).sqrt() - 1.0)
}

/// Anisotropic Beckmann `D(h)` (0 below the surface).
#[inline]
pub fn beckmann_d(au: f64, av: f64, h: Vec3) -> f64 {
    if h.z <= 0.0 {
        return 0.0;
    }
    let c2 = h.z * h.z;
    let (x, y) = (h.x / au, h.y / av);
    (-(x * x + y * y) / c2).exp() / (PI * au * av * c2 * c2)
}

/// Anisotropic Beckmann Smith `Lambda(v)` by Walter's fit, even in `v.z`.
#[inline]
pub fn beckmann_lambda(au: f64, av: f64, v: Vec3) -> f64 {
    if v.z == 0.0 {
        return f64::INFINITY;
    }
    let t = stretched_tan2(au, av, v);
    if t == 0.0 {
        return 0.0;
    }
    let b = 1.0 / t.sqrt();
    if b >= 1.6 {
        return 0.0;
    }
    (1.0 - 1.259 * b + 0.396 * b * b) / (3.535 * b + 2.181 * b * b)
}

/// A Beckmann normal of density `D(h) cos(theta_h)` (module documentation).
#[inline]
pub fn beckmann_normal(au: f64, av: f64, u: (f64, f64)) -> Vec3 {
    let r = (-(1.0 - u.0).ln()).max(0.0).sqrt();
    let phi = 2.0 * PI * u.1;
    Vec3::new(-au * r * phi.cos(), -av * r * phi.sin(), 1.0).normalize()
}

#[cfg(test)]
mod tests;
