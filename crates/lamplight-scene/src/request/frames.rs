//! Frame sequences: which frames to render (`--frames 1-120`, `--frames 7`)
//! and where each goes (`-o out/frame_####.png`: the run of `#` is the frame
//! number, zero-padded to the run's width, as Blender's output paths).
//!
//! The frames are bounded before anything renders: frame numbers are 0 to
//! [`MAX_FRAME`] (Blender's largest), so a sequence holds at most
//! `MAX_FRAME + 1` frames.

use std::path::{Path, PathBuf};

pub use crate::description::animation::MAX_FRAME;

/// Fails unless `frame` is 0 to [`MAX_FRAME`]; the message follows the option's name.
pub fn check_frame(frame: i64) -> Result<(), String> {
    if (0..=MAX_FRAME).contains(&frame) {
        Ok(())
    } else {
        Err(format!("must be a frame number from 0 to {MAX_FRAME}, got {frame}"))
    }
}

/// The frames `start..=end`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct FrameRange {
    /// The first.
    pub start: i64,
    /// The last (included).
    pub end: i64,
}

impl FrameRange {
    /// `N` or `START-END` (whole numbers, 0 to [`MAX_FRAME`], `START <= END`).
    /// The message is to follow the option's name (`--frames must be ...`).
    pub fn parse(text: &str) -> Result<FrameRange, String> {
        let form = || format!("must be a frame number or a range START-END such as 1-120, got {text:?}");
        let number = |s: &str| -> Result<i64, String> {
            if s.is_empty() || !s.bytes().all(|b| b.is_ascii_digit()) {
                return Err(form());
            }
            match s.parse::<i64>() {
                Ok(v) if v <= MAX_FRAME => Ok(v),
                _ => Err(format!("must be frame numbers from 0 to {MAX_FRAME}, got {text:?}")),
            }
        };
        let (start, end) = match text.split_once('-') {
            Some((a, b)) => (number(a.trim())?, number(b.trim())?),
            None => {
                let v = number(text.trim())?;
                (v, v)
            }
        };
        if end < start {
            return Err(format!("{text:?} ends before it starts (expected START <= END)"));
        }
        Ok(FrameRange { start, end })
    }

    /// How many frames.
    pub fn len(&self) -> u64 {
        (self.end - self.start + 1) as u64
    }

    /// Whether it has no frames (never, for a parsed range).
    pub fn is_empty(&self) -> bool {
        self.end < self.start
    }

    /// The frames, in order.
    pub fn iter(&self) -> impl Iterator<Item = i64> {
        self.start..=self.end
    }
}

/// An output path with one run of `#` that each frame's number fills.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct OutputPattern {
    before: String,
    width: usize,
    after: String,
}

impl OutputPattern {
    /// The pattern in `path`: `None` when it has no `#`, an error (to follow
    /// `-o PATH`) when it has more than one run of them or is not UTF-8.
    pub fn parse(path: &Path) -> Result<Option<OutputPattern>, String> {
        let Some(text) = path.to_str() else {
            return if path.to_string_lossy().contains('#') { Err("is not valid UTF-8".into()) } else { Ok(None) };
        };
        let Some(first) = text.find('#') else { return Ok(None) };
        let width = text[first..].bytes().take_while(|&b| b == b'#').count();
        let after = &text[first + width..];
        if after.contains('#') {
            return Err("has more than one run of #, expected one for the frame number (frame_####.png)".into());
        }
        Ok(Some(OutputPattern { before: text[..first].to_string(), width, after: after.to_string() }))
    }

    /// The file of frame `frame`: its number zero-padded to the run's width (longer numbers are written whole).
    pub fn path(&self, frame: i64) -> PathBuf {
        PathBuf::from(format!("{}{frame:0width$}{}", self.before, self.after, width = self.width))
    }

    /// The pattern in C's printf form, as ffmpeg's `image2` reader takes it:
    /// `out/frame_%04d.png`, with a `%` of the path itself doubled.
    pub fn printf(&self) -> String {
        let escape = |s: &str| s.replace('%', "%%");
        format!("{}%0{}d{}", escape(&self.before), self.width, escape(&self.after))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ranges_and_their_messages() {
        assert_eq!(FrameRange::parse("1-120"), Ok(FrameRange { start: 1, end: 120 }));
        assert_eq!(FrameRange::parse("7"), Ok(FrameRange { start: 7, end: 7 }));
        assert_eq!(FrameRange::parse("0-0").unwrap().len(), 1);
        assert_eq!(FrameRange::parse("5-2").unwrap_err(), "\"5-2\" ends before it starts (expected START <= END)");
        assert_eq!(FrameRange::parse("a-b").unwrap_err(), "must be a frame number or a range START-END such as 1-120, got \"a-b\"");
        assert_eq!(FrameRange::parse("-3").unwrap_err(), "must be a frame number or a range START-END such as 1-120, got \"-3\"");
        assert_eq!(FrameRange::parse("1-").unwrap_err(), "must be a frame number or a range START-END such as 1-120, got \"1-\"");
        assert_eq!(
            FrameRange::parse("1-99999999999999999999").unwrap_err(),
            "must be frame numbers from 0 to 1048574, got \"1-99999999999999999999\""
        );
        assert_eq!(FrameRange::parse("1048575").unwrap_err(), "must be frame numbers from 0 to 1048574, got \"1048575\"");
        assert_eq!(check_frame(-1).unwrap_err(), "must be a frame number from 0 to 1048574, got -1");
    }

    #[test]
    fn patterns_pad_the_frame_number() {
        let p = OutputPattern::parse(Path::new("out/frame_####.png")).unwrap().unwrap();
        assert_eq!(p.path(7), PathBuf::from("out/frame_0007.png"));
        assert_eq!(p.path(123456), PathBuf::from("out/frame_123456.png"));
        let p = OutputPattern::parse(Path::new("#.exr")).unwrap().unwrap();
        assert_eq!(p.path(3), PathBuf::from("3.exr"));
        assert_eq!(OutputPattern::parse(Path::new("out.png")), Ok(None));
        let p = OutputPattern::parse(Path::new("100%/f_###.png")).unwrap().unwrap();
        assert_eq!(p.printf(), "100%%/f_%03d.png");
        assert_eq!(
            OutputPattern::parse(Path::new("a_##_##.png")).unwrap_err(),
            "has more than one run of #, expected one for the frame number (frame_####.png)"
        );
    }
}
