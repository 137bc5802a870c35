//! Texture images from files and from bytes (glTF's embedded images): PNG,
//! JPEG, BMP, TGA and HDR through the `image` crate, EXR through `exr`.
//!
//! Every file is opened through [`crate::input::read_regular`] with the image
//! size cap, and its stated dimensions are checked
//! (`image_io::check_image_size`) before any pixel is allocated.
//! 8- and 16-bit images keep their depth (decoded through the colour space's
//! table at lookup, `lamplight_core::materials::image_data`); float images
//! (HDR, 32-bit) are linear floats.
//!
//! [`ImageFiles`] is the scene's [`ImageLoader`]: paths are relative to the
//! scene file's folder, and a file is decoded once per colour space, keyed by
//! its canonical path, however many textures name it.

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex};

use lamplight_core::materials::image::Texels;
use lamplight_core::materials::{ImageData, ImageLoader};

use crate::image_io::{check_image_size, MAX_IMAGE_FILE_BYTES};

/// Extensions a texture file may have, for messages.
pub const TEXTURE_EXTENSIONS: &str = ".png, .jpg, .jpeg, .bmp, .tga, .hdr, .exr";

/// Loads texture files relative to a folder, each once per colour space.
#[derive(Debug)]
pub struct ImageFiles {
    dir: PathBuf,
    cache: Mutex<HashMap<(PathBuf, bool), Arc<ImageData>>>,
}

impl ImageFiles {
    /// A loader for files named relative to `dir`.
    pub fn new(dir: &Path) -> ImageFiles {
        ImageFiles { dir: dir.to_path_buf(), cache: Mutex::new(HashMap::new()) }
    }

    /// Number of distinct images decoded so far.
    pub fn decoded(&self) -> usize {
        self.cache.lock().map_or(0, |c| c.len())
    }
}

impl ImageLoader for ImageFiles {
    fn load(&self, file: &str, srgb: bool) -> Result<Arc<ImageData>, String> {
        if file.is_empty() {
            return Err(format!("the path is empty, expected an image file ({TEXTURE_EXTENSIONS})"));
        }
        let path = self.dir.join(file);
        let key = (std::fs::canonicalize(&path).unwrap_or_else(|_| path.clone()), srgb);
        if let Some(image) = self.cache.lock().ok().and_then(|c| c.get(&key).cloned()) {
            return Ok(image);
        }
        let image = Arc::new(read_texture(&path, srgb)?);
        if let Ok(mut cache) = self.cache.lock() {
            cache.insert(key, image.clone());
        }
        Ok(image)
    }
}

/// Reads and decodes the texture file `path`; the message names it.
pub fn read_texture(path: &Path, srgb: bool) -> Result<ImageData, String> {
    let bytes = crate::input::read_regular(path, MAX_IMAGE_FILE_BYTES)
        .map_err(|r| format!("cannot read texture '{}': {}", path.display(), crate::image_io::refusal(&r)))?;
    decode_texture(path, &bytes, srgb)
}

/// A decoder's RGBA buffer as texels: the same allocation when its length and
/// capacity allow (an RGBA file's buffer), else a copy.
fn rgba_texels<T: bytemuck::Pod>(raw: Vec<T>) -> Vec<[T; 4]>
where
    [T; 4]: bytemuck::Pod,
{
    bytemuck::allocation::try_cast_vec(raw).unwrap_or_else(|(_, raw)| raw.chunks_exact(4).map(|c| [c[0], c[1], c[2], c[3]]).collect())
}

