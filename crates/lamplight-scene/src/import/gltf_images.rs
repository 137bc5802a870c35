//! The images of a glTF file, for its materials' textures: in a buffer view
//! (GLB files), a `data:` URI or a file beside the glTF, decoded once per
//! colour space ([`crate::texture_files::decode_texture`], with its size checks).
//!
//! The materials ask for their images one at a time, but a file's images are
//! independent: [`GltfImages::decode_ahead`] first finds every (image, colour
//! space) the materials will ask for and decodes them on all cores (the
//! Damaged Helmet's five 2048 x 2048 JPEGs took 100 ms of its 245 ms load on
//! one). The materials then take them in their own order, so what they get,
//! the order of [`GltfImages::into_sources`] and every error are as before.

use std::borrow::Cow;
use std::collections::HashMap;
use std::path::{Path, PathBuf};
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

/// An image's name in messages, its encoded bytes, and whether it is embedded.
type Encoded<'b> = (PathBuf, Cow<'b, [u8]>, bool);

/// Decoded images by (image index, sRGB), and where each came from.
pub(super) struct GltfImages<'p> {
    path: &'p Path,
    cache: HashMap<(usize, bool), Arc<ImageData>>,
    sources: Vec<ImageSource>,
    /// Images decoded by [`GltfImages::decode_ahead`] that no material has taken yet.
    ahead: HashMap<(usize, bool), (Encoded<'static>, Result<ImageData, String>)>,
}

