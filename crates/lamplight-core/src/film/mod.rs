//! The film: the per-pixel sums a render accumulates ([`Film`]), the linear-radiance
//! RGB image developed from them ([`Image`]), the sRGB encoding used for display formats,
//! and the rectangle of its pixels a render covers ([`PixelWindow`]).

mod accumulated;
mod filter;

pub mod tonemap;
mod window;

pub(crate) use accumulated::{variance_of_mean, TileBlock};
pub use accumulated::{Film, PixelSum, TILE};
pub use filter::{Filter, FilterSampler, FILTER_NAMES, MAX_LOBES};
pub use window::PixelWindow;

/// Largest sample radiance the film accepts, per channel. A sample beyond it
/// (or NaN, or infinite) is replaced by black and counted
/// ([`crate::RenderStats::nonfinite_samples`]), so that every pixel's mean and
/// variance fit an `f32` (`1e18^2` is far below `f32::MAX`, about `3.4e38`) and no
/// infinity reaches an image. This is the guard on brightness: scene inputs
/// are only refused when they do not fit an `f32` on their own
/// ([`crate::params::MAX_COLOR`]), since a physically consistent scene's
/// intensities grow as the square of its size while the radiance that reaches
/// the film does not; radiance is computed in `f64` (products of a few inputs
/// of `3.4e38` stay finite, and any that overflow become infinite or NaN and
/// are dropped here).
pub const MAX_RADIANCE: f64 = 1e18;

/// Whether the film accepts sample radiance `l` (see [`MAX_RADIANCE`]).
#[inline]
pub fn accepts(l: crate::math::Rgb) -> bool {
    // `max_element` skips NaN, so finiteness is checked on its own.
    l.is_finite() && l.abs().max_element() <= MAX_RADIANCE
}

/// What the film keeps of sample radiance `l`: `None` if it does not accept it
/// ([`accepts`]), else `l`, scaled by `clamp / max(l)` when its largest channel
/// exceeds `clamp` (hue kept; see [`crate::RenderOptions::clamp`]).
#[inline]
pub fn kept(l: crate::math::Rgb, clamp: f64) -> Option<crate::math::Rgb> {
    if !accepts(l) {
        return None;
    }
    let peak = l.max_element();
    Some(if peak > clamp { l * (clamp / peak) } else { l })
}

/// A linear RGB image, row-major from the top-left pixel.
#[derive(Clone, Debug, PartialEq)]
pub struct Image {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// `width * height` pixels of linear radiance.
    pub pixels: Vec<[f32; 3]>,
}

impl Image {
    /// A black image.
    pub fn new(width: u32, height: u32) -> Image {
        Image { width, height, pixels: crate::pages::zeroed([0.0; 3], width as usize * height as usize) }
    }

    /// The pixel at column `x`, row `y` (from the top).
    pub fn get(&self, x: u32, y: u32) -> [f32; 3] {
        self.pixels[y as usize * self.width as usize + x as usize]
    }

    /// 8-bit sRGB bytes, three per pixel: each channel clamped to `[0, 1]`, encoded
    /// with [`srgb_encode`] and rounded (see [`srgb8`]).
    pub fn to_srgb8(&self) -> Vec<u8> {
        // In parallel: for a large image this is the longest serial step after
        // the render (about 18 instructions per channel).
        use rayon::prelude::*;
        let quantizer = Srgb8::get();
        self.pixels.as_flattened().par_iter().with_min_len(1 << 16).map(|&c| quantizer.encode(c)).collect()
    }
}

impl Image {
    /// The pixels as 8-bit values of the linear numbers themselves:
    /// `round(255 clamp(x, 0, 1))`, NaN as 0 (for display-referred scenes whose
    /// numbers are already what a screen shows, as POV-Ray's `File_Gamma 1`).
    pub fn to_linear8(&self) -> Vec<u8> {
        self.pixels.as_flattened().iter().map(|&c| if c > 0.0 { (c.min(1.0) * 255.0).round() as u8 } else { 0 }).collect()
    }
}

