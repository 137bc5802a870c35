//! What the viewer shows now: the scene (the last one that loaded), its load
//! error if the files are broken now, the camera and the settings. Every change
//! makes a new [`Wanted`] for the renderer and a new `state` message for the
//! pages; both go out through channels that keep only the latest value.
//! An animated scene's view also holds the frame wanted and whether it plays
//! ([`crate::timeline`]).

use std::path::PathBuf;
use std::sync::{Arc, Mutex, MutexGuard};

use lamplight_core::integrators;
use lamplight_scene::request::{Naming, Request};
use serde_json::{json, Value};
use tokio::sync::watch;

use crate::camera::ViewCamera;
use crate::renderer::{Frame, Loaded, Renderer, Report, Wanted};
use crate::timeline::{self, Step, Timeline};

/// Samples per pixel the viewer's path tracer takes when neither the page nor
/// the scene says (`lamplight render` takes 1, a useless preview).
pub const VIEW_PATH_SPP: u32 = 64;

/// The scene and view, as last set.
pub struct View {
    /// The scene that loaded last.
    pub loaded: Arc<Loaded>,
    /// Its camera as a look-at camera ([`ViewCamera::probe`]).
    pub probed: ViewCamera,
    /// Why the scene's files do not load now (shown over the last good image).
    pub error: Option<String>,
    /// The page's camera; `None`: the scene's own.
    pub camera: Option<ViewCamera>,
    /// The settings (the command line's, then the page's); its `frame` is
    /// the frame wanted (`loaded` may still be the one before, while it builds).
    pub request: Request,
    /// Whether the timeline plays (frames render their preview only).
    pub playing: bool,
    /// `error` is a frame's build error (a later frame that builds clears it;
    /// a file's load error stays until a reload succeeds).
    pub frame_error: bool,
    /// Of the last request.
    pub generation: u64,
    /// Reloads so far.
    pub reloads: u64,
}

/// The viewer's shared state.
pub struct App {
    /// The token every request carries.
    pub token: String,
    /// The scene's folder (the working folder for built-in scenes).
    pub root: PathBuf,
    /// The one folder saves go into.
    pub save_dir: PathBuf,
    /// The scene as the command line named it.
    pub scene_arg: String,
    /// The scene file, when it is one.
    pub scene_file: Option<PathBuf>,
    view: Mutex<View>,
    renderer: Mutex<Option<Renderer>>,
    timeline: Mutex<Option<Timeline>>,
    /// The latest frame.
    pub frames: watch::Sender<Option<Arc<Frame>>>,
    /// The latest `state` message.
    pub status: watch::Sender<Arc<Value>>,
    /// Files the viewer wrote (the watcher ignores them).
    pub own_files: Arc<Mutex<std::collections::HashSet<PathBuf>>>,
}

/// The size the camera is probed at (only the aspect matters).
fn probe(loaded: &Loaded, request: &Request) -> ViewCamera {
    let (w, h) = (request.width.unwrap_or(640), request.height.unwrap_or(360));
    let scene = loaded.lock();
    ViewCamera::probe(&scene, loaded.scene_camera.as_ref(), w, h)
}

impl App {
    /// The viewer of `loaded` with the command line's `request`; starts rendering.
    pub fn start(
        token: String,
        root: PathBuf,
        save_dir: PathBuf,
        scene_arg: String,
        scene_file: Option<PathBuf>,
        loaded: Loaded,
        request: Request,
    ) -> Arc<App> {
        let loaded = Arc::new(loaded);
        let probed = probe(&loaded, &request);
        let view =
            View { loaded, probed, error: None, camera: None, request, playing: false, frame_error: false, generation: 0, reloads: 0 };
        let app = Arc::new(App {
            token,
            root,
            save_dir,
            scene_arg,
            scene_file,
            view: Mutex::new(view),
            renderer: Mutex::new(None),
            timeline: Mutex::new(None),
            frames: watch::channel(None).0,
            status: watch::channel(Arc::new(json!({}))).0,
            own_files: Arc::default(),
        });
        let weak = Arc::downgrade(&app);
        let renderer = Renderer::start(move |report| {
            let Some(app) = weak.upgrade() else { return };
            let generation = match report {
                Report::Frame(frame) => {
                    let generation = frame.wanted.generation;
                    app.frames.send_replace(Some(Arc::new(frame)));
                    generation
                }
                Report::Failed(generation, message) => {
                    let mut view = app.lock();
                    if view.generation == generation {
                        view.error = Some(message);
                        app.publish_state(&view);
                    }
                    generation
                }
            };
            // Play's next step waits for this.
            app.with_timeline(|t| t.shown(generation));
        });
        *app.renderer.lock().unwrap_or_else(|p| p.into_inner()) = Some(renderer);
        *app.timeline.lock().unwrap_or_else(|p| p.into_inner()) = Some(Timeline::start(Arc::downgrade(&app)));
        let mut view = app.lock();
        let first = view.request.clone();
        if let Err(e) = app.submit(&mut view, first) {
            view.error = Some(e);
            app.publish_state(&view);
        }
        drop(view);
        app
    }

