//! `[camera]`: the camera kinds of the registry.
//!
//! `perspective` is the default `type`; a table with `window_center` and no
//! `type` is the lecture's raw `window` camera, as it always was.

use std::sync::Arc;

use lamplight_core::camera::Camera;
use lamplight_core::params::{unknown_kind, Kind, ParamError, ParamResult, Params};

use crate::description::Node;
use crate::registry;

/// The camera `node` describes (for any image size: the aspect applies when rendering).
pub fn camera(node: &Node) -> ParamResult<Arc<dyn Camera>> {
    let p = Params::new("camera", &node.params);
    let name = if node.kind == "perspective" && p.has("window_center") { "window" } else { node.kind.as_str() };
    let Some(kind) = Kind::find(registry::CAMERAS, name) else {
        let message = format!("camera: {}", unknown_kind("camera type", name, registry::CAMERAS));
        return Err(ParamError { loc: node.kind_loc.clone(), message });
    };
    p.read(kind.params, &[], kind.build)
}
