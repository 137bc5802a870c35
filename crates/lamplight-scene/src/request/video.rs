//! A frame sequence to a video file: `lamplight render --frames 1-48 -o
//! out/frame_####.png --video turn.mp4` (and `lamplight.make_video` in Python).
//!
//! The frames are encoded by **ffmpeg**, run as a program found on `PATH`
//! (Debian's `ffmpeg` package; `scripts/test.sh` installs it), rather than by
//! a crate: ffmpeg's H.264 (libx264), VP9 (libvpx) and palette GIF encoders
//! are what players expect, and no pure-Rust encoder writes H.264 or VP9.
//! Without ffmpeg the video is refused with one message and the frames stay
//! where they are ([`VideoErrorKind::MissingFfmpeg`]).
//!
//! | extension | codec | notes |
//! |---|---|---|
//! | `.mp4` | H.264 (libx264), `yuv420p`, CRF 18 | odd sizes are padded by one black row or column (4:2:0 needs even ones) |
//! | `.webm` | VP9 (libvpx-vp9), `yuv420p`, CRF 30 | the same padding |
//! | `.gif` | GIF, one 256-colour palette made from all the frames | |
//!
//! The frame rate is the scene's `[animation] fps`. ffmpeg reads the frames
//! by their numbered names (its `image2` demuxer with the printf form of the
//! pattern, [`super::frames::OutputPattern::printf`]), the first at the range's
//! start, exactly as many as the range holds; every one must exist. The video
//! is written to a temporary file beside the target and renamed over it, as
//! every image is, so a failed encode leaves no broken video.

use std::io::ErrorKind;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

use super::frames::{FrameRange, OutputPattern};

/// A video container, by the output's extension.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum VideoFormat {
    /// `.mp4`: H.264.
    Mp4,
    /// `.webm`: VP9.
    Webm,
    /// `.gif`.
    Gif,
}

impl VideoFormat {
    /// The format of `path` by its extension (any case); the error follows the path.
    pub fn from_path(path: &Path) -> Result<VideoFormat, String> {
        let ext = path.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase);
        match ext.as_deref() {
            Some("mp4") => Ok(VideoFormat::Mp4),
            Some("webm") => Ok(VideoFormat::Webm),
            Some("gif") => Ok(VideoFormat::Gif),
            _ => Err("must end in .mp4, .webm or .gif (the video's format)".into()),
        }
    }

    /// ffmpeg's muxer name.
    fn muxer(self) -> &'static str {
        match self {
            VideoFormat::Mp4 => "mp4",
            VideoFormat::Webm => "webm",
            VideoFormat::Gif => "gif",
        }
    }

    /// The encoder's arguments.
    fn codec_args(self) -> &'static [&'static str] {
        // 4:2:0 chroma halves both sides: pad odd sizes by one row or column.
        const EVEN: &str = "pad=ceil(iw/2)*2:ceil(ih/2)*2";
        match self {
            VideoFormat::Mp4 => &["-vf", EVEN, "-c:v", "libx264", "-pix_fmt", "yuv420p", "-crf", "18", "-movflags", "+faststart"],
            VideoFormat::Webm => &["-vf", EVEN, "-c:v", "libvpx-vp9", "-pix_fmt", "yuv420p", "-crf", "30", "-b:v", "0"],
            // One palette for the whole clip, so colours do not flicker between frames.
            VideoFormat::Gif => &["-vf", "split[a][b];[a]palettegen[p];[b][p]paletteuse", "-loop", "0"],
        }
    }
}

/// Why a video was not made.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct VideoError {
    /// The message, one line, naming the video (and the frames, which are kept).
    pub message: String,
    /// What kind of failure.
    pub kind: VideoErrorKind,
}

/// The kinds of [`VideoError`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum VideoErrorKind {
    /// ffmpeg was not found: the user's setup, not a failure of the run.
    MissingFfmpeg,
    /// The request: the video's extension, the frame rate, a frame not rendered.
    Request,
    /// ffmpeg ran and failed, or the video could not be written.
    Failed,
}

impl std::fmt::Display for VideoError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.message)
    }
}

impl std::error::Error for VideoError {}

/// Checks a video request before anything renders: the video's extension,
/// and frames that ffmpeg reads as pictures (`.png` or `.ppm`, not the linear
/// values of `.exr`). The message is to follow `--video PATH`.
pub fn check(video: &Path, frames: &Path) -> Result<VideoFormat, String> {
    let format = VideoFormat::from_path(video)?;
    let ext = frames.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase);
    if !matches!(ext.as_deref(), Some("png") | Some("ppm")) {
        return Err(format!(
            "needs .png or .ppm frames, got -o {} (an .exr frame holds linear values a video cannot show)",
            frames.display()
        ));
    }
    Ok(format)
}

