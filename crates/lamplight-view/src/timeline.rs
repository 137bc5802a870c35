//! The timeline of an animated scene: scrubbing to a frame, and playing.
//!
//! The page sends `frame` (show frame N), `play` and `pause`
//! ([`crate::messages`]). They are checked at once ([`requested_frame`]), and
//! the work they ask for runs on the timeline's own thread ([`Timeline`]),
//! never on the server's: building a frame's scene (the request layer's
//! `SceneRequest::instantiate` at that frame, the scene file read once)
//! takes as long as the scene's BVH does.
//!
//! - **Scrubbing**: the newest frame asked for wins, as camera moves do: the
//!   frames asked for while one builds are dropped but the last, which is
//!   built next and rendered in every stage ([`crate::renderer`]). The build
//!   is kept as the view's scene, so camera moves and settings render it
//!   again without rebuilding. Scrubbing pauses play.
//! - **Playing** steps through the frames, each rendered at the preview's
//!   size and one sample per pixel only (the first stage), at most the
//!   scene's `fps` frames per second: the next frame starts when the last one
//!   is shown and `1/fps` has passed since it started, so a scene too slow
//!   for its rate plays as fast as it renders. Play stops at the last frame
//!   of the range (it does not loop), which is then refined in full; play
//!   from the last frame starts again at the first. Pausing refines the
//!   frame shown in full.

use std::sync::{Arc, Condvar, Mutex, MutexGuard, Weak};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

use lamplight_scene::description::Animation;
use lamplight_scene::request::{frames, Naming};
use serde_json::{json, Value};

use crate::state::App;

/// The frame the page asks for in `value`, checked: a whole number within
/// the scene's `[animation] frames`; otherwise the message to answer with.
pub fn requested_frame(animation: Option<&Animation>, value: &Value) -> Result<i64, String> {
    let name = Naming::Keywords.name("frame");
    let Some(a) = animation else {
        return Err(format!("{name}: the scene is not animated (it has no [animation] table), so it has no frames to show"));
    };
    let frame = value.as_i64().ok_or_else(|| format!("{name} must be a whole number, got {value}"))?;
    // The request layer's limits first, in its words (as `--frames` has them).
    frames::check_frame(frame).map_err(|e| format!("{name} {e}"))?;
    if !(a.start..=a.end).contains(&frame) {
        return Err(format!("{name} must be a frame of the scene's animation, from {} to {}, got {frame}", a.start, a.end));
    }
    Ok(frame)
}

/// The scene's animation as the page's `state` message has it (`null` for a static scene).
pub fn animation_json(animation: Option<&Animation>) -> Value {
    match animation {
        Some(a) => json!({ "start": a.start, "end": a.end, "fps": a.fps }),
        None => Value::Null,
    }
}

/// What the page wished last, for the timeline's thread: one slot, not a
/// queue, so a page that sends frames faster than they build costs nothing
/// (the renderer's slot does the same for cameras).
#[derive(Default)]
struct Wish {
    /// The newest frame asked for, not yet built.
    seek: Option<i64>,
    /// Play (`true`) or pause (`false`), asked after `seek`.
    play: Option<bool>,
    /// The newest generation shown (or failed).
    shown: u64,
    /// The viewer is stopping.
    stop: bool,
}

struct Shared {
    wish: Mutex<Wish>,
    wake: Condvar,
}

impl Shared {
    fn lock(&self) -> MutexGuard<'_, Wish> {
        self.wish.lock().unwrap_or_else(|p| p.into_inner())
    }

    fn change(&self, f: impl FnOnce(&mut Wish)) {
        f(&mut self.lock());
        self.wake.notify_one();
    }
}

/// The timeline's thread.
pub struct Timeline {
    shared: Arc<Shared>,
    thread: Mutex<Option<JoinHandle<()>>>,
}

impl Timeline {
    /// Starts the thread for `app` (it holds it weakly, so dropping the app ends it).
    pub fn start(app: Weak<App>) -> Timeline {
        let shared = Arc::new(Shared { wish: Mutex::default(), wake: Condvar::new() });
        let worker = shared.clone();
        let thread = std::thread::Builder::new()
            .name("lamplight-view-timeline".into())
            .spawn(move || run(&app, &worker))
            .expect("the operating system refused a thread");
        Timeline { shared, thread: Mutex::new(Some(thread)) }
    }

    /// Shows `frame` next (the newest wins); pauses play.
    pub fn seek(&self, frame: i64) {
        self.shared.change(|w| {
            w.seek = Some(frame);
            w.play = None;
        });
    }

