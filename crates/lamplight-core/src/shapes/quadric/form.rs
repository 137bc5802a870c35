//! A quadratic form around a local origin: `f(p) = [x, 1] Q [x, 1]^T` with `x = p - o`,
//! i.e. `f = x^T A x + 2 b.x + k` for the blocks `Q = [[A, b], [b^T, k]]`.
//!
//! Why a local origin: written around the world origin, a small quadric far away
//! (radius 10^-3 at distance 10^6) has a constant term `|c|^2 - R^2` in which `R^2`
//! is below the last bit. Around its own centre every coefficient keeps its digits,
//! and an affine map `p' = M p` only multiplies `Q` by its linear part
//! (`Q' = L^T Q L`, `L = diag(M3^-1, 1)`) while the origin moves to `M o`.

use crate::accel::Aabb;
use crate::math::{Mat4, Vec3};
use crate::Error;
use glam::{DMat3, DVec4};

/// A symmetric quadric matrix (scaled so that its largest entry is in `[1, 2)`;
/// a positive power-of-two factor, which changes neither the surface, nor the
/// sign of `f`, nor any rounding) around a local origin.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Form {
    pub(super) origin: Vec3,
    pub(super) q: Mat4,
}

/// Relative padding of computed boxes, far above their rounding error.
const BOX_PAD: f64 = 1e-7;

impl Form {
    /// Validates and stores `q` around `origin`. The matrix is symmetrized,
    /// `(Q + Q^T) / 2`, which leaves `f` unchanged (only the symmetric part of a
    /// matrix contributes to `x^T Q x`) and makes `Q [x, 1]` half the gradient.
    pub(super) fn new(origin: Vec3, q: Mat4, name: &str) -> Result<Form, Error> {
        if !(origin.is_finite() && q.is_finite()) {
            return Err(Error::invalid(name, "matrix and origin must be finite"));
        }
        let q = (q + q.transpose()) * 0.5;
        // The first three rows hold A and b; when they vanish f is a constant.
        let varying = (0..3).map(|i| q.row(i).abs().max_element()).fold(0.0, f64::max);
        if varying == 0.0 {
            return Err(Error::DegenerateGeometry(format!("{name}: quadratic and linear parts are zero, f is constant")));
        }
        let largest = q.abs().to_cols_array().into_iter().fold(0.0, f64::max);
        let scale = (-largest.log2().floor()).exp2();
        Ok(Form { origin, q: q * scale })
    }

    /// `f = (p-o)^T A (p-o) + 2 b.(p-o) + k` from its blocks.
    pub(super) fn from_parts(origin: Vec3, a: DMat3, b: Vec3, k: f64, name: &str) -> Result<Form, Error> {
        let q = Mat4::from_cols(a.x_axis.extend(b.x), a.y_axis.extend(b.y), a.z_axis.extend(b.z), b.extend(k));
        Form::new(origin, q, name)
    }

    /// `(f(p), Q [p - o, 1]^T)`; the xyz part of the second is half the gradient.
    #[inline]
    pub(super) fn eval(&self, p: Vec3) -> (f64, DVec4) {
        let x = (p - self.origin).extend(1.0);
        let qx = self.q * x;
        (x.dot(qx), qx)
    }

    /// `f(p)`.
    #[inline]
    pub(super) fn value(&self, p: Vec3) -> f64 {
        self.eval(p).0
    }

    /// Bounds `(lo, hi)` on `f` over the box `b`. Around the box's centre `c`
    /// with half-extents `r`, `f(c + h) = f(c) + 2 g.h + h^T A h` with
    /// `g = A (c - o) + b`, so `|f - f(c)| <= 2 |g|.r + r^T |A| r`; widened by
    /// `1e-9` of the terms' magnitude, far above the rounding of evaluating `f`
    /// anywhere in the box.
    pub(super) fn range_over(&self, b: &Aabb) -> (f64, f64) {
        let c = (b.min + b.max) * 0.5;
        let r = (b.max - c).max(c - b.min);
        let (fc, g) = self.eval(c);
        let a = DMat3::from_mat4(self.q);
        let abs_a = DMat3::from_cols(a.x_axis.abs(), a.y_axis.abs(), a.z_axis.abs());
        let spread = 2.0 * g.truncate().abs().dot(r) + r.dot(abs_a * r);
        let x = ((c - self.origin).abs() + r).extend(1.0);
        let abs_q = Mat4::from_cols(self.q.x_axis.abs(), self.q.y_axis.abs(), self.q.z_axis.abs(), self.q.w_axis.abs());
        let slack = 1e-9 * x.dot(abs_q * x);
        (fc - spread - slack, fc + spread + slack)
    }

