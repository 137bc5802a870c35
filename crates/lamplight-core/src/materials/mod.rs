//! Materials of the lecture's model: the rough (Phong-Blinn) terms, emission,
//! and smooth reflection and refraction with Fresnel or with artist-set weights.
//!
//! One [`Material`] holds every property, as in the lecture; a surface is rough,
//! reflective and refractive in any mix. At a hit the Whitted integrator computes
//!
//! `L = Ke + ka*C*La + sum_l Lin_l * (kd*C (L.N)+ + ks ((H.N)+)^shine) + R * L(refl) + T * L(refr)`
//!
//! where `C` is the texture colour, the light sum skips lights with `L.N <= 0` and
//! lights in shadow, and `R`, `T` are the weights of [`Reflection`] and
//! [`Refraction`].

/// A material kind's parameter table: its own rows, then the rows every
/// surface material shares (normal map, map shadowing, bump map and alpha, in that order), so
/// that the shared rows are written once.
macro_rules! surface_params {
    ($($own:expr),* $(,)?) => {
        &[
            $($own,)*
            $crate::materials::normal_map::NORMAL_MAP_PARAMS[0],
            $crate::materials::normal_map::NORMAL_MAP_PARAMS[1],
            $crate::materials::map_shadowing::MAP_SHADOWING_PARAM,
            $crate::materials::bump::BUMP_PARAMS[0],
            $crate::materials::bump::BUMP_PARAMS[1],
            $crate::materials::alpha::ALPHA_PARAMS[0],
            $crate::materials::alpha::ALPHA_PARAMS[1],
            $crate::materials::alpha::ALPHA_PARAMS[2],
        ]
    };
}
use surface_params;

/// The `emission` row of the kinds that emit as the lecture's material does.
const EMISSION_PARAM: crate::params::Param =
    crate::params::Param::new("emission", crate::params::ParamType::Texture, "0", "radiance", "emitted radiance");
/// The `two_sided` row of every emitting kind.
const TWO_SIDED_PARAM: crate::params::Param = crate::params::Param::new(
    "two_sided",
    crate::params::ParamType::Bool,
    "false",
    "",
    "emit from both sides of the surface, not only the front",
);

/// The end of every surface kind's build: the rows of [`surface_params`]
/// (normal map, map shadowing, bump map, alpha), then [`Material::validate`].
fn finish_surface(mut m: Material, p: &mut crate::params::Params<'_>, textures: &Textures<'_>) -> crate::params::ParamResult<Material> {
    m.normal_map = normal_map::read(p, textures)?;
    m.map_shadowing = map_shadowing::read(p)?;
    m.bump = bump::read(p, textures)?;
    m.alpha = alpha::read(p, textures)?;
    m.validate().map_err(|e| p.core_error(e))?;
    Ok(m)
}

/// [`finish_surface`] for a kind with [`TWO_SIDED_PARAM`] (emission from both
/// sides, off by default).
fn finish_emitting(mut m: Material, p: &mut crate::params::Params<'_>, textures: &Textures<'_>) -> crate::params::ParamResult<Material> {
    m.two_sided = p.boolean("two_sided")?.unwrap_or(false);
    finish_surface(m, p, textures)
}

pub mod alpha;
pub mod blend;
pub mod bump;
pub mod combine;
pub mod image;
pub mod image_data;
pub mod lobes;
pub mod map_shadowing;
pub mod normal_map;
pub mod pbr;
pub mod phong;
pub mod plastic;
pub mod principled;
pub mod principled_thin;
pub mod sided;
pub mod texture;
pub mod textured;
pub mod thin_dielectric;
pub mod uv_checker;
pub mod uv_set;
pub mod uv_transform;

pub use blend::Blend;
pub use bump::BumpMap;
// Fresnel and the metals' indices are the lobes' physics; the lecture's model
// and the Whitted integrator read them from here too.
pub use crate::bsdfs::{fresnel_conductor, fresnel_conductor_channel, fresnel_dielectric, Metal};
pub use image::{ImageData, ImageLoader, ImageTexture};
pub use lobes::{bsdf_for, ToBsdf};
pub use normal_map::NormalMap;
pub use pbr::Pbr;
pub use texture::{ShadingPoint, Texture, TextureKind, Textures};
pub use textured::Slot;
pub use uv_transform::UvTransform;

