//! glTF animations (the glTF 2.0 specification, section 3.11 "Animations"):
//! each channel of an animation becomes a [`Track`] of the scene format's
//! keyframes, so that glTF's `LINEAR` (spherical for rotations), `STEP` and
//! `CUBICSPLINE` (Hermite, tangents scaled by the key interval) are evaluated
//! by the same code as a scene file's `animate` tables
//! ([`crate::description::animation::interpolate`]).
//!
//! The importer keeps the node tree it walked ([`Animations`]), so that
//! [`Imported::pose`] can place every mesh, camera and light at a time `t`:
//! each animated node's translation, rotation and scale are its channels'
//! values at `t` (the rest values where a property has no channel), and each
//! node's world transform is its parent's times its own, as glTF defines, so
//! a parent's motion moves its children.
//!
//! Which animation plays, and when:
//!
//! | what | choice |
//! |---|---|
//! | the animation | the file's first (`animations[0]`), or the one chosen by name or index ([`super::gltf_choice`]); `lamplight info` lists them all |
//! | time of frame `f` | `f / fps` seconds, frame 0 being glTF's time 0 |
//! | frame rate | [`GLTF_FPS`] (24, Blender's and glTF exporters' usual rate) |
//! | frame range | `0` to `ceil(end * fps)`, `end` the animation's last key time (its duration, as glTF players take it) |
//!
//! Morph-target weights (`weights` channels) are reported once as a warning:
//! lamplight does not read morph targets.

use std::collections::HashMap;
use std::path::Path;

use glam::DQuat as Quat;
use gltf::accessor::{DataType, Dimensions};
use lamplight_core::math::{Mat4, Vec3};

pub use super::gltf_choice::{file_clip_frames, file_frames};
use super::{Imported, ImportedLight, Warnings};
use crate::description::animation::{interpolate, Animation, Interpolation, Shape, TimeUnit, Track};
use crate::error::LoadError;

/// The frame rate of a glTF file's animation rendered directly.
pub const GLTF_FPS: f64 = 24.0;

/// A file's animations and the node tree they move.
#[derive(Clone, Debug, PartialEq)]
pub struct Animations {
    /// The nodes as the importer walked them: a parent before its children.
    nodes: Vec<TreeNode>,
    /// The tree node of each of [`Imported::instances`], `cameras` and `lights`.
    instance_nodes: Vec<usize>,
    camera_nodes: Vec<usize>,
    light_nodes: Vec<usize>,
    /// The animations, in file order.
    pub clips: Vec<Clip>,
}

impl Animations {
    /// Whether animation `clip` moves a camera or a light of the file (a
    /// channel on its node or on one above it).
    pub fn moves_cameras_or_lights(&self, clip: usize) -> bool {
        let Some(clip) = self.clips.get(clip) else { return false };
        let moved = |mut n: usize| loop {
            if clip.channels.iter().any(|c| c.tree == n) {
                return true;
            }
            match self.nodes[n].parent {
                Some(p) => n = p,
                None => return false,
            }
        };
        self.camera_nodes.iter().chain(&self.light_nodes).any(|&n| moved(n))
    }
}

/// One node of the walked tree.
#[derive(Clone, Debug, PartialEq)]
struct TreeNode {
    /// Its parent's place in [`Animations::nodes`].
    parent: Option<usize>,
    /// Its local transform as the file gives it (what a static import uses).
    rest: Mat4,
    /// The same as translation, rotation and scale (for animated nodes).
    translation: Vec3,
    rotation: Quat,
    scale: Vec3,
}

/// One glTF animation.
#[derive(Clone, Debug, PartialEq)]
pub struct Clip {
    /// Its index in the file's `animations`.
    pub index: usize,
    /// Its `name`, if any.
    pub name: Option<String>,
    /// Its channels that move nodes of the scene.
    pub channels: Vec<Channel>,
}

/// One channel: a node's translation, rotation or scale over time (seconds).
#[derive(Clone, Debug, PartialEq)]
pub struct Channel {
    /// The glTF node it moves.
    pub node: usize,
    /// The node's `name`, if any.
    pub node_name: Option<String>,
    /// Its keys: `translate`, `rotate` (quaternions) or `scale`, in seconds.
    pub track: Track,
    /// The node's place in the walked tree.
    tree: usize,
}

