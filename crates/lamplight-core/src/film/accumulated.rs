//! The accumulated film: per pixel, the sum and the sum of squares of its sample
//! radiance, from which the image (the mean) and the variance of the mean follow.
//!
//! Pixels are stored tile by tile in the renderer's [`TILE`] x [`TILE`] tiles
//! (tiles in row-major order, each a row-major block, edge tiles padded), so each
//! tile of a pass writes one contiguous block and no tile touches another's.

use rayon::prelude::*;

use super::Image;
use crate::math::Rgb;

/// Side in pixels of the square tiles the renderer works in and the film stores.
pub const TILE: u32 = 16;
/// Entries of one stored tile.
pub(crate) const TILE_PIXELS: usize = (TILE * TILE) as usize;

/// One pixel's sums over its samples `l_i`: `sum = sum_i l_i`, `sum_sq = sum_i l_i^2`
/// (per channel), added in sample order.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PixelSum {
    /// Sum of the sample radiance.
    pub sum: Rgb,
    /// Sum of the squared sample radiance.
    pub sum_sq: Rgb,
}

impl PixelSum {
    /// Adds one sample `l`.
    #[inline]
    pub fn add(&mut self, l: Rgb) {
        self.sum += l;
        self.sum_sq += l * l;
    }
}

/// Stored form of a [`PixelSum`]: `[sum, sum_sq]` as plain arrays, so that a new
/// film is zeroed memory from the allocator rather than a serial fill.
type Stored = [f64; 6];

/// Per-pixel sums of `samples` samples per pixel of a `width x height` image.
#[derive(Clone, Debug, PartialEq)]
pub struct Film {
    width: u32,
    height: u32,
    tiles_x: u32,
    pixels: Vec<Stored>,
    samples: u32,
}

impl Film {
    /// An empty film (no samples).
    pub fn new(width: u32, height: u32) -> Film {
        let tiles_x = width.div_ceil(TILE);
        let tiles = tiles_x as usize * height.div_ceil(TILE) as usize;
        Film { width, height, tiles_x, pixels: vec![[0.0; 6]; tiles * TILE_PIXELS], samples: 0 }
    }

    /// Width in pixels.
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Height in pixels.
    pub fn height(&self) -> u32 {
        self.height
    }

    /// Samples per pixel accumulated.
    pub fn samples(&self) -> u32 {
        self.samples
    }

    /// The sums of the pixel at column `x`, row `y` (from the top).
    pub fn get(&self, x: u32, y: u32) -> PixelSum {
        assert!(x < self.width && y < self.height, "pixel ({x}, {y}) outside the {}x{} film", self.width, self.height);
        let tile = (y / TILE) as usize * self.tiles_x as usize + (x / TILE) as usize;
        let s = self.pixels[tile * TILE_PIXELS + ((y % TILE) * TILE + x % TILE) as usize];
        PixelSum { sum: Rgb::new(s[0], s[1], s[2]), sum_sq: Rgb::new(s[3], s[4], s[5]) }
    }

    /// The image: each pixel's mean `sum / n` (black before any sample).
    pub fn mean(&self) -> Image {
        let n = self.samples.max(1) as f64;
        self.develop(|s| {
            let m = s.sum / n;
            [m.x as f32, m.y as f32, m.z as f32]
        })
    }

    /// Variance of each pixel's mean, per channel: the sample variance
    /// `(sum_sq / n - mean^2) n / (n - 1)`, clamped at 0 against rounding, over `n`.
    /// Black with fewer than two samples.
    pub fn variance(&self) -> Image {
        let n = self.samples as f64;
        if n < 2.0 {
            return Image::new(self.width, self.height);
        }
        self.develop(|s| {
            let mean = s.sum / n;
            let var = ((s.sum_sq / n - mean * mean) * (n / (n - 1.0))).max(Rgb::ZERO) / n;
            [var.x as f32, var.y as f32, var.z as f32]
        })
    }

    /// A row-major image of `value` per pixel, rows in parallel (for a large image
    /// this is the longest serial step after the render otherwise).
    fn develop(&self, value: impl Fn(PixelSum) -> [f32; 3] + Sync) -> Image {
        let mut image = Image::new(self.width, self.height);
        let (width, tiles_x) = (self.width as usize, self.tiles_x as usize);
        image.pixels.par_chunks_mut(width.max(1)).enumerate().for_each(|(y, row)| {
            let first = (y / TILE as usize) * tiles_x * TILE_PIXELS + (y % TILE as usize) * TILE as usize;
            for (tx, out) in row.chunks_mut(TILE as usize).enumerate() {
                let start = first + tx * TILE_PIXELS;
                let stored = &self.pixels[start..start + out.len()];
                for (o, s) in out.iter_mut().zip(stored) {
                    *o = value(PixelSum { sum: Rgb::new(s[0], s[1], s[2]), sum_sq: Rgb::new(s[3], s[4], s[5]) });
                }
            }
        });
        image
    }

