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

use std::sync::mpsc::{self, Receiver, RecvTimeoutError, Sender};
use std::sync::{Mutex, Weak};
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

/// What the timeline's thread is told.
enum Command {
    /// Show this frame (checked), in full.
    Seek(i64),
    /// Step through the frames.
    Play,
    /// Stop stepping.
    Pause,
    /// A frame of this generation was shown (or failed): the next step may start.
    Shown(u64),
}

/// The timeline's thread.
pub struct Timeline {
    commands: Mutex<Option<Sender<Command>>>,
    thread: Mutex<Option<JoinHandle<()>>>,
}

impl Timeline {
    /// Starts the thread for `app` (it holds it weakly, so dropping the app ends it).
    pub fn start(app: Weak<App>) -> Timeline {
        let (tx, rx) = mpsc::channel();
        let thread = std::thread::Builder::new()
            .name("lamplight-view-timeline".into())
            .spawn(move || run(&app, &rx))
            .expect("the operating system refused a thread");
        Timeline { commands: Mutex::new(Some(tx)), thread: Mutex::new(Some(thread)) }
    }

    fn send(&self, command: Command) {
        if let Some(tx) = self.commands.lock().unwrap_or_else(|p| p.into_inner()).as_ref() {
            // A thread that ended has nothing left to do with it.
            let _ = tx.send(command);
        }
    }

    /// Shows `frame` next (the newest wins).
    pub fn seek(&self, frame: i64) {
        self.send(Command::Seek(frame));
    }

    /// Starts stepping.
    pub fn play(&self) {
        self.send(Command::Play);
    }

    /// Stops stepping.
    pub fn pause(&self) {
        self.send(Command::Pause);
    }

    /// A frame of `generation` is on show (called from the render thread).
    pub fn shown(&self, generation: u64) {
        self.send(Command::Shown(generation));
    }

    /// Ends the thread and waits for it (a build in flight finishes first).
    pub fn stop(&self) {
        self.commands.lock().unwrap_or_else(|p| p.into_inner()).take();
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

fn run(app: &Weak<App>, commands: &Receiver<Command>) {
    let mut playing = false;
    // The generation of the frame play waits to see shown before the next step.
    let mut waiting_for: Option<u64> = None;
    let mut next_step = Instant::now();
    let mut from_start = false;
    loop {
        let first = if playing && waiting_for.is_none() {
            match commands.recv_timeout(next_step.saturating_duration_since(Instant::now())) {
                Ok(c) => Some(c),
                Err(RecvTimeoutError::Timeout) => None,
                Err(RecvTimeoutError::Disconnected) => return,
            }
        } else {
            match commands.recv() {
                Ok(c) => Some(c),
                Err(_) => return,
            }
        };
        // Everything waiting at once: of the frames asked for, the newest wins.
        let mut seek = None;
        for command in first.into_iter().chain(commands.try_iter()) {
            match command {
                Command::Seek(frame) => {
                    seek = Some(frame);
                    playing = false;
                }
                Command::Play => {
                    playing = true;
                    waiting_for = None;
                    next_step = Instant::now();
                    from_start = true;
                }
                Command::Pause => playing = false,
                Command::Shown(generation) => {
                    if waiting_for.is_some_and(|w| generation >= w) {
                        waiting_for = None;
                    }
                }
            }
        }
        let Some(app) = app.upgrade() else { return };
        if let Some(frame) = seek {
            waiting_for = None;
            app.show_frame(frame);
            continue;
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
        Animation { start: 1, end: 48, fps: 24.0, loc: Default::default() }
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
