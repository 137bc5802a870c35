//! The film: a linear-radiance RGB image, and the sRGB encoding used for display formats.

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
    /// with [`srgb_encode`] and rounded.
    pub fn to_srgb8(&self) -> Vec<u8> {
        self.pixels.iter().flat_map(|p| p.map(|c| (srgb_encode(c as f64) * 255.0).round() as u8)).collect()
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
}
