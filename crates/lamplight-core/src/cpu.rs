//! What the processor offers beyond baseline x86-64, detected at run time, so
//! that one binary runs on any x86-64 and uses more where it can.
//!
//! The render loop compiles its per-pixel sampling three times: for baseline
//! x86-64, for [`RENDER_FEATURES`] (the AVX2 generation's instruction set, with
//! GFNI) and for [`AVX2_FEATURES`] (the same without GFNI), picked per tile row
//! by [`render_features`] and [`avx2_features`]. Neither feature set changes
//! a result: Rust never fuses a multiply and an add on its own, and every
//! instruction computes the same IEEE value or the same bits (GFNI reverses the
//! bits of the Sobol sampler's 32-bit words in four instructions where
//! baseline x86-64 needs about seventeen), so images are the same bytes on
//! every CPU. Checked: the golden-image tests pass through this compilation
//! on CPUs that have the features, and a whole-program build with
//! `-C target-cpu=x86-64-v3 -C target-feature=+gfni` wrote the same bytes as
//! the baseline build for spheres, luxo and the path-traced Cornell box
//! (`BENCHMARKS.md`, issue 24, which also measures what it gains). The
//! path tracer's lanes test each of their compilations this CPU has against
//! the one-sample loop (`integrators/path/lanes/tests.rs`); no test yet runs
//! the render loop's compilations side by side.
//!
//! The path tracer's lanes and their queries (`accel/ray_lanes.rs`) have a
//! fourth compilation, for [`AVX512_FEATURES`]: the same operations, so the
//! same bits, with 64-bit multiplies and conversions the lanes' Sobol
//! hashing lacks under AVX2, and 32 vector registers and mask registers for
//! the queries.
//!
//! Valgrind's CPU reports neither GFNI nor AVX-512, so instruction counts
//! (`scripts/bench-guard.sh`) measure the [`AVX2_FEATURES`] code.

/// The target features of the render loop's second compilation, as
/// `#[target_feature(enable = ...)]` takes them.
pub const RENDER_FEATURES: &str = "avx2,bmi1,bmi2,lzcnt,popcnt,gfni";

/// The features of its third compilation, [`RENDER_FEATURES`] without GFNI:
/// the AVX2 processors that lack it (AMD before Zen 4, Intel desktop cores
/// before Ice Lake) would otherwise run the baseline loop.
pub const AVX2_FEATURES: &str = "avx2,bmi1,bmi2,lzcnt,popcnt";

/// [`RENDER_FEATURES`] with AVX-512 (foundation, doubleword and quadword,
/// vector length, byte and word), for the path tracer's lanes only: their
/// Sobol hashing multiplies 64-bit integers lane by lane, one `vpmullq` here
/// and five instructions with AVX2 alone, and converts 32-bit integers to
/// floats in one `vcvtudq2pd`; the queries keep every value in a register
/// (BENCHMARKS.md, session 33). The Whitted loop
/// gained under 2 % from the same compilation and keeps [`RENDER_FEATURES`].
pub const AVX512_FEATURES: &str = "avx2,bmi1,bmi2,lzcnt,popcnt,gfni,avx512f,avx512dq,avx512vl,avx512bw";

/// What [`render_features`], [`avx2_features`] and [`avx512_features`]
/// found, detected once: bit 0 set when detection ran, bit 1 for
/// [`RENDER_FEATURES`], bit 2 for [`AVX2_FEATURES`], bit 3 for
/// [`AVX512_FEATURES`]. The scene's queries ask per ray; the standard library's
/// own cache tests each feature's flag separately (about twenty instructions
/// and a call), this is one load and one test (issue 24).
static DETECTED: std::sync::atomic::AtomicU8 = std::sync::atomic::AtomicU8::new(0);

/// The [`DETECTED`] bits, detecting on the first call.
#[inline(always)]
fn detected() -> u8 {
    let bits = DETECTED.load(std::sync::atomic::Ordering::Relaxed);
    if bits != 0 {
        return bits;
    }
    detect()
}

/// Detects the features and stores them in [`DETECTED`] (threads that race
/// here store the same value).
#[cold]
#[inline(never)]
fn detect() -> u8 {
    #[cfg(target_arch = "x86_64")]
    let bits = {
        use std::arch::is_x86_feature_detected as has;
        let avx2 = has!("avx2") && has!("bmi1") && has!("bmi2") && has!("lzcnt") && has!("popcnt");
        let render = avx2 && has!("gfni");
        let avx512 = render && has!("avx512f") && has!("avx512dq") && has!("avx512vl") && has!("avx512bw");
        1 | (u8::from(render) << 1) | (u8::from(avx2) << 2) | (u8::from(avx512) << 3)
    };
    #[cfg(not(target_arch = "x86_64"))]
    let bits = 1;
    DETECTED.store(bits, std::sync::atomic::Ordering::Relaxed);
    bits
}

/// Whether this CPU has every feature of [`RENDER_FEATURES`] (detected once per
/// process; each call is a load and a test).
#[inline]
pub fn render_features() -> bool {
    detected() & 2 != 0
}

/// Whether this CPU has every feature of [`AVX2_FEATURES`].
#[inline]
pub fn avx2_features() -> bool {
    detected() & 4 != 0
}

/// Whether this CPU has every feature of [`AVX512_FEATURES`].
#[inline]
pub fn avx512_features() -> bool {
    detected() & 8 != 0
}

#[cfg(all(test, target_arch = "x86_64"))]
mod tests {
    /// The cached answers are the standard library's, on the first call and after.
    #[test]
    fn cached_detection_matches_the_standard_library() {
        use std::arch::is_x86_feature_detected as has;
        let avx2 = has!("avx2") && has!("bmi1") && has!("bmi2") && has!("lzcnt") && has!("popcnt");
        for _ in 0..2 {
            assert_eq!(super::avx2_features(), avx2);
            assert_eq!(super::render_features(), avx2 && has!("gfni"));
            let avx512 = has!("avx512f") && has!("avx512dq") && has!("avx512vl") && has!("avx512bw");
            assert_eq!(super::avx512_features(), avx2 && has!("gfni") && avx512);
        }
    }
}
