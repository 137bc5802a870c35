//! Scenes built into the program, by name: `lamplight render luxo`.
//!
//! Each scene is one file with a `build()` function that builds the core scene
//! (for any image size: the camera applies the aspect when rendering); the
//! registry below lists them.
//! To add one: a new file and one line in [`BUILTINS`].

use lamplight_core::{Error, Scene};

use crate::image_io::Transfer;

mod business_card;
mod cornell_box;
mod luxo;
mod spheres;

/// A scene that ships with the program.
#[derive(Debug)]
pub struct Builtin {
    /// Name on the command line.
    pub name: &'static str,
    /// One line for `--help` and listings.
    pub summary: &'static str,
    /// Image size used when none is given.
    pub default_size: (u32, u32),
    /// The integrator used when none is given (the example file's `integrator`).
    pub integrator: &'static str,
    /// How PNG and PPM outputs store the values (the example file's `transfer`).
    pub transfer: Transfer,
    /// Samples per pixel when none is given (the example file's `spp`); `None`
    /// leaves it to the request layer (adaptive anti-aliasing under Whitted).
    pub spp: Option<u32>,
    /// Builds the scene.
    pub build: fn() -> Result<Scene, Error>,
}

/// Every built-in scene; the first is the default.
pub const BUILTINS: &[Builtin] = &[
    Builtin {
        name: "luxo",
        summary: "the lecture's Homework 2: a paraboloid desk lamp with a light in its focus over a table",
        default_size: (1280, 720),
        integrator: "whitted",
        transfer: Transfer::Srgb,
        spp: None,
        build: luxo::build,
    },
    Builtin {
        name: "business-card",
        summary: "Paul Heckbert's business-card ray tracer: five spheres, constant weights",
        default_size: (32, 32),
        integrator: "whitted",
        // The card prints display values: its PNG holds them as they are.
        transfer: Transfer::Linear,
        spp: Some(1),
        build: business_card::build,
    },
    Builtin {
        name: "cornell-box",
        summary: "the Cornell box with an area light in the ceiling (Mitsuba 3's cornell_box(), path traced)",
        default_size: (512, 512),
        integrator: "path",
        transfer: Transfer::Srgb,
        spp: Some(128),
        build: cornell_box::build,
    },
    Builtin {
        name: "spheres",
        summary: "100 spheres of three materials on a checkered floor (POV-Ray comparison scene)",
        default_size: (1280, 720),
        integrator: "whitted",
        transfer: Transfer::Srgb,
        spp: None,
        build: spheres::build,
    },
];

/// The built-in scene called `name`.
pub fn find(name: &str) -> Option<&'static Builtin> {
    BUILTINS.iter().find(|b| b.name == name)
}

/// The names of all built-in scenes, comma separated (for error messages).
pub fn names() -> String {
    BUILTINS.iter().map(|b| b.name).collect::<Vec<_>>().join(", ")
}

/// The message for `name`, which is no built-in scene:
/// `unknown scene "sphere" (did you mean 'spheres'? built-in scenes: ...)`.
pub fn unknown(name: &str) -> String {
    let names: Vec<&str> = BUILTINS.iter().map(|b| b.name).collect();
    lamplight_core::params::unknown_among("scene", name, &names, "built-in scenes")
}
