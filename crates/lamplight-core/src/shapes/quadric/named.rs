//! Named quadrics and their clipped segments.
//!
//! Each is written around a point `C` (centre or apex) with a unit axis `a`:
//! `v = p - C`, `h = v.a` (height along the axis) and `|v_perp|^2 = |v|^2 - h^2`
//! (squared distance from the axis). Every `f` is negative inside, so the normal
//! `grad f` points out of the solid (away from the axis for a cylinder, out of
//! the bowl for a paraboloid).

use super::form::Form;
use super::uv::Revolution;
use super::{Clip, Quadric};
use crate::accel::Aabb;
use crate::math::{Mat4, Vec3};
use crate::shapes::surface::Meridian;
use crate::Error;
use glam::DMat3;

/// How many sheets a [`Quadric::hyperboloid`] has.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Sheets {
    /// `|v_perp|^2 / a^2 - h^2 / c^2 = 1`: a connected waist (a cooling tower).
    One,
    /// `h^2 / c^2 - |v_perp|^2 / a^2 = 1`: two bowls opening away from each other.
    Two,
}

fn unit_axis(axis: Vec3) -> Result<Vec3, Error> {
    axis.try_normalize().ok_or_else(|| Error::invalid("axis", "must be a non-zero finite vector"))
}

fn positive(name: &str, value: f64) -> Result<f64, Error> {
    if value > 0.0 && value.is_finite() {
        Ok(value)
    } else {
        Err(Error::invalid(name, format!("must be a positive number, got {value}")))
    }
}

fn finite_point(name: &str, p: Vec3) -> Result<Vec3, Error> {
    if p.is_finite() {
        Ok(p)
    } else {
        Err(Error::invalid(name, "must be finite"))
    }
}

/// `I - a a^T`: the quadratic form of `|v_perp|^2`.
fn perp(a: Vec3) -> DMat3 {
    DMat3::IDENTITY - outer(a)
}

/// `a a^T`: the quadratic form of `h^2`.
fn outer(a: Vec3) -> DMat3 {
    DMat3::from_cols(a * a.x, a * a.y, a * a.z)
}

/// Box of the circle of radius `r` around `center` in the plane normal to unit
/// `axis`: it reaches `r sqrt(1 - axis_i^2)` along coordinate `i`.
fn circle_box(center: Vec3, axis: Vec3, r: f64) -> Aabb {
    let half = (Vec3::ONE - axis * axis).max(Vec3::ZERO).powf(0.5) * r;
    Aabb::new(center - half, center + half)
}

/// `v` along the axis.
const HEIGHT: Meridian = Meridian::Height { z0: 0.0, z1: 1.0 };

impl Quadric {
    /// Ellipsoid `sum_i ((p - center)_i / radii_i)^2 = 1` with axis-aligned
    /// semi-axes `radii` (all positive); rotate it with [`Quadric::transformed`].
    pub fn ellipsoid(center: Vec3, radii: Vec3) -> Result<Quadric, Error> {
        let center = finite_point("center", center)?;
        for r in radii.to_array() {
            positive("radii", r)?;
        }
        let a = DMat3::from_diagonal(radii.powf(-2.0));
        let frame = Mat4::from_cols(
            (Vec3::X * radii.x).extend(0.0),
            (Vec3::Y * radii.y).extend(0.0),
            (Vec3::Z * radii.z).extend(0.0),
            center.extend(1.0),
        );
        let mut q = Quadric::from_form(Form::from_parts(center, a, Vec3::ZERO, -1.0, "ellipsoid")?)?;
        q.revolution = Some(Revolution::new(frame, Meridian::Polar));
        Ok(q)
    }

    /// Infinite cylinder `|v_perp|^2 = radius^2` around the line through
    /// `point_on_axis` along `axis_dir`.
    pub fn cylinder(point_on_axis: Vec3, axis_dir: Vec3, radius: f64) -> Result<Quadric, Error> {
        let c = finite_point("point_on_axis", point_on_axis)?;
        let a = unit_axis(axis_dir)?;
        let r = positive("radius", radius)?;
        Ok(Quadric::from_form(Form::from_parts(c, perp(a), Vec3::ZERO, -r * r, "cylinder")?)?.revolving(c, a, 1.0, 1.0, HEIGHT))
    }

