//! The limits every front end enforces, in one place: each size and count that
//! comes from input is bounded here (or, for the renderer's own limits, read here
//! from `lamplight-core`), and each whole-number setting's range carries the one
//! message that the CLI, Python and scene requests give for a value outside it.

use super::Naming;

/// Deepest ray depth. Whitted tracing may spawn a reflected and a refracted
/// ray at every hit, so a camera ray's work grows as `2^depth`: 64 levels
/// already allow more rays than any render could trace.
pub const MAX_DEPTH: u32 = crate::instantiate::MAX_DEPTH_LIMIT;
/// Most pixels in an image (`2^28`, e.g. 16384x16384; the renderer's).
pub const MAX_PIXELS: u64 = lamplight_core::MAX_PIXELS;
/// Most samples per pixel.
pub const MAX_SPP: u32 = crate::instantiate::MAX_SPP;
/// Most worker threads: far above any machine's cores; more would only cost
/// memory, and huge counts make the thread pool fail (the batch-ray API's
/// limit too, so `render` and `raycast` agree).
pub const MAX_THREADS: usize = lamplight_core::batch::MAX_THREADS;
/// Longest time limit, seconds (about 31 years: beyond it is a typo).
pub const MAX_TIME_LIMIT: f64 = 1e9;
/// Most ray-march steps an implicit surface may take per ray (its `max_steps`).
pub const MAX_MARCH_STEPS: i64 = crate::instantiate::implicit::MAX_STEPS;

/// A whole-number setting's range, and the one message every front end gives
/// for a value outside it (the CLI after parsing, Python even for a value too
/// large for the setting's type, the request layer for the rest).
#[derive(Clone, Copy, Debug)]
pub struct Range {
    /// The setting's keyword (`max_depth`), spelled per front end by [`Naming`].
    pub key: &'static str,
    /// Smallest value allowed.
    pub min: u64,
    /// Largest value allowed.
    pub max: u64,
    /// What the user should know, after the range (`" (0 uses all cores)"`).
    pub note: &'static str,
    /// Whether the message gives both ends (`between 1 and 64`) or only the
    /// one crossed (`at most 1024`, for ranges from 0).
    pub both_ends: bool,
}

/// `spp`.
pub const SPP: Range = Range { key: "spp", min: 1, max: MAX_SPP as u64, note: "", both_ends: true };
/// `max_depth`.
pub const DEPTH: Range = Range { key: "max_depth", min: 1, max: MAX_DEPTH as u64, note: " (work grows as 2^depth)", both_ends: true };
/// `threads`.
pub const THREADS: Range = Range { key: "threads", min: 0, max: MAX_THREADS as u64, note: " (0 uses all cores)", both_ends: false };

impl Range {
    /// The message for `value` (as the user wrote it), which lies below the
    /// range when `below`, else above it.
    pub fn message(&self, value: &str, below: bool, naming: Naming) -> String {
        let (name, Range { min, max, note, .. }) = (naming.name(self.key), *self);
        match (self.both_ends, below) {
            (true, _) => format!("{name} must be between {min} and {max}{note}, got {value}"),
            (false, true) => format!("{name} must be at least {min}{note}, got {value}"),
            (false, false) => format!("{name} must be at most {max}{note}, got {value}"),
        }
    }

    /// `value` if it lies in the range, else [`Range::message`].
    pub fn check(&self, value: u64, naming: Naming) -> Result<u64, String> {
        match value {
            v if v < self.min => Err(self.message(&v.to_string(), true, naming)),
            v if v > self.max => Err(self.message(&v.to_string(), false, naming)),
            v => Ok(v),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_range_gives_one_message_per_front_end() {
        assert_eq!(SPP.check(0, Naming::Flags), Err("--spp must be between 1 and 1048576, got 0".to_string()));
        assert_eq!(SPP.check(1 << 20, Naming::Keywords), Ok(1 << 20));
        assert_eq!(
            DEPTH.check(65, Naming::Keywords),
            Err("max_depth must be between 1 and 64 (work grows as 2^depth), got 65".to_string())
        );
        assert_eq!(THREADS.check(1025, Naming::Flags), Err("--threads must be at most 1024 (0 uses all cores), got 1025".to_string()));
        assert_eq!(THREADS.check(0, Naming::Flags), Ok(0));
        // Python's values beyond any integer type read the same, only the value differs.
        assert_eq!(THREADS.message("-1", true, Naming::Keywords), "threads must be at least 0 (0 uses all cores), got -1");
        assert_eq!(
            DEPTH.message("8589934592", false, Naming::Keywords),
            "max_depth must be between 1 and 64 (work grows as 2^depth), got 8589934592"
        );
    }

    /// Each limit's value is written once in the workspace's sources: one
    /// `const` with a number, every other place naming that constant.
    #[test]
    fn each_limit_is_stated_once() {
        let crates = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
        let mut sources = Vec::new();
        let mut folders = vec![crates];
        while let Some(folder) = folders.pop() {
            for entry in std::fs::read_dir(&folder).unwrap().map(Result::unwrap) {
                let path = entry.path();
                let name = path.file_name().unwrap().to_string_lossy().to_string();
                if path.is_dir() && name != "target" && name != "tests" {
                    folders.push(path);
                } else if name.ends_with(".rs") {
                    sources.push((path.clone(), std::fs::read_to_string(&path).unwrap()));
                }
            }
        }
        assert!(sources.len() > 100, "found the workspace's sources ({})", sources.len());
        for limit in ["MAX_PIXELS", "MAX_DEPTH_LIMIT", "MAX_SPP", "MAX_THREADS"] {
            let stated: Vec<String> = sources
                .iter()
                .flat_map(|(path, text)| {
                    text.lines()
                        .enumerate()
                        .filter(|(_, line)| {
                            let line = line.trim_start().trim_start_matches("pub ").trim_start_matches("pub(crate) ");
                            line.starts_with(&format!("const {limit}:"))
                                && line.split('=').nth(1).is_some_and(|value| value.trim_start().starts_with(|c: char| c.is_ascii_digit()))
                        })
                        .map(move |(i, _)| format!("{}:{}", path.display(), i + 1))
                })
                .collect();
            assert!(stated.len() <= 1, "{limit} is stated {} times: {stated:?}", stated.len());
        }
    }
}