/// Decodes the bytes of an image named `name` (its extension decides EXR;
/// other formats are recognised by their content).
pub fn decode_texture(name: &Path, bytes: &[u8], srgb: bool) -> Result<ImageData, String> {
    let fail = |reason: String| format!("cannot use texture '{}': {reason}", name.display());
    let is_exr = name.extension().is_some_and(|e| e.eq_ignore_ascii_case("exr")) || bytes.starts_with(&[0x76, 0x2f, 0x31, 0x01]);
    if is_exr {
        // The budget's share from the largest layer's header, before any pixel
        // is read: the float RGBA texels kept (a third more for the smaller MIP
        // levels) and, while decoding, the RGB image they are made from.
        let (width, height) = crate::image_io::exr_size(name, bytes).map_err(|e| e.to_string())?;
        let pixels = u64::from(width) * u64::from(height);
        let (kept, transient) = (pixels * 16 * 4 / 3, pixels * 12);
        crate::memory::reserve(kept + transient, || format!("texture '{}' ({width}x{height} pixels)", name.display()))
            .map_err(|e| e.to_string())?;
        let image = crate::image_io::decode_exr(name, bytes).map_err(|e| e.to_string());
        let data = image.and_then(|image| {
            let texels = image.pixels.iter().map(|p| [p[0], p[1], p[2], 1.0]).collect();
            ImageData::new(image.width as usize, image.height as usize, Texels::F32(texels), false).map_err(|e| fail(e.to_string()))
        });
        crate::memory::release(transient);
        return data;
    }
    let reader = || image::ImageReader::new(std::io::Cursor::new(bytes)).with_guessed_format();
    let probe = reader().map_err(|e| fail(e.to_string()))?;
    if probe.format().is_none() {
        return Err(fail(format!("not an image file lamplight reads ({TEXTURE_EXTENSIONS})")));
    }
    use image::ImageDecoder;
    let decoder = probe.into_decoder().map_err(|e| fail(format!("not a valid image: {e}")))?;
    let (width, height) = decoder.dimensions();
    check_image_size(width.into(), height.into(), bytes.len() as u64).map_err(fail)?;
    // The memory budget's share, from the header, before any pixel is decoded
    // (lamplight_core::materials::image_data keeps 8- and 16-bit texels as
    // integers, float ones as f32, RGBA): the texels kept, a third more for the
    // smaller MIP levels, and while decoding, what the decoder's buffer and the
    // conversion to RGBA hold beyond them (nothing for an RGBA file, whose
    // buffer becomes the texels).
    let pixels = u64::from(width) * u64::from(height);
    let color = decoder.color_type();
    let depth = u64::from(color.bytes_per_pixel() / color.channel_count().max(1)).clamp(1, 4);
    let stored = pixels * 4 * depth;
    let converted = if color.has_alpha() && color.channel_count() == 4 { 0 } else { stored };
    let kept = stored * 4 / 3;
    let transient = (decoder.total_bytes() + converted).saturating_sub(stored);
    crate::memory::reserve(kept + transient, || format!("texture '{}' ({width}x{height} pixels)", name.display()))
        .map_err(|e| e.to_string())?;
    let decoded = image::DynamicImage::from_decoder(decoder).map_err(|e| fail(format!("not a valid image: {e}")));
    let data = decoded.map(|decoded| {
        let (w, h) = (decoded.width() as usize, decoded.height() as usize);
        match decoded.color().bytes_per_pixel() / decoded.color().channel_count().max(1) {
            1 => (false, ImageData::new(w, h, Texels::U8(rgba_texels(decoded.into_rgba8().into_raw())), srgb)),
            2 => (false, ImageData::new(w, h, Texels::U16(rgba_texels(decoded.into_rgba16().into_raw())), srgb)),
            // Float files are linear whatever the texture's colour space.
            _ => (true, ImageData::new(w, h, Texels::F32(rgba_texels(decoded.into_rgba32f().into_raw())), false)),
        }
    });
    crate::memory::release(transient);
    let (float, data) = data?;
    let data = data.map_err(|e| fail(e.to_string()))?;
    if float {
        let (w, h) = data.size();
        for y in 0..h {
            for x in 0..w {
                let t = data.texel(0, x, y);
                if t.iter().any(|c| !c.is_finite()) {
                    return Err(fail(format!("texel ({x}, {y}) is not finite: {t:?}")));
                }
            }
        }
    }
    Ok(data)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn png(dir: &Path, name: &str, w: u32, h: u32, pixel: impl Fn(u32, u32) -> [u8; 4]) -> PathBuf {
        let path = dir.join(name);
        image::RgbaImage::from_fn(w, h, |x, y| image::Rgba(pixel(x, y))).save(&path).unwrap();
        path
    }

    #[test]
    fn a_file_named_twice_is_decoded_once_per_colour_space() {
        let dir = tempfile::tempdir().unwrap();
        png(dir.path(), "a.png", 2, 1, |x, _| [x as u8 * 255, 0, 0, 255]);
        std::fs::create_dir(dir.path().join("sub")).unwrap();
        let files = ImageFiles::new(dir.path());
        let a = files.load("a.png", true).unwrap();
        let b = files.load("sub/../a.png", true).unwrap();
        assert!(Arc::ptr_eq(&a, &b), "the same canonical path shares one image");
        let linear = files.load("a.png", false).unwrap();
        assert!(!Arc::ptr_eq(&a, &linear));
        assert_eq!(files.decoded(), 2);
        assert_eq!(a.texel(0, 1, 0), [1.0, 0.0, 0.0, 1.0]);
    }

    /// The CRC-32 of PNG chunks (ISO 3309, polynomial 0xedb88320).
    fn crc32(bytes: &[u8]) -> u32 {
        let mut c = !0u32;
        for &b in bytes {
            c ^= u32::from(b);
            for _ in 0..8 {
                c = if c & 1 != 0 { 0xedb8_8320 ^ (c >> 1) } else { c >> 1 };
            }
        }
        !c
    }

    #[test]
    fn bad_files_name_themselves_and_what_is_wrong() {
        let dir = tempfile::tempdir().unwrap();
        let files = ImageFiles::new(dir.path());
        let missing = files.load("none.png", true).unwrap_err();
        assert!(missing.contains("none.png") && missing.contains("no such file"), "{missing}");
        std::fs::write(dir.path().join("text.png"), b"not an image at all").unwrap();
        let text = files.load("text.png", true).unwrap_err();
        assert!(text.contains("text.png") && text.contains("not an image file"), "{text}");
        // A PNG header that claims 60000 x 60000 pixels in a few bytes is refused before decoding.
        let mut chunk = b"IHDR".to_vec();
        chunk.extend(60000u32.to_be_bytes());
        chunk.extend(60000u32.to_be_bytes());
        chunk.extend([8, 6, 0, 0, 0]);
        let mut huge = b"\x89PNG\r\n\x1a\n\x00\x00\x00\x0d".to_vec();
        huge.extend(&chunk);
        huge.extend(crc32(&chunk).to_be_bytes());
        for name in [b"IDAT", b"IEND"] {
            huge.extend([0, 0, 0, 0]);
            huge.extend(name);
            huge.extend(crc32(name).to_be_bytes());
        }
        std::fs::write(dir.path().join("huge.png"), &huge).unwrap();
        let e = files.load("huge.png", true).unwrap_err();
        assert!(e.contains("huge.png") && e.contains("60000x60000"), "{e}");
        assert!(files.load("", true).unwrap_err().contains("empty"));
        assert!(files.load(".", true).unwrap_err().contains("directory"));
    }
}
