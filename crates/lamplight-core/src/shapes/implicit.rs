//! A general implicit surface `f(p) = 0`, found by sphere tracing with a Lipschitz bound.
//!
//! The lecture's implicit surface: substitute the ray into `f` and solve
//! `f(s + d t) = 0` for the smallest `t`; the normal is `grad f`. For a general `f`
//! there is no formula, so the root is searched for numerically, and the user gives
//! what makes that search safe: a box `bounds` that holds the whole surface, and a
//! Lipschitz bound `L` with `|f(a) - f(b)| <= L |a - b|`. `f < 0` is the inside,
//! `f > 0` the outside, and the outward normal is `grad f / |grad f|`, from the
//! user's gradient closure if given, else from central differences with step
//! `1e-5` of the box diagonal.
//!
//! # Root finding and its guarantee
//!
//! Within the box's slab interval the ray is marched by sphere tracing (Hart 1996):
//! at a point where `f = v`, no root lies closer than `|v| / L`, so a step of that
//! length cannot pass over the surface. Steps are over-relaxed by 1.6 (Keinert et
//! al. 2014, "Enhanced Sphere Tracing"); a relaxed step is kept only if the safe
//! balls at its two ends overlap, otherwise it is redone at the plain length, so
//! the guarantee stands. A sign change between two samples is refined by bisection
//! to a bracket of `1e-6` of the tolerance. When a sample comes within the
//! tolerance (`|v| / L < tol`, by default `tol = 1e-6` of the box diagonal) while
//! approaching the surface, the crossing is looked for just past the Newton
//! estimate and bisected if found; if not (the ray only touches, or meets the
//! surface at a grazing angle), the sample itself is the hit provided its
//! first-order distance `|v| / |grad f|` is below the tolerance too (with a loose
//! `L`, `|v| / L` alone would call far points close). Below the tolerance
//! steps are at least `tol` long, so a ray moving along the surface still advances.
//!
//! So: every root that the ray crosses is found, except where two crossings are
//! closer than `tol` (a sliver thinner than the tolerance), and a place where the
//! ray approaches within about `tol` of the surface (by both `|f| / L` and
//! `|f| / |grad f|`) counts as a hit. The march stops after `max_steps` samples
//! (default 4096) and then reports no hit: the only other way to miss, reached by a
//! ray that creeps along the surface for thousands of steps or by an `L` far above
//! the true bound. A NaN or infinite value of `f` also ends the march without a
//! hit. `SurfaceHit::error` is the root tolerance achieved: the bisection
//! bracket, or `tol` for a touching hit.

use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Arc;

use super::{Shape, SurfaceHit};
use crate::accel::Aabb;
use crate::math::Vec3;
use crate::ray::Ray;
use crate::Error;

/// The implicit function `f`: negative inside, positive outside, zero on the surface.
pub type ImplicitFn = Arc<dyn Fn(Vec3) -> f64 + Send + Sync>;

/// The gradient of an [`ImplicitFn`].
pub type GradientFn = Arc<dyn Fn(Vec3) -> Vec3 + Send + Sync>;

/// Over-relaxation factor of the sphere-tracing steps (Keinert et al. 2014).
const RELAXATION: f64 = 1.6;
/// Default tolerance, relative to the box diagonal.
const DEFAULT_TOLERANCE: f64 = 1e-6;
/// Central-difference step of the gradient, relative to the box diagonal: near the
/// cube root of the machine epsilon, balancing truncation and rounding error.
const GRADIENT_STEP: f64 = 1e-5;
/// Default sample cap of one march.
const DEFAULT_MAX_STEPS: usize = 4096;
/// Bisection stops at a bracket this fraction of the tolerance.
const BISECTION_FRACTION: f64 = 1e-6;
/// A crossing is looked for up to this many tolerances past a near sample.
const PROBE_REACH: f64 = 64.0;

