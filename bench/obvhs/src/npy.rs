//! The little of NumPy's `.npy` format the ray sets use: C-ordered little-endian
//! `(N, 3)` arrays of `<f4` (positions, origins, directions) or `<u4`/`<i4`
//! (triangle indices). Header: magic `\x93NUMPY`, version, header length (u16 in
//! version 1, u32 after), a Python dict literal, then the raw data.

use std::fs;
use std::path::Path;

/// Reads an `(N, 3)` array whose element type is `want` (`"f4"` or `"u4"`, where
/// `"u4"` also accepts non-negative `"i4"`); returns the raw 4-byte words.
fn read_rows(path: &Path, want: &str) -> Result<Vec<[u32; 3]>, String> {
    let bytes = fs::read(path).map_err(|e| format!("{}: {e}", path.display()))?;
    let bad = |why: &str| format!("{}: {why}", path.display());
    if bytes.len() < 10 || &bytes[..6] != b"\x93NUMPY" {
        return Err(bad("not a .npy file"));
    }
    let (len, start) = if bytes[6] == 1 {
        (u16::from_le_bytes([bytes[8], bytes[9]]) as usize, 10)
    } else {
        (u32::from_le_bytes([bytes[8], bytes[9], bytes[10], bytes[11]]) as usize, 12)
    };
    let header = std::str::from_utf8(bytes.get(start..start + len).ok_or_else(|| bad("short header"))?).map_err(|_| bad("header"))?;
    if header.contains("'fortran_order': True") {
        return Err(bad("Fortran order is not supported"));
    }
    let descr = header.split("'descr':").nth(1).and_then(|s| s.split('\'').nth(1)).ok_or_else(|| bad("no descr"))?;
    let ok = match want {
        "f4" => descr == "<f4",
        _ => descr == "<u4" || descr == "<i4",
    };
    if !ok {
        return Err(bad(&format!("element type {descr}, expected {want}")));
    }
    let shape = header.split("'shape':").nth(1).and_then(|s| s.split(['(', ')']).nth(1)).ok_or_else(|| bad("no shape"))?;
    let dims: Vec<usize> = shape.split(',').filter(|s| !s.trim().is_empty()).map(|s| s.trim().parse().unwrap_or(0)).collect();
    if dims.len() != 2 || dims[1] != 3 {
        return Err(bad(&format!("shape {shape}, expected (N, 3)")));
    }
    let data = &bytes[start + len..];
    if data.len() != dims[0] * 12 {
        return Err(bad("data length does not match the shape"));
    }
    let word = |k: usize| u32::from_le_bytes([data[4 * k], data[4 * k + 1], data[4 * k + 2], data[4 * k + 3]]);
    let rows: Vec<[u32; 3]> = (0..dims[0]).map(|r| [word(3 * r), word(3 * r + 1), word(3 * r + 2)]).collect();
    if descr == "<i4" && rows.iter().flatten().any(|&v| (v as i32) < 0) {
        return Err(bad("negative index"));
    }
    Ok(rows)
}

/// An `(N, 3)` `float32` array.
pub fn read_f32(path: &Path) -> Result<Vec<[f32; 3]>, String> {
    Ok(read_rows(path, "f4")?.into_iter().map(|r| r.map(f32::from_bits)).collect())
}

/// An `(N, 3)` array of 32-bit triangle indices.
pub fn read_u32(path: &Path) -> Result<Vec<[u32; 3]>, String> {
    read_rows(path, "u4")
}
