//! Environment maps from files: OpenEXR (`.exr`, linear float) or Radiance RGBE
//! (`.hdr`), chosen by the extension in any case.
//!
//! An RGBE pixel stores three 8-bit mantissas and one shared exponent `e`: channel
//! `c = m 2^(e - 136)` (Greg Ward's format; the `image` crate decodes it),
//! so each channel keeps about `1/256` of the pixel's brightest channel.

use std::path::Path;

use lamplight_core::film::Image;

use crate::image_io::ImageError;

/// The extensions [`read_environment`] understands, for messages.
pub const ENVIRONMENT_EXTENSIONS: &str = ".exr, .hdr";

/// Reads an equirectangular environment map (`.exr` or `.hdr`) as linear RGB.
pub fn read_environment(path: &Path) -> Result<Image, ImageError> {
    let format = format(path)?;
    let bytes = crate::input::read_regular(path, crate::image_io::MAX_IMAGE_FILE_BYTES)
        .map_err(|r| read_error(path, crate::image_io::refusal(&r)))?;
    decode(path, format, &bytes)
}

/// Bytes per pixel a built map keeps: its `f64` RGB pixels (24) and its
/// sampling distribution's function and CDF (16), with room for the rows'
/// own vectors.
const KEPT_PER_PIXEL: u64 = 48;
/// Bytes per pixel held only while a map is built: the decoded `f32` image
/// (12), the decoder's buffer (12) and the sampling weights (8).
const TRANSIENT_PER_PIXEL: u64 = 32;

/// Reads an environment map file as the renderer's map (linear RGB with its
/// sampling distribution), looked up at the nearest pixel; the message names the file.
pub fn load_map(path: &Path) -> Result<lamplight_core::lights::EnvMap, String> {
    let (map, transient) = read_budgeted(path)?;
    let built = env_map(path, &map);
    crate::memory::release(transient);
    built
}

/// [`read_environment`], having first taken the map's share of the memory
/// budget ([`crate::memory`]) from the size its header declares, before any
/// pixel is decoded. Returns the image and the transient share, which the
/// caller gives back once the map is built.
fn read_budgeted(path: &Path) -> Result<(Image, u64), String> {
    let format = format(path).map_err(|e| e.to_string())?;
    let bytes = crate::input::read_regular(path, crate::image_io::MAX_IMAGE_FILE_BYTES)
        .map_err(|r| read_error(path, crate::image_io::refusal(&r)).to_string())?;
    let (width, height) = match format {
        Format::Exr => crate::image_io::exr_size(path, &bytes).map_err(|e| e.to_string())?,
        Format::Hdr => image::ImageReader::with_format(std::io::Cursor::new(&bytes), image::ImageFormat::Hdr)
            .into_dimensions()
            .map_err(|e| read_error(path, format!("not a valid Radiance .hdr file: {e}")).to_string())?,
    };
    let pixels = u64::from(width) * u64::from(height);
    let transient = pixels.saturating_mul(TRANSIENT_PER_PIXEL);
    crate::memory::reserve(pixels.saturating_mul(KEPT_PER_PIXEL).saturating_add(transient), || {
        format!("environment map '{}' ({width}x{height} pixels)", path.display())
    })
    .map_err(|e| e.to_string())?;
    match decode(path, format, &bytes) {
        Ok(image) => Ok((image, transient)),
        Err(e) => {
            crate::memory::release(transient);
            Err(e.to_string())
        }
    }
}

/// Reads an environment map file as [`load_map`] does, looked up bilinearly
/// between pixel centres as Mitsuba's `envmap` ([`EnvMap::bilinear`]): the
/// lookup of `--environment` and Python's `environment=`, where the nearest
/// pixel showed every pixel of a small map as a block (issue 27). A map of one
/// row, which the bilinear lookup cannot place between zenith and nadir, is
/// read as that row twice: interpolated across, the same up and down.
///
/// [`EnvMap::bilinear`]: lamplight_core::lights::EnvMap::bilinear
pub fn load_bilinear_map(path: &Path) -> Result<lamplight_core::lights::EnvMap, String> {
    let (mut map, transient) = read_budgeted(path)?;
    if map.height == 1 {
        map.pixels.extend_from_within(..);
        map.height = 2;
    }
    let built =
        env_map(path, &map).and_then(|m| m.bilinear().map_err(|e| format!("cannot use '{}' as an environment map: {e}", path.display())));
    crate::memory::release(transient);
    built
}

fn env_map(path: &Path, map: &Image) -> Result<lamplight_core::lights::EnvMap, String> {
    let pixels = map.pixels.iter().map(|p| lamplight_core::math::Rgb::new(p[0] as f64, p[1] as f64, p[2] as f64)).collect();
    lamplight_core::lights::EnvMap::new(map.width as usize, map.height as usize, pixels)
        .map_err(|e| format!("cannot use '{}' as an environment map: {e}", path.display()))
}

/// Decodes the bytes of an environment map file named `path` (whose extension
/// picks the format, and which is only named in errors). The fuzz target and
/// the property tests enter here.
pub fn decode_environment(path: &Path, bytes: &[u8]) -> Result<Image, ImageError> {
    decode(path, format(path)?, bytes)
}

