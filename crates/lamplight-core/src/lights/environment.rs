//! Light from infinitely far away in every direction: a constant sky or an
//! equirectangular HDR map, importance-sampled by brightness.
//!
//! Map coordinates of a unit direction `d` (y up): `u = (pi + atan2(d.x, -d.z)) / (2 pi)`,
//! `v = acos(d.y) / pi` (`v = 0` at the zenith, the image's top row; the image
//! centre looks along `-z`). A pixel's value is weighted by `sin(theta)` of its row
//! when building the sampling distribution; the density in solid angle is
//! `pdf(u, v) / (2 pi^2 sin(theta))`. A constant sky is sampled uniformly, `1 / (4 pi)`.
//! A map turned by `a` degrees about `+y` ([`EnvMap::with_rotation`]) sends from
//! world direction `d` what the unturned map sends from `R(-a) d`; turning keeps
//! solid angle, so densities are the same at the matching directions.

use std::f64::consts::PI;

use crate::math::{Rgb, Vec3};
use crate::sampling::Distribution2d;
use crate::Error;

/// An equirectangular radiance map with its sampling distribution.
#[derive(Clone, Debug, PartialEq)]
pub struct EnvMap {
    width: usize,
    height: usize,
    pixels: Vec<Rgb>,
    distribution: Distribution2d,
    /// `(sin a, cos a)` of the turn about `+y`; `None` for none (no arithmetic, so
    /// an unturned map gives exactly the directions of the formulas above).
    rotation: Option<(f64, f64)>,
}

impl EnvMap {
    /// A map of `width x height` linear RGB pixels, row-major from the top.
    pub fn new(width: usize, height: usize, pixels: Vec<Rgb>) -> Result<EnvMap, Error> {
        if width == 0 || height == 0 || pixels.len() != width * height {
            return Err(Error::invalid("environment map", "size does not match the pixel count"));
        }
        if pixels.iter().any(|p| !(p.is_finite() && p.min_element() >= 0.0)) {
            return Err(Error::invalid("environment map", "pixels must be finite and non-negative"));
        }
        let weights: Vec<f64> = pixels
            .iter()
            .enumerate()
            .map(|(i, p)| {
                let theta = PI * ((i / width) as f64 + 0.5) / height as f64;
                luminance(*p) * theta.sin()
            })
            .collect();
        let distribution = Distribution2d::new(&weights, width, height);
        Ok(EnvMap { width, height, pixels, distribution, rotation: None })
    }

    /// The map turned by `degrees` about `+y` (seen from above, counter-clockwise:
    /// the image centre, along `-z` unturned, then looks along `R(a) (-z)`).
    pub fn with_rotation(self, degrees: f64) -> EnvMap {
        let rotation = (degrees != 0.0 && degrees.is_finite()).then(|| degrees.to_radians().sin_cos());
        EnvMap { rotation, ..self }
    }

    /// The map with every pixel multiplied by `factor` (its turn kept).
    pub fn scaled(&self, factor: Rgb) -> Result<EnvMap, Error> {
        let pixels = self.pixels.iter().map(|p| *p * factor).collect();
        Ok(EnvMap { rotation: self.rotation, ..EnvMap::new(self.width, self.height, pixels)? })
    }

    /// World direction to the map's own frame: `R(-a) d`.
    fn to_map(&self, d: Vec3) -> Vec3 {
        match self.rotation {
            None => d,
            Some((s, c)) => Vec3::new(c * d.x - s * d.z, d.y, s * d.x + c * d.z),
        }
    }

    /// The map's frame to the world: `R(a) m`.
    fn to_world(&self, m: Vec3) -> Vec3 {
        match self.rotation {
            None => m,
            Some((s, c)) => Vec3::new(c * m.x + s * m.z, m.y, -s * m.x + c * m.z),
        }
    }

    fn lookup(&self, u: f64, v: f64) -> Rgb {
        let x = ((u * self.width as f64) as usize).min(self.width - 1);
        let y = ((v * self.height as f64) as usize).min(self.height - 1);
        self.pixels[y * self.width + x]
    }
}

/// Rec. 709 luminance.
pub fn luminance(c: Rgb) -> f64 {
    0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z
}

/// Map coordinates of a unit direction.
pub fn direction_to_uv(d: Vec3) -> (f64, f64) {
    let u = (PI + d.x.atan2(-d.z)) / (2.0 * PI);
    let v = d.y.clamp(-1.0, 1.0).acos() / PI;
    (u.clamp(0.0, 1.0 - f64::EPSILON), v.clamp(0.0, 1.0 - f64::EPSILON))
}

/// The unit direction of map coordinates `(u, v)`.
pub fn uv_to_direction(u: f64, v: f64) -> Vec3 {
    let theta = v * PI;
    let phi = u * 2.0 * PI - PI;
    Vec3::new(theta.sin() * phi.sin(), theta.cos(), -theta.sin() * phi.cos())
}

/// Where light that reaches nothing comes from.
#[derive(Clone, Debug, PartialEq)]
pub enum Environment {
    /// The same radiance from every direction.
    Constant(Rgb),
    /// An HDR map.
    Map(EnvMap),
}

impl Environment {
    /// Radiance arriving from direction `d` (travelling along `-d`).
    pub fn radiance(&self, d: Vec3) -> Rgb {
        match self {
            Environment::Constant(c) => *c,
            Environment::Map(m) => {
                let (u, v) = direction_to_uv(m.to_map(d));
                m.lookup(u, v)
            }
        }
    }