    /// Infinite double cone `cos^2(th) |v_perp|^2 = sin^2(th) h^2` with apex
    /// `apex`, axis `axis_dir` and half-angle `th = half_angle_rad` in `(0, pi/2)`.
    /// Both nappes are present; [`Quadric::cone_segment`] keeps one. The apex is
    /// a singular point (zero gradient); a hit exactly there reports `-ray.dir`.
    pub fn cone(apex: Vec3, axis_dir: Vec3, half_angle_rad: f64) -> Result<Quadric, Error> {
        let c = finite_point("apex", apex)?;
        let a = unit_axis(axis_dir)?;
        if !(half_angle_rad > 0.0 && half_angle_rad < std::f64::consts::FRAC_PI_2) {
            return Err(Error::invalid("half_angle", format!("must be in (0, pi/2) radians, got {half_angle_rad}")));
        }
        let (sin, cos) = half_angle_rad.sin_cos();
        let q = perp(a) * (cos * cos) - outer(a) * (sin * sin);
        Ok(Quadric::from_form(Form::from_parts(c, q, Vec3::ZERO, 0.0, "cone")?)?.revolving(c, a, 1.0, 1.0, HEIGHT))
    }

    /// Paraboloid `|v_perp|^2 = 4 f h` (the issue's `|P-A|^2 - ((P-A).a)^2 =
    /// 4 f (P-A).a`) with apex `apex`, opening along `axis_dir`, focal length
    /// `f = focal_length > 0`; the focus is `apex + f a`. Inside is the bowl, so
    /// the normal points away from the axis and the focus.
    pub fn paraboloid(apex: Vec3, axis_dir: Vec3, focal_length: f64) -> Result<Quadric, Error> {
        let c = finite_point("apex", apex)?;
        let a = unit_axis(axis_dir)?;
        let f = positive("focal_length", focal_length)?;
        // 2 b.v = -4 f h  =>  b = -2 f a.
        Ok(Quadric::from_form(Form::from_parts(c, perp(a), a * (-2.0 * f), 0.0, "paraboloid")?)?.revolving(c, a, 1.0, 1.0, HEIGHT))
    }

    /// Hyperboloid around `center` with axis `axis_dir`:
    /// `f = |v_perp|^2 / a^2 - h^2 / c^2 - 1` for [`Sheets::One`] (waist radius `a`)
    /// and `f = |v_perp|^2 / a^2 - h^2 / c^2 + 1` for [`Sheets::Two`] (vertices
    /// at `h = +-c`). Asymptotic cone half-angle `atan(a / c)`.
    pub fn hyperboloid(center: Vec3, axis_dir: Vec3, a: f64, c: f64, sheets: Sheets) -> Result<Quadric, Error> {
        let centre = finite_point("center", center)?;
        let axis = unit_axis(axis_dir)?;
        let (a, c) = (positive("a", a)?, positive("c", c)?);
        let q = perp(axis) * (a * a).recip() - outer(axis) * (c * c).recip();
        let k = match sheets {
            Sheets::One => -1.0,
            Sheets::Two => 1.0,
        };
        Ok(Quadric::from_form(Form::from_parts(centre, q, Vec3::ZERO, k, "hyperboloid")?)?.revolving(centre, axis, 1.0, 1.0, HEIGHT))
    }

    /// The open tube of radius `radius` between `p0` and `p1`: the cylinder
    /// clipped to `0 <= (p - p0).a <= |p1 - p0|`, `a = (p1 - p0) / |p1 - p0|`. No caps.
    pub fn cylinder_segment(p0: Vec3, p1: Vec3, radius: f64) -> Result<Quadric, Error> {
        let (p0, p1) = (finite_point("p0", p0)?, finite_point("p1", p1)?);
        let a = (p1 - p0).try_normalize().ok_or_else(|| Error::DegenerateGeometry("cylinder segment ends coincide".into()))?;
        let b = circle_box(p0, a, radius).union(circle_box(p1, a, radius));
        let tube = Quadric::cylinder(p0, a, radius)?.revolving(p0, a, 1.0, (p1 - p0).length(), HEIGHT);
        Ok(tube.with_clip(Clip::half_space(p0, -a)?).with_clip(Clip::half_space(p1, a)?).within(b))
    }

    /// The nappe of a cone between `apex` and the circle of radius `base_radius`
    /// around `base_center` (normal to the axis `base_center - apex`): the cone of
    /// half-angle `atan(base_radius / height)` clipped to `0 <= h <= height`. No cap.
    pub fn cone_segment(apex: Vec3, base_center: Vec3, base_radius: f64) -> Result<Quadric, Error> {
        let (apex, base) = (finite_point("apex", apex)?, finite_point("base_center", base_center)?);
        let height = (base - apex).length();
        let a = (base - apex).try_normalize().ok_or_else(|| Error::DegenerateGeometry("cone apex and base coincide".into()))?;
        let r = positive("base_radius", base_radius)?;
        // The nappe lies in the convex hull of its apex and base circle.
        let b = circle_box(base, a, r).grow(apex);
        let cone = Quadric::cone(apex, a, r.atan2(height))?.revolving(apex, a, 1.0, height, HEIGHT);
        Ok(cone.with_clip(Clip::half_space(apex, -a)?).with_clip(Clip::half_space(base, a)?).within(b))
    }

