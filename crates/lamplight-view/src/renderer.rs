//! Progressive rendering on one thread, latest request wins.
//!
//! A [`Wanted`] is a scene, a camera and a resolved [`Job`]. The render thread
//! renders it in [`stages`]: a one-sample preview at a fraction of the size
//! (the frame that follows a drag at once; [`preview_divisor`] sizes it to
//! render in about [`PREVIEW_BUDGET`], by the time per sample measured so
//! far), then half the size, then the full image with one sample, then more
//! samples (4, 16, 64, ... for fixed supersampling), and last the job exactly
//! as `lamplight render` would run it, so the final frame is that render's
//! image. A job that denoises denoises every stage (Cycles' viewport
//! denoising), each frame reporting the time it added. Every stage is one call of the ordinary render entry
//! ([`Job::run`]); the viewer adds nothing to the render loop. A request
//! marked [`Wanted::preview`] (play, [`crate::timeline`]) stops after the preview.
//!
//! [`Renderer::submit`] replaces the one waiting request (there is never more
//! than one) and raises the cancel flag of the one in flight, which the render
//! loop checks before every tile, so a stale render stops within a tile and
//! dragging never piles renders up: memory holds one request waiting, one in
//! flight and the frames published, whatever the rate of requests.

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Condvar, Mutex, MutexGuard};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

use lamplight_core::camera::Camera;
use lamplight_core::film::Image;
use lamplight_core::{RenderControl, RenderOptions, Scene};
use lamplight_scene::description::Animation;
use lamplight_scene::request::{Defaults, Job, Naming, SceneRequest};

use crate::camera::ViewCamera;

/// A scene built and ready to render.
pub struct Loaded {
    /// The scene; whoever renders it sets its camera while holding the lock.
    pub scene: Mutex<Scene>,
    /// The scene's own camera.
    pub scene_camera: Arc<dyn Camera>,
    /// The scene's own settings.
    pub defaults: Defaults,
    /// Warnings of the files it read.
    pub warnings: Vec<String>,
    /// The scene as read, to build its other frames from without reading it again.
    pub source: Option<Arc<SceneRequest>>,
    /// The scene's `[animation]`; `None`: it is the same at every frame.
    pub animation: Option<Animation>,
    /// The frame `scene` was built at (`None` for a static scene).
    pub frame: Option<i64>,
}

impl Loaded {
    /// `scene` with `defaults`, a static scene of unknown source.
    pub fn new(scene: Scene, defaults: Defaults, warnings: Vec<String>) -> Loaded {
        Loaded {
            scene_camera: scene.settings.camera.clone(),
            scene: Mutex::new(scene),
            defaults,
            warnings,
            source: None,
            animation: None,
            frame: None,
        }
    }

    /// The scene, locked (a panic elsewhere leaves it usable: rendering never mutates it).
    pub fn lock(&self) -> MutexGuard<'_, Scene> {
        self.scene.lock().unwrap_or_else(|poisoned| poisoned.into_inner())
    }
}

/// What to render.
pub struct Wanted {
    /// Numbers every request; frames carry it.
    pub generation: u64,
    /// The scene.
    pub loaded: Arc<Loaded>,
    /// The camera; `None`: the scene's own.
    pub camera: Option<ViewCamera>,
    /// The last stage, as `lamplight render` would run it.
    pub job: Job,
    /// Render the first stage only (the preview), as play does ([`crate::timeline`]).
    pub preview: bool,
}

impl Wanted {
    /// The camera to render with.
    pub fn camera(&self) -> Arc<dyn Camera> {
        match self.camera.map(|c| c.build()) {
            Some(Ok(c)) => Arc::new(c),
            // Cameras are checked when they arrive; this cannot fail.
            _ => self.loaded.scene_camera.clone(),
        }
    }

    /// Explains pixel `(x, y)` of the final frame: the ray tree of `explain`,
    /// as JSON; errs soon after `cancel` is raised.
    pub fn explain(&self, x: u32, y: u32, cancel: Arc<AtomicBool>) -> Result<serde_json::Value, String> {
        let camera = self.camera();
        let explained = {
            // A blocking lock, not a try_lock loop: the render thread takes the
            // scene again at once after each stage, so polling starved the
            // explanation (30 s for a click at 4096 spp instead of 0.9 s),
            // while a waiter is handed the lock between stages.
            let mut scene = self.loaded.lock();
            scene.settings.camera = camera;
            lamplight_scene::explain::explain_cancellable(&scene, &self.job, (x, y), None, Naming::Keywords, Some(cancel))
        };
        explained.map(|e| e.to_json()).map_err(|e| e.0)
    }
}

