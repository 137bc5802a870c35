//! Command-line arguments in two stages (ripgrep's lowargs/hiargs split): clap
//! parses the raw flags into [`Cli`], then [`RenderArgs::validate`] checks them
//! and resolves defaults into a [`RenderJob`] that says exactly what to do.
//! Every rejection is a [`UsageError`] with a one-line message (exit code 2).

use std::fmt;
use std::path::{Path, PathBuf};

use clap::{Args, Parser, Subcommand};
use lamplight_core::film::tonemap::ToneMap;
use lamplight_core::film::Filter;
use lamplight_core::integrators::{self, IntegratorEntry};
use lamplight_core::RenderOptions;
use lamplight_scene::build::SceneFile;
use lamplight_scene::builtin::{self, Builtin};
use lamplight_scene::image_io::Format;
use lamplight_scene::import;

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
#[command(
    name = "lamplight",
    version,
    about = "A ray tracer: the lecture's Whitted tracer and a physically based path tracer",
    arg_required_else_help = true
)]
pub struct Cli {
    /// What to do.
    #[command(subcommand)]
    pub command: Command,
}

/// The subcommands.
#[derive(Debug, Subcommand)]
pub enum Command {
    /// Render a built-in scene or a scene file to an image file (.png, .ppm or .exr).
    Render(RenderArgs),
    /// List the built-in scenes.
    List,
    /// Cast a batch of rays (.npy arrays) against a mesh: nearest-hit distances and triangle indices.
    Raycast(crate::raycast::RaycastArgs),
}

/// `lamplight render` flags, as typed.
#[derive(Debug, Args)]
pub struct RenderArgs {
    /// Built-in scene (see `lamplight list`), scene file (.toml) or mesh file (.obj, .ply, .gltf, .glb).
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
    /// Samples per pixel, stratified and jittered when more than one [default: the file's, else 1].
    #[arg(long, value_name = "N")]
    pub spp: Option<u32>,
    /// Ray depth limit, 1 to 64, camera ray = 1 [default: the scene's].
    #[arg(long, value_name = "D")]
    pub max_depth: Option<u32>,
    /// Worker threads; 0 uses all cores. The image does not depend on it.
    #[arg(long, value_name = "T", default_value_t = 0)]
    pub threads: usize,
    /// Seed of the per-sample random numbers [default: the file's, else 0].
    #[arg(long, value_name = "S")]
    pub seed: Option<u64>,
    /// No progress bar and no summary line.
    #[arg(short, long)]
    pub quiet: bool,
    /// How light is computed: `whitted` (the lecture's ray tracer) or `path` (path tracing with NEE and MIS)
    /// [default: the file's, else whitted].
    #[arg(long, value_name = "NAME")]
    pub integrator: Option<&'static IntegratorEntry>,
    /// Stop after the last complete pass before this many seconds (the path tracer's
    /// passes double in size; Whitted renders all samples in one pass).
    #[arg(long, value_name = "SECONDS")]
    pub time_limit: Option<f64>,
    /// Path tracer: pixel reconstruction filter, `box` or `gaussian` (sigma 0.5 pixel).
    #[arg(long, value_name = "NAME", default_value = "box")]
    pub filter: Filter,
    /// Exposure in stops for .png/.ppm output (the image is scaled by 2^EV).
    #[arg(long, value_name = "EV", default_value_t = 0.0, allow_negative_numbers = true)]
    pub exposure: f64,
    /// Tone map for .png/.ppm output: `clamp` or `filmic` (ACES fit).
    #[arg(long, value_name = "NAME", default_value = "clamp")]
    pub tonemap: ToneMap,
    /// Path tracer: light the scene with this equirectangular HDR map (.exr or .hdr), importance-sampled.
    #[arg(long, value_name = "FILE")]
    pub environment: Option<PathBuf>,
    /// Path tracer: also write the per-pixel variance of the image's mean to this .exr file.
    #[arg(long, value_name = "FILE")]
    pub variance_output: Option<PathBuf>,
    /// Path tracer, .exr output: extra layers in the same file, comma-separated:
    /// `variance` (of each pixel's mean: variance.R/G/B), `samples` (per pixel: samples.Y).
    #[arg(long, value_name = "LIST", value_delimiter = ',')]
    pub exr_layers: Vec<ExrLayer>,
}