/// An implicit surface `f(p) = 0` inside a box, with a Lipschitz bound.
#[derive(Clone)]
pub struct Implicit {
    f: ImplicitFn,
    gradient: Option<GradientFn>,
    /// A field whose direction is the shading normal (an SDF grid's smooth
    /// normals); `None`: the shading normal is the geometric one.
    shading: Option<GradientFn>,
    /// The user's box, grown by twice the tolerance so a surface touching it is still traced.
    bounds: Aabb,
    lipschitz: f64,
    tolerance: f64,
    gradient_step: f64,
    max_steps: usize,
    /// The largest `|f(b) - f(a)| / |b - a|` seen between successive samples of a
    /// march that exceeded `lipschitz` (`f64` bits; 0: none), as POV-Ray reports
    /// an isosurface's `max_gradient`. Shared by clones, so a render's copies
    /// report to one place.
    steepest: Arc<AtomicU64>,
}

impl std::fmt::Debug for Implicit {
    fn fmt(&self, out: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        out.debug_struct("Implicit")
            .field("bounds", &self.bounds)
            .field("lipschitz", &self.lipschitz)
            .field("tolerance", &self.tolerance)
            .field("analytic_gradient", &self.gradient.is_some())
            .field("shading_normals", &self.shading.is_some())
            .field("max_steps", &self.max_steps)
            .finish()
    }
}

impl Implicit {
    /// The surface `f = 0` inside `bounds` (finite, non-empty), where `f` changes by
    /// at most `lipschitz` (positive, finite) per unit of distance.
    pub fn new(f: ImplicitFn, bounds: Aabb, lipschitz: f64) -> Result<Implicit, Error> {
        if !bounds.is_finite() || bounds.min.cmpgt(bounds.max).any() {
            return Err(Error::invalid("bounds", "must be a finite, non-empty box"));
        }
        if !(lipschitz > 0.0 && lipschitz.is_finite()) {
            return Err(Error::invalid("lipschitz", format!("must be a positive number, got {lipschitz}")));
        }
        let diagonal = bounds.extent().length();
        if diagonal <= 0.0 {
            return Err(Error::DegenerateGeometry("implicit surface bounds are a single point".into()));
        }
        let tolerance = DEFAULT_TOLERANCE * diagonal;
        let mut implicit = Implicit {
            f,
            gradient: None,
            shading: None,
            bounds,
            lipschitz,
            tolerance,
            gradient_step: GRADIENT_STEP * diagonal,
            max_steps: DEFAULT_MAX_STEPS,
            steepest: Arc::new(AtomicU64::new(0)),
        };
        implicit.bounds = implicit.padded(bounds);
        Ok(implicit)
    }

    /// The sphere-traced march of the module doc; with `WATCH`, it also keeps
    /// the steepest change of `f` it sees (compiled out otherwise, so the march
    /// itself is unchanged).
    fn march<const WATCH: bool>(&self, ray: &Ray, t_min: f64, t_max: f64) -> Option<SurfaceHit> {
        let (t_enter, t_exit) = self.bounds.hit(ray, t_min, t_max)?;
        let radius_of = |v: f64| v.abs() / self.lipschitz;
        // Sample spacing in distance is `dt |dir|`.
        let speed = if WATCH { ray.dir.length() } else { 0.0 };
        let mut t = t_enter;
        let mut v = self.value(ray.at(t));
        // The previous accepted sample (t, value).
        let mut previous: Option<(f64, f64)> = None;
        let mut relaxed = true;
        for _ in 0..self.max_steps {
            if !v.is_finite() {
                return None;
            }
            if v == 0.0 && t > t_min {
                return Some(self.surface_hit(ray, t, 0.0));
            }
            let radius = radius_of(v);
            if let Some((tp, vp)) = previous {
                if WATCH {
                    self.note_change((v - vp).abs(), (t - tp) * speed);
                }
                if (vp < 0.0) != (v < 0.0) && vp != 0.0 && v != 0.0 {
                    let (root, bracket) = self.bisect(ray, tp, t, vp);
                    return Some(self.surface_hit(ray, root, bracket));
                }
                if relaxed && radius_of(vp) + radius < t - tp {
                    // The relaxed step left a gap the two safe balls do not cover: redo it plainly.
                    relaxed = false;
                    t = tp + radius_of(vp).max(self.tolerance);
                    v = self.value(ray.at(t));
                    continue;
                }
            }
            // No root within `radius` of t; none before the exit means none at all
            // (tested first: at the exit a small `|f|` is a loose `L`, not a hit).
            if t + radius >= t_exit {
                // Where the bound jumps past the exit, one sample half way there
                // shows whether `f` really stays away from 0 (a root skipped
                // would make it change faster than the bound allows).
                if WATCH && t_exit > t {
                    let mid = 0.5 * (t + t_exit);
                    self.note_change((self.value(ray.at(mid)) - v).abs(), (mid - t) * speed);
                }
                return None;
            }
            if previous.is_some_and(|(_, vp)| radius < self.tolerance && radius < radius_of(vp)) {
                if let Some(hit) = self.finish_near(ray, t, v, t_exit) {
                    return Some(hit);
                }
            }
            let factor = if relaxed { RELAXATION } else { 1.0 };
            relaxed = true;
            previous = Some((t, v));
            t = (t + (factor * radius).max(self.tolerance)).min(t_exit);
            v = self.value(ray.at(t));
        }
        None
    }

