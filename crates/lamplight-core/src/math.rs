//! Vector and colour types, and the small numeric helpers the renderer shares.
//!
//! lamplight computes geometry in `f64` (glam's `DVec3`): the lecture's scenes mix
//! sizes from a 0.025 lamp arm to a 10^6 test floor, and double precision keeps the
//! quadric and implicit-surface root finding exact enough that one relative ray
//! offset works at every scale. Colours are RGB triples of radiance, also `f64`
//! while shading, stored as `f32` in the film.

/// A point or direction in world space.
pub type Vec3 = glam::DVec3;

/// A 4x4 matrix (quadrics, transforms).
pub type Mat4 = glam::DMat4;

/// Linear RGB radiance or reflectance. Components multiply channel by channel (`*`).
pub type Rgb = glam::DVec3;

/// `v` read one coordinate at a time, for a value a call has just written to
/// memory (an out-of-line query returns its `Rgb` or reads its ray there).
/// The call's stores may still be in the store buffer, and a 16-byte load
/// of two coordinates that two different stores wrote cannot be forwarded
/// from them: it waits until they reach the cache (a store-forwarding stall,
/// issue 24). An 8-byte load lies within one store whatever widths were
/// used. Volatile, so that the compiler does not merge the loads into wide
/// ones again. Worth it only where `perf` shows the stall: where the value's
/// own computation is what the reader waits for, it cost time (the checker
/// colour after `Texture::evaluate`, BENCHMARKS.md session 30).
#[inline(always)]
pub fn read_forwarded(v: &Vec3) -> Vec3 {
    // SAFETY: references to initialized `f64`s.
    unsafe { Vec3::new(std::ptr::read_volatile(&v.x), std::ptr::read_volatile(&v.y), std::ptr::read_volatile(&v.z)) }
}

/// The largest absolute coordinate of `v`, the magnitude used to scale ray offsets.
///
/// Plain comparisons rather than `f64::max`, whose NaN rules cost a dozen
/// instructions on every ray; a NaN coordinate may be skipped, but callers pass
/// finite points.
#[inline]
pub fn max_abs(v: Vec3) -> f64 {
    max_component(v.abs())
}

/// The largest component of `v`, by plain comparisons (see [`max_abs`]).
#[inline]
pub fn max_component(v: Vec3) -> f64 {
    let xy = if v.x > v.y { v.x } else { v.y };
    if xy > v.z {
        xy
    } else {
        v.z
    }
}

/// Builds an orthonormal basis `(t, b)` such that `(t, b, n)` is right-handed,
/// for a unit `n` (Duff et al. 2017, "Building an Orthonormal Basis, Revisited").
pub fn orthonormal_basis(n: Vec3) -> (Vec3, Vec3) {
    let sign = 1.0_f64.copysign(n.z);
    let a = -1.0 / (sign + n.z);
    let b = n.x * n.y * a;
    (Vec3::new(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x), Vec3::new(b, sign + n.y * n.y * a, -n.y))
}

/// `(sin x, cos x)` for `|x| <= pi/4` by their Taylor polynomials to degree 15
/// and 16: the first omitted terms, `x^17 / 17!` and `x^18 / 18!`, are below
/// `5e-17` there, so both are within a couple of ulps of the libm values at a
/// fifth of the cost (libm's `sincos` was 5 % of the path tracer's instructions,
/// called by every cosine-weighted direction). The polynomials in `y = x^2` are
/// evaluated by Estrin's scheme (pairs of terms combined with `y^2`, `y^4`, `y^8`),
/// whose dependency chain is half as long as Horner's.
#[inline]
pub fn sin_cos_quarter(x: f64) -> (f64, f64) {
    // Coefficients (-1)^k / (2k+1)! (sine over x) and (-1)^k / (2k)! (cosine).
    const S: [f64; 8] = [
        1.0,
        -1.0 / 6.0,
        1.0 / 120.0,
        -1.0 / 5040.0,
        1.0 / 362_880.0,
        -1.0 / 39_916_800.0,
        1.0 / 6_227_020_800.0,
        -1.0 / 1_307_674_368_000.0,
    ];
    const C: [f64; 9] = [
        1.0,
        -0.5,
        1.0 / 24.0,
        -1.0 / 720.0,
        1.0 / 40_320.0,
        -1.0 / 3_628_800.0,
        1.0 / 479_001_600.0,
        -1.0 / 87_178_291_200.0,
        1.0 / 20_922_789_888_000.0,
    ];
    let y = x * x;
    let y2 = y * y;
    let y4 = y2 * y2;
    let s = (S[0] + S[1] * y + (S[2] + S[3] * y) * y2) + (S[4] + S[5] * y + (S[6] + S[7] * y) * y2) * y4;
    let c = (C[0] + C[1] * y + (C[2] + C[3] * y) * y2) + (C[4] + C[5] * y + (C[6] + C[7] * y) * y2) * y4 + C[8] * (y4 * y4);
    (x * s, c)
}

