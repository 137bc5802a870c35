//! The viewer's camera: a look-at pinhole camera (`eye`, `look_at`, `up`,
//! `vfov`), the one docs/scene-format.md's `perspective` camera describes, so
//! the page can orbit, pan and zoom it and the view can be pasted into a scene
//! file as TOML.
//!
//! A scene's own camera may be of any kind; the viewer starts from it as it is
//! (so the first frames are the bytes `lamplight render` gives) and reads a
//! look-at camera off it by probing three of its rays ([`ViewCamera::probe`]):
//! the centre ray gives `eye` and the view direction, the rays through the
//! middle of the top and bottom edges give `vfov` (the angle between them) and
//! `up`, and the centre ray's first hit gives `look_at` (the point the page
//! orbits about). For a perspective camera that is the camera itself.

use lamplight_core::camera::{Camera, Fov, Perspective};
use lamplight_core::math::Vec3;
use lamplight_core::Scene;
use serde_json::{json, Value};

/// Largest coordinate the page may send: beyond it a scene's numbers lose their
/// precision anyway, and it keeps every product finite.
pub const MAX_COORDINATE: f64 = 1e9;

/// A look-at pinhole camera.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ViewCamera {
    /// Eye position.
    pub eye: Vec3,
    /// The point at the image centre, which orbiting turns about.
    pub look_at: Vec3,
    /// Sky direction.
    pub up: Vec3,
    /// Full vertical field of view, degrees.
    pub vfov: f64,
}

impl ViewCamera {
    /// The look-at camera that `camera` is, or is closest to, for a
    /// `width x height` image of `scene` (see the module doc).
    pub fn probe(scene: &Scene, camera: &dyn Camera, width: u32, height: u32) -> ViewCamera {
        let sized = camera.for_image(width, height);
        let camera = sized.as_deref().unwrap_or(camera);
        let (w, h) = (width as f64, height as f64);
        let centre = camera.ray(w / 2.0, h / 2.0, width, height, (0.5, 0.5));
        let top = camera.ray(w / 2.0, 0.0, width, height, (0.5, 0.5)).dir.normalize_or_zero();
        let bottom = camera.ray(w / 2.0, h, width, height, (0.5, 0.5)).dir.normalize_or_zero();
        let forward = centre.dir.normalize_or(Vec3::NEG_Z);
        let vfov = top.dot(bottom).clamp(-1.0, 1.0).acos().to_degrees();
        let vfov = if vfov.is_finite() && (1.0..=170.0).contains(&vfov) { vfov } else { 40.0 };
        let sky = top - bottom;
        let up = (sky - forward * sky.dot(forward)).try_normalize().unwrap_or(Vec3::Y);
        // The same camera with a coordinate axis as its sky, when one gives it
        // (no roll about that axis): the TOML then reads `up = [0, 1, 0]`.
        let up = [Vec3::Y, Vec3::Z, Vec3::X]
            .into_iter()
            .find(|axis| (axis - forward * axis.dot(forward)).try_normalize().is_some_and(|a| a.dot(up) > 1.0 - 1e-12))
            .unwrap_or(up);
        let distance = match scene.first_intersect(&centre, f64::INFINITY) {
            Some(hit) => (hit.point - centre.origin).length(),
            None => (scene.bounds().centroid() - centre.origin).length(),
        };
        let distance = if distance.is_finite() && distance > 1e-6 { distance } else { 1.0 };
        ViewCamera { eye: centre.origin, look_at: centre.origin + forward * distance, up, vfov }
    }

    /// The camera to render with.
    pub fn build(&self) -> Result<Perspective, String> {
        Perspective::look_at(self.eye, self.look_at, self.up, Fov::VerticalDeg(self.vfov)).map_err(|e| e.to_string())
    }

    /// The camera as the page sends and receives it.
    pub fn to_json(&self) -> Value {
        let v = |x: Vec3| json!([x.x, x.y, x.z]);
        json!({ "eye": v(self.eye), "look_at": v(self.look_at), "up": v(self.up), "vfov": self.vfov })
    }

    /// The camera the page sent: every key present, finite, coordinates within
    /// [`MAX_COORDINATE`], `vfov` strictly between 0 and 180, and a camera
    /// that can be built (eye and look_at apart, up not along the view).
    pub fn from_json(value: &Value) -> Result<ViewCamera, String> {
        let vector = |key: &str| -> Result<Vec3, String> {
            let a = value.get(key).and_then(Value::as_array).filter(|a| a.len() == 3);
            let a = a.ok_or_else(|| format!("camera.{key} must be an array of 3 numbers"))?;
            let mut out = [0.0; 3];
            for (o, x) in out.iter_mut().zip(a) {
                *o = x
                    .as_f64()
                    .filter(|x| x.abs() <= MAX_COORDINATE)
                    .ok_or_else(|| format!("camera.{key} must hold numbers of magnitude at most {MAX_COORDINATE}"))?;
            }
            Ok(Vec3::from_array(out))
        };
        let vfov = value.get("vfov").and_then(Value::as_f64).filter(|f| *f > 0.0 && *f < 180.0);
        let vfov = vfov.ok_or("camera.vfov must be a number of degrees between 0 and 180 (exclusive)")?;
        let camera = ViewCamera { eye: vector("eye")?, look_at: vector("look_at")?, up: vector("up")?, vfov };
        camera.build()?;
        Ok(camera)
    }

