//! `uv_set`: a texture read at a mesh's second texture coordinates (glTF
//! `TEXCOORD_1`, a textureInfo's `texCoord = 1`), for light maps and detail
//! textures laid out apart from the first set.
//!
//! | parameter | type | default | meaning |
//! |---|---|---|---|
//! | `set` | integer | 1 | `0`: the first coordinates (the texture as is); `1`: the second |
//! | `texture` | texture | required | what is read there |
//!
//! On shapes without a second set (every shape but meshes that carry one) the
//! first set is read. Trilinear filtering uses the footprint in the second
//! set's own coordinates, from its own tangents.

use std::sync::Arc;

use super::{Texture, TextureKind};
use crate::params::{Kind, Param, ParamType as T};

/// `uv_set`.
pub const KIND: TextureKind = Kind {
    name: "uv_set",
    summary: "a texture read at a mesh's second texture coordinates (glTF `TEXCOORD_1`)",
    params: &[
        Param::new("set", T::Integer, "1", "0 or 1", "which texture coordinates"),
        Param::new("texture", T::Texture, "", "", "the texture read there"),
    ],
    build: |p, textures| {
        let set = p.integer("set", 0..=1)?.unwrap_or(1);
        let texture = textures.read(p, "texture")?.ok_or_else(|| p.error("needs `texture` (a texture)"))?;
        Ok(if set == 0 || texture.constant().is_some() { texture } else { Texture::SecondUv(Arc::new(texture)) })
    },
};

#[cfg(test)]
mod tests {
    use super::super::{ShadingPoint, UvTransform};
    use super::*;
    use crate::math::{Rgb, Vec3};
    use crate::shapes::{SecondUv, SurfaceCoords};

    #[test]
    fn the_second_set_is_read_where_there_is_one_and_the_first_elsewhere() {
        // A checker of two cells along u: 0 for u < 0.5, 1 above.
        let checker = Texture::UvChecker(Arc::new(super::super::texture::UvChecker {
            transform: UvTransform::new([2.0, 1.0], 0.0, [0.0, 0.0]),
            even: Rgb::ZERO,
            odd: Rgb::ONE,
        }));
        let second = Texture::SecondUv(Arc::new(checker));
        let mut c = SurfaceCoords::new([0.25, 0.5], Vec3::X, Vec3::Y);
        assert_eq!(second.evaluate(&ShadingPoint::with_coords(Vec3::ZERO, &c)), Rgb::ZERO, "no second set: the first");
        c.uv1 = Some(SecondUv { uv: [0.75, 0.5], dpdu: Vec3::X, dpdv: Vec3::Y });
        assert_eq!(second.evaluate(&ShadingPoint::with_coords(Vec3::ZERO, &c)), Rgb::ONE);
    }
}
