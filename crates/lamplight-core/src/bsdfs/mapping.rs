//! From the lecture's all-in-one [`Material`] to a physically based [`Bsdf`], so
//! that every scene renders under both integrators without edits.
//!
//! | lecture term | path tracer |
//! |---|---|
//! | `kd * C` | Lambertian albedo (`f = kd C / pi`) |
//! | `ks`, `shininess` | GGX reflection of reflectance `ks`, roughness `sqrt(2 / (shine + 2))` |
//! | `Reflection::Constant(w)` | mirror of weight `w` |
//! | `Reflection::Dielectric` + `Refraction::Fresnel` of one index, `min 0 max 1` | smooth glass; rough glass (GGX, [`super::rough_dielectric`]) of `alpha = roughness` when `roughness >= 0.001` |
//! | `Reflection::Dielectric {min, max}` otherwise | mirror of weight `min + (max - min) F` |
//! | `Reflection::Conductor {eta, k}` | conductor mirror with complex Fresnel; rough metal (GGX, [`super::rough_conductor`]) of `alpha = roughness` when `roughness >= 0.001` |
//! | `Refraction::Fresnel` alone | refraction of weight `1 - F` |
//! | `Refraction::Constant(w)` | refraction of weight `w` |
//! | `emission` | area light radiance (see [`crate::lights::area`]) |
//! | [`Material::model`] plastic | the coating over a diffuse base of albedo `C` (capped at 1), smooth ([`super::plastic`]) or rough ([`super::rough_plastic`]), alone |
//! | [`Material::model`] principled | Mitsuba's principled BSDF ([`super::principled`]) of base colour `C`, alone |
//! | [`Material::model`] thin principled | Mitsuba's `principledthin` ([`super::principled_thin`]) of base colour `C`, alone |
//! | [`Material::model`] thin dielectric | a thin sheet ([`super::thin_dielectric`]), alone |
//! | [`Material::distribution`] | the distribution of the rough glass and metal lobes (GGX or Beckmann, [`super::distribution`]) |
//! | [`Material::pbr`] (glTF metallic-roughness) | the glTF BRDF ([`super::metallic_roughness`]) of base colour `C`, `metallic`, `alpha = max(roughness^2, 0.001)`, alone |
//! | `ka` | nothing: it stands for the indirect light the path tracer computes (the background is the sky, [`crate::lights::LightSet`]) |
//!
//! With lights read as [`crate::lights::DELTA_SCALE`] says, the Lambertian lobe
//! gives exactly the lecture's diffuse term under point, directional and spot
//! lights; the GGX lobe only approximates the Blinn highlight.
//!
//! On a conductor or on Fresnel glass the Blinn highlight is dropped: it stands for
//! the light source's own reflection, which the path tracer computes from the
//! mirror (a point light's reflection in a perfect mirror is invisible in both).
//! Then every lobe is scaled per channel so that the reflectance bounds sum to at
//! most 1 ([`Bsdf::new`]): the lecture lets `kd + ks + kr` exceed 1, physics does not.

use super::metallic_roughness::MetallicRoughness;
use super::plastic::Plastic;
use super::rough_plastic::RoughPlastic;
use super::{microfacet, Bsdf, Lobe, MirrorFresnel};
use crate::materials::{Material, Model, Reflection, Refraction};
use crate::math::{Rgb, Vec3};

