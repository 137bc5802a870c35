//! PLY (Stanford polygon file) reader: ASCII, binary little-endian and binary
//! big-endian bodies, vertex positions with optional normals (`nx ny nz`),
//! texture coordinates (`u v`, `s t`, `texture_u texture_v` or `texture_s
//! texture_t`) and colours (`red green blue`: integers are sRGB-encoded
//! fractions of their type's maximum, decoded to linear; floats are linear),
//! `face` lists of any length (fan-triangulated: `v0 v(k) v(k+1)`), and
//! `tristrips` lists with `-1` restarts (strip `a b c d ...` gives `abc`, `cbd`,
//! `cde`, ...: every second triangle swaps its first two corners so that all keep
//! the strip's winding; degenerate triangles are kept so counts match the file).
//!
//! Other scalar properties of vertices and faces are kept as the named
//! attributes a Mitsuba `mesh_attribute` reads ([`super::ply_attributes`]).
//!
//! Face `i` of a file whose faces are all triangles is triangle `i` of the mesh,
//! and strips unroll in file order. Other elements and properties are read past
//! and reported as warnings. The `vertex` element must come before the faces
//! (every PLY writer we know does this) so that indices are checked as read.
//!
//! Hand-written rather than the `ply-rs` crate because the importer must (1)
//! report the line and column of a header error and the byte offset (or line
//! and column, for ASCII) of a body error, (2) compare the sizes the header
//! claims with the file's size *before* allocating, so a header claiming 10^12
//! vertices fails at once instead of exhausting memory, (3) stream faces into
//! triangles without a map per element (ply-rs keeps a `HashMap` per vertex,
//! several times slower and larger on the 1M-triangle Igea), and (4) unroll
//! `tristrips`. The format is small enough (a header of `element`/`property`
//! lines, then packed values) that this is a few hundred lines.

use std::path::Path;

use lamplight_core::math::Vec3;

use super::ply_header::{check_sizes, header_lines, parse_header, Element, Format, Property, Scalar};
use super::{Imported, ImportedMesh, MeshData};
use crate::error::LoadError;
use lamplight_core::math::Mat4;

mod bulk;

/// Reads a PLY file's bytes into one mesh with an identity transform.
pub(super) fn parse(path: &Path, bytes: &[u8]) -> Result<Imported, LoadError> {
    let mut warnings = Vec::new();
    let mut mesh = parse_mesh(path, bytes, &mut warnings)?;
    mesh.name = path.file_stem().map(|s| s.to_string_lossy().into_owned());
    Ok(Imported {
        meshes: vec![mesh],
        instances: vec![ImportedMesh { mesh: 0, transform: Mat4::IDENTITY, material: None, material_name: None }],
        warnings,
        ..Imported::default()
    })
}

fn parse_mesh(path: &Path, bytes: &[u8], warnings: &mut Vec<String>) -> Result<MeshData, LoadError> {
    let (format, elements, body_start) = parse_header(path, bytes)?;
    let body = &bytes[body_start..];
    check_sizes(path, format, &elements, body.len())?;
    let mut reader = match format {
        Format::Ascii => Reader::Ascii(AsciiReader::new(body, header_lines(bytes, body_start))),
        Format::Binary { big_endian } => Reader::Binary { bytes, pos: body_start, start_of_last: body_start, big_endian },
    };
    let mut mesh = MeshData::default();
    let mut vertex_count: Option<u64> = None;
    for element in &elements {
        match element.name.as_str() {
            "vertex" => {
                read_vertices(path, &mut reader, element, &mut mesh, warnings)?;
                vertex_count = Some(element.count);
            }
            "face" | "tristrips" => {
                let Some(n) = vertex_count else {
                    return Err(LoadError::at(
                        path,
                        element.line,
                        1,
                        format!("element `{}` comes before element `vertex`; the vertices must come first", element.name),
                    ));
                };
                read_faces(path, &mut reader, element, n, &mut mesh, warnings)?;
            }
            _ => {
                warnings.push(format!("PLY element `{}` ({} items) ignored", element.name, element.count));
                // An element without properties takes no bytes, whatever its count: nothing to skip.
                let count = if element.props.is_empty() { 0 } else { element.count };
                for i in 0..count {
                    for p in &element.props {
                        skip_property(&mut reader, path, p, (&element.name, i))?;
                    }
                }
            }
        }
    }
    if vertex_count.is_none() {
        return Err(LoadError::file(path, "the PLY header declares no `vertex` element"));
    }
    if mesh.indices.is_empty() {
        warnings.push("PLY file has no faces: the mesh has no triangles".to_string());
    }
    Ok(mesh)
}

