//! The extra layers a render can hold beside its image (`--exr-layers`, Python's
//! `exr_layers`), and how each is written as channels of an `.exr` file.

use lamplight_core::film::Image;

use crate::exr_layers::ExtraLayer;

/// An extra layer of the `.exr` output.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Layer {
    /// Variance of each pixel's mean, per channel (`variance.R/G/B`).
    Variance,
    /// Samples taken per pixel (`samples.Y`).
    Samples,
    /// The denoiser's albedo feature (`albedo.R/G/B`, [`lamplight_core::Features`]).
    Albedo,
    /// The denoiser's normal feature, world space (`normal.X/Y/Z`, Cycles' and Blender's naming).
    Normal,
    /// The image before denoising (`noisy.R/G/B`), with `--denoise`.
    Noisy,
    /// The radiance of emitters and sky seen directly (`emitted.R/G/B`,
    /// [`lamplight_core::Features::emitted`]): the part the denoiser leaves alone.
    Emitted,
}

impl Layer {
    /// The layers' names, as `--exr-layers` and Python take them.
    pub const NAMES: [&'static str; 6] = ["variance", "samples", "albedo", "normal", "noisy", "emitted"];

    /// Every layer, in the order of [`Layer::NAMES`].
    const ALL: [Layer; 6] = [Layer::Variance, Layer::Samples, Layer::Albedo, Layer::Normal, Layer::Noisy, Layer::Emitted];

    /// The layer's name, the prefix of its channel names.
    pub fn name(self) -> &'static str {
        Layer::NAMES[Layer::ALL.iter().position(|l| *l == self).expect("every layer is in ALL")]
    }

    /// The message for a layer name that is none of [`Layer::NAMES`].
    pub fn unknown(name: &str) -> String {
        lamplight_core::params::unknown("layer", name, &Layer::NAMES)
    }

    /// Whether the layer comes from the feature pass ([`lamplight_core::render_features`]).
    pub fn is_feature(self) -> bool {
        matches!(self, Layer::Albedo | Layer::Normal | Layer::Emitted)
    }

    /// The layer's channels in an `.exr` file, from its image (`samples`: one
    /// channel, the image's first, as [`super::Job::run`] repeats it).
    pub fn to_exr(self, image: &Image) -> ExtraLayer {
        match self {
            Layer::Samples => ExtraLayer::single(self.name(), image.pixels.iter().map(|p| p[0]).collect()),
            Layer::Normal => ExtraLayer::xyz(self.name(), image),
            _ => ExtraLayer::rgb(self.name(), image),
        }
    }
}

impl std::str::FromStr for Layer {
    type Err = String;
    fn from_str(s: &str) -> Result<Layer, String> {
        Layer::ALL.into_iter().find(|l| l.name() == s).ok_or_else(|| Layer::unknown(s))
    }
}
