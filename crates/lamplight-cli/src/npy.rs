//! Just enough of NumPy's `.npy` format (version 1-3) for `lamplight raycast`:
//! read C-ordered little-endian `(N, 3)` arrays of `f32`/`f64` or integer indices,
//! write `(N,)` arrays of `f32` and `i64`.
//!
//! A file is the magic `\x93NUMPY`, a version byte pair, the header length (u16 in
//! version 1, u32 after), a Python dict literal
//! `{'descr': '<f4', 'fortran_order': False, 'shape': (N, 3), }` padded with spaces
//! and a newline so the data starts 64-byte aligned, then the raw data.

use std::fs;
use std::path::Path;

use crate::args::UsageError;

/// A parsed `(N, 3)` array, converted to the type the caller needs.
#[derive(Debug)]
pub struct Array {
    /// Element type as in the header, e.g. `<f4`.
    descr: String,
    /// Rows.
    rows: usize,
    /// Raw little-endian data, `rows * 3 * size` bytes.
    data: Vec<u8>,
}

fn bad(path: &Path, why: impl std::fmt::Display) -> UsageError {
    UsageError(format!("{}: {why}", path.display()))
}

/// Value of `key` in the header dict: the text after `'key':` up to the next
/// top-level comma (parentheses kept together).
fn field<'a>(header: &'a str, key: &str) -> Option<&'a str> {
    let start = header.find(&format!("'{key}'"))? + key.len() + 2;
    let rest = header[start..].trim_start().strip_prefix(':')?.trim_start();
    let mut depth = 0;
    for (i, c) in rest.char_indices() {
        match c {
            '(' => depth += 1,
            ')' => depth -= 1,
            ',' | '}' if depth == 0 => return Some(rest[..i].trim()),
            _ => {}
        }
    }
    None
}

/// Reads an `(N, 3)` array (exit code 2 on anything else).
pub fn read_rows3(path: &Path) -> Result<Array, UsageError> {
    let bytes = fs::read(path).map_err(|e| bad(path, format!("cannot read: {e}")))?;
    if bytes.len() < 10 || &bytes[..6] != b"\x93NUMPY" {
        return Err(bad(path, "not a .npy file (no \\x93NUMPY magic)"));
    }
    let (header_len, start) = match bytes[6] {
        1 => (u16::from_le_bytes([bytes[8], bytes[9]]) as usize, 10),
        2 | 3 if bytes.len() >= 12 => (u32::from_le_bytes([bytes[8], bytes[9], bytes[10], bytes[11]]) as usize, 12),
        v => return Err(bad(path, format!("unsupported .npy version {v}"))),
    };
    let header = bytes.get(start..start + header_len).ok_or_else(|| bad(path, "truncated header"))?;
    let header = std::str::from_utf8(header).map_err(|_| bad(path, "header is not text"))?;
    let descr = field(header, "descr").ok_or_else(|| bad(path, "header has no 'descr'"))?.trim_matches(|c| c == '\'' || c == '"');
    if field(header, "fortran_order") != Some("False") {
        return Err(bad(path, "array must be C-ordered (fortran_order False)"));
    }
    let shape = field(header, "shape").ok_or_else(|| bad(path, "header has no 'shape'"))?;
    let dims: Vec<usize> = shape
        .trim_matches(|c| c == '(' || c == ')')
        .split(',')
        .map(str::trim)
        .filter(|s| !s.is_empty())
        .map(|s| s.parse().map_err(|_| bad(path, format!("bad shape {shape}"))))
        .collect::<Result<_, _>>()?;
    let rows = match dims[..] {
        [n, 3] => n,
        _ => return Err(bad(path, format!("shape {shape}: expected (N, 3)"))),
    };
    let size = match descr {
        "<f4" | "<i4" | "<u4" => 4,
        "<f8" | "<i8" | "<u8" => 8,
        _ => return Err(bad(path, format!("dtype {descr}: expected little-endian float32/float64 or (u)int32/64"))),
    };
    let data = &bytes[start + header_len..];
    if data.len() != rows * 3 * size {
        return Err(bad(path, format!("{} data bytes for shape {shape} of {descr}: expected {}", data.len(), rows * 3 * size)));
    }
    Ok(Array { descr: descr.to_string(), rows, data: data.to_vec() })
}

