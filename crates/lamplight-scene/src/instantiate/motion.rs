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
//! groups and instances), and a `[meshes]` glTF file's parts as its own
//! animation places them at each instant ([`pose_parts`]). What is taken at
//! the frame: the camera, lights, other animated keys (a radius, an
//! intensity), emitting shapes (an area light is sampled where it stands, so
//! it is not smeared) and unbounded shapes (a plane has no box to sweep).
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
    /// The scene's frame rate (glTF meshes' animations count seconds).
    fps: f64,
    /// Per instant, the world transform of each shape node, in build order.
    leaves: Vec<Vec<Mat4>>,
}

/// The static descriptions of the shutter's instants (in frames from the
/// frame), and the scene's frame rate.
pub(super) struct Instants {
    fps: f64,
    list: Vec<(f64, SceneDescription)>,
}

impl Instants {
    /// A closed shutter: nothing moves.
    pub(super) const NONE: Instants = Instants { fps: 24.0, list: Vec::new() };
}

/// The shutter's instants around `frame`; none when the shutter is closed
/// (`open == close`).
pub(super) fn instants(desc: &SceneDescription, frame: i64) -> ParamResult<Instants> {
    let Some(animation) = &desc.animation else { return Ok(Instants::NONE) };
    let (open, close) = animation.shutter;
    if !(close > open) {
        return Ok(Instants::NONE);
    }
    let list = (0..=SAMPLES)
        .map(|k| {
            let t = open + (close - open) * k as f64 / SAMPLES as f64;
            Ok((t, desc.at_frame(frame as f64 + t)?))
        })
        .collect::<ParamResult<_>>()?;
    Ok(Instants { fps: animation.fps, list })
}

impl Motion {
    /// Reads the shapes' transforms from each instant's description.
    pub(super) fn new(instants: &Instants) -> ParamResult<Option<Motion>> {
        let (fps, instants) = (instants.fps, &instants.list);
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
        Ok(Some(Motion { times: instants.iter().map(|(t, _)| *t).collect(), fps, leaves }))
    }

    /// The scene's times in seconds at the instants, for a glTF mesh's own
    /// animation that stands at `seconds` at the frame.
    pub(super) fn seconds(&self, seconds: f64) -> impl Iterator<Item = f64> + '_ {
        self.times.iter().map(move |t| seconds + t / self.fps)
    }

    /// The keys of shape node `leaf` (in build order), standing at `frame`
    /// (its world transform at the frame), of its part placed by `placement`
    /// in the node, which a glTF mesh's own animation moves to `placements`
    /// at the instants (`None`: it keeps `placement`): `None` when the part
    /// does not move, or when its animation hides it at some instant (it
    /// then stands as at the frame).
    pub(super) fn keys(&self, leaf: usize, frame: &Mat4, placement: &Mat4, placements: Option<&[Mat4]>) -> Option<Vec<(f64, Mat4)>> {
        let hidden = |m: &Mat4| *m == super::mesh_animation::HIDDEN;
        if hidden(placement) || placements.is_some_and(|p| p.iter().any(hidden) || p.len() != self.times.len()) {
            return None;
        }
        let world = *frame * *placement;
        let inverse = world.inverse();
        let keys: Vec<(f64, Mat4)> = (0..self.times.len())
            .map(|k| {
                let node = self.leaves[k].get(leaf).copied().unwrap_or(*frame);
                let part = placements.map_or(*placement, |p| p[k]);
                (self.times[k], node * part * inverse)
            })
            .collect();
        let still = keys.iter().all(|(_, m)| m.abs_diff_eq(Mat4::IDENTITY, 1e-12 * (1.0 + world.w_axis.truncate().abs().max_element())));
        (!still).then_some(keys)
    }
}

/// Each part's placement at the instants of `motion`, where the glTF file
/// `base` (read from `path`, named by `file`) plays `clip`, standing at the
/// scene's `seconds` at the frame: `parts` (its instances, in order) whose
/// animation moves them get their placements (`Part`'s last field).
pub(super) fn pose_parts(
    motion: &Motion,
    seconds: f64,
    base: &crate::import::Imported,
    parts: &mut [super::nodes::Part],
    path: &std::path::Path,
    file: &str,
    clip: &super::mesh_animation::MeshClip,
) -> Result<(), String> {
    if base.animations.is_none() || *clip == super::mesh_animation::MeshClip::Rest {
        return Ok(());
    }
    let mut columns: Vec<Vec<Mat4>> = vec![Vec::new(); parts.len()];
    for at in motion.seconds(seconds) {
        // The node tree alone is posed: no mesh or image is copied.
        let mut posed = crate::import::Imported {
            meshes: Vec::new(),
            instances: base.instances.clone(),
            cameras: Vec::new(),
            lights: Vec::new(),
            warnings: Vec::new(),
            images: Vec::new(),
            animations: base.animations.clone(),
        };
        super::mesh_animation::pose(&mut posed, path, file, clip, Some(at))?;
        for (column, placed) in columns.iter_mut().zip(&posed.instances) {
            column.push(placed.transform);
        }
    }
    for (part, column) in parts.iter_mut().zip(columns) {
        if column.iter().any(|m| *m != part.1) {
            part.3 = Some(column.into());
        }
    }
    Ok(())
}

/// `shape` moved by `keys` ([`Motion::keys`]), or as it is without them
/// or when it is unbounded (an infinite plane stands as at the frame).
pub(super) fn wrap(shape: Arc<dyn Shape>, keys: Option<&Vec<(f64, Mat4)>>) -> Result<Arc<dyn Shape>, lamplight_core::Error> {
    let bounds = shape.bounds();
    match keys {
        Some(keys) if bounds.is_finite() && !bounds.is_empty() => Ok(Arc::new(MovingInstance::new(shape, keys)?)),
        _ => Ok(shape),
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
