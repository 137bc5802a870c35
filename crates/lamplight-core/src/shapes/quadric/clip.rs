//! Clip regions that cut a quadric down to a finite piece (a tube, a lamp shade).
//!
//! A clip region is a closed set of space: the half-space `n.(p - p0) <= 0` (the
//! normal points out of the kept side, like a solid's outward normal), or the
//! inside `g(p) <= 0` of another quadric. A quadric shows only the part of its
//! surface that lies in every one of its clip regions.

use super::form::{Affine, Form};
use super::Quadric;
use crate::accel::Aabb;
use crate::math::{Mat4, Vec3};
use crate::Error;

/// One clip region of a [`Quadric`]; see the module documentation.
#[derive(Clone, Debug, PartialEq)]
pub struct Clip {
    kind: Kind,
}

#[derive(Clone, Debug, PartialEq)]
enum Kind {
    /// Keeps `normal.(p - point) <= 0`; `normal` is unit.
    HalfSpace { point: Vec3, normal: Vec3 },
    /// Keeps `g(p) <= 0`.
    Inside(Form),
}

impl Clip {
    /// Keeps the closed half-space `normal.(p - point) <= 0`: the points on the
    /// side of the plane through `point` that `normal` points away from. `normal`
    /// need not be unit but must be non-zero.
    pub fn half_space(point: Vec3, normal: Vec3) -> Result<Clip, Error> {
        if !point.is_finite() {
            return Err(Error::invalid("clip point", "must be finite"));
        }
        let normal = normal.try_normalize().ok_or_else(|| Error::invalid("clip normal", "must be a non-zero finite vector"))?;
        Ok(Clip { kind: Kind::HalfSpace { point, normal } })
    }

    /// Keeps the inside `f(p) <= 0` of `quadric` (its own clip regions are not used).
    pub fn inside(quadric: &Quadric) -> Clip {
        Clip { kind: Kind::Inside(quadric.form) }
    }

    /// Keeps `[p, 1] G [p, 1]^T <= 0` for the 4x4 matrix `g`, which is symmetrized
    /// like [`Quadric::new`]'s. Fails when `g` is not finite, has no quadratic or
    /// linear part, or keeps nothing (a definite form with no real points).
    pub fn inside_matrix(g: Mat4) -> Result<Clip, Error> {
        let form = Form::new(Vec3::ZERO, g, "clip matrix")?;
        if form.region_box().is_empty() {
            return Err(Error::DegenerateGeometry("clip quadric keeps no point".into()));
        }
        Ok(Clip { kind: Kind::Inside(form) })
    }

    /// True when `p` lies in the region (boundary included).
    #[inline]
    pub fn keeps(&self, p: Vec3) -> bool {
        match &self.kind {
            Kind::HalfSpace { point, normal } => normal.dot(p - *point) <= 0.0,
            Kind::Inside(form) => form.value(p) <= 0.0,
        }
    }

    /// False only when no point of the box `b` lies in the region, with the
    /// allowance of [`Form::range_over`] (a plane's the same, relative to the
    /// box's distance from the plane's point).
    pub(super) fn may_keep(&self, b: &Aabb) -> bool {
        match &self.kind {
            Kind::HalfSpace { point, normal } => {
                let c = (b.min + b.max) * 0.5;
                let r = (b.max - c).max(c - b.min);
                let reach = normal.abs().dot(r);
                normal.dot(c - *point) - reach <= 1e-9 * ((c - *point).abs().element_sum() + reach)
            }
            Kind::Inside(form) => form.range_over(b).0 <= 0.0,
        }
    }

    /// The region after the affine map: `p0 -> M p0`, `n -> M^-T n` (which keeps
    /// `n.(p - p0)`'s sign), and `G -> M^-T G M^-1` for a quadric.
    pub(super) fn transformed(&self, affine: &Affine) -> Result<Clip, Error> {
        let kind = match &self.kind {
            Kind::HalfSpace { point, normal } => {
                let normal = (affine.linear_inverse.transpose() * *normal)
                    .try_normalize()
                    .ok_or_else(|| Error::DegenerateGeometry("transformed clip normal vanished".into()))?;
                Kind::HalfSpace { point: affine.matrix.transform_point3(*point), normal }
            }
            Kind::Inside(form) => Kind::Inside(form.transformed(affine)?),
        };
        Ok(Clip { kind })
    }

