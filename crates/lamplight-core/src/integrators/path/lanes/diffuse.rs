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
use crate::ray::offset_origin;
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
pub(in crate::integrators::path) struct Diffuse {
    slots: Vec<Slot>,
    light: Light,
    /// Per object of the scene, its slot in the lanes.
    slot_of: Vec<u32>,
}

impl Diffuse {
    /// The tables, where `scene` and `tracer` are of this kind; else `None`.
    pub(in crate::integrators::path) fn of(tracer: &PathTracer, scene: &Scene) -> Option<Diffuse> {
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

/// Four vectors, coordinate by coordinate: lane `k` is `(x[k], y[k], z[k])`.
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct L3 {
    pub(super) x: [f64; 4],
    pub(super) y: [f64; 4],
    pub(super) z: [f64; 4],
}

impl L3 {
    /// Lane `k`.
    #[inline(always)]
    pub(super) fn get(&self, k: usize) -> Vec3 {
        Vec3::new(self.x[k], self.y[k], self.z[k])
    }

    /// Sets lane `k`.
    #[inline(always)]
    pub(super) fn set(&mut self, k: usize, v: Vec3) {
        (self.x[k], self.y[k], self.z[k]) = (v.x, v.y, v.z);
    }
}

/// Four paths' state, lane by lane.
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct Paths {
    pub(super) origin: L3,
    pub(super) dir: L3,
    pub(super) beta: L3,
    pub(super) radiance: L3,
    pub(super) prev_pdf: [f64; 4],
    pub(super) prev_delta: [bool; 4],
    pub(super) depth: [u32; 4],
}

/// The light samples waiting for their shadow rays: per lane whether the
/// lane reached its light sample (its `beta * value` is added), whether the
/// sample gave a ray, the ray, its length, the throughput and the value
/// where the ray is clear.
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct Shadows {
    pub(super) nee: [bool; 4],
    pub(super) ray: [bool; 4],
    pub(super) origin: L3,
    pub(super) dir: L3,
    pub(super) distance: [f64; 4],
    pub(super) beta: L3,
    pub(super) value: L3,
}

/// One lane's hit as the lanes report it: its parameter, its object's slot
/// and the outward normal there.
pub(super) type LaneHit = (f64, u32, Vec3);

/// The four lanes' hits, field by field (a `[LaneHit; 4]` made afresh each
/// round was filled by copies that straddled its own stores).
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct Hits {
    pub(super) t: [f64; 4],
    pub(super) slot: [u32; 4],
    pub(super) normal: L3,
}

impl Diffuse {
    /// One vertex of each path of `live` (the lanes hit, `hits` their hits),
    /// with the sample values drawn for it, stage by stage over the four
    /// lanes (each stage a loop LLVM may turn into vector code; every lane
    /// computes what the general code computes, in its order). Fills
    /// `shadows`; returns the lanes whose paths go on.
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    pub(super) fn vertex(
        &self,
        tracer: &PathTracer,
        paths: &mut Paths,
        live: [bool; 4],
        hits: &Hits,
        u_light: &[(f64, f64); 4],
        u_bsdf: &[(f64, f64); 4],
        u_rr: &[f64; 4],
        shadows: &mut Shadows,
        counts: &mut crate::integrators::RayCounts,
    ) -> [bool; 4] {
        let light = &self.light;
        let mut shade = [false; 4];
        let mut gn = L3::default();
        let mut point = L3::default();
        let mut albedo = L3::default();
        let mut t = [0.0; 4];
        // The hit record, the emission, and which paths end here.
        for k in 0..4 {
            let (tk, slot, n) = (hits.t[k], hits.slot[k], hits.normal.get(k));
            let s = &self.slots[slot as usize];
            let dir = paths.dir.get(k);
            let faces_ray = dir.dot(n) < 0.0;
            let g = if faces_ray { n } else { -n };
            let front = faces_ray != s.reversed;
            let p = paths.origin.get(k) + dir * tk;
            if live[k] && s.emission != Rgb::ZERO && (front || s.two_sided) {
                let w = if s.light && !paths.prev_delta[k] {
                    // `AreaLight::pdf` of this direction, distance and normal.
                    let cos_y = dir.dot(g).abs();
                    let pdf = if cos_y <= 0.0 { 0.0 } else { tk * tk / (cos_y * light.area) };
                    power_heuristic(paths.prev_pdf[k], 1.0 * pdf)
                } else {
                    1.0
                };
                paths.radiance.set(k, paths.radiance.get(k) + paths.beta.get(k) * s.emission * w);
            }
            let a = s.albedo[usize::from(front)];
            shade[k] = live[k] && paths.depth[k] < tracer.max_depth && a.is_some();
            albedo.set(k, a.unwrap_or(Rgb::ZERO));
            gn.set(k, g);
            point.set(k, p);
            t[k] = tk;
        }
        // The frame, the direction towards the viewer, the BSDF's sample.
        let mut ft = L3::default();
        let mut fb = L3::default();
        let mut wo = L3::default();
        let mut wi_local = L3::default();
        let mut bsdf_pdf = [0.0; 4];
        for k in 0..4 {
            let g = gn.get(k);
            let (a, b) = orthonormal_basis(g);
            let v = -paths.dir.get(k);
            let o = Vec3::new(v.dot(a), v.dot(b), v.dot(g));
            let wi = lambertian::sample(u_bsdf[k]);
            ft.set(k, a);
            fb.set(k, b);
            wo.set(k, o);
            wi_local.set(k, wi);
            bsdf_pdf[k] = lambertian::pdf(o, wi);
        }
        // The light's sample (`AreaLight::sample` of the rectangle, then
        // `PathTracer::sample_light`); `ok` where it gives a shadow ray.
        let mut ok = [false; 4];
        for k in 0..4 {
            let (p, g, o, a) = (point.get(k), gn.get(k), wo.get(k), albedo.get(k));
            let u = u_light[k];
            let y = light.corner + light.edge_u * u.0 + light.edge_v * u.1;
            let to = y - p;
            let d2 = to.length_squared();
            let distance = d2.sqrt();
            let wi = to * (1.0 / distance);
            let facing = if light.reversed { wi.dot(light.normal) } else { -wi.dot(light.normal) };
            let cos_y = if light.two_sided { facing.abs() } else { facing };
            let pdf = d2 / (cos_y * light.area);
            let local = Vec3::new(wi.dot(ft.get(k)), wi.dot(fb.get(k)), wi.dot(g));
            let f = lambertian::f(a, o, local);
            let origin = offset_origin(p, g, wi, t[k], 0.0);
            let remaining = distance - (origin - p).length();
            let cos = local.z.abs();
            let pl = 1.0 * pdf;
            let w = power_heuristic(pl, lambertian::pdf(o, local));
            ok[k] = shade[k]
                && d2 > 0.0
                && !(cos_y <= 0.0)
                && pdf.is_finite()
                && light.radiance != Rgb::ZERO
                && (wi.dot(g) > 0.0) == (local.z > 0.0)
                && f != Rgb::ZERO;
            shadows.value.set(k, f * light.radiance * (cos * w / pl));
            shadows.origin.set(k, origin);
            shadows.dir.set(k, wi);
            shadows.distance[k] = remaining;
        }
        shadows.nee = shade;
        shadows.ray = ok;
        shadows.beta = paths.beta;
        counts.shadow += ok.iter().filter(|&&b| b).count() as u64;
        // The next segment, and Russian roulette.
        let mut next = [false; 4];
        for k in 0..4 {
            let (g, wl) = (gn.get(k), wi_local.get(k));
            let wi = ft.get(k) * wl.x + fb.get(k) * wl.y + g * wl.z;
            let origin = offset_origin(point.get(k), g, wi, t[k], 0.0);
            let a = albedo.get(k);
            let mut on = shade[k] && bsdf_pdf[k] > 0.0 && (wi.dot(g) > 0.0) == (wl.z > 0.0) && a != Rgb::ZERO;
            let mut beta = paths.beta.get(k) * a;
            if paths.depth[k] >= tracer.rr_depth {
                let survive = beta.max_element().min(1.0);
                on = on && u_rr[k] < survive;
                beta *= 1.0 / survive;
            }
            if on {
                paths.beta.set(k, beta);
                paths.prev_pdf[k] = bsdf_pdf[k];
                paths.prev_delta[k] = false;
                paths.origin.set(k, origin);
                paths.dir.set(k, wi);
                paths.depth[k] += 1;
            }
            next[k] = on;
        }
        counts.secondary += next.iter().filter(|&&b| b).count() as u64;
        next
    }

    /// Whether these tables can be those of `scene`: a tracer renders the
    /// scene it was built for, and one given another scene of another size
    /// runs the general lanes rather than index these tables.
    pub(super) fn fits(&self, scene: &Scene) -> bool {
        scene.object_lanes().is_some_and(|l| l.len() == self.slots.len()) && self.slot_of.len() == scene.objects.len()
    }

    /// The hit of the walk (where two objects tie) as a lane's: its
    /// parameter, its object's slot and the outward normal that the lane's
    /// hit record turns into the walk's.
    pub(super) fn walked(&self, hit: &crate::scene::Hit) -> LaneHit {
        let s = self.slot_of[hit.object];
        let faces_ray = hit.front_face != self.slots[s as usize].reversed;
        (hit.t, s, if faces_ray { hit.geometric_normal } else { -hit.geometric_normal })
    }

    /// The light's object, which its shadow rays may end on.
    pub(super) fn light_object(&self) -> u32 {
        self.light.object
    }
}