/// A rendered frame.
pub struct Frame {
    /// The request it belongs to.
    pub wanted: Arc<Wanted>,
    /// Linear radiance, at the stage's size.
    pub image: Image,
    /// Samples per pixel (the most any pixel took, with adaptive sampling).
    pub spp: u32,
    /// Samples per second of this stage.
    pub samples_per_second: f64,
    /// From the request's submission to this frame.
    pub latency: Duration,
    /// The stage is the last: the image is `lamplight render`'s.
    pub last: bool,
    /// The time the denoiser added to this frame, when the job denoises.
    pub denoise_time: Option<Duration>,
}

/// How long the preview that follows a camera change should take to render.
pub const PREVIEW_BUDGET: Duration = Duration::from_millis(30);

/// The largest preview divisor (1/16 of the width: 40x23 pixels of a 640x360 image).
pub const MAX_DIVISOR: u32 = 16;

/// The power of two `d` (1 to [`MAX_DIVISOR`]) by which the preview divides
/// the image's sides so that its `(w/d) (h/d)` samples take about
/// [`PREVIEW_BUDGET`] at `seconds_per_sample` (4 before anything is measured).
pub fn preview_divisor(width: u32, height: u32, seconds_per_sample: Option<f64>) -> u32 {
    let Some(per_sample) = seconds_per_sample.filter(|s| s.is_finite() && *s > 0.0) else { return 4 };
    let affordable = PREVIEW_BUDGET.as_secs_f64() / per_sample;
    let mut d = 1;
    while d < MAX_DIVISOR && (width / d).max(1) as f64 * (height / d).max(1) as f64 > affordable {
        d *= 2;
    }
    d
}

/// The stages of `last`, the preview `divisor` times smaller on each side (see the module doc).
pub fn stages(last: &RenderOptions, divisor: u32) -> Vec<RenderOptions> {
    let base = RenderOptions { spp: 1, adaptive: None, window: None, time_limit: None, ..last.clone() };
    let smaller = |d: u32| RenderOptions { width: (last.width / d).max(1), height: (last.height / d).max(1), ..base.clone() };
    let mut out = vec![smaller(divisor)];
    if divisor > 2 {
        out.push(smaller(2));
    }
    let mut spp = 1;
    while spp < last.spp || (spp == 1 && last.adaptive.is_some()) {
        out.push(RenderOptions { spp, ..base.clone() });
        spp *= 4;
        if last.adaptive.is_some() {
            break;
        }
    }
    out.push(last.clone());
    // A full-size preview is the one-sample stage (and may be the job itself).
    out.dedup();
    out
}

struct Slot {
    next: Option<(Arc<Wanted>, Instant)>,
    cancel: Arc<AtomicBool>,
    shutdown: bool,
}

struct Shared {
    slot: Mutex<Slot>,
    wake: Condvar,
}

impl Shared {
    fn lock(&self) -> MutexGuard<'_, Slot> {
        self.slot.lock().unwrap_or_else(|poisoned| poisoned.into_inner())
    }
}

/// The render thread.
pub struct Renderer {
    shared: Arc<Shared>,
    thread: Option<JoinHandle<()>>,
}

/// What the render thread reports: a frame, or why a request failed.
pub enum Report {
    /// A stage finished.
    Frame(Frame),
    /// The request cannot be rendered (the generation and the message).
    Failed(u64, String),
}

impl Renderer {
    /// Starts the render thread; `report` is called from it.
    pub fn start(report: impl Fn(Report) + Send + 'static) -> Renderer {
        let shared =
            Arc::new(Shared { slot: Mutex::new(Slot { next: None, cancel: Arc::default(), shutdown: false }), wake: Condvar::new() });
        let worker = shared.clone();
        let thread = std::thread::Builder::new()
            .name("lamplight-view-render".into())
            .spawn(move || render_loop(&worker, &report))
            .expect("the operating system refused a thread");
        Renderer { shared, thread: Some(thread) }
    }

    /// Renders `wanted` next, dropping any request still waiting and cancelling the one in flight.
    pub fn submit(&self, wanted: Arc<Wanted>) {
        let mut slot = self.shared.lock();
        slot.next = Some((wanted, Instant::now()));
        slot.cancel.store(true, Ordering::Relaxed);
        self.shared.wake.notify_one();
    }
}

