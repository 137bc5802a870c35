//! NumPy `.npy` files: lamplight's one reader and writer (the arrays of
//! `lamplight raycast`, and of the benchmarks that compare it).
//!
//! A file (format versions 1.0, 2.0 and 3.0) is the magic `\x93NUMPY`, the major
//! and minor version bytes, the header length `H` (`u16` little-endian in 1.0,
//! `u32` after), `H` bytes of header (a Python dict literal, [`header`], padded
//! with spaces and a newline), then the data: `d_0 d_1 ... d_k s` bytes for shape
//! `(d_0, ..., d_k)` and element size `s`, row-major (C order) or column-major
//! (`fortran_order`).
//!
//! Reading is defensive, for files from anywhere:
//!
//! - Only regular files are read (symbolic links followed). A FIFO, a device
//!   such as `/dev/zero`, a socket or a directory is refused before it is opened,
//!   so reading never blocks or runs forever; a file longer than the limit
//!   ([`MAX_BYTES`] by default) is refused before it is read.
//! - Every size taken from the header is computed with checked arithmetic and
//!   compared with the bytes actually in the file before anything is allocated
//!   from it: a shape of `(4611686018427387905, 3)` is an error, not an overflow
//!   that wraps to a small size (or a "capacity overflow" panic).
//! - Element types: little-endian `<f4`, `<f8`, `<i4`, `<u4`, `<i8`, `<u8`
//!   (what NumPy writes on every common machine); C or Fortran order.
//!
//! Every error is one line naming the file and what was expected, and every
//! write is atomic ([`crate::atomic`]): version 1.0, C order, the data 64-byte
//! aligned, as `numpy.save` writes it.

use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

pub mod header;

/// Default limit on the length of a file read: 4 GiB, e.g. 358 million rays of
/// `(N, 3)` float32 (the ray-casting structure allows 2^28 triangles).
pub const MAX_BYTES: u64 = 1 << 32;

/// Why a `.npy` file could not be read or written; the message names the file.
#[derive(Debug, thiserror::Error, PartialEq, Eq)]
#[non_exhaustive]
pub enum NpyError {
    /// The file is missing, unreadable, or not the array that was expected.
    #[error("{}: {reason}", path.display())]
    Read {
        /// The file.
        path: PathBuf,
        /// What was wrong and what was expected.
        reason: String,
    },
    /// The file system refused the write.
    #[error("cannot write {}: {reason}", path.display())]
    Write {
        /// The file.
        path: PathBuf,
        /// What the system said.
        reason: String,
    },
}

/// An element type this module reads.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Dtype {
    /// `<f4`.
    F32,
    /// `<f8`.
    F64,
    /// `<i4`.
    I32,
    /// `<u4`.
    U32,
    /// `<i8`.
    I64,
    /// `<u8`.
    U64,
}

impl Dtype {
    const ALL: [Dtype; 6] = [Dtype::F32, Dtype::F64, Dtype::I32, Dtype::U32, Dtype::I64, Dtype::U64];

    /// The header's spelling, e.g. `<f4`.
    pub fn descr(self) -> &'static str {
        match self {
            Dtype::F32 => "<f4",
            Dtype::F64 => "<f8",
            Dtype::I32 => "<i4",
            Dtype::U32 => "<u4",
            Dtype::I64 => "<i8",
            Dtype::U64 => "<u8",
        }
    }

    /// Bytes per element.
    pub fn size(self) -> usize {
        match self {
            Dtype::F32 | Dtype::I32 | Dtype::U32 => 4,
            Dtype::F64 | Dtype::I64 | Dtype::U64 => 8,
        }
    }
}

/// An array read from a file: its element type, shape, order and raw
/// little-endian data (exactly `product(shape) * dtype.size()` bytes).
#[derive(Clone, Debug, PartialEq)]
pub struct Array {
    path: PathBuf,
    /// Element type.
    pub dtype: Dtype,
    /// Dimensions.
    pub shape: Vec<usize>,
    /// Column-major data.
    pub fortran_order: bool,
    data: Vec<u8>,
}

/// `shape` as Python writes a tuple: `(3, 2)`, `(6,)`, `()`.
fn shape_text<T: std::fmt::Display>(shape: &[T]) -> String {
    match shape {
        [one] => format!("({one},)"),
        _ => format!("({})", shape.iter().map(|d| d.to_string()).collect::<Vec<_>>().join(", ")),
    }
}

fn read_error(path: &Path, reason: impl Into<String>) -> NpyError {
    NpyError::Read { path: path.to_path_buf(), reason: reason.into() }
}

/// Reads `path` with the default size limit ([`MAX_BYTES`]).
pub fn read(path: &Path) -> Result<Array, NpyError> {
    read_limited(path, MAX_BYTES)
}