    /// The `[camera]` table of a scene file (docs/scene-format.md) that gives this view.
    pub fn to_toml(&self) -> String {
        // Rounding residue (1e-16 where 0 was meant) is written as 0.
        let scale = self.eye.abs().max(self.look_at.abs()).max_element().max(1e-300);
        let snap = |x: f64| if x.abs() < scale * 1e-12 { 0.0 } else { x };
        let v = |x: Vec3| format!("[{}, {}, {}]", short(snap(x.x)), short(snap(x.y)), short(snap(x.z)));
        format!("[camera]\neye = {}\nlook_at = {}\nup = {}\nvfov = {}\n", v(self.eye), v(self.look_at), v(self.up), short(self.vfov))
    }
}

/// `x` with 6 significant digits and no trailing zeros, a number TOML reads
/// (`1`, `-0.25`, `1.5e-7`).
fn short(x: f64) -> String {
    if x == 0.0 {
        return "0".into();
    }
    let magnitude = x.abs().log10().floor() as i32;
    if !(-4..=9).contains(&magnitude) {
        return format!("{x:.5e}");
    }
    let decimals = (5 - magnitude).max(0) as usize;
    let text = format!("{x:.decimals$}");
    let text = if text.contains('.') { text.trim_end_matches('0').trim_end_matches('.').to_string() } else { text };
    if text == "-0" {
        "0".into()
    } else {
        text
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn probing_a_perspective_camera_gives_it_back() {
        let scene = lamplight_scene::request::SceneRequest::resolve("luxo").unwrap().build().unwrap();
        let probed = ViewCamera::probe(&scene, scene.settings.camera.as_ref(), 640, 360);
        // luxo's camera: eye (1.3, 1.6, 3), vfov 40.
        assert!((probed.eye - Vec3::new(1.3, 1.6, 3.0)).length() < 1e-12, "{probed:?}");
        assert!((probed.vfov - 40.0).abs() < 1e-9, "{probed:?}");
        assert_eq!(probed.up, Vec3::Y, "the scene's sky, not the orthonormal up");
        let built = probed.build().unwrap();
        for (x, y) in [(0.5, 0.5), (320.0, 180.0), (639.5, 10.25)] {
            let a = scene.settings.camera.ray(x, y, 640, 360, (0.5, 0.5));
            let b = built.ray(x, y, 640, 360, (0.5, 0.5));
            assert!((a.dir.normalize() - b.dir.normalize()).length() < 1e-9, "ray through ({x}, {y})");
        }
    }

    #[test]
    fn the_page_s_camera_is_checked() {
        let good = json!({ "eye": [0, 0, 5], "look_at": [0, 0, 0], "up": [0, 1, 0], "vfov": 40 });
        assert!(ViewCamera::from_json(&good).is_ok());
        let with = |key: &str, v: Value| {
            let mut c = good.clone();
            c[key] = v;
            ViewCamera::from_json(&c).unwrap_err()
        };
        assert_eq!(with("vfov", json!(180)), "camera.vfov must be a number of degrees between 0 and 180 (exclusive)");
        assert_eq!(with("eye", json!([0, 0])), "camera.eye must be an array of 3 numbers");
        assert_eq!(with("eye", json!([0, 0, 1e300])), "camera.eye must hold numbers of magnitude at most 1000000000");
        assert_eq!(with("eye", json!([0, 0, 0])), "invalid camera: eye and lookat coincide");
        assert_eq!(with("up", json!([0, 0, 1])), "invalid camera: up is parallel to the viewing direction");
    }

    #[test]
    fn the_toml_reads_back_as_the_same_view() {
        let c = ViewCamera { eye: Vec3::new(1.3, 1.6, 3.0), look_at: Vec3::new(-0.2, 0.25, 0.8), up: Vec3::Y, vfov: 42.0 };
        assert_eq!(c.to_toml(), "[camera]\neye = [1.3, 1.6, 3]\nlook_at = [-0.2, 0.25, 0.8]\nup = [0, 1, 0]\nvfov = 42\n");
        let c = ViewCamera { eye: Vec3::new(0.3, 1.2e-17, 2.0), look_at: Vec3::new(-0.7173913, 0.0, -1.45217), up: Vec3::Y, vfov: 37.5 };
        let file = lamplight_scene::instantiate::SceneFile::parse(std::path::Path::new("view.toml"), &c.to_toml()).unwrap();
        let (read, built) = (file.build().unwrap().settings.camera, c.build().unwrap());
        for (x, y) in [(0.5, 0.5), (99.5, 40.25)] {
            let (a, b) = (read.ray(x, y, 100, 50, (0.5, 0.5)), built.ray(x, y, 100, 50, (0.5, 0.5)));
            assert!((a.dir.normalize() - b.dir.normalize()).length() < 1e-5, "{a:?} {b:?}");
        }
        assert_eq!(short(1.5e-7), "1.50000e-7");
        assert_eq!(short(-123.456789), "-123.457");
    }
}
