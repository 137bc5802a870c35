//! The affine map from a surface's `(u, v)` to a texture's: scale, then rotate,
//! then offset (glTF's `KHR_texture_transform` `T R S`, Mitsuba's `to_uv`).
//!
//! `uv' = T(offset) R(rotation) S(scale) uv`, where `R` turns counter-clockwise
//! in the `(u, v)` plane (with `v` up, lamplight's convention). It is stored as a
//! 2x3 matrix so that transforms compose ([`UvTransform::then`]) and the
//! derivatives of `(u, v)` (for MIP-mapping) map by its linear part.

/// An affine map of the `(u, v)` plane, rows `[a, b, c]`, `[d, e, f]`:
/// `u' = a u + b v + c`, `v' = d u + e v + f`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct UvTransform(pub [[f64; 3]; 2]);

impl Default for UvTransform {
    fn default() -> UvTransform {
        UvTransform::IDENTITY
    }
}

impl UvTransform {
    /// `uv' = uv`.
    pub const IDENTITY: UvTransform = UvTransform([[1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]);

    /// `T(offset) R(rotation_rad) S(scale)`.
    pub fn new(scale: [f64; 2], rotation_rad: f64, offset: [f64; 2]) -> UvTransform {
        let (s, c) = rotation_rad.sin_cos();
        UvTransform([[c * scale[0], -s * scale[1], offset[0]], [s * scale[0], c * scale[1], offset[1]]])
    }

    /// Applies the map to a point.
    #[inline]
    pub fn apply(&self, uv: [f64; 2]) -> [f64; 2] {
        let [r0, r1] = self.0;
        [r0[0] * uv[0] + r0[1] * uv[1] + r0[2], r1[0] * uv[0] + r1[1] * uv[1] + r1[2]]
    }

    /// Applies the linear part to a difference of coordinates.
    #[inline]
    pub fn apply_vector(&self, d: [f64; 2]) -> [f64; 2] {
        let [r0, r1] = self.0;
        [r0[0] * d[0] + r0[1] * d[1], r1[0] * d[0] + r1[1] * d[1]]
    }

    /// `next` after `self`: `next(self(uv))`.
    pub fn then(&self, next: &UvTransform) -> UvTransform {
        let [a, b] = next.0;
        let [p, q] = self.0;
        let row = |r: [f64; 3]| [r[0] * p[0] + r[1] * q[0], r[0] * p[1] + r[1] * q[1], r[0] * p[2] + r[1] * q[2] + r[2]];
        UvTransform([row(a), row(b)])
    }

    /// True when every entry is finite.
    pub fn is_finite(&self) -> bool {
        self.0.iter().flatten().all(|x| x.is_finite())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn scale_then_rotate_then_offset() {
        let t = UvTransform::new([2.0, 3.0], std::f64::consts::FRAC_PI_2, [0.5, 0.25]);
        // (1, 0) -> scaled (2, 0) -> turned (0, 2) -> moved (0.5, 2.25).
        let p = t.apply([1.0, 0.0]);
        assert!((p[0] - 0.5).abs() < 1e-15 && (p[1] - 2.25).abs() < 1e-15, "{p:?}");
        let flip = UvTransform([[1.0, 0.0, 0.0], [0.0, -1.0, 1.0]]);
        let both = t.then(&flip);
        let q = both.apply([0.3, 0.7]);
        let r = flip.apply(t.apply([0.3, 0.7]));
        assert!((q[0] - r[0]).abs() < 1e-15 && (q[1] - r[1]).abs() < 1e-15);
    }
}
