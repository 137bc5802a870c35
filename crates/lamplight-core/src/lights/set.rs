//! Every light the path tracer samples: the lecture's point and directional lights
//! (delta lights), emitting objects (area lights) and the environment.
//!
//! One light is picked uniformly per light sample, with probability `1 / count`.
//!
//! An emitting object that is a delta light's own body (its `own_object`, a
//! bulb around a point light) is not an area light: its light is the delta
//! light's, and counting both would count it twice. It is still seen.
//!
//! The sky is the scene's environment map, or else its background colour as a
//! uniform environment light: every ray that leaves the scene sees it, camera
//! rays and reflections alike (what the Whitted integrator's rays see), and it
//! lights every surface. The ambient term `ka C La` lights nothing here: it is
//! the lecture's stand-in for indirect light, which the path tracer computes.

use std::sync::Arc;

use super::{AreaLight, Environment, LiSample, Light};
use crate::math::{Rgb, Vec3};

/// The lights of a scene in one list.
#[derive(Debug)]
pub struct LightSet {
    /// Point and directional lights.
    pub delta: Vec<Arc<dyn Light>>,
    /// Emitting objects.
    pub area: Vec<AreaLight>,
    /// The sky, if any.
    pub environment: Option<Arc<Environment>>,
    by_object: Vec<Option<u32>>,
    bulb: Vec<bool>,
}

impl LightSet {
    /// The set of the delta lights `delta`, the emitting objects' lights
    /// `area` (each names its object, of `objects` in the scene) and the sky:
    /// `environment`, or else a non-black `background` as a uniform one. An
    /// area light whose object is a delta light's own body is dropped (see the
    /// module doc). [`crate::Scene::light_set`] collects a scene's.
    pub fn new(
        delta: Vec<Arc<dyn Light>>,
        area: Vec<AreaLight>,
        environment: Option<Arc<Environment>>,
        background: Rgb,
        objects: usize,
    ) -> LightSet {
        let mut bulb = vec![false; objects];
        for own in delta.iter().filter_map(|l| l.own_object()) {
            if let Some(b) = bulb.get_mut(own) {
                *b = true;
            }
        }
        let area: Vec<AreaLight> = area.into_iter().filter(|l| !bulb.get(l.object).copied().unwrap_or(false)).collect();
        let mut by_object = vec![None; objects];
        for (i, light) in area.iter().enumerate() {
            if let Some(slot) = by_object.get_mut(light.object) {
                *slot = Some(i as u32);
            }
        }
        let environment = environment.or_else(|| (background.max_element() > 0.0).then(|| Arc::new(Environment::Constant(background))));
        LightSet { delta, area, environment, by_object, bulb }
    }

    /// Number of lights.
    pub fn count(&self) -> usize {
        self.delta.len() + self.area.len() + usize::from(self.environment.is_some())
    }

    /// Probability of picking any one light.
    pub fn pick_probability(&self) -> f64 {
        1.0 / self.count().max(1) as f64
    }

    /// The light picked by uniform `u`: delta lights first, then area lights,
    /// then the sky, each with probability [`LightSet::pick_probability`].
    pub fn pick(&self, u: f64) -> Option<&dyn Light> {
        let n = self.count();
        if n == 0 {
            return None;
        }
        let mut i = ((u * n as f64) as usize).min(n - 1);
        if i < self.delta.len() {
            return Some(self.delta[i].as_ref());
        }
        i -= self.delta.len();
        if i < self.area.len() {
            return Some(&self.area[i]);
        }
        self.environment.as_deref().map(|e| e as &dyn Light)
    }

    /// [`LightSet::pick`] and the picked light's [`Light::sample_li`] at `point`
    /// from `u`. An area light (the usual light of a path-traced scene) is
    /// sampled by a direct call that the path tracer's loop compiles in, not
    /// through `dyn Light`: the same operations, the same values. It repeats
    /// `pick`'s arithmetic: one pick returning an enum of the kinds for both
    /// cost the Cornell box 0.7 % (BENCHMARKS.md, session 28).
    #[inline(always)]
    pub fn pick_and_sample(&self, u_pick: f64, point: Vec3, u: (f64, f64)) -> Option<(&dyn Light, Option<LiSample>)> {
        let n = self.count();
        if n == 0 {
            return None;
        }
        let i = ((u_pick * n as f64) as usize).min(n - 1);
        match i.checked_sub(self.delta.len()) {
            Some(a) if a < self.area.len() => {
                let light = &self.area[a];
                Some((light as &dyn Light, light.sample_li_direct(point, u)))
            }
            _ => self.pick(u_pick).map(|light| (light, light.sample_li(point, u))),
        }
    }

