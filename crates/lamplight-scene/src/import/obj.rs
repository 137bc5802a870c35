//! Wavefront OBJ reader with MTL materials (mapping in [`super::mtl`]).
//!
//! Reads `v` (positions), `vn` (normals), `vt` (texture coordinates), `f` (polygons of any size in the forms
//! `v`, `v/vt`, `v//vn`, `v/vt/vn`, with 1-based or negative, relative indices),
//! `o`/`g` (names), `usemtl` and `mtllib`. Polygons are fan-triangulated
//! (`v0 v(k) v(k+1)`). Every run of faces with one object/group name and one
//! material becomes one mesh, in file order, so merging the meshes
//! ([`super::load_mesh`]) keeps the file's face order. A mesh has normals (texture
//! coordinates) when every corner of its faces names one; a `vt` keeps its
//! `(u, v)` as they are (OBJ's `v = 0` is the image's bottom row, the
//! convention of lamplight's textures). Lines, points,
//! free-form geometry and unknown statements are reported once each as
//! warnings; smoothing groups (`s`) only matter with normals and are skipped.
//! A `mtllib` whose file is missing (downloaded OBJs often come without it) is
//! a warning, and its materials are the default one; an MTL that is there but
//! broken is an error at its line.
//! A file with a single run of faces keeps the file's vertex numbering (see
//! `keep_file_numbering`); otherwise each mesh holds only the vertices it uses.
//!
//! Hand-written rather than the `tobj` crate: tobj's `LoadError` is a bare enum
//! (`PositionParseError`, `FaceParseError`, ...) with no line or column and no
//! file name for a broken `.mtl`, while this importer must name all three. OBJ is
//! line-based and small enough that the parser is shorter than the glue would be.

use std::collections::HashMap;
use std::path::Path;

use rustc_hash::FxHashMap;

use lamplight_core::materials::Material;
use lamplight_core::math::{Mat4, Vec3};

use super::{mtl, number, words_into, Imported, ImportedMesh, MeshData, Warnings};
use crate::error::LoadError;

/// One run of faces being built: its own vertices, remapped from the file's.
#[derive(Default)]
struct Group {
    name: Option<String>,
    material: Option<String>,
    mesh: MeshData,
    normals: Vec<Vec3>,
    uvs: Vec<[f64; 2]>,
    all_corners_have_normals: bool,
    all_corners_have_uvs: bool,
    /// File corner -> index in this mesh.
    /// Corner -> vertex: FxHash, as the keys are three small integers from the
    /// file and no one can pick them to collide to any effect but slowness.
    remap: FxHashMap<Corner, u32>,
    /// Index in this mesh -> file corner.
    origin: Vec<Corner>,
}

/// A face corner's 0-based file indices of position, texture coordinate and
/// normal, `u32::MAX` for none.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
struct Corner {
    v: u32,
    t: u32,
    n: u32,
}

impl Group {
    fn new(name: Option<String>, material: Option<String>) -> Group {
        Group { name, material, all_corners_have_normals: true, all_corners_have_uvs: true, ..Group::default() }
    }
}

