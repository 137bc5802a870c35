//! Loading the scene, and loading it again when its files change.
//!
//! The scene's folder and its direct subfolders (where meshes and textures
//! usually sit) are watched with `notify`. A change to a scene, mesh or
//! texture file there ([`WATCHED_EXTENSIONS`]) reloads the scene once the
//! burst of events an editor's save makes has been quiet for [`QUIET`].
//! Temporary files (`.name...`, `*.tmp`, `*~`) and the files the viewer saved
//! itself are ignored.

use std::collections::HashSet;
use std::path::{Path, PathBuf};
use std::sync::mpsc;
use std::sync::{Arc, Mutex};
use std::time::Duration;

use lamplight_scene::request::{MeshOptions, Naming, Request, SceneRequest};
use notify::{EventKind, RecursiveMode, Watcher};

use crate::renderer::Loaded;

/// Extensions whose files can change a scene: scene files, meshes and their
/// side files, and textures.
pub const WATCHED_EXTENSIONS: &[&str] =
    &["toml", "obj", "mtl", "ply", "gltf", "glb", "bin", "png", "jpg", "jpeg", "bmp", "tga", "hdr", "exr"];

/// How long events must stop before the scene is reloaded.
pub const QUIET: Duration = Duration::from_millis(60);

/// Reads and builds the scene `arg` names (a built-in, a scene file or a mesh
/// file), lit by the environment map `request` names, if any. Its warnings are
/// the mesh files' and then those `lamplight render` gives about its lights
/// ([`lamplight_scene::request::Job::light_warnings`]: none reaches the view, a
/// light shut in by geometry, naming what blocks it), probed through the
/// scene's own camera at the request's image size. An animated scene is
/// built at the request's frame, kept within its `[animation] frames` (a
/// reload keeps the frame shown, or the nearest one the edited range holds);
/// a glTF file plays the animation `--animation` chose.
pub fn load(arg: &str, request: &Request) -> Result<Loaded, String> {
    let options = request.mesh_options(MeshOptions::default());
    let scene = SceneRequest::resolve(arg)
        .and_then(|s| s.with_mesh_options(options, Naming::Flags))
        .and_then(|s| s.with_animation(request.animation.as_ref(), Naming::Flags))
        .map_err(|e| e.0)?;
    build(&Arc::new(scene), request, Naming::Flags)
}

/// Builds `scene`, read already, at the request's frame (see [`load`]):
/// the timeline builds each frame it shows this way, through the request
/// layer's `SceneRequest::instantiate` as `lamplight render --frames` does.
pub fn build(scene: &Arc<SceneRequest>, request: &Request, naming: Naming) -> Result<Loaded, String> {
    let animation = scene.animation();
    let mut request = request.clone();
    request.frame = animation.as_ref().map(|a| request.frame.unwrap_or(a.start).clamp(a.start, a.end));
    let job = request.resolve(&scene.defaults, naming).map_err(|e| e.0)?;
    let built = scene.instantiate(&job).map_err(|e| e.0)?;
    let mut warnings = built.warnings;
    // Lights move with the frames: the warnings are this frame's.
    warnings.extend(job.light_warnings(&built.scene));
    let mut loaded = Loaded::new(built.scene, scene.defaults, warnings);
    loaded.source = Some(scene.clone());
    loaded.animation = animation;
    loaded.frame = request.frame;
    Ok(loaded)
}

/// Whether a change to `path` may change the scene.
pub fn relevant(path: &Path, own: &HashSet<PathBuf>) -> bool {
    let name = path.file_name().map(|n| n.to_string_lossy()).unwrap_or_default();
    if name.starts_with('.') || name.ends_with(".tmp") || name.ends_with('~') || own.contains(path) {
        return false;
    }
    let extension = path.extension().map(|e| e.to_string_lossy().to_ascii_lowercase()).unwrap_or_default();
    WATCHED_EXTENSIONS.contains(&extension.as_str())
}

/// Watches `folder` (and its direct subfolders); calls `changed` on its own
/// thread after each quiet burst of relevant changes. Paths in `own` (files
/// the viewer wrote) are ignored. Dropping the watcher ends the watch.
pub fn watch(
    folder: &Path,
    own: Arc<Mutex<HashSet<PathBuf>>>,
    changed: impl Fn() + Send + 'static,
) -> Result<notify::RecommendedWatcher, String> {
    let (tx, rx) = mpsc::channel::<notify::Event>();
    let mut watcher = notify::recommended_watcher(move |event: notify::Result<notify::Event>| {
        if let Ok(event) = event {
            let _ = tx.send(event);
        }
    })
    .map_err(|e| format!("cannot watch {}: {e}", folder.display()))?;
    watcher.watch(folder, RecursiveMode::NonRecursive).map_err(|e| format!("cannot watch {}: {e}", folder.display()))?;
    if let Ok(entries) = std::fs::read_dir(folder) {
        for entry in entries.flatten() {
            if entry.file_type().is_ok_and(|t| t.is_dir()) && !entry.file_name().to_string_lossy().starts_with('.') {
                // A subfolder that cannot be watched only loses live reload for its files.
                let _ = watcher.watch(&entry.path(), RecursiveMode::NonRecursive);
            }
        }
    }
    let is_relevant = move |event: &notify::Event| {
        let own = own.lock().unwrap_or_else(|p| p.into_inner());
        matches!(event.kind, EventKind::Create(_) | EventKind::Modify(_) | EventKind::Remove(_))
            && event.paths.iter().any(|p| relevant(p, &own))
    };
    std::thread::Builder::new()
        .name("lamplight-view-watch".into())
        .spawn(move || {
            while let Ok(event) = rx.recv() {
                if !is_relevant(&event) {
                    continue;
                }
                // Wait for the burst to end, then reload once.
                while rx.recv_timeout(QUIET).is_ok() {}
                changed();
            }
        })
        .map_err(|e| format!("cannot start the watch thread: {e}"))?;
    Ok(watcher)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_scene_mesh_and_texture_files_count() {
        let own: HashSet<PathBuf> = [PathBuf::from("/s/out.png")].into();
        assert!(relevant(Path::new("/s/scene.toml"), &own));
        assert!(relevant(Path::new("/s/meshes/a.OBJ"), &own));
        assert!(relevant(Path::new("/s/wood.png"), &own));
        assert!(!relevant(Path::new("/s/out.png"), &own), "the viewer's own save");
        assert!(!relevant(Path::new("/s/.scene.toml.x1y2.tmp"), &own), "an atomic write's temporary file");
        assert!(!relevant(Path::new("/s/scene.toml~"), &own));
        assert!(!relevant(Path::new("/s/notes.txt"), &own));
    }
}
