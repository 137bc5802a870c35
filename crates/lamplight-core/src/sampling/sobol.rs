//! Owen-scrambled Sobol points, one independent scramble per (pixel, dimension).
//!
//! Every dimension a path consumes takes its values from the first two Sobol
//! dimensions (the (0,2)-sequence: van der Corput `x_i = reverse_bits(i)` and the
//! second Sobol dimension, generator columns `v_0 = 2^31`, `v_k = v_{k-1} ^ (v_{k-1} >> 1)`),
//! each scrambled by a nested uniform (Owen) scramble seeded by a hash of
//! (render seed, pixel, dimension) (Burley 2020, "Practical Hash-based Owen
//! Scrambling"). Scrambling keeps the stratification of the first `2^m` points
//! of every 1D and 2D projection and makes each point uniformly distributed, so
//! the estimate stays unbiased.
//!
//! The dimensions must not share the order of their points, or a pixel's samples
//! would pair dimension `a`'s point `i` with dimension `b`'s point `i` the same
//! way every time (measured: 4 % errors per pixel in the white furnace, against
//! 0.2 % for independent numbers). So each dimension also shuffles the sample
//! index with its own Owen scramble of the index bits (Burley's "shuffled"
//! sequence): that maps the first `2^m` indices onto one aligned block of `2^m`
//! Sobol indices, which is again a net, and the map does not depend on the
//! sample count. Sample `i` of a pixel is therefore the same whatever the count:
//! an image of `2N` samples continues the one of `N`.

/// Sample `i` of the van der Corput sequence as 32 bits of binary fraction.
#[cfg(test)]
fn sobol0(i: u32) -> u32 {
    i.reverse_bits()
}

/// Sample `i` of the second Sobol dimension as 32 bits of binary fraction: the XOR
/// of generator column `v_k` for every set bit `k` of `i`.
#[cfg(test)]
fn sobol1(mut i: u32) -> u32 {
    let mut v = 1u32 << 31;
    let mut x = 0u32;
    while i != 0 {
        if i & 1 != 0 {
            x ^= v;
        }
        i >>= 1;
        v ^= v >> 1;
    }
    x
}

/// `reverse_bits(sobol1(i))` in five shift-and-XOR steps.
///
/// Generator column `k` of the second dimension is `2^31 (1 + t)^k` with `t`
/// a shift right by one, so read as polynomials over GF(2) (bit `k` of `i`
/// the coefficient of `s^k`, bit `j` of the reversed value that of `t^j`)
/// the reversed value is `i(s)` at `s = 1 + t`: a Taylor shift by one. For a
/// degree below 32 it splits into halves, `i = A + s^h B` with `h` 16, 8, 4,
/// 2, 1, and since `(1 + t)^h = 1 + t^h` over GF(2) each level only adds
/// every block's upper half into its lower half: `x ^= (x >> h) & mask`.
/// The same bits as XOR-ing the columns of `i`'s set bits (the map is linear,
/// so equality on the 32 unit vectors proves it for every `i`, which a test
/// checks), without the 4 KB table whose four lookups per value became
/// gathers in the path tracer's lanes (issue 24).
#[inline]
fn sobol1_reversed(mut x: u32) -> u32 {
    x ^= (x >> 16) & 0x0000_ffff;
    x ^= (x >> 8) & 0x00ff_00ff;
    x ^= (x >> 4) & 0x0f0f_0f0f;
    x ^= (x >> 2) & 0x3333_3333;
    x ^= (x >> 1) & 0x5555_5555;
    x
}

/// Laine and Karras' hash-based permutation, which flips each bit depending only on
/// the bits below it: applied to bit-reversed values it is a nested uniform scramble.
#[inline]
fn laine_karras(mut x: u32, seed: u32) -> u32 {
    x = x.wrapping_add(seed);
    x ^= x.wrapping_mul(0x6c50_b47c);
    x ^= x.wrapping_mul(0xb82f_1e52);
    x ^= x.wrapping_mul(0xc7af_e638);
    x ^= x.wrapping_mul(0x8d22_f6e6);
    x
}

