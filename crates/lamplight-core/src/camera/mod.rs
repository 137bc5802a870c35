//! Cameras: how a point of the film becomes a primary ray.
//!
//! A camera is built once with a scene and knows nothing of the image size: the
//! render passes `width x height` with every ray, and the camera applies the
//! aspect `width / height` there, so one built scene renders at any size. A film
//! point `(x, y)` is in pixels from the top-left corner, `x` in `[0, W]`, `y` in
//! `[0, H]`; every camera here maps it to the normalized coordinates
//! `alpha = 2x/W - 1`, `beta = 1 - 2y/H` ([`film_ndc`]) of a window in the scene.
//!
//! To add a camera: a file in this folder with a type that implements [`Camera`]
//! and its scene kind (a [`CameraKind`]: name, parameter table, builder), its
//! `mod` line below, and one line in the scene crate's registry. Integrators take
//! rays only through the trait, so nothing else changes.

use std::fmt;
use std::sync::Arc;

use crate::params::{Kind, ParamResult, Params};
use crate::ray::Ray;
use crate::Error;

pub mod orthographic;
pub mod perspective;
pub mod spherical;
pub mod thin_lens;

/// Builds a camera kind's camera from its parameters.
pub type CameraBuild = fn(&mut Params<'_>) -> ParamResult<Arc<dyn Camera>>;
/// A camera kind of the scene format (`[camera] type = ...`).
pub type CameraKind = Kind<CameraBuild>;

pub use orthographic::Orthographic;
pub use perspective::{Fit, Perspective};
pub use thin_lens::ThinLens;

/// Makes the primary rays of an image.
pub trait Camera: Send + Sync + fmt::Debug {
    /// The ray through film point `(x, y)` of a `width x height` image (see the
    /// module doc), through the aperture point that `lens`, a point of `[0, 1)^2`,
    /// picks. Cameras without an aperture ignore `lens`. `width` and `height` are
    /// at least 1 (the renderer checks).
    fn ray(&self, x: f64, y: f64, width: u32, height: u32, lens: (f64, f64)) -> Ray;

    /// Whether [`Camera::ray`] depends on `lens`. Integrators draw a lens sample
    /// only when it does, so a pinhole render's sample streams, and its bytes, do
    /// not change when cameras with apertures exist.
    fn uses_lens_sample(&self) -> bool {
        false
    }

    /// Where in a pixel its single sample goes (0.5: the centre). With several
    /// samples per pixel the Whitted integrator shifts its strata by `offset - 0.5`.
    fn pixel_offset(&self) -> f64 {
        0.5
    }

    /// This camera for `width x height` images only, with the work that depends
    /// on nothing but the size (the window for the aspect) done once: the render
    /// loop asks once per render and then calls its [`Camera::ray`] with that size
    /// only. The rays are the same; `None` (the default) uses the camera itself.
    fn for_image(&self, _width: u32, _height: u32) -> Option<Box<dyn Camera>> {
        None
    }
}

/// Which angle a field of view measures.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Fov {
    /// Full vertical angle in degrees (POV-Ray's and SCENES.md's `vfov`).
    VerticalDeg(f64),
    /// Full horizontal angle in degrees (POV-Ray's `angle`).
    HorizontalDeg(f64),
    /// Full angle in degrees across the image's shorter side: vertical when
    /// `width >= height`, else horizontal (Mitsuba's `fov_axis = "smaller"`).
    SmallerSideDeg(f64),
}

impl Fov {
    /// The angle in degrees, whichever side it measures.
    pub fn degrees(self) -> f64 {
        match self {
            Fov::VerticalDeg(d) | Fov::HorizontalDeg(d) | Fov::SmallerSideDeg(d) => d,
        }
    }

    /// `(tan(hfov/2), tan(vfov/2))` for an image of aspect `width / height`, from
    /// `tan(fov/2)` of the measured side `tan_half`: the other side's tangent is
    /// `tan_v = tan_h / aspect` or `tan_h = tan_v * aspect`.
    #[inline]
    pub fn half_tangents(self, tan_half: f64, aspect: f64) -> (f64, f64) {
        match self {
            Fov::VerticalDeg(_) => (tan_half * aspect, tan_half),
            Fov::HorizontalDeg(_) => (tan_half, tan_half / aspect),
            Fov::SmallerSideDeg(_) if aspect >= 1.0 => (tan_half * aspect, tan_half),
            Fov::SmallerSideDeg(_) => (tan_half, tan_half / aspect),
        }
    }

    /// `tan(fov/2)`, checking that the angle lies strictly between 0 and 180 degrees.
    pub fn half_tan(self) -> Result<f64, Error> {
        let deg = self.degrees();
        if !(deg > 0.0 && deg < 180.0) {
            return Err(Error::invalid("fov", format!("must be between 0 and 180 degrees, got {deg}")));
        }
        Ok((deg.to_radians() / 2.0).tan())
    }
}

/// The image aspect `width / height`.
#[inline]
pub fn aspect(width: u32, height: u32) -> f64 {
    width as f64 / height as f64
}

/// Film point `(x, y)` of a `width x height` image in normalized window
/// coordinates: `alpha = 2x/W - 1` (left edge -1, right edge 1) and
/// `beta = 1 - 2y/H` (top edge 1, bottom edge -1).
#[inline]
pub fn film_ndc(x: f64, y: f64, width: u32, height: u32) -> (f64, f64) {
    (2.0 * x / width as f64 - 1.0, 1.0 - 2.0 * y / height as f64)
}
