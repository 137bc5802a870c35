//! Rays, and the rule that moves a new ray's origin off the surface it leaves.

use crate::math::{max_abs, Vec3};

/// A half line `origin + dir * t`, `t > 0`, at an instant `time`. `dir` is a
/// unit vector for every ray the renderer makes, so `t` is a distance.
///
/// `time` is where in the shutter the ray was sent, in frames from the frame
/// being rendered (0: the frame itself). A camera sample draws it once
/// ([`crate::integrators::View::shutter`]) and every ray of its path keeps
/// it ([`Ray::spawn`]): only moving shapes ([`crate::shapes::MovingInstance`])
/// read it, and everything else stands as it is at the frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ray {
    /// Start point.
    pub origin: Vec3,
    /// Unit direction.
    pub dir: Vec3,
    /// The instant, in frames from the rendered frame.
    pub time: f64,
}

impl Ray {
    /// A ray at time 0 from `origin` along `dir` (normalized here).
    pub fn new(origin: Vec3, dir: Vec3) -> Ray {
        Ray::unit(origin, dir.normalize())
    }

    /// A ray at time 0 from `origin` along `dir`, a unit vector already.
    #[inline]
    pub const fn unit(origin: Vec3, dir: Vec3) -> Ray {
        Ray { origin, dir, time: 0.0 }
    }

    /// A ray of the same path from `origin` along the unit `dir`: a shadow,
    /// reflected or refracted ray keeps the camera sample's instant.
    #[inline]
    pub const fn spawn(&self, origin: Vec3, dir: Vec3) -> Ray {
        Ray { origin, dir, time: self.time }
    }

    /// This ray, read one coordinate at a time ([`crate::math::read_forwarded`]),
    /// for a query that takes a ray its caller has just built: a 16-byte load
    /// of two coordinates that two of the caller's stores wrote stalled the
    /// shadow query (10 % of its time in `perf` on the Cornell box, issue 24).
    #[inline(always)]
    pub fn read_forwarded(&self) -> Ray {
        // SAFETY: a reference to an initialized `f64`.
        let time = unsafe { std::ptr::read_volatile(&self.time) };
        Ray { origin: crate::math::read_forwarded(&self.origin), dir: crate::math::read_forwarded(&self.dir), time }
    }

    /// The point at parameter `t`: `origin + dir * t`.
    #[inline]
    pub fn at(&self, t: f64) -> Vec3 {
        self.origin + self.dir * t
    }
}

/// Relative size of the offset that lifts a spawned ray off its surface.
///
/// A hit point computed in `f64` carries an absolute error of a few ulps of the
/// largest magnitude involved (the point and the distance travelled). 2^-32 of that
/// magnitude is about a million ulps: far above the rounding error, far below any
/// feature of a scene, and it scales with the scene so that a floor of size 10^6
/// is as free of shadow acne as one of size 1.
pub const OFFSET_SCALE: f64 = 1.0 / 4_294_967_296.0;

/// The origin for a ray leaving the surface at `point` in direction `dir`: `point`
/// moved along the geometric normal `normal` to the side `dir` points into, by
/// `OFFSET_SCALE * (|point|_inf + travelled)` or the shape's own error bound
/// `error`, whichever is larger.
#[inline]
pub fn offset_origin(point: Vec3, normal: Vec3, dir: Vec3, travelled: f64, error: f64) -> Vec3 {
    let scaled = OFFSET_SCALE * (max_abs(point) + travelled.abs());
    let magnitude = if scaled > 4.0 * error { scaled } else { 4.0 * error };
    let offset = normal * magnitude;
    if dir.dot(normal) >= 0.0 {
        point + offset
    } else {
        point - offset
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_ray_read_forwarded_is_the_same_ray_bit_for_bit() {
        let rays = [
            Ray { origin: Vec3::new(1.5, -2.25, 1e300), dir: Vec3::new(0.0, -0.0, 1.0), time: 0.25 },
            Ray { origin: Vec3::new(f64::NAN, f64::INFINITY, -5e-324), dir: Vec3::new(0.6, 0.8, 0.0), time: -1.0 },
        ];
        let bits = |r: &Ray| (r.origin.to_array().map(f64::to_bits), r.dir.to_array().map(f64::to_bits), r.time.to_bits());
        for ray in rays {
            assert_eq!(bits(&ray.read_forwarded()), bits(&ray));
        }
    }
}