/// Where a value is read from: ASCII words or packed binary.
enum Reader<'a> {
    Ascii(AsciiReader<'a>),
    Binary { bytes: &'a [u8], pos: usize, start_of_last: usize, big_endian: bool },
}

struct AsciiReader<'a> {
    body: &'a [u8],
    pos: usize,
    line: usize,
    column: usize,
    last: (usize, usize),
}

impl<'a> AsciiReader<'a> {
    fn new(body: &'a [u8], header_lines: usize) -> AsciiReader<'a> {
        AsciiReader { body, pos: 0, line: header_lines + 1, column: 1, last: (header_lines + 1, 1) }
    }

    /// The next whitespace-separated word, or `None` at the end.
    fn word(&mut self) -> Option<&'a [u8]> {
        while let Some(&b) = self.body.get(self.pos) {
            if !b.is_ascii_whitespace() {
                break;
            }
            self.pos += 1;
            if b == b'\n' {
                self.line += 1;
                self.column = 1;
            } else {
                self.column += 1;
            }
        }
        if self.pos >= self.body.len() {
            self.last = (self.line, self.column);
            return None;
        }
        self.last = (self.line, self.column);
        let start = self.pos;
        while let Some(&b) = self.body.get(self.pos) {
            if b.is_ascii_whitespace() {
                break;
            }
            self.pos += 1;
            // Columns count characters: UTF-8 continuation bytes do not start one.
            if b & 0xC0 != 0x80 {
                self.column += 1;
            }
        }
        Some(&self.body[start..self.pos])
    }
}

impl Reader<'_> {
    /// An error at the value read last.
    fn error(&self, path: &Path, message: String) -> LoadError {
        match self {
            Reader::Ascii(a) => LoadError::at(path, a.last.0, a.last.1, message),
            Reader::Binary { start_of_last, .. } => LoadError::byte(path, *start_of_last as u64, message),
        }
    }

    /// Reads one value of type `ty`; `what` names it for messages.
    fn value(&mut self, path: &Path, ty: Scalar, what: &dyn Fn() -> String) -> Result<f64, LoadError> {
        match self {
            Reader::Ascii(a) => {
                let Some(word) = a.word() else {
                    return Err(LoadError::at(
                        path,
                        a.last.0,
                        a.last.1,
                        format!("file ends where {} (a {}) was expected", what(), ty.name()),
                    ));
                };
                let text = String::from_utf8_lossy(word);
                let parsed = match ty.int_range() {
                    Some((lo, hi)) => text.parse::<i64>().ok().filter(|v| (lo..=hi).contains(v)).map(|v| v as f64),
                    None => text.parse::<f64>().ok(),
                };
                parsed.ok_or_else(|| {
                    LoadError::at(path, a.last.0, a.last.1, format!("expected {} (a {}), found `{text}`", what(), ty.name()))
                })
            }
            Reader::Binary { bytes, pos, start_of_last, big_endian } => {
                let size = ty.size();
                *start_of_last = *pos;
                let Some(raw) = bytes.get(*pos..*pos + size) else {
                    return Err(LoadError::byte(
                        path,
                        *pos as u64,
                        format!("file ends in the middle of {}: expected {size} bytes, {} left", what(), bytes.len() - *pos),
                    ));
                };
                *pos += size;
                Ok(decode(raw, ty, *big_endian))
            }
        }
    }

    /// Bytes left in a binary body (`usize::MAX` for ASCII, where lists are read word by word).
    fn remaining(&self) -> usize {
        match self {
            Reader::Ascii(_) => usize::MAX,
            Reader::Binary { bytes, pos, .. } => bytes.len() - *pos,
        }
    }
}