    /// Whether object `object` is a delta light's own body, whose light the
    /// delta light gives (see the module doc).
    pub fn is_bulb(&self, object: usize) -> bool {
        self.bulb.get(object).copied().unwrap_or(false)
    }

    /// The area light of object `object`, if it emits.
    pub fn area_light_of(&self, object: usize) -> Option<&AreaLight> {
        self.by_object.get(object).copied().flatten().map(|i| &self.area[i as usize])
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::camera::{Fov, Perspective};
    use crate::lights::{PointLight, SpotLight, SpotProfile};
    use crate::materials::Material;
    use crate::math::Vec3;
    use crate::shapes::Rectangle;
    use crate::SceneBuilder;

    /// Delta, area and environment lights are sampled through the one `Light`
    /// interface, each with the density its own `pdf` gives.
    #[test]
    fn every_kind_of_light_is_sampled_through_one_interface() {
        let camera = Perspective::look_at(Vec3::new(0.0, 0.0, 5.0), Vec3::ZERO, Vec3::Y, Fov::VerticalDeg(40.0)).unwrap();
        let mut b = SceneBuilder::new(camera);
        let lamp = b.material(Material { emission: Rgb::splat(4.0), ..Material::default() }).unwrap();
        // A downward-facing square lamp of area 1 at height 2.
        let square = Rectangle::new(Vec3::new(-0.5, 2.0, -0.5), Vec3::new(1.0, 0.0, 0.0), Vec3::new(0.0, 0.0, 1.0)).unwrap();
        let lamp_object = b.object(square, lamp).unwrap();
        b.light(PointLight::new(Vec3::new(0.0, 3.0, 0.0), Rgb::splat(9.0)).unwrap());
        b.light(SpotLight::new(Vec3::new(0.0, 3.0, 0.0), -Vec3::Y, Rgb::splat(9.0), 10.0, 20.0, SpotProfile::Smoothstep).unwrap());
        b.settings.environment = Some(Arc::new(Environment::Constant(Rgb::splat(0.5))));
        let set = b.build().unwrap().light_set();
        assert_eq!(set.count(), 4);
        let x = Vec3::ZERO;
        let picks: Vec<_> = [0.1, 0.3, 0.6, 0.9].iter().map(|&u| set.pick(u).unwrap().sample_li(x, (0.5, 0.5)).unwrap()).collect();
        // The point and spot lights: delta samples straight up, pi 9 / 3^2.
        for s in &picks[..2] {
            assert_eq!((s.wi, s.distance, s.radiance, s.pdf), (Vec3::Y, 3.0, Rgb::splat(std::f64::consts::PI), None));
        }
        // The area light: its centre from (0.5, 0.5), at distance 2 straight up: pdf d^2 / (cos A) = 4.
        let area = picks[2];
        assert_eq!((area.own_object, area.ends_on_own, area.radiance), (Some(lamp_object), true, Rgb::splat(4.0)));
        assert!((area.wi - Vec3::Y).length() < 1e-12 && (area.pdf.unwrap() - 4.0).abs() < 1e-12);
        let light = set.area_light_of(lamp_object).unwrap();
        assert_eq!(light.pdf(area.wi, area.distance, -Vec3::Y), area.pdf.unwrap());
        // The sky: uniform over the sphere, infinitely far.
        let sky = picks[3];
        assert_eq!((sky.distance, sky.radiance, sky.pdf), (f64::INFINITY, Rgb::splat(0.5), Some(1.0 / (4.0 * std::f64::consts::PI))));
        // The path tracer's pick_and_sample picks the same light and draws the
        // same sample, bit for bit, for every kind (the area light by a direct call).
        let mut rng = crate::sampling::Rng::for_sample(3, 0, 0);
        for _ in 0..400 {
            let (u_pick, u) = (rng.uniform(), (rng.uniform(), rng.uniform()));
            let point = Vec3::new(rng.uniform() * 4.0 - 2.0, rng.uniform() * 3.0 - 1.0, rng.uniform() * 4.0 - 2.0);
            let (light, sample) = set.pick_and_sample(u_pick, point, u).unwrap();
            let picked = set.pick(u_pick).unwrap();
            assert!(std::ptr::addr_eq(light, picked), "u_pick {u_pick}");
            assert_eq!(sample, picked.sample_li(point, u), "u_pick {u_pick}, point {point}");
        }
    }
}
