//! Abstract light sources of the lecture: each lights a point from one direction.
//!
//! The ambient light `La` is not a [`Light`]: it is a property of the scene
//! ([`crate::scene::Scene::ambient`]) that every surface reflects through `ka`.
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
mod set;
pub mod spot;

pub use area::AreaLight;
pub use directional::DirectionalLight;
pub use environment::{EnvMap, Environment};
pub use mesh::TriangleSampler;
pub use point::{Falloff, PointLight};
pub use set::{LightSet, Picked};
pub use spot::{SpotLight, SpotProfile};

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

/// A light source that illuminates points from one direction each.
pub trait Light: Send + Sync + std::fmt::Debug {
    /// The light arriving at `point`, or `None` if it sends none there.
    fn illuminate(&self, point: Vec3) -> Option<LightSample>;

    /// Index of a scene object that belongs to the light itself (a bulb around a
    /// point light) and must not shadow it.
    fn own_object(&self) -> Option<usize> {
        None
    }
}

/// What a light kind's builder may use besides its parameters.
pub struct LightContext<'a> {
    /// World from the light's own frame (the transforms of the nodes above it).
    pub world: Mat4,
    /// The index of the one scene object called `name`, or a message saying why not.
    pub object: &'a dyn Fn(&str) -> Result<usize, String>,
}

/// Builds a light kind's light from its parameters.
pub type LightBuild = fn(&mut Params<'_>, &LightContext<'_>) -> ParamResult<Arc<dyn Light>>;
/// A light kind of the scene format.
pub type LightKind = Kind<LightBuild>;
