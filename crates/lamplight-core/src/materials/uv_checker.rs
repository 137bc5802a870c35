//! `uv_checker`: a checkerboard in texture space (Mitsuba's `checkerboard`,
//! pbrt's 2D `checkerboard`), beside the 3D `checker`.
//!
//! With `(s, t) = T(u, v)` ([`super::uv_transform`]), the colour is `even` where
//! `floor(s) + floor(t)` is even and `odd` elsewhere: one cell per unit of
//! `(s, t)`, so `uv_scale = [8, 8]` puts 8 x 8 cells on a face whose `(u, v)`
//! span `[0, 1]`.
//!
//! | parameter | type | default | meaning |
//! |---|---|---|---|
//! | `even`, `odd` | colour | required | the two colours |
//! | `uv_scale`, `uv_rotate`, `uv_offset` | `[a, b]`, degrees, `[a, b]` | `[1, 1]`, 0, `[0, 0]` | the UV transform |

use std::sync::Arc;

use super::image::{read_uv_transform, UV_PARAMS};
use super::texture::UvChecker;
use super::{Texture, TextureKind};
use crate::params::{Kind, Param, ParamType as T};

/// `uv_checker`.
pub const KIND: TextureKind = Kind {
    name: "uv_checker",
    summary: "a checkerboard in texture space: one cell per unit of the transformed `(u, v)`",
    params: &[
        Param::new("even", T::Color, "", "", "colour where `floor(s) + floor(t)` is even"),
        Param::new("odd", T::Color, "", "", "colour of the other cells"),
        UV_PARAMS[0],
        UV_PARAMS[1],
        UV_PARAMS[2],
    ],
    build: |p, _| {
        let even = p.color("even")?.ok_or_else(|| p.error("needs `even` (a colour)"))?;
        let odd = p.color("odd")?.ok_or_else(|| p.error("needs `odd` (a colour)"))?;
        Ok(Texture::UvChecker(Arc::new(UvChecker { transform: read_uv_transform(p)?, even, odd })))
    },
};

#[cfg(test)]
mod tests {
    use super::super::{ShadingPoint, UvTransform};
    use super::*;
    use crate::math::{Rgb, Vec3};

    #[test]
    fn cells_alternate_in_texture_space() {
        let t = Texture::UvChecker(Arc::new(UvChecker {
            transform: UvTransform::new([4.0, 4.0], 0.0, [0.0, 0.0]),
            even: Rgb::ONE,
            odd: Rgb::ZERO,
        }));
        let at = |u: f64, v: f64| t.evaluate(&ShadingPoint { uv: [u, v], ..ShadingPoint::at(Vec3::ZERO) });
        assert_eq!(at(0.1, 0.1), Rgb::ONE);
        assert_eq!(at(0.3, 0.1), Rgb::ZERO);
        assert_eq!(at(0.3, 0.3), Rgb::ONE);
        assert_eq!(at(-0.1, 0.1), Rgb::ZERO, "negative coordinates continue the pattern");
    }
}
