//! Display transforms for 8-bit output: exposure in stops and a filmic curve.
//!
//! The filmic option is Narkowicz's fit of the ACES reference rendering
//! transform, `f(x) = x (2.51 x + 0.03) / (x (2.43 x + 0.59) + 0.14)` clamped
//! to `[0, 1]`, applied per channel to linear radiance before sRGB encoding.

use super::Image;

/// How linear radiance becomes display values before sRGB encoding.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum ToneMap {
    /// Clamp to `[0, 1]`.
    #[default]
    Clamp,
    /// The ACES filmic fit.
    Filmic,
}

impl std::str::FromStr for ToneMap {
    type Err = String;

    fn from_str(s: &str) -> Result<ToneMap, String> {
        match s {
            "clamp" | "none" => Ok(ToneMap::Clamp),
            "filmic" => Ok(ToneMap::Filmic),
            _ => Err(crate::params::unknown("tone map", s, &["clamp", "filmic"])),
        }
    }
}

/// The ACES fit on one value.
pub fn filmic(x: f64) -> f64 {
    let x = x.max(0.0);
    (x * (2.51 * x + 0.03) / (x * (2.43 * x + 0.59) + 0.14)).clamp(0.0, 1.0)
}

/// `image` scaled by `2^exposure` and tone mapped (still linear; sRGB encoding follows).
pub fn apply(image: &Image, exposure: f64, tonemap: ToneMap) -> Image {
    let scale = exposure.exp2();
    let map = |v: f32| -> f32 {
        let x = v as f64 * scale;
        match tonemap {
            ToneMap::Clamp => x as f32,
            ToneMap::Filmic => filmic(x) as f32,
        }
    };
    Image { width: image.width, height: image.height, pixels: image.pixels.iter().map(|p| p.map(map)).collect() }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn filmic_is_monotone_and_bounded() {
        assert_eq!(filmic(0.0), 0.0);
        let mut prev = 0.0;
        for i in 1..1000 {
            let y = filmic(i as f64 * 0.05);
            assert!(y >= prev && y <= 1.0);
            prev = y;
        }
        assert!(filmic(100.0) > 0.99);
        let img = Image { width: 1, height: 1, pixels: vec![[0.25, 0.5, 1.0]] };
        assert_eq!(apply(&img, 1.0, ToneMap::Clamp).pixels[0], [0.5, 1.0, 2.0]);
    }
}