    /// A paraboloid lamp shade: [`Quadric::paraboloid`] clipped to
    /// `0 <= h <= depth`, open at the rim (radius `sqrt(4 f depth)`), so a ray
    /// entering through the rim sees the inside. The focus is `apex + f a`.
    pub fn paraboloid_cup(apex: Vec3, axis_dir: Vec3, focal_length: f64, depth: f64) -> Result<Quadric, Error> {
        let depth = positive("depth", depth)?;
        let bowl = Quadric::paraboloid(apex, axis_dir, focal_length)?;
        let a = unit_axis(axis_dir)?;
        let rim = apex + a * depth;
        // h >= 0 holds on the whole paraboloid, so only the rim plane clips. The
        // surface stays within the rim radius: the cylinder of that radius bounds it.
        let rim_radius = (4.0 * focal_length * depth).sqrt();
        let b = circle_box(apex, a, rim_radius).union(circle_box(rim, a, rim_radius));
        Ok(bowl.revolving(apex, a, 1.0, depth, HEIGHT).with_clip(Clip::half_space(rim, a)?).within(b))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ray::Ray;
    use crate::shapes::Shape;

    const INF: f64 = f64::INFINITY;

    fn close(a: Vec3, b: Vec3) -> bool {
        (a - b).length() < 1e-12
    }

    #[test]
    fn surfaces_pass_through_their_defining_points() {
        let e = Quadric::ellipsoid(Vec3::new(1.0, 2.0, 3.0), Vec3::new(2.0, 1.0, 0.5)).unwrap();
        for p in [Vec3::new(3.0, 2.0, 3.0), Vec3::new(1.0, 1.0, 3.0), Vec3::new(1.0, 2.0, 3.5)] {
            assert!(e.value(p).abs() < 1e-15);
        }
        let a = Vec3::new(1.0, 1.0, 0.0).normalize();
        let cyl = Quadric::cylinder(Vec3::ZERO, a, 0.5).unwrap();
        assert!(cyl.value(Vec3::new(0.0, 0.0, 0.5) + a * 7.0).abs() < 1e-14);
        let cone = Quadric::cone(Vec3::ZERO, Vec3::Y, std::f64::consts::FRAC_PI_6).unwrap();
        let r = 3f64.sqrt().recip(); // tan 30 degrees
        assert!(cone.value(Vec3::new(r, 1.0, 0.0)).abs() < 1e-15 && cone.value(Vec3::new(0.0, -1.0, r)).abs() < 1e-15);
        let hyper1 = Quadric::hyperboloid(Vec3::ZERO, Vec3::Y, 1.0, 2.0, Sheets::One).unwrap();
        assert!(hyper1.value(Vec3::X).abs() < 1e-15 && hyper1.value(Vec3::new(0.0, 2.0, 2f64.sqrt())).abs() < 1e-15);
        let hyper2 = Quadric::hyperboloid(Vec3::ZERO, Vec3::Y, 1.0, 2.0, Sheets::Two).unwrap();
        assert!(hyper2.value(Vec3::new(0.0, -2.0, 0.0)).abs() < 1e-15 && hyper2.value(Vec3::X) > 0.0);
    }

    #[test]
    fn paraboloid_formula_and_focus() {
        let (apex, axis, f) = (Vec3::new(1.0, 2.0, 0.0), Vec3::new(0.0, 0.0, 2.0), 0.25);
        let p = Quadric::paraboloid(apex, axis, f).unwrap();
        // |v_perp|^2 = 4 f h = h at f = 1/4: (1, 0, 1) from the apex is on it.
        assert!(p.value(apex + Vec3::new(1.0, 0.0, 1.0)).abs() < 1e-15);
        assert!(p.value(apex + Vec3::new(0.0, 0.0, 0.25)) < 0.0, "the focus is inside");
        // The defining property: distance to the focus equals distance to the directrix h = -f.
        let q = apex + Vec3::new(0.6, -0.8, 1.0);
        assert!(p.value(q).abs() < 1e-15);
        assert!(((q - (apex + Vec3::Z * f)).length() - (1.0 + f)).abs() < 1e-15);
    }

    #[test]
    fn validation() {
        assert!(Quadric::ellipsoid(Vec3::ZERO, Vec3::new(1.0, 0.0, 1.0)).is_err());
        assert!(Quadric::ellipsoid(Vec3::NAN, Vec3::ONE).is_err());
        assert!(Quadric::cylinder(Vec3::ZERO, Vec3::ZERO, 1.0).is_err());
        assert!(Quadric::cylinder(Vec3::ZERO, Vec3::X, -1.0).is_err());
        assert!(Quadric::cone(Vec3::ZERO, Vec3::Y, 0.0).is_err());
        assert!(Quadric::cone(Vec3::ZERO, Vec3::Y, std::f64::consts::FRAC_PI_2).is_err());
        assert!(Quadric::paraboloid(Vec3::ZERO, Vec3::Y, 0.0).is_err());
        assert!(Quadric::hyperboloid(Vec3::ZERO, Vec3::Y, 1.0, f64::INFINITY, Sheets::One).is_err());
        assert!(Quadric::cylinder_segment(Vec3::ONE, Vec3::ONE, 1.0).is_err());
        assert!(Quadric::cone_segment(Vec3::ZERO, Vec3::Y, 0.0).is_err());
        assert!(Quadric::paraboloid_cup(Vec3::ZERO, Vec3::Y, 0.1, -0.5).is_err());
    }

    #[test]
    fn segment_bounds_are_the_end_circles() {
        let tube = Quadric::cylinder_segment(Vec3::ZERO, Vec3::new(0.0, 2.0, 0.0), 0.5).unwrap();
        let b = tube.bounds();
        assert!((b.min - Vec3::new(-0.5, 0.0, -0.5)).length() < 1e-6 && (b.max - Vec3::new(0.5, 2.0, 0.5)).length() < 1e-6);
        let cone = Quadric::cone_segment(Vec3::new(0.0, 1.0, 0.0), Vec3::ZERO, 0.3).unwrap();
        let b = cone.bounds();
        assert!((b.min - Vec3::new(-0.3, 0.0, -0.3)).length() < 1e-6 && (b.max - Vec3::new(0.3, 1.0, 0.3)).length() < 1e-6);
        let cup = Quadric::paraboloid_cup(Vec3::ZERO, Vec3::Y, 0.25, 1.0).unwrap();
        let b = cup.bounds();
        assert!((b.min - Vec3::new(-1.0, 0.0, -1.0)).length() < 1e-6 && (b.max - Vec3::new(1.0, 1.0, 1.0)).length() < 1e-6);
        assert_eq!(Quadric::cylinder(Vec3::ZERO, Vec3::Y, 1.0).unwrap().bounds(), Aabb::INFINITE);
        let e = Quadric::ellipsoid(Vec3::ZERO, Vec3::new(3.0, 2.0, 1.0)).unwrap().bounds();
        assert!((e.max - Vec3::new(3.0, 2.0, 1.0)).length() < 1e-5);
    }

    #[test]
    fn hyperboloid_hits_and_normals() {
        let one = Quadric::hyperboloid(Vec3::ZERO, Vec3::Y, 1.0, 1.0, Sheets::One).unwrap();
        let hit = one.intersect(&Ray::new(Vec3::new(3.0, 0.0, 0.0), -Vec3::X), 0.0, INF).unwrap();
        assert!((hit.t - 2.0).abs() < 1e-14 && close(hit.normal, Vec3::X));
        // At height 1 the waist has widened to sqrt(2); the normal (x, -y, z) / |.| tilts down.
        let hit = one.intersect(&Ray::new(Vec3::new(3.0, 1.0, 0.0), -Vec3::X), 0.0, INF).unwrap();
        assert!((hit.t - (3.0 - 2f64.sqrt())).abs() < 1e-14);
        assert!(close(hit.normal, Vec3::new(2f64.sqrt(), -1.0, 0.0).normalize()));
        let two = Quadric::hyperboloid(Vec3::ZERO, Vec3::Y, 1.0, 1.0, Sheets::Two).unwrap();
        let hit = two.intersect(&Ray::new(Vec3::new(0.0, 3.0, 0.0), -Vec3::Y), 0.0, INF).unwrap();
        assert!((hit.t - 2.0).abs() < 1e-14);
        assert!(close(hit.normal, -Vec3::Y), "out of the upper bowl, towards the centre");
        assert!(two.intersect(&Ray::new(Vec3::new(3.0, 0.0, 0.0), -Vec3::X), 0.0, INF).is_none(), "gap between the sheets");
    }
}
