//! General quadric surface `f(r) = [r, 1] Q [r, 1]^T = 0`, optionally clipped.
//!
//! `Q` is a symmetric 4x4 matrix. `f < 0` is the inside; the outward normal is
//! the gradient `grad f = 2 (Q [r, 1]^T)_xyz`, normalized.
//!
//! Substituting the ray `s + t d` gives `a t^2 + 2 b t + c = 0` with
//! `a = [d, 0] Q [d, 0]^T`, `b = [s, 1] Q [d, 0]^T` (half the lecture's linear
//! coefficient) and `c = [s, 1] Q [s, 1]^T`, solved with the cancellation-free
//! [`solve_quadratic`]. `a = 0` (the ray runs along an asymptotic direction: a
//! paraboloid's axis, a cylinder's axis) leaves the linear root `-c / 2b`. Each
//! root is then polished by solving the same quadratic again around the root
//! itself, where the constant term is tiny and exact.
//!
//! Polishing was half of a quadric test's instructions, so a root is polished only when
//! its polished value can matter (`Quadric::crossing`): each unpolished root
//! comes with a bound `m` on how far polishing can move it (the first-order
//! error of a root, `(|da| t^2 + 2 |db| |t| + |dc|) / (2 sqrt(b^2 - ac))`, from
//! the rounding bounds of the coefficients, times a safety factor of 4). A root
//! whose `[t - m, t + m]` lies outside `(t_min, t_max)` is skipped, and when the
//! two intervals are apart the near root is tried first and the far one only if
//! the near one is clipped away. The answer is the one that polishing both
//! roots gives, bit for bit (a test compares them on rays of every kind).
//!
//! Clipping: a quadric shows only the part of its surface inside every one of its
//! [`Clip`] regions. Both roots are tried in increasing `t`; the first that lies
//! in `(t_min, t_max)` and survives every clip is the hit. Where the near root is
//! clipped away the far one shows: an open cup is seen from inside, and a
//! clipped cylinder is a tube with open ends (add [`super::Disk`]s for caps).
//!
//! Named constructors (ellipsoid, cylinder, cone, paraboloid, hyperboloid and
//! their clipped segments) are in `quadric/named.rs`; any of them can be moved
//! with [`Quadric::transformed`].

mod clip;
mod form;
pub mod kinds;
mod named;
mod uv;

pub use clip::Clip;
pub use named::Sheets;

use super::surface::Meridian;
use super::{Shape, SurfaceCoords, SurfaceHit};
use crate::accel::Aabb;
use crate::math::{solve_quadratic, solve_quadratic_slope, Mat4, Vec3};
use crate::ray::Ray;
use crate::Error;
use form::{Affine, Form};
use glam::DMat3;
use uv::Revolution;

/// The safety factor of the bound on a root's polishing (module doc): the
/// first-order analysis gives about 64 ulps of `(x1 + 1 + 2 |t|)^2 / slope`.
const POLISH_BOUND: f64 = 256.0;

/// The roots of the ray equation before polishing ([`Quadric::unpolished`]).
struct Unpolished {
    /// The quadratic coefficient (0 in the linear case), which polishing reuses.
    a: f64,
    /// The roots, in increasing order.
    t: [f64; 2],
    /// How far polishing can move each.
    m: [f64; 2],
}

/// A quadric surface with optional clip regions; see the module documentation.
#[derive(Clone, Debug, PartialEq)]
pub struct Quadric {
    form: Form,
    clips: Vec<Clip>,
    /// Conservative box of the visible surface; may be infinite on some sides.
    bounds: Aabb,
    /// The frame of a named quadric, for its surface coordinates (`quadric/uv.rs`).
    revolution: Option<Revolution>,
}

