//! Time in the scene: `[animation]` (the frame range and rate) and the
//! `animate` tables of nodes and the camera, which keyframe their keys.
//!
//! Animation lives in the description: [`SceneDescription::at_frame`] turns a
//! description and a time into the static description of that frame, each
//! animated key replaced by its value then, which builds as any static scene
//! does. So a frame is the same scene, and renders to the same bytes, whether
//! it is rendered alone or within a sequence.
//!
//! ```toml
//! [animation]
//! frames = [1, 48]     # the range rendered by default, inclusive
//! fps = 24
//!
//! [[objects]]
//! type = "group"
//! animate.rotate = { frames = [1, 17, 33, 49], values = [[0, 0, 0], [0, 120, 0], [0, 240, 0], [0, 360, 0]] }
//! ```
//!
//! Any key of a node or the camera whose value is a number or `[x, y, z]` can
//! be animated (`translate`, `rotate`, `scale`; a camera's `eye`, `look_at`,
//! `vfov`; a light's `intensity`; a sphere's `radius`); `rotate` keys take any
//! `rotate` form and interpolate as quaternions. The interpolation modes are
//! glTF's ([`interpolate`]).

use lamplight_core::params::{Entry, Loc, Param, ParamError, ParamResult, ParamType as T, Params, Table};

use super::{Node, SceneDescription};

pub mod interpolate;
pub mod track;

pub use interpolate::Interpolation;
pub use track::{Shape, TimeUnit, Track};

/// The largest frame number (Blender's `MAXFRAME`).
pub const MAX_FRAME: i64 = 1_048_574;
/// The largest frame rate.
pub const MAX_FPS: f64 = 1000.0;

/// The keys of `[animation]`.
pub const ANIMATION_PARAMS: &[Param] = &[
    Param::new(
        "frames",
        T::Array,
        "",
        "[start, end], whole numbers, 0 to 1048574",
        "the frames of the animation, both included: what `--frames` renders by default, and where `seconds` count from (second 0 is frame `start`)",
    ),
    Param::new("fps", T::Number, "24", "frames per second, > 0, at most 1000", "frame rate: converts keys given in `seconds` to frames"),
    Param::new(
        "shutter",
        T::Array,
        "[0, 0]",
        "[open, close] in frames from the frame, open <= close, each within ±1000",
        "motion blur: each camera sample takes an instant in `[frame + open, frame + close]` and sees moving objects there (`[0, 0]`: none; Blender's default 0.5 is `[-0.25, 0.25]`)",
    ),
];

/// The largest `|open|` or `|close|` of a shutter, in frames.
pub const MAX_SHUTTER: f64 = 1000.0;

/// The keys of one `animate.KEY` table.
pub const TRACK_PARAMS: &[Param] = &[
    Param::new("frames", T::Array, "one of frames, seconds", "frame numbers, increasing", "the keys' times in frames (fractions allowed)"),
    Param::new("seconds", T::Array, "one of frames, seconds", "seconds, increasing", "the keys' times in seconds from the first frame"),
    Param::new(
        "values",
        T::Array,
        "",
        "one per key",
        "the key's value at each time, as the key itself takes it (a number or `[x, y, z]`; any `rotate` form)",
    ),
    Param::new(
        "interpolation",
        T::String,
        "\"linear\"",
        "",
        "`\"linear\"` (rotations: spherical, the shortest way), `\"step\"` (each value holds until the next key) or `\"cubicspline\"` (glTF's cubic Hermite spline)",
    ),
    Param::new(
        "in_tangents",
        T::Array,
        "zeros",
        "per frame or per second, as the times",
        "`\"cubicspline\"`: each key's incoming slope (rotations: `[x, y, z, w]`, a quaternion's rate)",
    ),
    Param::new("out_tangents", T::Array, "zeros", "per frame or per second, as the times", "`\"cubicspline\"`: each key's outgoing slope"),
];

