//! Image writers (and readers for checking them): PNG, binary PPM and OpenEXR.
//!
//! The format follows the file's extension, in any case:
//!
//! | extension | contents |
//! |-----------|----------|
//! | `.png`    | 8-bit RGB, sRGB-encoded and clamped ([`Image::to_srgb8`]) |
//! | `.ppm`    | binary PPM (`P6`, maxval 255), the same bytes as the PNG's pixels |
//! | `.exr`    | OpenEXR, linear 32-bit float R, G, B, ZIP-compressed (lossless) |
//!
//! Writes are atomic ([`crate::atomic`]): the file is encoded in memory, written
//! to a temporary file `.<name>.<random>.tmp` beside the target, synced, and
//! renamed over the target. A failed write removes the temporary file and leaves
//! an existing target as it was; a crash can leave at most a stray temporary
//! file, never a truncated image.

use std::fs::File;
use std::io::{self, BufReader};
use std::path::{Path, PathBuf};

use lamplight_core::film::Image;

/// The extensions [`write_image`] understands, for messages.
pub const SUPPORTED_EXTENSIONS: &str = ".png, .ppm, .exr";

/// Why an image could not be written or read. Every message names the file.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum ImageError {
    /// The extension names no supported format.
    #[error("cannot write {}: unknown image format {ext:?} (supported: {SUPPORTED_EXTENSIONS})", path.display())]
    UnknownFormat {
        /// The file.
        path: PathBuf,
        /// Its extension (empty when it has none).
        ext: String,
    },
    /// The file system refused (no such directory, permission denied, disk full...).
    #[error("cannot write {}: {}", path.display(), describe(io))]
    Write {
        /// The file.
        path: PathBuf,
        /// What the system said. Deliberately not a `source()`: the message already
        /// includes it, and error chains would print it twice.
        io: io::Error,
    },
    /// The image could not be encoded (zero size, pixel count not matching the size).
    #[error("cannot write {}: {reason}", path.display())]
    Encode {
        /// The file.
        path: PathBuf,
        /// What was wrong.
        reason: String,
    },
    /// The file could not be read or decoded.
    #[error("cannot read {}: {reason}", path.display())]
    Read {
        /// The file.
        path: PathBuf,
        /// What was wrong.
        reason: String,
    },
}

/// An image file format.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    /// PNG, 8-bit sRGB.
    Png,
    /// Binary PPM (`P6`), 8-bit sRGB.
    Ppm,
    /// OpenEXR, linear float32.
    Exr,
}

impl Format {
    /// The format named by `path`'s extension (case-insensitive).
    pub fn from_path(path: &Path) -> Result<Format, ImageError> {
        let ext = path.extension().map(|e| e.to_string_lossy().to_ascii_lowercase()).unwrap_or_default();
        match ext.as_str() {
            "png" => Ok(Format::Png),
            "ppm" => Ok(Format::Ppm),
            "exr" => Ok(Format::Exr),
            _ => Err(ImageError::UnknownFormat { path: path.to_path_buf(), ext }),
        }
    }
}

/// Writes `image` to `path` in the format of its extension, atomically (see the
/// module docs).
pub fn write_image(path: &Path, image: &Image) -> Result<(), ImageError> {
    write_image_as(path, image, Transfer::Srgb)
}

/// How an 8-bit format (PNG, PPM) stores linear values; EXR keeps the floats.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Transfer {
    /// sRGB-encoded ([`Image::to_srgb8`]): for scene-referred (physical) radiance.
    #[default]
    Srgb,
    /// The numbers themselves, `round(255 x)` ([`Image::to_linear8`]): for
    /// display-referred scenes, as POV-Ray's `File_Gamma 1` (Heckbert's card).
    Linear,
}

impl std::str::FromStr for Transfer {
    type Err = String;
    fn from_str(s: &str) -> Result<Transfer, String> {
        match s {
            "srgb" => Ok(Transfer::Srgb),
            "linear" => Ok(Transfer::Linear),
            _ => Err(lamplight_core::params::unknown("transfer", s, &["srgb", "linear"])),
        }
    }
}

/// [`write_image`] with the 8-bit formats' `transfer`.
pub fn write_image_as(path: &Path, image: &Image, transfer: Transfer) -> Result<(), ImageError> {
    let format = Format::from_path(path)?;
    let bytes = encode(format, image, transfer).map_err(|reason| ImageError::Encode { path: path.to_path_buf(), reason })?;
    write_atomically(path, &bytes)
}

/// Checks, before a long render, that `path` has a known extension and that its
/// directory accepts new files, by creating and removing a temporary file there.
/// The target itself is not touched.
pub fn check_writable(path: &Path) -> Result<(), ImageError> {
    Format::from_path(path)?;
    crate::atomic::check_writable(path).map_err(|io| ImageError::Write { path: path.to_path_buf(), io })
}