impl Quadric {
    /// The quadric `[r, 1] Q [r, 1]^T = 0` with no clipping.
    ///
    /// `q` is symmetrized, `(Q + Q^T) / 2`, rather than rejected when it is not
    /// symmetric: `f` depends only on the symmetric part, so the surface is the
    /// same. Fails when `q` is not finite, when its quadratic and linear parts are
    /// zero (`f` constant) and when the surface visibly has no real point (a
    /// definite form such as `x^2 + y^2 + z^2 + 1`).
    pub fn new(q: Mat4) -> Result<Quadric, Error> {
        Quadric::from_form(Form::new(Vec3::ZERO, q, "quadric matrix")?)
    }

    fn from_form(form: Form) -> Result<Quadric, Error> {
        let bounds = form.surface_box();
        if bounds.is_empty() {
            return Err(Error::DegenerateGeometry("quadric has no real points".into()));
        }
        Ok(Quadric { form, clips: Vec::new(), bounds, revolution: None })
    }

    /// This quadric with one more clip region: the visible surface shrinks to the
    /// part inside `clip` too.
    pub fn with_clip(mut self, clip: Clip) -> Quadric {
        self.bounds = self.bounds.intersection(clip.region_box());
        self.clips.push(clip);
        self
    }

    /// This quadric with the surface coordinates of a surface of revolution about
    /// `axis` (unit) through `origin`, `z` scaled by `axial` and `x`, `y` by `radial`.
    fn revolving(mut self, origin: Vec3, axis: Vec3, radial: f64, axial: f64, meridian: Meridian) -> Quadric {
        self.revolution = Some(Revolution::around(origin, axis, radial, axial, meridian));
        self
    }

    /// Narrows the stored box to `b` (a named constructor's known extent).
    fn within(mut self, b: Aabb) -> Quadric {
        self.bounds = self.bounds.intersection(form::padded(b));
        self
    }

    /// The quadric and its clip regions moved by the affine map `m` (points map
    /// as `p' = m p`): `Q' = M^-T Q M^-1`. Fails when `m` is not finite, not
    /// affine (last row other than `(0, 0, 0, 1)`) or singular.
    pub fn transformed(&self, m: Mat4) -> Result<Quadric, Error> {
        let affine = Affine::new(m)?;
        let mut moved = Quadric::from_form(self.form.transformed(&affine)?)?;
        moved.bounds = moved.bounds.intersection(affine.map_box(self.bounds));
        for clip in &self.clips {
            moved = moved.with_clip(clip.transformed(&affine)?);
        }
        moved.revolution = self.revolution.map(|r| r.transformed(&m));
        Ok(moved)
    }

    /// The symmetric matrix `Q` in world coordinates, up to a positive factor
    /// (the stored form is scaled so that its largest entry is about 1).
    pub fn matrix(&self) -> Mat4 {
        self.form.world_matrix()
    }

    /// `f(p)` in the scale of [`Quadric::matrix`]: negative inside, zero on the surface.
    pub fn value(&self, p: Vec3) -> f64 {
        self.form.value(p)
    }

    /// `grad f(p) = 2 (Q [p, 1]^T)_xyz`, pointing outward on the surface.
    pub fn gradient(&self, p: Vec3) -> Vec3 {
        2.0 * self.form.eval(p).1.truncate()
    }

    /// The clip regions, in the order added.
    pub fn clips(&self) -> &[Clip] {
        &self.clips
    }

    /// True when `p` lies in every clip region (the surface is visible there).
    #[inline(always)]
    pub fn is_visible(&self, p: Vec3) -> bool {
        self.clips.iter().all(|c| c.keeps(p))
    }

    /// The two roots of the ray equation in increasing order (equal for the
    /// linear case), polished, or `None`.
    #[cfg(test)]
    fn roots(&self, ray: &Ray) -> Option<(f64, f64)> {
        let r = self.unpolished(ray)?;
        let (t0, t1) = (self.polish(ray, r.a, r.t[0]), self.polish(ray, r.a, r.t[1]));
        Some((t0.min(t1), t0.max(t1)))
    }