fn decode(raw: &[u8], ty: Scalar, big: bool) -> f64 {
    macro_rules! num {
        ($t:ty, $n:expr) => {{
            let mut a = [0u8; $n];
            a.copy_from_slice(raw);
            (if big { <$t>::from_be_bytes(a) } else { <$t>::from_le_bytes(a) }) as f64
        }};
    }
    match ty {
        Scalar::I8 => raw[0] as i8 as f64,
        Scalar::U8 => raw[0] as f64,
        Scalar::I16 => num!(i16, 2),
        Scalar::U16 => num!(u16, 2),
        Scalar::I32 => num!(i32, 4),
        Scalar::U32 => num!(u32, 4),
        Scalar::F32 => num!(f32, 4),
        Scalar::F64 => num!(f64, 8),
    }
}

/// Reads a list's length, refusing negative counts and (binary) counts that overrun the file.
fn list_len(reader: &mut Reader, path: &Path, p: &Property, count: Scalar, at: (&str, u64)) -> Result<usize, LoadError> {
    let n = reader.value(path, count, &|| format!("the length of list `{}` of {} {}", p.name, at.0, at.1))?;
    if n < 0.0 {
        return Err(reader.error(path, format!("{} {}: list `{}` has negative length {n}", at.0, at.1, p.name)));
    }
    let n = n as usize;
    if n.saturating_mul(p.item.size()) > reader.remaining() {
        let msg = format!("{} {}: list `{}` claims {n} items but the file ends before them", at.0, at.1, p.name);
        return Err(reader.error(path, msg));
    }
    Ok(n)
}

fn skip_property(reader: &mut Reader, path: &Path, p: &Property, at: (&str, u64)) -> Result<(), LoadError> {
    let n = match p.count {
        Some(count) => list_len(reader, path, p, count, at)?,
        None => 1,
    };
    for _ in 0..n {
        reader.value(path, p.item, &|| format!("property `{}` of {} {}", p.name, at.0, at.1))?;
    }
    Ok(())
}