/// The uniform scale of `m`'s linear part when it is a similarity (rotation
/// times one scale factor), else `None`.
pub fn similarity_scale(m: &Mat4) -> Option<f64> {
    let cols = [m.x_axis.truncate(), m.y_axis.truncate(), m.z_axis.truncate()];
    let s = cols[0].length();
    let tol = 1e-12 * s;
    let same_length = cols.iter().all(|c| (c.length() - s).abs() <= tol);
    let orthogonal =
        cols[0].dot(cols[1]).abs() <= tol * s && cols[1].dot(cols[2]).abs() <= tol * s && cols[0].dot(cols[2]).abs() <= tol * s;
    (same_length && orthogonal && s > 0.0).then_some(s)
}

/// True when every component is finite (no NaN, no infinity).
#[inline]
pub fn is_finite(v: Vec3) -> bool {
    v.is_finite()
}

/// Solves `a t^2 + 2 b_half t + c = 0` and returns the real roots in increasing
/// order, using the cancellation-free form `q = -(b_half + sign(b_half) sqrt(D))`,
/// `t0 = q / a`, `t1 = c / q` (Press et al., Numerical Recipes 5.6).
/// `None` when there is no real root; a degenerate `a == 0` gives the linear root twice.
#[inline]
pub fn solve_quadratic(a: f64, b_half: f64, c: f64) -> Option<(f64, f64)> {
    solve_quadratic_slope(a, b_half, c).map(|(roots, _)| roots)
}

/// [`solve_quadratic`], with `|a t + b_half|` at the roots: `sqrt(D)`, the
/// square root the roots were made with (`|b_half|` when `a == 0`).
#[inline]
pub fn solve_quadratic_slope(a: f64, b_half: f64, c: f64) -> Option<((f64, f64), f64)> {
    if a == 0.0 {
        if b_half == 0.0 {
            return None;
        }
        let t = -c / (2.0 * b_half);
        return Some(((t, t), b_half.abs()));
    }
    let discriminant = b_half * b_half - a * c;
    if discriminant < 0.0 {
        return None;
    }
    let root = discriminant.sqrt();
    let q = -(b_half + root.copysign(b_half));
    let (t0, t1) = if q == 0.0 { (0.0, 0.0) } else { (q / a, c / q) };
    Some((if t0 <= t1 { (t0, t1) } else { (t1, t0) }, root))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quarter_sine_and_cosine_agree_with_libm() {
        let quarter = std::f64::consts::FRAC_PI_4;
        let mut worst = 0.0f64;
        for i in -100_000..=100_000 {
            let x = quarter * i as f64 / 100_000.0;
            let (s, c) = sin_cos_quarter(x);
            worst = worst.max((s - x.sin()).abs()).max((c - x.cos()).abs());
        }
        // A couple of ulps of values below 1.
        assert!(worst <= 3.0 * f64::EPSILON / 2.0, "largest difference {worst:e}");
        assert_eq!(sin_cos_quarter(0.0), (0.0, 1.0));
        assert_eq!(sin_cos_quarter(-0.25).0, -sin_cos_quarter(0.25).0);
    }

    #[test]
    fn quadratic_roots_are_accurate_without_cancellation() {
        // (t - 1e-8)(t - 1e8) = t^2 - (1e8 + 1e-8) t + 1
        let (t0, t1) = solve_quadratic(1.0, -(1e8 + 1e-8) / 2.0, 1.0).unwrap();
        assert!((t0 - 1e-8).abs() / 1e-8 < 1e-12, "t0 = {t0}");
        assert!((t1 - 1e8).abs() / 1e8 < 1e-12, "t1 = {t1}");
        assert!(solve_quadratic(1.0, 0.0, 1.0).is_none());
        assert_eq!(solve_quadratic(0.0, 1.0, -4.0), Some((2.0, 2.0)));
    }

    #[test]
    fn basis_is_orthonormal() {
        for n in [Vec3::X, Vec3::Y, Vec3::Z, -Vec3::Z, Vec3::new(1.0, 2.0, -3.0).normalize()] {
            let (t, b) = orthonormal_basis(n);
            assert!(t.dot(n).abs() < 1e-12 && b.dot(n).abs() < 1e-12 && t.dot(b).abs() < 1e-12);
            assert!((t.length() - 1.0).abs() < 1e-12 && (b.length() - 1.0).abs() < 1e-12);
            assert!((t.cross(b) - n).length() < 1e-12);
        }
    }
}