    /// Starts stepping.
    pub fn play(&self) {
        self.shared.change(|w| w.play = Some(true));
    }

    /// Stops stepping.
    pub fn pause(&self) {
        self.shared.change(|w| w.play = Some(false));
    }

    /// A frame of `generation` is on show (called from the render thread).
    pub fn shown(&self, generation: u64) {
        self.shared.change(|w| w.shown = w.shown.max(generation));
    }

    /// Ends the thread and waits for it (a build in flight finishes first).
    pub fn stop(&self) {
        self.shared.change(|w| w.stop = true);
        let thread = self.thread.lock().unwrap_or_else(|p| p.into_inner()).take();
        if let Some(thread) = thread {
            if thread.thread().id() != std::thread::current().id() {
                let _ = thread.join();
            }
        }
    }
}

impl Drop for Timeline {
    fn drop(&mut self) {
        self.stop();
    }
}

fn run(app: &Weak<App>, shared: &Shared) {
    let mut playing = false;
    // The generation of the frame play waits to see shown before the next step.
    let mut waiting_for: Option<u64> = None;
    let mut next_step = Instant::now();
    let mut from_start = false;
    loop {
        let (seek, play) = {
            let mut w = shared.lock();
            loop {
                if w.stop {
                    return;
                }
                if waiting_for.is_some_and(|g| w.shown >= g) {
                    waiting_for = None;
                }
                if w.seek.is_some() || w.play.is_some() {
                    break;
                }
                if playing && waiting_for.is_none() {
                    let now = Instant::now();
                    if now >= next_step {
                        break;
                    }
                    w = shared.wake.wait_timeout(w, next_step - now).unwrap_or_else(|p| p.into_inner()).0;
                } else {
                    w = shared.wake.wait(w).unwrap_or_else(|p| p.into_inner());
                }
            }
            (w.seek.take(), w.play.take())
        };
        let Some(app) = app.upgrade() else { return };
        if let Some(frame) = seek {
            playing = false;
            waiting_for = None;
            app.show_frame(frame);
        }
        match play {
            Some(true) => {
                playing = true;
                waiting_for = None;
                next_step = Instant::now();
                from_start = true;
            }
            Some(false) => playing = false,
            None => {}
        }
        if playing && waiting_for.is_none() && Instant::now() >= next_step {
            let started = Instant::now();
            match app.step(from_start) {
                Step::Shown(generation, fps) => {
                    waiting_for = Some(generation);
                    next_step = started + Duration::from_secs_f64(1.0 / fps);
                }
                Step::Failed => {}
                Step::End => playing = false,
            }
            from_start = false;
        }
    }
}

/// What one step of play did.
pub enum Step {
    /// The next frame is rendering as this generation; the scene's fps.
    Shown(u64, f64),
    /// The next frame did not build (its error is shown); play goes on.
    Failed,
    /// The last frame was shown already: play stopped.
    End,
}

#[cfg(test)]
mod tests {
    use super::*;
    use lamplight_scene::description::animation::Animation;

    fn turntable() -> Animation {
        Animation { start: 1, end: 48, fps: 24.0, shutter: (0.0, 0.0), loc: Default::default() }
    }

    #[test]
    fn a_frame_is_a_whole_number_within_the_animation() {
        let a = turntable();
        assert_eq!(requested_frame(Some(&a), &json!(13)), Ok(13));
        assert_eq!(requested_frame(Some(&a), &json!(48)), Ok(48));
        assert_eq!(
            requested_frame(Some(&a), &json!(49)),
            Err("frame must be a frame of the scene's animation, from 1 to 48, got 49".into())
        );
        assert_eq!(requested_frame(Some(&a), &json!(0)), Err("frame must be a frame of the scene's animation, from 1 to 48, got 0".into()));
        assert_eq!(requested_frame(Some(&a), &json!(-1)), Err("frame must be a frame number from 0 to 1048574, got -1".into()));
        assert_eq!(requested_frame(Some(&a), &json!(1.5)), Err("frame must be a whole number, got 1.5".into()));
        assert_eq!(requested_frame(Some(&a), &json!("7")), Err("frame must be a whole number, got \"7\"".into()));
        assert_eq!(requested_frame(Some(&a), &Value::Null), Err("frame must be a whole number, got null".into()));
        assert_eq!(
            requested_frame(None, &json!(1)),
            Err("frame: the scene is not animated (it has no [animation] table), so it has no frames to show".into())
        );
    }
}
