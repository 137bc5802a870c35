//! Running a resolved [`Job`] and writing what it rendered: the environment
//! map, the warnings for a scene no light reaches and for lights shut in, the
//! mean image, the extra layers and the denoised image, and the image file
//! with its display transform.

use std::path::Path;

use lamplight_core::film::tonemap::ToneMap;
use lamplight_core::film::Image;
use lamplight_core::{RenderControl, RenderStats, Scene};

use super::{bad, Job, Layer, RequestError};
use crate::image_io::Format;

/// A finished render: the image, the extra layers asked for and the statistics.
#[derive(Clone, Debug)]
pub struct Rendered {
    /// Linear radiance (of the window, when one was asked for).
    pub image: Image,
    /// The layers asked for, in order, as `(layer, image)`; `samples` is one channel repeated.
    pub layers: Vec<(Layer, Image)>,
    /// Figures about the render.
    pub stats: RenderStats,
    /// The time the denoiser took, when the image was denoised.
    pub denoise_time: Option<std::time::Duration>,
}

impl Job {
    /// Lights `scene` with the job's environment map, if any, looked up
    /// bilinearly ([`crate::env_map::load_bilinear_map`]).
    pub fn prepare(&self, scene: &mut Scene) -> Result<(), RequestError> {
        let Some(path) = &self.environment else { return Ok(()) };
        let env = crate::env_map::load_bilinear_map(path).map_err(bad)?;
        scene.settings.environment = Some(std::sync::Arc::new(lamplight_core::lights::Environment::Map(env)));
        Ok(())
    }

    /// The warnings about the lights of `scene` (prepared): one when no light
    /// reaches anything the camera sees, as a probe of camera rays finds
    /// ([`lamplight_core::scene::reaches_camera_hits`]), so that the image
    /// would be black but for what emits towards the camera; then one for each
    /// light that geometry shuts in ([`crate::enclosed`]), naming what blocks it.
    pub fn light_warnings(&self, scene: &Scene) -> Vec<String> {
        let (w, h) = (self.options.width, self.options.height);
        if scene.light_set().count() == 0 && scene.settings.ambient.max_element() <= 0.0 {
            return vec!["the scene has no lights: add a light, an emitting material, a background or an ambient term".to_string()];
        }
        let camera = scene.settings.camera.as_ref();
        let mut warnings = Vec::new();
        if !lamplight_core::scene::reaches_camera_hits(scene, camera, w, h) {
            warnings.push(
                "no light reaches anything the camera sees: emitters send light from their front (outward) side only \
                 (set `two_sided = true` on the material to emit from both), and point, spot and directional lights light \
                 only the side of a surface that faces them"
                    .to_string(),
            );
        }
        warnings.extend(crate::enclosed::enclosed_light_warnings(scene, camera, w, h));
        warnings
    }

    /// Renders `scene` (prepared) with the job's options: the mean image and the
    /// layers asked for, from the film's per-pixel sums (any integrator); the
    /// feature layers from a pass over the same camera rays; and, with a
    /// denoiser, the image denoised (linear radiance, before any display
    /// transform), guided by the features.
    pub fn run(&self, scene: &Scene, control: &RenderControl) -> Result<Rendered, lamplight_core::Error> {
        if self.layers.is_empty() && self.denoiser.is_none() {
            // The image alone: the renderer need not keep every pixel's sums.
            let (image, stats) = lamplight_core::render_image(scene, &self.options, control)?;
            return Ok(Rendered { image, layers: Vec::new(), stats, denoise_time: None });
        }
        let (film, stats) = lamplight_core::render(scene, &self.options, control)?;
        let mut image = film.mean();
        let features = match self.denoiser.is_some() || self.layers.iter().any(|l| l.is_feature()) {
            true => Some(lamplight_core::render_features(scene, &self.options, &film)?),
            false => None,
        };
        let (mut noisy, mut denoise_time) = (None, None);
        if let Some(denoiser) = &self.denoiser {
            let start = std::time::Instant::now();
            let f = features.as_ref().expect("made for the denoiser");
            let clean = denoiser
                .denoise(&image, crate::denoise::Guides::of(f), self.options.threads)
                .map_err(|e| lamplight_core::Error::Render(e.0))?;
            denoise_time = Some(start.elapsed());
            noisy = Some(std::mem::replace(&mut image, clean));
        }
        let layers = self
            .layers
            .iter()
            .map(|&layer| {
                let image = match layer {
                    Layer::Variance => film.variance(),
                    Layer::Samples => {
                        let mut image = Image::new(film.width(), film.height());
                        image.pixels.iter_mut().zip(film.sample_counts()).for_each(|(p, n)| *p = [n; 3]);
                        image
                    }
                    Layer::Albedo => features.as_ref().expect("made for its layer").albedo.clone(),
                    Layer::Normal => features.as_ref().expect("made for its layer").normal.clone(),
                    Layer::Emitted => features.as_ref().expect("made for its layer").emitted.clone(),
                    // Asked only with a denoiser (checked when resolved).
                    Layer::Noisy => noisy.take().unwrap_or_else(|| image.clone()),
                };
                (layer, image)
            })
            .collect();
        Ok(Rendered { image, layers, stats, denoise_time })
    }
}

/// How an image file is written: the display transform of `.png`/`.ppm`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DisplayTransform {
    /// Exposure in stops (the image is scaled by `2^EV`).
    pub exposure: f64,
    /// Tone map.
    pub tonemap: ToneMap,
    /// How PNG and PPM store the values (the scene's, unless `--transfer`).
    pub transfer: crate::image_io::Transfer,
}

/// Writes `rendered` to `path` (the format by extension): EXR keeps linear
/// radiance and the extra layers; display formats get the exposure and tone map
/// and cannot hold layers.
pub fn write(path: &Path, rendered: &Rendered, display: DisplayTransform) -> Result<(), crate::image_io::ImageError> {
    let format = Format::from_path(path)?;
    if format == Format::Exr {
        if rendered.layers.is_empty() {
            return crate::image_io::write_image(path, &rendered.image);
        }
        let layers: Vec<crate::exr_layers::ExtraLayer> = rendered.layers.iter().map(|(layer, image)| layer.to_exr(image)).collect();
        return crate::exr_layers::write_exr_with_layers(path, &rendered.image, &layers);
    }
    if display.exposure == 0.0 && display.tonemap == ToneMap::Clamp {
        // No copy of the image: at 1280x720 one costs a Whitted render some 3 %.
        return crate::image_io::write_image_as(path, &rendered.image, display.transfer);
    }
    let mapped = lamplight_core::film::tonemap::apply(&rendered.image, display.exposure, display.tonemap);
    crate::image_io::write_image_as(path, &mapped, display.transfer)
}
