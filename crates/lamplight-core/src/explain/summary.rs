//! What an explanation keeps of the samples it does not record in full, and
//! how much it records: at most [`MAX_RECORDED_SAMPLES`] samples, within a
//! memory allowance ([`RECORD_BYTES`] unless the caller gives less).

use crate::math::Rgb;

/// Samples an explanation of a whole pixel records in full; the rest are
/// traced as the render traces them but only summarised ([`SampleSummary`]),
/// and `--sample K` (or `sample=`) records any one of them. 64 covers
/// Whitted's 16 anti-aliasing samples and the viewer's 64 path-traced ones,
/// and bounds what an explanation holds: one record is some kilobytes (5 KB
/// of JSON for a `spheres` tree), so a pixel's explanation stays within some
/// megabytes at any sample count, where recording every sample of 131,072 took
/// 3.2 GB (issue 30).
pub const MAX_RECORDED_SAMPLES: u32 = 64;

/// The most memory the full records of one explanation may take by default:
/// 8 MiB by the recorder's estimate (the size of every node, light and vertex
/// recorded; the process's memory grows by about 1.5 times that). The count
/// alone does not bound it: a Whitted ray tree doubles at every glass
/// surface, so one sample of a deep glass scene holds tens of thousands of
/// rays (22 MB for 36,000 at depth 20 behind two glass shells). Recording
/// stops (the sample under way is dropped, it and the later ones are
/// summarised) where the estimate would pass the allowance. 8 MiB holds 64
/// path-traced samples of depth 8 thirty times over; the JSON form of a
/// record takes about 18 times the record (30 times as one string), which is
/// what a front end reserves ([`RECORD_OUTPUT_FACTOR`]).
pub const RECORD_BYTES: usize = 8 << 20;

/// The memory an explanation takes with its JSON form, per byte of record
/// estimate: measured 18 (written out as it is made) to 30 (made into one
/// string first), on Whitted trees of 2,000 to 36,000 rays.
pub const RECORD_OUTPUT_FACTOR: usize = 32;

/// Why samples were summarised rather than recorded in full.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Unrecorded {
    /// They come after the first [`MAX_RECORDED_SAMPLES`].
    PastCount,
    /// Recording them would have passed the explanation's memory allowance
    /// (bytes).
    Memory {
        /// The allowance in bytes.
        allowance: usize,
    },
}

/// The samples of a pixel from `first` on that were not recorded in full:
/// what the film made of them, without their trees or paths.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SampleSummary {
    /// Index of the first of them ([`MAX_RECORDED_SAMPLES`], or where the
    /// memory allowance ran out).
    pub first: u32,
    /// How many there are.
    pub count: u32,
    /// Why they were not recorded in full.
    pub why: Unrecorded,
    /// How many of them the film drops as not finite.
    pub dropped: u32,
    /// The sum of the film values it keeps of them, in sample order.
    pub film_sum: Rgb,
    /// Their mean film value, `film_sum / count`.
    pub mean: Rgb,
    /// The brightest of them by luminance (Rec. 709) of its film value: its
    /// index and that value, the sample to ask for in full when hunting a
    /// firefly (`None`: the film dropped them all).
    pub brightest: Option<(u32, Rgb)>,
}

impl SampleSummary {
    pub(super) fn new(first: u32, why: Unrecorded) -> SampleSummary {
        SampleSummary { first, count: 0, why, dropped: 0, film_sum: Rgb::ZERO, mean: Rgb::ZERO, brightest: None }
    }

    pub(super) fn add(&mut self, k: u32, film_value: Option<Rgb>) {
        self.count += 1;
        let Some(l) = film_value else {
            self.dropped += 1;
            return;
        };
        self.film_sum += l;
        self.mean = self.film_sum / self.count as f64;
        if self.brightest.is_none_or(|(_, b)| luminance(l) > luminance(b)) {
            self.brightest = Some((k, l));
        }
    }
}

/// Rec. 709 luminance.
pub(super) fn luminance(c: Rgb) -> f64 {
    0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z
}
