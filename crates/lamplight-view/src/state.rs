//! What the viewer shows now: the scene (the last one that loaded), its load
//! error if the files are broken now, the camera and the settings. Every change
//! makes a new [`Wanted`] for the renderer and a new `state` message for the
//! pages; both go out through channels that keep only the latest value.

use std::path::PathBuf;
use std::sync::{Arc, Mutex, MutexGuard};

use lamplight_core::integrators;
use lamplight_scene::request::{Naming, Request};
use serde_json::{json, Value};
use tokio::sync::watch;

use crate::camera::ViewCamera;
use crate::renderer::{Frame, Loaded, Renderer, Report, Wanted};

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
    /// The settings (the command line's, then the page's).
    pub request: Request,
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
        let view = View { loaded, probed, error: None, camera: None, request, generation: 0, reloads: 0 };
        let app = Arc::new(App {
            token,
            root,
            save_dir,
            scene_arg,
            scene_file,
            view: Mutex::new(view),
            renderer: Mutex::new(None),
            frames: watch::channel(None).0,
            status: watch::channel(Arc::new(json!({}))).0,
            own_files: Arc::default(),
        });
        let weak = Arc::downgrade(&app);
        let renderer = Renderer::start(move |report| {
            let Some(app) = weak.upgrade() else { return };
            match report {
                Report::Frame(frame) => {
                    app.frames.send_replace(Some(Arc::new(frame)));
                }
                Report::Failed(generation, message) => {
                    let mut view = app.lock();
                    if view.generation == generation {
                        view.error = Some(message);
                        app.publish_state(&view);
                    }
                }
            }
        });
        *app.renderer.lock().unwrap_or_else(|p| p.into_inner()) = Some(renderer);
        let mut view = app.lock();
        let first = view.request.clone();
        if let Err(e) = app.submit(&mut view, first) {
            view.error = Some(e);
            app.publish_state(&view);
        }
        drop(view);
        app
    }

    /// Stops the render thread.
    pub fn stop(&self) {
        self.renderer.lock().unwrap_or_else(|p| p.into_inner()).take();
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
        let wanted = Arc::new(Wanted { generation: view.generation, loaded: view.loaded.clone(), camera: view.camera, job });
        if let Some(r) = self.renderer.lock().unwrap_or_else(|p| p.into_inner()).as_ref() {
            r.submit(wanted);
        }
        self.publish_state(view);
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
