//! Cut-outs and stochastic transparency: a surface that is not there where
//! its alpha is below a cutoff (glTF `alphaMode = MASK` with `alphaCutoff`,
//! OBJ `map_d`), or that is there with probability alpha (glTF `BLEND`), for
//! camera, secondary and shadow rays alike.
//!
//! | parameter | type | default | meaning |
//! |---|---|---|---|
//! | `alpha` | number or texture | none | coverage, 0 to 1 (an image's `channel = "a"`) |
//! | `alpha_cutoff` | number | 0.5 | `mask`: the surface exists where `alpha >= alpha_cutoff` (glTF's rule) |
//! | `alpha_mode` | string | `"mask"` | `"mask"` (cut-out) or `"blend"`: the surface exists with probability `alpha` |
//!
//! Blending is stochastic transparency (Enderton et al. 2010, pbrt-v4's alpha
//! test): a ray meeting the surface at distance `t` keeps the hit when
//! `xi < alpha`, with `xi` in `[0, 1)` a hash of the ray's origin, direction
//! and `t` ([`blend_sample`]). Every sample's rays differ (their pixel and lens
//! positions come from the sampler), so over the samples of a pixel the surface
//! is seen with weight `alpha` and what lies behind with `1 - alpha`: the
//! expected image is the "over" composite, without ordering the layers. The
//! hash reads only the ray, so a render is the same for any thread count, and
//! shadow rays see the same statistics (their expected transmittance is
//! `1 - alpha`). Including `t` decorrelates the layers one ray crosses.
//!
//! A ray that meets a cut-out point goes on through it: the shape is asked
//! again beyond that point ([`first_covered`]), so a leaf of a mesh is seen
//! through its own holes. Evaluating alpha needs the hit's surface coordinates,
//! so only objects whose material has a mask pay for it (the scene marks them).

use super::{ShadingPoint, Texture, Textures};
use crate::params::{Param, ParamResult, ParamType as T, Params};
use crate::ray::{Ray, OFFSET_SCALE};
use crate::shapes::{Shape, SurfaceHit};

/// A coverage texture and how it is read.
#[derive(Clone, Debug, PartialEq)]
pub struct AlphaMask {
    /// Coverage (first channel).
    pub texture: Texture,
    /// Under [`AlphaMask::blend`] unused; else the surface exists where coverage `>= cutoff`.
    pub cutoff: f64,
    /// Stochastic transparency: the surface exists with probability coverage (module documentation).
    pub blend: bool,
}

/// The alpha keys the material kinds share.
pub const ALPHA_PARAMS: [Param; 3] = [
    Param::new("alpha", T::ScalarTexture, "none", "0 to 1", "coverage: the surface is cut out where it is below `alpha_cutoff`"),
    Param::new("alpha_cutoff", T::Number, "0.5", "0 to 1", "the least coverage that is kept (glTF `alphaCutoff`)"),
    Param::new(
        "alpha_mode",
        T::String,
        "\"mask\"",
        "\"mask\", \"blend\"",
        "`mask` cuts out below `alpha_cutoff`; `blend` keeps the surface with probability `alpha` (stochastic transparency)",
    ),
];

/// Reads [`ALPHA_PARAMS`].
pub fn read(p: &mut Params<'_>, textures: &Textures<'_>) -> ParamResult<Option<std::sync::Arc<AlphaMask>>> {
    let cutoff = p.number_or("alpha_cutoff", 0.5)?;
    if !(0.0..=1.0).contains(&cutoff) {
        return Err(p.key_error("alpha_cutoff", format!("must be between 0 and 1, got {cutoff}")));
    }
    let blend = p.choice("alpha_mode", &["mask", "blend"])? == "blend";
    Ok(textures.read_scalar(p, "alpha")?.map(|texture| std::sync::Arc::new(AlphaMask { texture, cutoff, blend })))
}

impl AlphaMask {
    /// A cut-out where `texture < cutoff`.
    pub fn mask(texture: Texture, cutoff: f64) -> AlphaMask {
        AlphaMask { texture, cutoff, blend: false }
    }

    /// Stochastic transparency of coverage `texture`.
    pub fn blend(texture: Texture) -> AlphaMask {
        AlphaMask { texture, cutoff: 0.0, blend: true }
    }

