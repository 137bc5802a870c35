//! The images of a glTF file, for its materials' textures: in a buffer view
//! (GLB files), a `data:` URI or a file beside the glTF, decoded once per
//! colour space ([`crate::texture_files::decode_texture`], with its size checks).

use std::collections::HashMap;
use std::path::Path;
use std::sync::Arc;

use base64::Engine;
use lamplight_core::materials::ImageData;

use super::{ImageOrigin, ImageSource};
use crate::error::LoadError;

/// The extension of an encoded image's format, from its first bytes
/// (glTF embeds PNG and JPEG; anything else keeps `.bin` and is decoded by content).
fn image_extension(bytes: &[u8]) -> &'static str {
    if bytes.starts_with(b"\x89PNG") {
        "png"
    } else if bytes.starts_with(&[0xff, 0xd8]) {
        "jpg"
    } else if bytes.starts_with(b"RIFF") && bytes.get(8..12) == Some(b"WEBP") {
        "webp"
    } else {
        "bin"
    }
}

/// Checks what gltf 1.4.1's `Image::source` unwraps without validating (found
/// by the `gltf` fuzz target: an image with a `bufferView` but no `mimeType`
/// panicked): an image has a `bufferView` with a `mimeType`, or a `uri`.
pub(super) fn check_sources(path: &Path, root: &gltf::json::Root) -> Result<(), LoadError> {
    for (i, image) in root.images.iter().enumerate() {
        let fail = |at: &str, message: &str| Err(LoadError::json(path, format!("images[{i}]{at}"), message));
        match (&image.buffer_view, &image.uri) {
            (Some(_), _) if image.mime_type.is_none() => return fail(".mimeType", "an image in a bufferView needs a mimeType"),
            (Some(view), _) if view.value() >= root.buffer_views.len() => {
                return fail(".bufferView", &format!("buffer view {} does not exist ({} views)", view.value(), root.buffer_views.len()))
            }
            (None, None) => return fail("", "expected a uri or a bufferView"),
            _ => {}
        }
    }
    Ok(())
}

/// Decoded images by (image index, sRGB), and where each came from.
pub(super) struct GltfImages<'p> {
    path: &'p Path,
    cache: HashMap<(usize, bool), Arc<ImageData>>,
    sources: Vec<ImageSource>,
}

impl<'p> GltfImages<'p> {
    pub(super) fn new(path: &'p Path) -> GltfImages<'p> {
        GltfImages { path, cache: HashMap::new(), sources: Vec::new() }
    }

    /// Every image decoded, in the order it was first used.
    pub(super) fn into_sources(self) -> Vec<ImageSource> {
        self.sources
    }

    /// Image `image` decoded, from sRGB when `srgb`; errors name `images[i]`.
    pub(super) fn load(&mut self, image: &gltf::Image, buffers: &[Vec<u8>], srgb: bool) -> Result<Arc<ImageData>, LoadError> {
        let key = (image.index(), srgb);
        if let Some(data) = self.cache.get(&key) {
            return Ok(data.clone());
        }
        let at = format!("images[{}]", image.index());
        let fail = |where_: &str, message: String| LoadError::json(self.path, format!("{at}{where_}"), message);
        let (name, bytes, embedded): (std::path::PathBuf, std::borrow::Cow<'_, [u8]>, bool) = match image.source() {
            gltf::image::Source::View { view, .. } => {
                let (start, len) = (view.offset(), view.length());
                let buffer = buffers.get(view.buffer().index());
                let Some(bytes) = start.checked_add(len).and_then(|end| buffer?.get(start..end)) else {
                    return Err(fail(
                        ".bufferView",
                        format!("bytes {start}..{} lie outside buffer {}", start.saturating_add(len), view.buffer().index()),
                    ));
                };
                (
                    self.path.with_file_name(format!("{}#{at}", self.path.file_name().map_or("glb".into(), |n| n.to_string_lossy()))),
                    bytes.into(),
                    true,
                )
            }
            gltf::image::Source::Uri { uri, .. } => {
                if let Some(rest) = uri.strip_prefix("data:") {
                    let Some((_, encoded)) = rest.split_once(";base64,") else {
                        return Err(fail(".uri", "expected a base64 data URI (`data:...;base64,...`)".into()));
                    };
                    let bytes = super::gltf::base64_engine().decode(encoded).map_err(|e| fail(".uri", format!("invalid base64: {e}")))?;
                    (
                        self.path.with_file_name(format!("{}#{at}", self.path.file_name().map_or("gltf".into(), |n| n.to_string_lossy()))),
                        bytes.into(),
                        true,
                    )
                } else if uri.contains("://") {
                    return Err(fail(".uri", format!("cannot fetch `{uri}`: only files beside the glTF are read")));
                } else {
                    let file = self.path.parent().unwrap_or(Path::new("")).join(percent_decoded(uri));
                    let bytes = crate::input::read_regular(&file, crate::image_io::MAX_IMAGE_FILE_BYTES)
                        .map_err(|r| fail(".uri", format!("cannot read image `{}`: {}", file.display(), crate::image_io::refusal(&r))))?;
                    (file, bytes.into(), false)
                }
            }
        };
        let data = crate::texture_files::decode_texture(&name, &bytes, srgb).map_err(|m| fail("", m))?;
        let data = Arc::new(data);
        self.cache.insert(key, data.clone());
        let origin = if embedded {
            ImageOrigin::Embedded {
                label: name.file_name().map_or_else(|| at.clone(), |n| n.to_string_lossy().into_owned()),
                index: image.index(),
                extension: image_extension(&bytes),
                bytes: Arc::from(&*bytes),
            }
        } else {
            ImageOrigin::File(name)
        };
        self.sources.push(ImageSource { data: data.clone(), srgb, origin });
        Ok(data)
    }
}

/// A relative URI's `%XX` escapes decoded (glTF URIs are RFC 3986: a space is `%20`).
fn percent_decoded(uri: &str) -> String {
    let bytes = uri.as_bytes();
    let mut out = Vec::with_capacity(bytes.len());
    let mut i = 0;
    while i < bytes.len() {
        let hex = |b: u8| (b as char).to_digit(16);
        if bytes[i] == b'%' && i + 2 < bytes.len() {
            if let (Some(h), Some(l)) = (hex(bytes[i + 1]), hex(bytes[i + 2])) {
                out.push((h * 16 + l) as u8);
                i += 3;
                continue;
            }
        }
        out.push(bytes[i]);
        i += 1;
    }
    String::from_utf8_lossy(&out).into_owned()
}

#[cfg(test)]
mod tests {
    #[test]
    fn uris_are_percent_decoded() {
        assert_eq!(super::percent_decoded("My%20Texture.png"), "My Texture.png");
        assert_eq!(super::percent_decoded("a%2"), "a%2");
        assert_eq!(super::percent_decoded("100%"), "100%");
    }
}
