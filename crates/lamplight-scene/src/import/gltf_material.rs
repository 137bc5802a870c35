//! glTF materials mapped onto lamplight's `pbr` material
//! ([`lamplight_core::materials::pbr`]): the specification's BRDF for the path
//! tracer, its lecture-model approximation for the Whitted tracer.
//!
//! | glTF | lamplight |
//! |---|---|
//! | `baseColorFactor` x `baseColorTexture` (sRGB) x `COLOR_0` | base colour: a `scale` texture of the three (the colours only on primitives that have them) |
//! | `metallicFactor` x `metallicRoughnessTexture`.b, `roughnessFactor` x its .g (linear) | `metallic`, `roughness` |
//! | `emissiveFactor` x `emissiveTexture` (sRGB) x `KHR_materials_emissive_strength` | `emission` (an emitting surface with a texture is not sampled as an area light) |
//! | sampler `wrapS`, `minFilter`/`magFilter` | `wrap`; `nearest` for NEAREST filters, `trilinear` for mipmapped ones, else `bilinear` |
//! | `KHR_materials_ior` `ior` | `ior`: the dielectric's `f0 = ((ior - 1) / (ior + 1))^2` |
//! | `KHR_materials_specular`: `specularFactor` x `specularTexture`.a (linear), `specularColorFactor` x `specularColorTexture` (sRGB) | `specular`, `specular_color` |
//! | `normalTexture`, its `scale` | the normal map (linear; the tangents from `TANGENT`, else MikkTSpace) |
//! | `KHR_texture_transform` | the texture's UV transform, in lamplight's `v`-up convention (`F T R S F`, `F(u, v) = (u, 1 - v)`) |
//! | `KHR_materials_transmission` `transmissionFactor` x `transmissionTexture`.r (linear) | `transmission`: thin-walled microfacet transmission replacing that share of the diffuse base (`KHR_materials_volume` is not read: a warning) |
//!
//! | `alphaMode` `MASK`, `alphaCutoff`; `BLEND` | coverage base colour alpha x `baseColorTexture` alpha ([`lamplight_core::materials::alpha`]): a cut-out at `alphaCutoff`; `BLEND` stochastic transparency |
//!
//! `occlusionTexture` is not read: the path tracer computes the occlusion it
//! stands for. A textureInfo's `texCoord` (or its `KHR_texture_transform`
//! `texCoord`) chooses `TEXCOORD_0` or `TEXCOORD_1` (a `uv_set` texture,
//! [`lamplight_core::materials::uv_set`]); sets from 2 up are read as
//! `TEXCOORD_0` (a warning says so). Numbers are clamped to their valid range
//! (non-finite ones become 0) so no NaN reaches the renderer.

use std::sync::Arc;

use lamplight_core::materials::alpha::AlphaMask;
use lamplight_core::materials::image::{Channel, Filter, Wrap};
use lamplight_core::materials::{pbr, ImageData, ImageTexture, Material, NormalMap, Slot, Texture, UvTransform};
use lamplight_core::math::Rgb;

use super::Warnings;
use crate::error::LoadError;

/// Decodes a glTF image (index, sRGB).
pub(super) type LoadImage<'a> = dyn FnMut(&gltf::Image, bool) -> Result<Arc<ImageData>, LoadError> + 'a;

/// A finite, non-negative number from an `f32` of the file.
fn clean(x: f32) -> f64 {
    if x.is_finite() {
        f64::from(x.max(0.0))
    } else {
        0.0
    }
}

fn rgb(c: [f32; 3]) -> Rgb {
    Rgb::new(clean(c[0]), clean(c[1]), clean(c[2]))
}

/// `texture * factor`, or the factor alone without a texture.
fn scaled(texture: Option<Texture>, factor: Rgb) -> Texture {
    match texture {
        None => Texture::Constant(factor),
        Some(t) if factor == Rgb::ONE => t,
        Some(t) => Texture::Scale(Arc::new([t, Texture::Constant(factor)])),
    }
}

/// The texture of a texture reference (module documentation).
fn image_texture(
    texture: &gltf::Texture,
    tex_coord: u32,
    transform: Option<gltf::texture::TextureTransform>,
    srgb: bool,
    channel: Channel,
    load: &mut LoadImage<'_>,
    warnings: &mut Warnings,
) -> Result<Texture, LoadError> {
    // KHR_texture_transform's texCoord overrides the textureInfo's.
    let set = transform.as_ref().and_then(|t| t.tex_coord()).unwrap_or(tex_coord);
    if set > 1 {
        warnings.once("glTF textures on TEXCOORD_2 and above are read with TEXCOORD_0".to_string());
    }
    let image = load(&texture.source(), srgb)?;
    let sampler = texture.sampler();
    use gltf::texture::{MagFilter, MinFilter, WrappingMode};
    let wrap = match sampler.wrap_s() {
        WrappingMode::ClampToEdge => Wrap::Clamp,
        WrappingMode::MirroredRepeat => Wrap::Mirror,
        WrappingMode::Repeat => Wrap::Repeat,
    };
    let filter = match (sampler.min_filter(), sampler.mag_filter()) {
        (Some(MinFilter::Nearest), Some(MagFilter::Nearest)) => Filter::Nearest,
        (
            Some(
                MinFilter::NearestMipmapNearest
                | MinFilter::LinearMipmapNearest
                | MinFilter::NearestMipmapLinear
                | MinFilter::LinearMipmapLinear,
            ),
            _,
        ) => Filter::Trilinear,
        _ => Filter::Bilinear,
    };
    let flip = UvTransform([[1.0, 0.0, 0.0], [0.0, -1.0, 1.0]]);
    let transform = match transform {
        None => UvTransform::IDENTITY,
        Some(t) => {
            let (offset, scale) = (t.offset().map(f64::from), t.scale().map(f64::from));
            let khr = UvTransform::new(scale, f64::from(t.rotation()), offset);
            let m = flip.then(&khr).then(&flip);
            if m.is_finite() {
                m
            } else {
                UvTransform::IDENTITY
            }
        }
    };
    let texture = Texture::Image(Arc::new(ImageTexture { image, wrap, filter, transform, channel }));
    Ok(if set == 1 { Texture::SecondUv(Arc::new(texture)) } else { texture })
}

