//! Abstract light sources of the lecture: each lights a point from one direction.
//!
//! The ambient light `La` is not a [`Light`]: it is a property of the scene
//! ([`crate::scene::SceneSettings::ambient`]) that every surface reflects through `ka`.
//! To add a light: a new file here with `impl Light` and its scene kind (a
//! [`LightKind`]: name, parameter table, builder), a `mod` line, and one line in
//! the scene crate's registry.

use std::sync::Arc;

use crate::math::{Mat4, Rgb, Vec3};
use crate::params::{Kind, ParamResult, Params};

pub mod area;
pub mod directional;
pub mod environment;
pub mod mesh;
pub mod point;
pub mod projector;
mod set;
pub mod slide;
pub mod spot;

pub use area::AreaLight;
pub use directional::DirectionalLight;
pub use environment::{EnvMap, Environment};
pub use mesh::TriangleSampler;
pub use point::{Falloff, PointLight};
pub use projector::Projector;
pub use set::LightSet;
pub use slide::Slide;
pub use spot::{SpotLight, SpotProfile};

/// The physical reading of a delta light's lecture intensity: `pi`.
///
/// The lecture's diffuse term `kd C (L.N) Lin` is what a Lambertian surface of
/// albedo `kd C` (BSDF `kd C / pi`) reflects under an irradiance of
/// `pi Lin (L.N)`. So a point or spot light of intensity `I` has the radiant
/// intensity `pi I` (per steradian) and a directional light of intensity `E`
/// gives the irradiance `pi E` across its direction. The path tracer uses these
/// physical values ([`Light::sample_li`]); the Whitted integrator uses `Lin`
/// itself ([`Light::illuminate`]). Direct light on a diffuse surface is then the
/// same number under both: `kd C (L.N) I / d^2`.
pub const DELTA_SCALE: f64 = std::f64::consts::PI;

/// What a light delivers to one point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LightSample {
    /// Unit direction from the point towards the light (`L` in the lecture).
    pub wi: Vec3,
    /// Distance to the light (`f64::INFINITY` for a directional light): shadow
    /// rays ignore occluders beyond it.
    pub distance: f64,
    /// Incident radiance `Lin` before shadowing.
    pub radiance: Rgb,
}

/// One light sample for a receiving point, as the path tracer draws it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LiSample {
    /// Unit direction from the point towards the light.
    pub wi: Vec3,
    /// Distance to the light point (`f64::INFINITY` for lights at infinity).
    pub distance: f64,
    /// Incident radiance before shadowing.
    pub radiance: Rgb,
    /// Solid-angle density of `wi`; `None` for a delta light (one direction only).
    pub pdf: Option<f64>,
    /// A scene object that belongs to the light and must not shadow it.
    pub own_object: Option<usize>,
    /// The sampled point lies where a shadow ray towards it first meets
    /// `own_object` (a convex emitter), so the shadow ray need not search for it.
    pub ends_on_own: bool,
}

/// A light source: the one interface of delta lights (point, directional, spot),
/// area lights (emitting objects) and the environment.
///
/// [`Light::illuminate`] is the lecture's question, asked by the Whitted
/// integrator: the light arriving at a point from the light's one direction
/// (`None` for lights that are not delta lights). [`Light::sample_li`] is the
/// path tracer's: one direction towards the light drawn from `u`, with its
/// density; its default is the delta sample `illuminate` gives. Lights a ray can
/// hit (emitting shapes, the environment) are also found by the path tracer's
/// BSDF samples, which [`LightSet`] weights against these densities.
pub trait Light: Send + Sync + std::fmt::Debug {
    /// The light arriving at `point` from a delta light, or `None`.
    fn illuminate(&self, point: Vec3) -> Option<LightSample>;

    /// This light as a [`PointLight`], asked once when the scene is built: the
    /// Whitted tracer then lights by a direct call, without `dyn Light`
    /// ([`crate::Scene::illuminate`]). `None` (the default) keeps the dyn call.
    fn point_light(&self) -> Option<&PointLight> {
        None
    }

    /// Index of a scene object that belongs to the light itself (a bulb around a
    /// point light) and must not shadow it.
    fn own_object(&self) -> Option<usize> {
        None
    }

    /// The one point all of the light's rays leave from (point and spot lights),
    /// around which the scene builds a light buffer for its shadow rays
    /// ([`crate::accel::LightBuffer`]); `None` for other lights.
    fn point_source(&self) -> Option<Vec3> {
        None
    }

    /// One light sample for receiver `point` from `u` in `[0, 1)^2`, or `None`
    /// when the light sends nothing there.
    ///
    /// The default is a delta light's: [`Light::illuminate`]'s `Lin` times `pi`
    /// ([`DELTA_SCALE`]), the physical reading of the lecture's intensities that
    /// makes both integrators agree.
    fn sample_li(&self, point: Vec3, u: (f64, f64)) -> Option<LiSample> {
        let _ = u;
        self.illuminate(point).map(|s| LiSample {
            wi: s.wi,
            distance: s.distance,
            radiance: s.radiance * DELTA_SCALE,
            pdf: None,
            own_object: self.own_object(),
            ends_on_own: false,
        })
    }
}

/// What a light kind's builder may use besides its parameters.
pub struct LightContext<'a> {
    /// World from the light's own frame (the transforms of the nodes above it).
    pub world: Mat4,
    /// The index of the one scene object called `name`, or a message saying why not.
    pub object: &'a dyn Fn(&str) -> Result<usize, String>,
    /// Reads texturable parameters (a projected image).
    pub textures: crate::materials::Textures<'a>,
}

/// Builds a light kind's light from its parameters.
pub type LightBuild = fn(&mut Params<'_>, &LightContext<'_>) -> ParamResult<Arc<dyn Light>>;
/// A light kind of the scene format.
pub type LightKind = Kind<LightBuild>;