    /// The two roots of the ray equation in increasing order, before polishing,
    /// with the bound on how far polishing can move each (module doc).
    #[inline(always)]
    fn unpolished(&self, ray: &Ray) -> Option<Unpolished> {
        let d = ray.dir;
        let (c, qs) = self.form.eval(ray.origin);
        let quad = DMat3::from_mat4(self.form.q);
        let mut a = d.dot(quad * d);
        let b_half = d.dot(qs.truncate());
        // Error bounds of a and b, dominated by the rounding already in Q's entries
        // (each off by an ulp of the largest, which the stored scaling keeps below
        // 2, as in 1 - a_x^2): below them the coefficient is indistinguishable from
        // 0. Treating a as exactly 0 there avoids a spurious root at
        // t ~ sqrt(c / a) ~ 10^8 for a ray inside a tilted cylinder along its axis.
        let d1 = d.abs().element_sum();
        let x1 = (ray.origin - self.form.origin).abs().element_sum();
        if a.abs() <= 16.0 * f64::EPSILON * d1 * d1 {
            a = 0.0;
            if b_half.abs() <= 16.0 * f64::EPSILON * d1 * (x1 + 1.0) {
                return None; // parallel to the surface: inside, outside or on it, never crossing
            }
        }
        // |a t + b| at a root (half the rate at which f changes along the ray
        // there): the square root the roots were made with.
        let ((t0, t1), slope) = solve_quadratic_slope(a, b_half, c)?;
        // The entries of Q are below 2 and |d| = 1: the rounding of a, b and c (and
        // of f at the polished point) is below a few ulps of (x1 + 1 + 2 |t|)^2.
        // A bound, not a value: multiplied by the reciprocal, one division for
        // both roots (the safety factor covers its rounding).
        let s = x1 + 1.0;
        let per_slope = 1.0 / slope;
        let bound = |t: f64| {
            let m = POLISH_BOUND * f64::EPSILON * ((s + 2.0 * t.abs()).powi(2) * per_slope + t.abs());
            if m.is_finite() {
                m
            } else {
                f64::INFINITY
            }
        };
        Some(Unpolished { a, t: [t0, t1], m: [bound(t0), bound(t1)] })
    }

    /// The ray parameter of the first visible crossing in `(t_min, t_max)`: the
    /// answer of polishing both roots and trying them in increasing order, with
    /// the roots that cannot be it left unpolished (module doc).
    #[inline(always)]
    fn crossing(&self, ray: &Ray, t_min: f64, t_max: f64) -> Option<f64> {
        let r = self.unpolished(ray)?;
        let [t0, t1] = r.t;
        let [m0, m1] = r.m;
        let shows = |t: f64| t > t_min && t < t_max && self.is_visible(ray.at(t));
        let first = |t: f64| {
            let p = self.polish(ray, r.a, t);
            shows(p).then_some(p)
        };
        // May polishing move the root into (t_min, t_max)?
        let may = |t: f64, m: f64| t + m > t_min && t - m < t_max;
        match (may(t0, m0), may(t1, m1)) {
            (false, false) => None,
            (true, false) => first(t0),
            (false, true) => first(t1),
            // Apart: the polished roots keep their order.
            (true, true) if t0 + m0 < t1 - m1 => first(t0).or_else(|| first(t1)),
            (true, true) => {
                let (p0, p1) = (self.polish(ray, r.a, t0), self.polish(ray, r.a, t1));
                let (lo, hi) = (p0.min(p1), p0.max(p1));
                [lo, hi].into_iter().find(|&t| shows(t))
            }
        }
    }