/// Maps one glTF material (module doc); `vertex_colors` when the primitive has
/// `COLOR_0`. Images are decoded through `load`.
pub(super) fn map(
    m: &gltf::Material,
    vertex_colors: bool,
    load: &mut LoadImage<'_>,
    warnings: &mut Warnings,
) -> Result<Material, LoadError> {
    let pbr_json = m.pbr_metallic_roughness();
    let [r, g, b, alpha_factor] = pbr_json.base_color_factor();
    let base_factor = rgb([r, g, b]).min(Rgb::ONE);
    let metal = clean(pbr_json.metallic_factor()).min(1.0);
    let rough = clean(pbr_json.roughness_factor()).min(1.0);
    let strength = m.emissive_strength().map_or(1.0, clean);
    let emissive = rgb(m.emissive_factor()) * strength;
    let transmission = m.transmission().map_or(0.0, |t| clean(t.transmission_factor()).min(1.0));
    // `Some(None)`: blend; `Some(Some(c))`: a cut-out at `c`.
    let cutoff = match m.alpha_mode() {
        gltf::material::AlphaMode::Opaque => None,
        gltf::material::AlphaMode::Mask => Some(Some(m.alpha_cutoff().map_or(0.5, |c| clean(c).min(1.0)))),
        gltf::material::AlphaMode::Blend => Some(None),
    };
    let mut texture = |info: Option<gltf::texture::Info>, srgb: bool, channel: Channel| -> Result<Option<Texture>, LoadError> {
        match info {
            None => Ok(None),
            Some(i) => image_texture(&i.texture(), i.tex_coord(), i.texture_transform(), srgb, channel, load, warnings).map(Some),
        }
    };
    let mut base = scaled(texture(pbr_json.base_color_texture(), true, Channel::Rgb)?, base_factor);
    if vertex_colors {
        base = match base {
            Texture::Constant(c) if c == Rgb::ONE => Texture::VertexColor,
            other => Texture::Scale(Arc::new([other, Texture::VertexColor])),
        };
    }
    let mut maps = Vec::new();
    let mr = pbr_json.metallic_roughness_texture();
    if mr.is_some() {
        let metallic = texture(mr.clone(), false, Channel::One(2))?;
        let roughness = texture(mr, false, Channel::One(1))?;
        maps.push((pbr::METALLIC, scaled(metallic, Rgb::splat(metal))));
        maps.push((Slot::ROUGHNESS, scaled(roughness, Rgb::splat(rough))));
    }
    let emission = match texture(m.emissive_texture(), true, Channel::Rgb)? {
        Some(t) if emissive != Rgb::ZERO => {
            maps.push((Slot::EMISSION, scaled(Some(t), emissive)));
            Rgb::ZERO
        }
        _ => emissive,
    };
    let alpha = match cutoff {
        None => None,
        Some(cutoff) => {
            let coverage = texture(pbr_json.base_color_texture(), true, Channel::One(3))?;
            let coverage = scaled(coverage, Rgb::splat(clean(alpha_factor).min(1.0)));
            Some(Arc::new(match cutoff {
                Some(c) => AlphaMask::mask(coverage, c),
                None => AlphaMask::blend(coverage),
            }))
        }
    };
    // KHR_materials_ior and KHR_materials_specular: the dielectric's Fresnel.
    let ior = m.ior().map(f64::from).filter(|i| i.is_finite() && *i > 0.0).unwrap_or(1.5);
    let (mut specular, mut specular_color) = (1.0, Rgb::ONE);
    if let Some(spec) = m.specular() {
        specular = clean(spec.specular_factor()).min(1.0);
        specular_color = rgb(spec.specular_color_factor());
        if let Some(t) = texture(spec.specular_texture(), false, Channel::One(3))? {
            maps.push((pbr::SPECULAR, scaled(Some(t), Rgb::splat(specular))));
        }
        if let Some(t) = texture(spec.specular_color_texture(), true, Channel::Rgb)? {
            maps.push((pbr::SPECULAR_COLOR, scaled(Some(t), specular_color)));
        }
    }
    if let Some(t) = texture(m.transmission().and_then(|t| t.transmission_texture()), false, Channel::One(0))? {
        maps.push((pbr::TRANSMISSION, scaled(Some(t), Rgb::splat(transmission))));
    }
    let mut material = pbr::material(base, metal, rough, emission, maps);
    if let Some(p) = &mut material.pbr {
        (p.ior, p.specular, p.specular_color, p.transmission) = (ior, specular, specular_color, transmission);
    }
    pbr::derive_lecture_terms(&mut material);
    material.alpha = alpha;
    if let Some(n) = m.normal_texture() {
        let texture = image_texture(&n.texture(), n.tex_coord(), None, false, Channel::Rgb, load, warnings)?;
        let scale = if n.scale().is_finite() { f64::from(n.scale()) } else { 1.0 };
        material.normal_map = Some(Arc::new(NormalMap { texture, scale }));
    }
    Ok(material)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn roughness_maps_to_the_ggx_matched_exponent() {
        assert_eq!(pbr::shininess(1.0), 1.0);
        assert_eq!(pbr::shininess(0.5), 30.0);
        assert_eq!(pbr::shininess(0.0), 10_000.0);
    }
}
