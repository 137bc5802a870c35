//! Sampling an emitting triangle mesh uniformly by area, so that any mesh (an OBJ
//! with an emissive MTL, a glTF with `emissiveFactor`, a native `mesh` node) is an
//! area light for next-event estimation.
//!
//! A triangle is picked with probability `A_k / A` (a CDF over the triangle areas,
//! [`Distribution1d`]), and a point on it from two uniform numbers by the
//! square-root map `b0 = 1 - sqrt(u0)`, `b1 = u1 sqrt(u0)`, `b2 = 1 - b0 - b1`,
//! `y = b0 p0 + b1 p1 + b2 p2`, which is uniform in area on the triangle (Osada et
//! al. 2002; pbrt's `SampleUniformTriangle` is a variant). The combined density in
//! area is `(A_k / A) (1 / A_k) = 1 / A`, the same for every point, so the
//! solid-angle density at a receiver is [`super::AreaLight::pdf`]'s
//! `|x - y|^2 / (|cos(theta_y)| A)` for any triangle: a BSDF-sampled ray that hits
//! the mesh gets the MIS weight without knowing which triangle it hit.

use crate::math::Vec3;
use crate::sampling::Distribution1d;

/// World-space triangles of an emitter with their area distribution.
#[derive(Clone, Debug)]
pub struct TriangleSampler {
    triangles: Vec<[Vec3; 3]>,
    normals: Vec<Vec3>,
    cdf: Distribution1d,
    area: f64,
}

impl TriangleSampler {
    /// From triangles counter-clockwise seen from their emitting side; `None` when
    /// their total area is zero or not finite. Zero-area triangles are never picked.
    pub fn new(triangles: Vec<[Vec3; 3]>) -> Option<TriangleSampler> {
        let mut areas = Vec::with_capacity(triangles.len());
        let mut normals = Vec::with_capacity(triangles.len());
        for [p0, p1, p2] in &triangles {
            let c = (*p1 - *p0).cross(*p2 - *p0);
            let twice = c.length();
            areas.push(0.5 * twice);
            normals.push(if twice > 0.0 { c / twice } else { Vec3::Z });
        }
        let area: f64 = areas.iter().sum();
        if !(area > 0.0 && area.is_finite()) {
            return None;
        }
        let cdf = Distribution1d::new(&areas);
        Some(TriangleSampler { triangles, normals, cdf, area })
    }

    /// Total area.
    pub fn area(&self) -> f64 {
        self.area
    }

    /// Number of triangles.
    pub fn len(&self) -> usize {
        self.triangles.len()
    }

    /// True when there are no triangles (never: construction needs some area).
    pub fn is_empty(&self) -> bool {
        self.triangles.is_empty()
    }

    /// A point uniform in area over all triangles, with its unit outward normal
    /// and the index of its triangle (the shape's face, for its surface coordinates).
    pub fn sample(&self, u: (f64, f64)) -> Option<(Vec3, Vec3, u32)> {
        let (x, _, k) = self.cdf.sample(u.0);
        // Reuse the position inside the picked cell as a fresh uniform number.
        let n = self.triangles.len() as f64;
        let u0 = (x * n - k as f64).clamp(0.0, 1.0);
        let [p0, p1, p2] = self.triangles[k];
        let s = u0.sqrt();
        let (b0, b1) = (1.0 - s, u.1 * s);
        let y = p0 * b0 + p1 * b1 + p2 * (1.0 - b0 - b1);
        y.is_finite().then_some((y, self.normals[k], k as u32))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn points_are_uniform_by_area() {
        // Two triangles of areas 0.5 and 2 (and a degenerate one): 20 % and 80 % of
        // the points, and a uniform point's mean is the triangle's centroid.
        let small = [Vec3::ZERO, Vec3::X, Vec3::Y];
        let big = [Vec3::new(0.0, 0.0, 1.0), Vec3::new(2.0, 0.0, 1.0), Vec3::new(0.0, 2.0, 1.0)];
        let flat = [Vec3::ONE, Vec3::ONE, Vec3::ONE];
        let s = TriangleSampler::new(vec![small, flat, big]).unwrap();
        assert!((s.area() - 2.5).abs() < 1e-12);
        let n = 400;
        let (mut in_big, mut centroid_big) = (0, Vec3::ZERO);
        for i in 0..n {
            for j in 0..n {
                let (p, normal, _) = s.sample(((i as f64 + 0.5) / n as f64, (j as f64 + 0.5) / n as f64)).unwrap();
                assert_eq!(normal, Vec3::Z);
                if p.z > 0.5 {
                    in_big += 1;
                    centroid_big += p;
                } else {
                    assert!(p.z == 0.0 && p.x >= 0.0 && p.y >= 0.0 && p.x + p.y <= 1.0 + 1e-12);
                }
            }
        }
        let fraction = in_big as f64 / (n * n) as f64;
        assert!((fraction - 0.8).abs() < 1e-3, "{fraction}");
        let centroid = centroid_big / in_big as f64;
        assert!((centroid - Vec3::new(2.0 / 3.0, 2.0 / 3.0, 1.0)).length() < 2e-3, "{centroid}");
        assert!(TriangleSampler::new(vec![flat]).is_none());
    }
}