    /// Keeps the secant slope `change / distance` of `f` seen along a ray when it
    /// exceeds the bound (tested by a product: no division on the march's path).
    #[inline]
    fn note_change(&self, change: f64, distance: f64) {
        if change > self.lipschitz * distance {
            let slope = change / distance;
            if slope.is_finite() {
                // Positive finite f64 bits order as the numbers do.
                self.steepest.fetch_max(slope.to_bits(), Ordering::Relaxed);
            }
        }
    }

    /// The same surface with an analytic gradient instead of central differences.
    pub fn with_gradient(mut self, gradient: GradientFn) -> Implicit {
        self.gradient = Some(gradient);
        self
    }

    /// The same surface shaded with the normal `shading(p) / |shading(p)|`
    /// (the geometric normal where that is zero or not finite).
    pub fn with_shading_normals(mut self, shading: GradientFn) -> Implicit {
        self.shading = Some(shading);
        self
    }

    /// The same surface with root tolerance `tolerance` (a distance, positive).
    pub fn with_tolerance(mut self, tolerance: f64) -> Result<Implicit, Error> {
        if !(tolerance > 0.0 && tolerance.is_finite()) {
            return Err(Error::invalid("tolerance", format!("must be a positive number, got {tolerance}")));
        }
        let unpadded = Aabb::new(self.bounds.min + Vec3::splat(2.0 * self.tolerance), self.bounds.max - Vec3::splat(2.0 * self.tolerance));
        self.tolerance = tolerance;
        self.bounds = self.padded(unpadded);
        Ok(self)
    }

    /// The same surface with at most `max_steps` samples per ray (at least 1).
    pub fn with_max_steps(mut self, max_steps: usize) -> Implicit {
        self.max_steps = max_steps.max(1);
        self
    }

    /// Root tolerance (a distance).
    pub fn tolerance(&self) -> f64 {
        self.tolerance
    }

    fn padded(&self, b: Aabb) -> Aabb {
        Aabb::new(b.min - Vec3::splat(2.0 * self.tolerance), b.max + Vec3::splat(2.0 * self.tolerance))
    }

    /// `f(p)`.
    #[inline]
    pub fn value(&self, p: Vec3) -> f64 {
        (self.f)(p)
    }

    /// `grad f(p)`: the user's closure, or central differences.
    pub fn gradient(&self, p: Vec3) -> Vec3 {
        if let Some(g) = &self.gradient {
            return g(p);
        }
        let h = self.gradient_step;
        let diff = |axis: Vec3| (self.value(p + axis * h) - self.value(p - axis * h)) / (2.0 * h);
        Vec3::new(diff(Vec3::X), diff(Vec3::Y), diff(Vec3::Z))
    }