/// The BSDF of `material` at `point`, for a ray that arrived on the outward side when
/// `front_face` (the relative index is `ior` entering, `1 / ior` leaving).
pub fn bsdf_for(material: &Material, point: Vec3, front_face: bool) -> Bsdf {
    let color = material.color.evaluate(&crate::materials::ShadingPoint::at(point));
    if let Some(pbr) = &material.pbr {
        let alpha = (material.roughness * material.roughness).max(microfacet::MIN_ALPHA);
        let lobe = MetallicRoughness {
            base: color.min(Rgb::ONE),
            metallic: pbr.metallic,
            spec: pbr.specular(),
            alpha,
            transmission: pbr.transmission,
        };
        return Bsdf::new(&[Lobe::MetallicRoughness(lobe)]);
    }
    match &material.model {
        Some(Model::Plastic(coating)) => {
            let base = color.clamp(Rgb::ZERO, Rgb::ONE);
            let lobe = match coating.rough {
                Some((m, table)) => Lobe::RoughPlastic(RoughPlastic::new(base, coating, m, table)),
                None => Lobe::Plastic(Plastic::new(base, coating)),
            };
            return Bsdf::new(&[lobe]);
        }
        // The sheet has the same medium on both sides: the face does not matter.
        // It tells the two sides apart itself, as Mitsuba's does.
        Some(Model::Principled(params)) => {
            return Bsdf::new(&[Lobe::Principled(super::principled::Principled::new(color.max(Rgb::ZERO), *params, front_face))])
        }
        Some(Model::PrincipledThin(params)) => {
            return Bsdf::new(&[Lobe::PrincipledThin(super::principled_thin::PrincipledThin::new(color.max(Rgb::ZERO), *params))])
        }
        Some(Model::ThinDielectric { eta }) => return Bsdf::new(&[Lobe::ThinGlass { eta: *eta, tint: Rgb::ONE }]),
        None => {}
    }
    let relative = |ior: f64| if front_face { ior } else { 1.0 / ior };
    let mut lobes: [Lobe; 4] = [Lobe::Diffuse(Rgb::ZERO); 4];
    let mut n = 0;
    let mut push = |lobe: Lobe| {
        lobes[n] = lobe;
        n += 1;
    };
    if material.kd != Rgb::ZERO {
        push(Lobe::Diffuse(material.kd * color));
    }
    let glass = match (&material.reflection, &material.refraction) {
        (Reflection::Dielectric { ior, min, max }, Refraction::Fresnel { ior: t }) => *ior == *t && *min == 0.0 && *max == 1.0,
        _ => false,
    };
    let conductor = matches!(material.reflection, Reflection::Conductor { .. });
    if material.ks != Rgb::ZERO && !glass && !conductor {
        push(Lobe::Glossy { ks: material.ks, alpha: microfacet::alpha_from_shininess(material.shininess) });
    }
    if glass {
        if let Refraction::Fresnel { ior } = material.refraction {
            // Below the smallest GGX roughness the lobe is a mirror that f64 cannot sample.
            if material.roughness >= microfacet::MIN_ALPHA {
                push(Lobe::RoughGlass {
                    eta: relative(ior),
                    alpha: material.roughness,
                    tint: Rgb::ONE,
                    distribution: material.distribution,
                });
            } else {
                push(Lobe::Glass { eta: relative(ior), tint: Rgb::ONE });
            }
        }
    } else {
        match material.reflection {
            Reflection::None => {}
            Reflection::Constant(w) => push(Lobe::Mirror(MirrorFresnel::Constant(w))),
            Reflection::Dielectric { ior, min, max } => push(Lobe::Mirror(MirrorFresnel::Dielectric { eta: relative(ior), min, max })),
            Reflection::Conductor { eta, k } if material.roughness >= microfacet::MIN_ALPHA => {
                push(Lobe::RoughConductor { eta, k, alpha: material.roughness, distribution: material.distribution })
            }
            Reflection::Conductor { eta, k } => push(Lobe::Mirror(MirrorFresnel::Conductor { eta, k })),
        }
        match material.refraction {
            Refraction::None => {}
            Refraction::Fresnel { ior } => push(Lobe::Refract { eta: relative(ior), weight: None }),
            Refraction::Constant { ior, weight } => push(Lobe::Refract { eta: relative(ior), weight: Some(weight) }),
        }
    }
    Bsdf::new(&lobes[..n])
}
