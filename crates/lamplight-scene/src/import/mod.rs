//! Importers for the formats people already have: OBJ (+MTL), PLY, glTF 2.0.
//!
//! Each importer turns a file into an [`Imported`] set of meshes, cameras and
//! lights in world space, with lamplight materials already mapped; it never
//! builds a core scene itself. Unsupported parts become warnings, never silent
//! losses. Dispatch by file extension is in [`load`].
//!
//! (Interface fixed first so that the scene format and the importers can be
//! written side by side; the formats are filled in by their own modules.)

use std::path::Path;

use lamplight_core::lights::{DirectionalLight, PointLight, SpotLight, SpotProfile};
use lamplight_core::materials::Material;
use lamplight_core::math::{Mat4, Rgb, Vec3};
use lamplight_core::shapes::VertexAttributes;

use crate::error::LoadError;

mod gltf;
pub mod gltf_animation;
pub mod gltf_choice;
mod gltf_images;
mod gltf_material;
mod mtl;
mod obj;
mod ply;
mod ply_attributes;
mod ply_header;
mod tangents;

pub use ply_attributes::NamedAttribute;

/// Triangle mesh data as read from a file (indices in the file's face order,
/// polygons triangulated as fans).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct MeshData {
    /// Name in the file, if any.
    pub name: Option<String>,
    /// Vertex positions.
    pub positions: Vec<Vec3>,
    /// Triangles as vertex indices.
    pub indices: Vec<[u32; 3]>,
    /// Per-vertex normals, if the file has them (same length as `positions`).
    pub normals: Option<Vec<Vec3>>,
    /// Texture coordinates, colours and tangents, each if the file has them.
    pub attributes: VertexAttributes,
    /// A PLY file's other properties as Mitsuba names them (`vertex_color`,
    /// `face_weight`, ...), for a mesh's `color` (grouped by the `ply_attributes` module).
    pub named: Vec<NamedAttribute>,
}

/// One mesh placed in the world with a material.
#[derive(Clone, Debug, PartialEq)]
pub struct ImportedMesh {
    /// Index into [`Imported::meshes`] (several instances may share one mesh).
    pub mesh: usize,
    /// World-from-object transform.
    pub transform: Mat4,
    /// Mapped material (`None`: the importer found none; the caller picks a default).
    pub material: Option<Material>,
    /// The material's name in the file (MTL `newmtl`, glTF `materials[i].name`), if any.
    pub material_name: Option<String>,
}

/// A camera from the file (glTF cameras).
#[derive(Clone, Debug, PartialEq)]
pub struct ImportedCamera {
    /// Eye position.
    pub eye: Vec3,
    /// A point the camera looks at.
    pub target: Vec3,
    /// Up direction.
    pub up: Vec3,
    /// How it projects.
    pub projection: ImportedProjection,
}

/// The projection of an [`ImportedCamera`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ImportedProjection {
    /// Perspective with this vertical field of view, degrees.
    Perspective {
        /// Vertical field of view, degrees.
        vfov_deg: f64,
    },
    /// Parallel projection of a window with these half-extents (glTF's `xmag`,
    /// `ymag`), widened to the image's aspect without cropping or stretching.
    Orthographic {
        /// Half-width.
        xmag: f64,
        /// Half-height.
        ymag: f64,
    },
}

/// A light from the file (glTF KHR_lights_punctual), as the arguments of its
/// constructor, so that a converted scene file builds the very same light.
#[derive(Clone, Debug, PartialEq)]
pub enum ImportedLight {
    /// Point light ([`PointLight::new`]).
    Point {
        /// Position.
        position: Vec3,
        /// Intensity.
        intensity: Rgb,
    },
    /// Directional light ([`DirectionalLight::new`]).
    Directional {
        /// The way the light travels (not normalized).
        direction: Vec3,
        /// Radiance.
        radiance: Rgb,
    },
    /// Spot light with the glTF cone profile ([`SpotLight::new`]).
    Spot {
        /// Position.
        position: Vec3,
        /// Axis (not normalized).
        direction: Vec3,
        /// Intensity on the axis.
        intensity: Rgb,
        /// Inner cone angle, degrees.
        inner_deg: f64,
        /// Outer cone angle, degrees.
        outer_deg: f64,
    },
}

