//! `lamplight convert`: another format's scene written as a native TOML file
//! that builds to the same scene (and so renders to the same bytes).
//!
//! - Mitsuba XML is read to the located table a TOML file would give
//!   ([`crate::formats::mitsuba::read_table`]) and written by
//!   [`crate::formats::native_writer`]. Relative `file` paths are relative to the
//!   scene's folder; when the TOML goes to another folder they are made absolute.
//! - A mesh file (OBJ, PLY, glTF, GLB) keeps its geometry and has its
//!   materials, camera and lights written out (`convert/mesh_file.rs`).

use std::path::Path;

use lamplight_core::params::{Table, Value};

use crate::error::LoadError;
use crate::formats::{mitsuba, native_writer};

mod images;
mod material;
mod mesh_file;

/// A converted scene: the TOML text, the files it refers to that must be
/// written beside it, and the reader's warnings.
#[derive(Debug)]
pub struct Converted {
    /// The native scene file.
    pub toml: String,
    /// Warnings, one line each.
    pub warnings: Vec<String>,
    /// Files to write before the TOML (absolute path, bytes): images embedded
    /// in a glTF file, extracted for the TOML's textures to name.
    pub files: Vec<(std::path::PathBuf, std::sync::Arc<[u8]>)>,
}

/// Converts the scene file `input` for writing to `output`.
pub fn convert(input: &Path, output: &Path, defines: &[(String, String)]) -> Result<Converted, LoadError> {
    convert_with(input, output, defines, None)
}

/// [`convert`] with the glTF animation `animation` names playing (`--animation`:
/// its frames and its `[meshes]` entry's `animation`); a name or index the
/// file lacks, or a file other than glTF, is refused as a render refuses it.
pub fn convert_with(
    input: &Path,
    output: &Path,
    defines: &[(String, String)],
    animation: Option<&crate::import::gltf_choice::AnimationChoice>,
) -> Result<Converted, LoadError> {
    if !output.extension().is_some_and(|e| e.eq_ignore_ascii_case("toml")) {
        return Err(LoadError::file(output, "convert writes a lamplight scene file, expected a name ending in .toml"));
    }
    let ext = input.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase).unwrap_or_default();
    if crate::import::EXTENSIONS.contains(&ext.as_str()) {
        if !defines.is_empty() {
            return Err(LoadError::file(input, "-D sets parameters of Mitsuba scenes; a mesh file has none"));
        }
        let clip = match animation {
            None => None,
            Some(_) if !crate::import::gltf_choice::is_gltf(input) => {
                return Err(LoadError::file(input, "--animation applies to a glTF file (.gltf, .glb); this file has no animations"))
            }
            Some(choice) => Some(crate::import::gltf_choice::resolve(input, choice, "--animation")?),
        };
        return mesh_file::convert(input, output, clip);
    }
    if ext != "xml" {
        return Err(LoadError::file(
            input,
            format!("convert reads Mitsuba scenes (.xml) and mesh files ({}), not .{ext} files", crate::import::EXTENSIONS.join(", ")),
        ));
    }
    if animation.is_some() {
        return Err(LoadError::file(input, "--animation applies to a glTF file (.gltf, .glb); a Mitsuba scene has no animations"));
    }
    let (mut table, source) = mitsuba::read_table(input, defines)?;
    let from = input.parent().unwrap_or(Path::new(""));
    let to = output.parent().unwrap_or(Path::new(""));
    if !crate::atomic::same_file(&absolute(from), &absolute(to)) {
        relocate(&mut table, &absolute(from));
    }
    let header = format!("Converted from {} by `lamplight convert`.", input.display());
    Ok(Converted { toml: native_writer::write(&table, &header), warnings: source.warnings, files: Vec::new() })
}

fn absolute(dir: &Path) -> std::path::PathBuf {
    let dir = if dir.as_os_str().is_empty() { Path::new(".") } else { dir };
    dir.canonicalize().unwrap_or_else(|_| dir.to_path_buf())
}

/// A file's absolute path (its folder made absolute, the name kept).
fn absolute_file(path: &Path) -> std::path::PathBuf {
    match path.file_name() {
        Some(name) => absolute(path.parent().unwrap_or(Path::new(""))).join(name),
        None => absolute(path),
    }
}

/// Every relative `file` value made absolute against `dir`.
fn relocate(table: &mut Table, dir: &Path) {
    for e in &mut table.entries {
        match &mut e.item.value {
            Value::String(s) if e.key == "file" && Path::new(s.as_str()).is_relative() => *s = dir.join(&*s).to_string_lossy().into_owned(),
            Value::Table(t) => relocate(t, dir),
            Value::Array(items) => {
                for item in items {
                    if let Value::Table(t) = &mut item.value {
                        relocate(t, dir);
                    }
                }
            }
            _ => {}
        }
    }
}
