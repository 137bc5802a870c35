//! The film: the per-pixel sums a render accumulates ([`Film`]), the linear-radiance
//! RGB image developed from them ([`Image`]), the sRGB encoding used for display formats,
//! and the rectangle of its pixels a render covers ([`PixelWindow`]).

mod accumulated;
mod filter;
mod srgb8;

pub mod tonemap;
mod window;

pub(crate) use accumulated::{variance_of_mean, TileBlock};
pub use accumulated::{Film, PixelSum, TILE};
pub use filter::{Filter, FilterSampler, FILTER_NAMES, MAX_LOBES};
pub use srgb8::{srgb8, Srgb8};
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
        // the render.
        use rayon::prelude::*;
        const CHUNK: usize = 1 << 16;
        let quantizer = Srgb8::get();
        let values = self.pixels.as_flattened();
        let mut bytes = vec![0u8; values.len()];
        bytes.par_chunks_mut(CHUNK).zip(values.par_chunks(CHUNK)).for_each(|(out, values)| quantizer.encode_all(values, out));
        bytes
    }
}

impl Image {
    /// The pixels as 8-bit values of the linear numbers themselves:
    /// `round(255 clamp(x, 0, 1))`, NaN as 0 (for display-referred scenes whose
    /// numbers are already what a screen shows, as POV-Ray's `File_Gamma 1`).
    pub fn to_linear8(&self) -> Vec<u8> {
        self.pixels.as_flattened().iter().map(|&c| linear8(c)).collect()
    }
}

/// `round(255 clamp(x, 0, 1))`, NaN as 0: a linear value as the 8-bit number
/// itself ([`Image::to_linear8`]).
#[inline]
pub fn linear8(x: f32) -> u8 {
    if x > 0.0 {
        (x.min(1.0) * 255.0).round() as u8
    } else {
        0
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
}
