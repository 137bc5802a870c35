//! Bump maps (OBJ `bump` / `map_Bump`, Mitsuba's `bumpmap`): a scalar height
//! texture `h` that moves the surface along its normal by `d = scale h`
//! without moving it, only turning the shading normal (Blinn 1978, pbrt-v4's
//! `BumpMap`).
//!
//! | parameter | type | default | meaning |
//! |---|---|---|---|
//! | `bump` | number or texture | none | height `h` (first channel; give an image `color_space = "linear"`) |
//! | `bump_scale` | number | 1 | `scale`: the displacement is `scale h` scene units (OBJ `-bm`) |
//!
//! With the displaced point `p' = p + d n`, its tangents are, dropping the
//! curvature term `d dn/du` (exact on flat surfaces, small where `d` is small
//! against the radius of curvature),
//!
//! `dp'/du = dp/du + (d(u + du, v) - d(u, v)) / du n`, likewise for `v`,
//!
//! by forward differences over the step `du = (|du/dx| + |du/dy|) / 2` of
//! the pixel footprint (pbrt-v4's choice; `0.0005` when the footprint is
//! unknown). The shading normal is `normalize(dp'/du x dp'/dv)`, turned to the
//! side of the outward normal `n`; like a normal map's, it is then kept from
//! facing away from the viewer ([`super::normal_map::facing`]).

use std::sync::Arc;

use super::{ShadingPoint, Texture, Textures};
use crate::math::Vec3;
use crate::params::{Param, ParamResult, ParamType as T, Params};
use crate::shapes::SurfaceCoords;

/// A height texture and its scale.
#[derive(Clone, Debug, PartialEq)]
pub struct BumpMap {
    /// Height `h` (first channel).
    pub texture: Texture,
    /// Displacement per unit of height, in scene units.
    pub scale: f64,
}

/// The bump keys the material kinds share.
pub const BUMP_PARAMS: [Param; 2] = [
    Param::new(
        "bump",
        T::ScalarTexture,
        "none",
        "",
        "a height map: the shading normal follows the surface displaced by `bump_scale` times it",
    ),
    Param::new("bump_scale", T::Number, "1", "scene units", "displacement per unit of height (OBJ `-bm`)"),
];

/// Reads [`BUMP_PARAMS`].
pub fn read(p: &mut Params<'_>, textures: &Textures<'_>) -> ParamResult<Option<Arc<BumpMap>>> {
    let scale = p.number_or("bump_scale", 1.0)?;
    Ok(textures.read_scalar(p, "bump")?.map(|texture| Arc::new(BumpMap { texture, scale })))
}

/// Step when the footprint is unknown (pbrt-v4's).
const DEFAULT_STEP: f64 = 0.0005;

impl BumpMap {
    /// The bumped shading normal at `at` (module documentation), for the
    /// outward normal `outward`, the surface coordinates `coords`, the shading
    /// normal `n` and geometric normal `ng` facing the viewer, and the unit
    /// direction to the viewer `wo`.
    pub fn apply(&self, at: &ShadingPoint, coords: &SurfaceCoords, outward: Vec3, n: Vec3, ng: Vec3, wo: Vec3) -> Vec3 {
        let step = |a: f64, b: f64| {
            let s = 0.5 * (a.abs() + b.abs());
            if s > 0.0 && s.is_finite() {
                s
            } else {
                DEFAULT_STEP
            }
        };
        let du = step(at.duv_dx[0], at.duv_dy[0]);
        let dv = step(at.duv_dx[1], at.duv_dy[1]);
        let height = |p: Vec3, uv: [f64; 2]| self.scale * self.texture.evaluate(&ShadingPoint { p, uv, ..*at }).x;
        let d = height(at.p, at.uv);
        let d_u = height(at.p + coords.dpdu * du, [at.uv[0] + du, at.uv[1]]);
        let d_v = height(at.p + coords.dpdv * dv, [at.uv[0], at.uv[1] + dv]);
        let dpdu = coords.dpdu + outward * ((d_u - d) / du);
        let dpdv = coords.dpdv + outward * ((d_v - d) / dv);
        let Some(mut bumped) = dpdu.cross(dpdv).try_normalize() else { return n };
        if !bumped.is_finite() {
            return n;
        }
        if bumped.dot(outward) < 0.0 {
            bumped = -bumped;
        }
        // Seen from the back, the normal faces the viewer's side as `n` does.
        if n.dot(outward) < 0.0 {
            bumped = -bumped;
        }
        super::normal_map::facing(bumped, ng, wo)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::materials::image::{Channel, Filter, ImageData, ImageTexture, Texels, Wrap};
    use crate::materials::UvTransform;

    /// `h(u, v) = u` over the whole unit square: a 2 x 1 linear image of 0 and 1,
    /// clamped, mapped so that its texel centres sit at `u = 0` and `u = 1`.
    fn ramp() -> Texture {
        let image = ImageData::new(2, 1, Texels::F32(vec![[0.0, 0.0, 0.0, 1.0], [1.0, 1.0, 1.0, 1.0]]), false).unwrap();
        // Texel centres at s = 0.25 and 0.75: s = 0.25 + u / 2.
        let transform = UvTransform([[0.5, 0.0, 0.25], [0.0, 1.0, 0.0]]);
        Texture::Image(Arc::new(ImageTexture {
            image: Arc::new(image),
            wrap: Wrap::Clamp,
            filter: Filter::Bilinear,
            transform,
            channel: Channel::One(0),
        }))
    }

    #[test]
    fn a_linear_ramp_tilts_the_normal_by_its_slope() {
        // A surface with dp/du = 4 x and dp/dv = 2 y: height s u rises s / 4 per
        // unit of x, so the normal tilts by atan(s / 4) towards -x.
        let coords = SurfaceCoords::new([0.5, 0.5], Vec3::new(4.0, 0.0, 0.0), Vec3::new(0.0, 2.0, 0.0));
        let at = ShadingPoint { uv: [0.5, 0.5], ..ShadingPoint::at(Vec3::new(2.0, 1.0, 0.0)) };
        for s in [0.5, 1.0, 3.0] {
            let bump = BumpMap { texture: ramp(), scale: s };
            let n = bump.apply(&at, &coords, Vec3::Z, Vec3::Z, Vec3::Z, Vec3::Z);
            let tilt = (-n.x).atan2(n.z);
            assert!((tilt - (s / 4.0_f64).atan()).abs() < 1e-9 && n.y.abs() < 1e-12, "scale {s}: {n}");
            // From the back: the same surface, the normal on the viewer's side.
            let back = bump.apply(&at, &coords, Vec3::Z, -Vec3::Z, -Vec3::Z, -Vec3::Z);
            assert!((back + n).length() < 1e-12, "{back} vs {n}");
        }
        // A constant height is flat.
        let flat = BumpMap { texture: Texture::Constant(crate::math::Rgb::splat(0.7)), scale: 2.0 };
        assert_eq!(flat.apply(&at, &coords, Vec3::Z, Vec3::Z, Vec3::Z, Vec3::Z), Vec3::Z);
    }
}
