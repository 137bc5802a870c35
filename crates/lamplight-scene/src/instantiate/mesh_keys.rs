//! A mesh asset's keys (`[meshes.NAME]`): the parameter table, how a mesh
//! file's shading normals are made, and a mesh given inline by its
//! positions and indices.

use std::sync::Arc;

use lamplight_core::math::Mat4;
use lamplight_core::params::{ParamResult, Params};
use lamplight_core::shapes::TriangleMesh;

use super::nodes::Asset;

/// The keys of `[meshes.NAME]`.
pub const MESH_PARAMS: &[lamplight_core::params::Param] = {
    use lamplight_core::params::{Param, ParamType as T};
    &[
        Param::new(
            "file",
            T::String,
            "",
            "",
            "an OBJ, PLY, glTF or GLB file: an absolute path, or one relative to the scene file's folder (a dict's `base_dir`)",
        ),
        Param::new("positions", T::Array, "", "", "inline vertex positions, `[x, y, z]` each"),
        Param::new("indices", T::Array, "", "", "inline triangles, `[i, j, k]` vertex indices from 0"),
        Param::new("normals", T::Array, "none", "", "inline per-vertex normals"),
        Param::new(
            "shading",
            T::String,
            "\"file\"",
            "",
            "`\"file\"`: the file's normals, flat where it has none; `\"smooth\"`: the file's, else angle-weighted vertex normals (Mitsuba's default, Blender's Shade Smooth); `\"flat\"`: face normals, the file's ignored (Mitsuba's face_normals)",
        ),
        Param::new(
            "color",
            T::String,
            "the file's colours",
            "",
            "the PLY attribute that is the mesh's colour (its `vertex_color` texture), as Mitsuba names it: `\"vertex_NAME\"` interpolated, `\"face_NAME\"` constant per face (a one-channel attribute is a grey)",
        ),
        Param::new(
            "animation",
            // Any value: a string, a whole number or false ([`mesh_animation::read`] checks it).
            T::Table,
            "the first",
            "a name, an index or `false`",
            "a glTF file's animation that plays, at the scene's time in seconds (`[animation]`): its name (`\"Walk\"`) or index (`2`), or `false` for the rest pose; without `[animation]` the glTF stands at its time 0",
        ),
    ]
};

/// How a mesh file's shading normals are made (`[meshes.NAME] shading`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub(super) enum Shading {
    /// The file's normals; flat where it has none.
    File,
    /// The file's normals; angle-weighted vertex normals where it has none.
    Smooth,
    /// Face normals, whatever the file has.
    Flat,
}

impl Shading {
    pub(super) fn read(p: &mut Params<'_>) -> ParamResult<Shading> {
        Ok(match p.choice("shading", &["file", "smooth", "flat"])? {
            "smooth" => Shading::Smooth,
            "flat" => Shading::Flat,
            _ => Shading::File,
        })
    }

    /// The normals a mesh of `positions` and `indices` is shaded with, given the file's.
    pub(super) fn normals(
        self,
        positions: &[lamplight_core::math::Vec3],
        indices: &[[u32; 3]],
        file: Option<Vec<lamplight_core::math::Vec3>>,
    ) -> Option<Vec<lamplight_core::math::Vec3>> {
        match (self, file) {
            (Shading::Flat, _) => None,
            (_, Some(n)) => Some(n),
            (Shading::File, None) => None,
            // An index out of range is the mesh's error to report, not a panic here.
            (Shading::Smooth, None) if indices.iter().flatten().all(|&i| (i as usize) < positions.len()) => {
                Some(TriangleMesh::angle_weighted_normals(positions, indices))
            }
            (Shading::Smooth, None) => None,
        }
    }
}

/// A mesh given inline by `positions` and `indices` (and `normals`): one part, unplaced.
pub(super) fn inline(p: &mut Params<'_>) -> ParamResult<Asset> {
    let positions = p.vec3_list("positions")?.unwrap_or_default();
    let indices = indices(p)?.ok_or_else(|| p.error("inline mesh needs `indices`"))?;
    let normals = p.vec3_list("normals")?;
    let normals = Shading::read(p)?.normals(&positions, &indices, normals);
    let mesh = TriangleMesh::new(positions, indices, normals).map_err(|e| p.error(e))?;
    Ok(Arc::new(vec![(Arc::new(mesh), Mat4::IDENTITY, None, None)]))
}

/// `indices`: triangles of vertex indices, each below 2^32.
fn indices(p: &mut Params<'_>) -> ParamResult<Option<Vec<[u32; 3]>>> {
    use lamplight_core::params::Value;
    let Some(item) = p.item("indices") else { return Ok(None) };
    let bad = || p.key_error("indices", "expected an array of [i, j, k] (whole numbers from 0 to 4294967295)");
    let Value::Array(faces) = &item.value else { return Err(bad()) };
    faces
        .iter()
        .map(|face| match &face.value {
            Value::Array(v) if v.len() == 3 => {
                let mut out = [0u32; 3];
                for (o, i) in out.iter_mut().zip(v) {
                    *o = match i.value {
                        Value::Integer(i) if (0..=u32::MAX as i64).contains(&i) => i as u32,
                        _ => return Err(bad()),
                    };
                }
                Ok(out)
            }
            _ => Err(bad()),
        })
        .collect::<ParamResult<Vec<_>>>()
        .map(Some)
}
