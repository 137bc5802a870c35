//! Textures made of textures: `scale` (a product), `mix` (a blend) and
//! `vertex_color` (a mesh's colours), so that a base colour can be an image
//! times a factor (glTF's `baseColorFactor x baseColorTexture x COLOR_0`).
//!
//! | kind | parameters | value |
//! |---|---|---|
//! | `scale` | `texture`, `scale` (colours or textures, default 1) | `texture * scale`, per channel |
//! | `mix` | `a`, `b`, `amount` (colours or textures; `amount` default 0.5) | `(1 - amount) a + amount b`, per channel |
//! | `vertex_color` | none | the mesh's interpolated vertex colour; 1 on shapes without one |

use std::sync::Arc;

use super::{Texture, TextureKind, Textures};
use crate::math::Rgb;
use crate::params::{Kind, Param, ParamResult, ParamType as T, Params};

/// A texture parameter, `default` when absent.
fn texture_or(p: &mut Params<'_>, textures: &Textures<'_>, key: &str, default: Rgb) -> ParamResult<Texture> {
    Ok(textures.read(p, key)?.unwrap_or(Texture::Constant(default)))
}

/// `scale`.
pub const SCALE: TextureKind = Kind {
    name: "scale",
    summary: "the product of two textures (an image times a factor)",
    params: &[
        Param::new("texture", T::Texture, "1", "", "the texture"),
        Param::new("scale", T::Texture, "1", "", "what it is multiplied by, per channel"),
    ],
    build: |p, textures| {
        let a = texture_or(p, textures, "texture", Rgb::ONE)?;
        let b = texture_or(p, textures, "scale", Rgb::ONE)?;
        Ok(match (a.constant(), b.constant()) {
            (Some(x), Some(y)) => Texture::Constant(x * y),
            _ => Texture::Scale(Arc::new([a, b])),
        })
    },
};

/// `mix`.
pub const MIX: TextureKind = Kind {
    name: "mix",
    summary: "a blend of two textures, `(1 - amount) a + amount b`",
    params: &[
        Param::new("a", T::Texture, "0", "", "the texture where `amount` is 0"),
        Param::new("b", T::Texture, "1", "", "the texture where `amount` is 1"),
        Param::new("amount", T::Texture, "0.5", "", "the blend, per channel"),
    ],
    build: |p, textures| {
        let a = texture_or(p, textures, "a", Rgb::ZERO)?;
        let b = texture_or(p, textures, "b", Rgb::ONE)?;
        let amount = texture_or(p, textures, "amount", Rgb::splat(0.5))?;
        Ok(Texture::Mix(Arc::new([a, b, amount])))
    },
};

/// `vertex_color`.
pub const VERTEX_COLOR: TextureKind = Kind {
    name: "vertex_color",
    summary: "a mesh's vertex colours, interpolated (1 on shapes without them)",
    params: &[],
    build: |_, _| Ok(Texture::VertexColor),
};

#[cfg(test)]
mod tests {
    use super::super::ShadingPoint;
    use super::*;
    use crate::math::Vec3;

    #[test]
    fn products_and_blends_per_channel() {
        let at = ShadingPoint { color: Some(Rgb::new(0.5, 1.0, 0.0)), ..ShadingPoint::at(Vec3::ZERO) };
        let scaled = Texture::Scale(Arc::new([Texture::VertexColor, Texture::Constant(Rgb::new(2.0, 0.5, 1.0))]));
        assert_eq!(scaled.evaluate(&at), Rgb::new(1.0, 0.5, 0.0));
        let mixed = Texture::Mix(Arc::new([
            Texture::Constant(Rgb::ZERO),
            Texture::Constant(Rgb::ONE),
            Texture::Constant(Rgb::new(0.25, 0.5, 1.0)),
        ]));
        assert_eq!(mixed.evaluate(&at), Rgb::new(0.25, 0.5, 1.0));
        assert_eq!(Texture::VertexColor.evaluate(&ShadingPoint::at(Vec3::ZERO)), Rgb::ONE);
        assert!(scaled.needs_coords() && !Texture::Constant(Rgb::ONE).needs_coords());
    }
}
