//! From a [`Material`] to the path tracer's [`Bsdf`], so that every scene renders
//! under both integrators without edits.
//!
//! Each scattering model says which lobes it is, in its own kind's file, through
//! [`ToBsdf`]; this file only decides which model speaks for a material:
//!
//! | the material has | its lobes come from |
//! |---|---|
//! | [`Material::pbr`] | [`super::pbr`]: the glTF metallic-roughness lobe |
//! | [`Material::model`] | the model's kind file, by [`Model`](super::Model)'s registry: [`super::plastic`], [`super::thin_dielectric`], [`super::principled`], [`super::principled_thin`] |
//! | neither | the lecture's terms, read as lobes by [`super::phong`] |
//!
//! The lobes are physics and know nothing of materials ([`crate::bsdfs`] sits
//! below this folder); the mapping from a material's parameters to them is the
//! material's business, so a new model is its kind file, its lobe (if it brings
//! one) and one line in [`Model`](super::Model)'s registry.

use super::{phong, Material, ShadingPoint};
use crate::bsdfs::Bsdf;
use crate::math::{Rgb, Vec3};

/// A scattering model that builds the path tracer's BSDF.
pub trait ToBsdf {
    /// The BSDF of `material` (whose model `self` is) with surface colour `color`,
    /// for a ray that arrived on the outward side when `front_face`.
    fn bsdf(&self, material: &Material, color: Rgb, front_face: bool) -> Bsdf;
}

/// The BSDF of `material` at `point`, for a ray that arrived on the outward side when
/// `front_face` (the relative index is `ior` entering, `1 / ior` leaving).
pub fn bsdf_for(material: &Material, point: Vec3, front_face: bool) -> Bsdf {
    let color = material.color.evaluate(&ShadingPoint::at(point));
    if let Some(pbr) = &material.pbr {
        return pbr.bsdf(material, color, front_face);
    }
    match &material.model {
        Some(model) => model.bsdf(material, color, front_face),
        None => phong::lecture_bsdf(material, color, front_face),
    }
}

#[cfg(test)]
mod tests;
