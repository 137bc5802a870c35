//! Shading a hit: the material's textures evaluated at the hit's surface
//! coordinates (computed only for materials that read them), its normal map
//! and bump map applied, and the pixel footprint carried into `(u, v)` for MIP-mapping.

use std::borrow::Cow;

use super::{Hit, Scene};
use crate::bsdfs::{Bsdf, Frame};
use crate::materials::blend::{choice_sample, picks_b};
use crate::materials::{Blend, Material, ShadingPoint};
use crate::math::Vec3;

impl Scene {
    /// The local shading frame of `bsdf` at `hit` (`z` the shading normal on the
    /// ray's side): any frame around the normal, or, for an anisotropic BSDF, the
    /// one whose first tangent follows the surface's `dp/du` as Mitsuba's
    /// ([`Frame::from_tangent`]). Only then are the surface coordinates computed,
    /// so isotropic surfaces keep their frame and their cost.
    #[inline(always)]
    pub fn shading_frame(&self, hit: &Hit, bsdf: &Bsdf) -> Frame {
        if bsdf.needs_tangent() {
            self.tangent_frame(hit)
        } else {
            Frame::new(hit.normal)
        }
    }

    /// [`Frame::from_tangent`] of the shading normal and the shape's `dp/du`; the
    /// fallback basis is built around the outward shading normal, as Mitsuba's.
    #[cold]
    #[inline(never)]
    fn tangent_frame(&self, hit: &Hit) -> Frame {
        let dpdu = self.surface_coords(hit).dpdu;
        let outward = if hit.front_face { hit.normal } else { -hit.normal };
        Frame::from_tangent(hit.normal, dpdu, outward)
    }

    /// What textures are evaluated at for `hit`: its point, and its surface
    /// coordinates and vertex colour when the material reads them (computed
    /// only then, [`Scene::surface_coords`]).
    #[inline]
    pub fn shading_point(&self, hit: &Hit) -> ShadingPoint {
        if self.materials[hit.material].needs_coords() {
            ShadingPoint::with_coords(hit.point, &self.surface_coords(hit))
        } else {
            ShadingPoint::at(hit.point)
        }
    }