fn read_vertices(path: &Path, reader: &mut Reader, e: &Element, mesh: &mut MeshData, warnings: &mut Vec<String>) -> Result<(), LoadError> {
    if e.count > u64::from(u32::MAX) {
        return Err(LoadError::at(path, e.line, e.count_column, format!("{} vertices are more than a mesh can index (2^32 - 1)", e.count)));
    }
    if bulk::vertices(reader, e, mesh) {
        return Ok(());
    }
    let find = |name: &str| e.props.iter().position(|p| p.name == name && p.count.is_none());
    let mut slot = vec![None; e.props.len()];
    for (axis, name) in ["x", "y", "z"].iter().enumerate() {
        let Some(i) = find(name) else {
            return Err(LoadError::at(path, e.line, 1, format!("element `vertex` has no scalar property `{name}`")));
        };
        slot[i] = Some(axis);
    }
    let normal_slots: Vec<Option<usize>> = ["nx", "ny", "nz"].iter().map(|n| find(n)).collect();
    let has_normals = normal_slots.iter().all(Option::is_some);
    if has_normals {
        for (axis, i) in normal_slots.iter().enumerate() {
            slot[i.unwrap_or_default()] = Some(3 + axis);
        }
    }
    let uv_names = [["u", "v"], ["s", "t"], ["texture_u", "texture_v"], ["texture_s", "texture_t"]];
    let uv_slots = uv_names.iter().map(|[a, b]| (find(a), find(b))).find(|(a, b)| a.is_some() && b.is_some());
    if let Some((Some(a), Some(b))) = uv_slots {
        (slot[a], slot[b]) = (Some(6), Some(7));
    }
    let color_slots: Vec<Option<usize>> = ["red", "green", "blue"].iter().map(|n| find(n)).collect();
    let has_colors = color_slots.iter().all(Option::is_some);
    if has_colors {
        for (k, i) in color_slots.iter().enumerate() {
            slot[i.unwrap_or_default()] = Some(8 + k);
        }
    }
    // The rest, Mitsuba's attributes where they group (their values at slot 11 + property index).
    let rest: Vec<(usize, &str)> =
        e.props.iter().enumerate().filter(|(i, p)| slot[*i].is_none() && p.count.is_none()).map(|(i, p)| (i, p.name.as_str())).collect();
    let (groups, mut ignored) = super::ply_attributes::group("vertex", &rest);
    for g in &groups {
        for &i in &g.props {
            slot[i] = Some(11 + i);
        }
    }
    ignored.extend(e.props.iter().filter(|p| p.count.is_some()).map(|p| p.name.clone()));
    if !ignored.is_empty() {
        warnings.push(format!("PLY vertex properties ignored: {}", ignored.join(", ")));
    }
    let mut named: Vec<Vec<lamplight_core::math::Rgb>> = vec![Vec::new(); groups.len()];
    mesh.positions.reserve_exact(e.count as usize);
    let mut normals = if has_normals { Vec::with_capacity(e.count as usize) } else { Vec::new() };
    let mut uvs = Vec::new();
    let mut colors = Vec::new();
    let mut xyz = vec![0.0; 11 + e.props.len()];
    for v in 0..e.count {
        for (p, s) in e.props.iter().zip(&slot) {
            match s {
                Some(k) => {
                    let value = reader.value(path, p.item, &|| format!("property `{}` of vertex {v}", p.name))?;
                    if !value.is_finite() {
                        return Err(reader.error(path, format!("vertex {v}: `{}` is {value}, expected a finite number", p.name)));
                    }
                    xyz[*k] = match p.item.int_range() {
                        Some((_, max)) if (8..11).contains(k) => lamplight_core::film::srgb_decode(value / max as f64),
                        _ => value,
                    };
                }
                None => skip_property(reader, path, p, ("vertex", v))?,
            }
        }
        mesh.positions.push(Vec3::new(xyz[0], xyz[1], xyz[2]));
        if has_normals {
            normals.push(Vec3::new(xyz[3], xyz[4], xyz[5]));
        }
        if uv_slots.is_some() {
            uvs.push([xyz[6], xyz[7]]);
        }
        if has_colors {
            colors.push(Vec3::new(xyz[8], xyz[9], xyz[10]));
        }
        for (g, values) in groups.iter().zip(&mut named) {
            values.push(g.value(&xyz[11..]));
        }
    }
    mesh.named.extend(groups.into_iter().zip(named).map(|(g, values)| super::NamedAttribute { name: g.name, values }));
    mesh.normals = has_normals.then_some(normals);
    mesh.attributes.uvs = uv_slots.is_some().then_some(uvs);
    mesh.attributes.colors = has_colors.then_some(colors);
    Ok(())
}

