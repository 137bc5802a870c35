//! A glTF file named by a scene file's `[meshes]` plays its animation: the
//! glTF's time is the scene's time in seconds (`(frame - start) / fps` of
//! `[animation]`, as `seconds` keys count), and `[meshes.NAME] animation`
//! chooses the clip: a name (`"Walk"`) or an index (`2`), `true` or absent for
//! the first, `false` for the rest pose (the nodes as the file places them).
//! A scene without `[animation]` shows the glTF at its time 0, with a warning
//! naming the key to add.

use std::path::Path;

use lamplight_core::math::Mat4;
use lamplight_core::params::{ParamResult, Params, Value};

use crate::import::gltf_choice::{self, AnimationChoice, ClipSummary};
use crate::import::Imported;

/// What `[meshes.NAME] animation` says.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub(super) enum MeshClip {
    /// The first animation, if the file has any (absent, or `true`).
    First,
    /// The rest pose (`false`).
    Rest,
    /// The one named or numbered.
    Chosen(AnimationChoice),
}

/// Reads `animation` (marked as read).
pub(super) fn read(p: &mut Params<'_>) -> ParamResult<MeshClip> {
    let Some(item) = p.item("animation") else { return Ok(MeshClip::First) };
    match &item.value {
        Value::Bool(true) => Ok(MeshClip::First),
        Value::Bool(false) => Ok(MeshClip::Rest),
        Value::String(name) if !name.is_empty() => Ok(MeshClip::Chosen(AnimationChoice::Name(name.clone()))),
        Value::Integer(i) if *i >= 0 => Ok(MeshClip::Chosen(AnimationChoice::Index(*i as usize))),
        other => Err(p.key_error(
            "animation",
            format!("expected an animation's name, its index from 0, or false for the rest pose, got {}", other.describe()),
        )),
    }
}

/// A part's placement that says it is hidden at this frame (its node scaled
/// to nothing): kept, so that `part = i` names the same part at every frame.
pub(super) const HIDDEN: Mat4 = Mat4::ZERO;

/// Poses `imported` (read from `path`, named by `file` in the scene) as
/// `clip` has it at the scene's `seconds` (`None`: the scene has no
/// `[animation]`), every instance kept: one hidden at this time is placed by
/// [`HIDDEN`]. `Ok` with a warning, if any, or the error's message.
pub(super) fn pose(
    imported: &mut Imported,
    path: &Path,
    file: &str,
    clip: &MeshClip,
    seconds: Option<f64>,
) -> Result<Option<String>, String> {
    let clips: Vec<ClipSummary> = match &imported.animations {
        Some(a) => a.clips.iter().map(|c| ClipSummary { index: c.index, name: c.name.clone() }).collect(),
        None => Vec::new(),
    };
    let index = match clip {
        MeshClip::Rest => return Ok(None),
        MeshClip::First if clips.is_empty() => return Ok(None),
        MeshClip::First => 0,
        MeshClip::Chosen(choice) if clips.is_empty() => return Err(format!("animation {choice}: file \"{file}\" has no animations")),
        MeshClip::Chosen(choice) => gltf_choice::find(&clips, choice)
            .map_err(|problem| format!("animation {choice} {problem}: file \"{file}\" has animations {}", gltf_choice::listing(&clips)))?,
    };
    let visible = imported.pose_all(path, index, seconds.unwrap_or(0.0)).map_err(|e| e.message)?;
    for (placed, _) in imported.instances.iter_mut().zip(visible).filter(|(_, v)| !v) {
        placed.transform = HIDDEN;
    }
    Ok(seconds.is_none().then(|| {
        format!(
            "{}: the scene has no [animation], so the glTF animation stands at its time 0: add [animation] (frames = [START, END], fps) \
             to play it, or give the mesh `animation = false` for the rest pose",
            path.display()
        )
    }))
}
