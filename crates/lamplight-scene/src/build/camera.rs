//! `[camera]`: the camera kinds.
//!
//! `perspective` (the default `type`) is the look-at camera; a table with
//! `window_center` and no `type` is the lecture's raw `window` camera, as is
//! `type = "window"`.

use lamplight_core::camera::{Camera, Fov};
use lamplight_core::math::Vec3;
use lamplight_core::params::{Param, ParamResult, ParamType as T, Params};

use crate::description::Node;

/// `perspective`: the look-at camera.
pub const PERSPECTIVE_PARAMS: &[Param] = &[
    Param::new("eye", T::Point, "", "", "eye position"),
    Param::new("look_at", T::Point, "", "", "point at the image centre"),
    Param::new("up", T::Vector, "[0, 1, 0]", "", "sky direction"),
    Param::new("vfov", T::Number, "one of vfov, hfov", "degrees, 0 to 180", "full vertical field of view"),
    Param::new("hfov", T::Number, "", "degrees, 0 to 180", "full horizontal field of view"),
    Param::new("pixel_offset", T::Number, "0.5", "0 to 1", "where in a pixel its sample is (0 = corner, 0.5 = centre)"),
];

/// `window`: the lecture's eye/window camera.
pub const WINDOW_PARAMS: &[Param] = &[
    Param::new("eye", T::Point, "", "", "eye position"),
    Param::new("window_center", T::Point, "", "", "centre of the window"),
    Param::new("right", T::Vector, "", "", "from the window centre to its right edge"),
    Param::new("up", T::Vector, "", "", "from the window centre to its top edge"),
    Param::new("pixel_offset", T::Number, "0.5", "0 to 1", "as for `perspective`"),
    Param::new(
        "fit",
        T::String,
        "\"none\"",
        "",
        "`\"none\"`: vectors as written; `\"width\"`: written for a square image, `up` is divided by width/height; `\"height\"`: `right` is multiplied by it",
    ),
];

/// The camera kinds: name, summary, parameters.
pub const KINDS: &[(&str, &str, &[Param])] = &[
    ("perspective", "a pinhole camera looking from `eye` at `look_at`", PERSPECTIVE_PARAMS),
    ("window", "the lecture's camera: the window `window_center + a right + b up`, `a, b` in [-1, 1], seen from `eye`", WINDOW_PARAMS),
];

/// The camera `node` describes, for an image of aspect `aspect`.
pub fn camera(node: &Node, aspect: f64) -> ParamResult<Camera> {
    let mut p = Params::new("camera", &node.params);
    let kind = if node.kind == "perspective" && p.has("window_center") { "window" } else { node.kind.as_str() };
    let camera = match kind {
        "perspective" => {
            p.check_keys(PERSPECTIVE_PARAMS, &[])?;
            look_at(&mut p, aspect)?
        }
        "window" => {
            p.check_keys(WINDOW_PARAMS, &[])?;
            window(&mut p, aspect)?
        }
        other => {
            let names: Vec<&str> = KINDS.iter().map(|k| k.0).collect();
            return Err(lamplight_core::params::ParamError {
                loc: node.kind_loc.clone(),
                message: format!("camera: unknown camera type \"{other}\" (camera types: {})", names.join(", ")),
            });
        }
    };
    p.finish()?;
    Ok(camera)
}

fn look_at(p: &mut Params<'_>, aspect: f64) -> ParamResult<Camera> {
    let eye = p.required_vec3("eye")?;
    let target = p.required_vec3("look_at")?;
    let sky = p.vec3("up")?.unwrap_or(Vec3::Y);
    let fov = match (p.number("vfov")?, p.number("hfov")?) {
        (Some(v), None) => Fov::VerticalDeg(v),
        (None, Some(h)) => Fov::HorizontalDeg(h),
        (None, None) => return Err(p.error("needs vfov or hfov (degrees)")),
        (Some(_), Some(_)) => return Err(p.error("takes vfov or hfov, not both")),
    };
    let mut camera = Camera::look_at(eye, target, sky, fov, aspect).map_err(|e| p.error(e))?;
    if let Some(offset) = p.number("pixel_offset")? {
        if !(0.0..=1.0).contains(&offset) {
            return Err(p.key_error("pixel_offset", format!("must be between 0 and 1, got {offset}")));
        }
        camera.pixel_offset = offset;
    }
    Ok(camera)
}

fn window(p: &mut Params<'_>, aspect: f64) -> ParamResult<Camera> {
    let eye = p.required_vec3("eye")?;
    let center = p.required_vec3("window_center")?;
    let mut right = p.required_vec3("right")?;
    let mut up = p.required_vec3("up")?;
    match p.choice("fit", &["none", "width", "height"])? {
        "none" => {}
        "width" => up /= aspect,
        _ => right *= aspect,
    }
    let pixel_offset = p.number_or("pixel_offset", 0.5)?;
    if !(0.0..=1.0).contains(&pixel_offset) {
        return Err(p.key_error("pixel_offset", format!("must be between 0 and 1, got {pixel_offset}")));
    }
    if right.cross(up).length_squared() == 0.0 {
        return Err(p.error("right and up must be non-zero and not parallel"));
    }
    Ok(Camera { eye, lookat: center, right, up, pixel_offset })
}
