//! The page's messages, JSON objects with a `type`:
//!
//! | type | fields | does |
//! |---|---|---|
//! | `camera` | `camera: {eye, look_at, up, vfov}` | looks through that camera |
//! | `reset` | | back to the scene's own camera |
//! | `settings` | `integrator`, `spp`, `max_depth`, `denoise` (each a value or `null` for the scene's) | renders with them; `denoise: true` denoises every frame (Open Image Denoise) |
//! | `explain` | `x`, `y` (pixels of the full image) | answers `explain` with the ray tree of `lamplight explain --json` |
//! | `save` | `name` (`.png`, `.ppm` or `.exr`), `exposure` (stops), `replace` | writes the latest frame into the save folder |
//! | `save_camera` | `name` (`.toml`), `replace` | writes the camera's `[camera]` table there |
//! | `frame` | `frame` (a frame of the scene's `[animation] frames`) | renders that frame ([`crate::timeline`]) |
//! | `play` | | steps through the frames at the preview's size, at most the scene's fps, stopping at the last |
//! | `pause` | | stops play; the frame shown is refined |
//!
//! Saving takes a file name, not a path, into the one save folder
//! ([`crate::ViewOptions::save_dir`]); a name starting with `.` is refused, and
//! so is a file that exists and that this viewer did not write, unless
//! `replace` names it (the page asks first). That refusal is answered with an
//! error that also has `exists: name`.
//!
//! Every value is checked here or by the request layer's limits
//! (`lamplight_scene::request::limits`); a refused message is answered with
//! `{"type": "error", "message": ...}` and changes nothing.

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;

use lamplight_scene::image_io::Format;
use lamplight_scene::request::{self, DisplayTransform, Rendered};
use serde_json::{json, Value};
use tokio::sync::mpsc;

use crate::camera::ViewCamera;
use crate::explainer::{Explainer, Work};
use crate::state::{integrator_name, App};

/// Largest exposure the page may ask a saved image for, in stops.
pub const MAX_EXPOSURE: f64 = 32.0;

/// `{"type": "error", "message": message}`.
pub fn error_reply(message: &str) -> String {
    json!({ "type": "error", "message": message }).to_string()
}

/// `value`, an integer from 0 to `u32::MAX`, or `null`.
fn optional_count(value: &Value, key: &str) -> Result<Option<u32>, String> {
    match value {
        Value::Null => Ok(None),
        v => v.as_u64().and_then(|n| u32::try_from(n).ok()).map(Some).ok_or_else(|| format!("{key} must be a whole number or null")),
    }
}

/// Handles one message; returns the answer to send now, if any (slow work
/// answers later through `answers`).
pub fn handle(app: &Arc<App>, text: &str, answers: &mpsc::Sender<String>, explainer: &Explainer) -> Option<String> {
    let message: Value = match serde_json::from_str(text) {
        Ok(v) => v,
        Err(e) => return Some(error_reply(&format!("the message is not JSON: {e}"))),
    };
    let result = match message["type"].as_str().unwrap_or("") {
        "camera" => ViewCamera::from_json(&message["camera"]).and_then(|c| app.set_camera(Some(c))),
        "reset" => app.set_camera(None),
        "settings" => settings(app, &message),
        "explain" => explain(app, &message, answers.clone(), explainer),
        "save" | "save_camera" => save(app, &message, answers.clone()),
        "frame" => app.seek(&message["frame"]),
        "play" => app.play(),
        "pause" => app.pause(),
        other => Err(lamplight_core::params::unknown(
            "message type",
            other,
            &["camera", "reset", "settings", "explain", "save", "save_camera", "frame", "play", "pause"],
        )),
    };
    result.err().map(|e| error_reply(&e))
}

fn settings(app: &App, message: &Value) -> Result<(), String> {
    let integrator = integrator_name(&message["integrator"])?;
    let spp = optional_count(&message["spp"], "spp")?;
    let max_depth = optional_count(&message["max_depth"], "max_depth")?;
    let denoise = match &message["denoise"] {
        Value::Null => None,
        Value::Bool(on) => Some(*on),
        _ => return Err("denoise must be true, false or null".to_string()),
    };
    app.set_request(|r| {
        r.integrator = integrator;
        r.spp = spp;
        r.max_depth = max_depth;
        r.denoise = denoise;
    })
}

