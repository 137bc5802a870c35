//! `lamplight explain` and `Scene.explain` in one place: the pixel and sample
//! are checked against the resolved request and named as the front end spells
//! them ([`Naming`]), then [`lamplight_core::explain::explain`] records the
//! pixel with the render's own code.

use std::sync::atomic::AtomicBool;
use std::sync::Arc;

use lamplight_core::explain::PixelExplanation;
use lamplight_core::Scene;

use crate::request::{Job, Naming, RequestError};

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
    plan.explain(scene, sample).map_err(|e| RequestError(e.to_string()))
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
