//! The accumulated film: per pixel, the sum and the sum of squares of its sample
//! radiance, from which the image (the mean) and the variance of the mean follow.
//!
//! Pixels are stored tile by tile in the renderer's [`TILE`] x [`TILE`] tiles
//! (tiles in row-major order, each a row-major block, edge tiles padded), so each
//! tile of a pass writes one contiguous block and no tile touches another's.
//!
//! While every pixel holds at most one sample `l`, its sum of squares is `l * l`,
//! the very product a sample adds, so it is not stored: a render of one sample
//! per pixel (the usual Whitted render) keeps half the memory, and the squares
//! appear, with the same bits, when a second sample is added.
//!
//! A render that wants only the image, in one pass ([`crate::render_image`] with
//! a one-pass integrator), keeps no sums at all: each tile stores its pixels'
//! means `sum / n` as `f32`, the very numbers [`Film::mean`] would compute, in a
//! quarter of the memory of sums and squares (page faults on a 1280x720 film
//! cost a Whitted render some 5 % of its time). Those means are stored row by
//! row, as the image is, each tile writing its rows' pieces, so that
//! [`Film::into_mean`] hands the buffer over as the image instead of copying
//! 11 MB into fresh memory (4 % of a 2-thread Whitted render, BENCHMARKS.md).

use rayon::prelude::*;

use super::Image;
use crate::math::Rgb;

/// Side in pixels of the square tiles the renderer works in and the film stores.
pub const TILE: u32 = 16;
/// Entries of one stored tile.
const TILE_PIXELS: usize = (TILE * TILE) as usize;

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

/// One stored channel triple. Plain arrays, so that a new film is zeroed memory
/// from the allocator rather than a serial fill.
type Stored = [f64; 3];

#[inline]
fn rgb(s: &Stored) -> Rgb {
    Rgb::new(s[0], s[1], s[2])
}

/// Per-pixel sums of `samples` samples per pixel of a `width x height` image.
#[derive(Clone, Debug, PartialEq)]
pub struct Film {
    width: u32,
    height: u32,
    tiles_x: u32,
    sums: Vec<Stored>,
    /// The sums of squares; `None` while no pixel holds more than one sample.
    squares: Option<Vec<Stored>>,
    /// The means alone (then `sums` is empty), for a one-pass image-only render;
    /// row-major, `width * height` of them, unlike the tiled sums.
    means: Option<Vec<[f32; 3]>>,
    /// Samples of each pixel, where an adaptive render gave pixels different
    /// counts; `None` while every pixel holds `samples`.
    counts: Option<Vec<u32>>,
    /// Samples per pixel (with `counts`, the most any pixel holds).
    samples: u32,
}

impl Film {
    /// An empty film (no samples).
    pub fn new(width: u32, height: u32) -> Film {
        let tiles_x = width.div_ceil(TILE);
        let tiles = tiles_x as usize * height.div_ceil(TILE) as usize;
        Film {
            width,
            height,
            tiles_x,
            sums: crate::pages::zeroed([0.0; 3], tiles * TILE_PIXELS),
            squares: None,
            means: None,
            counts: None,
            samples: 0,
        }
    }

    /// A film that keeps only the means of one pass of samples (see the module
    /// doc): [`Film::mean`] is exact, the sums and the variance are not kept.
    pub(crate) fn means_only(width: u32, height: u32) -> Film {
        Film {
            width,
            height,
            tiles_x: width.div_ceil(TILE),
            sums: Vec::new(),
            squares: None,
            means: Some(crate::pages::zeroed([0.0; 3], width as usize * height as usize)),
            counts: None,
            samples: 0,
        }
    }

    /// Width in pixels.
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Height in pixels.
    pub fn height(&self) -> u32 {
        self.height
    }

    /// Samples per pixel accumulated: after an adaptive render, the most any
    /// pixel holds ([`Film::samples_at`] gives each pixel's).
    pub fn samples(&self) -> u32 {
        self.samples
    }

