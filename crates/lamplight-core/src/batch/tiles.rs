//! Camera rays handed to a packet-walking target in small pixel tiles rather
//! than along their rows.
//!
//! A target that walks eight rays together ([`super::BatchTarget::PACKETS`],
//! the mesh's packets) gains when the eight stay close all the way down the
//! tree. Camera rays usually arrive as an image, row after row; eight
//! consecutive ones are then an 8x1 strip, and on a fine mesh (triangles about a
//! pixel wide) the strip fans out over more leaves than a compact tile would.
//! Measured on this project's anchor rays (1024x1024 camera rays, one thread,
//! issue 24), re-ordered offline: 2x4 tiles cast Igea-1M's 11 % faster than
//! rows, the bunny's 4 % faster, and 4x2 tiles 9 % and 3 %. Through [`cast`](super::cast),
//! which pays for reading each band out of order: Igea-1M +13 % and the bunny
//! +2 % against rows, in alternating rounds (`BENCHMARKS.md`, session 21).
//!
//! [`row_width`] recognises such a layout from the rays alone: directions that
//! move by a small, even step from one ray to the next, with one large jump
//! where a row ends, and the ray one row below each sampled ray as near as its
//! neighbour in the row. [`cast`](super::cast) then splits the batch into bands of
//! [`TILE_ROWS`] rows and presents each band in tile order ([`tile_order`]). The
//! guess only ever changes the order in which rays are walked: every ray's
//! distance is its own either way, bit for bit, and a wrong guess costs speed,
//! never an answer. (As with any packet, which of two triangles hit at the very
//! same distance is reported may follow the grouping; the grouping depends only
//! on the rays, never on the thread count.)

use super::Rays;
use crate::math::Vec3;

/// Rows per tile (and per band of rows handed to one worker).
pub const TILE_ROWS: usize = 4;

/// Columns per tile: a tile is `TILE_COLUMNS x TILE_ROWS` rays, one packet.
pub const TILE_COLUMNS: usize = 2;

/// Widest row [`row_width`] looks for: the scan of the first row is bounded by it.
pub const MAX_WIDTH: usize = 1 << 14;

/// How much larger than the first step the jump at a row's end must be, and how
/// far any other step (along a row or down a column) may stray from it.
const JUMP: f64 = 4.0;

/// Rays sampled over the batch to confirm the layout.
const SAMPLES: usize = 64;

/// The row width when `rays` look like an image of whole rows of an even number
/// of rays (at least [`TILE_COLUMNS`] x [`TILE_ROWS`] rays, at least two
/// rows), laid out row after row; `None` otherwise (see the module
/// documentation for the test).
pub fn row_width<R: Rays>(rays: &R) -> Option<usize> {
    let n = rays.len();
    let unit = |i: usize| {
        let (_, d) = rays.get(i);
        let d = Vec3::from_array(d.map(super::Float::to_f64));
        let length = d.length();
        (length.is_finite() && length > 0.0).then(|| d / length)
    };
    let step = |i: usize, j: usize| Some(unit(i)?.distance(unit(j)?));
    if n < 2 * TILE_COLUMNS * TILE_ROWS {
        return None;
    }
    let first = step(0, 1)?;
    if !(first > 0.0) {
        return None; // parallel rays (an orthographic camera): nothing to tell rows by
    }
    let near = |s: f64| s * JUMP >= first && s <= first * JUMP;
    // Along the first row until the jump back to the next row's start.
    let mut width = None;
    for i in 1..(n - 1).min(MAX_WIDTH) {
        let s = step(i, i + 1)?;
        if s > first * JUMP {
            width = Some(i + 1);
            break;
        }
        if !near(s) {
            return None;
        }
    }
    let width = width?;
    if !width.is_multiple_of(TILE_COLUMNS) || !n.is_multiple_of(width) || n / width < 2 {
        return None;
    }
    // Below each sampled ray, the ray of the next row is a neighbour too; and
    // each sampled ray's neighbour in its row is near (rows alike all the way down).
    (0..SAMPLES)
        .all(|k| {
            let i = k * (n - width) / SAMPLES;
            let along = if i % width + 1 < width { step(i, i + 1) } else { step(i - 1, i) };
            matches!((step(i, i + width), along), (Some(down), Some(along)) if near(down) && near(along))
        })
        .then_some(width)
}

