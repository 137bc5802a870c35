//! An OpenEXR file as the denoiser's input (`lamplight denoise`): the image and,
//! when the file has them, its albedo and normal layers, found by the names
//! renderers give them.
//!
//! Channels are `LAYER.CHANNEL` (OpenEXR's layers in a part); a layer is
//! recognised by its last component, case-insensitive, so a Blender view
//! layer's prefix does not matter:
//!
//! | what | layer names | channels |
//! |---|---|---|
//! | image | none (`R`, `G`, `B`), `combined`, `image` | `R G B` |
//! | albedo | `albedo` (lamplight, Mitsuba's `aov`), `denoising albedo` (Cycles), `diffcol` | `R G B` |
//! | normal | `normal` (lamplight, Cycles), `denoising normal` (Cycles), `sh_normal`, `nn` (Mitsuba), `n` | `X Y Z` or `R G B` |
//! | emitted | `emitted` (lamplight: emitters and sky seen directly, not filtered but added back) | `R G B` |
//!
//! A single-channel image (`Y`) is read as grey.

use std::path::Path;

use lamplight_core::film::Image;

use super::{DenoiseError, Denoiser, Guides};
use crate::exr_layers::{read_exr_channels, Channels};

const IMAGE_LAYERS: [&str; 3] = ["", "combined", "image"];
const ALBEDO_LAYERS: [&str; 3] = ["albedo", "denoising albedo", "diffcol"];
const NORMAL_LAYERS: [&str; 5] = ["normal", "denoising normal", "sh_normal", "nn", "n"];
const EMITTED_LAYERS: [&str; 1] = ["emitted"];

/// What a file gives the denoiser.
#[derive(Clone, Debug, PartialEq)]
pub struct DenoiseInput {
    /// The noisy image.
    pub image: Image,
    /// Its albedo layer, if the file has one.
    pub albedo: Option<Image>,
    /// Its normal layer, if the file has one.
    pub normal: Option<Image>,
    /// Its emitted layer (lamplight's), if the file has one.
    pub emitted: Option<Image>,
}

/// Reads the image and its feature layers from the `.exr` file `path`.
pub fn read_denoise_input(path: &Path) -> Result<DenoiseInput, DenoiseError> {
    let (width, height, channels) = read_exr_channels(path).map_err(|e| DenoiseError(e.to_string()))?;
    let image = find_layer(&channels, &IMAGE_LAYERS, &[["R", "G", "B"]], (width, height)).ok_or_else(|| {
        let names: Vec<&str> = channels.iter().map(|(n, _)| n.as_str()).collect();
        DenoiseError(format!("{}: no R, G, B channels to denoise (channels: {})", path.display(), names.join(", ")))
    })?;
    let albedo = find_layer(&channels, &ALBEDO_LAYERS, &[["R", "G", "B"]], (width, height));
    let normal = find_layer(&channels, &NORMAL_LAYERS, &[["X", "Y", "Z"], ["R", "G", "B"]], (width, height));
    let emitted = find_layer(&channels, &EMITTED_LAYERS, &[["R", "G", "B"]], (width, height));
    Ok(DenoiseInput { image, albedo, normal, emitted })
}

impl DenoiseInput {
    /// The image denoised, guided by the feature layers it has (clamped to the
    /// ranges the filter takes: a normal pass of unit length is in them, an
    /// unclamped albedo may not be); `threads` as [`Denoiser::denoise`].
    pub fn denoise(&self, denoiser: &Denoiser, threads: usize) -> Result<Image, DenoiseError> {
        let albedo = self.albedo.as_ref().map(|a| clamped(a, 0.0, 1.0));
        let normal = self.normal.as_ref().map(|n| clamped(n, -1.0, 1.0));
        let guides = Guides { albedo: albedo.as_ref(), normal: normal.as_ref(), emitted: self.emitted.as_ref() };
        denoiser.denoise(&self.image, guides, threads)
    }
}

fn clamped(image: &Image, lo: f32, hi: f32) -> Image {
    let pixels = image.pixels.iter().map(|p| p.map(|c| if c.is_finite() { c.clamp(lo, hi) } else { 0.0 })).collect();
    Image { width: image.width, height: image.height, pixels }
}

/// The first layer named one of `layers` (its last component, any case) that
/// has all channels of one of `sets`, as an image.
fn find_layer(channels: &Channels, layers: &[&str], sets: &[[&str; 3]], (width, height): (usize, usize)) -> Option<Image> {
    let split = |name: &str| -> (String, String) {
        match name.rsplit_once('.') {
            Some((layer, channel)) => (layer.rsplit('.').next().unwrap_or("").to_ascii_lowercase(), channel.to_ascii_uppercase()),
            None => (String::new(), name.to_ascii_uppercase()),
        }
    };
    let get = |layer: &str, channel: &str| channels.iter().find(|(name, _)| split(name) == (layer.to_string(), channel.to_string()));
    for layer in layers {
        for set in sets {
            let found: Option<Vec<&Vec<f32>>> = set.iter().map(|c| get(layer, c).map(|(_, v)| v)).collect();
            if let Some([r, g, b]) = found.as_deref() {
                let pixels = (0..width * height).map(|i| [r[i], g[i], b[i]]).collect();
                return Some(Image { width: width as u32, height: height as u32, pixels });
            }
        }
        // A grey image (`Y`) counts as its three channels.
        if let Some((_, y)) = get(layer, "Y").filter(|_| layers == IMAGE_LAYERS) {
            let pixels = y.iter().map(|&v| [v; 3]).collect();
            return Some(Image { width: width as u32, height: height as u32, pixels });
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::exr_layers::{write_exr_with_layers, ExtraLayer};

    fn image(w: u32, h: u32, v: [f32; 3]) -> Image {
        Image { width: w, height: h, pixels: vec![v; (w * h) as usize] }
    }

    #[test]
    fn layers_are_found_by_the_names_renderers_give_them() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("in.exr");
        let normal = ExtraLayer {
            name: "ViewLayer.Denoising Normal".into(),
            channels: ["X", "Y", "Z"].iter().zip([0.0, 0.0, 1.0]).map(|(c, v)| (c.to_string(), vec![v; 6])).collect(),
        };
        let albedo = ExtraLayer::rgb("albedo", &image(3, 2, [0.5, 0.25, 1.0]));
        write_exr_with_layers(&path, &image(3, 2, [2.0, 3.0, 4.0]), &[albedo, normal]).unwrap();
        let read = read_denoise_input(&path).unwrap();
        assert_eq!(read.image, image(3, 2, [2.0, 3.0, 4.0]));
        assert_eq!(read.albedo, Some(image(3, 2, [0.5, 0.25, 1.0])));
        assert_eq!(read.normal, Some(image(3, 2, [0.0, 0.0, 1.0])));
        // Without feature layers: the image alone.
        write_exr_with_layers(&path, &image(3, 2, [1.0; 3]), &[]).unwrap();
        let read = read_denoise_input(&path).unwrap();
        assert_eq!((read.albedo, read.normal), (None, None));
    }
}
