//! OpenEXR output with extra per-pixel layers beside the image: the variance of
//! each pixel's mean, its sample count and the denoiser's feature layers, in the same file.
//!
//! The file is one part whose channels are the image's `R`, `G`, `B` and, per
//! extra layer, `NAME.CHANNEL` (OpenEXR's naming of layers inside a part, as
//! Nuke and Blender write and read them): `variance.R`, `variance.G`,
//! `variance.B`, `samples.Y`, `albedo.R/G/B` and `normal.X/Y/Z`, all 32-bit float, ZIP-compressed. Readers that
//! want only the image (`R`, `G`, `B`) see it as before. The write is atomic like
//! every image write ([`crate::image_io`]).

use std::path::Path;

use exr::prelude::FlatSamples;
use lamplight_core::film::Image;

use crate::exr_zip::Samples;

use crate::image_io::{write_atomically, ImageError};

/// One extra layer: its name and its channels (name, one value per pixel, row-major).
#[derive(Clone, Debug, PartialEq)]
pub struct ExtraLayer {
    /// Layer name, the prefix of its channel names.
    pub name: String,
    /// `(channel name, values)`.
    pub channels: Vec<(String, Vec<f32>)>,
}

impl ExtraLayer {
    /// A three-channel layer `NAME.R`, `NAME.G`, `NAME.B` from an image.
    pub fn rgb(name: &str, image: &Image) -> ExtraLayer {
        let channels = (0..3).map(|c| (["R", "G", "B"][c].to_string(), image.pixels.iter().map(|p| p[c]).collect())).collect();
        ExtraLayer { name: name.to_string(), channels }
    }

    /// A three-channel layer of a vector, `NAME.X`, `NAME.Y`, `NAME.Z` (a normal pass).
    pub fn xyz(name: &str, image: &Image) -> ExtraLayer {
        let channels = (0..3).map(|c| (["X", "Y", "Z"][c].to_string(), image.pixels.iter().map(|p| p[c]).collect())).collect();
        ExtraLayer { name: name.to_string(), channels }
    }

    /// A one-channel layer `NAME.Y`.
    pub fn single(name: &str, values: Vec<f32>) -> ExtraLayer {
        ExtraLayer { name: name.to_string(), channels: vec![("Y".to_string(), values)] }
    }
}

/// Writes `image` and the `extra` layers to the `.exr` file `path`, atomically.
pub fn write_exr_with_layers(path: &Path, image: &Image, extra: &[ExtraLayer]) -> Result<(), ImageError> {
    let encode_error = |reason: String| ImageError::Encode { path: path.to_path_buf(), reason };
    let (width, height) = (image.width as usize, image.height as usize);
    let pixels = width * height;
    if pixels == 0 || image.pixels.len() != pixels {
        return Err(encode_error(format!("{} pixels do not make a {width}x{height} image", image.pixels.len())));
    }
    let mut channels: Vec<(String, Samples)> =
        ["R", "G", "B"].iter().enumerate().map(|(c, name)| (name.to_string(), Samples::Component(&image.pixels, c))).collect();
    for layer in extra {
        for (name, values) in &layer.channels {
            if values.len() != pixels {
                return Err(encode_error(format!("layer {}.{name} has {} values for {pixels} pixels", layer.name, values.len())));
            }
            channels.push((format!("{}.{name}", layer.name), Samples::Plane(values)));
        }
    }
    let bytes = crate::exr_zip::encode(width, height, channels).map_err(encode_error)?;
    write_atomically(path, &bytes)
}

/// Named channels of an image: `(name, values)`, values row-major.
pub type Channels = Vec<(String, Vec<f32>)>;

/// Every channel of the first part of an `.exr` file as 32-bit floats, by name:
/// `(width, height, channels)`.
pub fn read_exr_channels(path: &Path) -> Result<(usize, usize, Channels), ImageError> {
    let read_error = |reason: String| ImageError::Read { path: path.to_path_buf(), reason };
    let image = exr::prelude::read_first_flat_layer_from_file(path).map_err(|e| read_error(e.to_string()))?;
    let size = image.layer_data.size;
    let channels = image
        .layer_data
        .channel_data
        .list
        .iter()
        .map(|c| {
            let values = match &c.sample_data {
                FlatSamples::F16(v) => v.iter().map(|x| x.to_f32()).collect(),
                FlatSamples::F32(v) => v.clone(),
                FlatSamples::U32(v) => v.iter().map(|x| *x as f32).collect(),
            };
            (c.name.to_string(), values)
        })
        .collect();
    Ok((size.width(), size.height(), channels))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::image_io::read_exr;

    #[test]
    fn layers_round_trip_beside_the_image() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("out.exr");
        let mut image = Image::new(3, 2);
        let mut variance = Image::new(3, 2);
        for i in 0..6 {
            image.pixels[i] = [i as f32, 0.5, 1e-3 * i as f32];
            variance.pixels[i] = [1e-6 * i as f32, 2.0, 0.0];
        }
        let layers = [ExtraLayer::rgb("variance", &variance), ExtraLayer::single("samples", vec![64.0; 6])];
        write_exr_with_layers(&path, &image, &layers).unwrap();
        let (w, h, channels) = read_exr_channels(&path).unwrap();
        assert_eq!((w, h), (3, 2));
        let names: Vec<&str> = channels.iter().map(|(n, _)| n.as_str()).collect();
        assert_eq!(names, ["B", "G", "R", "samples.Y", "variance.B", "variance.G", "variance.R"]);
        let get = |n: &str| channels.iter().find(|(name, _)| name == n).unwrap().1.clone();
        assert_eq!(get("variance.R"), variance.pixels.iter().map(|p| p[0]).collect::<Vec<_>>());
        assert_eq!(get("samples.Y"), vec![64.0; 6]);
        // Image-only readers still find the image.
        assert_eq!(read_exr(&path).unwrap().pixels, image.pixels);
        let entries = std::fs::read_dir(dir.path()).unwrap().count();
        assert_eq!(entries, 1, "no temporary file is left");
        let bad = write_exr_with_layers(&path, &image, &[ExtraLayer::single("samples", vec![1.0; 5])]).unwrap_err();
        assert!(bad.to_string().contains("out.exr") && bad.to_string().contains("samples.Y has 5 values"), "{bad}");
    }
}
