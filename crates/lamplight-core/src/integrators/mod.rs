//! Integrators: how the radiance arriving along a camera ray is computed.
//!
//! To add an integrator: a new file here with `impl Integrator`, a `mod` line, and
//! a variant in [`IntegratorKind`].

use crate::math::Rgb;
use crate::ray::Ray;
use crate::sampling::Rng;
use crate::scene::Scene;

mod path;
mod simple_path;
mod whitted;

pub use path::{power_heuristic, unoccluded, PathTracer};
pub use simple_path::SimplePath;
pub use whitted::Whitted;

/// Counts of rays traced, by kind; summed over threads at the end of a render.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct RayCounts {
    /// Camera rays.
    pub camera: u64,
    /// Reflected and refracted rays.
    pub secondary: u64,
    /// Shadow rays towards lights.
    pub shadow: u64,
}

impl RayCounts {
    /// All rays.
    pub fn total(&self) -> u64 {
        self.camera + self.secondary + self.shadow
    }

    /// Adds another count.
    pub fn add(&mut self, other: &RayCounts) {
        self.camera += other.camera;
        self.secondary += other.secondary;
        self.shadow += other.shadow;
    }
}

/// Computes the radiance arriving at the camera along a ray.
pub trait Integrator: Send + Sync {
    /// Radiance along camera ray `ray`. `rng` is this pixel sample's own generator.
    fn radiance(&self, scene: &Scene, ray: &Ray, rng: &mut Rng, counts: &mut RayCounts) -> Rgb;
}

/// The integrators the program offers by name.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum IntegratorKind {
    /// Recursive (Whitted) ray tracing: the lecture's `trace`.
    #[default]
    Whitted,
    /// Unidirectional path tracing with next-event estimation and MIS.
    Path,
}

impl std::str::FromStr for IntegratorKind {
    type Err = String;

    fn from_str(s: &str) -> Result<IntegratorKind, String> {
        match s {
            "whitted" => Ok(IntegratorKind::Whitted),
            "path" => Ok(IntegratorKind::Path),
            _ => Err(format!("unknown integrator '{s}' (whitted, path)")),
        }
    }
}
