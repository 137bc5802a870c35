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
#[repr(C)]
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

    /// This ray copied into `out` with two overlapping 32-byte stores
    /// (origin and `dir.x`, then `dir` and time), read one coordinate at a
    /// time as [`Ray::read_forwarded`] reads it. A query then reads its
    /// copy with loads that each lie within one store, so none waits for a
    /// store to reach the cache; its own copy of a [`Ray::read_forwarded`]
    /// had been stored a coordinate at a time and read back in pairs, a
    /// stall on the shadow query's first pair (issue 24).
    ///
    /// # Safety
    /// The CPU must have [`crate::cpu::AVX2_FEATURES`].
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2,bmi1,bmi2,lzcnt,popcnt")]
    #[inline]
    pub unsafe fn copy_forwarded_avx2(&self, out: &mut std::mem::MaybeUninit<Ray>) {
        use std::arch::x86_64::*;
        let (o, d) = (crate::math::read_forwarded(&self.origin), crate::math::read_forwarded(&self.dir));
        let time = std::ptr::read_volatile(&self.time);
        // `repr(C)`: the seven values in order, origin first.
        // Each store written out, so that the compiler cannot split it (it
        // had cut `_mm256_storeu_pd`'s into 16-byte halves).
        let at = out.as_mut_ptr() as *mut f64;
        let store = |to: *mut f64, v: __m256d| {
            std::arch::asm!("vmovupd [{to}], {v}", to = in(reg) to, v = in(ymm_reg) v, options(nostack, preserves_flags));
        };
        store(at, _mm256_setr_pd(o.x, o.y, o.z, d.x));
        store(at.add(3), _mm256_setr_pd(d.x, d.y, d.z, time));
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
            #[cfg(target_arch = "x86_64")]
            if crate::cpu::avx2_features() {
                // Copied over a copy of another ray, so that a field left
                // unwritten would show.
                let mut copy = std::mem::MaybeUninit::new(Ray { origin: Vec3::splat(7.0), dir: Vec3::splat(-7.0), time: 7.0 });
                // SAFETY: the CPU has AVX2 (checked above).
                unsafe { ray.copy_forwarded_avx2(&mut copy) };
                // SAFETY: initialized above.
                assert_eq!(bits(unsafe { copy.assume_init_ref() }), bits(&ray));
            }
        }
    }
}