fn explain(app: &Arc<App>, message: &Value, answers: mpsc::Sender<String>, explainer: &Explainer) -> Result<(), String> {
    let x = optional_count(&message["x"], "x")?.ok_or("x must be a whole number")?;
    let y = optional_count(&message["y"], "y")?.ok_or("y must be a whole number")?;
    let frame = app.latest_frame().ok_or("no frame yet")?;
    let wanted = frame.wanted.clone();
    let camera = wanted.camera.unwrap_or(app.lock().probed);
    let work: Work = Box::new(move |cancel: Arc<AtomicBool>| match wanted.explain(x, y, cancel.clone()) {
        Ok(tree) => Some(
            json!({
                "type": "explain", "x": x, "y": y, "generation": wanted.generation,
                "camera": camera.to_json(), "tree": tree,
            })
            .to_string(),
        ),
        Err(_) if cancel.load(Ordering::Relaxed) => None,
        Err(e) => Some(error_reply(&e)),
    });
    explainer.submit(work, move |reply| {
        let _ = answers.blocking_send(reply);
    });
    Ok(())
}

fn save(app: &Arc<App>, message: &Value, answers: mpsc::Sender<String>) -> Result<(), String> {
    let name = message["name"].as_str().ok_or("name must be a file name (saved into the viewer's save folder)")?;
    let camera_only = message["type"] == "save_camera";
    if name.contains('/') || name.contains('\\') {
        return Err(format!("'{name}' is refused: a name, not a path; the viewer saves into {} only", app.save_dir.display()));
    }
    if name.starts_with('.') {
        return Err(format!("'{name}' is refused: names starting with '.' (hidden and configuration files) are not saved"));
    }
    let path = crate::confine::writable_file(&app.save_dir, name).map_err(|e| e.0)?;
    if app.scene_file.as_ref().is_some_and(|f| lamplight_scene::atomic::same_file(f, &path)) {
        return Err(format!("'{name}' is the scene file itself; choose another name"));
    }
    let own = app.own_files.lock().unwrap_or_else(|p| p.into_inner()).contains(&path);
    if path.exists() && !own && message["replace"].as_str() != Some(name) {
        let why = format!("'{name}' exists and the viewer did not write it; to replace it, send \"replace\": \"{name}\"");
        // With `exists`, for the page to ask; a full queue gets the plain error.
        return match answers.try_send(json!({ "type": "error", "message": why, "exists": name }).to_string()) {
            Ok(()) => Ok(()),
            Err(_) => Err(why),
        };
    }
    let extension = path.extension().map(|e| e.to_string_lossy().to_ascii_lowercase()).unwrap_or_default();
    let exposure = match &message["exposure"] {
        Value::Null => 0.0,
        v => v
            .as_f64()
            .filter(|e| e.abs() <= MAX_EXPOSURE)
            .ok_or(format!("exposure must be a number of stops from -{MAX_EXPOSURE} to {MAX_EXPOSURE}"))?,
    };
    let frame = app.latest_frame().ok_or("no frame yet")?;
    if camera_only {
        if extension != "toml" {
            return Err(format!("'{name}': a camera is saved as .toml"));
        }
    } else {
        Format::from_path(&path).map_err(|e| e.to_string())?;
    }
    let camera = frame.wanted.camera.unwrap_or(app.lock().probed);
    let transfer = frame.wanted.loaded.defaults.transfer;
    app.own_files.lock().unwrap_or_else(|p| p.into_inner()).insert(path.clone());
    let name = name.to_string();
    tokio::task::spawn_blocking(move || {
        let written = if camera_only {
            lamplight_scene::atomic::write(&path, camera.to_toml().as_bytes()).map_err(|e| format!("cannot write '{name}': {e}"))
        } else {
            let rendered = Rendered { image: frame.image.clone(), layers: Vec::new(), stats: Default::default(), denoise_time: None };
            let display = DisplayTransform { exposure, tonemap: Default::default(), transfer };
            request::write(&path, &rendered, display).map_err(|e| e.to_string())
        };
        let reply = match written {
            Ok(()) => json!({ "type": "saved", "name": name, "spp": frame.spp, "last": frame.last }).to_string(),
            Err(e) => error_reply(&e),
        };
        let _ = answers.blocking_send(reply);
    });
    Ok(())
}
