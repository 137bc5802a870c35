//! The usual binary layouts read in bulk: vertices of exactly `float x`,
//! `float y`, `float z`, and faces of exactly one `list uchar int` (or `uint`)
//! `vertex_indices`, every one a triangle. Scanned's and subdivided meshes
//! come this way; the general reader decodes each value through the property
//! table, which was a fifth of loading a million-triangle PLY.
//!
//! Each function reads the whole element or nothing: at anything else (a
//! face that is not a triangle, an index out of range, a value that is not
//! finite, a file that ends early) it leaves the reader and the mesh as they
//! were and returns `false`, and the general reader then reads the element
//! and gives the error it always gave. The values are the general reader's:
//! the same decoding (`f32` widened to `f64`), the same fan of a triangle.

use super::{Element, MeshData, Reader, Scalar};
use lamplight_core::math::Vec3;

/// Reads the vertices `e` if they are `float x, y, z`; `false` to leave them
/// to the general reader.
pub(super) fn vertices(reader: &mut Reader, e: &Element, mesh: &mut MeshData) -> bool {
    let Reader::Binary { bytes, pos, start_of_last, big_endian } = reader else { return false };
    let xyz = e.props.len() == 3
        && e.props.iter().zip(["x", "y", "z"]).all(|(p, name)| p.name == name && p.count.is_none() && p.item == Scalar::F32);
    let Some(body) = xyz.then(|| element_bytes(bytes, *pos, e.count, 12)).flatten() else { return false };
    let big = *big_endian;
    let value = |b: &[u8]| {
        let b = [b[0], b[1], b[2], b[3]];
        f64::from(if big { f32::from_be_bytes(b) } else { f32::from_le_bytes(b) })
    };
    let before = mesh.positions.len();
    mesh.positions.reserve_exact(body.len() / 12);
    for v in body.chunks_exact(12) {
        let p = Vec3::new(value(&v[0..4]), value(&v[4..8]), value(&v[8..12]));
        if !p.is_finite() {
            mesh.positions.truncate(before);
            return false;
        }
        mesh.positions.push(p);
    }
    advance(pos, start_of_last, body.len(), 4);
    mesh.normals = None;
    mesh.attributes.uvs = None;
    mesh.attributes.colors = None;
    true
}

/// Reads the faces `e` if they are triangles of `list uchar int|uint
/// vertex_indices` alone, every index below `vertex_count`; `false` to leave
/// them to the general reader.
pub(super) fn triangles(reader: &mut Reader, e: &Element, vertex_count: u64, mesh: &mut MeshData) -> bool {
    let Reader::Binary { bytes, pos, start_of_last, big_endian } = reader else { return false };
    let signed = match e.props.as_slice() {
        [p] if e.name == "face" && (p.name == "vertex_indices" || p.name == "vertex_index") && p.count == Some(Scalar::U8) => {
            match p.item {
                Scalar::I32 => true,
                Scalar::U32 => false,
                _ => return false,
            }
        }
        _ => return false,
    };
    let Some(body) = element_bytes(bytes, *pos, e.count, 13) else { return false };
    let big = *big_endian;
    // An index as the general reader takes it: an `int` must not be negative.
    let index = |b: &[u8]| -> Option<u32> {
        let b = [b[0], b[1], b[2], b[3]];
        let i = match (signed, big) {
            (true, true) => u32::try_from(i32::from_be_bytes(b)).ok()?,
            (true, false) => u32::try_from(i32::from_le_bytes(b)).ok()?,
            (false, true) => u32::from_be_bytes(b),
            (false, false) => u32::from_le_bytes(b),
        };
        (u64::from(i) < vertex_count).then_some(i)
    };
    let before = mesh.indices.len();
    mesh.indices.reserve(body.len() / 13);
    for f in body.chunks_exact(13) {
        let triangle = (f[0] == 3).then(|| Some([index(&f[1..5])?, index(&f[5..9])?, index(&f[9..13])?])).flatten();
        let Some(triangle) = triangle else {
            mesh.indices.truncate(before);
            return false;
        };
        mesh.indices.push(triangle);
    }
    advance(pos, start_of_last, body.len(), 4);
    true
}

/// The `count` records of `size` bytes from `pos`, if the file holds them all.
fn element_bytes(bytes: &[u8], pos: usize, count: u64, size: usize) -> Option<&[u8]> {
    let len = usize::try_from(count).ok()?.checked_mul(size)?;
    (len > 0).then_some(())?;
    bytes.get(pos..pos.checked_add(len)?)
}

