//! The lecture's `DirectLight` for the Whitted tracer: what a hit reflects
//! of each light it sees (ambient, emission and the rough model over the
//! unshadowed delta lights and area-light points), each light's shadow ray
//! asked only when its unshadowed term could show.

use std::cell::Cell;

use super::AREA_SAMPLES;
use crate::integrators::trace::{LightRef, LightTerm, Unlit, WhittedTrace};
use crate::integrators::RayCounts;
use crate::lights::AreaLight;
use crate::materials::Material;
use crate::math::{max_component, Rgb, Vec3};
use crate::ray::{offset_origin, Ray};
use crate::scene::{Hit, OccluderHint, Scene};

/// Lights that keep an [`OccluderHint`] of their own; further lights share them
/// (light `i` uses hint `i % HINTS`, area lights numbered after the delta lights).
const HINTS: usize = 8;

thread_local! {
    /// Per light, the object that last blocked a shadow ray towards it on this
    /// thread, tried first by the next one (`scene/shadow.rs`): neighbouring
    /// pixels mostly share their occluder. Kept per thread because the render
    /// loop hands a sample nothing mutable but its ray counts; no value here
    /// changes an answer, only how soon it is known, so images do not depend
    /// on the thread or the order pixels are traced in.
    static OCCLUDERS: [Cell<OccluderHint>; HINTS] = const { [const { Cell::new(OccluderHint::NONE) }; HINTS] };
}

/// Lights whose `N.L` is at or below this are skipped (POV-Ray's threshold).
const MIN_COSINE: f64 = 1e-10;
/// A light whose unshadowed reflection factor (`kd C (L.N) + ks (H.N)^n`, per unit
/// incident radiance) is below this in every channel is skipped without a shadow
/// ray: 1e-12 is far below what an `f32` film value of a lit pixel can resolve.
const NEGLIGIBLE: f64 = 1e-12;

/// The lecture's `DirectLight`: `Ke + ka*C*La + sum over visible lights of
/// Lin * (kd*C (L.N) + ks (H.N)^shine)`, skipping lights with `L.N <= 1e-10`.
/// `Ke` counts on the side the surface emits from ([`Material::emits_towards`]).
/// The lights are the scene's delta lights and the area lights `area_lights`,
/// whose points are drawn from `uniform` (16 per light, see the module doc).
/// Each term is told to `trace`.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
pub fn direct_light<T: WhittedTrace + ?Sized>(
    scene: &Scene,
    area_lights: &[AreaLight],
    ray: &Ray,
    hit: &Hit,
    material: &Material,
    uniform: &mut dyn FnMut() -> f64,
    counts: &mut RayCounts,
    trace: &mut T,
) -> Rgb {
    // The material as evaluated at the hit (`Scene::material_at`): its colour is
    // a constant or the 3D checker, worked out here from the point; any other
    // colour `Texture::evaluate` (not inlined) returns through memory is read
    // back a coordinate at a time (issue 24: `BENCHMARKS.md`, session 34, has
    // the variants measured).
    let color = match material.color.of_point(hit.point) {
        Some(c) => c,
        None => crate::math::read_forwarded(&material.color.evaluate(&crate::materials::ShadingPoint::at(hit.point))),
    };
    let emission = if material.emits_towards(hit.front_face) { material.emission } else { Rgb::ZERO };
    // The back of a one-sided surface scatters nothing, not even the ambient light.
    let scatters = material.scatters_at(hit.front_face);
    let ambient = if scatters { material.ka * color * scene.settings.ambient } else { Rgb::ZERO };
    trace.surface(color, emission, ambient);
    let mut radiance = emission + ambient;
    if !material.is_lit() || !scatters {
        return radiance;
    }
    for i in 0..scene.lights.len() {
        trace.light(LightRef::Delta(i));
        let (Some(sample), own) = scene.illuminate(i, hit.point) else {
            trace.unlit(Unlit::NotReached);
            continue;
        };
        let incident = Incident { wi: sample.wi, distance: sample.distance, lin: sample.radiance, own, light: i };
        radiance += lit_by(scene, ray, hit, material, color, &incident, counts, trace);
    }
    if !area_lights.is_empty() {
        radiance += area_light(scene, area_lights, ray, hit, material, color, uniform, counts, trace);
    }
    radiance
}

