//! Mitsuba's `.serialized` meshes: a file of zlib-compressed shapes.
//!
//! Each shape starts with `u16 0x041C` and `u16` version (3 or 4), then a zlib
//! stream of: `u32` flags (`0x0001` normals, `0x0002` texture coordinates,
//! `0x0008` vertex colours, `0x2000` doubles), a NUL-terminated name (version 4),
//! `u64` vertex and `u64` triangle counts, the positions, normals, texture
//! coordinates and colours (`f32` or `f64` each), then the triangles' indices
//! (`u32`, or `u64` above 2^32 vertices). The file ends with the shapes' byte
//! offsets (`u64`, `u32` in version 3) and the `u32` shape count. All little-endian.

use std::io::Read;
use std::path::Path;

use lamplight_core::params::{Item, Loc, Value};

use super::{num, table_of};

/// Most vertices or triangles of one mesh.
pub const MAX_ELEMENTS: u64 = 1 << 24;
/// Largest file read, in bytes.
pub const MAX_FILE_BYTES: u64 = 1 << 30;
/// Longest shape name (version 4), in bytes.
pub const MAX_NAME_BYTES: usize = 4096;

/// A mesh read from a `.serialized` file.
#[derive(Debug, PartialEq)]
pub struct Mesh {
    /// Vertex positions.
    pub positions: Vec<[f64; 3]>,
    /// Per-vertex normals, if stored.
    pub normals: Option<Vec<[f64; 3]>>,
    /// Triangles.
    pub indices: Vec<[u32; 3]>,
}

impl Mesh {
    /// The mesh as an inline `[meshes]` table.
    pub fn table(&self, loc: &Loc, shading: Item) -> Item {
        let list = |rows: Vec<Item>| Item { value: Value::Array(rows), loc: loc.clone() };
        let row = |v: &[f64]| Item { value: Value::Array(v.iter().map(|&x| num(x, loc)).collect()), loc: loc.clone() };
        let mut pairs = vec![
            ("positions", list(self.positions.iter().map(|p| row(p)).collect())),
            (
                "indices",
                list(
                    self.indices
                        .iter()
                        .map(|t| Item {
                            value: Value::Array(t.iter().map(|&i| Item { value: Value::Integer(i as i64), loc: loc.clone() }).collect()),
                            loc: loc.clone(),
                        })
                        .collect(),
                ),
            ),
        ];
        if let Some(n) = &self.normals {
            pairs.push(("normals", list(n.iter().map(|p| row(p)).collect())));
        }
        pairs.push(("shading", shading));
        table_of(pairs, loc)
    }
}

struct Cursor<'a> {
    data: &'a [u8],
    at: usize,
}

impl Cursor<'_> {
    fn take(&mut self, n: usize) -> Result<&[u8], String> {
        let end = self.at.checked_add(n).filter(|&e| e <= self.data.len()).ok_or("the mesh data ends early")?;
        let s = &self.data[self.at..end];
        self.at = end;
        Ok(s)
    }
    fn u32(&mut self) -> Result<u32, String> {
        Ok(u32::from_le_bytes(self.take(4)?.try_into().expect("4 bytes")))
    }
    fn u64(&mut self) -> Result<u64, String> {
        Ok(u64::from_le_bytes(self.take(8)?.try_into().expect("8 bytes")))
    }
    fn real(&mut self, double: bool) -> Result<f64, String> {
        Ok(if double {
            f64::from_le_bytes(self.take(8)?.try_into().expect("8 bytes"))
        } else {
            f32::from_le_bytes(self.take(4)?.try_into().expect("4 bytes")) as f64
        })
    }
}

/// Reads shape `index` of the file at `path`; its bytes and the mesh are taken
/// from the memory budget ([`crate::memory`]) before they are allocated.
pub fn read(path: &Path, index: i64) -> Result<Mesh, String> {
    let name = path.display();
    let (file, len) =
        crate::input::open_regular(path, MAX_FILE_BYTES).map_err(|r| format!("\"{name}\" {}", r.describe("a .serialized file")))?;
    crate::memory::reserve(len, || format!("reading \"{name}\" ({len} bytes)")).map_err(|e| e.to_string())?;
    let bytes =
        crate::input::read_opened(file, len, MAX_FILE_BYTES).map_err(|r| format!("\"{name}\" {}", r.describe("a .serialized file")));
    let mesh = bytes.and_then(|bytes| parse_named(&bytes, index, &name.to_string()));
    crate::memory::release(len);
    mesh
}

/// Shape `index` of a `.serialized` file's bytes.
pub fn parse(bytes: &[u8], index: i64) -> Result<Mesh, String> {
    parse_named(bytes, index, "the .serialized file")
}