impl ImportedLight {
    /// The core light.
    pub fn build(&self) -> Result<std::sync::Arc<dyn lamplight_core::lights::Light>, lamplight_core::Error> {
        use std::sync::Arc;
        Ok(match *self {
            ImportedLight::Point { position, intensity } => Arc::new(PointLight::new(position, intensity)?),
            ImportedLight::Directional { direction, radiance } => Arc::new(DirectionalLight::new(direction, radiance)?),
            ImportedLight::Spot { position, direction, intensity, inner_deg, outer_deg } => {
                Arc::new(SpotLight::new(position, direction, intensity, inner_deg, outer_deg, SpotProfile::Gltf)?)
            }
        })
    }
}

/// Where a texture image of an imported material came from, so that a
/// converted scene file can name it ([`crate::convert`]).
#[derive(Clone, Debug)]
pub struct ImageSource {
    /// The decoded image the materials hold.
    pub data: std::sync::Arc<lamplight_core::materials::ImageData>,
    /// Decoded from sRGB.
    pub srgb: bool,
    /// The file, or the bytes of an image embedded in the file.
    pub origin: ImageOrigin,
}

/// The origin of an [`ImageSource`].
#[derive(Clone, Debug)]
pub enum ImageOrigin {
    /// An image file.
    File(std::path::PathBuf),
    /// An image inside the mesh file (a GLB buffer view, a `data:` URI).
    Embedded {
        /// What it is called in messages (`model.glb#images[0]`).
        label: String,
        /// Its index in the file's images.
        index: usize,
        /// The encoded bytes.
        bytes: std::sync::Arc<[u8]>,
        /// The extension its format is written with (`png`, `jpg`).
        extension: &'static str,
    },
}

/// Everything an importer read from one file.
#[derive(Clone, Debug, Default)]
pub struct Imported {
    /// Mesh data, shared by the instances.
    pub meshes: Vec<MeshData>,
    /// Placed meshes.
    pub instances: Vec<ImportedMesh>,
    /// Cameras, in file order.
    pub cameras: Vec<ImportedCamera>,
    /// Lights.
    pub lights: Vec<ImportedLight>,
    /// Parts of the file that were not used, one line each (reported once).
    pub warnings: Vec<String>,
    /// The texture images the materials use, where each came from.
    pub images: Vec<ImageSource>,
    /// A glTF file's animations and the node tree they move ([`Imported::pose`]).
    pub animations: Option<gltf_animation::Animations>,
}

/// Extensions [`load`] understands, lower case.
pub const EXTENSIONS: &[&str] = &["obj", "ply", "gltf", "glb"];

/// Reads `path` with the importer its extension names.
pub fn load(path: &Path) -> Result<Imported, LoadError> {
    if let Ok(len) = crate::input::check_regular(path) {
        // The memory budget's share, before the file is read: what its
        // readers make of a byte of file at most (a PLY's declared counts are
        // checked against its size), the file itself included.
        crate::memory::reserve(len.saturating_mul(MESH_BYTES_PER_FILE_BYTE), || format!("mesh file {} ({len} bytes)", path.display()))
            .map_err(|e| LoadError::file(path, e.to_string()))?;
    }
    let bytes = read_file(path)?;
    load_bytes(path, &bytes)
}

/// The memory a mesh file's readers take per byte of the file, at most: the
/// file, the mesh's arrays and its BVH (a binary PLY's 12-byte vertex becomes
/// 24 bytes of positions and normals, a 13-byte face 12 bytes of indices and
/// about 64 of BVH).
pub const MESH_BYTES_PER_FILE_BYTE: u64 = 8;

/// Parses `bytes` as the file `path` (whose extension picks the importer, and
/// against whose folder relative references such as `.mtl` and `.bin` files
/// are resolved). The fuzz targets and property tests enter here.
pub fn load_bytes(path: &Path, bytes: &[u8]) -> Result<Imported, LoadError> {
    let ext = path.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase).unwrap_or_default();
    if ext.is_empty() {
        // `/etc/passwd` named as a mesh: there is no extension to pick a reader by.
        return Err(LoadError::file(
            path,
            format!("has no file extension, expected a mesh file named for its format (.{})", EXTENSIONS.join(", .")),
        ));
    }
    if !EXTENSIONS.contains(&ext.as_str()) {
        return Err(LoadError::file(path, format!("cannot read .{ext} files (supported: {})", EXTENSIONS.join(", "))));
    }
    if bytes.is_empty() {
        return Err(LoadError::file(path, "the file is empty"));
    }
    let imported = match ext.as_str() {
        "ply" => ply::parse(path, bytes),
        "obj" => obj::parse(path, bytes),
        "gltf" | "glb" => gltf::parse(path, bytes),
        _ => Err(LoadError::file(path, format!("cannot read .{ext} files yet"))),
    }?;
    // Every caller (a rendered mesh file, a scene's `[meshes]`, `raycast --mesh`)
    // wants triangles: a file with none is not what was meant, most often not a
    // mesh file at all (an OBJ reader skips what it does not know, so random
    // bytes read as an OBJ of unknown statements).
    let placed = |i: &ImportedMesh| imported.meshes.get(i.mesh).is_some_and(|m| !m.indices.is_empty());
    if !imported.instances.iter().any(placed) {
        return Err(LoadError::file(path, "has no triangles, expected a mesh"));
    }
    Ok(imported)
}