/// Reads an OBJ file's text; `.mtl` files are read relative to `path`'s folder.
pub(super) fn parse(path: &Path, bytes: &[u8]) -> Result<Imported, LoadError> {
    let text = String::from_utf8_lossy(bytes);
    let mut warnings = Warnings::default();
    // A `mtllib` whose file is missing was warned about once; its `usemtl`s are not.
    let mut missing_library = false;
    let mut positions: Vec<Vec3> = Vec::new();
    let mut normals: Vec<Vec3> = Vec::new();
    let mut uvs: Vec<[f64; 2]> = Vec::new();
    let mut materials: HashMap<String, Material> = HashMap::new();
    let mut image_sources = Vec::new();
    let mut done: Vec<Group> = Vec::new();
    let mut group = Group::new(None, None);
    let mut corners: Vec<Corner> = Vec::new();
    // One buffer of words for all lines: a new vector per line was an
    // allocation per vertex and face.
    let mut w = Vec::new();
    for (line_index, raw) in text.lines().enumerate() {
        let line_no = line_index + 1;
        let line = raw.split('#').next().unwrap_or("");
        words_into(line, &mut w);
        let Some(&(_, keyword)) = w.first() else { continue };
        let num = |i: usize, what: &str| number(path, line_no, line, &w, i, what);
        match keyword {
            "v" => positions.push(Vec3::new(num(1, "x")?, num(2, "y")?, num(3, "z")?)),
            "vn" => normals.push(Vec3::new(num(1, "normal x")?, num(2, "normal y")?, num(3, "normal z")?)),
            // `vt u [v [w]]`: v defaults to 0 and w (3D textures) is not used.
            "vt" => uvs.push([num(1, "texture u")?, if w.len() > 2 { num(2, "texture v")? } else { 0.0 }]),
            "f" => {
                if w.len() < 4 {
                    return Err(LoadError::at(path, line_no, w[0].0, format!("a face needs at least 3 vertices, found {}", w.len() - 1)));
                }
                corners.clear();
                for &(column, word) in &w[1..] {
                    let corner = parse_corner(word, positions.len(), uvs.len(), normals.len())
                        .map_err(|message| LoadError::at(path, line_no, column, format!("face corner `{word}`: {message}")))?;
                    corners.push(corner);
                }
                add_face(&mut group, &corners, &positions, &uvs, &normals);
            }
            "o" | "g" | "usemtl" => {
                let rest = line.trim_start()[keyword.len()..].trim();
                let (name, material) = match keyword {
                    "usemtl" => {
                        if !materials.contains_key(rest) && !missing_library {
                            warnings.once(format!("OBJ material `{rest}` is defined by no `mtllib` read so far: no material used"));
                        }
                        (group.name.clone(), Some(rest.to_string()))
                    }
                    _ => ((!rest.is_empty()).then(|| rest.to_string()), group.material.clone()),
                };
                let next = Group::new(name, material);
                done.push(std::mem::replace(&mut group, next));
            }
            "mtllib" => {
                for &(column, file) in &w[1..] {
                    let mtl_path = path.parent().unwrap_or(Path::new("")).join(file);
                    if matches!(std::fs::symlink_metadata(&mtl_path), Err(e) if e.kind() == std::io::ErrorKind::NotFound) {
                        // Downloaded OBJs often come without their MTL: render
                        // with the default material, as a missing map_Kd does.
                        warnings.once(format!(
                            "{}:{line_no}:{column}: material library `{}` not found: its materials are the default material",
                            path.display(),
                            mtl_path.display()
                        ));
                        missing_library = true;
                        continue;
                    }
                    let bytes = super::read_file(&mtl_path).map_err(|e| {
                        LoadError::at(
                            path,
                            line_no,
                            column,
                            format!("cannot read material library `{}`: {}", mtl_path.display(), e.message),
                        )
                    })?;
                    materials.extend(mtl::parse(&mtl_path, &String::from_utf8_lossy(&bytes), &mut warnings, &mut image_sources)?);
                }
            }
            "s" => {}
            "l" | "p" => warnings.once(format!("OBJ {} elements ignored", if keyword == "l" { "line" } else { "point" })),
            _ => warnings.once(format!("OBJ statement `{keyword}` ignored")),
        }
    }
    done.push(group);
    done.retain(|g| !g.mesh.indices.is_empty());
    if let [single] = done.as_mut_slice() {
        keep_file_numbering(single, &positions, &uvs, &normals);
    }
    let mut imported = Imported { warnings: warnings.into_vec(), images: image_sources, ..Imported::default() };
    for g in done {
        let mut mesh = g.mesh;
        mesh.name = g.name;
        if g.all_corners_have_normals {
            mesh.normals = Some(g.normals);
        }
        if g.all_corners_have_uvs {
            mesh.attributes.uvs = Some(g.uvs);
        }
        let material = g.material.as_ref().and_then(|m| materials.get(m).cloned());
        let material_name = if material.is_some() { g.material } else { None };
        imported.instances.push(ImportedMesh { mesh: imported.meshes.len(), transform: Mat4::IDENTITY, material, material_name });
        imported.meshes.push(mesh);
    }
    if imported.meshes.is_empty() {
        imported.warnings.push("OBJ file has no faces: nothing to render".to_string());
    }
    Ok(imported)
}