/// The bytes of a PNG file of `image` (8-bit, its values encoded with
/// `transfer`): what [`write_image_as`] writes to a `.png` path, for callers
/// that keep the file in memory (the Python package's notebook display).
pub fn png_bytes(image: &Image, transfer: Transfer) -> Result<Vec<u8>, String> {
    encode(Format::Png, image, transfer)
}

/// The file's bytes for `image` in `format`.
fn encode(format: Format, image: &Image, transfer: Transfer) -> Result<Vec<u8>, String> {
    let bytes8 = || match transfer {
        Transfer::Srgb => image.to_srgb8(),
        Transfer::Linear => image.to_linear8(),
    };
    let (width, height) = (image.width, image.height);
    if width == 0 || height == 0 {
        return Err(format!("the image is empty ({width}x{height})"));
    }
    if image.pixels.len() as u64 != width as u64 * height as u64 {
        return Err(format!("{} pixels do not make a {width}x{height} image", image.pixels.len()));
    }
    match format {
        Format::Png => crate::png_write::encode(image, transfer),
        Format::Ppm => {
            let mut bytes = format!("P6\n{width} {height}\n255\n").into_bytes();
            bytes.extend_from_slice(&bytes8());
            Ok(bytes)
        }
        Format::Exr => {
            use crate::exr_zip::Samples;
            let channel = |name: &str, k| (name.to_string(), Samples::Component(&image.pixels, k));
            crate::exr_zip::encode(width as usize, height as usize, vec![channel("R", 0), channel("G", 1), channel("B", 2)])
        }
    }
}

/// Writes `bytes` to `path` atomically ([`crate::atomic::write`]).
pub(crate) fn write_atomically(path: &Path, bytes: &[u8]) -> Result<(), ImageError> {
    crate::atomic::write(path, bytes).map_err(|io| ImageError::Write { path: path.to_path_buf(), io })
}

/// An I/O error as a short lower-case phrase: "permission denied" rather than
/// "Permission denied (os error 13)".
pub(crate) fn describe(error: &io::Error) -> String {
    let text = error.to_string();
    let text = match error.raw_os_error() {
        Some(code) => text.strip_suffix(&format!(" (os error {code})")).unwrap_or(&text).to_string(),
        None => text,
    };
    let mut chars = text.chars();
    match chars.next() {
        Some(first) => first.to_lowercase().chain(chars).collect(),
        None => text,
    }
}

/// Reads an 8-bit RGB PNG: `(width, height, bytes)` with three bytes per pixel.
pub fn read_png_srgb8(path: &Path) -> Result<(u32, u32, Vec<u8>), ImageError> {
    let read_error = |reason: String| ImageError::Read { path: path.to_path_buf(), reason };
    let file = File::open(path).map_err(|e| read_error(describe(&e)))?;
    let decoded =
        image::ImageReader::with_format(BufReader::new(file), image::ImageFormat::Png).decode().map_err(|e| read_error(e.to_string()))?;
    if decoded.color() != image::ColorType::Rgb8 {
        return Err(read_error(format!("expected 8-bit RGB, found {:?}", decoded.color())));
    }
    let rgb = decoded.into_rgb8();
    Ok((rgb.width(), rgb.height(), rgb.into_raw()))
}

/// Reads the first RGB(A) layer of an OpenEXR file as linear float RGB (alpha is dropped).
pub fn read_exr(path: &Path) -> Result<Image, ImageError> {
    let read_error = |reason: String| ImageError::Read { path: path.to_path_buf(), reason };
    let bytes = crate::input::read_regular(path, MAX_IMAGE_FILE_BYTES).map_err(|r| read_error(refusal(&r)))?;
    decode_exr(path, &bytes)
}

/// Most pixels of an input image (`2^27`, a 16384x8192 environment map).
pub const MAX_IMAGE_PIXELS: u64 = 1 << 27;

/// Most pixels per byte of an image file: deflate, EXR's strongest compression
/// of ordinary data, stays below about 1032:1, so a header that claims more
/// pixels than this many per byte of the file is not telling the truth.
pub const MAX_PIXELS_PER_BYTE: u64 = 100;

/// Checks an image's stated size before its pixels are allocated: at most
/// [`MAX_IMAGE_PIXELS`], and at most [`MAX_PIXELS_PER_BYTE`] per byte of the file.
pub(crate) fn check_image_size(width: u64, height: u64, file_len: u64) -> Result<(), String> {
    let pixels = width.saturating_mul(height);
    if pixels > MAX_IMAGE_PIXELS {
        return Err(format!("is {width}x{height} pixels, more than the {MAX_IMAGE_PIXELS} an input image may have"));
    }
    if pixels > file_len.saturating_mul(MAX_PIXELS_PER_BYTE) {
        return Err(format!("claims {width}x{height} pixels, more than a file of {file_len} bytes can hold"));
    }
    Ok(())
}

