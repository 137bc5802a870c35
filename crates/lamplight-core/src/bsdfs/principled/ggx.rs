//! The GGX of Mitsuba's principled BSDFs (`principled`, `principledthin`):
//! roughness from `roughness` and `anisotropic` as Mitsuba's `calc_dist_params`
//! (`principledhelpers.h`, after Burley 2012's course notes),
//!
//! `aspect = sqrt(1 - 0.9 anisotropic)`,
//! `a_u = max(0.001, roughness^2 / aspect)`, `a_v = max(0.001, roughness^2 aspect)`
//!
//! (`a_u` along the shading frame's first tangent, the surface's `dp/du`), and
//! the separable Smith masking with Mitsuba's orientation checks. An
//! isotropic pair (`a_u = a_v`) takes the isotropic forms of
//! [`super::super::microfacet`] bit for bit; the anisotropic forms are
//! [`super::super::anisotropic`]'s.

use super::super::{anisotropic, microfacet};
use crate::math::Vec3;

/// GGX roughness `(a_u, a_v)` of a principled surface (module documentation);
/// `anisotropic = 0` gives Mitsuba's isotropic `max(0.001, roughness^2)` exactly.
#[inline]
pub fn alphas(roughness: f64, anisotropic: f64) -> (f64, f64) {
    let r2 = roughness * roughness;
    if anisotropic == 0.0 {
        let a = r2.max(0.001);
        return (a, a);
    }
    let aspect = (1.0 - 0.9 * anisotropic).sqrt();
    ((r2 / aspect).max(0.001), (r2 * aspect).max(0.001))
}

/// GGX `D(m)` of roughness `a = (a_u, a_v)`.
#[inline]
pub fn d(a: (f64, f64), m: Vec3) -> f64 {
    if a.0 == a.1 {
        microfacet::d(a.0, m)
    } else {
        anisotropic::ggx_d(a.0, a.1, m)
    }
}

/// Smith's GGX masking of `v` by normal `m` (Mitsuba's `smith_g1`):
/// `2 / (1 + sqrt(1 + t))`, `t = (a_u^2 v_x^2 + a_v^2 v_y^2) / v_z^2` (for `a_u = a_v`
/// the isotropic `a^2 tan^2`), 0 where `m` faces away from `v`'s side.
#[inline]
pub fn smith_g1(a: (f64, f64), v: Vec3, m: Vec3) -> f64 {
    if v.dot(m) * v.z <= 0.0 {
        return 0.0;
    }
    if v.x * v.x + v.y * v.y == 0.0 {
        return 1.0;
    }
    let t = if a.0 == a.1 {
        let tan2 = (v.x * v.x + v.y * v.y) / (v.z * v.z);
        a.0 * a.0 * tan2
    } else {
        let (x, y) = (a.0 * v.x, a.1 * v.y);
        (x * x + y * y) / (v.z * v.z)
    };
    2.0 / (1.0 + (1.0 + t).sqrt())
}

/// GGX's density of the normals visible from `v` (upper side): `D(m) G1(v, m) |v.m| / cos_v`.
#[inline]
pub fn visible_pdf(a: (f64, f64), v: Vec3, m: Vec3) -> f64 {
    d(a, m) * smith_g1(a, v, m) * v.dot(m).abs() / v.z
}

/// A normal visible from `v` (`v.z > 0`), density [`visible_pdf`] (Heitz 2018).
#[inline]
pub fn visible_normal(a: (f64, f64), v: Vec3, u: (f64, f64)) -> Vec3 {
    microfacet::visible_normal_stretched(a.0, a.1, v, u)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mitsubas_aspect_mapping() {
        // roughness 0.5, anisotropic 0.5: aspect sqrt(0.55), a = 0.25 / aspect and 0.25 aspect.
        let (u, v) = alphas(0.5, 0.5);
        let aspect = 0.55f64.sqrt();
        assert!((u - 0.25 / aspect).abs() < 1e-15 && (v - 0.25 * aspect).abs() < 1e-15, "{u} {v}");
        // Both clamped at 0.001; anisotropic 0 is the isotropic roughness^2 exactly.
        assert_eq!(alphas(0.01, 1.0), (0.001f64.max(1e-4 / 0.1f64.sqrt()), 0.001));
        assert_eq!(alphas(0.3, 0.0), (0.3 * 0.3, 0.3 * 0.3));
    }

    #[test]
    fn visible_normals_follow_their_density() {
        // The sampled normals' histogram against visible_pdf (chi-square), along
        // and across the tangent and isotropic.
        use crate::bsdfs::test_support::{chi_square_z, Sampled};
        for a in [(0.4, 0.1), (0.1, 0.4), (0.3, 0.3)] {
            let v = Vec3::new(0.3, 0.5, 0.7).normalize();
            let z = chi_square_z(|m| visible_pdf(a, v, m), |_, u| Some(Sampled::Smooth(visible_normal(a, v, u), 1.0)), 200_000, 5);
            assert!(z < 4.0, "{a:?}: z {z}");
        }
    }
}
