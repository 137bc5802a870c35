//! Frame sequences for Python: the frame range and output pattern of
//! `lamplight render --frames 1-48 -o out/frame_####.png`, read by the same
//! code ([`lamplight_scene::request::frames`]), and the video of `--video`
//! ([`lamplight_scene::request::video`]), for `lamplight.dask.render_frames`
//! and `lamplight.make_video`.

use std::path::PathBuf;

use lamplight_scene::request::frames::{FrameRange, OutputPattern};
use lamplight_scene::request::video::{self, VideoErrorKind};
use pyo3::exceptions::{PyFileNotFoundError, PyRuntimeError, PyValueError};
use pyo3::prelude::*;

/// `(start, end)` of a range written as `--frames` takes it (`"1-48"`, `"7"`);
/// the `ValueError` follows `name` (`frames must be ...`).
#[pyfunction]
pub fn frame_range(text: &str, name: &str) -> PyResult<(i64, i64)> {
    let range = FrameRange::parse(text).map_err(|e| PyValueError::new_err(format!("{name} {e}")))?;
    Ok((range.start, range.end))
}

fn pattern_of(pattern: &std::path::Path, name: &str) -> PyResult<OutputPattern> {
    match OutputPattern::parse(pattern) {
        Ok(Some(p)) => Ok(p),
        Ok(None) => Err(PyValueError::new_err(format!(
            "{name}={:?} must hold a run of # for the frame number, such as frame_####.png",
            pattern.display().to_string()
        ))),
        Err(e) => Err(PyValueError::new_err(format!("{name}={:?} {e}", pattern.display().to_string()))),
    }
}

/// The file of each of `frames` under `pattern` (a path with one run of `#`,
/// as `-o` takes it); the `ValueError` names the argument `name`.
#[pyfunction]
pub fn frame_paths(pattern: PathBuf, frames: Vec<i64>, name: &str) -> PyResult<Vec<PathBuf>> {
    let pattern = pattern_of(&pattern, name)?;
    Ok(frames.into_iter().map(|f| pattern.path(f)).collect())
}

/// Checks a video request before anything renders, as `--video` is checked:
/// the video's extension and frames a video can show (`frames` is the path of
/// one of them); the `ValueError` names the video.
#[pyfunction]
pub fn check_video(video: PathBuf, frames: PathBuf) -> PyResult<()> {
    video::check(&video, &frames).map(|_| ()).map_err(|e| PyValueError::new_err(format!("video={:?} {e}", video.display().to_string())))
}

/// Encodes frames `start` to `end` of `pattern` into `video` at `fps` with
/// ffmpeg, as `--video` does: `FileNotFoundError` when ffmpeg is not on
/// `PATH` (the frames are kept), `ValueError` for a bad request or a missing
/// frame, `RuntimeError` when ffmpeg fails.
#[pyfunction]
pub fn make_video(py: Python<'_>, pattern: PathBuf, start: i64, end: i64, fps: f64, video: PathBuf) -> PyResult<()> {
    let pattern = pattern_of(&pattern, "frames")?;
    check_video(video.clone(), pattern.path(start))?;
    py.allow_threads(|| video::assemble(&pattern, FrameRange { start, end }, fps, &video)).map_err(|e| match e.kind {
        VideoErrorKind::MissingFfmpeg => PyFileNotFoundError::new_err(e.message),
        VideoErrorKind::Request => PyValueError::new_err(e.message),
        VideoErrorKind::Failed => PyRuntimeError::new_err(e.message),
    })
}