    /// Bisection of `[a, b]`, where `f(ray(a)) = va` differs in sign from `f(ray(b))`,
    /// to a bracket of `BISECTION_FRACTION` of the tolerance; returns the midpoint and
    /// the bracket length.
    fn bisect(&self, ray: &Ray, mut a: f64, mut b: f64, va: f64) -> (f64, f64) {
        let negative_at_a = va < 0.0;
        let goal = BISECTION_FRACTION * self.tolerance;
        // Halvings needed from the bracket to the goal; the cap also ends a bracket
        // that rounding keeps from shrinking.
        for _ in 0..200 {
            let mid = 0.5 * (a + b);
            if b - a <= goal || mid <= a || mid >= b {
                break;
            }
            let v = self.value(ray.at(mid));
            if v == 0.0 {
                return (mid, 0.0);
            }
            if (v < 0.0) == negative_at_a {
                a = mid;
            } else {
                b = mid;
            }
        }
        (0.5 * (a + b), b - a)
    }

    /// The hit at `t` with the normal from the gradient there.
    fn surface_hit(&self, ray: &Ray, t: f64, error: f64) -> SurfaceHit {
        let p = ray.at(t);
        let normal = self.gradient(p).try_normalize().unwrap_or(-ray.dir);
        let shading_normal = self.shading.as_ref().map_or(normal, |s| s(p).try_normalize().unwrap_or(normal));
        SurfaceHit { t, normal, shading_normal, error, primitive_index: SurfaceHit::NO_PRIMITIVE }
    }

    /// Close to the surface at `t` (value `v`) by the Lipschitz bound and approaching
    /// it: looks for the crossing just past the Newton estimate, else reports a
    /// touching hit at `t` if the first-order distance `|v| / |grad f|` is within the
    /// tolerance too (a loose `L` makes every point look close), else `None`.
    fn finish_near(&self, ray: &Ray, t: f64, v: f64, t_exit: f64) -> Option<SurfaceHit> {
        let h = self.gradient_step;
        let slope = (self.value(ray.at(t + h)) - self.value(ray.at(t - h))) / (2.0 * h);
        let newton = -v / slope;
        if newton > 0.0 && newton <= PROBE_REACH * self.tolerance {
            let probe = (t + 2.0 * newton + self.tolerance).min(t_exit);
            let vp = self.value(ray.at(probe));
            if vp.is_finite() && (vp < 0.0) != (v < 0.0) {
                let (root, bracket) = self.bisect(ray, t, probe, v);
                return Some(self.surface_hit(ray, root, bracket));
            }
        }
        let gradient = self.gradient(ray.at(t)).length();
        (v.abs() < self.tolerance * gradient).then(|| self.surface_hit(ray, t, self.tolerance))
    }
}

impl Shape for Implicit {
    fn bounds(&self) -> Aabb {
        self.bounds
    }

    /// A warning when a march saw `f` change faster than the Lipschitz bound.
    fn warnings(&self) -> Vec<String> {
        let steepest = f64::from_bits(self.steepest.load(Ordering::Relaxed));
        if !(steepest > self.lipschitz && steepest.is_finite()) {
            return Vec::new();
        }
        vec![format!(
            "implicit surface: f changed by {steepest:.4} per unit of distance between samples, above its lipschitz = {}: \
             rays may miss parts of the surface; set lipschitz to at least {steepest:.4}",
            self.lipschitz
        )]
    }

    /// One ray in 16, chosen by its own bits (deterministic), watches how fast
    /// `f` changes (`Implicit::march`): a bound too small shows on many rays,
    /// and watching every one cost 10 % of an implicit render.
    fn intersect(&self, ray: &Ray, t_min: f64, t_max: f64) -> Option<SurfaceHit> {
        if (ray.dir.x.to_bits() ^ ray.dir.y.to_bits()) & 0xf0 == 0 {
            self.march::<true>(ray, t_min, t_max)
        } else {
            self.march::<false>(ray, t_min, t_max)
        }
    }
}

#[cfg(test)]
mod tests;