/// Moves the reader past `len` bytes whose last value took `last` bytes, as
/// reading them one by one would have left it.
fn advance(pos: &mut usize, start_of_last: &mut usize, len: usize, last: usize) {
    *start_of_last = *pos + len - last;
    *pos += len;
}

#[cfg(test)]
mod tests {
    use super::super::Property;
    use super::*;

    fn element(name: &str, count: u64, props: &[(&str, Option<Scalar>, Scalar)]) -> Element {
        let props = props.iter().map(|&(name, count, item)| Property { name: name.to_string(), count, item }).collect();
        Element { name: name.to_string(), count, props, line: 3, count_column: 16 }
    }

    #[test]
    fn takes_the_usual_layouts_whole_and_leaves_the_rest_untouched() {
        let xyz = element("vertex", 2, &[("x", None, Scalar::F32), ("y", None, Scalar::F32), ("z", None, Scalar::F32)]);
        let values: Vec<u8> = [1.0f32, 2.0, 3.0, -4.0, 0.5, 6.0].iter().flat_map(|v| v.to_le_bytes()).collect();
        let mut bytes = b"head".to_vec();
        bytes.extend(&values);
        let mut reader = Reader::Binary { bytes: &bytes, pos: 4, start_of_last: 4, big_endian: false };
        let mut mesh = MeshData::default();
        assert!(vertices(&mut reader, &xyz, &mut mesh));
        assert_eq!(mesh.positions, vec![Vec3::new(1.0, 2.0, 3.0), Vec3::new(-4.0, 0.5, 6.0)]);
        assert!(matches!(reader, Reader::Binary { pos: 28, start_of_last: 24, .. }));

        // Doubles, one value too few, or an infinity: left to the general reader.
        let doubles = element("vertex", 1, &[("x", None, Scalar::F64), ("y", None, Scalar::F32), ("z", None, Scalar::F32)]);
        let three = element("vertex", 3, &xyz.props.iter().map(|p| (p.name.as_str(), p.count, p.item)).collect::<Vec<_>>());
        let mut infinite = bytes.clone();
        infinite[8..12].copy_from_slice(&f32::INFINITY.to_le_bytes());
        for (e, bytes) in [(&doubles, &bytes), (&three, &bytes), (&xyz, &infinite)] {
            let mut reader = Reader::Binary { bytes, pos: 4, start_of_last: 4, big_endian: false };
            let mut mesh = MeshData::default();
            assert!(!vertices(&mut reader, e, &mut mesh));
            assert!(mesh.positions.is_empty() && matches!(reader, Reader::Binary { pos: 4, start_of_last: 4, .. }));
        }

        let faces = element("face", 2, &[("vertex_indices", Some(Scalar::U8), Scalar::I32)]);
        let mut bytes = vec![3];
        bytes.extend([0i32, 1, 2].iter().flat_map(|i| i.to_be_bytes()));
        bytes.push(3);
        bytes.extend([2i32, 1, 0].iter().flat_map(|i| i.to_be_bytes()));
        let mut reader = Reader::Binary { bytes: &bytes, pos: 0, start_of_last: 0, big_endian: true };
        let mut mesh = MeshData::default();
        assert!(triangles(&mut reader, &faces, 3, &mut mesh));
        assert_eq!(mesh.indices, vec![[0, 1, 2], [2, 1, 0]]);
        assert!(matches!(reader, Reader::Binary { pos: 26, start_of_last: 22, .. }));
        // An index out of range, a quad, a strip: left to the general reader.
        let mut quad = bytes.clone();
        quad[13] = 4;
        let strips = element("tristrips", 2, &[("vertex_indices", Some(Scalar::U8), Scalar::I32)]);
        for (e, bytes, vertex_count) in [(&faces, &bytes, 2), (&faces, &quad, 3), (&strips, &bytes, 3)] {
            let mut reader = Reader::Binary { bytes, pos: 0, start_of_last: 0, big_endian: true };
            let mut mesh = MeshData::default();
            assert!(!triangles(&mut reader, e, vertex_count, &mut mesh));
            assert!(mesh.indices.is_empty() && matches!(reader, Reader::Binary { pos: 0, start_of_last: 0, .. }));
        }
    }
}