    /// Samples the pixel at column `x`, row `y` holds.
    pub fn samples_at(&self, x: u32, y: u32) -> u32 {
        let i = self.index(x, y);
        self.counts.as_ref().map_or(self.samples, |c| c[i])
    }

    /// Each pixel's sample count, row-major (the `samples` layer).
    pub fn sample_counts(&self) -> Vec<f32> {
        let mut counts = Vec::with_capacity(self.width as usize * self.height as usize);
        for y in 0..self.height {
            counts.extend((0..self.width).map(|x| self.samples_at(x, y) as f32));
        }
        counts
    }

    /// Whether pixels hold different sample counts (an adaptive render).
    pub fn is_adaptive(&self) -> bool {
        self.counts.is_some()
    }

    /// Index in storage of the pixel at column `x`, row `y`; panics outside the film.
    fn index(&self, x: u32, y: u32) -> usize {
        assert!(x < self.width && y < self.height, "pixel ({x}, {y}) outside the {}x{} film", self.width, self.height);
        storage_index(self.width, self.tiles_x, self.means.is_some(), x, y)
    }

    /// Samples of the pixel at storage index `i`.
    #[inline]
    fn count(&self, i: usize) -> u32 {
        self.counts.as_ref().map_or(self.samples, |c| c[i])
    }

    /// The sums of the pixel at column `x`, row `y` (from the top). Panics outside
    /// the film, as indexing does. (A means-only film gives `n` times its mean.)
    pub fn get(&self, x: u32, y: u32) -> PixelSum {
        let i = self.index(x, y);
        if let Some(means) = &self.means {
            let sum = Rgb::new(means[i][0] as f64, means[i][1] as f64, means[i][2] as f64) * self.samples.max(1) as f64;
            return PixelSum { sum, sum_sq: Rgb::ZERO };
        }
        let sum = rgb(&self.sums[i]);
        PixelSum { sum, sum_sq: self.squares.as_ref().map_or(sum * sum, |q| rgb(&q[i])) }
    }

    /// The image: each pixel's mean `sum / n` (black before any sample).
    pub fn mean(&self) -> Image {
        if let Some(means) = &self.means {
            return Image { width: self.width, height: self.height, pixels: means.clone() };
        }
        self.develop(|i| {
            let m = rgb(&self.sums[i]) / self.count(i).max(1) as f64;
            [m.x as f32, m.y as f32, m.z as f32]
        })
    }

    /// [`Film::mean`], taking the film: a means-only film's buffer becomes the
    /// image as it is (no copy).
    pub fn into_mean(self) -> Image {
        match self.means {
            Some(pixels) => Image { width: self.width, height: self.height, pixels },
            None => self.mean(),
        }
    }

    /// Variance of each pixel's mean, per channel: the sample variance
    /// `(sum_sq / n - mean^2) n / (n - 1)`, clamped at 0 against rounding, over `n`,
    /// `n` the pixel's own sample count. Black with fewer than two samples.
    pub fn variance(&self) -> Image {
        let Some(squares) = self.squares.as_ref().filter(|_| self.samples >= 2) else {
            return Image::new(self.width, self.height);
        };
        self.develop(|i| {
            let n = self.count(i) as f64;
            if n < 2.0 {
                return [0.0; 3];
            }
            let var = variance_of_mean(rgb(&self.sums[i]), rgb(&squares[i]), n);
            [var.x as f32, var.y as f32, var.z as f32]
        })
    }

    /// A row-major image of `value(i)` per pixel, `i` its index in the tiled
    /// storage of the sums; rows in parallel: for a large image this would
    /// otherwise be the longest serial step after the render.
    fn develop(&self, value: impl Fn(usize) -> [f32; 3] + Sync) -> Image {
        let mut image = Image::new(self.width, self.height);
        let (width, tiles_x) = (self.width as usize, self.tiles_x as usize);
        image.pixels.par_chunks_mut(width.max(1)).enumerate().for_each(|(y, row)| {
            let first = (y / TILE as usize) * tiles_x * TILE_PIXELS + (y % TILE as usize) * TILE as usize;
            for (tx, out) in row.chunks_mut(TILE as usize).enumerate() {
                let start = first + tx * TILE_PIXELS;
                for (k, o) in out.iter_mut().enumerate() {
                    *o = value(start + k);
                }
            }
        });
        image
    }