/// Where the `j`-th ray in tile order lies in a band of `rows` rows of `width`
/// rays (row after row): tiles of [`TILE_COLUMNS`] columns by the band's rows,
/// left to right, each read row by row. `width` is a multiple of `TILE_COLUMNS`.
#[inline(always)]
pub fn tile_order(j: usize, width: usize, rows: usize) -> usize {
    let per_tile = TILE_COLUMNS * rows;
    (j % per_tile / TILE_COLUMNS) * width + j / per_tile * TILE_COLUMNS + j % TILE_COLUMNS
}

/// [`tile_order`] in a band of [`TILE_ROWS`] rows: the same index, with the
/// tile sizes known to the compiler.
#[inline(always)]
pub fn full_band_order(j: usize, width: usize) -> usize {
    const PER_TILE: usize = TILE_COLUMNS * TILE_ROWS;
    (j % PER_TILE / TILE_COLUMNS) * width + j / PER_TILE * TILE_COLUMNS + j % TILE_COLUMNS
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::batch::RaySlices;

    /// Pinhole camera rays of a `width x height` image, row after row, 0.8
    /// wide at unit distance.
    fn camera(width: usize, height: usize) -> (Vec<[f64; 3]>, Vec<[f64; 3]>) {
        let dirs = (0..width * height)
            .map(|i| {
                let (x, y) = ((i % width) as f64 + 0.5, (i / width) as f64 + 0.5);
                let pixel = 0.8 / width as f64; // square pixels
                [(x - width as f64 / 2.0) * pixel, (height as f64 / 2.0 - y) * pixel, -1.0]
            })
            .collect();
        (vec![[0.0, 0.0, 5.0]; width * height], dirs)
    }

    #[test]
    fn finds_the_row_width_of_camera_rays() {
        for (w, h) in [(64, 48), (1024, 8), (6, 5), (200, 3)] {
            let (o, d) = camera(w, h);
            assert_eq!(row_width(&RaySlices::new(&o, &d).unwrap()), Some(w), "{w}x{h}");
        }
    }

    #[test]
    fn other_layouts_are_not_taken_for_images() {
        let check = |o: &[[f64; 3]], d: &[[f64; 3]], what: &str| assert_eq!(row_width(&RaySlices::new(o, d).unwrap()), None, "{what}");
        // Odd widths (no whole tiles), one row, a partial last row.
        let (o, d) = camera(63, 10);
        check(&o, &d, "odd width");
        let (o, d) = camera(512, 1);
        check(&o, &d, "one row");
        let (o, d) = camera(64, 10);
        check(&o[..o.len() - 3], &d[..d.len() - 3], "partial last row");
        // Parallel rays (orthographic), and scattered ones.
        check(&o, &vec![[0.0, 0.0, -1.0]; o.len()], "parallel");
        let scattered: Vec<[f64; 3]> = (0..640u64)
            .map(|i| {
                let h = i.wrapping_mul(0x9E37_79B9_7F4A_7C15);
                [(h >> 40) as f64 / 16777216.0 - 0.5, (h >> 16 & 0xFF_FFFF) as f64 / 16777216.0 - 0.5, 1.0]
            })
            .collect();
        check(&o, &scattered, "scattered");
        // A second image of another width glued below: the sampled rows disagree.
        let (o2, d2) = camera(32, 20);
        let (mut o3, mut d3) = camera(64, 10);
        o3.extend(o2);
        d3.extend(d2);
        check(&o3, &d3, "two images");
        // A zero direction where a row should continue.
        let (o, mut d) = camera(64, 10);
        d[5] = [0.0; 3];
        check(&o, &d, "unusable ray in the first row");
    }

    #[test]
    fn tile_order_visits_every_ray_of_a_band_once() {
        for (width, rows) in [(8, 4), (1024, 4), (6, 3), (2, 1), (10, 4)] {
            let mut seen = vec![false; width * rows];
            for j in 0..width * rows {
                let i = tile_order(j, width, rows);
                assert!(!seen[i], "{width}x{rows}: ray {i} twice");
                seen[i] = true;
            }
            assert!(seen.iter().all(|&s| s), "{width}x{rows}");
            if rows == TILE_ROWS {
                assert!((0..width * rows).all(|j| full_band_order(j, width) == tile_order(j, width, rows)), "{width}x{rows}");
            }
        }
        // 2x4 tiles: the first packet is columns 0-1 of rows 0-3.
        let first: Vec<usize> = (0..8).map(|j| tile_order(j, 100, 4)).collect();
        assert_eq!(first, [0, 1, 100, 101, 200, 201, 300, 301]);
        assert_eq!(tile_order(8, 100, 4), 2);
    }
}