/// Reads `path`, a regular file of at most `max_bytes` bytes (see the module
/// documentation for what is checked).
pub fn read_limited(path: &Path, max_bytes: u64) -> Result<Array, NpyError> {
    use crate::input::Refusal;
    let bytes = crate::input::read_regular(path, max_bytes).map_err(|r| {
        read_error(
            path,
            match r {
                Refusal::Directory => "is a directory, expected a regular .npy file".to_string(),
                Refusal::NotRegular(kind) => format!("is {kind}, expected a regular .npy file"),
                Refusal::TooLarge { len, max } => format!("{len} bytes, more than the {max} allowed for a .npy file"),
                Refusal::NotFound => "cannot read: no such file or directory".to_string(),
                Refusal::PermissionDenied => "cannot read: permission denied".to_string(),
                Refusal::Io(e) => format!("cannot read: {e}"),
            },
        )
    })?;
    from_bytes(path, bytes)
}

/// Parses the bytes of a `.npy` file; `path` is only named in errors.
pub fn from_bytes(path: &Path, mut bytes: Vec<u8>) -> Result<Array, NpyError> {
    let bad = |reason: String| read_error(path, reason);
    if bytes.len() < 10 || &bytes[..6] != b"\x93NUMPY" {
        return Err(bad("not a .npy file (no \\x93NUMPY magic)".into()));
    }
    let (header_len, start) = match (bytes[6], bytes[7]) {
        (1, 0) => (u64::from(u16::from_le_bytes([bytes[8], bytes[9]])), 10),
        (2 | 3, 0) if bytes.len() >= 12 => (u64::from(u32::from_le_bytes([bytes[8], bytes[9], bytes[10], bytes[11]])), 12),
        (2 | 3, 0) => return Err(bad("truncated header length".into())),
        (major, minor) => return Err(bad(format!("unsupported .npy version {major}.{minor} (expected 1.0, 2.0 or 3.0)"))),
    };
    let present = bytes.len() - start;
    let end = match usize::try_from(header_len) {
        Ok(len) if len <= present => start + len,
        _ => return Err(bad(format!("truncated header: {header_len} bytes announced, {present} present"))),
    };
    let text = std::str::from_utf8(&bytes[start..end]).map_err(|_| bad("the header is not text".into()))?;
    let h = header::parse(text).map_err(|why| bad(format!("bad header: {why}")))?;
    let dtype = Dtype::ALL.into_iter().find(|d| d.descr() == h.descr).ok_or_else(|| {
        let all = Dtype::ALL.map(|d| format!("'{}'", d.descr())).join(", ");
        bad(format!("dtype '{}': expected one of {all} (little-endian)", h.descr))
    })?;
    let data_len = bytes.len() - end;
    let needed = h.shape.iter().try_fold(dtype.size() as u64, |acc, &d| acc.checked_mul(d));
    let shape = shape_text(&h.shape);
    match needed {
        None => return Err(bad(format!("shape {shape} of '{}' needs over 2^64 bytes; the file has {data_len} bytes of data", h.descr))),
        Some(n) if n != data_len as u64 => {
            return Err(bad(format!("shape {shape} of '{}' needs {n} bytes of data; the file has {data_len}", h.descr)))
        }
        Some(_) => {}
    }
    // The product fits in the data, so every dimension of a non-empty array fits
    // in a usize; an empty one may still name a huge dimension beside a zero.
    let shape = h
        .shape
        .iter()
        .map(|&d| usize::try_from(d))
        .collect::<Result<Vec<usize>, _>>()
        .map_err(|_| bad(format!("shape {shape} is too large for this machine")))?;
    bytes.drain(..end);
    Ok(Array { path: path.to_path_buf(), dtype, shape, fortran_order: h.fortran_order, data: bytes })
}

impl Array {
    /// Row count of an `(N, 3)` array, or the error naming the shape.
    fn rows3(&self) -> Result<usize, NpyError> {
        match self.shape[..] {
            [n, 3] => Ok(n),
            _ => Err(read_error(&self.path, format!("shape {}: expected (N, 3)", shape_text(&self.shape)))),
        }
    }

    /// The `N` little-endian bytes of element `k` in storage order.
    fn word<const N: usize>(&self, k: usize) -> [u8; N] {
        let mut w = [0u8; N];
        w.copy_from_slice(&self.data[k * N..(k + 1) * N]);
        w
    }

    /// Storage index of row `r`, column `c` of an `(n, 3)` array.
    fn index(&self, n: usize, r: usize, c: usize) -> usize {
        if self.fortran_order {
            c * n + r
        } else {
            3 * r + c
        }
    }

