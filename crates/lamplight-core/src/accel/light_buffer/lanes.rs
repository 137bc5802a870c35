//! The light buffer's cell lookup for four directions at once (the eye's
//! four-ray search, `scene/eye_lanes.rs`): `LightBuffer::list_towards`'s
//! face and cell, lane by lane, with the same operations.

use super::{LightBuffer, N};

impl LightBuffer {
    /// The number of the cell holding each lane's direction `(e[0], e[1],
    /// e[2])` seen from the centre, the number [`LightBuffer::list_of_cell`]
    /// takes: the cell [`LightBuffer::cell_from_centre`] looks up.
    ///
    /// # Safety
    /// The CPU must have [`crate::cpu::AVX2_FEATURES`].
    #[target_feature(enable = "avx2,bmi1,bmi2,lzcnt,popcnt")]
    #[inline]
    pub(crate) unsafe fn cells_from_centre(e: [std::arch::x86_64::__m256d; 3]) -> [u32; 4] {
        use std::arch::x86_64::*;
        let sign = _mm256_set1_pd(-0.0);
        let [mx, my, mz] = e.map(|c| _mm256_andnot_pd(sign, c));
        let on_x = _mm256_and_pd(_mm256_cmp_pd::<_CMP_GE_OQ>(mx, my), _mm256_cmp_pd::<_CMP_GE_OQ>(mx, mz));
        let on_y = _mm256_cmp_pd::<_CMP_GE_OQ>(my, mz);
        // x where `on_x`, else y where `on_y`, else z, of the three choices.
        let pick = |x: __m256d, y: __m256d, z: __m256d| _mm256_blendv_pd(_mm256_blendv_pd(z, y, on_y), x, on_x);
        let major = pick(e[0], e[1], e[2]);
        let u = pick(e[1], e[2], e[0]);
        let v = pick(e[2], e[0], e[1]);
        let face = pick(_mm256_set1_pd(0.0), _mm256_set1_pd(2.0), _mm256_set1_pd(4.0));
        let face = _mm256_add_pd(face, _mm256_and_pd(_mm256_cmp_pd::<_CMP_LT_OQ>(major, _mm256_setzero_pd()), _mm256_set1_pd(1.0)));
        let inv = _mm256_div_pd(_mm256_set1_pd(1.0), _mm256_andnot_pd(sign, major));
        // `cell_index`: `max` with the operands in this order turns NaN into 0.
        let index = |x: __m256d| {
            let x = _mm256_mul_pd(_mm256_add_pd(x, _mm256_set1_pd(1.0)), _mm256_set1_pd(0.5 * N as f64));
            _mm256_min_pd(_mm256_max_pd(x, _mm256_setzero_pd()), _mm256_set1_pd((N - 1) as f64))
        };
        let n = _mm256_set1_pd(N as f64);
        // Whole numbers below 2^15: exact in `f64`.
        let cell = _mm256_add_pd(
            _mm256_mul_pd(_mm256_add_pd(_mm256_mul_pd(face, n), _mm256_round_pd::<_MM_FROUND_TRUNC>(index(_mm256_mul_pd(v, inv)))), n),
            _mm256_round_pd::<_MM_FROUND_TRUNC>(index(_mm256_mul_pd(u, inv))),
        );
        let mut cells = [0u32; 4];
        _mm_storeu_si128(cells.as_mut_ptr().cast(), _mm256_cvttpd_epi32(cell));
        cells
    }
}
