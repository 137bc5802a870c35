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
//! (`BENCHMARKS.md`, issue 24, which also measures what it gains). No test
//! yet runs both compilations of one render side by side.
//!
//! Valgrind's CPU does not report GFNI, so instruction counts
//! (`scripts/bench-guard.sh`) measure the [`AVX2_FEATURES`] code.

/// The target features of the render loop's second compilation, as
/// `#[target_feature(enable = ...)]` takes them.
pub const RENDER_FEATURES: &str = "avx2,bmi1,bmi2,lzcnt,popcnt,gfni";

/// The features of its third compilation, [`RENDER_FEATURES`] without GFNI:
/// the AVX2 processors that lack it (AMD before Zen 4, Intel desktop cores
/// before Ice Lake) would otherwise run the baseline loop.
pub const AVX2_FEATURES: &str = "avx2,bmi1,bmi2,lzcnt,popcnt";

/// Whether this CPU has every feature of [`RENDER_FEATURES`] (the standard
/// library detects them once per process; each call is a load and a few tests).
#[inline]
pub fn render_features() -> bool {
    #[cfg(target_arch = "x86_64")]
    {
        use std::arch::is_x86_feature_detected as has;
        has!("avx2") && has!("bmi1") && has!("bmi2") && has!("lzcnt") && has!("popcnt") && has!("gfni")
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        false
    }
}

/// Whether this CPU has every feature of [`AVX2_FEATURES`].
#[inline]
pub fn avx2_features() -> bool {
    #[cfg(target_arch = "x86_64")]
    {
        use std::arch::is_x86_feature_detected as has;
        has!("avx2") && has!("bmi1") && has!("bmi2") && has!("lzcnt") && has!("popcnt")
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        false
    }
}