    /// Tiles per row.
    pub(crate) fn tiles_x(&self) -> u32 {
        self.tiles_x
    }

    /// Makes room for the squares before a pass of `count` samples per pixel
    /// writes them (a single sample's square is its sum's).
    pub(crate) fn prepare_pass(&mut self, count: u32) {
        if count > 1 && self.squares.is_none() && self.means.is_none() {
            self.squares = Some(crate::pages::zeroed([0.0; 3], self.sums.len()));
        }
    }

    /// Every tile's block, in tile order, for the renderer's workers.
    /// `count` is the pass's samples per pixel (a means-only film divides by it).
    pub(crate) fn tiles_mut(&mut self, count: u32) -> impl IndexedParallelIterator<Item = TileBlock<'_>> {
        let blocks: Vec<TileBlock> = if let Some(means) = self.means.as_mut() {
            let (n, width, tiles_x) = (count.max(1) as f64, self.width.max(1) as usize, self.tiles_x as usize);
            let mut blocks = Vec::with_capacity(tiles_x * self.height.div_ceil(TILE) as usize);
            // Each band of TILE rows, cut into its tiles' pieces of each row.
            for band in means.chunks_mut(TILE as usize * width) {
                let mut rows: Vec<_> = band.chunks_mut(width).map(|row| row.chunks_mut(TILE as usize)).collect();
                for _ in 0..tiles_x {
                    let pieces = std::array::from_fn(|y| rows.get_mut(y).and_then(Iterator::next).unwrap_or_default());
                    blocks.push(TileBlock { sums: &mut [], squares: None, means: Some((pieces, n)) });
                }
            }
            blocks
        } else {
            let sums = self.sums.chunks_mut(TILE_PIXELS);
            match self.squares.as_mut() {
                Some(q) => sums
                    .zip(q.chunks_mut(TILE_PIXELS))
                    .map(|(sums, squares)| TileBlock { sums, squares: Some(squares), means: None })
                    .collect(),
                None => sums.map(|sums| TileBlock { sums, squares: None, means: None }).collect(),
            }
        };
        blocks.into_par_iter()
    }

    /// Adds the samples of `pass` (a film of the same size) to this one, pixel by
    /// pixel in the order the samples were taken. A pass that sampled only some
    /// pixels (zeros elsewhere) is counted by [`Film::add_counts`] first.
    pub(crate) fn add(&mut self, pass: &Film) {
        debug_assert_eq!((self.width, self.height), (pass.width, pass.height));
        debug_assert!(self.means.is_none() && pass.means.is_none(), "a means-only film holds one pass");
        if self.squares.is_none() {
            // At most one sample so far: its square is its sum's.
            self.squares = Some(self.sums.par_iter().map(|s| s.map(|v| v * v)).collect());
        }
        let squares = self.squares.as_mut().expect("made above");
        let add = |mine: &mut Stored, theirs: Stored| {
            for (a, b) in mine.iter_mut().zip(theirs) {
                *a += b;
            }
        };
        squares.par_chunks_mut(TILE_PIXELS).zip(pass.sums.par_chunks(TILE_PIXELS)).enumerate().for_each(|(tile, (mine, sums))| match &pass
            .squares
        {
            Some(q) => mine.iter_mut().zip(&q[tile * TILE_PIXELS..]).for_each(|(m, t)| add(m, *t)),
            None => mine.iter_mut().zip(sums).for_each(|(m, s)| add(m, s.map(|v| v * v))),
        });
        self.sums.par_chunks_mut(TILE_PIXELS).zip(pass.sums.par_chunks(TILE_PIXELS)).for_each(|(mine, theirs)| {
            mine.iter_mut().zip(theirs).for_each(|(m, t)| add(m, *t));
        });
        if self.counts.is_none() {
            // Otherwise `add_counts` has already counted this pass.
            self.samples += pass.samples;
        }
    }

    /// Records that every pixel now holds `samples` samples.
    pub(crate) fn set_samples(&mut self, samples: u32) {
        self.samples = samples;
    }

    /// Records that the pixels `active` marks (row-major, one per pixel) took
    /// `count` more samples in the pass just added and the others none.
    pub(crate) fn add_counts(&mut self, active: &[bool], count: u32) {
        debug_assert_eq!(active.len(), self.width as usize * self.height as usize);
        if self.counts.is_none() {
            self.counts = Some(vec![self.samples; self.sums.len().max(self.means.as_ref().map_or(0, Vec::len))]);
        }
        let (width, tiles_x, row_major) = (self.width, self.tiles_x, self.means.is_some());
        let counts = self.counts.as_mut().expect("made above");
        for (k, _) in active.iter().enumerate().filter(|(_, a)| **a) {
            let (x, y) = (k as u32 % width, k as u32 / width);
            let i = storage_index(width, tiles_x, row_major, x, y);
            counts[i] += count;
            self.samples = self.samples.max(counts[i]);
        }
    }

    /// Sets the pixel at column `x`, row `y` to the sums of `count` samples
    /// (composing an adaptive render; the film must keep sums, not means only).
    pub(crate) fn set_pixel(&mut self, x: u32, y: u32, sum: PixelSum, count: u32) {
        debug_assert!(self.means.is_none());
        let i = self.index(x, y);
        let len = self.sums.len();
        let samples = self.samples;
        self.sums[i] = sum.sum.to_array();
        self.squares.get_or_insert_with(|| vec![[0.0; 3]; len])[i] = sum.sum_sq.to_array();
        self.counts.get_or_insert_with(|| vec![samples; len])[i] = count;
        self.samples = self.samples.max(count);
    }
}

