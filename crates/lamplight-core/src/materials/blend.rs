//! `blend`: two materials mixed by a weight (Blender's Mix Shader, Mitsuba's
//! `blendbsdf`, pbrt-v4's `mix`):
//!
//! `f = (1 - w) f_a + w f_b`
//!
//! with `w` a number or a scalar texture (its first channel, clamped to `[0, 1]`).
//!
//! | parameter | type | default | meaning |
//! |---|---|---|---|
//! | `a` | string or table | | the material where `w = 0`: the name of a `[materials]` entry, or a material table `{ type = ..., ... }` |
//! | `b` | string or table | | the material where `w = 1` |
//! | `weight` | number or texture | 0.5 | `w`, 0 to 1 |
//! | `normal_map`, `bump` | | | as for `phong`; turn the normal before the components' own maps |
//! | `alpha`, `alpha_cutoff`, `alpha_mode` | | | as for `phong`: the blend's cut-out (its components take none) |
//!
//! ```toml
//! [materials.rusty]
//! type = "blend"
//! a = "paint"                                   # a [materials] entry
//! b = { type = "pbr", base_color = [0.4, 0.2, 0.1], roughness = 0.8 }
//! weight = { type = "image", file = "rust.png", channel = "r" }
//! ```
//!
//! **Sampling.** Each hit takes one component, `b` with probability `w` and `a`
//! otherwise, as pbrt-v4's `MixMaterial` does, and is shaded as that material
//! alone: its textures, normal map, BSDF (value, density and samples together)
//! and emission. The expected radiance is the mixture's. The choice is a hash of
//! the hit point, the direction to the viewer and the blend's index
//! ([`choice_sample`]), not a sampler dimension: a render is the same for any
//! thread count, and scenes without blends draw exactly the numbers they drew
//! before. `w = 0` always takes `a` and `w = 1` always `b`.
//!
//! **Emission.** With a constant weight and components of constant emission
//! (from the same sides) the blend emits `(1 - w) Le_a + w Le_b` everywhere,
//! and is an area light that light samples find; otherwise each hit emits what
//! its component emits (found by BSDF samples only, as a textured emission).
//!
//! **Nesting.** A component may be a blend itself, at most [`MAX_DEPTH`]
//! blends deep; a blend that names itself, directly or through others, is an
//! error. The Whitted tracer sees the chosen component too, so it needs more
//! than one sample per pixel to average them.

use std::sync::Arc;

use super::textured::Slot;
use super::{Material, MaterialKind, Texture, Textures};
use crate::math::{Rgb, Vec3};
use crate::params::{Kind, Param, ParamResult, ParamType as T, Params};

/// Most blends nested in one another.
pub const MAX_DEPTH: usize = 8;

/// Reads the components of a blend: a material named by a string, or a
/// material table built by its kind. The scene format provides it (it knows
/// the scene's named materials and the registry's kinds), with the cycle and
/// depth checks.
pub trait Components {
    /// The material of key `key` of `p`, `None` when the key is absent.
    fn component(&self, p: &mut Params<'_>, key: &str, textures: &Textures<'_>) -> ParamResult<Option<Material>>;
}

/// Two materials and the weight of the second.
#[derive(Clone, Debug, PartialEq)]
pub struct Blend {
    /// `w` (first channel), the probability of `b`.
    pub weight: Texture,
    /// The material where `w = 0`.
    pub a: Material,
    /// The material where `w = 1`.
    pub b: Material,
}

impl Blend {
    /// How many blends deep it is (1 for a blend of plain materials).
    pub fn depth(&self) -> usize {
        1 + [&self.a, &self.b].iter().map(|m| m.blend.as_ref().map_or(0, |b| b.depth())).max().unwrap_or(0)
    }