/// Reads a Radiance RGBE (`.hdr`) file as linear RGB.
pub fn read_hdr(path: &Path) -> Result<Image, ImageError> {
    let bytes = crate::input::read_regular(path, crate::image_io::MAX_IMAGE_FILE_BYTES)
        .map_err(|r| read_error(path, crate::image_io::refusal(&r)))?;
    decode(path, Format::Hdr, &bytes)
}

#[derive(Clone, Copy)]
enum Format {
    Exr,
    Hdr,
}

fn read_error(path: &Path, reason: String) -> ImageError {
    ImageError::Read { path: path.to_path_buf(), reason }
}

fn format(path: &Path) -> Result<Format, ImageError> {
    let ext = path.extension().map(|e| e.to_string_lossy().to_ascii_lowercase()).unwrap_or_default();
    match ext.as_str() {
        "exr" => Ok(Format::Exr),
        "hdr" => Ok(Format::Hdr),
        _ => Err(read_error(path, format!("unknown environment map format {ext:?} (supported: {ENVIRONMENT_EXTENSIONS})"))),
    }
}

fn decode(path: &Path, format: Format, bytes: &[u8]) -> Result<Image, ImageError> {
    let image = match format {
        Format::Exr => crate::image_io::decode_exr(path, bytes)?,
        Format::Hdr => decode_hdr(path, bytes)?,
    };
    if let Some(i) = image.pixels.iter().position(|p| p.iter().any(|c| !c.is_finite() || *c < 0.0)) {
        return Err(read_error(path, format!("pixel {i} is not a finite non-negative colour: {:?}", image.pixels[i])));
    }
    // A finite f32 pixel is as bright as a scene's colours may be
    // (`lamplight_core::params::MAX_COLOR`, the largest f32): finiteness is the whole rule.
    Ok(image)
}

fn decode_hdr(path: &Path, bytes: &[u8]) -> Result<Image, ImageError> {
    let invalid = |e: image::ImageError| read_error(path, format!("not a valid Radiance .hdr file: {e}"));
    let reader = image::ImageReader::with_format(std::io::Cursor::new(bytes), image::ImageFormat::Hdr);
    let (width, height) = reader.into_dimensions().map_err(invalid)?;
    crate::image_io::check_image_size(width.into(), height.into(), bytes.len() as u64).map_err(|m| read_error(path, m))?;
    let decoded = image::ImageReader::with_format(std::io::Cursor::new(bytes), image::ImageFormat::Hdr).decode().map_err(invalid)?;
    let rgb = decoded.into_rgb32f();
    let mut image = Image::new(rgb.width(), rgb.height());
    for (p, q) in image.pixels.iter_mut().zip(rgb.pixels()) {
        *p = q.0;
    }
    Ok(image)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::image_io::write_image;

    fn scratch() -> tempfile::TempDir {
        tempfile::Builder::new().prefix("lamplight-env-map-").tempdir().unwrap()
    }

    #[test]
    fn hdr_and_exr_of_the_same_map_load_equal_within_rgbe_precision() {
        let dir = scratch();
        let (w, h) = (8u32, 4u32);
        let mut image = Image::new(w, h);
        for (i, p) in image.pixels.iter_mut().enumerate() {
            let v = (i as f32 * 0.37).fract();
            *p = [v * 40.0, 0.01 + v * v, 1.0 / (1.0 + i as f32)];
        }
        let exr = dir.path().join("sky.exr");
        write_image(&exr, &image).unwrap();
        let hdr = dir.path().join("sky.HDR");
        let pixels: Vec<image::Rgb<f32>> = image.pixels.iter().map(|p| image::Rgb(*p)).collect();
        let file = std::io::BufWriter::new(std::fs::File::create(&hdr).unwrap());
        image::codecs::hdr::HdrEncoder::new(file).encode(&pixels, w as usize, h as usize).unwrap();

        let a = read_environment(&exr).unwrap();
        let b = read_environment(&hdr).unwrap();
        assert_eq!((a.width, a.height), (w, h));
        assert_eq!((b.width, b.height), (w, h));
        for (i, (p, q)) in a.pixels.iter().zip(&b.pixels).enumerate() {
            // Shared exponent: each channel within 1/128 of the pixel's largest channel.
            let max = p.iter().fold(0.0f32, |m, c| m.max(*c));
            for c in 0..3 {
                assert!((p[c] - q[c]).abs() <= max / 128.0, "pixel {i} channel {c}: exr {} vs hdr {}", p[c], q[c]);
            }
        }
    }

    #[test]
    fn malformed_or_unknown_maps_name_the_file() {
        let dir = scratch();
        let bad = dir.path().join("broken.hdr");
        std::fs::write(&bad, b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 4 +X nonsense").unwrap();
        let message = read_environment(&bad).unwrap_err().to_string();
        assert!(message.contains("broken.hdr") && message.contains("not a valid Radiance .hdr file"), "{message}");
        let truncated = dir.path().join("short.hdr");
        std::fs::write(&truncated, b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 4 +X 4\n\x02\x02").unwrap();
        let message = read_environment(&truncated).unwrap_err().to_string();
        assert!(message.contains("short.hdr"), "{message}");
        let message = read_environment(&dir.path().join("sky.png")).unwrap_err().to_string();
        assert!(message.contains("sky.png") && message.contains(".exr, .hdr"), "{message}");
        let message = read_environment(&dir.path().join("missing.hdr")).unwrap_err().to_string();
        assert!(message.contains("missing.hdr"), "{message}");
    }
}