/// Light arriving at a hit from one light (or one point of an area light).
struct Incident {
    /// Unit direction towards the light.
    wi: Vec3,
    /// Distance to the light.
    distance: f64,
    /// Radiance arriving if nothing blocks it.
    lin: Rgb,
    /// The light's own body, which does not block it.
    own: Option<usize>,
    /// The light's number, delta lights first, which picks its [`OccluderHint`].
    light: usize,
}

/// What the rough model reflects towards `-ray.dir` of light `lin` arriving
/// from `wi` over `distance` if nothing blocks it: `Lin (kd C (L.N) + ks
/// (H.N)^shine)` times the shadow ray's transmittance (`own` does not block).
#[allow(clippy::too_many_arguments)]
#[inline(always)]
fn lit_by<T: WhittedTrace + ?Sized>(
    scene: &Scene,
    ray: &Ray,
    hit: &Hit,
    material: &Material,
    color: Rgb,
    incident: &Incident,
    counts: &mut RayCounts,
    trace: &mut T,
) -> Rgb {
    let Incident { wi, distance, lin, own, light } = *incident;
    // A light point that sends nothing (a black texel of a textured emitter)
    // adds `0 * visible * reflected = 0` whatever blocks it: no shadow ray.
    if lin == Rgb::ZERO {
        trace.unlit(Unlit::NotReached);
        return Rgb::ZERO;
    }
    let n = hit.normal;
    let cos_light = n.dot(wi);
    if cos_light <= MIN_COSINE || hit.geometric_normal.dot(wi) <= 0.0 {
        trace.unlit(Unlit::Below(cos_light));
        return Rgb::ZERO;
    }
    // The unshadowed reflection first: a light whose contribution could not
    // show (a highlight of a material without diffuse term, far from its peak)
    // costs no shadow ray.
    let diffuse = material.kd * color * cos_light;
    let cos_half = n.dot((wi - ray.dir).normalize());
    let specular =
        if cos_half > 0.0 && material.ks != Rgb::ZERO { material.ks * blinn_power(cos_half, material.shininess) } else { Rgb::ZERO };
    let reflected = diffuse + specular;
    if max_component(reflected) < NEGLIGIBLE {
        trace.unlit(Unlit::Negligible);
        return Rgb::ZERO;
    }
    counts.shadow += 1;
    let origin = offset_origin(hit.point, hit.geometric_normal, wi, hit.t, hit.error);
    let remaining = distance - (origin - hit.point).length();
    // The query stays outside `with`'s closure, which the compiler may keep out of line.
    let mut hint = OCCLUDERS.with(|hints| hints[light % HINTS].get()).towards(light);
    // Read back one component at a time: the first test of the query's
    // answer below stalled on its stores (issue 24, `read_forwarded`).
    let visible = crate::math::read_forwarded(&scene.transmittance_hinted(&hit.spawn(origin, wi), remaining, own, &mut hint));
    // Only the object is read back (the query writes that alone): loading the
    // whole hint spanned the query's narrower store, a store-forwarding stall
    // on every shadow ray (issue 24).
    OCCLUDERS.with(|hints| hints[light % HINTS].set(hint.towards(light)));
    let mut told = |radiance: Rgb| {
        let shadow = hit.spawn(origin, wi);
        let term = LightTerm {
            wi,
            distance,
            lin,
            cos_light,
            cos_half,
            diffuse,
            specular,
            shadow,
            shadow_length: remaining,
            own,
            visible,
            radiance,
        };
        trace.lit(scene, &term);
    };
    if visible == Rgb::ZERO {
        told(Rgb::ZERO);
        return Rgb::ZERO;
    }
    let radiance = lin * visible * reflected;
    told(radiance);
    radiance
}

/// The rough model under the area lights `lights`: [`AREA_SAMPLES`] points on
/// each, stratified on a 4 x 4 grid of the light's sample square and jittered by
/// `uniform`, each standing for `Lin = Le / (pi pdf N)`; `color` is `C` at the hit.
#[allow(clippy::too_many_arguments)]
fn area_light<T: WhittedTrace + ?Sized>(
    scene: &Scene,
    lights: &[AreaLight],
    ray: &Ray,
    hit: &Hit,
    material: &Material,
    color: Rgb,
    uniform: &mut dyn FnMut() -> f64,
    counts: &mut RayCounts,
    trace: &mut T,
) -> Rgb {
    let mut radiance = Rgb::ZERO;
    let side = (AREA_SAMPLES as f64).sqrt() as u32;
    let scale = 1.0 / (std::f64::consts::PI * AREA_SAMPLES as f64);
    for (j, light) in lights.iter().enumerate() {
        for k in 0..AREA_SAMPLES {
            let (jx, jy) = (uniform(), uniform());
            let u = (((k % side) as f64 + jx) / side as f64, ((k / side) as f64 + jy) / side as f64);
            trace.light(LightRef::Area { object: light.object, sample: k });
            let Some(s) = light.sample(hit.point, u) else {
                trace.unlit(Unlit::NotReached);
                continue;
            };
            let lin = s.radiance * (scale / s.pdf);
            let incident = Incident { wi: s.wi, distance: s.distance, lin, own: Some(light.object), light: scene.lights.len() + j };
            radiance += lit_by(scene, ray, hit, material, color, &incident, counts, trace);
        }
    }
    radiance
}