    /// A direction towards the sky, its radiance and solid-angle density.
    pub fn sample(&self, u: (f64, f64)) -> Option<(Vec3, Rgb, f64)> {
        match self {
            Environment::Constant(c) => {
                let z = 1.0 - 2.0 * u.0;
                let r = (1.0 - z * z).max(0.0).sqrt();
                let phi = 2.0 * PI * u.1;
                Some((Vec3::new(r * phi.cos(), r * phi.sin(), z), *c, 1.0 / (4.0 * PI)))
            }
            Environment::Map(m) => {
                let ((x, y), p) = m.distribution.sample(u);
                let sin_theta = (y * PI).sin();
                if !(p > 0.0 && sin_theta > 0.0) {
                    return None;
                }
                let d = m.to_world(uv_to_direction(x, y));
                Some((d, m.lookup(x, y), p / (2.0 * PI * PI * sin_theta)))
            }
        }
    }

    /// Solid-angle density of [`Environment::sample`] for direction `d`.
    pub fn pdf(&self, d: Vec3) -> f64 {
        match self {
            Environment::Constant(_) => 1.0 / (4.0 * PI),
            Environment::Map(m) => {
                let (u, v) = direction_to_uv(m.to_map(d));
                let sin_theta = (v * PI).sin();
                if sin_theta <= 0.0 {
                    return 0.0;
                }
                m.distribution.pdf(u, v) / (2.0 * PI * PI * sin_theta)
            }
        }
    }
}

impl super::Light for Environment {
    /// Not a delta light: the Whitted integrator sees the sky as its background.
    fn illuminate(&self, _point: Vec3) -> Option<super::LightSample> {
        None
    }

    /// A direction towards the sky ([`Environment::sample`]), infinitely far.
    fn sample_li(&self, _point: Vec3, u: (f64, f64)) -> Option<super::LiSample> {
        let (wi, radiance, pdf) = self.sample(u)?;
        Some(super::LiSample { wi, distance: f64::INFINITY, radiance, pdf: Some(pdf), own_object: None, ends_on_own: false })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn uv_mapping_round_trips() {
        for d in [Vec3::new(0.3, 0.5, -0.2), Vec3::new(-0.7, -0.1, 0.4), Vec3::new(0.1, 0.9, 0.9)] {
            let d = d.normalize();
            let (u, v) = direction_to_uv(d);
            assert!((uv_to_direction(u, v) - d).length() < 1e-12);
        }
        assert!((uv_to_direction(0.5, 0.5) - -Vec3::Z).length() < 1e-12);
    }

    #[test]
    fn map_sampling_estimates_the_irradiance_integral() {
        // A map bright in one patch: E[L / pdf] over samples = integral of L over the sphere,
        // which quadrature over the pixels gives exactly.
        let (w, h) = (16, 8);
        let mut pixels = vec![Rgb::splat(0.1); w * h];
        pixels[2 * w + 5] = Rgb::splat(50.0);
        let env = Environment::Map(EnvMap::new(w, h, pixels.clone()).unwrap());
        let mut exact = 0.0;
        for y in 0..h {
            let (t0, t1) = (PI * y as f64 / h as f64, PI * (y + 1) as f64 / h as f64);
            let solid = 2.0 * PI / w as f64 * (t0.cos() - t1.cos());
            exact += (0..w).map(|x| pixels[y * w + x].x * solid).sum::<f64>();
        }
        let n = 256;
        let mut est = 0.0;
        for i in 0..n {
            for j in 0..n {
                let (d, l, p) = env.sample(((i as f64 + 0.5) / n as f64, (j as f64 + 0.5) / n as f64)).unwrap();
                assert!((env.pdf(d) - p).abs() / p < 1e-6);
                est += l.x / p;
            }
        }
        est /= (n * n) as f64;
        assert!((est - exact).abs() / exact < 1e-2, "{est} vs {exact}");
    }

    #[test]
    fn a_turned_map_sends_its_light_from_the_turned_directions() {
        // One bright texel at the image centre (looking along -z unturned).
        let (w, h) = (8, 4);
        let mut pixels = vec![Rgb::splat(0.1); w * h];
        pixels[w + w / 2] = Rgb::splat(9.0);
        let plain = Environment::Map(EnvMap::new(w, h, pixels.clone()).unwrap());
        let turned = Environment::Map(EnvMap::new(w, h, pixels).unwrap().with_rotation(90.0));
        let centre = uv_to_direction(0.5 + 0.5 / w as f64, 1.5 / h as f64);
        // Turned 90 degrees counter-clockwise seen from above, -z goes to -x.
        let moved = Vec3::new(centre.z, centre.y, -centre.x);
        assert_eq!(plain.radiance(centre), Rgb::splat(9.0));
        assert_eq!(turned.radiance(centre), Rgb::splat(0.1));
        assert_eq!(turned.radiance(moved), Rgb::splat(9.0));
        assert!(moved.x < 0.0, "towards -x: {moved}");
        // Sampling and density agree on the turned map, and samples find the bright texel where it went.
        for i in 0..64 {
            for j in 0..64 {
                let (d, l, p) = turned.sample(((i as f64 + 0.5) / 64.0, (j as f64 + 0.5) / 64.0)).unwrap();
                assert!((turned.pdf(d) - p).abs() / p < 1e-6, "pdf at {d}");
                assert_eq!(turned.radiance(d), l, "radiance at {d}");
            }
        }
        assert_eq!(EnvMap::new(1, 1, vec![Rgb::ONE]).unwrap().with_rotation(0.0).rotation, None, "no turn, no arithmetic");
    }
}
