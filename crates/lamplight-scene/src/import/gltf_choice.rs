//! Which animation of a glTF file plays, chosen by name or index as Blender
//! and three.js users name clips (`--animation Walk`, `--animation 2`,
//! Python `animation="Walk"`, a scene file's `[meshes.NAME] animation`), and
//! the frames of a chosen animation read from the file's JSON alone, so that
//! choosing frames does not decode meshes and images.

use std::fmt;
use std::path::Path;
use std::str::FromStr;

use super::gltf_animation::{frames_to, GLTF_FPS};
use crate::description::animation::Animation;
use crate::error::LoadError;

/// An animation of a glTF file, as a user names it.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub enum AnimationChoice {
    /// Its index in the file's `animations`.
    Index(usize),
    /// Its `name`.
    Name(String),
}

impl FromStr for AnimationChoice {
    type Err = String;

    /// Digits are an index (`2`), anything else a name (`Walk`).
    fn from_str(text: &str) -> Result<AnimationChoice, String> {
        if text.is_empty() {
            return Err("must be an animation's name or index, got an empty string".into());
        }
        match text.bytes().all(|b| b.is_ascii_digit()) {
            true => text.parse().map(AnimationChoice::Index).map_err(|_| format!("index {text} is too large")),
            false => Ok(AnimationChoice::Name(text.to_string())),
        }
    }
}

impl fmt::Display for AnimationChoice {
    /// `2`, or `"Walk"` quoted.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            AnimationChoice::Index(i) => write!(f, "{i}"),
            AnimationChoice::Name(n) => write!(f, "{n:?}"),
        }
    }
}

/// An animation as the file's JSON lists it.
#[derive(Clone, Debug, PartialEq)]
pub struct ClipSummary {
    /// Its index in `animations`.
    pub index: usize,
    /// Its `name`, if any.
    pub name: Option<String>,
}

/// `0 "Survey", 1 "Walk", 2 (unnamed)`.
pub fn listing(clips: &[ClipSummary]) -> String {
    let one = |c: &ClipSummary| match &c.name {
        Some(n) => format!("{} {n:?}", c.index),
        None => format!("{} (unnamed)", c.index),
    };
    clips.iter().map(one).collect::<Vec<_>>().join(", ")
}

/// Whether `path` names a glTF file (`.gltf`, `.glb`, any case).
pub fn is_gltf(path: &Path) -> bool {
    let ext = path.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase);
    matches!(ext.as_deref(), Some("gltf" | "glb"))
}

/// The document of the glTF file at `path`, from its JSON alone.
fn document(path: &Path) -> Result<gltf::Document, LoadError> {
    let is_glb = path.extension().and_then(|e| e.to_str()).is_some_and(|e| e.eq_ignore_ascii_case("glb"));
    let bytes = match is_glb {
        true => glb_json(path).ok_or_else(|| LoadError::file(path, "is not a GLB file (no JSON chunk)"))?,
        false => super::read_file(path)?,
    };
    let gltf::Gltf { document, .. } =
        gltf::Gltf::from_slice_without_validation(&bytes).map_err(|e| LoadError::file(path, format!("invalid glTF: {e}")))?;
    Ok(document)
}

/// The animations of the glTF file at `path`, read from its JSON alone.
pub fn file_clips(path: &Path) -> Result<Vec<ClipSummary>, LoadError> {
    let document = document(path)?;
    Ok(document.animations().map(|a| ClipSummary { index: a.index(), name: a.name().map(str::to_string) }).collect())
}

/// The index of the animation `choice` names in the glTF file at `path`;
/// `key` is how the front end spells the choice (`--animation`,
/// `animation`, `meshes.fox.animation`), for the message of a name or
/// index the file does not have.
pub fn resolve(path: &Path, choice: &AnimationChoice, key: &str) -> Result<usize, LoadError> {
    let clips = file_clips(path)?;
    if clips.is_empty() {
        return Err(LoadError::file(path, format!("{key} {choice}: the file has no animations")));
    }
    find(&clips, choice)
        .map_err(|problem| LoadError::file(path, format!("{key} {choice} {problem}: it has animations {}", listing(&clips))))
}

