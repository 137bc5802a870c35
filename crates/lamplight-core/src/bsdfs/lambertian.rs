//! Lambertian reflection: `f = albedo / pi`, sampled with the cosine-weighted
//! hemisphere (`pdf = cos(theta_i) / pi`), so each sample's weight `f cos / pdf`
//! is exactly the albedo.

use std::f64::consts::{FRAC_1_PI, FRAC_PI_4};

use super::{Lobe, Sampled, Scatter};
use crate::math::{sin_cos_quarter, Rgb, Vec3};

/// `albedo / pi` when both directions lie above the surface (local `z > 0`), else 0.
#[inline]
pub fn f(albedo: Rgb, wo: Vec3, wi: Vec3) -> Rgb {
    if wo.z > 0.0 && wi.z > 0.0 {
        albedo * FRAC_1_PI
    } else {
        Rgb::ZERO
    }
}

/// Density of [`sample`] in solid angle: `cos(theta_i) / pi` above the surface.
#[inline]
pub fn pdf(wo: Vec3, wi: Vec3) -> f64 {
    if wo.z > 0.0 && wi.z > 0.0 {
        wi.z * FRAC_1_PI
    } else {
        0.0
    }
}

/// A cosine-distributed direction above the surface: a point of the unit disk
/// (Shirley and Chiu's concentric map of `u`) lifted onto the hemisphere.
#[inline]
pub fn sample(u: (f64, f64)) -> Vec3 {
    let (x, y) = concentric_disk(u);
    // The disk point's radius is the larger of |2u - 1|: the height is computed
    // from it directly, alongside the angle rather than after it.
    let radius = (2.0 * u.0 - 1.0).abs().max((2.0 * u.1 - 1.0).abs());
    Vec3::new(x, y, (1.0 - radius * radius).max(0.0).sqrt())
}

/// Shirley and Chiu's area-preserving map of the unit square onto the unit disk.
///
/// Written without branches on the sample (which of `|a|`, `|b|` is larger is a
/// coin flip that a branch predictor loses half the time): the larger coordinate
/// is the radius, the angle `pi/4 * minor / major` is measured from its axis.
#[inline]
pub fn concentric_disk(u: (f64, f64)) -> (f64, f64) {
    let (a, b) = (2.0 * u.0 - 1.0, 2.0 * u.1 - 1.0);
    let a_major = a.abs() > b.abs();
    let (major, minor) = if a_major { (a, b) } else { (b, a) };
    // The centre (major = 0) maps to itself; the division would give 0/0 there.
    let ratio = if major != 0.0 { minor / major } else { 0.0 };
    let (sin, cos) = sin_cos_quarter(FRAC_PI_4 * ratio);
    let (along, across) = (major * cos, major * sin);
    // a major: angle pi/4 * b/a from +x; b major: pi/2 - pi/4 * a/b, i.e. x and y swap.
    if a_major {
        (along, across)
    } else {
        (across, along)
    }
}

/// The Lambertian lobe of albedo `.0`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Lambertian(pub Rgb);

impl Scatter for Lambertian {
    const DELTA: bool = false;

    fn bound(&self) -> Rgb {
        self.0
    }

    fn scaled(self, s: Rgb) -> Lobe {
        Lambertian(self.0 * s).into()
    }

    #[inline]
    fn f(&self, wo: Vec3, wi: Vec3) -> Rgb {
        f(self.0, wo, wi)
    }

    #[inline]
    fn pdf(&self, wo: Vec3, wi: Vec3) -> f64 {
        pdf(wo, wi)
    }

    #[inline]
    fn sample(&self, _wo: Vec3, _u_choice: f64, u: (f64, f64)) -> Option<Sampled> {
        Some(Sampled::Smooth(sample(u)))
    }
}

#[cfg(test)]
mod tests {
    use std::f64::consts::PI;

    use super::*;

    #[test]
    fn concentric_map_matches_its_trigonometric_definition() {
        // Shirley and Chiu's map with libm's sine and cosine of the full angle.
        let reference = |u: (f64, f64)| {
            let (a, b) = (2.0 * u.0 - 1.0, 2.0 * u.1 - 1.0);
            let (r, theta) = if a.abs() > b.abs() { (a, PI / 4.0 * (b / a)) } else { (b, PI / 2.0 - PI / 4.0 * (a / b)) };
            (r * theta.cos(), r * theta.sin())
        };
        let n = 200;
        for i in 0..=n {
            for j in 0..=n {
                let u = (i as f64 / n as f64 * 0.999_999, j as f64 / n as f64 * 0.999_999);
                let (x, y) = concentric_disk(u);
                let (rx, ry) = reference(u);
                assert!((x - rx).abs() < 4e-16 && (y - ry).abs() < 4e-16, "{u:?}: ({x}, {y}) vs ({rx}, {ry})");
            }
        }
        assert_eq!(concentric_disk((0.5, 0.5)), (0.0, 0.0));
    }

    #[test]
    fn samples_follow_the_cosine_density() {
        // Moments of cos(theta) under pdf cos/pi: E[cos] = 2/3, E[cos^2] = 1/2.
        let n = 256;
        let (mut m1, mut m2) = (0.0, 0.0);
        for i in 0..n {
            for j in 0..n {
                let w = sample(((i as f64 + 0.5) / n as f64, (j as f64 + 0.5) / n as f64));
                assert!((w.length() - 1.0).abs() < 1e-12 && w.z >= 0.0);
                m1 += w.z;
                m2 += w.z * w.z;
            }
        }
        let count = (n * n) as f64;
        assert!((m1 / count - 2.0 / 3.0).abs() < 1e-3, "{}", m1 / count);
        assert!((m2 / count - 0.5).abs() < 1e-3);
        let wi = Vec3::new(0.6, 0.0, 0.8);
        assert!((pdf(Vec3::Z, wi) - 0.8 / PI).abs() < 1e-15);
        assert_eq!(f(Rgb::ONE, Vec3::Z, -wi), Rgb::ZERO);
    }
}