/// Encodes the frames `range` of `pattern` at `fps` frames a second into
/// `video` (whose extension picks the format), with ffmpeg from `PATH`.
pub fn assemble(pattern: &OutputPattern, range: FrameRange, fps: f64, video: &Path) -> Result<(), VideoError> {
    let fail = |message: String| VideoError { message, kind: VideoErrorKind::Failed };
    let bad = |message: String| VideoError { message, kind: VideoErrorKind::Request };
    let format = VideoFormat::from_path(video).map_err(|e| bad(format!("{} {e}", video.display())))?;
    if !(fps.is_finite() && fps > 0.0) {
        return Err(bad(format!("cannot make {}: the frame rate must be a positive number, got {fps}", video.display())));
    }
    if let Some(missing) = range.iter().find(|&f| !pattern.path(f).is_file()) {
        return Err(bad(format!(
            "cannot make {}: frame {missing} ({}) is missing; render it first",
            video.display(),
            pattern.path(missing).display()
        )));
    }
    let dir = match video.parent() {
        Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
        _ => PathBuf::from("."),
    };
    std::fs::create_dir_all(&dir).map_err(|e| fail(format!("{}: cannot create the folder: {e}", dir.display())))?;
    // Removed when dropped, unless renamed over the target below.
    let temp = tempfile::Builder::new()
        .prefix(&format!(".{}.", video.file_name().map(|n| n.to_string_lossy()).unwrap_or_default()))
        .suffix(".tmp")
        .tempfile_in(&dir)
        .map_err(|e| fail(format!("{}: cannot write: {e}", video.display())))?;
    let mut command = Command::new("ffmpeg");
    command
        .args(["-hide_banner", "-loglevel", "error", "-nostdin", "-y"])
        .args(["-f", "image2", "-pattern_type", "sequence", "-framerate", &fps.to_string()])
        .args(["-start_number", &range.start.to_string(), "-i"])
        .arg(pattern.printf())
        .args(["-frames:v", &range.len().to_string()])
        .args(format.codec_args())
        .args(["-f", format.muxer()])
        .arg(temp.path())
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(Stdio::piped());
    let output = match command.output() {
        Ok(output) => output,
        Err(e) if e.kind() == ErrorKind::NotFound => {
            return Err(VideoError {
                message: format!(
                    "cannot make {}: ffmpeg is not on PATH (install it: apt-get install ffmpeg, brew install ffmpeg, or \
                     ffmpeg.org); the frames are kept ({} to {})",
                    video.display(),
                    pattern.path(range.start).display(),
                    pattern.path(range.end).display()
                ),
                kind: VideoErrorKind::MissingFfmpeg,
            })
        }
        Err(e) => return Err(fail(format!("cannot make {}: cannot run ffmpeg: {e}", video.display()))),
    };
    if !output.status.success() {
        let said = String::from_utf8_lossy(&output.stderr);
        let said: Vec<&str> = said.lines().map(str::trim).filter(|l| !l.is_empty()).collect();
        let tail = said[said.len().saturating_sub(3)..].join("; ");
        return Err(fail(format!("cannot make {}: ffmpeg failed ({}): {tail}", video.display(), output.status)));
    }
    temp.persist(video).map_err(|e| fail(format!("{}: cannot write: {}", video.display(), e.error)))?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn formats_by_extension_and_frames_that_a_video_can_show() {
        assert_eq!(VideoFormat::from_path(Path::new("a/turn.MP4")), Ok(VideoFormat::Mp4));
        assert_eq!(VideoFormat::from_path(Path::new("turn.webm")), Ok(VideoFormat::Webm));
        assert_eq!(VideoFormat::from_path(Path::new("turn.gif")), Ok(VideoFormat::Gif));
        assert_eq!(VideoFormat::from_path(Path::new("turn.avi")).unwrap_err(), "must end in .mp4, .webm or .gif (the video's format)");
        assert_eq!(check(Path::new("t.mp4"), Path::new("f_####.png")), Ok(VideoFormat::Mp4));
        assert_eq!(
            check(Path::new("t.mp4"), Path::new("f_####.exr")).unwrap_err(),
            "needs .png or .ppm frames, got -o f_####.exr (an .exr frame holds linear values a video cannot show)"
        );
    }

    #[test]
    fn a_missing_frame_is_named_before_ffmpeg_runs() {
        let dir = tempfile::tempdir().unwrap();
        let pattern = OutputPattern::parse(&dir.path().join("f_##.png")).unwrap().unwrap();
        std::fs::write(pattern.path(1), b"").unwrap();
        let video = dir.path().join("v.mp4");
        let err = assemble(&pattern, FrameRange { start: 1, end: 2 }, 24.0, &video).unwrap_err();
        assert_eq!(
            err.message,
            format!("cannot make {}: frame 2 ({}) is missing; render it first", video.display(), pattern.path(2).display())
        );
        assert!(err.kind == VideoErrorKind::Request && !video.exists());
    }
}
