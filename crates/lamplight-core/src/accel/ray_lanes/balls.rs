//! A ball's test in lanes ([`crate::shapes::Sphere`]'s, four rays at
//! once), as `ray_lanes.rs` has the rectangle's and the box's: the scalar
//! operations in their order, so the same bits (`tests.rs` compares them).

use super::avx2::{dot, splat, Rays};
use crate::math::Vec3;
use std::arch::x86_64::*;

/// [`crate::shapes::Sphere`]'s root in each lane (its `roots`, with
/// `t_min = 0`): the parameter and an all-ones mask where it is a hit in
/// `(0, t_max)`. The scalar operations in their order; a negative
/// discriminant, where the scalar test returns early, gives a NaN root
/// here, which no range holds.
#[inline(always)]
pub(crate) unsafe fn sphere(center: Vec3, radius: f64, r: &Rays, t_max: __m256d) -> (__m256d, __m256d) {
    let zero = _mm256_setzero_pd();
    let sign = _mm256_set1_pd(-0.0);
    let c = splat(center);
    let f = [_mm256_sub_pd(r.o[0], c[0]), _mm256_sub_pd(r.o[1], c[1]), _mm256_sub_pd(r.o[2], c[2])];
    let b_half = dot(f, r.d);
    let perpendicular = [
        _mm256_sub_pd(f[0], _mm256_mul_pd(r.d[0], b_half)),
        _mm256_sub_pd(f[1], _mm256_mul_pd(r.d[1], b_half)),
        _mm256_sub_pd(f[2], _mm256_mul_pd(r.d[2], b_half)),
    ];
    let r2 = _mm256_set1_pd(radius * radius);
    let discriminant = _mm256_sub_pd(r2, dot(perpendicular, perpendicular));
    let c = _mm256_sub_pd(dot(f, f), r2);
    // `-(b + sqrt(disc).copysign(b))`: negation and `copysign` move sign bits alone.
    let root = _mm256_sqrt_pd(discriminant);
    let signed = _mm256_or_pd(_mm256_andnot_pd(sign, root), _mm256_and_pd(sign, b_half));
    let q = _mm256_xor_pd(_mm256_add_pd(b_half, signed), sign);
    let q_zero = _mm256_cmp_pd::<_CMP_EQ_OQ>(q, zero);
    let t0 = _mm256_andnot_pd(q_zero, q);
    let t1 = _mm256_andnot_pd(q_zero, _mm256_div_pd(c, q));
    let swap = _mm256_cmp_pd::<_CMP_GT_OQ>(t0, t1);
    let (lo, hi) = (_mm256_blendv_pd(t0, t1, swap), _mm256_blendv_pd(t1, t0, swap));
    let within = |t: __m256d| _mm256_and_pd(_mm256_cmp_pd::<_CMP_GT_OQ>(t, zero), _mm256_cmp_pd::<_CMP_LT_OQ>(t, t_max));
    let (lo_ok, hi_ok) = (within(lo), within(hi));
    (_mm256_blendv_pd(hi, lo, lo_ok), _mm256_or_pd(lo_ok, hi_ok))
}
