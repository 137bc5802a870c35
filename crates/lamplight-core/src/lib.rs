//! # lamplight-core
//!
//! Everything that renders, and no file formats: geometry ([`shapes`]), the BVH
//! ([`accel`]), materials, lights, the camera, integrators, sampling and the film,
//! with [`render()`] as the one entry point.
//!
//! Data flows one way: a [`scene::SceneBuilder`] collects shapes, materials and
//! lights and builds an immutable [`Scene`] (with its BVH and a camera that fits
//! any image size); [`render()`] runs an integrator over every pixel sample in one
//! tiled loop and returns the accumulated [`film::Film`], whose mean is the linear
//! [`film::Image`] that [`render_image()`] returns.
//!
//! ```
//! use lamplight_core::prelude::*;
//!
//! let camera = Perspective::look_at(Vec3::new(0.0, 0.0, 5.0), Vec3::ZERO, Vec3::Y, Fov::VerticalDeg(30.0)).unwrap();
//! let mut builder = SceneBuilder::new(camera);
//! let red = builder.material(Material::plastic(Rgb::new(1.0, 0.1, 0.1), 0.1, 0.8, 0.3, 40.0)).unwrap();
//! builder.object(Sphere::new(Vec3::ZERO, 1.0).unwrap(), red).unwrap();
//! builder.light(PointLight::new(Vec3::new(5.0, 5.0, 5.0), Rgb::splat(75.0)).unwrap());
//! builder.settings.ambient = Rgb::splat(1.0);
//! let scene = builder.build().unwrap();
//! let options = RenderOptions { width: 32, height: 32, ..RenderOptions::default() };
//! let (image, stats) = render_image(&scene, &options, &RenderControl::default()).unwrap();
//! let centre = image.get(16, 16);
//! assert!(centre[0] > centre[1], "the sphere is red");
//! assert_eq!(stats.rays.camera, 32 * 32);
//! ```
#![deny(missing_docs)]

pub mod accel;
#[cfg(test)]
mod architecture_tests;
pub mod batch;
pub mod bsdfs;
pub mod camera;
pub mod cpu;
mod error;
pub mod explain;
pub mod film;
pub mod integrators;
pub mod lights;
pub mod materials;
pub mod math;
mod pages;
pub mod params;
pub mod ray;
mod render;
pub mod sampling;
pub mod scene;
pub mod shapes;

pub use error::Error;
pub use film::PixelWindow;
pub use render::adaptive;
pub use render::{
    render, render_features, render_image, Adaptive, Antialias, Features, NoiseThreshold, RenderControl, RenderOptions, RenderStats,
    MAX_PIXELS,
};
pub use scene::{Scene, SceneBuilder};

/// The types most programs need.
pub mod prelude {
    pub use crate::camera::{Camera, Fov, Orthographic, Perspective, ThinLens};
    pub use crate::lights::{DirectionalLight, Falloff, PointLight};
    pub use crate::materials::{Material, Metal, Reflection, Refraction, Texture};
    pub use crate::math::{Mat4, Rgb, Vec3};
    pub use crate::shapes::*;
    pub use crate::{render, render_image, RenderControl, RenderOptions, RenderStats, Scene, SceneBuilder};
}
