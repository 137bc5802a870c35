//! Tangent-space normal maps (glTF `normalTexture`, Mitsuba's `normalmap`):
//! a texture whose texel `c` stores the normal `n_t = 2 c - 1` in the frame of
//! the tangent `T`, bitangent `B` and shading normal `N`.
//!
//! | parameter | type | default | meaning |
//! |---|---|---|---|
//! | `normal_map` | texture | none | the map, read linearly (give the image `color_space = "linear"`) |
//! | `normal_scale` | number | 1 | scales the map's `x` and `y` (glTF `normalTexture.scale`) |
//!
//! The frame: a mesh's tangent `(t, w)` gives `T = t`, `B = w (N x T)` (glTF's
//! rule, from `TANGENT` or MikkTSpace); elsewhere `T = dp/du` and `B` the side
//! of `dp/dv`: with lamplight's `v` up the image, `+y` of the map is up the
//! image, the convention glTF and OpenGL-style maps share. `T` is made
//! orthogonal to `N` (Gram-Schmidt) and `B = +-N x T`. The mapped normal is
//! `normalize(s x T + s y B + z N)`.
//!
//! The mapped normal must not turn the surface away from the viewer: a
//! shading normal below the incoming direction `wo` makes black seams or lets
//! light through (mitsuba3#1158). Where `n . wo < 0.01` it is bent towards
//! `wo` until `n . wo = 0.01` ([`facing`]), and a normal below the geometric
//! surface is replaced by the geometric normal; the path tracer also drops any
//! scattered direction on the wrong side of the geometry.

use super::{ShadingPoint, Texture, Textures};
use crate::math::Vec3;
use crate::params::{Param, ParamResult, ParamType as T, Params};
use crate::shapes::SurfaceCoords;

/// A normal map and its strength.
#[derive(Clone, Debug, PartialEq)]
pub struct NormalMap {
    /// The map (linear values in `[0, 1]`).
    pub texture: Texture,
    /// `normalTexture.scale`.
    pub scale: f64,
}

/// The normal map keys the material kinds share.
pub const NORMAL_MAP_PARAMS: [Param; 2] = [
    Param::new("normal_map", T::Texture, "none", "", "a tangent-space normal map (an image with `color_space = \"linear\"`)"),
    Param::new("normal_scale", T::Number, "1", "", "scales the map's x and y (glTF `normalTexture.scale`)"),
];

/// Reads [`NORMAL_MAP_PARAMS`].
pub fn read(p: &mut Params<'_>, textures: &Textures<'_>) -> ParamResult<Option<std::sync::Arc<NormalMap>>> {
    let scale = p.number_or("normal_scale", 1.0)?;
    Ok(textures.read(p, "normal_map")?.map(|texture| std::sync::Arc::new(NormalMap { texture, scale })))
}

/// Smallest `n . wo` a mapped normal keeps.
pub const MIN_FACING: f64 = 0.01;

impl NormalMap {
    /// The mapped shading normal at `at` for shading normal `n`, surface
    /// coordinates `coords`, geometric normal `ng` and unit direction to the
    /// viewer `wo` (`n`, `ng` and `wo` on the same side).
    pub fn apply(&self, at: &ShadingPoint, coords: &SurfaceCoords, n: Vec3, ng: Vec3, wo: Vec3) -> Vec3 {
        let c = self.texture.evaluate(at);
        let local = Vec3::new((2.0 * c.x - 1.0) * self.scale, (2.0 * c.y - 1.0) * self.scale, 2.0 * c.z - 1.0);
        let (t, b_hint) = match coords.tangent {
            Some((t, w)) => (t, n.cross(t) * w),
            None => (coords.dpdu, coords.dpdv),
        };
        let Some(t) = (t - n * n.dot(t)).try_normalize() else { return n };
        let mut b = n.cross(t);
        if b.dot(b_hint) < 0.0 {
            b = -b;
        }
        let Some(mapped) = (t * local.x + b * local.y + n * local.z).try_normalize() else { return n };
        facing(mapped, ng, wo)
    }
}