/// `[animation]`: the frame range and rate.
#[derive(Clone, Debug, PartialEq)]
pub struct Animation {
    /// The first frame.
    pub start: i64,
    /// The last frame (included).
    pub end: i64,
    /// Frames per second.
    pub fps: f64,
    /// The shutter `(open, close)` in frames from the frame (`(0, 0)`: no
    /// motion blur).
    pub shutter: (f64, f64),
    /// Where the table is.
    pub loc: Loc,
}

impl Animation {
    /// Reads `[animation]`.
    pub fn read(table: &Table) -> ParamResult<Animation> {
        Params::new("animation", table).read(ANIMATION_PARAMS, &[], |p| {
            let item = p.item("frames").ok_or_else(|| p.error("needs `frames` ([start, end])"))?;
            let whole: Option<Vec<i64>> = match &item.value {
                lamplight_core::params::Value::Array(items) if items.len() == 2 => items
                    .iter()
                    .map(|i| match i.value {
                        lamplight_core::params::Value::Integer(v) => Some(v),
                        _ => None,
                    })
                    .collect(),
                _ => None,
            };
            let Some(v) = whole else {
                return Err(p.key_error("frames", format!("expected [start, end], two whole numbers, got {}", item.value.describe())));
            };
            let (start, end) = (v[0], v[1]);
            if !(0..=MAX_FRAME).contains(&start) || !(start..=MAX_FRAME).contains(&end) {
                return Err(p.key_error("frames", format!("[{start}, {end}] must have 0 <= start <= end <= {MAX_FRAME}")));
            }
            let fps = p.number_or("fps", 24.0)?;
            if !(fps > 0.0 && fps <= MAX_FPS) {
                return Err(p.key_error("fps", format!("must be a positive number of frames per second, at most {MAX_FPS}, got {fps}")));
            }
            let shutter = match p.pair("shutter")? {
                None => (0.0, 0.0),
                Some([open, close]) if open <= close && open.abs() <= MAX_SHUTTER && close.abs() <= MAX_SHUTTER => (open, close),
                Some([open, close]) => {
                    return Err(
                        p.key_error("shutter", format!("[{open}, {close}] must have open <= close, both within ±{MAX_SHUTTER} frames"))
                    )
                }
            };
            Ok(Animation { start, end, fps, shutter, loc: table.loc.clone() })
        })
    }

    /// How many frames the range holds.
    pub fn frame_count(&self) -> u64 {
        (self.end - self.start + 1) as u64
    }

    /// The time of frame `frame` in `unit`: the frame itself, or seconds from `start`.
    pub fn time(&self, frame: f64, unit: TimeUnit) -> f64 {
        match unit {
            TimeUnit::Frames => frame,
            TimeUnit::Seconds => (frame - self.start as f64) / self.fps,
        }
    }
}

/// An animated node or camera: where it is (`objects[0]`, `camera`,
/// `definitions.lamp.children[1]`), its label, and its tracks.
#[derive(Clone, Debug, PartialEq)]
pub struct Animated {
    /// Its place in the description.
    pub path: String,
    /// Its label (the kind, or `camera`).
    pub label: String,
    /// Its `name`, if it has one.
    pub name: Option<String>,
    /// What is keyframed.
    pub tracks: Vec<Track>,
}

impl SceneDescription {
    /// The static description of frame `frame` (a frame number, fractions
    /// allowed): each `animate` table removed and the keys it animates set to
    /// their values then. A description without `[animation]` is returned as it is.
    pub fn at_frame(&self, frame: f64) -> ParamResult<SceneDescription> {
        let mut out = self.clone();
        let Some(animation) = out.animation.take() else { return Ok(out) };
        let mut resolve = |node: &mut Node, tree: bool| -> ParamResult<()> {
            for track in tracks(node)? {
                let item = track.at(animation.time(frame, track.unit));
                let entry = Entry { key: track.key.clone(), key_loc: track.key_loc.clone(), item };
                if tree && super::TRANSFORM_KEYS.contains(&track.key.as_str()) {
                    node.transform.entries.push(entry);
                } else {
                    node.params.entries.push(entry);
                }
            }
            node.params.remove("animate");
            Ok(())
        };
        if let Some(camera) = &mut out.camera {
            resolve(camera, false)?;
        }
        for node in out.objects.iter_mut().chain(out.definitions.iter_mut().map(|d| &mut d.value)) {
            visit_mut(node, &mut resolve)?;
        }
        Ok(out)
    }