/// `round(255 * srgb_encode(x))`, equal to the direct formula for every `f32` input
/// (NaN gives 0), without a `pow` per value. See [`Srgb8`].
pub fn srgb8(x: f32) -> u8 {
    Srgb8::get().encode(x)
}

/// Mantissa bits of an `f32` that, with its exponent, select a bucket.
const BUCKET_MANTISSA_BITS: u32 = 8;
const BUCKET_SHIFT: u32 = 23 - BUCKET_MANTISSA_BITS;

/// The exact 8-bit sRGB quantizer as two small tables.
///
/// `boundaries[k]` is the smallest `f32` whose code exceeds `k`, found by bisection
/// on the bit patterns (which order like the values for non-negative floats)
/// against the direct formula. For a value in `[boundaries[0], boundaries[254])`,
/// its exponent and top mantissa bits select a bucket; `bucket_codes` holds the
/// code at the bucket's lowest value, and since no bucket holds two boundaries
/// (a bucket is at most 2^-8 of its values wide, narrower than the gap between
/// neighbouring boundaries; a test checks every bucket) one comparison with the
/// next boundary finishes the job.
#[derive(Debug)]
pub struct Srgb8 {
    /// 255 boundaries, padded to 256 so a `u8` code indexes it without a check.
    boundaries: [f32; 256],
    first_bucket: u32,
    /// Codes of the buckets from `first_bucket` on, padded to a power of two so
    /// that a masked index needs no check.
    bucket_codes: Box<[u8; BUCKET_TABLE]>,
}

/// Size of the bucket table: at least the 13 binades from `boundaries[0]` (about
/// 2^-13) to 1, times 2^BUCKET_MANTISSA_BITS buckets each.
const BUCKET_TABLE: usize = 4096;

impl Srgb8 {
    /// The shared quantizer, built on first use (about a millisecond).
    pub fn get() -> &'static Srgb8 {
        static TABLE: std::sync::OnceLock<Srgb8> = std::sync::OnceLock::new();
        TABLE.get_or_init(Srgb8::build)
    }

    fn build() -> Srgb8 {
        let direct = |v: f32| (srgb_encode(v as f64) * 255.0).round() as u8;
        let mut boundaries = [f32::INFINITY; 256];
        for (k, slot) in boundaries[..255].iter_mut().enumerate() {
            let (mut lo, mut hi) = (0u32, 1f32.to_bits());
            while lo < hi {
                let mid = lo + (hi - lo) / 2;
                if direct(f32::from_bits(mid)) > k as u8 {
                    hi = mid;
                } else {
                    lo = mid + 1;
                }
            }
            *slot = f32::from_bits(lo);
        }
        let first_bucket = boundaries[0].to_bits() >> BUCKET_SHIFT;
        let last_bucket = boundaries[254].to_bits() >> BUCKET_SHIFT;
        assert!(((last_bucket - first_bucket) as usize) < BUCKET_TABLE, "the bucket table covers [boundaries[0], 1)");
        let mut bucket_codes = Box::new([255u8; BUCKET_TABLE]);
        for (bucket, code) in (first_bucket..=last_bucket).zip(bucket_codes.iter_mut()) {
            let lowest = f32::from_bits(bucket << BUCKET_SHIFT);
            *code = boundaries[..255].partition_point(|&b| b <= lowest) as u8;
        }
        Srgb8 { boundaries, first_bucket, bucket_codes }
    }

    /// The code of linear value `x` (clamped to `[0, 1]`; NaN gives 0).
    #[inline]
    pub fn encode(&self, x: f32) -> u8 {
        // `!(x >= b)` is also true for NaN.
        if !(x >= self.boundaries[0]) {
            return 0;
        }
        if x >= self.boundaries[254] {
            return 255;
        }
        let bucket = ((x.to_bits() >> BUCKET_SHIFT) - self.first_bucket) as usize;
        let code = self.bucket_codes[bucket & (BUCKET_TABLE - 1)];
        code + (x >= self.boundaries[code as usize]) as u8
    }
}