    /// Whether the surface exists at `hit` of `shape` along `ray`.
    pub fn covers(&self, shape: &dyn Shape, ray: &Ray, hit: &SurfaceHit) -> bool {
        let p = ray.at(hit.t);
        let at = if self.texture.needs_coords() {
            ShadingPoint::with_coords(p, &shape.surface_coords(p, hit.normal, hit.primitive()))
        } else {
            ShadingPoint::at(p)
        };
        let alpha = self.texture.evaluate(&at).x;
        if self.blend {
            // Fully opaque and fully clear points need no draw.
            alpha >= 1.0 || (alpha > 0.0 && blend_sample(ray, hit.t) < alpha)
        } else {
            alpha >= self.cutoff
        }
    }
}

/// The uniform number in `[0, 1)` that decides whether `ray` keeps a blended
/// surface at distance `t`: the bits of its origin, direction and `t` folded
/// one word at a time through the SplitMix64 finalizer (pbrt-v4 hashes the
/// ray the same way for its alpha test).
pub fn blend_sample(ray: &Ray, t: f64) -> f64 {
    let words = [ray.origin.x, ray.origin.y, ray.origin.z, ray.dir.x, ray.dir.y, ray.dir.z, t];
    let mut h: u64 = 0x6A09_E667_F3BC_C909;
    for w in words {
        h = mix(h ^ w.to_bits());
    }
    (h >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
}

/// The SplitMix64 step: add the golden ratio, then its finalizer.
#[inline]
pub(crate) fn mix(z: u64) -> u64 {
    let mut z = z.wrapping_add(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// The nearest hit of `shape` in `(t_min, t_max)` where `mask` covers it.
/// (Not inlined: shadow rays' traversal stays as small as without masks.)
#[inline(never)]
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
        let mask = AlphaMask::mask(
            Texture::UvChecker(std::sync::Arc::new(crate::materials::texture::UvChecker {
                transform: UvTransform::new([2.0, 1.0], 0.0, [0.0, 0.0]),
                even: Rgb::ZERO,
                odd: Rgb::ONE,
            })),
            0.5,
        );
        let square = Rectangle::new(Vec3::ZERO, Vec3::X, Vec3::Y).unwrap();
        let down = |x: f64| Ray::new(Vec3::new(x, 0.5, 1.0), -Vec3::Z);
        assert!(first_covered(&square, &mask, &down(0.25), 0.0, f64::INFINITY).is_none());
        assert_eq!(first_covered(&square, &mask, &down(0.75), 0.0, f64::INFINITY).map(|h| h.t), Some(1.0));
    }

    #[test]
    fn a_blended_surface_is_met_by_the_fraction_alpha_of_rays() {
        let square = Rectangle::new(Vec3::ZERO, Vec3::X, Vec3::Y).unwrap();
        let quarter = AlphaMask::blend(Texture::Constant(Rgb::splat(0.25)));
        let n = 20_000;
        let hits = (0..n)
            .filter(|i| {
                let x = (*i as f64 + 0.5) / n as f64;
                // Every ray meets the square (at x = 0.1 to 0.9), each from its own origin and direction.
                let ray = Ray::new(Vec3::new(x, 0.5, 1.0), Vec3::new(0.2 * (0.5 - x), 0.01, -1.0).normalize());
                first_covered(&square, &quarter, &ray, 0.0, f64::INFINITY).is_some()
            })
            .count();
        // Binomial: sd = sqrt(n 0.25 0.75) = 61 rays; 5 sd.
        assert!((hits as f64 - 0.25 * n as f64).abs() < 5.0 * 61.0, "{hits} of {n}");
        // The same ray decides the same way every time.
        let ray = Ray::new(Vec3::new(0.3, 0.5, 1.0), -Vec3::Z);
        assert_eq!(blend_sample(&ray, 1.0), blend_sample(&ray, 1.0));
        let opaque = AlphaMask::blend(Texture::Constant(Rgb::ONE));
        let clear = AlphaMask::blend(Texture::Constant(Rgb::ZERO));
        assert!(first_covered(&square, &opaque, &ray, 0.0, f64::INFINITY).is_some());
        assert!(first_covered(&square, &clear, &ray, 0.0, f64::INFINITY).is_none());
    }
}