/// An extra layer of the .exr output.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum ExrLayer {
    /// Variance of each pixel's mean, per channel.
    Variance,
    /// Samples taken per pixel.
    Samples,
}

/// Where the scene comes from.
#[derive(Debug)]
pub enum SceneSource {
    /// A built-in scene.
    Builtin(&'static Builtin),
    /// A native scene file, parsed.
    File(Box<SceneFile>),
    /// A mesh file for an importer.
    Mesh(PathBuf),
}

/// A render request, checked and with every default resolved.
#[derive(Debug)]
pub struct RenderJob {
    /// The scene.
    pub scene: SceneSource,
    /// Its name in messages.
    pub name: String,
    /// Where the image goes.
    pub output: PathBuf,
    /// Size, samples, depth, threads and seed.
    pub options: RenderOptions,
    /// Whether to stay silent.
    pub quiet: bool,
    /// Exposure in stops for display formats.
    pub exposure: f64,
    /// Tone map for display formats.
    pub tonemap: ToneMap,
    /// An environment map replacing the scene's sky.
    pub environment: Option<PathBuf>,
    /// Where the path tracer's variance image goes.
    pub variance_output: Option<PathBuf>,
    /// Extra layers of the .exr output (path tracer), each at most once.
    pub exr_layers: Vec<ExrLayer>,
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
    /// Checks the flags, reads a scene file, and resolves the defaults: flags
    /// override the file's settings, which override the program's defaults.
    pub fn validate(self) -> Result<RenderJob, UsageError> {
        let (scene, name, defaults) = resolve_scene(&self.scene)?;
        let (width, height) = image_size(self.width, self.height, defaults.size)?;
        let spp = self.spp.unwrap_or(defaults.spp);
        if spp == 0 {
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
        let time_limit = match self.time_limit {
            None => None,
            Some(t) if t.is_finite() && t > 0.0 && t < 1e9 => Some(std::time::Duration::from_secs_f64(t)),
            Some(t) => return Err(usage(format!("--time-limit must be a positive number of seconds, got {t}"))),
        };
        if !self.exposure.is_finite() {
            return Err(usage("--exposure must be a finite number"));
        }
        let integrator = self.integrator.unwrap_or(defaults.integrator);
        let variance_output = self.variance_output;
        if let Some(path) = &variance_output {
            if integrator.name != "path" {
                return Err(usage("--variance-output needs --integrator path"));
            }
            if Format::from_path(path).map_err(|e| usage(e.to_string()))? != Format::Exr {
                return Err(usage("--variance-output must be an .exr file"));
            }
        }
        let output = self.output.unwrap_or_else(|| PathBuf::from(format!("{name}.png")));
        let format = Format::from_path(&output).map_err(|e| usage(e.to_string()))?;
        let mut exr_layers = self.exr_layers;
        exr_layers.dedup();
        if !exr_layers.is_empty() {
            if integrator.name != "path" {
                return Err(usage("--exr-layers needs --integrator path"));
            }
            if format != Format::Exr {
                return Err(usage("--exr-layers needs an .exr output file"));
            }
        }
        let options = RenderOptions {
            width,
            height,
            spp,
            max_depth: self.max_depth,
            threads: self.threads,
            seed: self.seed.unwrap_or(defaults.seed),
            integrator,
            time_limit,
            filter: self.filter,
            window: None,
        };
        Ok(RenderJob {
            scene,
            name,
            output,
            options,
            quiet: self.quiet,
            exposure: self.exposure,
            tonemap: self.tonemap,
            environment: self.environment,
            variance_output,
            exr_layers,
        })
    }
}

/// Size, samples, seed and integrator a scene asks for when no flag is given.
struct Defaults {
    size: (u32, u32),
    spp: u32,
    seed: u64,
    integrator: &'static IntegratorEntry,
}

/// The scene `arg` names: a built-in name (no path separator, no extension), a
/// `.toml` scene file (read and parsed here, so that a bad file stops before any
/// work), or a mesh file.
fn resolve_scene(arg: &str) -> Result<(SceneSource, String, Defaults), UsageError> {
    let path = Path::new(arg);
    let has_separator = arg.contains('/') || arg.contains(std::path::MAIN_SEPARATOR);
    let extension = path.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase);
    if !has_separator && extension.is_none() {
        let b = builtin::find(arg).ok_or_else(|| usage(format!("unknown scene '{arg}' (built-in scenes: {})", builtin::names())))?;
        return Ok((
            SceneSource::Builtin(b),
            b.name.to_string(),
            Defaults { size: b.default_size, spp: 1, seed: 0, integrator: integrators::default_integrator() },
        ));
    }
    let stem = path.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_else(|| "scene".into());
    match extension.as_deref() {
        Some("toml") => {
            let file = SceneFile::read(path).map_err(|e| usage(e.to_string()))?;
            let s = file.settings().map_err(|e| usage(e.to_string()))?;
            Ok((
                SceneSource::File(Box::new(file)),
                stem,
                Defaults { size: (s.width, s.height), spp: s.spp, seed: s.seed, integrator: s.integrator },
            ))
        }
        Some(ext) if import::EXTENSIONS.contains(&ext) => Ok((
            SceneSource::Mesh(path.to_path_buf()),
            stem,
            Defaults { size: (640, 360), spp: 1, seed: 0, integrator: integrators::default_integrator() },
        )),
        _ => Err(usage(format!(
            "{arg}: unknown scene file type, expected .toml or a mesh file ({})",
            import::EXTENSIONS.iter().map(|e| format!(".{e}")).collect::<Vec<_>>().join(", ")
        ))),
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
        assert!(matches!(job.scene, SceneSource::Builtin(b) if b.name == first.name));
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
        assert_eq!(job.name, "spheres");
        assert_eq!(job.output, PathBuf::from("x.EXR"));
        let o = &job.options;
        assert_eq!((o.width, o.height, o.spp, o.max_depth, o.threads, o.seed), (64, 36, 4, Some(64), 3, 9));
        assert!(job.quiet);
    }

