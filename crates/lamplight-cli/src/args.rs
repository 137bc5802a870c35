//! Command-line arguments in two stages (ripgrep's lowargs/hiargs split): clap
//! parses the raw flags into [`Cli`], then [`RenderArgs::validate`] checks them
//! and resolves defaults into a [`RenderJob`] that says exactly what to do.
//! Every rejection is a [`UsageError`] with a one-line message (exit code 2).

use std::fmt;
use std::path::PathBuf;

use clap::{Args, Parser, Subcommand};
use lamplight_core::RenderOptions;
use lamplight_scene::builtin::{self, Builtin};
use lamplight_scene::image_io::Format;

/// Deepest allowed `--max-depth`. Whitted tracing may spawn a reflected and a
/// refracted ray at every hit, so a camera ray's work grows as `2^depth`: 64 levels
/// already allow more rays than any render could trace, and a larger value can
/// only be a typo (such as 1000 for 10), which would otherwise look like a hang.
pub const MAX_DEPTH_LIMIT: u32 = 64;

/// Most allowed `--threads`: far above any machine's cores; more threads would only
/// cost memory and scheduling, and huge counts make the thread pool fail.
pub const MAX_THREADS: usize = 1024;

/// Most pixels in an image: the core renderer's limit (`2^28`, e.g. 16384x16384).
pub const MAX_PIXELS: u64 = 1 << 28;

/// The `lamplight` command line.
#[derive(Debug, Parser)]
#[command(name = "lamplight", version, about = "A Whitted ray tracer", arg_required_else_help = true)]
pub struct Cli {
    /// What to do.
    #[command(subcommand)]
    pub command: Command,
}

/// The subcommands.
#[derive(Debug, Subcommand)]
pub enum Command {
    /// Render a built-in scene to an image file (.png, .ppm or .exr).
    Render(RenderArgs),
    /// List the built-in scenes.
    List,
    /// Cast a batch of rays (.npy arrays) against a mesh; see `raycast.rs`.
    Raycast(crate::raycast::RaycastArgs),
}

/// `lamplight render` flags, as typed.
#[derive(Debug, Args)]
pub struct RenderArgs {
    /// Built-in scene to render (see `lamplight list`).
    #[arg(value_name = "SCENE", default_value = builtin::BUILTINS[0].name)]
    pub scene: String,
    /// Output file; the extension picks the format (.png, .ppm, .exr) [default: SCENE.png].
    #[arg(short, long, value_name = "FILE")]
    pub output: Option<PathBuf>,
    /// Image width in pixels [default: the scene's; with only --height, keeps the scene's aspect].
    #[arg(long, value_name = "W")]
    pub width: Option<u32>,
    /// Image height in pixels [default: the scene's; with only --width, keeps the scene's aspect].
    #[arg(long, value_name = "H")]
    pub height: Option<u32>,
    /// Samples per pixel (stratified and jittered when more than one).
    #[arg(long, value_name = "N", default_value_t = 1)]
    pub spp: u32,
    /// Ray depth limit, 1 to 64, camera ray = 1 [default: the scene's].
    #[arg(long, value_name = "D")]
    pub max_depth: Option<u32>,
    /// Worker threads; 0 uses all cores. The image does not depend on it.
    #[arg(long, value_name = "T", default_value_t = 0)]
    pub threads: usize,
    /// Seed of the per-sample random numbers.
    #[arg(long, value_name = "S", default_value_t = 0)]
    pub seed: u64,
    /// No progress bar and no summary line.
    #[arg(short, long)]
    pub quiet: bool,
}

/// A render request, checked and with every default resolved.
#[derive(Debug)]
pub struct RenderJob {
    /// The scene.
    pub builtin: &'static Builtin,
    /// Where the image goes.
    pub output: PathBuf,
    /// Size, samples, depth, threads and seed.
    pub options: RenderOptions,
    /// Whether to stay silent.
    pub quiet: bool,
}

/// Bad input from the user: the program exits with code 2.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct UsageError(pub String);

impl fmt::Display for UsageError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for UsageError {}

fn usage(message: impl Into<String>) -> UsageError {
    UsageError(message.into())
}

impl RenderArgs {
    /// Checks the flags and resolves the defaults.
    pub fn validate(self) -> Result<RenderJob, UsageError> {
        let builtin = builtin::find(&self.scene)
            .ok_or_else(|| usage(format!("unknown scene '{}' (built-in scenes: {})", self.scene, builtin::names())))?;
        let (width, height) = image_size(self.width, self.height, builtin.default_size)?;
        if self.spp == 0 {
            return Err(usage("--spp must be at least 1"));
        }
        if let Some(depth) = self.max_depth {
            if !(1..=MAX_DEPTH_LIMIT).contains(&depth) {
                return Err(usage(format!("--max-depth must be between 1 and {MAX_DEPTH_LIMIT}, got {depth} (work grows as 2^depth)")));
            }
        }
        if self.threads > MAX_THREADS {
            return Err(usage(format!("--threads must be at most {MAX_THREADS} (0 uses all cores), got {}", self.threads)));
        }
        let output = self.output.unwrap_or_else(|| PathBuf::from(format!("{}.png", builtin.name)));
        Format::from_path(&output).map_err(|e| usage(e.to_string()))?;
        let options = RenderOptions {
            width,
            height,
            spp: self.spp,
            max_depth: self.max_depth,
            threads: self.threads,
            seed: self.seed,
            ..RenderOptions::default()
        };
        Ok(RenderJob { builtin, output, options, quiet: self.quiet })
    }
}

