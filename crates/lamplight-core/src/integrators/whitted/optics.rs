//! The mirror and refracted directions of the Whitted tracer's smooth
//! surfaces, and the weights its materials give them (constant, or Fresnel's
//! for dielectrics and conductors).

use crate::integrators::trace::{ReflectionWeight, WhittedTrace};
use crate::materials::{fresnel_conductor, fresnel_dielectric, Material, Reflection, Refraction};
use crate::math::{Rgb, Vec3};
use crate::ray::Ray;
use crate::scene::Hit;

/// Mirror direction of unit `d` about unit `n`: `d - 2 (d.n) n`.
#[inline]
pub fn reflect(d: Vec3, n: Vec3) -> Vec3 {
    d - n * (2.0 * d.dot(n))
}

/// Refracted direction of unit `d` through a surface with unit normal `n` facing
/// the ray, `eta = n_i / n_t` (Heckbert's form): with `c = -d.n` and
/// `k = 1 - eta^2 (1 - c^2)`, `T = eta d + (eta c - sqrt(k)) n`; `None` when `k < 0`
/// (total internal reflection). Snell's law `n_i sin(i) = n_t sin(t)` holds for `T`.
#[inline]
pub fn refract(d: Vec3, n: Vec3, eta: f64) -> Option<Vec3> {
    let c = -d.dot(n);
    let k = 1.0 - eta * eta * (1.0 - c * c);
    if k < 0.0 {
        return None;
    }
    Some((d * eta + n * (eta * c - k.sqrt())).normalize())
}

/// The reflected and refracted directions with their weights (at most two),
/// announced to `trace` in that order.
#[inline(always)]
pub(super) fn smooth_directions<T: WhittedTrace + ?Sized>(
    ray: &Ray,
    hit: &Hit,
    material: &Material,
    trace: &mut T,
) -> impl Iterator<Item = (Vec3, Rgb)> {
    let n = hit.normal;
    let cos_i = (-ray.dir.dot(n)).clamp(0.0, 1.0);
    // Relative index n_t / n_i for a boundary of index `ior`, entered from outside
    // when the ray is on the front face.
    let relative = |ior: f64| if hit.front_face { ior } else { 1.0 / ior };
    // Whether the weight is nonzero is decided from the value it is made of:
    // comparing the splatted `Rgb` read it back with a load across two of the
    // splat's stores, a store-forwarding stall on every mirror hit (issue 24).
    let (reflection, how, reflects) = match &material.reflection {
        Reflection::None => (Rgb::ZERO, ReflectionWeight::Constant, false),
        Reflection::Constant(w) => (*w, ReflectionWeight::Constant, *w != Rgb::ZERO),
        Reflection::Dielectric { ior, min, max } => {
            let fresnel = fresnel_dielectric(cos_i, relative(*ior));
            let w = min + (max - min) * fresnel;
            (Rgb::splat(w), ReflectionWeight::Dielectric { fresnel }, w != 0.0)
        }
        Reflection::Conductor { eta, k } => {
            let w = fresnel_conductor(cos_i, *eta, *k);
            (w, ReflectionWeight::Conductor, w != Rgb::ZERO)
        }
    };
    if reflects {
        trace.reflection(how, reflection);
    }
    let refraction = match &material.refraction {
        Refraction::None => None,
        Refraction::Fresnel { ior } => {
            let eta = relative(*ior);
            match refract(ray.dir, n, 1.0 / eta) {
                Some(t) => {
                    let fresnel = fresnel_dielectric(cos_i, eta);
                    trace.refraction(Some(fresnel), Some(Rgb::splat(1.0 - fresnel)));
                    // Tested as the scalar, as the reflection's weight above.
                    (1.0 - fresnel != 0.0).then_some((t, Rgb::splat(1.0 - fresnel)))
                }
                None => {
                    trace.refraction(None, None);
                    None
                }
            }
        }
        Refraction::Constant { ior, weight } => {
            let refracted = refract(ray.dir, n, 1.0 / relative(*ior)).map(|t| (t, *weight));
            trace.refraction(None, refracted.map(|(_, w)| w));
            refracted.filter(|(_, w)| *w != Rgb::ZERO)
        }
    };
    let reflected = reflects.then(|| (reflect(ray.dir, n), reflection));
    reflected.into_iter().chain(refraction)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn snells_law_holds() {
        let n = Vec3::Y;
        for deg in [0.0f64, 10.0, 30.0, 60.0, 85.0] {
            let th = deg.to_radians();
            let d = Vec3::new(th.sin(), -th.cos(), 0.0);
            let t = refract(d, n, 1.0 / 1.5).unwrap();
            let sin_t = t.x;
            assert!((th.sin() - 1.5 * sin_t).abs() < 1e-12, "{deg} deg");
            assert!((t.length() - 1.0).abs() < 1e-12 && t.y < 0.0);
        }
    }

    #[test]
    fn total_internal_reflection_past_the_critical_angle() {
        let critical = (1.0f64 / 1.5).asin();
        let n = Vec3::Y;
        let dir = |th: f64| Vec3::new(th.sin(), -th.cos(), 0.0);
        assert!(refract(dir(critical + 1e-6), n, 1.5).is_none());
        let grazing = refract(dir(critical - 1e-6), n, 1.5).unwrap();
        assert!(grazing.y.abs() < 0.01, "refracted ray leaves almost along the surface");
    }

    #[test]
    fn reflection_keeps_the_angle() {
        let d = Vec3::new(1.0, -1.0, 0.0).normalize();
        assert!((reflect(d, Vec3::Y) - Vec3::new(1.0, 1.0, 0.0).normalize()).length() < 1e-15);
    }
}