impl<'p> GltfImages<'p> {
    pub(super) fn new(path: &'p Path) -> GltfImages<'p> {
        GltfImages { path, cache: HashMap::new(), sources: Vec::new(), ahead: HashMap::new() }
    }

    /// Decodes, in parallel, every image that `materials` will ask for (found
    /// by mapping each material with a loader that only records), for
    /// [`GltfImages::load`] to take. If any of them fails (a broken image, or
    /// the memory budget, which decoding in parallel draws on at once), none is
    /// kept and their budget is given back: `load` then decodes one by one as
    /// before, so every error, and the budget each image meets, is as before.
    /// An image whose bytes cannot be read is left to `load` too.
    pub(super) fn decode_ahead(&mut self, document: &gltf::Document, materials: &[gltf::Material], buffers: &[Vec<u8>]) {
        use rayon::prelude::*;
        let placeholder =
            Arc::new(ImageData::new(1, 1, lamplight_core::materials::image::Texels::F32(vec![[0.0; 4]]), false).expect("1 x 1"));
        let (mut wanted, mut seen) = (Vec::new(), std::collections::HashSet::new());
        for material in materials {
            let mut record = |image: &gltf::Image, srgb: bool| {
                if seen.insert((image.index(), srgb)) {
                    wanted.push((image.index(), srgb));
                }
                Ok(placeholder.clone())
            };
            let _ = super::gltf_material::map(material, false, &mut record, &mut super::Warnings::default());
        }
        wanted.retain(|key| !self.cache.contains_key(key));
        if wanted.len() < 2 {
            return;
        }
        let images: Vec<gltf::Image> = document.images().collect();
        let jobs: Vec<((usize, bool), Encoded<'static>)> = wanted
            .into_iter()
            .filter_map(|(index, srgb)| {
                let (name, bytes, embedded) = self.encoded(images.get(index)?, buffers).ok()?;
                Some(((index, srgb), (name, Cow::Owned(bytes.into_owned()), embedded)))
            })
            .collect();
        let budget_before = crate::memory::used();
        let decoded: HashMap<_, _> = jobs
            .into_par_iter()
            .map(|(key, encoded)| {
                let decoded = crate::texture_files::decode_texture(&encoded.0, &encoded.1, key.1);
                (key, (encoded, decoded))
            })
            .collect();
        if decoded.values().all(|(_, d)| d.is_ok()) {
            self.ahead = decoded;
        } else {
            // What these decodes reserved (a load reserves from one thread, so
            // nothing else has drawn on the budget since), given back.
            crate::memory::release(crate::memory::used().saturating_sub(budget_before));
        }
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
        let fail = |message: String| LoadError::json(self.path, at.clone(), message);
        let ((name, bytes, embedded), data): (Encoded<'_>, _) = match self.ahead.remove(&key) {
            Some((encoded, decoded)) => (encoded, decoded),
            None => {
                let encoded = self.encoded(image, buffers)?;
                let decoded = crate::texture_files::decode_texture(&encoded.0, &encoded.1, srgb);
                (encoded, decoded)
            }
        };
        let data = Arc::new(data.map_err(fail)?);
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

    /// Where image `image` is and its encoded bytes; errors name `images[i]`.
    fn encoded<'b>(&self, image: &gltf::Image, buffers: &'b [Vec<u8>]) -> Result<Encoded<'b>, LoadError> {
        let at = format!("images[{}]", image.index());
        let fail = |where_: &str, message: String| LoadError::json(self.path, format!("{at}{where_}"), message);
        Ok(match image.source() {
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
        })
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
    use super::*;

    /// A 2 x 2 PNG of one colour, as a `data:` URI.
    fn png_uri(rgb: [u8; 3]) -> String {
        use image::ImageEncoder;
        let pixels: Vec<u8> = (0..4).flat_map(|_| rgb).collect();
        let mut bytes = Vec::new();
        image::codecs::png::PngEncoder::new(&mut bytes).write_image(&pixels, 2, 2, image::ExtendedColorType::Rgb8).unwrap();
        format!("data:image/png;base64,{}", base64::engine::general_purpose::STANDARD.encode(bytes))
    }

    /// Loading after `decode_ahead` gives every material the images, sources
    /// and errors that loading one by one gives.
    #[test]
    fn images_decoded_ahead_are_the_ones_decoded_one_by_one() {
        let broken = format!("data:image/png;base64,{}", base64::engine::general_purpose::STANDARD.encode(b"\x89PNG not really"));
        let json = format!(
            r#"{{"asset": {{"version": "2.0"}},
  "images": [{{"uri": "{}"}}, {{"uri": "{}"}}, {{"uri": "{broken}"}}],
  "textures": [{{"source": 0}}, {{"source": 1}}, {{"source": 2}}],
  "materials": [
    {{"pbrMetallicRoughness": {{"baseColorTexture": {{"index": 0}}}}}},
    {{"pbrMetallicRoughness": {{"metallicRoughnessTexture": {{"index": 0}}}}, "emissiveTexture": {{"index": 1}}, "emissiveFactor": [1, 1, 1]}},
    {{"normalTexture": {{"index": 2}}}}]}}"#,
            png_uri([200, 100, 50]),
            png_uri([10, 20, 30])
        );
        let document = gltf::Gltf::from_slice(json.as_bytes()).unwrap().document;
        let path = Path::new("t.gltf");
        let load_all = |images: &mut GltfImages| -> Vec<Result<Vec<Arc<ImageData>>, String>> {
            document
                .materials()
                .map(|m| {
                    let mut got = Vec::new();
                    let mut load = |image: &gltf::Image, srgb: bool| {
                        let data = images.load(image, &[], srgb)?;
                        got.push(data.clone());
                        Ok(data)
                    };
                    super::super::gltf_material::map(&m, false, &mut load, &mut super::super::Warnings::default())
                        .map(|_| got)
                        .map_err(|e| e.to_string())
                })
                .collect()
        };
        let materials: Vec<gltf::Material> = document.materials().collect();
        // The first two materials: every image they use decoded ahead, in its colour space.
        let mut ahead = GltfImages::new(path);
        ahead.decode_ahead(&document, &materials[..2], &[]);
        let mut keys: Vec<_> = ahead.ahead.keys().copied().collect();
        keys.sort();
        assert_eq!(keys, [(0, false), (0, true), (1, true)]);
        // All three: the broken image makes it keep none (the budget is
        // process-wide and other tests draw on it, so its release is not checked here).
        let mut fallback = GltfImages::new(path);
        fallback.decode_ahead(&document, &materials, &[]);
        assert!(fallback.ahead.is_empty(), "a failure keeps nothing");
        let (with, without) = (load_all(&mut ahead), load_all(&mut GltfImages::new(path)));
        assert_eq!(with, without);
        assert!(with[2].as_ref().is_err_and(|e| e.contains("images[2]")), "{:?}", with[2]);
        assert!(ahead.ahead.is_empty(), "every image decoded ahead was taken");
        assert_eq!(load_all(&mut fallback), without);
        let sources = |images: GltfImages| -> Vec<(bool, String)> {
            images.into_sources().iter().map(|s| (s.srgb, format!("{:?}", s.origin).chars().take(60).collect())).collect()
        };
        let mut one_by_one = GltfImages::new(path);
        load_all(&mut one_by_one);
        assert_eq!(sources(ahead), sources(one_by_one));
    }

    #[test]
    fn uris_are_percent_decoded() {
        assert_eq!(super::percent_decoded("My%20Texture.png"), "My Texture.png");
        assert_eq!(super::percent_decoded("a%2"), "a%2");
        assert_eq!(super::percent_decoded("100%"), "100%");
    }
}
