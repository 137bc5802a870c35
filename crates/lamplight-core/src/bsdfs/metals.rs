//! Measured complex indices of refraction of common metals, reduced to RGB.
//!
//! They are the conductor Fresnel's input, so the conductor lobes' tests use
//! them without reaching up into the materials.

use crate::math::Rgb;

/// A metal with a tabulated complex index of refraction.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Metal {
    /// Gold (Au).
    Gold,
    /// Silver (Ag).
    Silver,
    /// Copper (Cu).
    Copper,
    /// Aluminium (Al).
    Aluminium,
}

impl Metal {
    /// `(eta, k)` per RGB channel: the measured spectral data (Palik's handbook, as
    /// tabulated with pbrt and Mitsuba) averaged over the red, green and blue bands.
    pub fn eta_k(self) -> (Rgb, Rgb) {
        match self {
            Metal::Gold => (Rgb::new(0.18299, 0.42108, 1.37340), Rgb::new(3.42420, 2.34590, 1.77040)),
            Metal::Silver => (Rgb::new(0.15943, 0.14512, 0.13547), Rgb::new(3.92910, 3.19000, 2.38080)),
            Metal::Copper => (Rgb::new(0.27105, 0.67693, 1.31640), Rgb::new(3.60920, 2.62480, 2.29210)),
            Metal::Aluminium => (Rgb::new(1.65746, 0.88032, 0.52123), Rgb::new(9.22387, 6.26952, 4.83700)),
        }
    }

    /// The names [`Metal::from_name`] takes, for messages (`aluminum` is taken too).
    pub const NAMES: [&'static str; 4] = ["gold", "silver", "copper", "aluminium"];

    /// Looks a preset up by its lower-case English name (`gold`, `silver`, `copper`, `aluminium`/`aluminum`).
    pub fn from_name(name: &str) -> Option<Metal> {
        match name {
            "gold" => Some(Metal::Gold),
            "silver" => Some(Metal::Silver),
            "copper" => Some(Metal::Copper),
            "aluminium" | "aluminum" => Some(Metal::Aluminium),
            _ => None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bsdfs::fresnel::fresnel_conductor;

    #[test]
    fn gold_is_yellow_and_silver_is_bright_at_normal_incidence() {
        let (eta, k) = Metal::Gold.eta_k();
        let gold = fresnel_conductor(1.0, eta, k);
        assert!(gold.x > gold.y && gold.y > gold.z, "gold reflects red most, blue least: {gold}");
        let (eta, k) = Metal::Silver.eta_k();
        let silver = fresnel_conductor(1.0, eta, k);
        assert!(silver.min_element() > 0.9, "silver: {silver}");
    }
}