    /// A box holding the region, possibly infinite on some sides: bounded for an
    /// ellipsoid's inside; for a half-space whose normal is a coordinate axis, the
    /// one bound it gives on that coordinate; otherwise infinite.
    pub(super) fn region_box(&self) -> Aabb {
        match &self.kind {
            Kind::HalfSpace { point, normal } => {
                let mut b = Aabb::INFINITE;
                for axis in 0..3 {
                    let others_zero = (0..3).all(|j| j == axis || normal[j] == 0.0);
                    if others_zero && normal[axis] > 0.0 {
                        b.max[axis] = point[axis];
                    } else if others_zero && normal[axis] < 0.0 {
                        b.min[axis] = point[axis];
                    }
                }
                b
            }
            Kind::Inside(form) => form.region_box(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec4;

    #[test]
    fn half_space_keeps_the_side_the_normal_points_away_from() {
        let c = Clip::half_space(Vec3::new(0.0, 1.0, 0.0), Vec3::new(0.0, 2.0, 0.0)).unwrap();
        assert!(c.keeps(Vec3::new(5.0, 0.5, -3.0)));
        assert!(c.keeps(Vec3::new(0.0, 1.0, 0.0)), "boundary kept");
        assert!(!c.keeps(Vec3::new(0.0, 1.0001, 0.0)));
        let b = c.region_box();
        assert_eq!(b.max.y, 1.0);
        assert_eq!((b.min.y, b.max.x), (f64::NEG_INFINITY, f64::INFINITY));
        assert_eq!(Clip::half_space(Vec3::ZERO, Vec3::ONE).unwrap().region_box(), Aabb::INFINITE);
        assert!(Clip::half_space(Vec3::ZERO, Vec3::ZERO).is_err());
        assert!(Clip::half_space(Vec3::NAN, Vec3::X).is_err());
    }

    #[test]
    fn quadric_clip_keeps_its_inside_and_is_bounded_for_an_ellipsoid() {
        let unit_ball = Clip::inside_matrix(Mat4::from_diagonal(DVec4::new(1.0, 1.0, 1.0, -1.0))).unwrap();
        assert!(unit_ball.keeps(Vec3::new(0.5, 0.5, 0.5)));
        assert!(!unit_ball.keeps(Vec3::new(0.6, 0.6, 0.6)));
        let b = unit_ball.region_box();
        assert!(b.contains(Vec3::X) && !b.contains(Vec3::new(1.001, 0.0, 0.0)));
        assert!(Clip::inside_matrix(Mat4::IDENTITY).is_err(), "x^2 + y^2 + z^2 + 1 <= 0 keeps nothing");
        let outside = Clip::inside_matrix(Mat4::from_diagonal(DVec4::new(-1.0, -1.0, -1.0, 1.0))).unwrap();
        assert!(outside.keeps(Vec3::splat(2.0)) && !outside.keeps(Vec3::ZERO));
        assert_eq!(outside.region_box(), Aabb::INFINITE);
    }

    #[test]
    fn transform_moves_the_plane_and_keeps_the_side() {
        let c = Clip::half_space(Vec3::ZERO, Vec3::new(1.0, 1.0, 0.0)).unwrap();
        // Shear x += y, then shift by (0, 0, 2).
        let m = Mat4::from_translation(Vec3::new(0.0, 0.0, 2.0))
            * Mat4::from_cols_array(&[1.0, 0.0, 0.0, 0.0, 1.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0]);
        let moved = c.transformed(&Affine::new(m).unwrap()).unwrap();
        for p in [Vec3::new(0.3, -0.9, 0.1), Vec3::new(-1.0, 0.2, 4.0), Vec3::new(2.0, 2.0, 2.0), Vec3::new(0.1, -0.05, 0.0)] {
            assert_eq!(moved.keeps(m.transform_point3(p)), c.keeps(p), "{p}");
        }
    }

    /// `may_keep` is true for every box that holds a kept point, and false for
    /// boxes clearly on the dropped side.
    #[test]
    fn may_keep_holds_every_box_with_a_kept_point() {
        let mut rng = crate::sampling::Rng::for_sample(22, 0, 0);
        let mut rand = move || rng.uniform();
        let clips = [
            Clip::half_space(Vec3::new(0.3, 0.0, -0.5), Vec3::new(0.2, 1.0, -0.4)).unwrap(),
            Clip::inside_matrix(Mat4::from_diagonal(DVec4::new(0.25, 1.0, 0.25, -1.0))).unwrap(),
        ];
        for clip in &clips {
            let (mut kept, mut dropped) = (0, 0);
            for _ in 0..3000 {
                let size = 10f64.powf(-7.0 + 7.0 * rand());
                let c = Vec3::new(rand() - 0.5, rand() - 0.5, rand() - 0.5) * 4.0;
                let b = Aabb::new(c, c + Vec3::new(rand(), rand(), rand()) * size);
                let any =
                    (0..20).map(|_| b.min + b.extent() * Vec3::new(rand(), rand(), rand())).chain([b.min, b.max]).any(|p| clip.keeps(p));
                if any {
                    kept += 1;
                    assert!(clip.may_keep(&b), "{b:?} holds a kept point");
                } else if !clip.may_keep(&b) {
                    dropped += 1;
                }
            }
            assert!(kept > 300 && dropped > 300, "{kept} kept, {dropped} ruled out: too few of a kind");
        }
    }
}
