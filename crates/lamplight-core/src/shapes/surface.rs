//! Surface coordinates `(u, v)` and the tangents `dp/du`, `dp/dv` of a point on a
//! shape, what textures and normal maps read.
//!
//! They are not part of a hit ([`super::SurfaceHit`]): the hot intersection path
//! stays as it was, and [`super::Shape::surface_coords`] computes them from the hit
//! point, its normal and its primitive only when a material reads them (pbrt
//! computes them in every intersection; most of lamplight's surfaces are not
//! textured). Each shape documents its parametrization, following pbrt-v4's
//! conventions: `u` is the angle around an axis over `2 pi`, `v` the position
//! along it.
//!
//! Surfaces of revolution share one computation ([`revolution`]): with `q` the
//! point in a local frame whose `z` axis is the axis of symmetry and
//! `phi = atan2(q.y, q.x)` in `[0, 2 pi)`, `u = phi / (2 pi)` and
//! `dp/du = 2 pi (-q.y, q.x, 0)` (turning about the axis keeps a point on the
//! surface). Along the meridian (fixed `phi`) the surface's tangent is
//! `T = e_z (n.e_r) - e_r (n.e_z)` for the outward normal `n` and radial
//! direction `e_r`; with `v` a function of the point, `dp/dv = T / (grad v . T)`.

use crate::math::{orthonormal_basis, Mat4, Rgb, Vec3};

/// `(u, v)`, the tangents and what a mesh interpolates at a point of a surface.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SurfaceCoords {
    /// Texture coordinates.
    pub uv: [f64; 2],
    /// `dp/du`: how the point moves with `u` (scene units per unit of `u`).
    pub dpdu: Vec3,
    /// `dp/dv`.
    pub dpdv: Vec3,
    /// The mesh's vertex colour, interpolated; `None` elsewhere.
    pub color: Option<Rgb>,
    /// The mesh's unit tangent and bitangent sign (glTF `TANGENT`'s `w`: the
    /// bitangent is `w (n x t)`), interpolated; `None` elsewhere.
    pub tangent: Option<(Vec3, f64)>,
    /// The mesh's second texture coordinates (glTF `TEXCOORD_1`); `None` elsewhere.
    pub uv1: Option<SecondUv>,
}

/// A second set of texture coordinates with its own tangents.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SecondUv {
    /// Texture coordinates.
    pub uv: [f64; 2],
    /// `dp/du` of this set.
    pub dpdu: Vec3,
    /// `dp/dv` of this set.
    pub dpdv: Vec3,
}

impl SurfaceCoords {
    /// `(u, v)` with its tangents, no vertex data.
    #[inline]
    pub fn new(uv: [f64; 2], dpdu: Vec3, dpdv: Vec3) -> SurfaceCoords {
        SurfaceCoords { uv, dpdu, dpdv, color: None, tangent: None, uv1: None }
    }

    /// The coordinates of a shape with no parametrization: `(0, 0)`, with an
    /// orthonormal tangent frame around the normal `n`.
    pub fn unparametrized(n: Vec3) -> SurfaceCoords {
        let (t, b) = orthonormal_basis(n);
        SurfaceCoords::new([0.0, 0.0], t, b)
    }

    /// These coordinates moved by the affine `m` (tangents are vectors).
    pub fn transformed(mut self, m: &Mat4) -> SurfaceCoords {
        self.dpdu = m.transform_vector3(self.dpdu);
        self.dpdv = m.transform_vector3(self.dpdv);
        self.tangent = self.tangent.and_then(|(t, w)| m.transform_vector3(t).try_normalize().map(|t| (t, w)));
        self.uv1 = self.uv1.map(|s| SecondUv { uv: s.uv, dpdu: m.transform_vector3(s.dpdu), dpdv: m.transform_vector3(s.dpdv) });
        self
    }
}

/// `phi = atan2(y, x)` in `[0, 2 pi)`.
#[inline]
pub fn azimuth(x: f64, y: f64) -> f64 {
    let phi = y.atan2(x);
    if phi < 0.0 {
        phi + std::f64::consts::TAU
    } else {
        phi
    }
}

/// What `v` measures on a surface of revolution (local frame, axis `+z`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Meridian {
    /// `v = (z - z0) / (z1 - z0)`: a cylinder, cone, paraboloid or hyperboloid.
    Height {
        /// `z` where `v = 0`.
        z0: f64,
        /// `z` where `v = 1`.
        z1: f64,
    },
    /// `v = (pi - theta) / pi` with `theta = acos(z / |q|)`: 0 at the `-z` pole,
    /// 1 at `+z` (pbrt's sphere).
    Polar,
}

/// The coordinates of local point `q` with local outward normal `n` on a surface
/// of revolution about `+z` (module documentation); `None` on the axis, where
/// `phi` is undefined, or where the meridian's tangent does not change `v`.
pub fn revolution(q: Vec3, n: Vec3, meridian: Meridian) -> Option<SurfaceCoords> {
    let rho = q.x.hypot(q.y);
    if !(rho > 0.0) {
        return None;
    }
    let phi = azimuth(q.x, q.y);
    let e_r = Vec3::new(q.x / rho, q.y / rho, 0.0);
    let tangent = Vec3::Z * n.dot(e_r) - e_r * n.z;
    let (v, grad) = match meridian {
        Meridian::Height { z0, z1 } => ((q.z - z0) / (z1 - z0), Vec3::Z / (z1 - z0)),
        Meridian::Polar => {
            let len = q.length();
            let w = (q.z / len).clamp(-1.0, 1.0);
            let theta = w.acos();
            // grad w = (e_z - w q / |q|) / |q|, and v = (pi - acos w) / pi.
            let grad_w = (Vec3::Z - q * (w / len)) / len;
            ((std::f64::consts::PI - theta) / std::f64::consts::PI, grad_w / (std::f64::consts::PI * (1.0 - w * w).sqrt()))
        }
    };
    let rate = grad.dot(tangent);
    if !(rate.abs() > 0.0 && rate.is_finite()) {
        return None;
    }
    let dpdu = Vec3::new(-q.y, q.x, 0.0) * std::f64::consts::TAU;
    Some(SurfaceCoords::new([phi / std::f64::consts::TAU, v], dpdu, tangent / rate))
}