impl Clip {
    /// The first and last key times over its channels, in seconds (0 and 0 without channels).
    pub fn time_span(&self) -> (f64, f64) {
        let first = self.channels.iter().map(|c| c.track.times[0]).fold(f64::INFINITY, f64::min);
        let last = self.channels.iter().map(|c| c.track.times[c.track.times.len() - 1]).fold(f64::NEG_INFINITY, f64::max);
        if self.channels.is_empty() {
            (0.0, 0.0)
        } else {
            (first, last)
        }
    }

    /// Its frames at [`GLTF_FPS`] (module doc): 0 to the frame of its last key, rounded up.
    pub fn frames(&self) -> Animation {
        Animation { start: 0, end: frames_to(self.time_span().1, GLTF_FPS), fps: GLTF_FPS, shutter: (0.0, 0.0), loc: Default::default() }
    }
}

/// The frame at or after `seconds` at `fps`; a time within a millionth of a
/// frame of a whole frame is that frame (key times are `f32`s).
pub(super) fn frames_to(seconds: f64, fps: f64) -> i64 {
    let end = (seconds.max(0.0) * fps - 1e-6).ceil().max(0.0);
    end.min(crate::description::animation::MAX_FRAME as f64) as i64
}

/// Records, while the importer walks the nodes, where each thing it placed hangs.
#[derive(Default)]
pub(super) struct TreeRecorder {
    nodes: Vec<TreeNode>,
    /// glTF node index -> place in `nodes`.
    places: HashMap<usize, usize>,
    instance_nodes: Vec<usize>,
    camera_nodes: Vec<usize>,
    light_nodes: Vec<usize>,
}

impl TreeRecorder {
    /// Adds glTF node `node` under the tree node `parent`, with local transform `rest`; its place.
    pub(super) fn add(&mut self, node: &gltf::Node, parent: Option<usize>, rest: Mat4) -> usize {
        let (t, r, s) = node.transform().decomposed();
        let place = self.nodes.len();
        self.nodes.push(TreeNode {
            parent,
            rest,
            translation: Vec3::from_array(t.map(f64::from)),
            rotation: Quat::from_array(r.map(f64::from)),
            scale: Vec3::from_array(s.map(f64::from)),
        });
        self.places.insert(node.index(), place);
        place
    }

    /// Says that what `out` gained since `before` (instances, cameras, lights) hangs from `place`.
    pub(super) fn placed(&mut self, place: usize, before: (usize, usize, usize), out: &Imported) {
        self.instance_nodes.extend(std::iter::repeat_n(place, out.instances.len() - before.0));
        self.camera_nodes.extend(std::iter::repeat_n(place, out.cameras.len() - before.1));
        self.light_nodes.extend(std::iter::repeat_n(place, out.lights.len() - before.2));
    }
}

/// Reads an accessor's components (the importer's checked reader).
pub(super) type ReadAccessor<'r> = dyn Fn(&gltf::Accessor, Dimensions, &[DataType]) -> Result<Vec<f64>, LoadError> + 'r;

/// The file's animations over the tree `tree` recorded; `None` when it has none.
pub(super) fn read(
    path: &Path,
    document: &gltf::Document,
    tree: TreeRecorder,
    values: &ReadAccessor<'_>,
    warnings: &mut Warnings,
) -> Result<Option<Animations>, LoadError> {
    if document.animations().len() == 0 {
        return Ok(None);
    }
    let mut clips = Vec::new();
    for animation in document.animations() {
        let mut channels = Vec::new();
        for channel in animation.channels() {
            let target = channel.target();
            let (key, shape) = match target.property() {
                gltf::animation::Property::Translation => ("translate", Shape::Vector),
                gltf::animation::Property::Rotation => ("rotate", Shape::Rotation),
                gltf::animation::Property::Scale => ("scale", Shape::Vector),
                gltf::animation::Property::MorphTargetWeights => {
                    warnings.once("glTF animation of morph target weights ignored: morph targets are not supported".to_string());
                    continue;
                }
            };
            // A node outside the scene read is not shown: its channel moves nothing.
            let Some(&place) = tree.places.get(&target.node().index()) else { continue };
            let track = channel_track(path, &channel.sampler(), key, shape, values)?;
            channels.push(Channel { node: target.node().index(), node_name: target.node().name().map(str::to_string), track, tree: place });
        }
        clips.push(Clip { index: animation.index(), name: animation.name().map(str::to_string), channels });
    }
    let TreeRecorder { nodes, instance_nodes, camera_nodes, light_nodes, .. } = tree;
    Ok(Some(Animations { nodes, instance_nodes, camera_nodes, light_nodes, clips }))
}

