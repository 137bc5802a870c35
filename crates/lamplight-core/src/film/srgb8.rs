//! The exact 8-bit sRGB quantizer: `round(255 srgb_encode(x))` for every `f32`
//! from two small tables instead of a `pow` per value, one value at a time
//! ([`Srgb8::encode`]) or a slice at a time ([`Srgb8::encode_all`], eight
//! values per AVX2 step where the CPU has it).
//!
//! Written by hand: the image crates convert with `powf` per value or a table
//! indexed by a rounded value, neither of which gives the formula's byte for
//! every input.

use super::srgb_encode;

/// `round(255 * srgb_encode(x))`, equal to the direct formula for every `f32` input
/// (NaN gives 0), without a `pow` per value. See [`Srgb8`].
pub fn srgb8(x: f32) -> u8 {
    Srgb8::get().encode(x)
}

/// Mantissa bits of an `f32` that, with its exponent, select a bucket.
const BUCKET_MANTISSA_BITS: u32 = 8;
const BUCKET_SHIFT: u32 = 23 - BUCKET_MANTISSA_BITS;

/// The exact 8-bit sRGB quantizer as two small tables.
///
/// `boundaries[k]` is the smallest `f32` whose code exceeds `k`, found by bisection
/// on the bit patterns (which order like the values for non-negative floats)
/// against the direct formula. For a value in `[boundaries[0], boundaries[254])`,
/// its exponent and top mantissa bits select a bucket; `bucket_codes` holds the
/// code at the bucket's lowest value, and since no bucket holds two boundaries
/// (a bucket is at most 2^-8 of its values wide, narrower than the gap between
/// neighbouring boundaries; a test checks every bucket) one comparison with the
/// next boundary finishes the job.
#[derive(Debug)]
pub struct Srgb8 {
    /// 255 boundaries, padded to 256 so a `u8` code indexes it without a check.
    boundaries: [f32; 256],
    first_bucket: u32,
    /// Codes of the buckets from `first_bucket` on, padded to a power of two so
    /// that a masked index needs no check; 32-bit words, which AVX2 gathers
    /// eight at a time ([`Srgb8::encode_all`]).
    bucket_codes: Box<[u32; BUCKET_TABLE]>,
}

/// Size of the bucket table: at least the 13 binades from `boundaries[0]` (about
/// 2^-13) to 1, times 2^BUCKET_MANTISSA_BITS buckets each.
const BUCKET_TABLE: usize = 4096;

