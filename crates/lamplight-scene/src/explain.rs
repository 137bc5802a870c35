//! `lamplight explain` and `Scene.explain` in one place: the pixel and sample
//! are checked against the resolved request and named as the front end spells
//! them ([`Naming`]), then [`lamplight_core::explain::explain`] records the
//! pixel with the render's own code.
//!
//! The recorder draws on the render's memory budget ([`crate::memory`]): the
//! explanation and its JSON form take [`RECORD_OUTPUT_FACTOR`] times what the
//! recorder holds, so it reserves that many times
//! [`lamplight_core::explain::RECORD_BYTES`], or what is left of the budget if
//! that is less (at least [`RECORDER_MIN_BYTES`]), while it records, and the
//! recorder stops recording samples in full at that share's fraction.

use std::sync::atomic::AtomicBool;
use std::sync::Arc;

use lamplight_core::explain::{PixelExplanation, Unrecorded, RECORD_BYTES, RECORD_OUTPUT_FACTOR};
use lamplight_core::Scene;

use crate::request::{Job, Naming, RequestError};

/// The least of the memory budget an explanation needs: 1 MiB, a record of
/// 32 KiB (some tens of paths or trees of a usual scene) with its JSON form.
pub const RECORDER_MIN_BYTES: u64 = 1 << 20;

/// Explains pixel `(x, y)` (every sample, or only `sample`) of the render `job`
/// asks for of `scene` (prepared, as for [`Job::run`]). Sample indices run
/// below the samples the render takes at that pixel, which adaptive sampling
/// decides ([`lamplight_core::explain::plan`]).
pub fn explain(scene: &Scene, job: &Job, pixel: (u32, u32), sample: Option<u32>, naming: Naming) -> Result<PixelExplanation, RequestError> {
    explain_cancellable(scene, job, pixel, sample, naming, None)
}

/// [`explain`], which stops with an error soon after `cancel` is raised
/// ([`lamplight_core::explain::plan_cancellable`]): the viewer's stale explanations.
pub fn explain_cancellable(
    scene: &Scene,
    job: &Job,
    (x, y): (u32, u32),
    sample: Option<u32>,
    naming: Naming,
    cancel: Option<Arc<AtomicBool>>,
) -> Result<PixelExplanation, RequestError> {
    let o = &job.options;
    let (w, h) = (o.width, o.height);
    if x >= w || y >= h {
        let asked = match naming {
            Naming::Flags => format!("--pixel {x},{y}"),
            Naming::Keywords => format!("pixel ({x}, {y})"),
        };
        return Err(RequestError(format!("{asked} is outside the {w}x{h} image (x from 0 to {}, y from 0 to {})", w - 1, h - 1)));
    }
    let plan = lamplight_core::explain::plan_cancellable(scene, o, x, y, cancel).map_err(|e| RequestError(e.to_string()))?;
    if let Some(k) = sample.filter(|k| *k >= plan.samples) {
        let n = plan.samples;
        return Err(RequestError(format!(
            "{} {k} does not exist: the render takes {n} sample{} at pixel ({x}, {y}), numbered 0 to {}",
            naming.name("sample"),
            if n == 1 { "" } else { "s" },
            n - 1
        )));
    }
    let left = crate::memory::limit().saturating_sub(crate::memory::used());
    let share = ((RECORD_BYTES * RECORD_OUTPUT_FACTOR) as u64).min(left).max(RECORDER_MIN_BYTES);
    crate::memory::reserve(share, || "the explain recorder".into()).map_err(|e| RequestError(e.to_string()))?;
    let allowance = share / RECORD_OUTPUT_FACTOR as u64;
    let explained = plan.explain_within(scene, sample, allowance as usize).map_err(|e| RequestError(e.to_string()));
    crate::memory::release(share);
    let explained = explained?;
    if let (Some(k), Some(u)) = (sample, &explained.unrecorded) {
        if let Unrecorded::Memory { .. } = u.why {
            let raise = match naming {
                Naming::Flags => "--memory-budget",
                Naming::Keywords => "memory_budget=",
            };
            return Err(RequestError(format!(
                "{} {k}'s record needs more than the {} of the memory budget the explain recorder may take \
                 ({} for the record, the rest for its JSON form); raise it with {raise}",
                naming.name("sample"),
                crate::memory::bytes(share),
                crate::memory::bytes(allowance)
            )));
        }
    }
    Ok(explained)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::request::{Request, SceneRequest};

    #[test]
    fn bad_pixels_and_samples_are_named_as_the_front_end_spells_them() {
        let scene = SceneRequest::resolve("business-card").unwrap();
        let built = scene.build().unwrap();
        let job = Request { spp: Some(2), ..Request::default() }.resolve(&scene.defaults, Naming::Flags).unwrap();
        let err = |xy, s, n| explain(&built, &job, xy, s, n).unwrap_err().0;
        assert_eq!(err((32, 0), None, Naming::Flags), "--pixel 32,0 is outside the 32x32 image (x from 0 to 31, y from 0 to 31)");
        assert_eq!(err((0, 40), None, Naming::Keywords), "pixel (0, 40) is outside the 32x32 image (x from 0 to 31, y from 0 to 31)");
        assert_eq!(
            err((0, 0), Some(2), Naming::Flags),
            "--sample 2 does not exist: the render takes 2 samples at pixel (0, 0), numbered 0 to 1"
        );
        assert_eq!(
            err((0, 0), Some(5), Naming::Keywords),
            "sample 5 does not exist: the render takes 2 samples at pixel (0, 0), numbered 0 to 1"
        );
        assert_eq!(explain(&built, &job, (3, 4), Some(1), Naming::Flags).unwrap().samples.len(), 1);
    }
}
