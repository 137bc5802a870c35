//! `lamplight render SCENE --frames 1-120 -o out/frame_####.png`: a frame
//! sequence, each frame built from the scene's description at that frame and
//! written atomically to its own file. Frames whose file exists are skipped
//! (said once), so an interrupted sequence resumes where it stopped, unless
//! `--overwrite`.
//!
//! Which frames: `--frames N` or `--frames START-END`, else the scene's
//! `[animation] frames` when `-o` holds a run of `#`. A scene without
//! `[animation]` is the same at every frame, as Blender and POV-Ray render it:
//! it is rendered once and that image written to each frame's file.
//!
//! `--video out.mp4` then encodes the frames with ffmpeg
//! ([`lamplight_scene::request::video`]); frames skipped because they exist
//! are encoded too, so a rerun with ffmpeg installed only makes the video.

use std::path::{Path, PathBuf};

use lamplight_scene::request::frames::{FrameRange, OutputPattern};
use lamplight_scene::request::video;
use lamplight_scene::request::SceneRequest;

use crate::args::{RenderJob, UsageError};

/// A checked frame sequence.
#[derive(Clone, Debug)]
pub struct Sequence {
    /// The frames.
    pub range: FrameRange,
    /// Where each goes; `None` for one frame written to `-o` as given.
    pub pattern: Option<OutputPattern>,
    /// Render frames whose file exists too.
    pub overwrite: bool,
    /// The video to encode the frames into (`--video`), and its frame rate.
    pub video: Option<(PathBuf, f64)>,
}

impl Sequence {
    /// The file of `frame`.
    pub fn path(&self, frame: i64, output: &Path) -> PathBuf {
        self.pattern.as_ref().map_or_else(|| output.to_path_buf(), |p| p.path(frame))
    }
}

/// The sequence `--frames` (`frames`), `-o` (`output`, `None` when not given)
/// and `--overwrite` ask of `scene`, `None` for a single image; and the
/// output path (a pattern by default for a sequence: `SCENE_####.png`).
/// `video` (`--video`) needs a sequence of numbered `.png` or `.ppm` frames.
pub fn sequence(
    scene: &SceneRequest,
    frames: Option<&str>,
    output: Option<PathBuf>,
    overwrite: bool,
    video: Option<PathBuf>,
) -> Result<(Option<Sequence>, PathBuf), UsageError> {
    let (sequence, output) = frame_sequence(scene, frames, output, overwrite)?;
    let Some(path) = video else { return Ok((sequence, output)) };
    let Some(mut sequence) = sequence.filter(|s| s.pattern.is_some()) else {
        return Err(UsageError(format!(
            "--video {} encodes a frame sequence: give -o a run of # for the frame number (frame_####.png), with --frames \
             or the scene's [animation]",
            path.display()
        )));
    };
    video::check(&path, &output).map_err(|e| UsageError(format!("--video {} {e}", path.display())))?;
    let fps = scene.animation().map_or(24.0, |a| a.fps);
    sequence.video = Some((path, fps));
    Ok((Some(sequence), output))
}

fn frame_sequence(
    scene: &SceneRequest,
    frames: Option<&str>,
    output: Option<PathBuf>,
    overwrite: bool,
) -> Result<(Option<Sequence>, PathBuf), UsageError> {
    let usage = |m: String| UsageError(m);
    let pattern = match &output {
        Some(path) => OutputPattern::parse(path).map_err(|e| usage(format!("-o {} {e}", path.display())))?,
        None => None,
    };
    let range = match (frames, scene.animation(), &pattern) {
        (Some(text), _, _) => FrameRange::parse(text).map_err(|e| usage(format!("--frames {e}")))?,
        (None, Some(a), Some(_)) => FrameRange { start: a.start, end: a.end },
        (None, None, Some(_)) => {
            return Err(usage(format!(
                "-o {} numbers frames (#), but '{}' has no [animation] to give them; say which with --frames",
                output.as_deref().unwrap_or(Path::new("")).display(),
                scene.name
            )))
        }
        (None, _, None) if overwrite => {
            return Err(usage("--overwrite applies to frame sequences (--frames, or -o with a run of # in an animated scene)".into()))
        }
        (None, _, None) => return Ok((None, output.unwrap_or_else(|| PathBuf::from(format!("{}.png", scene.name))))),
    };
    let (pattern, output) = match (pattern, output) {
        (Some(p), Some(o)) => (Some(p), o),
        (None, Some(o)) if range.len() == 1 => (None, o),
        (None, Some(o)) => {
            return Err(usage(format!(
                "--frames {}-{} renders {} frames: -o {} must hold a run of # for the frame number, such as frame_####.png",
                range.start,
                range.end,
                range.len(),
                o.display()
            )))
        }
        (None, None) => {
            let o = PathBuf::from(format!("{}_####.png", scene.name));
            (OutputPattern::parse(&o).map_err(usage)?, o)
        }
        (Some(_), None) => unreachable!("a pattern comes from -o"),
    };
    Ok((Some(Sequence { range, pattern, overwrite, video: None }), output))
}

/// Renders the frames of `render.sequence` that are not written yet.
pub fn render_sequence(render: &RenderJob) -> anyhow::Result<()> {
    let sequence = render.sequence.as_ref().expect("a sequence");
    let todo: Vec<i64> = sequence.range.iter().filter(|&f| sequence.overwrite || !sequence.path(f, &render.output).exists()).collect();
    let skipped = sequence.range.len() - todo.len() as u64;
    if skipped > 0 {
        eprintln!(
            "lamplight: skipping {skipped} of {} frames whose files exist (such as {}); --overwrite renders them again",
            sequence.range.len(),
            sequence.path(sequence.range.iter().find(|f| !todo.contains(f)).unwrap_or(sequence.range.start), &render.output).display()
        );
    }
    render_frames(render, sequence, &todo)?;
    let (Some((path, fps)), Some(pattern)) = (&sequence.video, &sequence.pattern) else { return Ok(()) };
    match video::assemble(pattern, sequence.range, *fps, path) {
        Ok(()) => {
            if !render.quiet {
                eprintln!("{} frames -> {}", sequence.range.len(), path.display());
            }
            Ok(())
        }
        Err(e) if e.kind == video::VideoErrorKind::Failed => Err(anyhow::anyhow!(e.message)),
        // ffmpeg not installed is the user's setup, as bad input is (exit code 2).
        Err(e) => Err(UsageError(e.message).into()),
    }
}

/// Renders the frames `todo` of `sequence`, each to its file.
fn render_frames(render: &RenderJob, sequence: &Sequence, todo: &[i64]) -> anyhow::Result<()> {
    let Some(&first) = todo.first() else { return Ok(()) };
    let first_path = sequence.path(first, &render.output);
    if let Some(dir) = first_path.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir).map_err(|e| UsageError(format!("{}: cannot create the folder: {e}", dir.display())))?;
    }
    // Fail before a long render, not after it, when the files cannot be written.
    lamplight_scene::image_io::check_writable(&first_path)?;
    let animated = render.scene.animation().is_some();
    for &frame in todo {
        let path = sequence.path(frame, &render.output);
        if !animated && frame != first {
            // The same scene at every frame: the same bytes.
            let bytes = std::fs::read(&first_path)?;
            lamplight_scene::atomic::write(&path, &bytes).map_err(|e| anyhow::anyhow!("{}: cannot write: {e}", path.display()))?;
            continue;
        }
        let job = lamplight_scene::request::Job { frame: Some(frame), ..render.job.clone() };
        crate::render_to(render, &job, &path, Some(frame))?;
    }
    Ok(())
}