    /// Tiles per row.
    pub(crate) fn tiles_x(&self) -> u32 {
        self.tiles_x
    }

    /// Every tile's block, in tile order, for the renderer's workers.
    pub(crate) fn tiles_mut(&mut self) -> impl IndexedParallelIterator<Item = TileBlock<'_>> {
        self.pixels.par_chunks_mut(TILE_PIXELS).map(TileBlock)
    }

    /// Adds the samples of `pass` (a film of the same size) to this one.
    pub(crate) fn add(&mut self, pass: &Film) {
        debug_assert_eq!((self.width, self.height), (pass.width, pass.height));
        self.pixels.par_chunks_mut(TILE_PIXELS).zip(pass.pixels.par_chunks(TILE_PIXELS)).for_each(|(mine, theirs)| {
            for (m, t) in mine.iter_mut().zip(theirs) {
                for (a, b) in m.iter_mut().zip(t) {
                    *a += b;
                }
            }
        });
        self.samples += pass.samples;
    }

    /// Records that every pixel now holds `samples` samples.
    pub(crate) fn set_samples(&mut self, samples: u32) {
        self.samples = samples;
    }
}

/// One tile's pixels of a film, written by the worker rendering that tile.
pub(crate) struct TileBlock<'a>(&'a mut [Stored]);

impl TileBlock<'_> {
    /// Sets the pixel at column `x`, row `y` of the tile (from its top-left corner).
    #[inline]
    pub(crate) fn set(&mut self, x: u32, y: u32, sum: PixelSum) {
        let (s, q) = (sum.sum, sum.sum_sq);
        self.0[(y * TILE + x) as usize] = [s.x, s.y, s.z, q.x, q.y, q.z];
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A film whose pixel (x, y) holds the samples `x + 100 y` and `2 (x + 100 y)`.
    fn two_sample_film(width: u32, height: u32) -> Film {
        let mut film = Film::new(width, height);
        let tiles_x = film.tiles_x();
        for (t, block) in film.pixels.chunks_mut(TILE_PIXELS).enumerate() {
            let mut block = TileBlock(block);
            let (tx, ty) = (t as u32 % tiles_x, t as u32 / tiles_x);
            for (lx, ly) in (0..TILE).flat_map(|ly| (0..TILE).map(move |lx| (lx, ly))) {
                let (x, y) = (tx * TILE + lx, ty * TILE + ly);
                if x < width && y < height {
                    let v = Rgb::splat((x + 100 * y) as f64);
                    let mut s = PixelSum::default();
                    s.add(v);
                    s.add(v * 2.0);
                    block.set(lx, ly, s);
                }
            }
        }
        film.set_samples(2);
        film
    }

    #[test]
    fn tiles_map_back_to_rows() {
        // Sizes that are and are not multiples of the tile.
        for (w, h) in [(37, 23), (16, 16), (1, 40), (33, 1)] {
            let film = two_sample_film(w, h);
            let mean = film.mean();
            let variance = film.variance();
            for y in 0..h {
                for x in 0..w {
                    let v = (x + 100 * y) as f64;
                    assert_eq!(film.get(x, y).sum, Rgb::splat(3.0 * v));
                    assert_eq!(mean.get(x, y), [(1.5 * v) as f32; 3], "{w}x{h} ({x}, {y})");
                    // Samples v and 2v: sample variance v^2 / 2, of the mean v^2 / 4.
                    assert_eq!(variance.get(x, y), [(v * v / 4.0) as f32; 3]);
                }
            }
        }
    }

    #[test]
    fn adding_films_adds_sums_and_samples() {
        let mut a = two_sample_film(20, 3);
        a.add(&two_sample_film(20, 3));
        assert_eq!(a.samples(), 4);
        assert_eq!(a.get(19, 2).sum_sq, Rgb::splat(2.0 * 5.0 * 219.0 * 219.0));
        assert_eq!(Film::new(5, 5).mean(), Image::new(5, 5), "no samples: black");
        assert_eq!(Film::new(5, 5).variance(), Image::new(5, 5));
    }
}
