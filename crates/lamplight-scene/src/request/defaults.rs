//! What a scene asks for when a render request does not say
//! ([`Defaults`]), from a scene file's `[render]` table or the program's own.

use lamplight_core::film::Filter;
use lamplight_core::integrators::{self, IntegratorEntry};
use lamplight_core::PixelWindow;

use super::AntialiasRequest;

/// What a scene asks for when the request does not say.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Defaults {
    /// Image size.
    pub size: (u32, u32),
    /// Samples per pixel, when the scene says.
    pub spp: Option<u32>,
    /// Adaptive anti-aliasing, when the scene says.
    pub antialias: Option<AntialiasRequest>,
    /// The path tracer's noise threshold, when the scene gives one.
    pub noise_threshold: Option<f64>,
    /// Samples before a noise threshold stops pixels, when the scene says.
    pub min_spp: Option<u32>,
    /// Seed.
    pub seed: u64,
    /// Integrator.
    pub integrator: &'static IntegratorEntry,
    /// How PNG and PPM outputs store the values.
    pub transfer: crate::image_io::Transfer,
    /// The pixel filter, when the scene says.
    pub filter: Option<Filter>,
    /// The film's crop in pixels of `size`, when the scene has one (`[render] crop`).
    pub crop: Option<PixelWindow>,
    /// Whether the variance layer is made unasked (`[render] variance`, Mitsuba's
    /// `moment`), where the output can hold it ([`super::Job::add_scene_layers`]).
    pub variance: bool,
    /// Whether the image is denoised unasked (`[render] denoise`).
    pub denoise: bool,
    /// The memory budget in bytes, when the scene says (`[render] memory_budget`).
    pub memory_budget: Option<u64>,
}

impl Defaults {
    /// The settings of a scene file's `[render]` table.
    pub fn from_settings(s: &crate::instantiate::Settings) -> Defaults {
        Defaults {
            size: (s.width, s.height),
            spp: s.spp,
            antialias: s.antialias,
            noise_threshold: s.noise_threshold,
            min_spp: s.min_spp,
            seed: s.seed,
            integrator: s.integrator,
            transfer: s.transfer,
            filter: s.filter,
            crop: s.crop,
            variance: s.variance,
            denoise: s.denoise,
            memory_budget: s.memory_budget,
        }
    }
}

/// The program's own settings, for scenes without any.
pub fn program_defaults() -> Defaults {
    Defaults {
        size: (640, 360),
        spp: None,
        antialias: None,
        noise_threshold: None,
        min_spp: None,
        seed: 0,
        integrator: integrators::default_integrator(),
        transfer: Default::default(),
        filter: None,
        crop: None,
        variance: false,
        denoise: false,
        memory_budget: None,
    }
}