/// Index in storage of the pixel at column `x`, row `y` of a film `width` wide
/// with `tiles_x` tiles a row: row-major for a means-only film, else tile by tile.
fn storage_index(width: u32, tiles_x: u32, row_major: bool, x: u32, y: u32) -> usize {
    if row_major {
        return y as usize * width as usize + x as usize;
    }
    let tile = (y / TILE) as usize * tiles_x as usize + (x / TILE) as usize;
    tile * TILE_PIXELS + ((y % TILE) * TILE + x % TILE) as usize
}

/// Variance of the mean of `n` samples with sums `sum` and `sum_sq`, per channel:
/// `(sum_sq / n - mean^2) n / (n - 1) / n`, clamped at 0 against rounding.
pub(crate) fn variance_of_mean(sum: Rgb, sum_sq: Rgb, n: f64) -> Rgb {
    let mean = sum / n;
    ((sum_sq / n - mean * mean) * (n / (n - 1.0))).max(Rgb::ZERO) / n
}

/// One tile's pixels of a film, written by the worker rendering that tile.
pub(crate) struct TileBlock<'a> {
    sums: &'a mut [Stored],
    squares: Option<&'a mut [Stored]>,
    /// A means-only film's block, as the piece of each of the tile's rows, and
    /// the pass's sample count.
    means: Option<([&'a mut [[f32; 3]]; TILE as usize], f64)>,
}

impl TileBlock<'_> {
    /// Sets the pixel at column `x`, row `y` of the tile (from its top-left corner).
    #[inline]
    pub(crate) fn set(&mut self, x: u32, y: u32, sum: PixelSum) {
        if let Some((rows, n)) = self.means.as_mut() {
            // The arithmetic of `Film::mean`, so the bits are the same.
            let m = sum.sum / *n;
            rows[y as usize][x as usize] = [m.x as f32, m.y as f32, m.z as f32];
            return;
        }
        let i = (y * TILE + x) as usize;
        self.sums[i] = sum.sum.to_array();
        if let Some(squares) = self.squares.as_mut() {
            squares[i] = sum.sum_sq.to_array();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A film whose pixel (x, y) holds the samples `v = x + 100 y` and, with two
    /// samples, `2 v`, written as a render writes them.
    fn film(width: u32, height: u32, samples: u32) -> Film {
        let mut film = Film::new(width, height);
        film.prepare_pass(samples);
        let tiles_x = film.tiles_x();
        for (t, mut block) in film.tiles_mut(samples).collect::<Vec<_>>().into_iter().enumerate() {
            let (tx, ty) = (t as u32 % tiles_x, t as u32 / tiles_x);
            for (lx, ly) in (0..TILE).flat_map(|ly| (0..TILE).map(move |lx| (lx, ly))) {
                let (x, y) = (tx * TILE + lx, ty * TILE + ly);
                if x < width && y < height {
                    let v = Rgb::splat((x + 100 * y) as f64);
                    let mut s = PixelSum::default();
                    for k in 1..=samples {
                        s.add(v * k as f64);
                    }
                    block.set(lx, ly, s);
                }
            }
        }
        film.set_samples(samples);
        film
    }

    #[test]
    fn tiles_map_back_to_rows() {
        // Sizes that are and are not multiples of the tile.
        for (w, h) in [(37, 23), (16, 16), (1, 40), (33, 1)] {
            let film = film(w, h, 2);
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
    fn a_means_only_film_develops_the_same_image_without_a_copy() {
        // Written as a render writes, tile by tile: row-major means whose image
        // is the full film's to the bit, at sizes off and on the tile grid.
        for (w, h, samples) in [(37, 23, 3), (16, 16, 1), (1, 40, 2), (33, 1, 5), (0, 7, 1)] {
            let full = film(w, h, samples);
            let mut means = Film::means_only(w, h);
            let tiles_x = means.tiles_x();
            let blocks: Vec<TileBlock> = means.tiles_mut(samples).collect();
            assert_eq!(blocks.len(), (tiles_x * h.div_ceil(TILE)) as usize, "{w}x{h}");
            for (t, mut block) in blocks.into_iter().enumerate() {
                let (tx, ty) = (t as u32 % tiles_x, t as u32 / tiles_x);
                for (lx, ly) in (0..TILE).flat_map(|ly| (0..TILE).map(move |lx| (lx, ly))) {
                    let (x, y) = (tx * TILE + lx, ty * TILE + ly);
                    if x < w && y < h {
                        block.set(lx, ly, full.get(x, y));
                    }
                }
            }
            means.set_samples(samples);
            let expected = full.mean();
            assert_eq!(means.mean(), expected, "{w}x{h}");
            if w > 0 && h > 0 {
                assert_eq!(means.get(w - 1, h - 1).sum.x as f32, expected.get(w - 1, h - 1)[0] * samples as f32);
            }
            let buffer = means.means.as_ref().map(|m| m.as_ptr());
            let image = means.into_mean();
            assert_eq!(Some(image.pixels.as_ptr()), buffer, "handed over, not copied");
            assert_eq!(image, expected);
        }
    }

    #[test]
    fn single_samples_keep_their_squares_implicit_and_exact() {
        // Two one-sample passes give the bits of one two-sample pass: the first
        // pass's squares appear as its sums squared, the second's likewise.
        let mut two_passes = film(20, 3, 1);
        assert!(two_passes.squares.is_none());
        assert_eq!(two_passes.get(19, 2).sum_sq, Rgb::splat(219.0 * 219.0));
        assert_eq!(two_passes.variance(), Image::new(20, 3), "one sample: no variance");
        let second = film(20, 3, 1);
        two_passes.add(&second);
        two_passes.add(&film(20, 3, 2));
        assert_eq!(two_passes.samples(), 4);
        let v = 219.0;
        assert_eq!(two_passes.get(19, 2).sum, Rgb::splat(v + v + 3.0 * v));
        assert_eq!(two_passes.get(19, 2).sum_sq, Rgb::splat(v * v + v * v + 5.0 * v * v));
        assert_eq!(Film::new(5, 5).mean(), Image::new(5, 5), "no samples: black");
        assert_eq!(Film::new(5, 5).variance(), Image::new(5, 5));
    }
}