/// The width and height of the largest layer of the OpenEXR file `bytes`,
/// from its headers (no pixel is read), each layer checked as
/// an image's size is checked (its pixel count bounded); `path` is only named in errors.
pub fn exr_size(path: &Path, bytes: &[u8]) -> Result<(u32, u32), ImageError> {
    let read_error = |reason: String| ImageError::Read { path: path.to_path_buf(), reason };
    let meta = exr::meta::MetaData::read_from_buffered(bytes, false).map_err(|e| read_error(e.to_string()))?;
    let mut largest = (0u32, 0u32);
    for header in meta.headers.iter() {
        let size = header.layer_size;
        check_image_size(size.width() as u64, size.height() as u64, bytes.len() as u64).map_err(read_error)?;
        // Below MAX_IMAGE_PIXELS, so each side fits a u32.
        let (w, h) = (size.width() as u32, size.height() as u32);
        if u64::from(w) * u64::from(h) > u64::from(largest.0) * u64::from(largest.1) {
            largest = (w, h);
        }
    }
    Ok(largest)
}

/// Decodes the bytes of an OpenEXR file as [`read_exr`] does; `path` is only named in errors.
pub fn decode_exr(path: &Path, bytes: &[u8]) -> Result<Image, ImageError> {
    let read_error = |reason: String| ImageError::Read { path: path.to_path_buf(), reason };
    use exr::prelude::{ReadChannels, ReadLayers};
    exr_size(path, bytes)?;
    let exr = exr::prelude::read()
        .no_deep_data()
        .largest_resolution_level()
        .rgba_channels(
            |size: exr::math::Vec2<usize>, _: &exr::prelude::RgbaChannels| Image::new(size.width() as u32, size.height() as u32),
            |image: &mut Image, at: exr::math::Vec2<usize>, (r, g, b, _a): (f32, f32, f32, f32)| {
                let width = image.width as usize;
                image.pixels[at.y() * width + at.x()] = [r, g, b];
            },
        )
        .first_valid_layer()
        .all_attributes()
        .from_buffered(std::io::Cursor::new(bytes))
        .map_err(|e| read_error(e.to_string()))?;
    Ok(exr.layer_data.channel_data.pixels)
}

/// Largest image file read (an environment map or a texture), in bytes.
pub const MAX_IMAGE_FILE_BYTES: u64 = 1 << 30;

