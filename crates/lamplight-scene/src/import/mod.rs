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

use lamplight_core::lights::{DirectionalLight, PointLight};
use lamplight_core::materials::Material;
use lamplight_core::math::{Mat4, Vec3};

use crate::error::LoadError;

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
}

/// A camera from the file (glTF perspective cameras).
#[derive(Clone, Debug, PartialEq)]
pub struct ImportedCamera {
    /// Eye position.
    pub eye: Vec3,
    /// A point the camera looks at.
    pub target: Vec3,
    /// Up direction.
    pub up: Vec3,
    /// Vertical field of view, degrees.
    pub vfov_deg: f64,
}

/// A light from the file (glTF KHR_lights_punctual).
#[derive(Clone, Debug)]
pub enum ImportedLight {
    /// Point light.
    Point(PointLight),
    /// Directional light.
    Directional(DirectionalLight),
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
}

/// Extensions [`load`] understands, lower case.
pub const EXTENSIONS: &[&str] = &["obj", "ply", "gltf", "glb"];

/// Reads `path` with the importer its extension names.
pub fn load(path: &Path) -> Result<Imported, LoadError> {
    let ext = path.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase).unwrap_or_default();
    Err(LoadError::file(path, format!("cannot read .{ext} files yet (supported: {})", EXTENSIONS.join(", "))))
}