/// A sampler's keys as a [`Track`], checked: times finite and strictly
/// increasing, one value per key (three, in-tangent, value, out-tangent, for
/// `CUBICSPLINE`), every value finite.
fn channel_track(
    path: &Path,
    sampler: &gltf::animation::Sampler,
    key: &str,
    shape: Shape,
    values: &ReadAccessor<'_>,
) -> Result<Track, LoadError> {
    let sampler_at = format!("animations[{}].samplers[{}]", sampler.animation().index(), sampler.index());
    let err = |at: String, m: String| Err(LoadError::json(path, at, m));
    let times = values(&sampler.input(), Dimensions::Scalar, &[DataType::F32])?;
    if times.is_empty() {
        return err(format!("{sampler_at}.input"), "has no keys, expected at least one time".into());
    }
    for (i, w) in times.windows(2).enumerate() {
        if !(w[1] > w[0]) {
            return err(
                format!("{sampler_at}.input"),
                format!("time {} ({}) is not after time {i} ({}): times must increase", i + 1, w[1], w[0]),
            );
        }
    }
    if let Some(i) = times.iter().position(|t| !t.is_finite()) {
        return err(format!("{sampler_at}.input"), format!("time {i} is not finite"));
    }
    let output = sampler.output();
    let (dims, width) = if shape == Shape::Rotation { (Dimensions::Vec4, 4) } else { (Dimensions::Vec3, 3) };
    let raw = if shape == Shape::Rotation {
        // Rotations may be normalized integers (the specification's table of
        // accessor types for `rotation`): c / 127 (at least -1), c / 255, ...
        let ty = output.data_type();
        let scale = match ty {
            DataType::F32 => 1.0,
            DataType::I8 => 127.0,
            DataType::U8 => 255.0,
            DataType::I16 => 32767.0,
            DataType::U16 => 65535.0,
            DataType::U32 => return err(format!("accessors[{}]", output.index()), "rotation keys cannot be unsigned int".into()),
        };
        let types = [DataType::F32, DataType::I8, DataType::U8, DataType::I16, DataType::U16];
        values(&output, dims, &types)?.into_iter().map(|c| (c / scale).max(-1.0)).collect::<Vec<f64>>()
    } else {
        values(&output, dims, &[DataType::F32])?
    };
    let interpolation = match sampler.interpolation() {
        gltf::animation::Interpolation::Linear => Interpolation::Linear,
        gltf::animation::Interpolation::Step => Interpolation::Step,
        gltf::animation::Interpolation::CubicSpline => Interpolation::CubicSpline,
    };
    let per_key = if interpolation == Interpolation::CubicSpline { 3 } else { 1 };
    let items: Vec<[f64; 4]> = raw.chunks_exact(width).map(|c| std::array::from_fn(|i| c.get(i).copied().unwrap_or(0.0))).collect();
    if items.len() != times.len() * per_key {
        let what = if per_key == 3 { " (in-tangent, value and out-tangent per key)" } else { "" };
        let m = format!("has {} values for {} key times, expected {}{what}", items.len(), times.len(), times.len() * per_key);
        return err(format!("{sampler_at}.output"), m);
    }
    if let Some(i) = items.iter().position(|v| v.iter().any(|x| !x.is_finite())) {
        return err(format!("{sampler_at}.output"), format!("value {i} is not finite"));
    }
    let (values, tangents) = if per_key == 3 {
        (items.chunks_exact(3).map(|c| c[1]).collect(), items.chunks_exact(3).map(|c| (c[0], c[2])).collect())
    } else {
        (items, Vec::new())
    };
    if shape == Shape::Rotation {
        if let Some(i) = values.iter().position(|q: &[f64; 4]| q.iter().map(|x| x * x).sum::<f64>() == 0.0) {
            return err(format!("{sampler_at}.output"), format!("rotation {i} is the zero quaternion, expected a unit quaternion"));
        }
    }
    // Unit quaternions, as the specification requires of rotation keys (an
    // exporter's rounding is taken out, so that a key's rotation is exact).
    let values = if shape == Shape::Rotation { values.into_iter().map(interpolate::normalized).collect() } else { values };
    Ok(Track::new(key, TimeUnit::Seconds, shape, interpolation, times, values, tangents))
}

impl Imported {
    /// Places the file's meshes, cameras and lights as animation `clip` (an
    /// index into [`Animations::clips`]) has them at `seconds`: see the module
    /// doc. A file without animations, or a `clip` it does not have, stays as read.
    /// A mesh whose node is scaled to nothing (an animation hiding it) is left out.
    pub fn pose(&mut self, path: &Path, clip: usize, seconds: f64) -> Result<(), LoadError> {
        let visible = self.pose_all(path, clip, seconds)?;
        let mut keep = visible.into_iter();
        self.instances.retain(|_| keep.next().unwrap_or(true));
        Ok(())
    }