/// The image size from the flags: both given, one given (the other follows the
/// default aspect, rounded, at least 1), or the default.
fn image_size(width: Option<u32>, height: Option<u32>, default: (u32, u32)) -> Result<(u32, u32), UsageError> {
    for (flag, value) in [("--width", width), ("--height", height)] {
        if value == Some(0) {
            return Err(usage(format!("{flag} must be at least 1")));
        }
    }
    let (dw, dh) = (default.0 as f64, default.1 as f64);
    let scaled = |v: u32, ratio: f64| ((v as f64 * ratio).round().max(1.0)).min(u32::MAX as f64) as u32;
    let (w, h) = match (width, height) {
        (Some(w), Some(h)) => (w, h),
        (Some(w), None) => (w, scaled(w, dh / dw)),
        (None, Some(h)) => (scaled(h, dw / dh), h),
        (None, None) => default,
    };
    if w as u64 * h as u64 > MAX_PIXELS {
        return Err(usage(format!("image {w}x{h} is too large (at most {MAX_PIXELS} pixels)")));
    }
    Ok((w, h))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(args: &[&str]) -> Result<RenderJob, UsageError> {
        let cli = Cli::try_parse_from(["lamplight", "render"].iter().chain(args)).expect("clap accepts the flags");
        match cli.command {
            Command::Render(render) => render.validate(),
            Command::List | Command::Raycast(_) => unreachable!(),
        }
    }

    #[test]
    fn defaults_come_from_the_first_builtin() {
        let job = parse(&[]).unwrap();
        let first = &builtin::BUILTINS[0];
        assert_eq!(job.builtin.name, first.name);
        assert_eq!(job.output, PathBuf::from(format!("{}.png", first.name)));
        assert_eq!((job.options.width, job.options.height), first.default_size);
        assert_eq!((job.options.spp, job.options.max_depth, job.options.threads, job.options.seed), (1, None, 0, 0));
        assert!(!job.quiet);
    }

    #[test]
    fn one_side_keeps_the_default_aspect() {
        assert_eq!(image_size(Some(640), None, (1280, 720)).unwrap(), (640, 360));
        assert_eq!(image_size(None, Some(36), (1280, 720)).unwrap(), (64, 36));
        assert_eq!(image_size(Some(1), None, (1280, 720)).unwrap(), (1, 1), "never rounds to 0");
        assert_eq!(image_size(Some(7), Some(3), (1280, 720)).unwrap(), (7, 3));
        assert_eq!(image_size(None, None, (32, 32)).unwrap(), (32, 32));
    }

    #[test]
    fn flags_reach_the_options() {
        let job =
            parse(&["spheres", "-o", "x.EXR", "--width", "64", "--spp", "4", "--max-depth", "64", "--threads", "3", "--seed", "9", "-q"])
                .unwrap();
        assert_eq!(job.builtin.name, "spheres");
        assert_eq!(job.output, PathBuf::from("x.EXR"));
        let o = &job.options;
        assert_eq!((o.width, o.height, o.spp, o.max_depth, o.threads, o.seed), (64, 36, 4, Some(64), 3, 9));
        assert!(job.quiet);
    }

    #[test]
    fn bad_input_is_a_one_line_usage_error() {
        let cases: &[(&[&str], &str)] = &[
            (&["foo"], "unknown scene 'foo' (built-in scenes: luxo, business-card, spheres)"),
            (&["--width", "0"], "--width must be at least 1"),
            (&["--height", "0"], "--height must be at least 1"),
            (&["--spp", "0"], "--spp must be at least 1"),
            (&["--max-depth", "0"], "--max-depth must be between 1 and 64, got 0 (work grows as 2^depth)"),
            (&["--max-depth", "65"], "--max-depth must be between 1 and 64, got 65 (work grows as 2^depth)"),
            (&["--threads", "1025"], "--threads must be at most 1024 (0 uses all cores), got 1025"),
            (&["--width", "100000"], "image 100000x56250 is too large (at most 268435456 pixels)"),
            (&["-o", "out.jpg"], "cannot write out.jpg: unknown image format \"jpg\" (supported: .png, .ppm, .exr)"),
        ];
        for (args, expected) in cases {
            let err = parse(args).unwrap_err();
            assert_eq!(err.0, *expected, "{args:?}");
            assert!(!err.0.contains('\n'));
        }
    }
}
