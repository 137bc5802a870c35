//! Deterministic random numbers and stratified pixel samples.
//!
//! Every pixel sample draws from its own generator seeded by (seed, pixel, sample
//! index), so an image does not depend on which thread renders which pixel.

mod cone;
mod distribution;
mod sobol;

pub use cone::Cone;
pub use distribution::{Distribution1d, Distribution2d};
pub use sobol::{owen_scramble, peek_2d_lanes, PixelSampler};

/// SplitMix64 (Steele et al. 2014): a fast generator with good statistical quality
/// for the short streams a pixel sample needs; seeded by hashing its inputs.
#[derive(Clone, Debug)]
pub struct Rng {
    state: u64,
}

impl Rng {
    /// A generator for sample `sample` of pixel `pixel` under the render seed `seed`.
    pub fn for_sample(seed: u64, pixel: u64, sample: u64) -> Rng {
        let mut rng = Rng { state: seed ^ 0x6A09E667F3BCC909 };
        rng.state = rng.next_u64() ^ pixel.wrapping_mul(0x9E3779B97F4A7C15);
        rng.state = rng.next_u64() ^ sample.wrapping_mul(0xD1B54A32D192ED03);
        rng
    }

    /// Next 64 random bits.
    #[inline]
    pub fn next_u64(&mut self) -> u64 {
        self.state = self.state.wrapping_add(0x9E3779B97F4A7C15);
        let mut z = self.state;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58476D1CE4E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D049BB133111EB);
        z ^ (z >> 31)
    }

    /// Uniform in `[0, 1)`.
    #[inline]
    pub fn uniform(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
    }
}

/// Position of sample `index` of `count` inside the unit pixel square, jittered
/// inside its stratum.
///
/// The pixel is cut into `rows = round(sqrt(count))` rows; row `r` holds
/// `n_r` samples (the counts differ by at most one) and has height `n_r / count`,
/// so each of the `count` cells, `1 / n_r` wide, has area exactly `1 / count`:
/// a partition into equal-area strata for any `count`, not only squares.
pub fn stratified_2d(index: u32, count: u32, jitter: (f64, f64)) -> (f64, f64) {
    debug_assert!(index < count);
    let rows = ((count as f64).sqrt().round() as u32).max(1);
    let base = count / rows;
    let extra = count % rows; // the first `extra` rows get one more sample
    let (mut row, mut first, mut y0) = (0u32, 0u32, 0.0f64);
    loop {
        let n = base + u32::from(row < extra);
        if index < first + n || row + 1 == rows {
            let column = index - first;
            let height = n as f64 / count as f64;
            let x = (column as f64 + jitter.0) / n as f64;
            let y = y0 + jitter.1 * height;
            return (x.min(1.0 - f64::EPSILON), y.min(1.0 - f64::EPSILON));
        }
        first += n;
        y0 += n as f64 / count as f64;
        row += 1;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn strata_partition_the_pixel_into_equal_areas() {
        for count in [1u32, 2, 3, 4, 5, 7, 9, 16, 17, 64] {
            // The cell corners (jitter 0) and far corners (jitter ~1) bound disjoint cells.
            let mut area = 0.0;
            let mut cells = Vec::new();
            for i in 0..count {
                let lo = stratified_2d(i, count, (0.0, 0.0));
                let hi = stratified_2d(i, count, (1.0 - 1e-12, 1.0 - 1e-12));
                area += (hi.0 - lo.0) * (hi.1 - lo.1);
                assert!((hi.0 - lo.0) * (hi.1 - lo.1) - 1.0 / count as f64 <= 1e-9);
                cells.push((lo, hi));
            }
            assert!((area - 1.0).abs() < 1e-9, "count {count}: area {area}");
            for (a, (la, ha)) in cells.iter().enumerate() {
                for (lb, hb) in cells.iter().skip(a + 1) {
                    let overlap_x = ha.0.min(hb.0) - la.0.max(lb.0);
                    let overlap_y = ha.1.min(hb.1) - la.1.max(lb.1);
                    assert!(overlap_x <= 1e-9 || overlap_y <= 1e-9, "count {count}: cells overlap");
                }
            }
        }
    }

    #[test]
    fn streams_are_deterministic_and_distinct() {
        let a: Vec<u64> = (0..4).map(|_| 0).scan(Rng::for_sample(1, 2, 3), |r, _: u64| Some(r.next_u64())).collect();
        let b: Vec<u64> = (0..4).map(|_| 0).scan(Rng::for_sample(1, 2, 3), |r, _: u64| Some(r.next_u64())).collect();
        let c: Vec<u64> = (0..4).map(|_| 0).scan(Rng::for_sample(1, 2, 4), |r, _: u64| Some(r.next_u64())).collect();
        assert_eq!(a, b);
        assert_ne!(a, c);
        let mut r = Rng::for_sample(0, 0, 0);
        let mean = (0..100_000).map(|_| r.uniform()).sum::<f64>() / 100_000.0;
        assert!((mean - 0.5).abs() < 0.01);
    }
}