/// `x^n` for the Blinn lobe; integer exponents (the usual case) by repeated
/// squaring, which is several times faster than `powf`. Written out rather than
/// `powi`, which calls a runtime routine; the multiplications are the same, in
/// the same order, so the value is the same.
#[inline]
fn blinn_power(x: f64, n: f64) -> f64 {
    // `(n as u32) as f64 == n` tests for an integer without the libm call that
    // `fract` is on baseline x86-64.
    if (0.0..=4096.0).contains(&n) && (n as u32) as f64 == n {
        let (mut base, mut exponent, mut result) = (x, n as u32, 1.0);
        loop {
            if exponent & 1 != 0 {
                result *= base;
            }
            exponent >>= 1;
            if exponent == 0 {
                return result;
            }
            base *= base;
        }
    } else {
        x.powf(n)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::integrators::trace::NoTrace;

    /// A light point of zero radiance adds nothing and traces no shadow ray; the
    /// same point with radiance traces one, blocked or not.
    #[test]
    fn a_light_point_that_sends_nothing_costs_no_shadow_ray() {
        use crate::camera::{Fov, Perspective};
        use crate::scene::SceneBuilder;
        use crate::shapes::Sphere;
        let camera = Perspective::look_at(Vec3::new(0.0, 0.0, 10.0), Vec3::ZERO, Vec3::Y, Fov::VerticalDeg(40.0)).unwrap();
        let mut builder = SceneBuilder::new(camera);
        let matte = builder.material(Material::default()).unwrap();
        builder.object(Sphere::new(Vec3::ZERO, 1.0).unwrap(), matte).unwrap();
        builder.object(Sphere::new(Vec3::new(0.0, 0.0, 3.0), 0.5).unwrap(), matte).unwrap();
        let scene = builder.build().unwrap();
        let ray = Ray::new(Vec3::new(0.0, 0.0, 10.0), -Vec3::Z);
        let mut hit = scene.first_intersect(&Ray::new(Vec3::new(0.0, 0.0, 2.0), -Vec3::Z), f64::INFINITY).unwrap();
        let material = &*scene.shade(&mut hit, Vec3::Z, 0.0);
        let towards = |z: f64, lin: Rgb| {
            let to = Vec3::new(0.0, 0.0, z) - hit.point;
            Incident { wi: to.normalize(), distance: to.length(), lin, own: None, light: 0 }
        };
        let lit = |incident: Incident| {
            let mut counts = RayCounts::default();
            let value = lit_by(&scene, &ray, &hit, material, Rgb::ONE, &incident, &mut counts, &mut NoTrace);
            (value, counts.shadow)
        };
        // Towards z = 6 the small ball at z = 3 blocks; towards z = 2 nothing does.
        assert_eq!(lit(towards(6.0, Rgb::ZERO)), (Rgb::ZERO, 0));
        assert_eq!(lit(towards(2.0, Rgb::ZERO)), (Rgb::ZERO, 0));
        assert_eq!(lit(towards(6.0, Rgb::ONE)), (Rgb::ZERO, 1));
        let (value, shadow) = lit(towards(2.0, Rgb::ONE));
        assert!(value.x > 0.0 && shadow == 1, "{value:?}");
    }

    #[test]
    fn blinn_power_equals_powi() {
        for x in [0.0, 0.3, 0.5, 0.99, 1.0] {
            for n in [0u32, 1, 2, 7, 40, 255, 4096] {
                assert_eq!(blinn_power(x, n as f64), x.powi(n as i32), "{x}^{n}");
            }
        }
        assert_eq!(blinn_power(0.5, 2.5), 0.5f64.powf(2.5));
    }
}