/// All triangles of a mesh file merged into one mesh in file order, in world
/// space (instance transforms applied). For a PLY file, face `i` is triangle
/// `i`. Normals are kept only when every merged mesh has them.
pub fn load_mesh(path: &Path) -> Result<MeshData, LoadError> {
    Ok(load(path)?.into_mesh())
}

impl MeshData {
    /// The core mesh, with its vertex attributes.
    pub fn to_mesh(&self) -> Result<lamplight_core::shapes::TriangleMesh, lamplight_core::Error> {
        self.to_mesh_with(self.normals.clone())
    }

    /// The core mesh with `normals` in place of the file's.
    pub fn to_mesh_with(&self, normals: Option<Vec<Vec3>>) -> Result<lamplight_core::shapes::TriangleMesh, lamplight_core::Error> {
        lamplight_core::shapes::TriangleMesh::new(self.positions.clone(), self.indices.clone(), normals)?
            .with_attributes(self.attributes.clone())
    }
}

impl Imported {
    /// The warnings as the front ends show them: `PATH: what`, `path` being the
    /// file they came from, each once.
    pub fn warnings_of(&self, path: &Path) -> Vec<String> {
        self.warnings.iter().map(|w| format!("{}: {w}", path.display())).collect()
    }

    /// Merges every instance into one world-space mesh, in instance order.
    pub fn into_mesh(mut self) -> MeshData {
        // The common case (PLY, one OBJ object): hand the mesh over without copying.
        if self.meshes.len() == 1 && self.instances.len() == 1 && self.instances[0].transform == Mat4::IDENTITY {
            return self.meshes.pop().unwrap_or_default();
        }
        // Vertex attributes are for rendering the file's own scene; a merged mesh
        // (the batch ray-casting API) has positions and normals only.
        let mut out = MeshData { name: None, positions: Vec::new(), indices: Vec::new(), normals: Some(Vec::new()), ..MeshData::default() };
        for instance in &self.instances {
            let Some(mesh) = self.meshes.get(instance.mesh) else { continue };
            let base = out.positions.len() as u32;
            out.positions.extend(mesh.positions.iter().map(|&p| instance.transform.transform_point3(p)));
            out.indices.extend(mesh.indices.iter().map(|t| t.map(|i| i + base)));
            match (&mut out.normals, &mesh.normals) {
                (Some(all), Some(normals)) => {
                    // Normals transform with the inverse transpose.
                    let m = instance.transform.inverse().transpose();
                    all.extend(normals.iter().map(|&n| m.transform_vector3(n).normalize_or_zero()));
                }
                (all, _) => *all = None,
            }
        }
        out
    }
}

/// Largest mesh file read, in bytes (a 1 GiB mesh is some 40 million triangles).
pub const MAX_MESH_BYTES: u64 = 1 << 30;

/// Reads a whole file, naming a missing file, a directory, a pipe or device, or
/// an unreadable one.
pub(crate) fn read_file(path: &Path) -> Result<Vec<u8>, LoadError> {
    crate::input::read_regular(path, MAX_MESH_BYTES).map_err(|r| {
        use crate::input::Refusal;
        LoadError::file(
            path,
            match r {
                Refusal::NotFound => "file not found".to_string(),
                Refusal::Directory => "is a directory, expected a file".to_string(),
                Refusal::NotRegular(kind) => format!("is {kind}, expected a mesh file"),
                Refusal::TooLarge { len, max } => format!("is {len} bytes, larger than the {max} bytes a mesh file may have"),
                Refusal::PermissionDenied => "cannot read the file: permission denied".to_string(),
                Refusal::Io(e) => format!("cannot read the file: {e}"),
            },
        )
    })
}