/// A file of one group keeps the file's vertex numbering (vertex `i` of the mesh is
/// `v` line `i`, unused ones included) when its corners name no normals (texture
/// coordinates), or each names the one of the same number, so that tools can
/// refer to file indices.
fn keep_file_numbering(group: &mut Group, positions: &[Vec3], uvs: &[[f64; 2]], normals: &[Vec3]) {
    let no_normals = group.origin.iter().all(|c| c.n == u32::MAX);
    let paired = normals.len() == positions.len() && group.origin.iter().all(|c| c.v == c.n);
    let no_uvs = group.origin.iter().all(|c| c.t == u32::MAX);
    let uvs_paired = uvs.len() == positions.len() && group.origin.iter().all(|c| c.v == c.t);
    if !((no_normals || paired) && (no_uvs || uvs_paired)) {
        return;
    }
    for t in &mut group.mesh.indices {
        *t = t.map(|i| group.origin[i as usize].v);
    }
    group.mesh.positions = positions.to_vec();
    group.normals = if paired { normals.to_vec() } else { Vec::new() };
    group.all_corners_have_normals = paired;
    group.uvs = if uvs_paired { uvs.to_vec() } else { Vec::new() };
    group.all_corners_have_uvs = uvs_paired;
}

/// `v`, `v/vt`, `v//vn` or `v/vt/vn` -> 0-based indices, `u32::MAX` for none.
fn parse_corner(word: &str, n_positions: usize, n_uvs: usize, n_normals: usize) -> Result<Corner, String> {
    let mut parts = word.split('/');
    let v = resolve(parts.next().unwrap_or(""), n_positions, "vertex")?;
    let t = match parts.next() {
        Some(s) if !s.is_empty() => resolve(s, n_uvs, "texture coordinate")?,
        _ => u32::MAX,
    };
    let n = match parts.next() {
        Some(s) if !s.is_empty() => resolve(s, n_normals, "normal")?,
        _ => u32::MAX,
    };
    if parts.next().is_some() {
        return Err("expected at most 3 indices separated by `/`".to_string());
    }
    Ok(Corner { v, t, n })
}

/// An OBJ index (1-based, or negative counting back from the last one read) -> 0-based.
fn resolve(text: &str, count: usize, what: &str) -> Result<u32, String> {
    let Ok(i) = text.parse::<i64>() else {
        return Err(format!("expected an integer {what} index, found `{text}`"));
    };
    let count = count as i64;
    let plural = match what {
        "vertex" => "vertices",
        "normal" => "normals",
        _ => "texture coordinates",
    };
    let zero_based = if i > 0 { i - 1 } else { count + i };
    if i == 0 || zero_based < 0 || zero_based >= count || zero_based >= i64::from(u32::MAX) {
        return Err(format!("{what} index {i} out of range ({count} {plural} defined so far)"));
    }
    Ok(zero_based as u32)
}

fn add_face(group: &mut Group, corners: &[Corner], positions: &[Vec3], uvs: &[[f64; 2]], normals: &[Vec3]) {
    let mut local = [0u32; 3];
    let index_of = |group: &mut Group, c: Corner| -> u32 {
        if c.n == u32::MAX {
            group.all_corners_have_normals = false;
        }
        if c.t == u32::MAX {
            group.all_corners_have_uvs = false;
        }
        let next = group.mesh.positions.len() as u32;
        *group.remap.entry(c).or_insert_with(|| {
            group.mesh.positions.push(positions[c.v as usize]);
            group.normals.push(normals.get(c.n as usize).copied().unwrap_or(Vec3::ZERO));
            group.uvs.push(uvs.get(c.t as usize).copied().unwrap_or([0.0, 0.0]));
            group.origin.push(c);
            next
        })
    };
    local[0] = index_of(group, corners[0]);
    let mut previous = index_of(group, corners[1]);
    for &corner in &corners[2..] {
        let current = index_of(group, corner);
        local[1] = previous;
        local[2] = current;
        group.mesh.indices.push(local);
        previous = current;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn negative_indices_count_back() {
        assert_eq!(resolve("-1", 4, "vertex"), Ok(3));
        assert_eq!(resolve("4", 4, "vertex"), Ok(3));
        assert!(resolve("0", 4, "vertex").is_err());
        assert!(resolve("-5", 4, "vertex").is_err());
        assert_eq!(parse_corner("2//-1", 3, 0, 2), Ok(Corner { v: 1, t: u32::MAX, n: 1 }));
        assert_eq!(parse_corner("2/7", 3, 7, 0), Ok(Corner { v: 1, t: 6, n: u32::MAX }));
        assert!(parse_corner("2/7", 3, 0, 0).unwrap_err().contains("texture coordinate index 7 out of range"));
    }
}
