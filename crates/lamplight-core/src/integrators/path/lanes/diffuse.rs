//! The lanes' shading for the Cornell box's kind of scene: Lambertian
//! surfaces of constant colour, one emitting rectangle as the only light, no
//! sky, every surface opaque, sides by the geometric normal.
//!
//! Here the paths' state is kept lane by lane (structure of arrays) and each
//! vertex is worked out from the lanes' hits with the operations of the
//! general code, in its order, written out for this case: the hit record
//! ([`Scene::first_intersect`]'s), the emission and its MIS weight, the
//! frame ([`crate::bsdfs::Frame::new`]), the Lambertian sample
//! ([`crate::bsdfs::lambertian`]), the rectangle light's sample
//! ([`crate::lights::AreaLight`]), the offsets
//! ([`crate::ray::offset_origin`]) and Russian roulette. No `Bsdf`, `Hit`
//! or material is built. The row test (`tests.rs`) compares the sums with
//! the one-sample loop bit for bit.

use super::super::{power_heuristic, PathTracer};
use crate::accel::LaneShape;
use crate::bsdfs::lambertian;
use crate::math::{orthonormal_basis, Rgb, Vec3};
use crate::ray::{offset_origin, Ray};
use crate::scene::{Scene, Sides};

/// What a vertex needs of one object of the lanes (by its slot).
#[derive(Clone, Debug)]
struct Slot {
    object: u32,
    reversed: bool,
    emission: Rgb,
    two_sided: bool,
    /// The Lambertian albedo seen from the back (`[0]`) and the front (`[1]`);
    /// `None` where the surface scatters nothing from that side.
    albedo: [Option<Rgb>; 2],
    /// The object is the light's.
    light: bool,
}

/// The one light: an emitting rectangle.
#[derive(Clone, Debug)]
struct Light {
    corner: Vec3,
    edge_u: Vec3,
    edge_v: Vec3,
    normal: Vec3,
    area: f64,
    reversed: bool,
    two_sided: bool,
    radiance: Rgb,
    object: u32,
}

/// The tables of a scene of this kind (module doc).
#[derive(Clone, Debug)]
pub(super) struct Diffuse {
    slots: Vec<Slot>,
    light: Light,
    /// Per object of the scene, its slot in the lanes.
    slot_of: Vec<u32>,
}

impl Diffuse {
    /// The tables, where `scene` and `tracer` are of this kind; else `None`.
    pub(super) fn of(tracer: &PathTracer, scene: &Scene) -> Option<Diffuse> {
        let lanes = scene.object_lanes()?;
        let lights = &tracer.lights;
        if !tracer.all_opaque || scene.settings.sides != Sides::Geometric || !lights.delta.is_empty() || lights.environment.is_some() {
            return None;
        }
        let [area] = lights.area.as_slice() else { return None };
        if area.texture.is_some() || !area.convex {
            return None;
        }
        let LaneShape::Rectangle(rect) = area.shape.lane()? else { return None };
        let light = Light {
            corner: rect.corner,
            edge_u: rect.edge_u,
            edge_v: rect.edge_v,
            normal: rect.normal,
            area: area.area(),
            reversed: area.reversed,
            two_sided: area.two_sided,
            radiance: area.radiance,
            object: u32::try_from(area.object).ok()?,
        };
        let mut slots = Vec::with_capacity(lanes.len());
        for slot in 0..lanes.len() as u32 {
            let object = scene.lane_object(slot);
            let o = &scene.objects[object];
            let material = &scene.materials[o.material];
            let albedo = [false, true].map(|front| {
                let bsdf = scene.prebuilt_bsdf(o.material, front)?;
                if bsdf.is_black() {
                    Some(None)
                } else {
                    bsdf.single_diffuse().map(Some)
                }
            });
            let [Some(back), Some(front)] = albedo else { return None };
            let emits = material.emission != Rgb::ZERO;
            // An emitter other than the light would be a second light.
            if emits != (object == area.object) || lights.is_bulb(object) {
                return None;
            }
            slots.push(Slot {
                object: object as u32,
                reversed: o.reversed,
                emission: material.emission,
                two_sided: material.two_sided,
                albedo: [back, front],
                light: emits,
            });
        }
        let mut slot_of = vec![u32::MAX; scene.objects.len()];
        for (k, s) in slots.iter().enumerate() {
            slot_of[s.object as usize] = k as u32;
        }
        Some(Diffuse { slots, light, slot_of })
    }
}

/// Four paths' state, lane by lane.
#[derive(Clone, Copy, Debug)]
pub(super) struct Paths {
    pub(super) origin: [Vec3; 4],
    pub(super) dir: [Vec3; 4],
    pub(super) beta: [Rgb; 4],
    pub(super) radiance: [Rgb; 4],
    pub(super) prev_pdf: [f64; 4],
    pub(super) prev_delta: [bool; 4],
    pub(super) depth: [u32; 4],
}

/// A light sample waiting for its shadow ray: the ray, its length, the
/// light's object, the throughput and the value where the ray is clear.
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct Shadows {
    /// The lane reached its light sample: its `beta * value` is added.
    pub(super) nee: [bool; 4],
    pub(super) rays: [Option<Ray>; 4],
    pub(super) distance: [f64; 4],
    pub(super) beta: [Rgb; 4],
    pub(super) value: [Rgb; 4],
}

