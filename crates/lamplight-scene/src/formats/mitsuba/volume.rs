//! Mitsuba's binary grid file (`.vol`), as `sdfgrid` reads it: one channel of
//! `float32` samples.
//!
//! Layout (little-endian): `"VOL"` and version byte 3; `int32` encoding (1:
//! `float32`); `int32` `xres`, `yres`, `zres`; `int32` channels; six `float32`
//! of a bounding box (`sdfgrid` ignores it: the grid spans the unit cube); then
//! `xres yres zres channels` samples, `x` fastest, then `y`, then `z`. The size
//! is checked against the header, and the header against
//! [`lamplight_core::shapes::sdf_grid::MAX_SAMPLES`], before any sample is read.

use std::path::Path;

use lamplight_core::shapes::sdf_grid::MAX_SAMPLES;

/// Bytes before the samples.
const HEADER: usize = 48;

/// A grid's samples per axis and its values, `x` fastest.
#[derive(Debug, PartialEq)]
pub struct Grid {
    /// `[xres, yres, zres]`.
    pub resolution: [usize; 3],
    /// The samples.
    pub values: Vec<f32>,
}

/// The one-channel grid of the file at `path`.
pub fn read(path: &Path) -> Result<Grid, String> {
    // Header and the most samples allowed: nothing larger is read into memory.
    let max = (HEADER + 4 * MAX_SAMPLES) as u64;
    let bytes = crate::input::read_regular(path, max).map_err(|e| match e {
        crate::input::Refusal::TooLarge { len, max } => {
            format!("{len} bytes, expected at most {max} (a grid of at most {MAX_SAMPLES} samples)")
        }
        _ => format!("cannot read \"{}\"", path.display()),
    })?;
    parse(&bytes)
}

/// The one-channel grid in a `.vol` file's bytes.
pub fn parse(bytes: &[u8]) -> Result<Grid, String> {
    if bytes.len() < HEADER || &bytes[..3] != b"VOL" {
        return Err("not a Mitsuba .vol grid file (no \"VOL\" header)".into());
    }
    if bytes[3] != 3 {
        return Err(format!("unsupported .vol version {}, expected 3", bytes[3]));
    }
    let int = |i: usize| i32::from_le_bytes(bytes[4 + 4 * i..8 + 4 * i].try_into().expect("4 bytes"));
    let (encoding, res, channels) = (int(0), [int(1), int(2), int(3)], int(4));
    if encoding != 1 {
        return Err(format!("unsupported .vol encoding {encoding}, expected 1 (float32)"));
    }
    if channels != 1 {
        return Err(format!("the grid has {channels} channels, expected 1 (a signed distance)"));
    }
    if res.iter().any(|&n| n < 2) {
        return Err(format!("resolution {} x {} x {}, expected at least 2 samples per axis", res[0], res[1], res[2]));
    }
    let count = res.iter().map(|&n| n as u64).product::<u64>();
    if count > MAX_SAMPLES as u64 {
        return Err(format!("{} x {} x {} = {count} samples, expected at most {MAX_SAMPLES}", res[0], res[1], res[2]));
    }
    let expected = HEADER + 4 * count as usize;
    if bytes.len() != expected {
        return Err(format!("{} bytes, expected {expected} for {} x {} x {} samples", bytes.len(), res[0], res[1], res[2]));
    }
    let values: Vec<f32> = bytes[HEADER..].chunks_exact(4).map(|b| f32::from_le_bytes(b.try_into().expect("4 bytes"))).collect();
    if let Some(i) = values.iter().position(|v| !v.is_finite()) {
        return Err(format!("sample {i} is {}, expected a finite number", values[i]));
    }
    Ok(Grid { resolution: res.map(|n| n as usize), values })
}

/// A `.vol` file's bytes for `grid` (tests and tools write grids with it).
pub fn write(grid: &Grid) -> Vec<u8> {
    let mut out = b"VOL\x03".to_vec();
    let [x, y, z] = grid.resolution.map(|n| n as i32);
    for v in [1, x, y, z, 1] {
        out.extend(v.to_le_bytes());
    }
    for v in [0.0f32, 0.0, 0.0, 1.0, 1.0, 1.0].iter().chain(&grid.values) {
        out.extend(v.to_le_bytes());
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_grid_reads_back_and_bad_files_say_why() {
        let grid = Grid { resolution: [2, 3, 2], values: (0..12).map(|i| i as f32 - 5.5).collect() };
        let bytes = write(&grid);
        assert_eq!(parse(&bytes), Ok(grid));
        let with = |at: usize, v: i32| {
            let mut b = bytes.clone();
            b[at..at + 4].copy_from_slice(&v.to_le_bytes());
            parse(&b).unwrap_err()
        };
        assert_eq!(parse(b"VOX\x03"), Err("not a Mitsuba .vol grid file (no \"VOL\" header)".into()));
        assert_eq!(with(20, 3), "the grid has 3 channels, expected 1 (a signed distance)");
        assert_eq!(with(8, 1), "resolution 1 x 3 x 2, expected at least 2 samples per axis");
        assert_eq!(with(8, i32::MAX), "2147483647 x 3 x 2 = 12884901882 samples, expected at most 4194304");
        assert_eq!(with(8, 3), "96 bytes, expected 120 for 3 x 3 x 2 samples");
        assert_eq!(with(48, f32::NAN.to_bits() as i32), "sample 0 is NaN, expected a finite number");
    }
}