    /// Shades `hit`, seen from the unit direction `wo` by a ray whose pixel
    /// footprint there is `footprint` wide (0: unknown): the material with its
    /// textures evaluated there ([`Material::at`]), and the shading normal
    /// turned by the material's bump map ([`crate::materials::bump`]) and
    /// normal map ([`crate::materials::normal_map`]).
    /// The surface coordinates are computed once, and only when the material
    /// reads them.
    /// The material of a plain surface is answered here, compiled into every
    /// caller (the Whitted packets' loop called this out of line otherwise);
    /// the rest goes to `Scene::shade_textured`.
    #[inline(always)]
    pub fn shade(&self, hit: &mut Hit, wo: Vec3, footprint: f64) -> Cow<'_, Material> {
        // A colour of the point alone (the 3D checker) is evaluated where it is
        // used, as before textures: copying the material per hit slowed `spheres` (its floor).
        if self.plain[hit.material] {
            return Cow::Borrowed(&self.materials[hit.material]);
        }
        self.shade_textured(hit, wo, footprint)
    }

    /// [`Scene::shade`] of a material that is not plain.
    #[inline]
    fn shade_textured(&self, hit: &mut Hit, wo: Vec3, footprint: f64) -> Cow<'_, Material> {
        let material = &self.materials[hit.material];
        let constant = matches!(self.bsdfs.get(hit.material), Some(Some(_)));
        let mut at = ShadingPoint::at(hit.point);
        let coords = material.needs_coords().then(|| self.surface_coords(hit));
        if let Some(c) = &coords {
            at = ShadingPoint::with_coords(hit.point, c);
            if footprint > 0.0 {
                (at.duv_dx, at.duv_dy) = footprint_in_uv(c.dpdu, c.dpdv, hit.geometric_normal, wo, footprint);
                if let (Some(second), Some(s)) = (&mut at.second, &c.uv1) {
                    (second[1], second[2]) = footprint_in_uv(s.dpdu, s.dpdv, hit.geometric_normal, wo, footprint);
                }
            }
        }
        if let (Some(bump), Some(c)) = (&material.bump, &coords) {
            hit.normal = bump.apply(&at, c, self.shape_outward(hit), hit.normal, hit.geometric_normal, wo);
        }
        if let (Some(map), Some(c)) = (&material.normal_map, &coords) {
            hit.normal = map.apply(&at, c, hit.normal, hit.geometric_normal, wo);
        }
        if let Some(blend) = &material.blend {
            return self.shade_component(hit, wo, footprint, blend, &at);
        }
        if constant {
            return Cow::Borrowed(material);
        }
        match material.at(&at) {
            Cow::Owned(m) => Cow::Owned(m),
            Cow::Borrowed(_) => Cow::Borrowed(material),
        }
    }

    /// Shades `hit` as one component of the blend `blend` (its material):
    /// `b` with probability `w`, else `a` ([`crate::materials::blend`]).
    /// `hit.material` becomes the component's, so that its prebuilt BSDF is found.
    #[inline(never)]
    fn shade_component(&self, hit: &mut Hit, wo: Vec3, footprint: f64, blend: &Blend, at: &ShadingPoint) -> Cow<'_, Material> {
        let Some([a, b]) = self.blend_parts.get(hit.material).copied().flatten() else {
            return Cow::Borrowed(&self.materials[hit.material]);
        };
        let u = choice_sample(hit.point, wo, hit.material as u64);
        hit.material = if picks_b(u, blend.weight_at(at)) { b } else { a };
        self.shade(hit, wo, footprint)
    }

    /// The material of `hit` with its textures evaluated there
    /// ([`Material::at`]; borrowed for a constant material). A blend is its
    /// own material here (black); [`Scene::shade`] picks its component.
    #[inline]
    pub fn material_at(&self, hit: &Hit) -> Cow<'_, Material> {
        let material = &self.materials[hit.material];
        // A prebuilt BSDF marks a constant material, one load instead of three tests.
        if matches!(self.bsdfs.get(hit.material), Some(Some(_))) {
            return Cow::Borrowed(material);
        }
        match material.at(&self.shading_point(hit)) {
            Cow::Owned(m) => Cow::Owned(m),
            Cow::Borrowed(_) => Cow::Borrowed(material),
        }
    }
}

/// A footprint `width` wide at a surface seen along `-wo`, as changes of
/// `(u, v)` along its two axes: the long one in the plane of the view and the
/// normal `ng`, stretched by `1 / cos` (to at most 100x), and the one across it
/// (ray cones' elliptical footprint). Each world step `a` in the tangent plane
/// becomes the least-squares `(du, dv)` of `a = du dp/du + dv dp/dv` (`dpdu`, `dpdv`).
fn footprint_in_uv(dpdu: Vec3, dpdv: Vec3, ng: Vec3, wo: Vec3, width: f64) -> ([f64; 2], [f64; 2]) {
    let cos = ng.dot(wo).abs().max(0.01);
    let along = (wo - ng * ng.dot(wo)).try_normalize().unwrap_or_else(|| crate::math::orthonormal_basis(ng).0);
    let across = ng.cross(along);
    let (a, b) = (dpdu, dpdv);
    let (aa, ab, bb) = (a.dot(a), a.dot(b), b.dot(b));
    let det = aa * bb - ab * ab;
    if !(det > 0.0 && det.is_finite()) {
        return ([0.0; 2], [0.0; 2]);
    }
    let solve = |v: Vec3| {
        let (av, bv) = (a.dot(v), b.dot(v));
        [(bb * av - ab * bv) / det, (aa * bv - ab * av) / det]
    };
    (solve(along * (width / cos)), solve(across * width))
}
