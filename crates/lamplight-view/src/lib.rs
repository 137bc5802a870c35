//! `lamplight view`: a live viewer of a scene in the browser.
//!
//! A local web server ([`server`], axum on tokio) serves a page built into the
//! binary (no CDN, no build step) that shows the scene converging
//! ([`renderer`]: a quick preview, then refinement, each new camera or setting
//! cancelling stale work at once), lets the mouse orbit, pan and zoom the
//! camera ([`camera`]), reloads the scene when its files change ([`reload`]),
//! scrubs and plays an animated scene's frames ([`timeline`]),
//! and shows the ray tree of any pixel clicked (the tree of `lamplight
//! explain`, drawn over the image).
//!
//! It is safe by default: it listens on `127.0.0.1` only, every request must
//! carry a random token that only the printed URL holds ([`token`]), and it
//! answers only requests naming it in `Host` and coming from its own page
//! ([`doors`]), serves only its page, and writes only into one save folder
//! ([`confine`], [`messages`]). `docs/view.md` states the whole model.
//! Rendering goes through the request layer (`lamplight_scene::request`), so
//! every size, sample count and depth has the limits `lamplight render` has.

use std::net::{SocketAddr, TcpListener};
use std::path::PathBuf;
use std::sync::Arc;

use lamplight_scene::request::Request;

pub mod camera;
pub mod confine;
pub mod doors;
pub mod explainer;
pub mod messages;
pub mod reload;
pub mod renderer;
pub mod server;
pub mod state;
pub mod timeline;
pub mod token;

pub use state::App;

/// Where the viewer listens unless told.
pub const DEFAULT_ADDRESS: &str = "127.0.0.1:8765";

/// How to start the viewer.
#[derive(Clone, Debug)]
pub struct ViewOptions {
    /// The scene: a built-in name, a scene file or a mesh file.
    pub scene: String,
    /// Where to listen; `None`: [`DEFAULT_ADDRESS`], or any free port of
    /// `127.0.0.1` when that one is taken (port 0 also picks a free one).
    pub listen: Option<SocketAddr>,
    /// The settings to start with (image size, samples, depth, integrator, threads).
    pub request: Request,
    /// The one folder the page's saves go into; `None`: the scene file's
    /// folder, or the current folder for a built-in scene.
    pub save_dir: Option<PathBuf>,
}

/// A running viewer.
pub struct Viewer {
    /// The shared state (tests drive it directly).
    pub app: Arc<App>,
    /// The address it listens on.
    pub address: SocketAddr,
    runtime: Option<tokio::runtime::Runtime>,
    shutdown: Option<tokio::sync::oneshot::Sender<()>>,
    _watcher: Option<notify::RecommendedWatcher>,
}

impl Viewer {
    /// Loads the scene, binds the address and starts serving (in background threads).
    /// Errors are bad input (a scene that does not load, settings out of bounds,
    /// an address in use), one line each.
    pub fn start(options: ViewOptions) -> Result<Viewer, String> {
        let ViewOptions { scene, listen, mut request, save_dir } = options;
        // The viewer's image: the scene's aspect, 640 pixels wide, unless asked.
        if request.width.is_none() && request.height.is_none() {
            request.width = Some(640);
        }
        let scene_file = is_file(&scene).then(|| PathBuf::from(&scene));
        // Settings out of bounds stop here, before anything listens.
        let loaded = reload::load(&scene, &request)?;
        request.frame = loaded.frame;
        let job = request.resolve(&loaded.defaults, lamplight_scene::request::Naming::Flags).map_err(|e| e.0)?;
        request.width = Some(job.options.width);
        request.height = Some(job.options.height);
        let root = match &scene_file {
            Some(f) => f.parent().filter(|p| !p.as_os_str().is_empty()).map(PathBuf::from).unwrap_or_else(|| PathBuf::from(".")),
            None => PathBuf::from("."),
        };
        let root = root.canonicalize().map_err(|e| format!("{}: {e}", root.display()))?;
        let save_dir = match save_dir {
            Some(d) if !d.is_dir() => return Err(format!("--save-dir {}: not a folder", d.display())),
            Some(d) => d.canonicalize().map_err(|e| format!("--save-dir {}: {e}", d.display()))?,
            None => root.clone(),
        };
        let listener = match listen {
            Some(address) => TcpListener::bind(address).map_err(|e| format!("cannot listen on {address}: {e}"))?,
            None => TcpListener::bind(DEFAULT_ADDRESS)
                .or_else(|_| TcpListener::bind("127.0.0.1:0"))
                .map_err(|e| format!("cannot listen on 127.0.0.1: {e}"))?,
        };
        let address = listener.local_addr().map_err(|e| e.to_string())?;
        listener.set_nonblocking(true).map_err(|e| e.to_string())?;
        let token = token::new_token()?;
        let app = App::start(token, root.clone(), save_dir, scene.clone(), scene_file.clone(), loaded, request);
        let watcher = match &scene_file {
            Some(_) => {
                let weak = Arc::downgrade(&app);
                Some(reload::watch(&root, app.own_files.clone(), move || {
                    if let Some(app) = weak.upgrade() {
                        app.reload();
                    }
                })?)
            }
            None => None,
        };
        let runtime = tokio::runtime::Builder::new_multi_thread()
            .worker_threads(2)
            .thread_name("lamplight-view-http")
            .enable_all()
            .build()
            .map_err(|e| format!("cannot start the server's threads: {e}"))?;
        let (shutdown, stopped) = tokio::sync::oneshot::channel::<()>();
        let router = server::router(app.clone(), doors::Doors::new(address));
        let listener = {
            let _guard = runtime.enter();
            tokio::net::TcpListener::from_std(listener).map_err(|e| e.to_string())?
        };
        runtime.spawn(async move {
            let served = axum::serve(listener, router).with_graceful_shutdown(async {
                let _ = stopped.await;
            });
            if let Err(e) = served.await {
                // Not eprintln!: stderr may be gone (issue 30).
                let _ =
                    std::io::Write::write_fmt(&mut std::io::stderr(), format_args!("lamplight: error: the viewer's server stopped: {e}\n"));
            }
        });
        Ok(Viewer { app, address, runtime: Some(runtime), shutdown: Some(shutdown), _watcher: watcher })
    }

    /// The URL to open, with the token.
    pub fn url(&self) -> String {
        format!("http://{}/?token={}", self.address, self.app.token)
    }

    /// Serves until the process ends.
    pub fn wait(self) -> ! {
        loop {
            std::thread::park();
        }
    }
}

impl Drop for Viewer {
    fn drop(&mut self) {
        if let Some(s) = self.shutdown.take() {
            let _ = s.send(());
        }
        if let Some(r) = self.runtime.take() {
            r.shutdown_timeout(std::time::Duration::from_secs(1));
        }
        self.app.stop();
    }
}

/// Whether `scene` names a file rather than a built-in scene (as `SceneRequest::resolve` decides).
fn is_file(scene: &str) -> bool {
    scene.contains('/') || scene.contains(std::path::MAIN_SEPARATOR) || std::path::Path::new(scene).extension().is_some()
}

/// Whether `address` is a loopback address (no warning needed).
pub fn is_loopback(address: &SocketAddr) -> bool {
    address.ip().is_loopback()
}