/// Owen scramble of a 32-bit binary fraction under `seed`.
#[inline]
pub fn owen_scramble(x: u32, seed: u32) -> u32 {
    laine_karras(x.reverse_bits(), seed).reverse_bits()
}

/// A 64-bit mix (the SplitMix64 finalizer), used to derive scramble seeds.
#[inline]
fn mix(mut z: u64) -> u64 {
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// Converts 32 bits of binary fraction to a float in `[0, 1)`.
#[inline]
fn to_unit(x: u32) -> f64 {
    x as f64 * (1.0 / 4_294_967_296.0)
}

/// The sample values of one pixel sample: dimension after dimension, each a 1D
/// value or a 2D point of its own scrambled (0,2)-sequence.
#[derive(Clone, Debug)]
pub struct PixelSampler {
    pixel_seed: u64,
    /// The sample index, bit-reversed once here rather than per dimension.
    index_reversed: u32,
    dimension: u32,
}

impl PixelSampler {
    /// Sample `index` of pixel `pixel` under render seed `seed`.
    pub fn new(seed: u64, pixel: u64, index: u32) -> PixelSampler {
        let pixel_seed = mix(mix(seed ^ 0x5851_F42D_4C95_7F2D) ^ pixel.wrapping_mul(0x9E37_79B9_7F4A_7C15));
        PixelSampler { pixel_seed, index_reversed: index.reverse_bits(), dimension: 0 }
    }

    /// Passes over the next dimension without computing it: a caller that does not
    /// need a value keeps every later decision on the dimension it always uses.
    #[inline]
    pub fn skip(&mut self) {
        self.dimension += 1;
    }

    /// [`PixelSampler::skip`] for a 1D value whose consumer ignores it: returns 0.5.
    #[inline]
    pub fn skip_value(&mut self) -> f64 {
        self.skip();
        0.5
    }

    /// The next dimension's shuffled index and its two value scramble seeds.
    #[inline]
    fn next_dimension(&mut self) -> (u32, u32, u32) {
        let seeds = self.dimension_seeds(self.dimension);
        self.dimension += 1;
        seeds
    }

    /// Dimension `dimension`'s shuffled index and its two value scramble seeds.
    #[inline]
    fn dimension_seeds(&self, dimension: u32) -> (u32, u32, u32) {
        let h = mix(self.pixel_seed ^ (dimension as u64).wrapping_mul(0xD1B5_4A32_D192_ED03));
        let h2 = mix(h ^ 0x2545_F491_4F6C_DD1D);
        // owen_scramble(index, h2) with the index reversed beforehand.
        (laine_karras(self.index_reversed, h2 as u32).reverse_bits(), h as u32, (h >> 32) as u32)
    }

    /// The 2D value of the dimension `ahead` places after the next one, without
    /// moving: what [`PixelSampler::get_2d`] will return there. The path tracer
    /// computes a vertex's values before its ray is traced, so that the hashing
    /// overlaps the intersection's latency.
    #[inline]
    pub fn peek_2d(&self, ahead: u32) -> (f64, f64) {
        let (i, s0, s1) = self.dimension_seeds(self.dimension + ahead);
        (to_unit(laine_karras(i, s0).reverse_bits()), to_unit(laine_karras(sobol1_reversed(i), s1).reverse_bits()))
    }

    /// The next dimension as one value in `[0, 1)`.
    #[inline]
    pub fn get_1d(&mut self) -> f64 {
        let (i, s, _) = self.next_dimension();
        // owen_scramble(sobol0(i), s), with the two reversals of `i` cancelled.
        to_unit(laine_karras(i, s).reverse_bits())
    }

    /// The next dimension as a point in `[0, 1)^2`.
    #[inline]
    pub fn get_2d(&mut self) -> (f64, f64) {
        // owen_scramble(sobol0(i), s0) and owen_scramble(sobol1(i), s1), with the
        // reversals folded into the index and the table.
        let value = self.peek_2d(0);
        self.dimension += 1;
        value
    }
}

/// [`PixelSampler::peek_2d`] of four samplers, `ahead.0` and `ahead.1`
/// dimensions past each one's next: the same values, worked out as eight
/// lanes side by side (the path tracer's lanes draw two 2D values a vertex
/// for four paths at once, `integrators/path/lanes.rs`). Plain loops over
/// arrays, which LLVM turns into vector code where the caller is compiled
/// for AVX2; the same operations either way, so the same bits.
#[inline(always)]
pub fn peek_2d_lanes(samplers: [&PixelSampler; 4], ahead: (u32, u32)) -> [[(f64, f64); 4]; 2] {
    let mut seed = [0u64; 8];
    let mut index = [0u32; 8];
    let mut dimension = [0u32; 8];
    for k in 0..8 {
        let s = samplers[k % 4];
        seed[k] = s.pixel_seed;
        index[k] = s.index_reversed;
        dimension[k] = s.dimension + if k < 4 { ahead.0 } else { ahead.1 };
    }
    // `dimension_seeds`, lane by lane.
    let mut h = [0u64; 8];
    for k in 0..8 {
        h[k] = mix(seed[k] ^ (dimension[k] as u64).wrapping_mul(0xD1B5_4A32_D192_ED03));
    }
    let mut i = [0u32; 8];
    for k in 0..8 {
        i[k] = laine_karras(index[k], mix(h[k] ^ 0x2545_F491_4F6C_DD1D) as u32).reverse_bits();
    }
    let mut x = [0u32; 8];
    let mut y = [0u32; 8];
    for k in 0..8 {
        x[k] = laine_karras(i[k], h[k] as u32).reverse_bits();
        y[k] = laine_karras(sobol1_reversed(i[k]), (h[k] >> 32) as u32).reverse_bits();
    }
    let mut out = [[(0.0, 0.0); 4]; 2];
    for k in 0..8 {
        out[k / 4][k % 4] = (to_unit(x[k]), to_unit(y[k]));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lanes_peek_the_values_each_sampler_peeks() {
        let mut rng = crate::sampling::Rng::for_sample(3, 0, 0);
        for round in 0..2000u32 {
            let mut samplers: Vec<PixelSampler> = (0..4)
                .map(|k| PixelSampler::new(u64::from(round % 7), (rng.uniform() * 1e12) as u64, (rng.uniform() * 4e9) as u32 + k))
                .collect();
            for (k, s) in samplers.iter_mut().enumerate() {
                for _ in 0..(round as usize + 3 * k) % 41 {
                    s.skip();
                }
            }
            let ahead = (round % 5, (round / 5) % 7);
            let lanes = peek_2d_lanes([&samplers[0], &samplers[1], &samplers[2], &samplers[3]], ahead);
            for (k, s) in samplers.iter().enumerate() {
                assert_eq!(lanes[0][k], s.peek_2d(ahead.0), "lane {k}, round {round}");
                assert_eq!(lanes[1][k], s.peek_2d(ahead.1), "lane {k}, round {round}");
            }
        }
    }

    #[test]
    fn peeked_values_are_the_ones_drawn_later() {
        let mut sampler = PixelSampler::new(9, 4321, 37);
        let ahead = sampler.peek_2d(3);
        let next = sampler.peek_2d(0);
        assert_eq!(sampler.get_2d(), next);
        sampler.get_1d();
        sampler.skip();
        assert_eq!(sampler.get_2d(), ahead);
    }

    #[test]
    fn skipped_dimensions_leave_the_later_ones_unchanged() {
        for index in [0, 1, 5, 1000] {
            let mut all = PixelSampler::new(3, 77, index);
            let mut skipping = all.clone();
            let (_, _, kept) = (all.get_1d(), all.get_2d(), all.get_2d());
            skipping.skip();
            assert_eq!(skipping.skip_value(), 0.5);
            assert_eq!(skipping.get_2d(), kept);
        }
    }

    #[test]
    fn folded_forms_equal_the_definitions() {
        let mut x = 0x1234_5678u32;
        for _ in 0..100_000 {
            x = x.wrapping_mul(747_796_405).wrapping_add(2_891_336_453);
            let i = x.rotate_left(7);
            assert_eq!(sobol1_reversed(i), sobol1(i).reverse_bits(), "{i:#x}");
            assert_eq!(laine_karras(i, x).reverse_bits(), owen_scramble(sobol0(i), x));
            assert_eq!(laine_karras(sobol1_reversed(i), x).reverse_bits(), owen_scramble(sobol1(i), x));
        }
        for i in [0, 1, 2, 3, u32::MAX, 1 << 31] {
            assert_eq!(sobol1_reversed(i), sobol1(i).reverse_bits());
        }
    }

    /// Both sides are linear over GF(2): equal on every unit vector, equal
    /// for every index.
    #[test]
    fn the_taylor_shift_is_the_generator_matrix() {
        for k in 0..32 {
            assert_eq!(sobol1_reversed(1 << k), sobol1(1 << k).reverse_bits(), "column {k}");
        }
        for (a, b) in [(0x8000_0001u32, 0x7fff_fffeu32), (0x1234_5678, 0x0f0f_f0f0)] {
            assert_eq!(sobol1_reversed(a ^ b), sobol1_reversed(a) ^ sobol1_reversed(b));
        }
    }

    #[test]
    fn a_2d_value_is_both_dimensions_owen_scrambled() {
        // The definition, with each 32-bit word reversed on its own.
        for (seed, pixel, index) in [(0, 0, 0), (9, 4321, 37), (1, u64::MAX, u32::MAX), (77, 5, 1 << 20)] {
            let mut sampler = PixelSampler::new(seed, pixel, index);
            for dimension in 0..64 {
                let (i, s0, s1) = sampler.dimension_seeds(dimension);
                let expected = (to_unit(owen_scramble(sobol0(i), s0)), to_unit(owen_scramble(sobol1(i), s1)));
                assert_eq!(sampler.get_2d(), expected, "dimension {dimension}");
            }
        }
    }

    #[test]
    fn second_dimension_matches_the_published_sequence() {
        let got: Vec<f64> = (0..4).map(|i| to_unit(sobol1(i))).collect();
        assert_eq!(got, vec![0.0, 0.5, 0.75, 0.25]);
    }

    #[test]
    fn scrambled_points_stay_stratified() {
        // The first 2^m points of a scrambled (0,2)-sequence put exactly one point
        // in each of the 2^m elementary boxes of every shape (here 16x16, 4x64, 64x4).
        for pixel in 0..4u64 {
            let pts: Vec<(f64, f64)> = (0..256).map(|i| PixelSampler::new(7, pixel, i).get_2d()).collect();
            for (nx, ny) in [(16usize, 16usize), (4, 64), (64, 4), (256, 1), (1, 256)] {
                let mut cells = vec![0u32; nx * ny];
                for &(x, y) in &pts {
                    cells[(x * nx as f64) as usize * ny + (y * ny as f64) as usize] += 1;
                }
                assert!(cells.iter().all(|&c| c == 1), "pixel {pixel}, boxes {nx}x{ny}");
            }
        }
    }

    #[test]
    fn index_shuffle_keeps_power_of_two_prefixes_in_one_aligned_block() {
        for seed in [1u32, 0xdead_beef, 12345] {
            for m in [1u32, 4, 8] {
                let block: Vec<u32> = (0..1u32 << m).map(|i| owen_scramble(i, seed)).collect();
                let base = block[0] >> m;
                assert!(block.iter().all(|&j| j >> m == base), "seed {seed}, 2^{m}");
                let mut sorted = block.clone();
                sorted.sort_unstable();
                sorted.dedup();
                assert_eq!(sorted.len(), 1 << m);
            }
        }
    }

    #[test]
    fn dimensions_and_pixels_are_decorrelated_and_uniform() {
        // Mean of products of two dimensions over many pixels is 1/4 (independent).
        let n = 20_000;
        let (mut prod, mut sum) = (0.0, 0.0);
        for p in 0..n {
            let mut s = PixelSampler::new(1, p, 3);
            let a = s.get_1d();
            let (b, c) = s.get_2d();
            prod += a * b;
            sum += a + b + c;
        }
        assert!((prod / n as f64 - 0.25).abs() < 0.01, "{}", prod / n as f64);
        assert!((sum / (3 * n) as f64 - 0.5).abs() < 0.01);
    }
}