/// Why an input image was not read, in words.
pub(crate) fn refusal(r: &crate::input::Refusal) -> String {
    use crate::input::Refusal;
    match r {
        Refusal::NotFound => "no such file".to_string(),
        Refusal::PermissionDenied => "permission denied".to_string(),
        Refusal::Directory => "is a directory, expected an image file".to_string(),
        Refusal::NotRegular(kind) => format!("is {kind}, expected an image file"),
        Refusal::TooLarge { len, max } => format!("is {len} bytes, larger than the {max} bytes an image file may have"),
        Refusal::Io(e) => e.clone(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::fs;

    /// A scratch directory, removed on drop.
    struct Scratch(PathBuf, #[allow(dead_code)] tempfile::TempDir);

    impl Scratch {
        fn new(tag: &str) -> Scratch {
            let dir = tempfile::Builder::new().prefix(&format!("lamplight-image-io-{tag}-")).tempdir().unwrap();
            Scratch(dir.path().to_path_buf(), dir)
        }

        fn entries(&self) -> Vec<String> {
            let mut names: Vec<String> = fs::read_dir(&self.0).unwrap().map(|e| e.unwrap().file_name().to_string_lossy().into()).collect();
            names.sort();
            names
        }
    }

    /// A 5x3 image with values below 0, inside [0, 1], above 1, and not exactly
    /// representable in 8 bits, so clamping and float precision both show.
    fn test_image() -> Image {
        let mut image = Image::new(5, 3);
        for (i, p) in image.pixels.iter_mut().enumerate() {
            let v = i as f32 / 7.0;
            *p = [v - 0.3, v * v, 1.0 / (1.0 + v) + if i == 4 { 10.0 } else { 0.0 }];
        }
        image
    }

    #[test]
    fn png_round_trip_is_byte_exact() {
        let dir = Scratch::new("png");
        let image = test_image();
        let path = dir.0.join("out.PNG");
        write_image(&path, &image).unwrap();
        let (w, h, bytes) = read_png_srgb8(&path).unwrap();
        assert_eq!((w, h), (5, 3));
        assert_eq!(bytes, image.to_srgb8());
        assert_eq!(bytes[0], 0, "negative values clamp to 0");
        assert_eq!(bytes[4 * 3 + 2], 255, "values above 1 clamp to 255");
        assert_eq!(dir.entries(), ["out.PNG"], "no temporary file is left");
    }

    #[test]
    fn ppm_has_header_and_the_png_bytes() {
        let dir = Scratch::new("ppm");
        let image = test_image();
        let path = dir.0.join("out.ppm");
        write_image(&path, &image).unwrap();
        let data = fs::read(&path).unwrap();
        let header = b"P6\n5 3\n255\n";
        assert_eq!(&data[..header.len()], header);
        assert_eq!(&data[header.len()..], &image.to_srgb8()[..]);
    }

    #[test]
    fn exr_round_trip_is_float_exact() {
        let dir = Scratch::new("exr");
        let mut image = test_image();
        image.pixels[1] = [1e-30, 65504.0 * 4.0, f32::MIN_POSITIVE];
        let path = dir.0.join("out.exr");
        write_image(&path, &image).unwrap();
        let back = read_exr(&path).unwrap();
        assert_eq!(back, image, "linear float32 values come back bit for bit");
        assert_eq!(&fs::read(&path).unwrap()[..4], &[0x76, 0x2f, 0x31, 0x01], "OpenEXR magic number");
    }

    #[test]
    fn unknown_extension_lists_the_supported_ones() {
        let dir = Scratch::new("ext");
        for name in ["out.jpg", "out", "out.png.bak"] {
            let err = write_image(&dir.0.join(name), &test_image()).unwrap_err();
            assert!(matches!(err, ImageError::UnknownFormat { .. }), "{name}: {err:?}");
            let message = err.to_string();
            assert!(message.contains(name) && message.contains(".png, .ppm, .exr"), "{message}");
        }
        assert!(dir.entries().is_empty());
    }

    #[test]
    fn empty_or_inconsistent_images_are_errors() {
        let dir = Scratch::new("empty");
        let err = write_image(&dir.0.join("a.png"), &Image::new(0, 4)).unwrap_err();
        assert!(err.to_string().contains("empty"), "{err}");
        let bad = Image { width: 2, height: 2, pixels: vec![[0.0; 3]; 3] };
        let err = write_image(&dir.0.join("b.exr"), &bad).unwrap_err();
        assert!(err.to_string().contains("3 pixels do not make a 2x2 image"), "{err}");
        assert!(dir.entries().is_empty());
    }

    #[test]
    fn directory_that_is_a_file_fails_and_leaves_nothing() {
        // A parent that is a regular file blocks the write even for root.
        let dir = Scratch::new("notdir");
        let blocker = dir.0.join("blocker");
        fs::write(&blocker, b"keep").unwrap();
        let target = blocker.join("out.png");
        let err = write_image(&target, &test_image()).unwrap_err();
        assert!(matches!(err, ImageError::Write { .. }));
        let message = err.to_string();
        assert!(message.starts_with(&format!("cannot write {}: ", target.display())), "{message}");
        assert!(!message.contains("os error"), "{message}");
        assert!(check_writable(&target).is_err());
        assert_eq!(dir.entries(), ["blocker"]);
        assert_eq!(fs::read(&blocker).unwrap(), b"keep");
    }

    #[test]
    fn failed_replace_keeps_the_existing_file_and_removes_the_temporary() {
        // The target is a non-empty directory: the temporary file is written, but
        // renaming it over the target fails (for root too).
        let dir = Scratch::new("replace");
        let target = dir.0.join("out.png");
        fs::create_dir(&target).unwrap();
        fs::write(target.join("inside"), b"old").unwrap();
        let err = write_image(&target, &test_image()).unwrap_err();
        assert!(matches!(err, ImageError::Write { .. }), "{err:?}");
        assert_eq!(dir.entries(), ["out.png"], "the temporary file is gone");
        assert_eq!(fs::read(target.join("inside")).unwrap(), b"old");
    }

    #[test]
    fn replaces_an_existing_file_whole() {
        let dir = Scratch::new("overwrite");
        let path = dir.0.join("out.ppm");
        fs::write(&path, vec![b'x'; 10_000]).unwrap();
        let image = test_image();
        write_image(&path, &image).unwrap();
        assert_eq!(fs::read(&path).unwrap().len(), 11 + 5 * 3 * 3);
        assert!(check_writable(&path).is_ok());
        assert_eq!(fs::read(&path).unwrap().len(), 11 + 5 * 3 * 3, "the check leaves the target alone");
        assert_eq!(dir.entries(), ["out.ppm"]);
    }

    #[test]
    fn io_errors_read_as_short_phrases() {
        assert_eq!(describe(&io::Error::from_raw_os_error(2)), "no such file or directory");
        assert_eq!(describe(&io::Error::other("Disk on fire")), "disk on fire");
    }
}