impl Diffuse {
    /// One vertex of lane `l` of `paths` at its hit (`t`, `slot`, `face`; a
    /// tie's hit from the walk comes as its object's slot and face 0 with its
    /// normal in `tie_normal`), with the sample values drawn for it. Fills
    /// `shadows` for the lane; returns whether the path ends here.
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    pub(super) fn vertex(
        &self,
        tracer: &PathTracer,
        paths: &mut Paths,
        l: usize,
        hit: Option<(f64, u32, Vec3)>,
        (u_light, u_bsdf, u_rr): ((f64, f64), (f64, f64), f64),
        shadows: &mut Shadows,
        counts: &mut crate::integrators::RayCounts,
    ) -> bool {
        let (origin, dir) = (paths.origin[l], paths.dir[l]);
        let depth = paths.depth[l];
        let Some((t, slot, n)) = hit else { return true };
        let s = &self.slots[slot as usize];
        // `Scene::hit_record`: the normal turned against the ray.
        let faces_ray = dir.dot(n) < 0.0;
        let gn = if faces_ray { n } else { -n };
        let front = faces_ray != s.reversed;
        let point = origin + dir * t;
        if s.emission != Rgb::ZERO && (front || s.two_sided) {
            let w = if s.light && !paths.prev_delta[l] {
                // `AreaLight::pdf` of this direction, distance and normal.
                let cos_y = dir.dot(gn).abs();
                let pdf = if cos_y <= 0.0 { 0.0 } else { t * t / (cos_y * self.light.area) };
                power_heuristic(paths.prev_pdf[l], 1.0 * pdf)
            } else {
                1.0
            };
            paths.radiance[l] += paths.beta[l] * s.emission * w;
        }
        if depth >= tracer.max_depth {
            return true;
        }
        let Some(albedo) = s.albedo[usize::from(front)] else { return true };
        let (ft, fb) = orthonormal_basis(gn);
        let to_local = |v: Vec3| Vec3::new(v.dot(ft), v.dot(fb), v.dot(gn));
        let wo = to_local(-dir);
        // The BSDF's sample (`Bsdf::sample` of a single Lambertian lobe).
        let wi_local = lambertian::sample(u_bsdf);
        let bsdf_pdf = lambertian::pdf(wo, wi_local);
        let beta = paths.beta[l];
        shadows.nee[l] = true;
        shadows.rays[l] = None;
        shadows.beta[l] = beta;
        shadows.value[l] = Rgb::ZERO;
        self.light_sample(point, gn, t, wo, albedo, u_light, &to_local, l, shadows, counts);
        if !(bsdf_pdf > 0.0) {
            return true;
        }
        let wi = ft * wi_local.x + fb * wi_local.y + gn * wi_local.z;
        let next = offset_origin(point, gn, wi, t, 0.0);
        if (wi.dot(gn) > 0.0) != (wi_local.z > 0.0) || albedo == Rgb::ZERO {
            return true;
        }
        paths.beta[l] *= albedo;
        paths.prev_pdf[l] = bsdf_pdf;
        paths.prev_delta[l] = false;
        if depth >= tracer.rr_depth {
            let survive = paths.beta[l].max_element().min(1.0);
            if !(u_rr < survive) {
                return true;
            }
            paths.beta[l] *= 1.0 / survive;
        }
        counts.secondary += 1;
        paths.origin[l] = next;
        paths.dir[l] = wi;
        paths.depth[l] += 1;
        false
    }

    /// The light sample of `PathTracer::sample_light` for this light and a
    /// Lambertian surface: its shadow ray and value into `shadows` (lane `l`),
    /// or nothing where it gives nothing.
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    fn light_sample(
        &self,
        point: Vec3,
        gn: Vec3,
        t: f64,
        wo: Vec3,
        albedo: Rgb,
        u: (f64, f64),
        to_local: &impl Fn(Vec3) -> Vec3,
        l: usize,
        shadows: &mut Shadows,
        counts: &mut crate::integrators::RayCounts,
    ) {
        let light = &self.light;
        // `AreaLight::sample` of the rectangle (`Rectangle::sample_area`).
        let y = light.corner + light.edge_u * u.0 + light.edge_v * u.1;
        let to = y - point;
        let d2 = to.length_squared();
        if !(d2 > 0.0) {
            return;
        }
        let distance = d2.sqrt();
        let wi = to * (1.0 / distance);
        let facing = if light.reversed { wi.dot(light.normal) } else { -wi.dot(light.normal) };
        let cos_y = if light.two_sided { facing.abs() } else { facing };
        if cos_y <= 0.0 {
            return;
        }
        let pdf = d2 / (cos_y * light.area);
        if !pdf.is_finite() || light.radiance == Rgb::ZERO {
            return;
        }
        let wi_local = to_local(wi);
        if (wi.dot(gn) > 0.0) != (wi_local.z > 0.0) {
            return;
        }
        let f = lambertian::f(albedo, wo, wi_local);
        if f == Rgb::ZERO {
            return;
        }
        counts.shadow += 1;
        let origin = offset_origin(point, gn, wi, t, 0.0);
        let remaining = distance - (origin - point).length();
        let cos = wi_local.z.abs();
        let pl = 1.0 * pdf;
        let w = power_heuristic(pl, lambertian::pdf(wo, wi_local));
        shadows.value[l] = f * light.radiance * (cos * w / pl);
        shadows.rays[l] = Some(Ray::unit(origin, wi));
        shadows.distance[l] = remaining;
    }

    /// The hit of the walk (where two objects tie) as a lane's: its
    /// parameter, its object's slot and the outward normal that the lane's
    /// hit record turns into the walk's.
    pub(super) fn walked(&self, hit: &crate::scene::Hit) -> (f64, u32, Vec3) {
        let s = self.slot_of[hit.object];
        let faces_ray = hit.front_face != self.slots[s as usize].reversed;
        (hit.t, s, if faces_ray { hit.geometric_normal } else { -hit.geometric_normal })
    }

    /// The light's object, which its shadow rays may end on.
    pub(super) fn light_object(&self) -> u32 {
        self.light.object
    }
}