    /// [`Imported::pose`] keeping every instance: whether each is visible (not
    /// scaled to nothing), for a scene file's `part = i` to keep its meaning.
    pub fn pose_all(&mut self, path: &Path, clip: usize, seconds: f64) -> Result<Vec<bool>, LoadError> {
        let all = vec![true; self.instances.len()];
        let Some(animations) = &self.animations else { return Ok(all) };
        let Some(clip) = animations.clips.get(clip) else { return Ok(all) };
        let mut locals: Vec<Option<(Vec3, Quat, Vec3)>> = vec![None; animations.nodes.len()];
        for channel in &clip.channels {
            let node = &animations.nodes[channel.tree];
            let trs = locals[channel.tree].get_or_insert((node.translation, node.rotation, node.scale));
            let v = channel.track.value(seconds);
            match channel.track.key.as_str() {
                "translate" => trs.0 = Vec3::new(v[0], v[1], v[2]),
                "rotate" => trs.1 = Quat::from_array(v),
                _ => trs.2 = Vec3::new(v[0], v[1], v[2]),
            }
        }
        // Parents come before their children.
        let mut world: Vec<Mat4> = Vec::with_capacity(animations.nodes.len());
        for (i, node) in animations.nodes.iter().enumerate() {
            let local = match locals[i] {
                Some((t, r, s)) => Mat4::from_scale_rotation_translation(s, r, t),
                None => node.rest,
            };
            let m = node.parent.map_or(local, |p| world[p] * local);
            if !m.is_finite() {
                return Err(LoadError::file(path, format!("the animation at {seconds} s moves a node to a transform that is not finite")));
            }
            world.push(m);
        }
        // Instance::new's test for a singular transform (a zero scale).
        let visible = |m: &Mat4| {
            let scale = m.x_axis.truncate().length().max(m.y_axis.truncate().length()).max(m.z_axis.truncate().length());
            m.determinant().abs() > 1e-12 * scale.powi(3)
        };
        let visible: Vec<bool> = animations.instance_nodes.iter().map(|&n| visible(&world[n])).collect();
        for (placed, &n) in self.instances.iter_mut().zip(&animations.instance_nodes) {
            placed.transform = world[n];
        }
        for (camera, &n) in self.cameras.iter_mut().zip(&animations.camera_nodes) {
            let m = world[n];
            let eye = m.transform_point3(Vec3::ZERO);
            (camera.eye, camera.target, camera.up) = (eye, eye + m.transform_vector3(-Vec3::Z), m.transform_vector3(Vec3::Y));
        }
        for (light, &n) in self.lights.iter_mut().zip(&animations.light_nodes) {
            let m = world[n];
            let (origin, forward) = (m.transform_point3(Vec3::ZERO), m.transform_vector3(-Vec3::Z));
            match light {
                ImportedLight::Point { position, .. } => *position = origin,
                ImportedLight::Directional { direction, .. } => *direction = forward,
                ImportedLight::Spot { position, direction, .. } => (*position, *direction) = (origin, forward),
            }
        }
        Ok(visible)
    }

    /// [`Imported::pose`] at frame `frame` of the first animation at [`GLTF_FPS`] (module doc).
    pub fn pose_frame(&mut self, path: &Path, frame: i64) -> Result<(), LoadError> {
        self.pose(path, 0, frame as f64 / GLTF_FPS)
    }

    /// [`Imported::pose_frame`] for animation `clip` (an index into [`Animations::clips`]).
    pub fn pose_clip_frame(&mut self, path: &Path, clip: usize, frame: i64) -> Result<(), LoadError> {
        self.pose(path, clip, frame as f64 / GLTF_FPS)
    }

    /// The frames of the animation [`Imported::pose_frame`] plays, if the file has one.
    pub fn frames(&self) -> Option<Animation> {
        self.clip_frames(0)
    }

    /// The frames of animation `clip`, if the file has it.
    pub fn clip_frames(&self, clip: usize) -> Option<Animation> {
        self.animations.as_ref()?.clips.get(clip).map(Clip::frames)
    }

    /// The note a file with several animations gets when none was chosen.
    pub fn several_animations_note(&self) -> Option<String> {
        let n = self.animations.as_ref()?.clips.len();
        (n > 1).then(|| {
            format!("glTF file has {n} animations: the first plays unless --animation (Python animation=) chooses another; lamplight info lists them")
        })
    }
}