    /// The matrix in world coordinates, `T^T Q T` with `T` the translation by `-o`.
    pub(super) fn world_matrix(&self) -> Mat4 {
        let t = Mat4::from_translation(-self.origin);
        let m = t.transpose() * self.q * t;
        (m + m.transpose()) * 0.5
    }

    /// The same surface after the affine map `affine`.
    pub(super) fn transformed(&self, affine: &Affine) -> Result<Form, Error> {
        let l = Mat4::from_mat3(affine.linear_inverse);
        Form::new(affine.matrix.transform_point3(self.origin), l.transpose() * self.q * l, "transformed quadric")
    }

    /// A box holding `{f <= 0}` when that set is bounded (A positive definite: an
    /// ellipsoid or nothing); [`Aabb::INFINITE`] otherwise, [`Aabb::EMPTY`] when empty.
    ///
    /// With `x0 = -A^-1 b`, `f = (x - x0)^T A (x - x0) - r` where `r = -b.x0 - k`,
    /// and the ellipsoid `(x - x0)^T A (x - x0) <= r` reaches `sqrt(r (A^-1)_ii)`
    /// along axis `i`.
    pub(super) fn region_box(&self) -> Aabb {
        let a = DMat3::from_mat4(self.q);
        if !positive_definite(a) {
            return Aabb::INFINITE;
        }
        let a_inv = a.inverse();
        let b = self.q.w_axis.truncate();
        let x0 = -(a_inv * b);
        let r = -b.dot(x0) - self.q.w_axis.w;
        if r < 0.0 {
            return Aabb::EMPTY;
        }
        let diag = Vec3::new(a_inv.x_axis.x, a_inv.y_axis.y, a_inv.z_axis.z);
        let half = (diag * r).max(Vec3::ZERO).powf(0.5);
        let centre = self.origin + x0;
        padded(Aabb::new(centre - half, centre + half))
    }

    /// A box holding the surface `{f = 0}`: bounded when A is definite of either
    /// sign (the zero set of `-f` is the same).
    pub(super) fn surface_box(&self) -> Aabb {
        let region = self.region_box();
        if region != Aabb::INFINITE {
            return region;
        }
        Form { origin: self.origin, q: -self.q }.region_box()
    }
}

/// Sylvester's criterion with a relative tolerance: a nearly singular A (a
/// cylinder's, up to rounding) counts as not definite, so its box is infinite
/// rather than huge and unreliable. The tolerance admits condition numbers up to
/// about 10^9, whose inverse is still accurate to far better than [`BOX_PAD`].
fn positive_definite(a: DMat3) -> bool {
    let s = a.abs().to_cols_array().into_iter().fold(0.0, f64::max);
    let tol = 1e-9;
    let m1 = a.x_axis.x;
    let m2 = a.x_axis.x * a.y_axis.y - a.x_axis.y * a.y_axis.x;
    s > 0.0 && m1 > tol * s && m2 > tol * s * s && a.determinant() > tol * s * s * s
}

/// `b` grown on every side by `BOX_PAD` of its size and of its distance from the
/// world origin, so that rounding in the box or in a hit point never puts a hit
/// outside. Non-finite boxes are returned unchanged.
pub(super) fn padded(b: Aabb) -> Aabb {
    if !b.is_finite() {
        return b;
    }
    let size = b.extent().max_element() + b.min.abs().max(b.max.abs()).max_element() * 1e-3;
    let pad = Vec3::splat(BOX_PAD * size + f64::MIN_POSITIVE);
    Aabb::new(b.min - pad, b.max + pad)
}

/// A validated affine map: finite, last row `(0, 0, 0, 1)`, invertible linear part.
#[derive(Clone, Copy, Debug)]
pub(super) struct Affine {
    pub(super) matrix: Mat4,
    pub(super) linear_inverse: DMat3,
}

