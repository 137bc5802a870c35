//! The texture images of a converted mesh file, as the TOML names them: an
//! image file by its path relative to the TOML's folder; an image embedded in
//! a glTF file (a GLB buffer view, a `data:` URI) by the file it is extracted
//! to, `STEM_textures/imageN.EXT` beside the TOML, holding the very bytes the
//! glTF holds (so that it decodes to the same texels).

use std::path::{Path, PathBuf};
use std::sync::Arc;

use lamplight_core::materials::{ImageData, ImageLoader};

use crate::import::{ImageOrigin, ImageSource};

/// Names images for the TOML and records the files to extract.
pub(super) struct Images<'a> {
    sources: &'a [ImageSource],
    /// The TOML's folder, absolute.
    out_dir: PathBuf,
    /// Folder (relative to `out_dir`) for extracted images.
    extract_dir: String,
    /// Names given so far: the name, its sRGB flag and the decoded image.
    named: Vec<(String, bool, Arc<ImageData>)>,
    /// Files to write: absolute path and bytes.
    pub(super) extracted: Vec<(PathBuf, Arc<[u8]>)>,
}

impl<'a> Images<'a> {
    pub(super) fn new(sources: &'a [ImageSource], out_dir: PathBuf, stem: &str) -> Images<'a> {
        Images { sources, out_dir, extract_dir: format!("{stem}_textures"), named: Vec::new(), extracted: Vec::new() }
    }

    /// The TOML's name of the decoded image `data` and whether it is sRGB.
    pub(super) fn name(&mut self, data: &Arc<ImageData>) -> Result<(String, bool), String> {
        let Some(source) = self.sources.iter().find(|s| Arc::ptr_eq(&s.data, data)) else {
            return Err("a texture image of unknown origin".to_string());
        };
        let name = match &source.origin {
            ImageOrigin::File(path) => relative_to(&self.out_dir, &super::absolute_file(path)),
            ImageOrigin::Embedded { index, bytes, extension, .. } => {
                let name = format!("{}/image{index}.{extension}", self.extract_dir);
                let path = self.out_dir.join(&name);
                if !self.extracted.iter().any(|(p, _)| *p == path) {
                    self.extracted.push((path, bytes.clone()));
                }
                name
            }
        };
        if !self.named.iter().any(|(n, s, _)| *n == name && *s == source.srgb) {
            self.named.push((name.clone(), source.srgb, data.clone()));
        }
        Ok((name, source.srgb))
    }
}

impl ImageLoader for Images<'_> {
    /// The images named so far, by name (reading a material back).
    fn load(&self, file: &str, srgb: bool) -> Result<Arc<ImageData>, String> {
        self.named
            .iter()
            .find(|(n, s, _)| n == file && *s == srgb)
            .map(|(_, _, d)| d.clone())
            .ok_or_else(|| format!("image \"{file}\" was not named by the converter"))
    }
}

/// `path` relative to the folder `dir` (both absolute), with `/` separators;
/// `path` itself where they share no root.
pub(super) fn relative_to(dir: &Path, path: &Path) -> String {
    let (d, p): (Vec<_>, Vec<_>) = (dir.components().collect(), path.components().collect());
    let common = d.iter().zip(&p).take_while(|(a, b)| a == b).count();
    if common == 0 {
        return path.to_string_lossy().into_owned();
    }
    let mut parts: Vec<String> = vec!["..".to_string(); d.len() - common];
    parts.extend(p[common..].iter().map(|c| c.as_os_str().to_string_lossy().into_owned()));
    parts.join("/")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn paths_are_written_relative_to_the_toml() {
        assert_eq!(relative_to(Path::new("/a/b"), Path::new("/a/b/m.obj")), "m.obj");
        assert_eq!(relative_to(Path::new("/a/b"), Path::new("/a/c/t/m.png")), "../c/t/m.png");
        assert_eq!(relative_to(Path::new("/a/b/c"), Path::new("/a/m.obj")), "../../m.obj");
    }
}