impl Drop for Renderer {
    fn drop(&mut self) {
        {
            let mut slot = self.shared.lock();
            slot.shutdown = true;
            slot.cancel.store(true, Ordering::Relaxed);
            self.shared.wake.notify_one();
        }
        if let Some(thread) = self.thread.take() {
            let _ = thread.join();
        }
    }
}

fn render_loop(shared: &Shared, report: &dyn Fn(Report)) {
    // Seconds per sample of the latest full-size stage (a preview's is noisier).
    let mut per_sample: Option<f64> = None;
    loop {
        let (wanted, submitted, cancel) = {
            let mut slot = shared.lock();
            while slot.next.is_none() && !slot.shutdown {
                slot = shared.wake.wait(slot).unwrap_or_else(|poisoned| poisoned.into_inner());
            }
            if slot.shutdown {
                return;
            }
            let (wanted, submitted) = slot.next.take().expect("checked above");
            // A fresh flag per request: a later submit cancels this one only.
            slot.cancel = Arc::new(AtomicBool::new(false));
            (wanted, submitted, slot.cancel.clone())
        };
        let camera = wanted.camera();
        let control = RenderControl { progress: &|_, _| {}, cancel: Some(&cancel), stop: None };
        let o = &wanted.job.options;
        let mut stages = stages(o, preview_divisor(o.width, o.height, per_sample));
        let count = stages.len();
        if wanted.preview {
            stages.truncate(1);
        }
        for (i, options) in stages.into_iter().enumerate() {
            if cancel.load(Ordering::Relaxed) {
                break;
            }
            let job = Job { options, ..wanted.job.clone() };
            let rendered = {
                let mut scene = wanted.loaded.lock();
                scene.settings.camera = camera.clone();
                job.run(&scene, &control)
            };
            match rendered {
                Ok(r) => {
                    let seconds = r.stats.elapsed.as_secs_f64().max(1e-9);
                    if r.image.width == o.width && r.stats.pixel_samples > 0 {
                        per_sample = Some(seconds / r.stats.pixel_samples as f64);
                    }
                    report(Report::Frame(Frame {
                        wanted: wanted.clone(),
                        spp: r.stats.samples_per_pixel,
                        samples_per_second: r.stats.pixel_samples as f64 / seconds,
                        latency: submitted.elapsed(),
                        last: i + 1 == count,
                        denoise_time: r.denoise_time,
                        image: r.image,
                    }));
                }
                Err(_) if cancel.load(Ordering::Relaxed) => break,
                Err(e) => {
                    report(Report::Failed(wanted.generation, e.to_string()));
                    break;
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use lamplight_core::Adaptive;

    #[test]
    fn stages_preview_then_refine_then_end_with_the_job() {
        let fixed = RenderOptions { width: 640, height: 360, spp: 64, ..RenderOptions::default() };
        let s = stages(&fixed, 4);
        let sizes: Vec<_> = s.iter().map(|o| (o.width, o.height, o.spp)).collect();
        assert_eq!(sizes, [(160, 90, 1), (320, 180, 1), (640, 360, 1), (640, 360, 4), (640, 360, 16), (640, 360, 64)]);
        assert_eq!(s.last(), Some(&fixed));
        let adaptive = RenderOptions { adaptive: Some(Adaptive::Antialias(Default::default())), ..RenderOptions::default() };
        let s = stages(&adaptive, 2);
        assert_eq!(
            s.iter().map(|o| (o.width, o.spp, o.adaptive.is_some())).collect::<Vec<_>>(),
            [(320, 1, false), (640, 1, false), (640, 1, true)]
        );
        let one = RenderOptions { width: 3, height: 2, ..RenderOptions::default() };
        assert_eq!(stages(&one, 4).iter().map(|o| (o.width, o.height)).collect::<Vec<_>>(), [(1, 1), (3, 2)]);
    }

    #[test]
    fn the_preview_is_sized_to_its_time_budget() {
        assert_eq!(preview_divisor(640, 360, None), 4, "before any measurement");
        // 30 ms at 1 us a sample: 30,000 samples; 160x90 = 14,400 fits, 320x180 = 57,600 does not.
        assert_eq!(preview_divisor(640, 360, Some(1e-6)), 4);
        assert_eq!(preview_divisor(640, 360, Some(1e-9)), 1, "a fast scene previews at full size");
        assert_eq!(preview_divisor(640, 360, Some(1.0)), MAX_DIVISOR, "never smaller than 1/16");
        let one = RenderOptions { width: 64, height: 36, ..RenderOptions::default() };
        assert_eq!(stages(&one, 1), vec![one], "at full size the preview is the job");
    }
}