    /// An `(N, 3)` float array as `f32` rows (`f64` values rounded to nearest).
    pub fn rows3_f32(&self) -> Result<Vec<[f32; 3]>, NpyError> {
        let n = self.rows3()?;
        let get: fn(&Array, usize) -> f32 = match self.dtype {
            Dtype::F32 => |a, k| f32::from_le_bytes(a.word(k)),
            Dtype::F64 => |a, k| f64::from_le_bytes(a.word(k)) as f32,
            d => return Err(read_error(&self.path, format!("dtype '{}': expected float32 or float64 ('<f4', '<f8')", d.descr()))),
        };
        Ok((0..n).map(|r| std::array::from_fn(|c| get(self, self.index(n, r, c)))).collect())
    }

    /// An `(N, 3)` integer array as `u32` rows (every value must be in `0..2^32`).
    pub fn rows3_u32(&self) -> Result<Vec<[u32; 3]>, NpyError> {
        let n = self.rows3()?;
        let get: fn(&Array, usize) -> i128 = match self.dtype {
            Dtype::I32 => |a, k| i32::from_le_bytes(a.word(k)).into(),
            Dtype::U32 => |a, k| u32::from_le_bytes(a.word(k)).into(),
            Dtype::I64 => |a, k| i64::from_le_bytes(a.word(k)).into(),
            Dtype::U64 => |a, k| u64::from_le_bytes(a.word(k)).into(),
            d => return Err(read_error(&self.path, format!("dtype '{}': expected integers ('<i4', '<u4', '<i8', '<u8')", d.descr()))),
        };
        let mut rows = Vec::with_capacity(n);
        for r in 0..n {
            let mut row = [0u32; 3];
            for (c, slot) in row.iter_mut().enumerate() {
                let v = get(self, self.index(n, r, c));
                *slot = u32::try_from(v).map_err(|_| read_error(&self.path, format!("row {r}: index {v} is not in 0..2^32")))?;
            }
            rows.push(row);
        }
        Ok(rows)
    }
}

/// Reads an `(N, 3)` float array as `f32` rows ([`read`], [`Array::rows3_f32`]).
pub fn read_rows3_f32(path: &Path) -> Result<Vec<[f32; 3]>, NpyError> {
    read(path)?.rows3_f32()
}

/// Reads an `(N, 3)` integer array as `u32` rows ([`read`], [`Array::rows3_u32`]).
pub fn read_rows3_u32(path: &Path) -> Result<Vec<[u32; 3]>, NpyError> {
    read(path)?.rows3_u32()
}

/// The header of a C-ordered array: magic, version 1.0, length, dict padded
/// with spaces and a newline so that the data starts at a multiple of 64.
fn header_bytes(descr: &str, shape: &[usize]) -> Vec<u8> {
    let mut dict = format!("{{'descr': '{descr}', 'fortran_order': False, 'shape': {}, }}", shape_text(shape));
    dict.push_str(&" ".repeat(63 - (10 + dict.len()) % 64));
    dict.push('\n');
    let mut out = b"\x93NUMPY\x01\x00".to_vec();
    // A 1-D or 2-D shape is a short header; `u16` is enough by far.
    out.extend_from_slice(&(dict.len() as u16).to_le_bytes());
    out.extend_from_slice(dict.as_bytes());
    out
}

/// Writes `values` as a C-ordered array of `shape` and element type `descr`,
/// atomically; `bytes` turns one value into its little-endian bytes.
fn write<T: Copy, const N: usize>(
    path: &Path,
    descr: &str,
    shape: &[usize],
    values: &[T],
    bytes: fn(T) -> [u8; N],
) -> Result<(), NpyError> {
    crate::atomic::write_with(path, |file| {
        let mut out = BufWriter::new(file);
        out.write_all(&header_bytes(descr, shape))?;
        for &v in values {
            out.write_all(&bytes(v))?;
        }
        out.flush()
    })
    .map_err(|e| NpyError::Write { path: path.to_path_buf(), reason: crate::image_io::describe(&e) })
}

/// Writes `values` as a float32 `(N,)` array.
pub fn write_f32(path: &Path, values: &[f32]) -> Result<(), NpyError> {
    write(path, "<f4", &[values.len()], values, f32::to_le_bytes)
}

/// Writes `values` as an int64 `(N,)` array.
pub fn write_i64(path: &Path, values: &[i64]) -> Result<(), NpyError> {
    write(path, "<i8", &[values.len()], values, i64::to_le_bytes)
}

/// Writes `rows` as a float32 `(N, 3)` array.
pub fn write_rows3_f32(path: &Path, rows: &[[f32; 3]]) -> Result<(), NpyError> {
    write(path, "<f4", &[rows.len(), 3], rows.as_flattened(), f32::to_le_bytes)
}

#[cfg(test)]
mod tests;
