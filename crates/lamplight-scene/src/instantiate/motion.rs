//! Motion blur for a scene file: `[animation] shutter = [open, close]`.
//!
//! A frame is built as ever, from the static description of its own instant
//! ([`SceneDescription::at_frame`]). With an open shutter the description is
//! also taken at [`SAMPLES`] + 1 evenly spaced instants of `[frame + open,
//! frame + close]`, and each shape's world transform is read from each of
//! them, by a walk of the node tree that visits the shapes in the order the
//! build does. A shape whose transform differs between those instants becomes
//! a [`MovingInstance`] with keys `M(t) M(frame)^-1`: the map from where it
//! stands at the frame to where it stands at `t`. Every other shape is built
//! exactly as without motion blur, so still geometry costs nothing, and a
//! shutter of zero length builds the same scene as none.
//!
//! What moves: a node's `translate`, `rotate` and `scale` (and those of its
//! groups and instances). What is taken at the frame: the camera, lights,
//! other animated keys (a radius, an intensity), and emitting shapes (an area
//! light is sampled where it stands, so it is not smeared).
//!
//! Between the instants the motion is interpolated by parts
//! ([`lamplight_core::shapes::moving`]): exact for motion at constant
//! velocity, and within `1 / SAMPLES` of the shutter for the rest.

use std::sync::Arc;

use lamplight_core::math::Mat4;
use lamplight_core::params::ParamResult;
use lamplight_core::shapes::{MovingInstance, Shape};

use super::{nodes::MAX_NESTING, transform};
use crate::description::{Node, SceneDescription};
use crate::registry;

/// Segments the shutter is cut into.
pub const SAMPLES: usize = 16;

/// Each shape's world transform at each instant of the shutter.
pub(super) struct Motion {
    /// The instants, in frames from the frame.
    times: Vec<f64>,
    /// Per instant, the world transform of each shape node, in build order.
    leaves: Vec<Vec<Mat4>>,
}

/// The static descriptions of the shutter's instants, in frames from
/// `frame`; none when the shutter is closed (`open == close`).
pub(super) fn instants(desc: &SceneDescription, frame: i64) -> ParamResult<Vec<(f64, SceneDescription)>> {
    let Some(animation) = &desc.animation else { return Ok(Vec::new()) };
    let (open, close) = animation.shutter;
    if !(close > open) {
        return Ok(Vec::new());
    }
    (0..=SAMPLES)
        .map(|k| {
            let t = open + (close - open) * k as f64 / SAMPLES as f64;
            Ok((t, desc.at_frame(frame as f64 + t)?))
        })
        .collect()
}

impl Motion {
    /// Reads the shapes' transforms from each instant's description.
    pub(super) fn new(instants: &[(f64, SceneDescription)]) -> ParamResult<Option<Motion>> {
        if instants.is_empty() {
            return Ok(None);
        }
        let mut leaves = Vec::with_capacity(instants.len());
        for (_, desc) in instants {
            let mut found = Vec::new();
            for node in &desc.objects {
                walk(desc, node, Mat4::IDENTITY, 0, &mut found)?;
            }
            leaves.push(found);
        }
        Ok(Some(Motion { times: instants.iter().map(|(t, _)| *t).collect(), leaves }))
    }

    /// The keys of shape node `leaf` (in build order), standing at `frame`
    /// (its world transform at the frame): `None` when it does not move.
    pub(super) fn keys(&self, leaf: usize, frame: &Mat4) -> Option<Vec<(f64, Mat4)>> {
        let inverse = frame.inverse();
        let keys: Vec<(f64, Mat4)> = self
            .times
            .iter()
            .zip(&self.leaves)
            .map(|(&t, leaves)| (t, leaves.get(leaf).map_or(Mat4::IDENTITY, |m| *m * inverse)))
            .collect();
        let still = keys.iter().all(|(_, m)| m.abs_diff_eq(Mat4::IDENTITY, 1e-12 * (1.0 + frame.w_axis.truncate().abs().max_element())));
        (!still).then_some(keys)
    }
}

/// `shape` moved by `keys` ([`Motion::keys`]), or as it is without them.
pub(super) fn wrap(shape: Arc<dyn Shape>, keys: Option<&Vec<(f64, Mat4)>>) -> Result<Arc<dyn Shape>, lamplight_core::Error> {
    match keys {
        Some(keys) => Ok(Arc::new(MovingInstance::new(shape, keys)?)),
        None => Ok(shape),
    }
}

/// The world transform of each shape node under `n`, in the order
/// `nodes::Ctx::node` places them (one per shape or mesh node). Errors and
/// limits are the build's to report: the walk stops where the build fails.
fn walk(desc: &SceneDescription, n: &Node, parent: Mat4, depth: usize, out: &mut Vec<Mat4>) -> ParamResult<()> {
    if depth >= MAX_NESTING {
        return Ok(());
    }
    let m = parent * transform::local(&n.label, &n.transform)?;
    if lamplight_core::params::Kind::find(registry::LIGHTS, &n.kind).is_some() {
        return Ok(());
    }
    match n.kind.as_str() {
        "group" => {
            for child in n.children.iter().flatten() {
                walk(desc, child, m, depth + 1, out)?;
            }
        }
        "instance" => {
            let of = n.params.get("of").and_then(|e| match &e.item.value {
                lamplight_core::params::Value::String(s) => Some(s.as_str()),
                _ => None,
            });
            if let Some(def) = of.and_then(|of| desc.definition(of)) {
                walk(desc, &def.value, m, depth + 1, out)?;
            }
        }
        _ => out.push(m),
    }
    Ok(())
}
