//! What a scene is seen and lit with besides its objects and lights: the
//! camera, the lecture's ambient and background light, the path tracer's sky,
//! and the recursion's limits. One struct, which the builder fills and the
//! built scene keeps, so a new setting is one field with its default here.

use std::sync::Arc;

use crate::camera::Camera;
use crate::lights::Environment;
use crate::math::Rgb;
use crate::Error;

/// A scene's settings ([`crate::Scene::settings`], [`crate::SceneBuilder::settings`]).
#[derive(Clone, Debug)]
pub struct SceneSettings {
    /// Ambient radiance `La`, reflected by every surface through `ka`; black by default.
    pub ambient: Rgb,
    /// Radiance of rays that hit nothing; black by default.
    pub background: Rgb,
    /// Light from everywhere for the path tracer (`None`, the default: the
    /// background becomes a uniform sky, see [`crate::lights::LightSet`]).
    pub environment: Option<Arc<Environment>>,
    /// The camera (shared: a scene seen by another camera shares it).
    pub camera: Arc<dyn Camera>,
    /// Default recursion depth limit (camera ray = depth 1); 5 by default.
    pub max_depth: u32,
    /// Secondary rays whose weight falls to or below this (every channel) are not
    /// traced (POV-Ray's `adc_bailout`; 0, the default, traces every ray up to the depth limit).
    pub min_weight: f64,
    /// Path segments before the path tracer's Russian roulette starts
    /// ([`crate::integrators::PathTracer::rr_depth`], camera ray = 1; 4 by default).
    pub rr_depth: u32,
    /// Camera rays go through emitting surfaces and see black where they leave
    /// to the sky (Mitsuba's `hide_emitters`, [`crate::Scene::first_camera_hit`]);
    /// the light those give the scene is kept. `false` by default.
    pub hide_emitters: bool,
    /// Which normal decides the side of a hit when a shading normal and the
    /// geometry disagree ([`Sides`]); [`Sides::Geometric`] by default.
    pub sides: Sides,
    /// The instants the shutter is open, `(open, close)` in frames from the
    /// rendered frame, for motion blur: each camera sample of a scene with a
    /// moving shape ([`crate::shapes::MovingInstance`]) takes a time uniformly
    /// between them ([`crate::integrators::View::shutter`]). `(0, 0)` by default.
    pub shutter: (f64, f64),
}

/// Which normal decides a hit's side (front or back: whether a one-sided
/// material scatters there) where an interpolated shading normal faces away
/// from the ray that the geometry faces, as near the silhouette of a coarse
/// mesh with vertex normals.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Sides {
    /// The geometry's: the hit keeps its side and is shaded with the geometric
    /// normal there, and the path tracer ends a path whose sampled direction
    /// lies on different sides of the two normals (no light leaks through the
    /// surface). lamplight's own convention.
    #[default]
    Geometric,
    /// The shading normal's (Mitsuba 3's convention, which its BSDFs evaluate in
    /// the shading frame alone): where the shading normal faces away from the
    /// ray the hit is on the back, a one-sided material there is black, a
    /// two-sided one is shaded with the shading normal turned to the ray, and
    /// the path tracer follows directions whatever side of the geometry they
    /// leave on. The Mitsuba XML reader sets it, so that such scenes render as
    /// Mitsuba renders them.
    Shading,
}

impl SceneSettings {
    /// The defaults, seen by `camera`.
    pub fn new(camera: Arc<dyn Camera>) -> SceneSettings {
        SceneSettings {
            ambient: Rgb::ZERO,
            background: Rgb::ZERO,
            environment: None,
            camera,
            max_depth: 5,
            min_weight: 0.0,
            rr_depth: 4,
            hide_emitters: false,
            sides: Sides::Geometric,
            shutter: (0.0, 0.0),
        }
    }

    /// Checks the numbers a scene cannot be built with.
    pub(super) fn validate(&self) -> Result<(), Error> {
        if self.max_depth == 0 {
            return Err(Error::invalid("max_depth", "must be at least 1"));
        }
        for (name, c) in [("ambient", self.ambient), ("background", self.background)] {
            if !(c.is_finite() && c.min_element() >= 0.0) {
                return Err(Error::invalid(name, "must be finite and non-negative"));
            }
        }
        Ok(())
    }
}