    /// Every animated node, in file order (camera, objects, definitions).
    pub fn animated(&self) -> ParamResult<Vec<Animated>> {
        let mut found = Vec::new();
        let mut add = |path: String, node: &Node| -> ParamResult<()> {
            let tracks = tracks(node)?;
            if !tracks.is_empty() {
                found.push(Animated { path, label: node.label.clone(), name: node.name.clone(), tracks });
            }
            Ok(())
        };
        if let Some(camera) = &self.camera {
            add("camera".into(), camera)?;
        }
        for (i, node) in self.objects.iter().enumerate() {
            visit(node, format!("objects[{i}]"), &mut add)?;
        }
        for d in &self.definitions {
            visit(&d.value, format!("definitions.{}", d.name), &mut add)?;
        }
        Ok(found)
    }

    /// Checks the animation when the description is read: every `animate`
    /// table parses, names no key also given a fixed value, and has an
    /// `[animation]` to count its time in.
    pub(crate) fn check_animation(&self) -> ParamResult<()> {
        let animated = self.animated()?;
        if let (None, Some(first)) = (&self.animation, animated.first()) {
            return Err(ParamError {
                loc: first.tracks[0].key_loc.clone(),
                message: format!("{}: animate: needs the scene's [animation] table (frames = [start, end])", first.label),
            });
        }
        Ok(())
    }
}

/// The tracks of `node`'s `animate` table (none without one), checked
/// against the keys the node also gives a fixed value.
fn tracks(node: &Node) -> ParamResult<Vec<Track>> {
    let Some(entry) = node.params.get("animate") else { return Ok(Vec::new()) };
    let label = &node.label;
    let lamplight_core::params::Value::Table(table) = &entry.item.value else {
        return Err(ParamError {
            loc: entry.item.loc.clone(),
            message: format!(
                "{label}: animate: expected a table of animated keys, such as animate.translate = {{ frames = [...], values = [...] }}, got {}",
                entry.item.value.describe()
            ),
        });
    };
    let mut out = Vec::with_capacity(table.entries.len());
    for e in &table.entries {
        if node.transform.get(&e.key).is_some() || node.params.get(&e.key).is_some() {
            return Err(ParamError {
                loc: e.key_loc.clone(),
                message: format!("{label}: animate.{0}: '{0}' is also given a fixed value; give it in one place", e.key),
            });
        }
        if e.key == "matrix" {
            return Err(ParamError {
                loc: e.key_loc.clone(),
                message: format!("{label}: animate.matrix: a matrix cannot be animated; animate translate, rotate and scale"),
            });
        }
        out.push(Track::read(label, e)?);
    }
    Ok(out)
}

fn visit(node: &Node, path: String, f: &mut impl FnMut(String, &Node) -> ParamResult<()>) -> ParamResult<()> {
    f(path.clone(), node)?;
    for (i, child) in node.children.iter().flatten().enumerate() {
        visit(child, format!("{path}.children[{i}]"), f)?;
    }
    Ok(())
}

fn visit_mut(node: &mut Node, f: &mut impl FnMut(&mut Node, bool) -> ParamResult<()>) -> ParamResult<()> {
    f(node, true)?;
    for child in node.children.iter_mut().flatten() {
        visit_mut(child, f)?;
    }
    Ok(())
}

#[cfg(test)]
mod tests;