    /// One refinement of root `t`: the quadratic re-expanded around `ray.at(t)`,
    /// `a dt^2 + 2 b' dt + f(ray.at(t)) = 0`, whose root nearest 0 is the
    /// correction. Its constant term is small and free of the cancellation that
    /// `c` suffers when the ray starts far from a small quadric.
    #[inline(always)]
    fn polish(&self, ray: &Ray, a: f64, t: f64) -> f64 {
        if !t.is_finite() {
            return t;
        }
        let (c, qp) = self.form.eval(ray.at(t));
        match solve_quadratic(a, ray.dir.dot(qp.truncate()), c) {
            Some((d0, d1)) => {
                let dt = if d0.abs() <= d1.abs() { d0 } else { d1 };
                if dt.is_finite() {
                    t + dt
                } else {
                    t
                }
            }
            None => t, // grazing: rounding removed the local crossing; keep the first estimate
        }
    }

    /// [`Shape::intersect`]: the crossing and the normal there.
    #[inline(always)]
    fn intersect_in(&self, ray: &Ray, t_min: f64, t_max: f64) -> Option<SurfaceHit> {
        let t = self.crossing(ray, t_min, t_max)?;
        // At a singular point (a cone's apex) the gradient vanishes and no normal
        // exists; facing the ray keeps the hit usable and free of NaN.
        let normal = self.form.eval(ray.at(t)).1.truncate().try_normalize().unwrap_or(-ray.dir);
        Some(SurfaceHit::new(t, normal))
    }

    /// [`Quadric::intersect_in`] compiled for [`crate::cpu::AVX2_FEATURES`]:
    /// the same operations, so the same bits.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2,bmi1,bmi2,lzcnt,popcnt")]
    unsafe fn intersect_avx2(&self, ray: &Ray, t_min: f64, t_max: f64) -> Option<SurfaceHit> {
        self.intersect_in(ray, t_min, t_max)
    }

    /// [`Quadric::crossing`] compiled for [`crate::cpu::AVX2_FEATURES`].
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2,bmi1,bmi2,lzcnt,popcnt")]
    unsafe fn crossing_avx2(&self, ray: &Ray, t_min: f64, t_max: f64) -> Option<f64> {
        self.crossing(ray, t_min, t_max)
    }
}

impl Shape for Quadric {
    fn hit_ignores_t_max(&self) -> bool {
        true
    }

    fn bounds(&self) -> Aabb {
        if self.bounds.is_finite() {
            self.bounds
        } else {
            Aabb::INFINITE
        }
    }

    fn intersect(&self, ray: &Ray, t_min: f64, t_max: f64) -> Option<SurfaceHit> {
        #[cfg(target_arch = "x86_64")]
        if crate::cpu::avx2_features() {
            // SAFETY: the CPU has every feature the compilation assumes.
            return unsafe { self.intersect_avx2(ray, t_min, t_max) };
        }
        self.intersect_in(ray, t_min, t_max)
    }

    /// Where `f` can vanish over the part of `region` in the stored box
    /// (`Form::range_over`) and every clip region may keep a point of it.
    fn may_meet(&self, region: &Aabb) -> bool {
        let b = region.intersection(self.bounds);
        if b.is_empty() {
            return false;
        }
        let (lo, hi) = self.form.range_over(&b);
        lo <= 0.0 && hi >= 0.0 && self.clips.iter().all(|c| c.may_keep(&b))
    }

    /// `Quadric::crossing` without the normal.
    fn intersect_p(&self, ray: &Ray, t_min: f64, t_max: f64) -> bool {
        #[cfg(target_arch = "x86_64")]
        if crate::cpu::avx2_features() {
            // SAFETY: the CPU has every feature the compilation assumes.
            return unsafe { self.crossing_avx2(ray, t_min, t_max).is_some() };
        }
        self.crossing(ray, t_min, t_max).is_some()
    }

    /// See `quadric/uv.rs`.
    fn surface_coords(&self, p: Vec3, n: Vec3, _primitive: Option<u32>) -> SurfaceCoords {
        match &self.revolution {
            Some(r) => r.coords(p, n),
            None => SurfaceCoords::unparametrized(n),
        }
    }
}

#[cfg(test)]
mod tests;