impl Array {
    fn words<const N: usize>(&self) -> impl Iterator<Item = [u8; N]> + '_ {
        self.data.chunks_exact(N).map(|c| c.try_into().expect("chunk of N bytes"))
    }

    /// Rows as `f32` triples (`f64` input is rounded).
    pub fn to_f32(&self, path: &Path) -> Result<Vec<[f32; 3]>, UsageError> {
        let flat: Vec<f32> = match self.descr.as_str() {
            "<f4" => self.words::<4>().map(f32::from_le_bytes).collect(),
            "<f8" => self.words::<8>().map(|w| f64::from_le_bytes(w) as f32).collect(),
            d => return Err(bad(path, format!("dtype {d}: expected float32 or float64"))),
        };
        Ok(flat.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect())
    }

    /// Rows as `u32` index triples (each must be in `0..2^32`).
    pub fn to_u32(&self, path: &Path) -> Result<Vec<[u32; 3]>, UsageError> {
        let flat: Vec<i128> = match self.descr.as_str() {
            "<u4" => self.words::<4>().map(|w| u32::from_le_bytes(w).into()).collect(),
            "<i4" => self.words::<4>().map(|w| i32::from_le_bytes(w).into()).collect(),
            "<u8" => self.words::<8>().map(|w| u64::from_le_bytes(w).into()).collect(),
            "<i8" => self.words::<8>().map(|w| i64::from_le_bytes(w).into()).collect(),
            d => return Err(bad(path, format!("dtype {d}: expected an integer type for indices"))),
        };
        let mut out = Vec::with_capacity(self.rows);
        for (row, c) in flat.chunks_exact(3).enumerate() {
            let get = |v: i128| u32::try_from(v).map_err(|_| bad(path, format!("row {row}: index {v} out of range")));
            out.push([get(c[0])?, get(c[1])?, get(c[2])?]);
        }
        Ok(out)
    }
}

/// Writes a 1-D array of `n` elements of `descr` from its little-endian bytes.
fn write(path: &Path, descr: &str, n: usize, data: &[u8]) -> anyhow::Result<()> {
    let mut header = format!("{{'descr': '{descr}', 'fortran_order': False, 'shape': ({n},), }}");
    // Pad so that magic + version + length + header + '\n' is a multiple of 64.
    while (10 + header.len() + 1) % 64 != 0 {
        header.push(' ');
    }
    header.push('\n');
    let mut out = Vec::with_capacity(10 + header.len() + data.len());
    out.extend_from_slice(b"\x93NUMPY\x01\x00");
    out.extend_from_slice(&(header.len() as u16).to_le_bytes());
    out.extend_from_slice(header.as_bytes());
    out.extend_from_slice(data);
    fs::write(path, out).map_err(|e| anyhow::anyhow!("cannot write {}: {e}", path.display()))
}

/// Writes `values` as a float32 `(N,)` array.
pub fn write_f32(path: &Path, values: &[f32]) -> anyhow::Result<()> {
    write(path, "<f4", values.len(), &values.iter().flat_map(|v| v.to_le_bytes()).collect::<Vec<u8>>())
}

/// Writes `values` as an int64 `(N,)` array.
pub fn write_i64(path: &Path, values: &[i64]) -> anyhow::Result<()> {
    write(path, "<i8", values.len(), &values.iter().flat_map(|v| v.to_le_bytes()).collect::<Vec<u8>>())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn npy(descr: &str, shape: &str, data: &[u8]) -> Vec<u8> {
        let header = format!("{{'descr': '{descr}', 'fortran_order': False, 'shape': {shape}, }}\n");
        let mut out = b"\x93NUMPY\x01\x00".to_vec();
        out.extend_from_slice(&(header.len() as u16).to_le_bytes());
        out.extend_from_slice(header.as_bytes());
        out.extend_from_slice(data);
        out
    }

    #[test]
    fn reads_rows_and_rejects_bad_shape_dtype_and_size() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("a.npy");
        let floats: Vec<u8> = [1.0f32, 2.0, 3.0, 4.0, 5.0, 6.0].iter().flat_map(|v| v.to_le_bytes()).collect();
        fs::write(&path, npy("<f4", "(2, 3)", &floats)).unwrap();
        let a = read_rows3(&path).unwrap();
        assert_eq!(a.rows, 2);
        assert_eq!(a.to_f32(&path).unwrap(), vec![[1.0, 2.0, 3.0], [4.0, 5.0, 6.0]]);
        assert!(a.to_u32(&path).is_err(), "floats are not indices");
        for (descr, shape, data) in
            [("<f4", "(3, 2)", &floats[..]), ("<f4", "(6,)", &floats[..]), (">f4", "(2, 3)", &floats[..]), ("<f4", "(3, 3)", &floats[..])]
        {
            fs::write(&path, npy(descr, shape, data)).unwrap();
            assert!(read_rows3(&path).is_err(), "{descr} {shape}");
        }
        fs::write(&path, b"not numpy").unwrap();
        assert!(read_rows3(&path).unwrap_err().0.contains("magic"));
        let negative: Vec<u8> = [0i32, 1, -1].iter().flat_map(|v| v.to_le_bytes()).collect();
        fs::write(&path, npy("<i4", "(1, 3)", &negative)).unwrap();
        assert!(read_rows3(&path).unwrap().to_u32(&path).is_err());
    }

    #[test]
    fn written_header_is_aligned_and_data_round_trips() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("t.npy");
        write_f32(&path, &[1.5, f32::INFINITY]).unwrap();
        let bytes = fs::read(&path).unwrap();
        let header_len = u16::from_le_bytes([bytes[8], bytes[9]]) as usize;
        assert_eq!((10 + header_len) % 64, 0);
        assert!(std::str::from_utf8(&bytes[10..10 + header_len]).unwrap().contains("'shape': (2,)"));
        assert_eq!(&bytes[10 + header_len..], [1.5f32.to_le_bytes(), f32::INFINITY.to_le_bytes()].concat());
    }
}
