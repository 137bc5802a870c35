//! Cut-outs: a surface that is not there where its alpha is below a cutoff
//! (glTF `alphaMode = MASK` with `alphaCutoff`, OBJ `map_d`), for camera,
//! secondary and shadow rays alike.
//!
//! | parameter | type | default | meaning |
//! |---|---|---|---|
//! | `alpha` | number or texture | none | coverage, 0 to 1 (an image's `channel = "a"`) |
//! | `alpha_cutoff` | number | 0.5 | the surface exists where `alpha >= alpha_cutoff` (glTF's rule) |
//!
//! A ray that meets a cut-out point goes on through it: the shape is asked
//! again beyond that point ([`first_covered`]), so a leaf of a mesh is seen
//! through its own holes. Evaluating alpha needs the hit's surface coordinates,
//! so only objects whose material has a mask pay for it (the scene marks them).
//! glTF's `BLEND` is read as `MASK` at 0.5 (stochastic blending is not done).

use super::{ShadingPoint, Texture, Textures};
use crate::params::{Param, ParamResult, ParamType as T, Params};
use crate::ray::{Ray, OFFSET_SCALE};
use crate::shapes::{Shape, SurfaceHit};

/// A coverage texture and its cutoff.
#[derive(Clone, Debug, PartialEq)]
pub struct AlphaMask {
    /// Coverage (first channel).
    pub texture: Texture,
    /// The surface exists where coverage `>= cutoff`.
    pub cutoff: f64,
}

/// The alpha keys the material kinds share.
pub const ALPHA_PARAMS: [Param; 2] = [
    Param::new("alpha", T::ScalarTexture, "none", "0 to 1", "coverage: the surface is cut out where it is below `alpha_cutoff`"),
    Param::new("alpha_cutoff", T::Number, "0.5", "0 to 1", "the least coverage that is kept (glTF `alphaCutoff`)"),
];

/// Reads [`ALPHA_PARAMS`].
pub fn read(p: &mut Params<'_>, textures: &Textures<'_>) -> ParamResult<Option<std::sync::Arc<AlphaMask>>> {
    let cutoff = p.number_or("alpha_cutoff", 0.5)?;
    if !(0.0..=1.0).contains(&cutoff) {
        return Err(p.key_error("alpha_cutoff", format!("must be between 0 and 1, got {cutoff}")));
    }
    Ok(textures.read_scalar(p, "alpha")?.map(|texture| std::sync::Arc::new(AlphaMask { texture, cutoff })))
}

impl AlphaMask {
    /// Whether the surface exists at `hit` of `shape` along `ray`.
    pub fn covers(&self, shape: &dyn Shape, ray: &Ray, hit: &SurfaceHit) -> bool {
        let p = ray.at(hit.t);
        let mut at = ShadingPoint::at(p);
        if self.texture.needs_coords() {
            let c = shape.surface_coords(p, hit.normal, hit.primitive);
            at.uv = c.uv;
            at.color = c.color;
        }
        self.texture.evaluate(&at).x >= self.cutoff
    }
}

/// The nearest hit of `shape` in `(t_min, t_max)` where `mask` covers it.
pub fn first_covered(shape: &dyn Shape, mask: &AlphaMask, ray: &Ray, t_min: f64, t_max: f64) -> Option<SurfaceHit> {
    let mut from = t_min;
    // Each miss moves past the hit by at least the relative offset, so the loop ends.
    for _ in 0..1024 {
        let h = shape.intersect(ray, from, t_max)?;
        if mask.covers(shape, ray, &h) {
            return Some(h);
        }
        from = h.t + OFFSET_SCALE * (crate::math::max_abs(ray.at(h.t)) + h.t) + 4.0 * h.error;
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::materials::UvTransform;
    use crate::math::{Rgb, Vec3};
    use crate::shapes::Rectangle;

    #[test]
    fn rays_pass_through_cut_out_points_to_what_lies_behind() {
        // A unit square whose left half (u < 0.5) is cut out by a UV checker of two cells.
        let mask = AlphaMask {
            texture: Texture::UvChecker(std::sync::Arc::new(crate::materials::texture::UvChecker {
                transform: UvTransform::new([2.0, 1.0], 0.0, [0.0, 0.0]),
                even: Rgb::ZERO,
                odd: Rgb::ONE,
            })),
            cutoff: 0.5,
        };
        let square = Rectangle::new(Vec3::ZERO, Vec3::X, Vec3::Y).unwrap();
        let down = |x: f64| Ray::new(Vec3::new(x, 0.5, 1.0), -Vec3::Z);
        assert!(first_covered(&square, &mask, &down(0.25), 0.0, f64::INFINITY).is_none());
        assert_eq!(first_covered(&square, &mask, &down(0.75), 0.0, f64::INFINITY).map(|h| h.t), Some(1.0));
    }
}