/// `n` bent towards `wo` where the viewer would see it from below (module
/// documentation); the geometric normal `ng` when it points below the surface.
pub fn facing(n: Vec3, ng: Vec3, wo: Vec3) -> Vec3 {
    let n = if n.dot(ng) > 0.0 { n } else { ng };
    let cos = n.dot(wo);
    if cos >= MIN_FACING {
        return n;
    }
    // Move n along wo: n' = n + k wo with n'.wo / |n'| = MIN_FACING, solved for k
    // (|wo| = 1): (c + k)^2 = m^2 (1 + 2 c k + k^2).
    let m2 = MIN_FACING * MIN_FACING;
    let (a, b, cc) = (1.0 - m2, 2.0 * cos * (1.0 - m2), cos * cos - m2);
    let disc = (b * b - 4.0 * a * cc).max(0.0);
    let k = (-b + disc.sqrt()) / (2.0 * a);
    (n + wo * k).try_normalize().unwrap_or(ng)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::Rgb;

    fn flat() -> SurfaceCoords {
        SurfaceCoords::new([0.5, 0.5], Vec3::X, Vec3::Y)
    }

    #[test]
    fn the_flat_texel_keeps_the_normal_and_others_tilt_along_the_tangents() {
        let at = ShadingPoint::at(Vec3::ZERO);
        let up = NormalMap { texture: Texture::Constant(Rgb::new(0.5, 0.5, 1.0)), scale: 1.0 };
        assert_eq!(up.apply(&at, &flat(), Vec3::Z, Vec3::Z, Vec3::Z), Vec3::Z);
        // (1, 0.5, 0.5 + 0.5 / sqrt 2 ...) : 45 degrees towards +u.
        let tilted = NormalMap { texture: Texture::Constant(Rgb::new(1.0, 0.5, 1.0)), scale: 1.0 };
        let n = tilted.apply(&at, &flat(), Vec3::Z, Vec3::Z, Vec3::Z);
        assert!((n - Vec3::new(1.0, 0.0, 1.0).normalize()).length() < 1e-12, "{n}");
        // Green tilts towards dp/dv; with a mesh tangent, towards w (n x t).
        let green = NormalMap { texture: Texture::Constant(Rgb::new(0.5, 1.0, 1.0)), scale: 1.0 };
        assert!(green.apply(&at, &flat(), Vec3::Z, Vec3::Z, Vec3::Z).y > 0.5);
        let mirrored = SurfaceCoords { tangent: Some((Vec3::X, -1.0)), ..flat() };
        assert!(green.apply(&at, &mirrored, Vec3::Z, Vec3::Z, Vec3::Z).y < -0.5);
        // Scale 0 removes the tilt.
        let none = NormalMap { scale: 0.0, ..tilted };
        assert_eq!(none.apply(&at, &flat(), Vec3::Z, Vec3::Z, Vec3::Z), Vec3::Z);
    }

    #[test]
    fn a_normal_the_viewer_sees_from_below_is_bent_back() {
        // Viewer at grazing incidence from -x; the map tilts the normal away from it.
        let wo = Vec3::new(-0.99, 0.0, 0.141).normalize();
        let away = Vec3::new(1.0, 0.0, 0.2).normalize();
        let n = facing(away, Vec3::Z, wo);
        assert!((n.dot(wo) - MIN_FACING).abs() < 1e-9, "{}", n.dot(wo));
        assert!(n.dot(Vec3::Z) > 0.0 && (n.length() - 1.0).abs() < 1e-12);
        // Below the geometric surface: the geometric normal.
        assert_eq!(facing(-Vec3::Z, Vec3::Z, Vec3::Z), Vec3::Z);
        // Already facing: unchanged.
        assert_eq!(facing(Vec3::Z, Vec3::Z, wo), Vec3::Z);
    }
}
