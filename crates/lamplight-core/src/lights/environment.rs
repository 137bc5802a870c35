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
//!
//! A map is looked up at the nearest pixel (pixel `(x, y)` covers
//! `[x, x + 1) / w` by `[y, y + 1) / h`), or, [`EnvMap::bilinear`], as
//! Mitsuba's `envmap` reads it: interpolated bilinearly between pixel values
//! placed at `u = (x + 1/2) / w` (wrapping around from the last column to the
//! first) and `v = y / (h - 1)` (the first row at the zenith, the last at the
//! nadir). Its sampling distribution is then piecewise constant over the
//! `w x (h - 1)` cells between those points, each weighted by the largest
//! luminance of its four corners times `sin(theta)` of its centre, so that
//! every direction with light has a density; `u` is shifted by half a pixel
//! into the cells' grid and back, which keeps the density of a direction the
//! density it was sampled with.

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
    /// Bilinear lookup between pixels (module documentation); `false`: nearest pixel.
    bilinear: bool,
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
        Ok(EnvMap { width, height, pixels, distribution, rotation: None, bilinear: false })
    }

    /// The map looked up bilinearly, as Mitsuba's `envmap` (module
    /// documentation), with the sampling distribution of its cells. Needs at
    /// least two rows (the zenith's and the nadir's).
    pub fn bilinear(self) -> Result<EnvMap, Error> {
        let (w, h) = (self.width, self.height);
        if h < 2 {
            return Err(Error::invalid("environment map", "bilinear lookup needs at least two rows"));
        }
        let lum = |x: usize, y: usize| luminance(self.pixels[y * w + x % w]);
        let mut weights = Vec::with_capacity(w * (h - 1));
        for y in 0..h - 1 {
            let sin_theta = (PI * (y as f64 + 0.5) / (h - 1) as f64).sin();
            for x in 0..w {
                let corners = lum(x, y).max(lum(x + 1, y)).max(lum(x, y + 1)).max(lum(x + 1, y + 1));
                weights.push(corners * sin_theta);
            }
        }
        let distribution = Distribution2d::new(&weights, w, h - 1);
        Ok(EnvMap { distribution, bilinear: true, ..self })
    }

    /// Whether the map is looked up bilinearly ([`EnvMap::bilinear`]).
    pub fn is_bilinear(&self) -> bool {
        self.bilinear
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
        let map = EnvMap { rotation: self.rotation, ..EnvMap::new(self.width, self.height, pixels)? };
        if self.bilinear {
            map.bilinear()
        } else {
            Ok(map)
        }
    }

    /// Map `u` to the sampling distribution's `u`: the same, or for a
    /// bilinear map shifted by half a pixel to the grid of its cells.
    fn u_to_cells(&self, u: f64) -> f64 {
        if self.bilinear {
            let x = u - 0.5 / self.width as f64;
            x - x.floor()
        } else {
            u
        }
    }

    /// The inverse of [`EnvMap::u_to_cells`].
    fn cells_to_u(&self, x: f64) -> f64 {
        if self.bilinear {
            let u = x + 0.5 / self.width as f64;
            (u - u.floor()).min(1.0 - f64::EPSILON)
        } else {
            x
        }
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

    /// The radiance at map coordinates `(u, v)`: the nearest pixel, or the
    /// bilinear interpolation of the four around it (module documentation).
    fn lookup(&self, u: f64, v: f64) -> Rgb {
        if self.bilinear {
            let (w, h) = (self.width, self.height);
            let fx = u * w as f64 - 0.5;
            let x0f = fx.floor();
            let tx = fx - x0f;
            let x0 = (x0f as i64).rem_euclid(w as i64) as usize;
            let x1 = (x0 + 1) % w;
            let fy = (v * (h - 1) as f64).clamp(0.0, (h - 1) as f64);
            let y0 = (fy as usize).min(h - 2);
            let ty = fy - y0 as f64;
            let at = |x: usize, y: usize| self.pixels[y * w + x];
            let top = at(x0, y0) * (1.0 - tx) + at(x1, y0) * tx;
            let bottom = at(x0, y0 + 1) * (1.0 - tx) + at(x1, y0 + 1) * tx;
            return top * (1.0 - ty) + bottom * ty;
        }
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
                let x = m.cells_to_u(x);
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
                m.distribution.pdf(m.u_to_cells(u), v) / (2.0 * PI * PI * sin_theta)
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

    /// The 4 x 3 map of the probe below: pixel `(x, y)` is `(x + 1, y + 1, 10 (x + 1) + y + 1)`.
    fn probe_map() -> EnvMap {
        let pixels =
            (0..3).flat_map(|y| (0..4).map(move |x| Rgb::new(x as f64 + 1.0, y as f64 + 1.0, 10.0 * (x as f64 + 1.0) + y as f64 + 1.0)));
        EnvMap::new(4, 3, pixels.collect()).unwrap().bilinear().unwrap()
    }

    #[test]
    fn a_bilinear_map_reads_as_mitsubas_envmap() {
        // Mitsuba 3.9.1 scalar_rgb, `envmap` of this bitmap, `eval` towards map
        // coordinates (u, v) (Mitsuba's u is lamplight's minus 1/2, which the
        // reader's 180 degree turn gives; here both are the map's own u).
        let env = Environment::Map(probe_map());
        let at = |u: f64, v: f64| env.radiance(uv_to_direction(u, v));
        let close = |a: Rgb, b: [f64; 3]| (a - Rgb::from_array(b)).abs().max_element() < 1e-9;
        for (u, v, mitsuba) in [
            (0.125, 0.5, [1.0, 2.0, 12.0]),
            (0.25, 0.5, [1.5, 2.0, 17.0]),
            (0.375, 0.5, [2.0, 2.0, 22.0]),
            (0.5, 0.5, [2.5, 2.0, 27.0]),
            (0.875, 0.5, [4.0, 2.0, 42.0]),
            (0.95, 0.5, [3.1, 2.0, 33.0]),
            (0.125, 0.25, [1.0, 1.5, 11.5]),
            (0.125, 0.75, [1.0, 2.5, 12.5]),
            (0.125, 1.0 - 1e-12, [1.0, 3.0, 13.0]),
        ] {
            assert!(close(at(u, v), mitsuba), "({u}, {v}): {} vs {mitsuba:?}", at(u, v));
        }
        // The nearest-pixel map of the same pixels stays as it was.
        let nearest = Environment::Map(EnvMap::new(4, 3, (0..12).map(|i| Rgb::splat(i as f64)).collect()).unwrap());
        assert_eq!(nearest.radiance(uv_to_direction(0.3, 0.5)), Rgb::splat(5.0));
    }

    #[test]
    fn a_bilinear_maps_density_integrates_to_one_and_its_samples_to_the_radiance_integral() {
        // A dark map with one bright pixel and a turn: the density over the sphere
        // (midpoint quadrature in (u, v)) sums to 1, each sample's density is the
        // one `pdf` gives, and E[L / pdf] is the integral of the interpolated radiance.
        let (w, h) = (16, 9);
        let mut pixels = vec![Rgb::splat(0.1); w * h];
        pixels[3 * w + 5] = Rgb::splat(50.0);
        pixels[w - 1] = Rgb::splat(20.0); // the first row's last pixel: the wrap and the zenith
        let env = Environment::Map(EnvMap::new(w, h, pixels).unwrap().bilinear().unwrap().with_rotation(30.0));
        let n = 512;
        let (mut total_pdf, mut exact) = (0.0, 0.0);
        for i in 0..n {
            for j in 0..n {
                let (u, v) = ((i as f64 + 0.5) / n as f64, (j as f64 + 0.5) / n as f64);
                let d = EnvMap::new(1, 1, vec![Rgb::ONE]).unwrap().with_rotation(30.0).to_world(uv_to_direction(u, v));
                let solid = 2.0 * PI * PI * (v * PI).sin() / (n * n) as f64;
                total_pdf += env.pdf(d) * solid;
                exact += env.radiance(d).x * solid;
            }
        }
        assert!((total_pdf - 1.0).abs() < 2e-3, "density integrates to {total_pdf}");
        let m = 256;
        let mut est = 0.0;
        for i in 0..m {
            for j in 0..m {
                let (d, l, p) = env.sample(((i as f64 + 0.5) / m as f64, (j as f64 + 0.5) / m as f64)).unwrap();
                assert!((env.pdf(d) - p).abs() / p < 1e-6, "pdf at {d}: {} vs {p}", env.pdf(d));
                assert!((env.radiance(d) - l).abs().max_element() < 1e-9 * (1.0 + l.max_element()), "radiance at {d}");
                est += l.x / p;
            }
        }
        est /= (m * m) as f64;
        assert!((est - exact).abs() / exact < 1e-2, "{est} vs {exact}");
        // Scaling keeps the lookup.
        let Environment::Map(map) = &env else { unreachable!() };
        assert!(map.scaled(Rgb::splat(2.0)).unwrap().is_bilinear());
        assert!(EnvMap::new(4, 1, vec![Rgb::ONE; 4]).unwrap().bilinear().is_err());
    }
}