/// Builds a material kind's material from its parameters, reading texturable
/// parameters through the registered texture kinds.
pub type MaterialBuild = fn(&mut crate::params::Params<'_>, &Textures<'_>) -> crate::params::ParamResult<Material>;
/// A material kind of the scene format.
pub type MaterialKind = crate::params::Kind<MaterialBuild>;

use std::borrow::Cow;
use std::sync::Arc;

use crate::math::Rgb;

/// How much of the mirror direction's radiance a surface reflects.
#[derive(Clone, Debug, PartialEq)]
pub enum Reflection {
    /// No mirror reflection.
    None,
    /// A constant weight per channel, set by the artist (the lecture's
    /// alternative to Fresnel; Heckbert's `ks`).
    Constant(Rgb),
    /// Dielectric Fresnel reflectance `F` of index `ior` (relative to the outside),
    /// rescaled to `min + (max - min) F` (POV-Ray's `reflection {min, max fresnel}`;
    /// clear glass is `min 0, max 1`).
    Dielectric {
        /// Index of refraction inside the surface.
        ior: f64,
        /// Reflectance at `F = 0`.
        min: f64,
        /// Reflectance at `F = 1`.
        max: f64,
    },
    /// Conductor Fresnel reflectance with complex index `eta + i k` per channel.
    Conductor {
        /// Real part of the index of refraction, per channel.
        eta: Rgb,
        /// Extinction coefficient, per channel.
        k: Rgb,
    },
}

/// How much of the refracted direction's radiance a surface transmits.
#[derive(Clone, Debug, PartialEq)]
pub enum Refraction {
    /// Opaque.
    None,
    /// Refraction with index `ior` and weight `1 - F` (dielectric Fresnel at the
    /// same index); on total internal reflection nothing is transmitted and the
    /// reflection's `F = 1` takes all.
    Fresnel {
        /// Index of refraction inside.
        ior: f64,
    },
    /// Refraction with index `ior` and a constant weight (Heckbert's `kt`); on total
    /// internal reflection nothing is transmitted.
    Constant {
        /// Index of refraction inside.
        ior: f64,
        /// Weight per channel.
        weight: Rgb,
    },
}

impl Refraction {
    /// The index of refraction, if the surface refracts.
    pub fn ior(&self) -> Option<f64> {
        match self {
            Refraction::None => None,
            Refraction::Fresnel { ior } | Refraction::Constant { ior, .. } => Some(*ior),
        }
    }
}