    /// Stops the timeline's and the render thread.
    pub fn stop(&self) {
        // Taken out first and dropped (joined) unlocked: the render thread's
        // reports lock `timeline` while the timeline's thread may be finishing.
        let timeline = self.timeline.lock().unwrap_or_else(|p| p.into_inner()).take();
        drop(timeline);
        let renderer = self.renderer.lock().unwrap_or_else(|p| p.into_inner()).take();
        drop(renderer);
    }

    /// The view, locked.
    pub fn lock(&self) -> MutexGuard<'_, View> {
        self.view.lock().unwrap_or_else(|p| p.into_inner())
    }

    /// Renders `request` of the view's scene and camera (the view keeps it when it resolves).
    fn submit(&self, view: &mut View, request: Request) -> Result<(), String> {
        let mut job = request.resolve(&view.loaded.defaults, Naming::Keywords).map_err(|e| e.0)?;
        let path = job.options.integrator.name == "path";
        if path && request.spp.is_none() && view.loaded.defaults.spp.is_none() && job.options.adaptive.is_none() {
            job.options.spp = VIEW_PATH_SPP;
        }
        view.request = request;
        view.generation += 1;
        let wanted =
            Arc::new(Wanted { generation: view.generation, loaded: view.loaded.clone(), camera: view.camera, job, preview: view.playing });
        // The state first: a frame of this generation (a small one renders in
        // microseconds) never goes out before the state that announces it.
        self.publish_state(view);
        if let Some(r) = self.renderer.lock().unwrap_or_else(|p| p.into_inner()).as_ref() {
            r.submit(wanted);
        }
        Ok(())
    }

    /// Sends every page the view's `state` message.
    fn publish_state(&self, view: &View) {
        let r = &view.request;
        let camera = view.camera.unwrap_or(view.probed);
        let message = json!({
            "type": "state",
            "generation": view.generation,
            "scene": self.scene_arg,
            "save_dir": self.save_dir.display().to_string(),
            "scene_file": self.scene_file.as_ref().and_then(|f| f.file_name()).map(|n| n.to_string_lossy()),
            "camera": camera.to_json(),
            "camera_toml": camera.to_toml(),
            "own_camera": view.camera.is_none(),
            "error": view.error,
            "reloads": view.reloads,
            "warnings": view.loaded.warnings,
            // The timeline (docs/view.md): `null` for a static scene, which shows none.
            "animation": timeline::animation_json(view.loaded.animation.as_ref()),
            "frame": view.request.frame,
            "playing": view.playing,
            "settings": {
                "integrator": r.integrator,
                "spp": r.spp,
                "max_depth": r.max_depth,
                "denoise": r.denoise,
                "width": r.width,
                "height": r.height,
            },
            "integrators": integrators::INTEGRATORS.iter().map(|i| i.name).collect::<Vec<_>>(),
        });
        self.status.send_replace(Arc::new(message));
    }

    /// Looks through `camera` (`None`: the scene's own).
    pub fn set_camera(&self, camera: Option<ViewCamera>) -> Result<(), String> {
        let mut view = self.lock();
        view.camera = camera;
        let request = view.request.clone();
        self.submit(&mut view, request)
    }

    /// Changes the settings; a setting out of bounds is refused and the old ones kept.
    pub fn set_request(&self, change: impl FnOnce(&mut Request)) -> Result<(), String> {
        let mut view = self.lock();
        let mut request = view.request.clone();
        change(&mut request);
        self.submit(&mut view, request)
    }

    /// Loads the scene again: on success it replaces the scene and clears the
    /// error; on failure the error is shown and the last good scene kept.
    pub fn reload(&self) {
        let request = self.lock().request.clone();
        let loaded = crate::reload::load(&self.scene_arg, &request);
        let mut view = self.lock();
        view.reloads += 1;
        match loaded {
            Ok(loaded) => {
                view.loaded = Arc::new(loaded);
                view.probed = probe(&view.loaded, &view.request);
                view.error = None;
                view.frame_error = false;
                // The frame shown, or the nearest one an edited range holds.
                view.request.frame = view.loaded.frame;
                view.playing &= view.loaded.animation.is_some();
                let request = view.request.clone();
                if let Err(e) = self.submit(&mut view, request) {
                    view.error = Some(e);
                    self.publish_state(&view);
                }
            }
            Err(e) => {
                view.error = Some(e);
                self.publish_state(&view);
            }
        }
    }

    /// Shows the frame the page asks for in `value` (checked at once: see
    /// [`timeline::requested_frame`]); the timeline's thread builds it, the
    /// newest winning. Scrubbing pauses play.
    pub fn seek(&self, value: &Value) -> Result<(), String> {
        let mut view = self.lock();
        let frame = timeline::requested_frame(view.loaded.animation.as_ref(), value)?;
        view.request.frame = Some(frame);
        view.playing = false;
        self.publish_state(&view);
        drop(view);
        self.with_timeline(|t| t.seek(frame));
        Ok(())
    }

    /// Plays the timeline from the frame shown (from the first after the last).
    pub fn play(&self) -> Result<(), String> {
        let mut view = self.lock();
        if view.loaded.animation.is_none() {
            return Err("play: the scene is not animated (it has no [animation] table), so it has no frames to play".into());
        }
        view.playing = true;
        self.publish_state(&view);
        drop(view);
        self.with_timeline(Timeline::play);
        Ok(())
    }

    /// Stops play; the frame shown is refined in full.
    pub fn pause(&self) -> Result<(), String> {
        self.with_timeline(Timeline::pause);
        let mut view = self.lock();
        if !view.playing {
            return Ok(());
        }
        view.playing = false;
        let request = view.request.clone();
        self.submit(&mut view, request)
    }

    fn with_timeline(&self, f: impl FnOnce(&Timeline)) {
        if let Some(t) = self.timeline.lock().unwrap_or_else(|p| p.into_inner()).as_ref() {
            f(t);
        }
    }

    /// Builds `frame` of the scene (without the view's lock) and shows it:
    /// the generation rendering it, or `None` when it did not build (the
    /// error is shown) or a reload replaced the scene meanwhile (the reload
    /// built the frame wanted itself).
    pub(crate) fn show_frame(&self, frame: i64) -> Option<u64> {
        let (source, mut request) = {
            let view = self.lock();
            (view.loaded.source.clone()?, view.request.clone())
        };
        request.frame = Some(frame);
        let built = crate::reload::build(&source, &request, Naming::Keywords);
        let mut view = self.lock();
        if !view.loaded.source.as_ref().is_some_and(|s| Arc::ptr_eq(s, &source)) {
            return None;
        }
        match built {
            Ok(loaded) => {
                view.loaded = Arc::new(loaded);
                view.probed = probe(&view.loaded, &view.request);
                if view.frame_error {
                    view.error = None;
                    view.frame_error = false;
                }
                let request = view.request.clone();
                match self.submit(&mut view, request) {
                    Ok(()) => Some(view.generation),
                    Err(e) => {
                        view.error = Some(e);
                        self.publish_state(&view);
                        None
                    }
                }
            }
            Err(e) => {
                view.error = Some(e);
                view.frame_error = true;
                self.publish_state(&view);
                None
            }
        }
    }

    /// One step of play: shows the frame after the one wanted (the first,
    /// `from_start`, when play starts on the last); at the end of the range
    /// play stops and the last frame is refined in full.
    pub(crate) fn step(&self, from_start: bool) -> Step {
        let (next, fps) = {
            let mut view = self.lock();
            let Some(a) = view.loaded.animation.clone().filter(|_| view.playing) else { return Step::End };
            let current = view.request.frame.unwrap_or(a.start);
            let next = if from_start && current >= a.end { a.start } else { current + 1 };
            if next > a.end {
                view.playing = false;
                let request = view.request.clone();
                if let Err(e) = self.submit(&mut view, request) {
                    view.error = Some(e);
                    self.publish_state(&view);
                }
                return Step::End;
            }
            view.request.frame = Some(next);
            (next, a.fps)
        };
        match self.show_frame(next) {
            Some(generation) => Step::Shown(generation, fps),
            None => Step::Failed,
        }
    }

    /// The request of the latest frame, for the inspector and saving.
    pub fn latest_frame(&self) -> Option<Arc<Frame>> {
        self.frames.borrow().clone()
    }
}

/// An integrator name from the page, checked by the request layer when resolved.
pub fn integrator_name(value: &Value) -> Result<Option<String>, String> {
    match value {
        Value::Null => Ok(None),
        Value::String(s) if s.len() <= 64 => Ok(Some(s.clone())),
        _ => Err(format!("integrator must be {} or null", integrators::quoted_names())),
    }
}