/// What the mesh data after the counts holds, in bytes, as the header declares it.
fn declared_body(flags: u32, vertices: u64, triangles: u64) -> u64 {
    let real = if flags & 0x2000 != 0 { 8 } else { 4 };
    let mut per_vertex = 3;
    for (flag, reals) in [(0x0001, 3), (0x0002, 2), (0x0008, 3)] {
        if flags & flag != 0 {
            per_vertex += reals;
        }
    }
    let index = if vertices > u32::MAX as u64 { 8 } else { 4 };
    vertices * per_vertex * real + triangles * 3 * index
}

/// The memory a mesh of `vertices` and `triangles` takes once read: its arrays,
/// the inline table the scene holds it as (one [`Item`] per number and per row),
/// and the core mesh with its BVH (about 64 bytes a triangle).
pub fn mesh_bytes(vertices: u64, triangles: u64, normals: bool) -> u64 {
    let item = std::mem::size_of::<Item>() as u64;
    let vertex_rows = if normals { 2 } else { 1 };
    let arrays = vertices * 24 * vertex_rows + triangles * 12;
    let table = (vertices * vertex_rows + triangles) * 4 * item;
    let core = vertices * 24 * vertex_rows + triangles * (12 + 64);
    arrays + table + core
}

/// [`parse`], `name` naming the file in budget messages.
fn parse_named(bytes: &[u8], index: i64, name: &str) -> Result<Mesh, String> {
    if bytes.len() < 8 {
        return Err("not a Mitsuba .serialized file (too short)".into());
    }
    let count = u32::from_le_bytes(bytes[bytes.len() - 4..].try_into().expect("4 bytes")) as i64;
    if index < 0 || index >= count.max(1) {
        return Err(format!("shape_index {index} is out of range (the file has {count} shapes)"));
    }
    let version = u16::from_le_bytes([bytes[2], bytes[3]]);
    let start = if index == 0 {
        0
    } else {
        let wide = version >= 4;
        let size = if wide { 8 } else { 4 };
        let table_at = (bytes.len() - 4).checked_sub(count as usize * size).ok_or("the shape table is cut short")?;
        let at = table_at + index as usize * size;
        if wide {
            u64::from_le_bytes(bytes[at..at + 8].try_into().expect("8 bytes")) as usize
        } else {
            u32::from_le_bytes(bytes[at..at + 4].try_into().expect("4 bytes")) as usize
        }
    };
    let head = start.checked_add(4).and_then(|end| bytes.get(start..end)).ok_or("a shape offset points past the end")?;
    if u16::from_le_bytes([head[0], head[1]]) != 0x041C {
        return Err("not a Mitsuba .serialized file (no 0x041C header)".into());
    }
    let version = u16::from_le_bytes([head[2], head[3]]);
    if !(3..=4).contains(&version) {
        return Err(format!("unsupported .serialized version {version}, expected 3 or 4"));
    }
    let damaged = |e: std::io::Error| format!("the compressed mesh data is damaged: {e}");
    let mut stream = flate2::read::ZlibDecoder::new(&bytes[start + 4..]);
    // The header: flags, the name (version 4) and the two counts, read a piece
    // at a time so that nothing is inflated before the sizes are known.
    let mut word = [0u8; 8];
    let exact = |stream: &mut flate2::read::ZlibDecoder<&[u8]>, out: &mut [u8]| {
        stream.read_exact(out).map_err(|e| {
            if e.kind() == std::io::ErrorKind::UnexpectedEof {
                "the mesh data ends early".to_string()
            } else {
                damaged(e)
            }
        })
    };
    exact(&mut stream, &mut word[..4])?;
    let flags = u32::from_le_bytes(word[..4].try_into().expect("4 bytes"));
    if version == 4 {
        let mut length = 0;
        loop {
            exact(&mut stream, &mut word[..1])?;
            if word[0] == 0 {
                break;
            }
            length += 1;
            if length > MAX_NAME_BYTES {
                return Err(format!("the shape's name is longer than {MAX_NAME_BYTES} bytes, expected a NUL-terminated name"));
            }
        }
    }
    exact(&mut stream, &mut word)?;
    let vertices = u64::from_le_bytes(word);
    exact(&mut stream, &mut word)?;
    let triangles = u64::from_le_bytes(word);
    if vertices > MAX_ELEMENTS || triangles > MAX_ELEMENTS {
        return Err(format!("{vertices} vertices and {triangles} triangles, expected at most {MAX_ELEMENTS} each"));
    }
    // Inflate against the declared size: never more than the header says.
    let body = declared_body(flags, vertices, triangles);
    let normals_stored = flags & 0x0001 != 0;
    let needed = body + mesh_bytes(vertices, triangles, normals_stored);
    crate::memory::reserve(needed, || format!("\"{name}\": a mesh of {vertices} vertices and {triangles} triangles"))
        .map_err(|e| e.to_string())?;
    let mut data = Vec::with_capacity(body as usize);
    let inflated = (&mut stream).take(body + 1).read_to_end(&mut data).map_err(damaged);
    let data = match inflated {
        Err(e) => Err(e),
        Ok(_) if data.len() as u64 > body => Err(format!(
            "the compressed mesh data holds more than the {body} bytes its header declares ({vertices} vertices, {triangles} triangles)"
        )),
        Ok(_) if (data.len() as u64) < body => {
            Err(format!("the mesh data ends early: {} of the {body} bytes its header declares", data.len()))
        }
        Ok(_) => Ok(data),
    };
    let mesh = data.and_then(|data| mesh_of(&data, flags, vertices, triangles));
    // The inflated bytes are freed here; the mesh keeps the rest of its share.
    crate::memory::release(body);
    mesh
}