/// Barycentric weights `(b0, b1, b2)` of `p` projected onto the triangle's plane.
#[inline]
pub fn barycentric(p: Vec3, p0: Vec3, p1: Vec3, p2: Vec3) -> [f64; 3] {
    let (e1, e2, d) = (p1 - p0, p2 - p0, p - p0);
    let n = e1.cross(e2);
    let inv = 1.0 / n.length_squared();
    let b1 = d.cross(e2).dot(n) * inv;
    let b2 = e1.cross(d).dot(n) * inv;
    [1.0 - b1 - b2, b1, b2]
}

/// `dp/du`, `dp/dv` of the triangle `p` with texture coordinates `uv` (pbrt-v4's
/// `Triangle::InteractionFromIntersection`): the solution of
/// `[du02 dv02; du12 dv12] [dpdu; dpdv] = [p0 - p2; p1 - p2]`. Degenerate
/// coordinates (a zero determinant, or parallel tangents) fall back to a frame
/// around the face normal `n`.
pub fn triangle_tangents(p: [Vec3; 3], uv: [[f64; 2]; 3], n: Vec3) -> (Vec3, Vec3) {
    let (du02, dv02) = (uv[0][0] - uv[2][0], uv[0][1] - uv[2][1]);
    let (du12, dv12) = (uv[1][0] - uv[2][0], uv[1][1] - uv[2][1]);
    let (dp02, dp12) = (p[0] - p[2], p[1] - p[2]);
    let det = du02 * dv12 - dv02 * du12;
    if det.abs() > 1e-12 * (du02.abs() + dv02.abs()) * (du12.abs() + dv12.abs()) && det != 0.0 {
        let inv = 1.0 / det;
        let dpdu = (dp02 * dv12 - dp12 * dv02) * inv;
        let dpdv = (dp12 * du02 - dp02 * du12) * inv;
        if dpdu.cross(dpdv).length_squared() > 0.0 && dpdu.is_finite() && dpdv.is_finite() {
            return (dpdu, dpdv);
        }
    }
    orthonormal_basis(n)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_unit_cylinder_has_its_height_as_v() {
        // x^2 + y^2 = 1, z in [0, 2]: at (0, 1, 0.5) phi = pi / 2.
        let c = revolution(Vec3::new(0.0, 1.0, 0.5), Vec3::Y, Meridian::Height { z0: 0.0, z1: 2.0 }).unwrap();
        assert!((c.uv[0] - 0.25).abs() < 1e-15 && (c.uv[1] - 0.25).abs() < 1e-15, "{:?}", c.uv);
        assert!((c.dpdu - Vec3::new(-std::f64::consts::TAU, 0.0, 0.0)).length() < 1e-12);
        assert!((c.dpdv - Vec3::new(0.0, 0.0, 2.0)).length() < 1e-12, "{}", c.dpdv);
    }

    #[test]
    fn the_polar_meridian_matches_pbrts_sphere() {
        // pbrt: dpdv = (thetaMax - thetaMin) (z cos phi, z sin phi, -r sin theta) with thetaMax - thetaMin = -pi.
        let (theta, phi) = (1.1_f64, 0.7_f64);
        let q = Vec3::new(theta.sin() * phi.cos(), theta.sin() * phi.sin(), theta.cos());
        let c = revolution(q, q, Meridian::Polar).unwrap();
        let pbrt = Vec3::new(q.z * phi.cos(), q.z * phi.sin(), -theta.sin()) * -std::f64::consts::PI;
        assert!((c.dpdv - pbrt).length() < 1e-12, "{} vs {pbrt}", c.dpdv);
        assert!((c.uv[1] - (1.0 - theta / std::f64::consts::PI)).abs() < 1e-15);
    }

    #[test]
    fn triangle_tangents_reproduce_the_edges() {
        let p = [Vec3::ZERO, Vec3::new(2.0, 0.0, 0.0), Vec3::new(0.0, 3.0, 0.0)];
        let (dpdu, dpdv) = triangle_tangents(p, [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]], Vec3::Z);
        assert!((dpdu - Vec3::new(2.0, 0.0, 0.0)).length() < 1e-15 && (dpdv - Vec3::new(0.0, 3.0, 0.0)).length() < 1e-15);
        let b = barycentric(Vec3::new(0.5, 1.5, 0.0), p[0], p[1], p[2]);
        assert!((b[1] - 0.25).abs() < 1e-15 && (b[2] - 0.5).abs() < 1e-15);
        // All corners at one (u, v): a frame around the normal.
        let (t, s) = triangle_tangents(p, [[0.5, 0.5]; 3], Vec3::Z);
        assert!(t.dot(Vec3::Z).abs() < 1e-15 && s.dot(Vec3::Z).abs() < 1e-15);
    }
}