fn read_faces(
    path: &Path,
    reader: &mut Reader,
    e: &Element,
    vertex_count: u64,
    mesh: &mut MeshData,
    warnings: &mut Vec<String>,
) -> Result<(), LoadError> {
    if bulk::triangles(reader, e, vertex_count, mesh) {
        return Ok(());
    }
    let strips = e.name == "tristrips";
    let Some(list) = e.props.iter().position(|p| (p.name == "vertex_indices" || p.name == "vertex_index") && p.count.is_some()) else {
        return Err(LoadError::at(path, e.line, 1, format!("element `{}` has no list property `vertex_indices`", e.name)));
    };
    let rest: Vec<(usize, &str)> =
        e.props.iter().enumerate().filter(|(i, p)| *i != list && p.count.is_none()).map(|(i, p)| (i, p.name.as_str())).collect();
    let (groups, mut others) = super::ply_attributes::group("face", &rest);
    others.extend(e.props.iter().enumerate().filter(|(i, p)| *i != list && p.count.is_some()).map(|(_, p)| p.name.clone()));
    if !others.is_empty() {
        warnings.push(format!("PLY {} properties ignored: {}", e.name, others.join(", ")));
    }
    let kept: Vec<bool> = (0..e.props.len()).map(|i| groups.iter().any(|g| g.props.contains(&i))).collect();
    let mut values = vec![0.0; e.props.len()];
    let mut named: Vec<Vec<lamplight_core::math::Rgb>> = vec![Vec::new(); groups.len()];
    if !strips {
        mesh.indices.reserve(e.count as usize);
    }
    let mut short_faces = 0u64;
    let mut corners: Vec<u32> = Vec::new();
    for f in 0..e.count {
        let before = mesh.indices.len();
        for (pi, p) in e.props.iter().enumerate() {
            if kept[pi] {
                let value = reader.value(path, p.item, &|| format!("property `{}` of {} {f}", p.name, e.name))?;
                if !value.is_finite() {
                    return Err(reader.error(path, format!("{} {f}: `{}` is {value}, expected a finite number", e.name, p.name)));
                }
                values[pi] = value;
                continue;
            }
            let Some(count) = p.count.filter(|_| pi == list) else {
                skip_property(reader, path, p, (&e.name, f))?;
                continue;
            };
            let n = list_len(reader, path, p, count, (&e.name, f))?;
            corners.clear();
            let mut strip_start = 0;
            for _ in 0..n {
                let value = reader.value(path, p.item, &|| format!("a vertex index of {} {f}", e.name))?;
                if strips && value == -1.0 {
                    unroll_strip(&corners[strip_start..], &mut mesh.indices);
                    strip_start = corners.len();
                    continue;
                }
                if !(value >= 0.0 && value < vertex_count as f64 && value.fract() == 0.0) {
                    let msg = format!("{} {f}: vertex index {value} out of range (the file has {vertex_count} vertices)", e.name);
                    return Err(reader.error(path, msg));
                }
                corners.push(value as u32);
            }
            if strips {
                unroll_strip(&corners[strip_start..], &mut mesh.indices);
            } else if corners.len() < 3 {
                short_faces += 1;
            } else {
                for k in 1..corners.len() - 1 {
                    mesh.indices.push([corners[0], corners[k], corners[k + 1]]);
                }
            }
        }
        // After the whole face: its attributes may follow its index list.
        for (g, list) in groups.iter().zip(&mut named) {
            list.extend(std::iter::repeat_n(g.value(&values), mesh.indices.len() - before));
        }
    }
    mesh.named.extend(groups.into_iter().zip(named).map(|(g, values)| super::NamedAttribute { name: g.name, values }));
    if short_faces > 0 {
        warnings.push(format!("PLY: {short_faces} faces with fewer than 3 vertices skipped"));
    }
    Ok(())
}

/// Unrolls one triangle strip, keeping the winding of its first triangle.
fn unroll_strip(strip: &[u32], out: &mut Vec<[u32; 3]>) {
    for k in 2..strip.len() {
        if k % 2 == 0 {
            out.push([strip[k - 2], strip[k - 1], strip[k]]);
        } else {
            out.push([strip[k - 1], strip[k - 2], strip[k]]);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn strips_alternate_so_the_winding_is_kept() {
        let mut out = Vec::new();
        unroll_strip(&[0, 1, 2, 3, 4], &mut out);
        assert_eq!(out, vec![[0, 1, 2], [2, 1, 3], [2, 3, 4]]);
    }
}