impl Affine {
    pub(super) fn new(matrix: Mat4) -> Result<Affine, Error> {
        if !matrix.is_finite() {
            return Err(Error::invalid("transform", "must be finite"));
        }
        if matrix.row(3) != DVec4::W {
            return Err(Error::invalid("transform", "must be affine (last row 0, 0, 0, 1)"));
        }
        let linear = DMat3::from_mat4(matrix);
        // Scale-free singularity test: |det| against the product of column lengths.
        let volume = linear.x_axis.length() * linear.y_axis.length() * linear.z_axis.length();
        if linear.determinant().abs() <= 1e-12 * volume {
            return Err(Error::DegenerateGeometry("transform is singular".into()));
        }
        Ok(Affine { matrix, linear_inverse: linear.inverse() })
    }

    /// The box holding the image of `b` (its eight corners mapped).
    pub(super) fn map_box(&self, b: Aabb) -> Aabb {
        if !b.is_finite() {
            return Aabb::INFINITE;
        }
        let corners = (0..8).map(|i| {
            let pick = |bit: usize, lo: f64, hi: f64| if i & bit == 0 { lo } else { hi };
            self.matrix.transform_point3(Vec3::new(pick(1, b.min.x, b.max.x), pick(2, b.min.y, b.max.y), pick(4, b.min.z, b.max.z)))
        });
        padded(Aabb::from_points(corners))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sphere_form(centre: Vec3, r: f64) -> Form {
        Form::from_parts(centre, DMat3::IDENTITY, Vec3::ZERO, -r * r, "q").unwrap()
    }

    #[test]
    fn symmetrizes_and_scales_by_a_power_of_two() {
        let mut q = Mat4::from_diagonal(DVec4::new(3.0, 3.0, 3.0, -3.0));
        q.x_axis.y = 2.0; // asymmetric: only (Q + Q^T) / 2 matters
        let f = Form::new(Vec3::ZERO, q, "q").unwrap();
        assert_eq!(f.q, f.q.transpose());
        assert_eq!(f.q.x_axis.x, 1.5, "3 scaled by 1/2");
        assert_eq!(f.q.x_axis.y, 0.5);
        let p = Vec3::new(0.3, -0.7, 1.1);
        let expected = 3.0 * p.length_squared() - 3.0 + 2.0 * p.x * p.y;
        assert!((f.value(p) * 2.0 - expected).abs() < 1e-14);
    }

    #[test]
    fn rejects_non_finite_and_constant() {
        assert!(Form::new(Vec3::ZERO, Mat4::from_diagonal(DVec4::new(f64::NAN, 1.0, 1.0, 1.0)), "q").is_err());
        assert!(Form::new(Vec3::ZERO, Mat4::from_diagonal(DVec4::new(0.0, 0.0, 0.0, 1.0)), "q").is_err());
        assert!(Form::new(Vec3::ZERO, Mat4::ZERO, "q").is_err());
    }

    #[test]
    fn world_matrix_matches_local_evaluation() {
        let f = Form::from_parts(Vec3::new(1.0, -2.0, 3.0), DMat3::from_diagonal(Vec3::new(1.0, 4.0, 0.5)), Vec3::X, -2.0, "q").unwrap();
        let w = f.world_matrix();
        for p in [Vec3::ZERO, Vec3::new(0.5, 7.0, -1.0), Vec3::new(-3.0, 2.0, 2.0)] {
            let h = p.extend(1.0);
            assert!((h.dot(w * h) - f.value(p)).abs() < 1e-12);
        }
    }

    #[test]
    fn ellipsoid_box_is_exact_and_signs_handled() {
        let f = Form::from_parts(Vec3::new(1.0, 2.0, 3.0), DMat3::from_diagonal(Vec3::new(0.25, 1.0, 4.0)), Vec3::ZERO, -1.0, "q").unwrap();
        let b = f.region_box();
        assert!((b.min - Vec3::new(-1.0, 1.0, 2.5)).length() < 1e-5 && (b.max - Vec3::new(3.0, 3.0, 3.5)).length() < 1e-5);
        assert!(b.contains(Vec3::new(3.0, 2.0, 3.0)), "padding keeps the extreme point inside");
        let negated = Form { origin: f.origin, q: -f.q };
        assert_eq!(negated.region_box(), Aabb::INFINITE, "{{-f <= 0}} is the outside");
        assert_eq!(negated.surface_box(), b);
        assert!(sphere_form(Vec3::ZERO, 1.0).region_box().is_finite());
        let empty = Form::from_parts(Vec3::ZERO, DMat3::IDENTITY, Vec3::ZERO, 1.0, "q").unwrap();
        assert!(empty.region_box().is_empty());
        let cylinder = Form::from_parts(Vec3::ZERO, DMat3::from_diagonal(Vec3::new(1.0, 0.0, 1.0)), Vec3::ZERO, -1.0, "q").unwrap();
        assert_eq!(cylinder.surface_box(), Aabb::INFINITE);
    }

    #[test]
    fn affine_validation_and_form_transform() {
        assert!(Affine::new(Mat4::from_scale(Vec3::new(1.0, 0.0, 1.0))).is_err());
        let mut projective = Mat4::IDENTITY;
        projective.x_axis.w = 0.5;
        assert!(Affine::new(projective).is_err());
        assert!(Affine::new(Mat4::from_translation(Vec3::splat(f64::INFINITY))).is_err());
        let m = Mat4::from_translation(Vec3::new(0.0, 5.0, 0.0)) * Mat4::from_scale(Vec3::new(2.0, 1.0, 1.0));
        let affine = Affine::new(m).unwrap();
        let moved = sphere_form(Vec3::ZERO, 1.0).transformed(&affine).unwrap();
        // The unit sphere becomes the ellipsoid (x/2)^2 + (y-5)^2 + z^2 = 1.
        assert!(moved.value(Vec3::new(2.0, 5.0, 0.0)).abs() < 1e-15);
        assert!(moved.value(Vec3::new(0.0, 6.0, 0.0)).abs() < 1e-15);
        assert!(moved.value(Vec3::new(0.0, 5.0, 0.0)) < 0.0);
        let b = affine.map_box(Aabb::new(Vec3::splat(-1.0), Vec3::splat(1.0)));
        assert!((b.max - Vec3::new(2.0, 6.0, 1.0)).length() < 1e-5);
    }

    /// Every value of `f` at points of a box (corners, centre, random points)
    /// lies in `range_over`'s bounds, for boxes from a millionth to ten times
    /// the form's size and far from its origin; and the bounds are tight
    /// enough to exclude a box well inside or outside a sphere.
    #[test]
    fn range_over_bounds_every_value_in_the_box() {
        let mut rng = crate::sampling::Rng::for_sample(21, 0, 0);
        let mut rand = move || rng.uniform();
        let forms = [
            sphere_form(Vec3::new(1.0, -2.0, 3.0), 0.7),
            Form::from_parts(Vec3::new(-0.45, 1.35, -0.25), DMat3::from_diagonal(Vec3::new(1.0, 0.0, 1.0)), -0.4 * Vec3::Y, 0.0, "q")
                .unwrap(),
            Form::new(
                Vec3::new(5e3, 0.0, -1e3),
                Mat4::from_cols_array(&[2.0, 0.3, -0.5, 0.1, 0.3, -1.0, 0.2, 0.0, -0.5, 0.2, 0.5, -0.3, 0.1, 0.0, -0.3, -1.0]),
                "q",
            )
            .unwrap(),
        ];
        for f in &forms {
            for _ in 0..400 {
                let size = 10f64.powf(-6.0 + 7.0 * rand());
                let c = f.origin + Vec3::new(rand() - 0.5, rand() - 0.5, rand() - 0.5) * 4.0;
                let b = Aabb::new(c, c + Vec3::new(rand(), rand(), rand()) * size);
                let (lo, hi) = f.range_over(&b);
                let corners = (0..8).map(|k| {
                    Vec3::new(
                        if k & 1 == 0 { b.min.x } else { b.max.x },
                        if k & 2 == 0 { b.min.y } else { b.max.y },
                        if k & 4 == 0 { b.min.z } else { b.max.z },
                    )
                });
                let inside: Vec<Vec3> = (0..20).map(|_| b.min + b.extent() * Vec3::new(rand(), rand(), rand())).collect();
                for p in corners.chain(inside).chain([b.centroid()]) {
                    let v = f.value(p);
                    assert!(lo <= v && v <= hi, "f({p}) = {v} outside [{lo}, {hi}] over {b:?}");
                }
            }
        }
        let unit = sphere_form(Vec3::ZERO, 1.0);
        assert!(unit.range_over(&Aabb::new(Vec3::splat(-0.3), Vec3::splat(0.3))).1 < 0.0, "well inside");
        assert!(unit.range_over(&Aabb::new(Vec3::splat(1.0), Vec3::splat(1.5))).0 > 0.0, "well outside");
    }
}
