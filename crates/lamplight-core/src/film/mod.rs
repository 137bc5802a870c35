//! The film: a linear-radiance RGB image, and the sRGB encoding used for display formats.

mod filter;
pub mod tonemap;

pub use filter::Filter;

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
        Image { width, height, pixels: vec![[0.0; 3]; width as usize * height as usize] }
    }

    /// The pixel at column `x`, row `y` (from the top).
    pub fn get(&self, x: u32, y: u32) -> [f32; 3] {
        self.pixels[y as usize * self.width as usize + x as usize]
    }

    /// 8-bit sRGB bytes, three per pixel: each channel clamped to `[0, 1]`, encoded
    /// with [`srgb_encode`] and rounded (see [`srgb8`]).
    pub fn to_srgb8(&self) -> Vec<u8> {
        self.pixels.iter().flat_map(|p| p.map(srgb8)).collect()
    }
}

/// `round(255 * srgb_encode(x))` without a `pow` per value: a binary search over
/// the 255 linear values where the rounded code changes. Each boundary is found by
/// bisection on the `f32` bit patterns against the direct formula, so the result
/// equals the direct formula for every `f32` input.
pub fn srgb8(x: f32) -> u8 {
    static BOUNDARIES: std::sync::OnceLock<[f32; 255]> = std::sync::OnceLock::new();
    let boundaries = BOUNDARIES.get_or_init(|| {
        let direct = |v: f32| (srgb_encode(v as f64) * 255.0).round() as u8;
        let mut table = [0f32; 255];
        for (k, slot) in table.iter_mut().enumerate() {
            // Smallest non-negative f32 whose code exceeds k: bisect on bit patterns,
            // which are ordered like the values for non-negative floats.
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
        table
    });
    if x.is_nan() {
        return 0;
    }
    boundaries.partition_point(|&b| b <= x) as u8
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

#[cfg(test)]
mod tests {
    use super::*;

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
}