impl Srgb8 {
    /// The shared quantizer, built on first use (about a millisecond).
    pub fn get() -> &'static Srgb8 {
        static TABLE: std::sync::OnceLock<Srgb8> = std::sync::OnceLock::new();
        TABLE.get_or_init(Srgb8::build)
    }

    fn build() -> Srgb8 {
        let direct = |v: f32| (srgb_encode(v as f64) * 255.0).round() as u8;
        let mut boundaries = [f32::INFINITY; 256];
        for (k, slot) in boundaries[..255].iter_mut().enumerate() {
            let (mut lo, mut hi) = (0u32, 1f32.to_bits());
            while lo < hi {
                let mid = lo + (hi - lo) / 2;
                if direct(f32::from_bits(mid)) > k as u8 {
                    hi = mid;
                } else {
                    lo = mid + 1;
                }
            }
            *slot = f32::from_bits(lo);
        }
        let first_bucket = boundaries[0].to_bits() >> BUCKET_SHIFT;
        let last_bucket = boundaries[254].to_bits() >> BUCKET_SHIFT;
        assert!(((last_bucket - first_bucket) as usize) < BUCKET_TABLE, "the bucket table covers [boundaries[0], 1)");
        let mut bucket_codes = Box::new([255u32; BUCKET_TABLE]);
        for (bucket, code) in (first_bucket..=last_bucket).zip(bucket_codes.iter_mut()) {
            let lowest = f32::from_bits(bucket << BUCKET_SHIFT);
            *code = boundaries[..255].partition_point(|&b| b <= lowest) as u32;
        }
        Srgb8 { boundaries, first_bucket, bucket_codes }
    }

    /// The code of linear value `x` (clamped to `[0, 1]`; NaN gives 0).
    #[inline]
    pub fn encode(&self, x: f32) -> u8 {
        // `!(x >= b)` is also true for NaN.
        if !(x >= self.boundaries[0]) {
            return 0;
        }
        if x >= self.boundaries[254] {
            return 255;
        }
        let bucket = ((x.to_bits() >> BUCKET_SHIFT) - self.first_bucket) as usize;
        let code = self.bucket_codes[bucket & (BUCKET_TABLE - 1)] as u8;
        code + (x >= self.boundaries[code as usize]) as u8
    }

    /// `out[i] = self.encode(values[i])` for every `i` (the slices have the
    /// same length). With AVX2, eight values a step: the same buckets, codes
    /// and comparisons, gathered, so the same bytes, in a quarter of the time
    /// of the value-by-value loop (`benches/srgb8.rs`; `BENCHMARKS.md`, issue 24).
    pub fn encode_all(&self, values: &[f32], out: &mut [u8]) {
        assert_eq!(values.len(), out.len(), "one byte per value");
        #[cfg(target_arch = "x86_64")]
        if std::arch::is_x86_feature_detected!("avx2") {
            // SAFETY: the CPU has AVX2.
            return unsafe { self.encode_all_avx2(values, out) };
        }
        self.encode_each(values, out);
    }

    /// [`Srgb8::encode_all`] a value at a time.
    fn encode_each(&self, values: &[f32], out: &mut [u8]) {
        for (o, &x) in out.iter_mut().zip(values) {
            *o = self.encode(x);
        }
    }

    /// [`Srgb8::encode_all`] eight values a step, the rest one at a time.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    unsafe fn encode_all_avx2(&self, values: &[f32], out: &mut [u8]) {
        use std::arch::x86_64::*;
        let first_bucket = _mm256_set1_epi32(self.first_bucket as i32);
        let index_mask = _mm256_set1_epi32(BUCKET_TABLE as i32 - 1);
        let lowest = _mm256_set1_ps(self.boundaries[0]);
        let highest = _mm256_set1_ps(self.boundaries[254]);
        let white = _mm256_set1_epi32(255);
        // The low byte of each 32-bit word to the first four bytes of its half.
        let low_bytes = _mm256_setr_epi8(
            0, 4, 8, 12, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, //
            0, 4, 8, 12, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1,
        );
        let steps = values.len() / 8;
        for step in 0..steps {
            let at = 8 * step;
            // SAFETY: `at + 8 <= values.len() == out.len()`; every gather index
            // is masked into `bucket_codes` or is a code below 256, inside
            // `boundaries`.
            unsafe {
                let x = _mm256_loadu_ps(values.as_ptr().add(at));
                // `encode`'s steps, lane by lane: the bucket (its wrapping
                // subtraction only matters for lanes the selects below replace) ...
                let bits = _mm256_srli_epi32::<{ BUCKET_SHIFT as i32 }>(_mm256_castps_si256(x));
                let bucket = _mm256_and_si256(_mm256_sub_epi32(bits, first_bucket), index_mask);
                let code = _mm256_i32gather_epi32::<4>(self.bucket_codes.as_ptr() as *const i32, bucket);
                // ... one comparison with the next boundary (true is -1) ...
                let boundary = _mm256_i32gather_ps::<4>(self.boundaries.as_ptr(), code);
                let inside = _mm256_sub_epi32(code, _mm256_castps_si256(_mm256_cmp_ps::<_CMP_GE_OQ>(x, boundary)));
                // ... then 255 at and above the last boundary, 0 below the first and for NaN.
                let high = _mm256_castps_si256(_mm256_cmp_ps::<_CMP_GE_OQ>(x, highest));
                let low = _mm256_castps_si256(_mm256_cmp_ps::<_CMP_NGE_UQ>(x, lowest));
                let codes = _mm256_andnot_si256(low, _mm256_blendv_epi8(inside, white, high));
                let bytes = _mm256_shuffle_epi8(codes, low_bytes);
                let eight = _mm_unpacklo_epi32(_mm256_castsi256_si128(bytes), _mm256_extracti128_si256::<1>(bytes));
                _mm_storel_epi64(out.as_mut_ptr().add(at) as *mut __m128i, eight);
            }
        }
        self.encode_each(&values[8 * steps..], &mut out[8 * steps..]);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quantizer_equals_the_direct_formula() {
        let direct = |v: f32| (srgb_encode(v as f64) * 255.0).round() as u8;
        // Every f32 in [0, 1] with a stride, plus values around each boundary.
        let mut bits = 0u32;
        while bits <= 1f32.to_bits() {
            let v = f32::from_bits(bits);
            assert_eq!(srgb8(v), direct(v), "{v}");
            bits += 997;
        }
        for v in [-1.0f32, 0.0, 1.0, 2.0, f32::INFINITY, f32::NEG_INFINITY, f32::MIN_POSITIVE] {
            assert_eq!(srgb8(v), direct(v), "{v}");
        }
        assert_eq!(srgb8(f32::NAN), 0);
    }

    #[test]
    fn quantizer_is_exact_at_every_boundary_and_bucket_edge() {
        let direct = |v: f32| (srgb_encode(v as f64) * 255.0).round() as u8;
        let table = Srgb8::get();
        // Both functions are steps that only rise, so agreeing just below and at
        // every boundary, and at every bucket edge, means agreeing everywhere.
        for &b in &table.boundaries[..255] {
            for v in [b.next_down(), b, b.next_up()] {
                assert_eq!(srgb8(v), direct(v), "{v}");
            }
        }
        let last_bucket = table.boundaries[254].to_bits() >> BUCKET_SHIFT;
        for bucket in table.first_bucket..=last_bucket + 1 {
            let lowest = f32::from_bits(bucket << BUCKET_SHIFT);
            for v in [lowest.next_down(), lowest] {
                assert_eq!(srgb8(v), direct(v), "{v}");
            }
            let inside =
                table.boundaries[..255].iter().filter(|&&b| b > lowest && b < f32::from_bits((bucket + 1) << BUCKET_SHIFT)).count();
            assert!(inside <= 1, "bucket at {lowest} holds {inside} boundaries");
        }
    }

    /// The slice encoder (eight at a time where the CPU has AVX2, and the
    /// value-by-value loop) gives `encode`'s byte for every value: values
    /// spread over every bit pattern (negatives, subnormals, above 1,
    /// infinities and NaNs among them), both sides of every boundary and
    /// bucket edge, and slices whose length is not a multiple of eight.
    #[test]
    fn encoding_a_slice_is_encoding_each_value() {
        let table = Srgb8::get();
        let mut values: Vec<f32> = (0..=u32::MAX / 4093).map(|k| f32::from_bits(k * 4093)).collect();
        for &b in &table.boundaries[..255] {
            values.extend([b.next_down(), b, b.next_up()]);
        }
        let last_bucket = table.boundaries[254].to_bits() >> BUCKET_SHIFT;
        for bucket in table.first_bucket..=last_bucket + 1 {
            let edge = f32::from_bits(bucket << BUCKET_SHIFT);
            values.extend([edge.next_down(), edge]);
        }
        values.extend([0.0, -0.0, 1.0, f32::INFINITY, f32::NEG_INFINITY, f32::NAN, -f32::NAN, f32::from_bits(0x7fc0_0001)]);
        let expected: Vec<u8> = values.iter().map(|&x| table.encode(x)).collect();
        for len in [values.len(), values.len() - 3, 7, 1, 0] {
            let mut out = vec![7u8; len];
            table.encode_all(&values[..len], &mut out);
            assert_eq!(out, expected[..len], "{len} values");
            let mut each = vec![7u8; len];
            table.encode_each(&values[..len], &mut each);
            assert_eq!(each, expected[..len], "{len} values, one at a time");
        }
        assert!((0..=255).all(|code| expected.contains(&code)), "every code is met");
    }
}