/// Whitespace-separated words of a line with their 1-based character columns.
pub(crate) fn words(line: &str) -> Vec<(usize, &str)> {
    let mut out = Vec::new();
    words_into(line, &mut out);
    out
}

/// [`words`] into `out`, which is cleared first (so a parser reuses one buffer).
pub(crate) fn words_into<'a>(line: &'a str, out: &mut Vec<(usize, &'a str)>) {
    if line.is_ascii() {
        // Mesh files are ASCII: a byte is a character (its column), and the
        // ASCII characters `char::is_whitespace` takes are these six. Decoding
        // every character was a twentieth of loading an OBJ file.
        let bytes = line.bytes().enumerate().map(|(i, b)| (i, i, matches!(b, b' ' | b'\t' | b'\n' | b'\x0b' | b'\x0c' | b'\r')));
        split_words(line, bytes, out);
    } else {
        words_by_char(line, out);
    }
}

/// [`words_into`] decoding every character.
fn words_by_char<'a>(line: &'a str, out: &mut Vec<(usize, &'a str)>) {
    split_words(line, line.char_indices().enumerate().map(|(col, (i, c))| (col, i, c.is_whitespace())), out);
}

/// The words of `line` from its characters as (0-based column, byte index,
/// whether it is whitespace), into `out`, cleared first.
#[inline(always)]
fn split_words<'a>(line: &'a str, chars: impl Iterator<Item = (usize, usize, bool)>, out: &mut Vec<(usize, &'a str)>) {
    out.clear();
    let mut start = None;
    for (col, i, space) in chars {
        match (space, start) {
            (false, None) => start = Some((col + 1, i)),
            (true, Some((c0, i0))) => {
                out.push((c0, &line[i0..i]));
                start = None;
            }
            _ => {}
        }
    }
    if let Some((c0, i0)) = start {
        out.push((c0, &line[i0..]));
    }
}

/// Word `i` of a text line as a finite number, or an error at its column saying what was expected.
pub(crate) fn number(path: &Path, line_no: usize, line: &str, words: &[(usize, &str)], i: usize, what: &str) -> Result<f64, LoadError> {
    let Some(&(column, word)) = words.get(i) else {
        let end = line.trim_end().chars().count() + 1;
        return Err(LoadError::at(path, line_no, end, format!("expected a number ({what}), found the end of the line")));
    };
    match word.parse::<f64>() {
        Ok(v) if v.is_finite() => Ok(v),
        Ok(v) => Err(LoadError::at(path, line_no, column, format!("expected a finite number ({what}), found {v}"))),
        Err(_) => Err(LoadError::at(path, line_no, column, format!("expected a number ({what}), found `{word}`"))),
    }
}

/// Warnings in order, each text kept once.
#[derive(Default)]
pub(crate) struct Warnings(Vec<String>);

impl Warnings {
    /// Adds `text` unless it was added before.
    pub(crate) fn once(&mut self, text: String) {
        if !self.0.contains(&text) {
            self.0.push(text);
        }
    }

    /// The warnings in the order they were first added.
    pub(crate) fn into_vec(self) -> Vec<String> {
        self.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn words_carry_their_columns() {
        assert_eq!(words("  element  vértex 8"), vec![(3, "element"), (12, "vértex"), (19, "8")]);
        // ASCII lines take the byte path: every ASCII character splits as
        // `char::is_whitespace` says, and the columns are the same.
        let ascii: String = (0u8..128).map(char::from).collect();
        let by_char = |line| {
            let mut out = Vec::new();
            words_by_char(line, &mut out);
            out
        };
        for line in [ascii.as_str(), "v 1 2 3", "\x0bf 1/2/3\x0c4//5 6\r", "  ", ""] {
            assert_eq!(words(line), by_char(line), "{line:?}");
        }
    }

    #[test]
    fn numbers_must_be_finite() {
        let p = Path::new("a.obj");
        let line = "v 1 nan";
        let w = words(line);
        assert_eq!(number(p, 2, line, &w, 1, "x"), Ok(1.0));
        assert_eq!(number(p, 2, line, &w, 2, "y").unwrap_err().to_string(), "a.obj:2:5: expected a finite number (y), found NaN");
        assert_eq!(number(p, 2, line, &w, 3, "z").unwrap_err().to_string(), "a.obj:2:8: expected a number (z), found the end of the line");
    }
}
