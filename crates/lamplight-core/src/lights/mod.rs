//! Abstract light sources of the lecture: each lights a point from one direction.
//!
//! The ambient light `La` is not a [`Light`]: it is a property of the scene
//! ([`crate::scene::Scene::ambient`]) that every surface reflects through `ka`.
//! To add a light: a new file here with `impl Light`, and a `mod`/`pub use` line.

use crate::math::{Rgb, Vec3};

pub mod area;
mod directional;
pub mod environment;
pub mod mesh;
mod point;
mod set;

pub use area::AreaLight;
pub use directional::DirectionalLight;
pub use environment::{EnvMap, Environment};
pub use mesh::TriangleSampler;
pub use point::{Falloff, PointLight};
pub use set::{LightSet, Picked};

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