/// The sRGB transfer curve (IEC 61966-2-1) on a value clamped to `[0, 1]`:
/// `12.92 x` for `x <= 0.0031308`, else `1.055 x^(1/2.4) - 0.055`. NaN maps to 0.
pub fn srgb_encode(x: f64) -> f64 {
    let x = if x.is_nan() { 0.0 } else { x.clamp(0.0, 1.0) };
    if x <= 0.0031308 {
        12.92 * x
    } else {
        1.055 * x.powf(1.0 / 2.4) - 0.055
    }
}

/// The inverse of [`srgb_encode`]: `x / 12.92` for `x <= 0.04045`, else
/// `((x + 0.055) / 1.055)^2.4`, on a value clamped to `[0, 1]` (8-bit colour
/// textures and vertex colours are stored encoded).
pub fn srgb_decode(x: f64) -> f64 {
    let x = if x.is_nan() { 0.0 } else { x.clamp(0.0, 1.0) };
    if x <= 0.04045 {
        x / 12.92
    } else {
        ((x + 0.055) / 1.055).powf(2.4)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn srgb_decode_inverts_the_encoding() {
        for x in [0.0, 0.002, 0.01, 0.2, 0.5, 0.99, 1.0] {
            assert!((srgb_decode(srgb_encode(x)) - x).abs() < 1e-12, "{x}");
        }
    }

    #[test]
    fn srgb_curve_values() {
        assert_eq!(srgb_encode(0.0), 0.0);
        assert!((srgb_encode(1.0) - 1.0).abs() < 1e-12);
        assert!((srgb_encode(0.18) - 0.461356).abs() < 1e-5);
        assert_eq!(srgb_encode(2.0), srgb_encode(1.0));
        assert_eq!(srgb_encode(f64::NAN), 0.0);
        let img = Image { width: 1, height: 1, pixels: vec![[0.0, 0.5, 1.0]] };
        assert_eq!(img.to_srgb8(), vec![0, 188, 255]);
    }

    #[test]
    fn quantizer_equals_the_direct_formula() {
        let direct = |v: f32| (srgb_encode(v as f64) * 255.0).round() as u8;
        // Every f32 in [0, 1] with a stride, plus values around each boundary.
        let mut bits = 0u32;
        while bits <= 1f32.to_bits() {
            let v = f32::from_bits(bits);
            assert_eq!(srgb8(v), direct(v), "{v}");
            bits += 997;
        }
        for v in [-1.0f32, 0.0, 1.0, 2.0, f32::INFINITY, f32::NEG_INFINITY, f32::MIN_POSITIVE] {
            assert_eq!(srgb8(v), direct(v), "{v}");
        }
        assert_eq!(srgb8(f32::NAN), 0);
    }

    #[test]
    fn quantizer_is_exact_at_every_boundary_and_bucket_edge() {
        let direct = |v: f32| (srgb_encode(v as f64) * 255.0).round() as u8;
        let table = Srgb8::get();
        // Both functions are steps that only rise, so agreeing just below and at
        // every boundary, and at every bucket edge, means agreeing everywhere.
        for &b in &table.boundaries[..255] {
            for v in [b.next_down(), b, b.next_up()] {
                assert_eq!(srgb8(v), direct(v), "{v}");
            }
        }
        let last_bucket = table.boundaries[254].to_bits() >> BUCKET_SHIFT;
        for bucket in table.first_bucket..=last_bucket + 1 {
            let lowest = f32::from_bits(bucket << BUCKET_SHIFT);
            for v in [lowest.next_down(), lowest] {
                assert_eq!(srgb8(v), direct(v), "{v}");
            }
            let inside =
                table.boundaries[..255].iter().filter(|&&b| b > lowest && b < f32::from_bits((bucket + 1) << BUCKET_SHIFT)).count();
            assert!(inside <= 1, "bucket at {lowest} holds {inside} boundaries");
        }
    }
}