    #[test]
    fn path_tracer_flags_reach_the_options() {
        let job = parse(&[
            "cornell-box",
            "--integrator",
            "path",
            "--time-limit",
            "2.5",
            "--filter",
            "gaussian",
            "--tonemap",
            "filmic",
            "--exposure",
            "-1.5",
        ])
        .unwrap();
        assert_eq!(job.options.integrator.name, "path");
        assert_eq!(job.options.time_limit, Some(std::time::Duration::from_millis(2500)));
        assert_eq!(job.options.filter, Filter::Gaussian { sigma: 0.5 });
        assert_eq!((job.exposure, job.tonemap), (-1.5, ToneMap::Filmic));
        assert_eq!(parse(&[]).unwrap().options.integrator.name, "whitted", "whitted stays the default");
        assert!(Cli::try_parse_from(["lamplight", "render", "--integrator", "photon"]).is_err());
    }

    #[test]
    fn bad_input_is_a_one_line_usage_error() {
        let cases: &[(&[&str], &str)] = &[
            (&["foo"], "unknown scene 'foo' (built-in scenes: luxo, business-card, cornell-box, spheres)"),
            (&["--time-limit", "0"], "--time-limit must be a positive number of seconds, got 0"),
            (&["--width", "0"], "--width must be at least 1"),
            (&["--height", "0"], "--height must be at least 1"),
            (&["--spp", "0"], "--spp must be at least 1"),
            (&["--max-depth", "0"], "--max-depth must be between 1 and 64, got 0 (work grows as 2^depth)"),
            (&["--max-depth", "65"], "--max-depth must be between 1 and 64, got 65 (work grows as 2^depth)"),
            (&["--threads", "1025"], "--threads must be at most 1024 (0 uses all cores), got 1025"),
            (&["--width", "100000"], "image 100000x56250 is too large (at most 268435456 pixels)"),
            (&["-o", "out.jpg"], "cannot write out.jpg: unknown image format \"jpg\" (supported: .png, .ppm, .exr)"),
            (&["scene.txt"], "scene.txt: unknown scene file type, expected .toml or a mesh file (.obj, .ply, .gltf, .glb)"),
            (&["missing.toml"], "missing.toml: no such file"),
        ];
        for (args, expected) in cases {
            let err = parse(args).unwrap_err();
            assert_eq!(err.0, *expected, "{args:?}");
            assert!(!err.0.contains('\n'));
        }
    }
}
