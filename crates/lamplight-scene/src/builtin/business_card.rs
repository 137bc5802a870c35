//! `business-card`: placeholder (replaced in this session).
use lamplight_core::{Error, Scene};

/// Builds the scene.
pub fn build(aspect: f64) -> Result<Scene, Error> {
    super::spheres::build(aspect)
}