/// The index of the animation `choice` names among `clips`, or what is
/// wrong with the choice (`"is out of range"`, `"names no animation of the file"`).
pub fn find(clips: &[ClipSummary], choice: &AnimationChoice) -> Result<usize, &'static str> {
    match choice {
        AnimationChoice::Index(i) => (*i < clips.len()).then_some(*i).ok_or("is out of range"),
        AnimationChoice::Name(n) => {
            clips.iter().position(|c| c.name.as_deref() == Some(n.as_str())).ok_or("names no animation of the file")
        }
    }
}

/// The frames of the first animation of the glTF file at `path` ([`file_clip_frames`]).
pub fn file_frames(path: &Path) -> Option<Animation> {
    file_clip_frames(path, 0)
}

/// The frames of animation `clip` of the glTF file at `path`, read from its
/// JSON alone (the specification requires each sampler input's `max`);
/// `None` for other files, files without that animation, and files that
/// cannot be read (the render reports those).
pub fn file_clip_frames(path: &Path, clip: usize) -> Option<Animation> {
    let end = file_clip_end(path, clip)?;
    Some(Animation { start: 0, end: frames_to(end, GLTF_FPS), fps: GLTF_FPS, shutter: (0.0, 0.0), loc: Default::default() })
}

/// The time of the last key of animation `clip` of the glTF file at `path`,
/// in seconds ([`file_clip_frames`]).
pub fn file_clip_end(path: &Path, clip: usize) -> Option<f64> {
    if !is_gltf(path) {
        return None;
    }
    let document = document(path).ok()?;
    let animation = document.animations().nth(clip)?;
    let mut end: f64 = 0.0;
    for channel in animation.channels() {
        if channel.target().property() == gltf::animation::Property::MorphTargetWeights {
            continue;
        }
        let max = channel.sampler().input().max().and_then(|m| m.as_array()?.first()?.as_f64());
        match max {
            Some(m) if m.is_finite() => end = end.max(m),
            // An input without its `max`: read the whole file.
            _ => return Some(super::load(path).ok()?.animations?.clips.get(clip)?.time_span().1),
        }
    }
    Some(end)
}

/// The JSON chunk of the GLB file at `path`, read without the binary chunk
/// (a model's meshes and images, often most of the file): the 12-byte header
/// (`glTF`, version, length), then the first chunk's length and type `JSON`
/// (glTF 2.0 specification, section 4.4).
fn glb_json(path: &Path) -> Option<Vec<u8>> {
    use std::io::Read;
    let len = crate::input::check_regular(path).ok()?;
    let mut file = std::fs::File::open(path).ok()?;
    let mut head = [0u8; 20];
    file.read_exact(&mut head).ok()?;
    let chunk = u64::from(u32::from_le_bytes(head[12..16].try_into().ok()?));
    if &head[0..4] != b"glTF" || &head[16..20] != b"JSON" || chunk > len.saturating_sub(20) {
        return None;
    }
    let mut json = vec![0; chunk as usize];
    file.read_exact(&mut json).ok()?;
    Some(json)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn digits_are_an_index_and_anything_else_a_name() {
        assert_eq!("2".parse(), Ok(AnimationChoice::Index(2)));
        assert_eq!("Walk".parse(), Ok(AnimationChoice::Name("Walk".into())));
        assert_eq!("-1".parse(), Ok(AnimationChoice::Name("-1".into())));
        assert_eq!("".parse::<AnimationChoice>().unwrap_err(), "must be an animation's name or index, got an empty string");
        assert_eq!(AnimationChoice::Name("Walk".into()).to_string(), "\"Walk\"");
        let clips = [ClipSummary { index: 0, name: Some("Survey".into()) }, ClipSummary { index: 1, name: None }];
        assert_eq!(listing(&clips), "0 \"Survey\", 1 (unnamed)");
    }
}
