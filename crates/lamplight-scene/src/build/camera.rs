//! `[camera]`: the camera kinds of the registry.
//!
//! `perspective` is the default `type`; a table with `window_center` and no
//! `type` is the lecture's raw `window` camera, as it always was.

use std::sync::Arc;

use lamplight_core::camera::Camera;
use lamplight_core::params::{ParamError, ParamResult, Params};

use crate::description::Node;
use crate::registry;

/// The camera `node` describes (for any image size: the aspect applies when rendering).
pub fn camera(node: &Node) -> ParamResult<Arc<dyn Camera>> {
    let mut p = Params::new("camera", &node.params);
    let name = if node.kind == "perspective" && p.has("window_center") { "window" } else { node.kind.as_str() };
    let Some(kind) = registry::camera(name) else {
        let names: Vec<&str> = registry::CAMERAS.iter().map(|k| k.name).collect();
        let hint =
            lamplight_core::params::suggestion(name, names.iter().copied()).map(|s| format!("did you mean '{s}'? ")).unwrap_or_default();
        return Err(ParamError {
            loc: node.kind_loc.clone(),
            message: format!("camera: unknown camera type \"{name}\" ({hint}camera types: {})", names.join(", ")),
        });
    };
    p.check_keys(kind.params, &[])?;
    let camera = (kind.build)(&mut p)?;
    p.finish()?;
    Ok(camera)
}