/// Declares [`Model`] from its registry: one line per model, the variant and the
/// type that holds its parameters, which maps itself to lobes ([`ToBsdf`], in
/// the model's kind file). The BSDF's dispatch is generated from the same lines,
/// so that adding a model cannot forget it.
macro_rules! models {
    ($($(#[$doc:meta])* $variant:ident($params:ty),)*) => {
        /// A scattering model of its own, which then decides the path tracer's BSDF; the
        /// lecture's fields are its Whitted approximation.
        #[derive(Clone, Debug, PartialEq)]
        pub enum Model {
            $($(#[$doc])* $variant($params),)*
        }

        impl ToBsdf for Model {
            #[inline]
            fn bsdf(&self, material: &Material, color: Rgb, front_face: bool) -> crate::bsdfs::Bsdf {
                match self {
                    $(Model::$variant(params) => params.bsdf(material, color, front_face),)*
                }
            }
        }
    };
}

models! {
    /// A diffuse base (albedo `color`) under a dielectric coating, smooth or rough
    /// (Mitsuba's `plastic` and `roughplastic`; [`plastic`]).
    Plastic(crate::bsdfs::plastic::Coating),
    /// A thin dielectric sheet (Mitsuba's `thindielectric`; [`thin_dielectric`]).
    ThinDielectric(thin_dielectric::ThinSheet),
    /// Mitsuba's principled BSDF of base colour `color` ([`principled`]).
    Principled(crate::bsdfs::principled::PrincipledParams),
    /// Mitsuba's thin principled BSDF of base colour `color` ([`principled_thin`]).
    PrincipledThin(crate::bsdfs::principled_thin::ThinParams),
}

/// Every property of a surface, the lecture's `Material`.
#[derive(Clone, Debug, PartialEq)]
pub struct Material {
    /// Surface colour `C`, multiplied into the ambient and diffuse terms.
    pub color: Texture,
    /// Ambient reflectance factor: the ambient term is `ka * C * La`.
    pub ka: Rgb,
    /// Diffuse reflectance factor: `kd * C * (L.N)`.
    pub kd: Rgb,
    /// Specular (Blinn) factor, not multiplied by `C`: `ks * (H.N)^shininess`.
    pub ks: Rgb,
    /// Blinn exponent.
    pub shininess: f64,
    /// Emitted radiance `Ke`, from the outward (front) side only unless
    /// [`Material::two_sided`], as pbrt's and Mitsuba's area lights emit.
    pub emission: Rgb,
    /// Whether `emission` leaves both sides of the surface (Mitsuba's
    /// `twosided` emitter, Blender's default for emission shaders).
    pub two_sided: bool,
    /// Whether the surface scatters light only on its front side and is black
    /// from the back ([`sided`]; Mitsuba's one-sided BSDFs). Emission is
    /// [`Material::two_sided`]'s business, not this.
    pub one_sided: bool,
    /// Smooth mirror reflection.
    pub reflection: Reflection,
    /// Smooth refraction.
    pub refraction: Refraction,
    /// Fraction of light a shadow ray keeps when it crosses this surface:
    /// 0 for opaque objects; POV-Ray lets clear glass pass shadow rays (1).
    pub shadow_transmittance: Rgb,
    /// GGX roughness `alpha` of Fresnel glass and of conductor reflection for the path
    /// tracer (0: smooth; see [`lobes`]); the Whitted tracer ignores it.
    /// Under [`Material::pbr`], glTF's perceptual roughness `r` (GGX `alpha = r^2`).
    pub roughness: f64,
    /// Anisotropic roughness: `Some(alpha_v)` makes the rough glass and conductor
    /// lobes [`Material::roughness`] rough along the surface's `dp/du` and
    /// `alpha_v` rough along the other tangent ([`crate::bsdfs::anisotropic`]);
    /// `None` (isotropic) by default.
    pub roughness_v: Option<f64>,
    /// The microfacet distribution of the rough glass and conductor lobes (GGX by default).
    pub distribution: crate::bsdfs::Distribution,
    /// A scattering model of its own ([`Model`]), which then decides the path tracer's BSDF.
    pub model: Option<Model>,
    /// Parameters driven by textures ([`textured`]); `None` when all are constant.
    pub textures: Option<Arc<[(Slot, Texture)]>>,
    /// The glTF metallic-roughness model ([`pbr`]), which then decides the path
    /// tracer's BSDF; the lecture's fields above are its Whitted approximation.
    pub pbr: Option<Pbr>,
    /// A tangent-space normal map ([`normal_map`]), applied where the surface is shaded.
    /// (Shared: rare and large, kept out of the material's cache lines.)
    pub normal_map: Option<Arc<NormalMap>>,
    /// A height map ([`bump`]) that turns the shading normal, applied before the normal map.
    pub bump: Option<Arc<BumpMap>>,
    /// Whether light reaching a point whose normal a map turned is dimmed by
    /// Mitsuba's shadowing term ([`map_shadowing`]).
    pub map_shadowing: bool,
    /// A cut-out mask ([`alpha`]): where it is below its cutoff the surface is not there.
    pub alpha: Option<Arc<alpha::AlphaMask>>,
    /// Two materials mixed by a weight ([`blend`]): the scene shades each hit
    /// as one of them, and this material's own lobes are none.
    pub blend: Option<Arc<Blend>>,
}

impl Default for Material {
    /// Mid-grey diffuse: `C = 0.5`, `ka = 0.1`, `kd = 0.9`, nothing else.
    fn default() -> Material {
        Material {
            color: Texture::Constant(Rgb::splat(0.5)),
            ka: Rgb::splat(0.1),
            kd: Rgb::splat(0.9),
            ks: Rgb::ZERO,
            shininess: 1.0,
            emission: Rgb::ZERO,
            two_sided: false,
            one_sided: false,
            reflection: Reflection::None,
            refraction: Refraction::None,
            shadow_transmittance: Rgb::ZERO,
            roughness: 0.0,
            roughness_v: None,
            distribution: crate::bsdfs::Distribution::Ggx,
            model: None,
            textures: None,
            pbr: None,
            normal_map: None,
            bump: None,
            map_shadowing: false,
            alpha: None,
            blend: None,
        }
    }
}

impl Material {
    /// A diffuse-specular ("plastic") material: colour `c`, scalar factors, white highlight.
    pub fn plastic(c: Rgb, ka: f64, kd: f64, ks: f64, shininess: f64) -> Material {
        Material {
            color: Texture::Constant(c),
            ka: Rgb::splat(ka),
            kd: Rgb::splat(kd),
            ks: Rgb::splat(ks),
            shininess,
            ..Material::default()
        }
    }

    /// Clear glass of index `ior`: Fresnel reflection and refraction, a white highlight
    /// of `ks`/`shininess`, and no shadow (POV-Ray's convention).
    pub fn glass(ior: f64, ks: f64, shininess: f64) -> Material {
        Material {
            color: Texture::Constant(Rgb::ONE),
            ka: Rgb::ZERO,
            kd: Rgb::ZERO,
            ks: Rgb::splat(ks),
            shininess,
            reflection: Reflection::Dielectric { ior, min: 0.0, max: 1.0 },
            refraction: Refraction::Fresnel { ior },
            shadow_transmittance: Rgb::ONE,
            ..Material::default()
        }
    }

    /// A polished metal: conductor Fresnel reflection of a preset, plus a highlight.
    pub fn metal(metal: Metal, ks: f64, shininess: f64) -> Material {
        let (eta, k) = metal.eta_k();
        Material {
            color: Texture::Constant(Rgb::ONE),
            ka: Rgb::ZERO,
            kd: Rgb::ZERO,
            ks: Rgb::splat(ks),
            shininess,
            reflection: Reflection::Conductor { eta, k },
            ..Material::default()
        }
    }

    /// Whether a texture drives some parameter or the colour varies over the surface.
    pub fn is_constant(&self) -> bool {
        self.textures.is_none() && self.color.constant().is_some() && self.pbr.as_ref().is_none_or(Pbr::is_constant) && self.blend.is_none()
    }

    /// Whether some texture of the material is filtered over the pixel footprint.
    pub fn uses_footprint(&self) -> bool {
        self.color.uses_footprint()
            || self.textures.as_ref().is_some_and(|t| t.iter().any(|(_, t)| t.uses_footprint()))
            || self.normal_map.as_ref().is_some_and(|n| n.texture.uses_footprint())
            || self.bump.is_some()
            || self.blend.as_ref().is_some_and(|b| b.weight.uses_footprint() || b.a.uses_footprint() || b.b.uses_footprint())
    }

    /// Whether evaluating the material needs the hit's surface coordinates.
    pub fn needs_coords(&self) -> bool {
        self.color.needs_coords()
            || self.normal_map.is_some()
            || self.bump.is_some()
            || self.textures.as_ref().is_some_and(|t| t.iter().any(|(_, t)| t.needs_coords()))
            || self.pbr.as_ref().is_some_and(Pbr::needs_coords)
            || self.blend.as_ref().is_some_and(|b| b.weight.needs_coords())
    }

    /// The material at a shading point: every texture evaluated into its field
    /// ([`textured`]), the colour made constant, and the metallic-roughness
    /// model's Whitted terms derived ([`pbr`]). Borrowed when nothing varies.
    pub fn at(&self, at: &ShadingPoint) -> Cow<'_, Material> {
        if self.is_constant() {
            return Cow::Borrowed(self);
        }
        let mut m = self.clone();
        m.color = Texture::Constant(self.color.evaluate(at));
        if let Some(maps) = m.textures.take() {
            for (slot, texture) in maps.iter() {
                slot.apply(&mut m, texture.evaluate(at));
            }
        }
        pbr::derive_lecture_terms(&mut m);
        Cow::Owned(m)
    }

    /// Whether the surface emits towards a ray that met its front face
    /// (`front_face`) or its back: some emission, and the front side or
    /// [`Material::two_sided`].
    #[inline]
    pub fn emits_towards(&self, front_face: bool) -> bool {
        self.emission != Rgb::ZERO && (front_face || self.two_sided)
    }

    /// The texture of `emission`, where a texture drives it.
    pub fn emission_texture(&self) -> Option<&Texture> {
        self.textures.as_deref()?.iter().find(|(s, _)| *s == Slot::EMISSION).map(|(_, t)| t)
    }

    /// Whether the material emits anywhere: a non-zero `emission` or a texture for it.
    pub fn emits(&self) -> bool {
        self.emission != Rgb::ZERO || self.emission_texture().is_some()
    }

    /// Whether the surface scatters light (reflects or transmits) at a hit
    /// on its front face (`front_face`) or its back: always, unless
    /// [`Material::one_sided`] and the back.
    #[inline]
    pub fn scatters_at(&self, front_face: bool) -> bool {
        front_face || !self.one_sided
    }

    /// True when the material needs the light loop (some diffuse or specular term).
    pub fn is_lit(&self) -> bool {
        self.kd != Rgb::ZERO || self.ks != Rgb::ZERO
    }

    /// Checks every number: finite, and non-negative where physics asks it.
    pub fn validate(&self) -> Result<(), crate::Error> {
        let rgb_ok = |name: &str, c: Rgb| {
            if c.is_finite() && c.min_element() >= 0.0 {
                Ok(())
            } else {
                Err(crate::Error::invalid(name, format!("must be finite and non-negative, got {c}")))
            }
        };
        rgb_ok("ka", self.ka)?;
        rgb_ok("kd", self.kd)?;
        rgb_ok("ks", self.ks)?;
        rgb_ok("emission", self.emission)?;
        rgb_ok("shadow_transmittance", self.shadow_transmittance)?;
        if !(self.shininess.is_finite() && self.shininess >= 0.0) {
            return Err(crate::Error::invalid("shininess", "must be a non-negative number"));
        }
        if !(self.roughness.is_finite() && (0.0..=1.0).contains(&self.roughness)) {
            return Err(crate::Error::invalid("roughness", format!("must be between 0 and 1, got {}", self.roughness)));
        }
        if let Some(v) = self.roughness_v.filter(|v| !(v.is_finite() && (0.0..=1.0).contains(v))) {
            return Err(crate::Error::invalid("roughness_v", format!("must be between 0 and 1, got {v}")));
        }
        match &self.color {
            Texture::Constant(c) => rgb_ok("color", *c)?,
            Texture::Checker { size, even, odd, offset } => {
                rgb_ok("color", *even)?;
                rgb_ok("color", *odd)?;
                if !(size.is_finite() && *size > 0.0 && offset.is_finite()) {
                    return Err(crate::Error::invalid("checker size", "must be a positive number"));
                }
            }
            // Read through the registry's kinds, which check their own numbers.
            _ => {}
        }
        let ior_ok = |ior: f64| {
            if ior.is_finite() && ior > 0.0 {
                Ok(())
            } else {
                Err(crate::Error::invalid("ior", format!("must be a positive number, got {ior}")))
            }
        };
        match &self.reflection {
            Reflection::None => {}
            Reflection::Constant(c) => rgb_ok("reflection", *c)?,
            Reflection::Dielectric { ior, min, max } => {
                ior_ok(*ior)?;
                if !(min.is_finite() && max.is_finite()) {
                    return Err(crate::Error::invalid("reflection", "min and max must be finite"));
                }
                if !(0.0 <= *min && min <= max && *max <= 1.0) {
                    return Err(crate::Error::invalid("reflection", format!("needs 0 <= min <= max <= 1, got min {min} and max {max}")));
                }
            }
            Reflection::Conductor { eta, k } => {
                rgb_ok("eta", *eta)?;
                rgb_ok("k", *k)?;
            }
        }
        match &self.refraction {
            Refraction::None => {}
            Refraction::Fresnel { ior } => ior_ok(*ior)?,
            Refraction::Constant { ior, weight } => {
                ior_ok(*ior)?;
                rgb_ok("transmission", *weight)?;
            }
        }
        Ok(())
    }
}