    /// The weight at `at`, clamped to `[0, 1]` (NaN counts as 0).
    #[inline]
    pub fn weight_at(&self, at: &super::ShadingPoint) -> f64 {
        let w = self.weight.evaluate(at).x;
        if w >= 1.0 {
            1.0
        } else if w > 0.0 {
            w
        } else {
            0.0
        }
    }
}

/// The uniform number in `[0, 1)` that picks a blend's component at `point`
/// seen along `-wo`: the bits of both and of `salt` (the blend's material
/// index, so that nested blends choose independently) folded through the
/// SplitMix64 finalizer, as [`super::alpha::blend_sample`] hashes a ray.
#[inline]
pub fn choice_sample(point: Vec3, wo: Vec3, salt: u64) -> f64 {
    let words = [point.x, point.y, point.z, wo.x, wo.y, wo.z];
    let mut h: u64 = 0xBB67_AE85_84CA_A73B ^ salt.wrapping_mul(0x9E37_79B9_7F4A_7C15);
    for w in words {
        h = super::alpha::mix(h ^ w.to_bits());
    }
    (h >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
}

/// Whether component `m` picks `b`: `u < w` (so `w = 0` never does, `w = 1` always).
#[inline]
pub fn picks_b(u: f64, w: f64) -> bool {
    u < w
}

/// A constant emission of `m`, `None` where a texture drives it.
fn constant_emission(m: &Material) -> Option<Rgb> {
    let textured = m.textures.as_ref().is_some_and(|t| t.iter().any(|(s, _)| *s == Slot::EMISSION));
    (!textured).then_some(m.emission)
}

/// The blend of `a` and `b` by `weight` (module documentation): a material
/// whose own lobes are none, which the scene replaces by a component per hit.
/// Errors name `a` or `b` (a component with a cut-out, nesting too deep).
pub fn material(weight: Texture, mut a: Material, mut b: Material) -> Result<Material, (&'static str, String)> {
    for (key, m) in [("a", &a), ("b", &b)] {
        if m.alpha.is_some() {
            return Err((key, "a blend's components take no `alpha` (give it to the blend)".into()));
        }
    }
    let w = weight.constant().map(|c| c.x.clamp(0.0, 1.0));
    let mut m = Material { color: Texture::Constant(Rgb::ZERO), ka: Rgb::ZERO, kd: Rgb::ZERO, ..Material::default() };
    // Emission: mixed into one area light where it can be (module documentation).
    let sides_agree = a.emission == Rgb::ZERO || b.emission == Rgb::ZERO || a.two_sided == b.two_sided;
    if let (Some(w), Some(ea), Some(eb), true) = (w, constant_emission(&a), constant_emission(&b), sides_agree) {
        let mixed = (1.0 - w) * ea + w * eb;
        let two_sided = if ea != Rgb::ZERO { a.two_sided } else { b.two_sided };
        for c in [&mut a, &mut b] {
            (c.emission, c.two_sided) = (mixed, two_sided);
        }
        (m.emission, m.two_sided) = (mixed, two_sided);
    }
    // Shadow rays (the Whitted tracer's) keep the mixture of what each lets through,
    // the least of both under a varying weight.
    m.shadow_transmittance = match w {
        Some(w) => (1.0 - w) * a.shadow_transmittance + w * b.shadow_transmittance,
        None => a.shadow_transmittance.min(b.shadow_transmittance),
    };
    let blend = Blend { weight, a, b };
    let depth = blend.depth();
    if depth > MAX_DEPTH {
        return Err(("a", format!("blends nested {depth} deep, more than {MAX_DEPTH}")));
    }
    m.blend = Some(Arc::new(blend));
    Ok(m)
}

/// `blend`.
pub const KIND: MaterialKind = Kind {
    name: "blend",
    summary: "two materials mixed by a weight, `(1 - w) a + w b` (Blender's Mix Shader, Mitsuba's `blendbsdf`)",
    params: super::surface_params![
        Param::new("a", T::Material, "", "", "the material where `weight` is 0: a `[materials]` name or a material table"),
        Param::new("b", T::Material, "", "", "the material where `weight` is 1"),
        Param::new("weight", T::ScalarTexture, "0.5", "0 to 1", "`w`: the share of `b`"),
    ],
    build,
};

fn build(p: &mut Params<'_>, textures: &Textures<'_>) -> ParamResult<Material> {
    let Some(components) = textures.materials else {
        return Err(p.error("a blend needs the scene's materials, which are not available here"));
    };
    let read = |p: &mut Params<'_>, key: &str| -> ParamResult<Material> {
        components.component(p, key, textures)?.ok_or_else(|| p.error(format!("needs `{key}` (a material name or table)")))
    };
    let a = read(p, "a")?;
    let b = read(p, "b")?;
    let weight = textures.read_scalar(p, "weight")?.unwrap_or(Texture::Constant(Rgb::splat(0.5)));
    if let Some(w) = weight.constant().map(|c| c.x) {
        if !(0.0..=1.0).contains(&w) {
            return Err(p.key_error("weight", format!("must be between 0 and 1, got {w}")));
        }
    }
    let m = material(weight, a, b).map_err(|(key, message)| p.key_error(key, message))?;
    super::finish_surface(m, p, textures)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn diffuse(albedo: f64) -> Material {
        Material { color: Texture::Constant(Rgb::ONE), kd: Rgb::splat(albedo), ka: Rgb::ZERO, ..Material::default() }
    }

    #[test]
    fn the_choice_is_uniform_and_picks_b_with_probability_w() {
        let n = 100_000;
        let w = 0.3;
        let picked = (0..n)
            .filter(|i| {
                let p = Vec3::new(*i as f64 * 1e-3, 0.5, -(*i as f64).sqrt());
                picks_b(choice_sample(p, Vec3::Z, 7), w)
            })
            .count();
        // Binomial sd sqrt(n w (1 - w)) = 145; 5 sd.
        assert!((picked as f64 - w * n as f64).abs() < 5.0 * 145.0, "{picked}");
        // Weights 0 and 1 never and always pick `b`, whatever the number.
        for u in [0.0, 0.5, 1.0 - f64::EPSILON] {
            assert!(!picks_b(u, 0.0) && picks_b(u, 1.0));
        }
        // Another blend index draws another number.
        assert_ne!(choice_sample(Vec3::X, Vec3::Z, 1), choice_sample(Vec3::X, Vec3::Z, 2));
    }

    #[test]
    fn emissions_mix_and_nesting_is_bounded() {
        let glow = |e: f64| Material { emission: Rgb::splat(e), ..diffuse(0.5) };
        let m = material(Texture::Constant(Rgb::splat(0.25)), glow(1.0), glow(3.0)).unwrap();
        assert_eq!(m.emission, Rgb::splat(1.5));
        let blend = m.blend.as_ref().unwrap();
        assert_eq!((blend.a.emission, blend.b.emission), (Rgb::splat(1.5), Rgb::splat(1.5)));
        // A varying weight leaves each component its own emission, and no area light.
        let checker = Texture::Checker { size: 1.0, even: Rgb::ZERO, odd: Rgb::ONE, offset: Vec3::ZERO };
        let m = material(checker, glow(1.0), glow(3.0)).unwrap();
        assert_eq!(m.emission, Rgb::ZERO);
        assert_eq!(m.blend.as_ref().unwrap().b.emission, Rgb::splat(3.0));
        let mut m = diffuse(0.5);
        for _ in 0..MAX_DEPTH {
            m = material(Texture::Constant(Rgb::splat(0.5)), m, diffuse(0.1)).unwrap();
        }
        assert_eq!(m.blend.as_ref().unwrap().depth(), MAX_DEPTH);
        let err = material(Texture::Constant(Rgb::splat(0.5)), m, diffuse(0.1)).unwrap_err();
        assert_eq!(err, ("a", format!("blends nested 9 deep, more than {MAX_DEPTH}")));
    }
}