/// The mesh of the inflated data after the counts.
fn mesh_of(data: &[u8], flags: u32, vertices: u64, triangles: u64) -> Result<Mesh, String> {
    let mut c = Cursor { data, at: 0 };
    let double = flags & 0x2000 != 0;
    let vec3s = |c: &mut Cursor<'_>, n: u64| -> Result<Vec<[f64; 3]>, String> {
        (0..n).map(|_| Ok([c.real(double)?, c.real(double)?, c.real(double)?])).collect()
    };
    let positions = vec3s(&mut c, vertices)?;
    let normals = if flags & 0x0001 != 0 { Some(vec3s(&mut c, vertices)?) } else { None };
    if flags & 0x0002 != 0 {
        for _ in 0..vertices * 2 {
            c.real(double)?;
        }
    }
    if flags & 0x0008 != 0 {
        for _ in 0..vertices * 3 {
            c.real(double)?;
        }
    }
    let wide = vertices > u32::MAX as u64;
    let mut indices = Vec::with_capacity(triangles as usize);
    for _ in 0..triangles {
        let mut t = [0u32; 3];
        for i in &mut t {
            let v = if wide { c.u64()? } else { c.u32()? as u64 };
            if v >= vertices {
                return Err(format!("a triangle names vertex {v}, expected below {vertices}"));
            }
            *i = v as u32;
        }
        indices.push(t);
    }
    if positions.iter().flatten().any(|v| !v.is_finite()) {
        return Err("a vertex position is not finite".into());
    }
    Ok(Mesh { positions, normals, indices })
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::io::Write;

    /// A version-4 file of one triangle, as Mitsuba writes it.
    pub fn one_triangle() -> Vec<u8> {
        let mut body = Vec::new();
        body.extend(0x0001u32.to_le_bytes());
        body.extend(b"tri\0");
        body.extend(3u64.to_le_bytes());
        body.extend(1u64.to_le_bytes());
        for p in [[0f32, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]] {
            for v in p {
                body.extend(v.to_le_bytes());
            }
        }
        for _ in 0..3 {
            for v in [0f32, 0.0, 1.0] {
                body.extend(v.to_le_bytes());
            }
        }
        for i in [0u32, 1, 2] {
            body.extend(i.to_le_bytes());
        }
        let mut z = flate2::write::ZlibEncoder::new(Vec::new(), flate2::Compression::default());
        z.write_all(&body).unwrap();
        let mut file = vec![0x1C, 0x04, 4, 0];
        file.extend(z.finish().unwrap());
        file.extend(0u64.to_le_bytes());
        file.extend(1u32.to_le_bytes());
        file
    }

    #[test]
    fn reads_a_triangle_with_normals() {
        let mesh = parse(&one_triangle(), 0).unwrap();
        assert_eq!(mesh.positions, vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]);
        assert_eq!(mesh.normals, Some(vec![[0.0, 0.0, 1.0]; 3]));
        assert_eq!(mesh.indices, vec![[0, 1, 2]]);
    }

    #[test]
    fn damaged_files_are_errors() {
        let file = one_triangle();
        assert_eq!(parse(&file, 1).unwrap_err(), "shape_index 1 is out of range (the file has 1 shapes)");
        assert_eq!(parse(&file[..6], 0).unwrap_err(), "not a Mitsuba .serialized file (too short)");
        let mut cut = file[..file.len() - 30].to_vec();
        cut.extend(1u32.to_le_bytes());
        assert!(parse(&cut, 0).is_err());
        let mut bad = file.clone();
        bad[0] = 0;
        assert_eq!(parse(&bad, 0).unwrap_err(), "not a Mitsuba .serialized file (no 0x041C header)");
    }
}
