//! Command-line arguments in two stages (ripgrep's lowargs/hiargs split): clap
//! parses the raw flags into [`Cli`], then [`RenderArgs::validate`] hands them to
//! the scene crate's request layer (`lamplight_scene::request`, shared with
//! Python), which resolves defaults and limits into a [`RenderJob`]. Every
//! rejection is a [`UsageError`] with a one-line message (exit code 2).

use std::fmt;
use std::path::{Path, PathBuf};

use clap::{Args, Parser, Subcommand};
use lamplight_core::film::tonemap::ToneMap;
use lamplight_scene::builtin;
use lamplight_scene::image_io::Format;
use lamplight_scene::image_io::Transfer;
use lamplight_scene::request::{
    AnimationChoice, AntialiasRequest, AutoLights, DisplayTransform, Job, Layer, MeshOptions, Naming, Request, RequestError, SceneRequest,
};

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
    /// Describe a scene or mesh file: triangles, bounds, materials, lights, cameras and warnings.
    Info(InfoArgs),
    /// Cast a batch of rays (.npy arrays) against a mesh: distances to the nearest hits and triangle indices.
    Raycast(crate::raycast::RaycastArgs),
    /// Show why a pixel has its colour: the ray tree of each sample (Whitted) or its paths (path tracer).
    Explain(ExplainArgs),
    /// Write a Mitsuba scene (.xml) or a mesh file (.obj, .ply, .gltf, .glb) as a lamplight scene file (.toml) that renders the same.
    Convert(ConvertArgs),
    /// Look at a scene live in the browser: progressive rendering, mouse camera, live reload, pixel inspector.
    View(ViewArgs),
    /// Denoise an .exr image (lamplight's, Mitsuba's, Blender's) with Intel Open Image Denoise, guided by its albedo and normal layers when it has them.
    Denoise(crate::denoise::DenoiseArgs),
}

/// `lamplight convert` flags.
#[derive(Debug, Args)]
pub struct ConvertArgs {
    /// The scene to convert: Mitsuba 3 XML, or a mesh file (its meshes stay in it; materials, camera and lights are written out).
    #[arg(value_name = "SCENE")]
    pub input: PathBuf,
    /// The TOML file to write.
    #[arg(short, long, value_name = "FILE")]
    pub output: PathBuf,
    /// Set the scene parameter $NAME (Mitsuba XML), as `mitsuba -D`; repeatable.
    #[arg(short = 'D', value_name = "NAME=VALUE", value_parser = define)]
    pub define: Vec<(String, String)>,
    /// A glTF file (.gltf, .glb) with several animations: write this one, by name (`Walk`) or index (`2`), as the
    /// scene's `[animation]` frames and its mesh's `animation` key [default: the first].
    #[arg(long, value_name = "NAME|INDEX")]
    pub animation: Option<AnimationChoice>,
}

/// `NAME=VALUE` of `-D`.
pub fn define(text: &str) -> Result<(String, String), String> {
    let (name, value) = text.split_once('=').ok_or_else(|| format!("must be NAME=VALUE, got {text:?}"))?;
    if name.is_empty() || !name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_') {
        return Err(format!("NAME must be letters, digits and _, got {name:?}"));
    }
    Ok((name.to_string(), value.to_string()))
}

/// `lamplight view` flags: the scene and render settings of `render`, and where to listen.
#[derive(Debug, Args)]
pub struct ViewArgs {
    /// The scene and how it is rendered, as for `render` [default size: 640 pixels wide].
    #[command(flatten)]
    pub render: SceneArgs,
    /// Worker threads; 0 uses all cores.
    #[arg(long, value_name = "T", default_value_t = 0, allow_negative_numbers = true, value_parser = count::<usize>)]
    pub threads: usize,
    /// Listen on this address instead of 127.0.0.1:8765 (anything but loopback lets other machines connect, with the token).
    #[arg(long, value_name = "ADDR:PORT")]
    pub listen: Option<std::net::SocketAddr>,
    /// The one folder the page saves images and cameras into [default: the scene file's folder, or the current folder].
    #[arg(long, value_name = "DIR")]
    pub save_dir: Option<std::path::PathBuf>,
    /// Open the viewer's URL in a browser.
    #[arg(long)]
    pub open: bool,
}

/// `lamplight explain` flags: the scene and render settings of `render`, and the pixel.
#[derive(Debug, Args)]
pub struct ExplainArgs {
    /// The scene and how it is rendered, as for `render`.
    #[command(flatten)]
    pub render: SceneArgs,
    /// The pixel: column and row from the top-left corner, `X,Y`.
    #[arg(long, value_name = "X,Y", value_parser = pixel)]
    pub pixel: (u32, u32),
    /// Only this sample of the pixel (0 to spp - 1) [default: every sample].
    #[arg(long, value_name = "K", allow_negative_numbers = true, value_parser = count::<u32>)]
    pub sample: Option<u32>,
    /// Print the tree as JSON instead of text.
    #[arg(long)]
    pub json: bool,
}

/// What `render` and `explain` share: the scene and the settings that decide each pixel's value.
#[derive(Debug, Args)]
pub struct SceneArgs {
    /// Built-in scene (see `lamplight list`), scene file (.toml, Mitsuba 3 .xml) or mesh file (.obj, .ply, .gltf, .glb).
    #[arg(value_name = "SCENE", default_value = builtin::BUILTINS[0].name)]
    pub scene: String,
    /// Image width in pixels [default: the scene's; with only --height, keeps the scene's aspect].
    #[arg(long, value_name = "W", allow_negative_numbers = true, value_parser = count::<u32>)]
    pub width: Option<u32>,
    /// Image height in pixels [default: the scene's; with only --width, keeps the scene's aspect].
    #[arg(long, value_name = "H", allow_negative_numbers = true, value_parser = count::<u32>)]
    pub height: Option<u32>,
    /// Samples per pixel, stratified and jittered when more than one: fixed supersampling
    /// [default: the file's; else Whitted anti-aliases adaptively and path samples each pixel
    /// to noise 0.05, 16 to 1024 samples (see --noise-threshold)].
    #[arg(long, value_name = "N", allow_negative_numbers = true, value_parser = count::<u32>)]
    pub spp: Option<u32>,
    /// Whitted: adaptive anti-aliasing (POV-Ray's +A): 16 samples in each pixel whose colour differs
    /// from a neighbour's by more than T (summed over channels); `on` (T = 0.3) or `off`
    /// [default: on unless --spp or the file's spp is given].
    #[arg(long, value_name = "T|on|off", allow_negative_numbers = true)]
    pub antialias: Option<AntialiasRequest>,
    /// Path tracer: stop sampling a pixel once its noise (the standard error of its mean over the square root
    /// of its brightness, Cycles' measure) is below E, e.g. 0.01; --spp is then the most a pixel takes (1024 if not given)
    /// [default: 0.05 when neither --spp nor the file's spp is given].
    #[arg(long, value_name = "E", allow_negative_numbers = true)]
    pub noise_threshold: Option<f64>,
    /// Path tracer with --noise-threshold: samples every pixel takes before any stops [default: 16].
    #[arg(long, value_name = "N", allow_negative_numbers = true, value_parser = count::<u32>)]
    pub min_spp: Option<u32>,
    /// Ray depth limit, 1 to 64, camera ray = 1 [default: the scene's].
    #[arg(long, value_name = "D", allow_negative_numbers = true, value_parser = count::<u32>)]
    pub max_depth: Option<u32>,
    /// Seed of the per-sample random numbers [default: the file's, else 0].
    #[arg(long, value_name = "S", allow_negative_numbers = true, value_parser = count::<u64>)]
    pub seed: Option<u64>,
    /// How light is computed: `whitted` (the lecture's ray tracer) or `path` (path tracing with NEE and MIS)
    /// [default: the file's, else whitted].
    #[arg(long, value_name = "NAME")]
    pub integrator: Option<String>,
    /// Scale every sample whose brightest channel exceeds V down to V: removes fireflies, but biased (darker where it acts). Off by default.
    #[arg(long, value_name = "V", allow_negative_numbers = true)]
    pub clamp: Option<f64>,
    /// Path tracer: pixel reconstruction filter, `box`, `tent` (radius 1), `gaussian` (sigma 0.5, cut at 2 pixels), `mitchell` (`mitchell(B=0.5, C=0.25)`), `catmullrom` or `lanczos` (`lanczos(lobes=2)`) [default: the file's, else box].
    #[arg(long, value_name = "NAME")]
    pub filter: Option<String>,
    /// Set the scene parameter $NAME of a Mitsuba XML scene, as `mitsuba -D`; repeatable.
    #[arg(short = 'D', value_name = "NAME=VALUE", value_parser = define)]
    pub define: Vec<(String, String)>,
    /// Path tracer: light the scene with this equirectangular HDR map (.exr or .hdr), looked up bilinearly, importance-sampled.
    #[arg(long, value_name = "FILE")]
    pub environment: Option<PathBuf>,
    /// The memory meshes, textures, BVHs and the film may take together, such as 4G or 512M [default: the scene's, else half the available memory].
    #[arg(long, value_name = "SIZE", value_parser = lamplight_scene::memory::parse)]
    pub memory_budget: Option<u64>,
    /// A mesh file (.obj, .ply, .gltf, .glb): shade its meshes that have no normals smooth (angle-weighted vertex normals, Mitsuba's default) rather than flat (glTF's rule, Blender's import). In a scene file, a mesh's `shading = "smooth"` says it.
    #[arg(long)]
    pub smooth: bool,
    /// A mesh file (.obj, .ply, .gltf, .glb) with lights of its own: keep the automatic lights a bare model gets (a neutral studio, key, fill and rim) `on` always, `off` never, or `auto` when the file's lights reach less than a quarter of what the camera sees (a light shut inside the model); a note says when they are kept. `--keep-auto-lights` alone is `on` [default: auto].
    #[arg(long, value_name = "on|off|auto", num_args = 0..=1, default_missing_value = "on", value_parser = auto_lights)]
    pub keep_auto_lights: Option<AutoLights>,
    /// A glTF file (.gltf, .glb) with several animations: play this one, by name (`Walk`) or index (`2`) as `lamplight info`
    /// lists them; the frames follow it [default: the first]. In a scene file, a glTF mesh's `animation` key chooses it.
    #[arg(long, value_name = "NAME|INDEX")]
    pub animation: Option<AnimationChoice>,
}

impl SceneArgs {
    /// The request these flags make (no time limit, window or layers).
    pub fn request(&self, threads: usize) -> Request {
        Request {
            width: self.width,
            height: self.height,
            spp: self.spp,
            antialias: self.antialias,
            noise_threshold: self.noise_threshold,
            min_spp: self.min_spp,
            max_depth: self.max_depth,
            threads: Some(threads),
            seed: self.seed,
            integrator: self.integrator.clone(),
            time_limit: None,
            clamp: self.clamp,
            filter: self.filter.clone(),
            window: None,
            environment: self.environment.clone(),
            layers: Vec::new(),
            denoise: None,
            denoise_library_hints: Vec::new(),
            memory_budget: self.memory_budget,
            smooth: self.smooth.then_some(true),
            keep_auto_lights: self.keep_auto_lights,
            frame: None,
            animation: self.animation.clone(),
        }
    }

    /// The scene these flags name, with the mesh file options they give.
    pub fn scene_request(&self) -> Result<SceneRequest, UsageError> {
        let options = self.request(0).mesh_options(MeshOptions::default());
        let scene = SceneRequest::resolve_with(&self.scene, &self.define)?.with_mesh_options(options, Naming::Flags)?;
        Ok(scene.with_animation(self.animation.as_ref(), Naming::Flags)?)
    }

    /// Starts the memory budget ([`lamplight_scene::memory`]) before the scene
    /// is read: a Mitsuba scene's `.serialized` meshes are read with it.
    pub fn begin_memory_budget(&self) {
        lamplight_scene::memory::begin(self.memory_budget, Naming::Flags);
    }
}

/// `--keep-auto-lights on|off|auto`.
fn auto_lights(text: &str) -> Result<AutoLights, String> {
    text.parse()
}

/// `X,Y` as two whole numbers.
fn pixel(text: &str) -> Result<(u32, u32), String> {
    let message = || "must be the pixel's column and row as X,Y, two whole numbers such as 320,180".to_string();
    let (x, y) = text.split_once(',').ok_or_else(message)?;
    let whole = |s: &str| s.trim().parse::<u32>().map_err(|_| message());
    Ok((whole(x)?, whole(y)?))
}

/// `--window X,Y,W,H`: four whole numbers.
fn window(text: &str) -> Result<(u32, u32, u32, u32), String> {
    let message = || "must be the window's corner and size as X,Y,W,H, four whole numbers such as 0,0,64,32".to_string();
    let parts: Vec<u32> = text.split(',').map(|s| s.trim().parse::<u32>().map_err(|_| message())).collect::<Result<_, _>>()?;
    match parts[..] {
        [x, y, w, h] => Ok((x, y, w, h)),
        _ => Err(message()),
    }
}

/// An explain request, checked and with every default resolved.
#[derive(Debug)]
pub struct ExplainJob {
    /// The scene.
    pub scene: SceneRequest,
    /// The render whose pixel is explained.
    pub job: Job,
    /// The pixel.
    pub pixel: (u32, u32),
    /// The one sample asked for.
    pub sample: Option<u32>,
    /// JSON rather than text.
    pub json: bool,
}

impl ExplainArgs {
    /// Reads the scene and resolves the render settings as `render` does.
    pub fn validate(self) -> Result<ExplainJob, UsageError> {
        self.render.begin_memory_budget();
        let scene = self.render.scene_request()?;
        let job = self.render.request(1).resolve(&scene.defaults, Naming::Flags)?;
        Ok(ExplainJob { scene, job, pixel: self.pixel, sample: self.sample, json: self.json })
    }
}

/// `lamplight render` flags, as typed.
#[derive(Debug, Args)]
pub struct RenderArgs {
    /// The scene and the settings that decide each pixel's value.
    #[command(flatten)]
    pub scene: SceneArgs,
    /// Output file; the extension picks the format (.png, .ppm, .exr); a run of # is a frame sequence's
    /// frame number, zero-padded, as in frame_####.png. Default: SCENE.png, or SCENE_####.png for several frames.
    #[arg(short, long, value_name = "FILE")]
    pub output: Option<PathBuf>,
    /// Render these frames of an animated scene, one file each: `1-120`, or one frame `7`.
    /// Default: the scene's first frame, or all the frames of its animation table when -o holds a run of #.
    /// Frames whose file exists are skipped. A scene without an animation table is the same at every frame.
    #[arg(long, value_name = "N|START-END")]
    pub frames: Option<String>,
    /// Render again, and replace, the frames of a sequence whose files exist.
    #[arg(long)]
    pub overwrite: bool,
    /// Then encode the sequence's frames into this video (.mp4, .webm or .gif) at the scene's fps, with ffmpeg
    /// from PATH; without ffmpeg the frames are kept and the command exits with code 2.
    #[arg(long, value_name = "FILE")]
    pub video: Option<PathBuf>,
    /// Worker threads; 0 uses all cores. The image does not depend on it.
    #[arg(long, value_name = "T", default_value_t = 0, allow_negative_numbers = true, value_parser = count::<usize>)]
    pub threads: usize,
    /// No progress bar and no summary line. Warnings (a missing texture, a scene no light reaches) and
    /// errors still print: they say what went wrong.
    #[arg(short, long)]
    pub quiet: bool,
    /// Path tracer: stop within this many seconds, the last pass shortened to the samples that fit (every pixel gets the same count).
    #[arg(long, value_name = "SECONDS")]
    pub time_limit: Option<f64>,
    /// Render only the pixels X..X+W, Y..Y+H of the image (from the top-left corner), each exactly as the
    /// whole render has it; the output is W x H.
    #[arg(long, value_name = "X,Y,W,H", value_parser = window)]
    pub window: Option<(u32, u32, u32, u32)>,
    /// Exposure in stops for .png/.ppm output (the image is scaled by 2^EV).
    #[arg(long, value_name = "EV", default_value_t = 0.0, allow_negative_numbers = true)]
    pub exposure: f64,
    /// Tone map for .png/.ppm output: `clamp` or `filmic` (ACES fit).
    #[arg(long, value_name = "NAME", default_value = "clamp")]
    pub tonemap: ToneMap,
    /// How .png/.ppm store the values: `srgb` (encoded) or `linear` (the numbers as they are, for display-referred scenes such as business-card). Default: the scene's `transfer`, else srgb.
    #[arg(long, value_name = "NAME")]
    pub transfer: Option<Transfer>,
    /// Also write the per-pixel variance of the image's mean to this .exr file.
    #[arg(long, value_name = "FILE")]
    pub variance_output: Option<PathBuf>,
    /// .exr output: extra layers in the same file, comma-separated:
    /// `variance` (of each pixel's mean: variance.R/G/B), `samples` (per pixel: samples.Y),
    /// `albedo` and `normal` (the denoiser's features: albedo.R/G/B, normal.X/Y/Z), `noisy` (the image before --denoise: noisy.R/G/B).
    #[arg(long, value_name = "LIST", value_delimiter = ',')]
    pub exr_layers: Vec<ExrLayer>,
    /// Denoise the image with Intel Open Image Denoise (HDR, on linear radiance, guided by albedo and normal layers).
    /// Needs the library: `pip install pyoidn`, or LAMPLIGHT_OIDN set to it.
    #[arg(long)]
    pub denoise: bool,
}

/// `lamplight info` arguments.
#[derive(Debug, Args)]
pub struct InfoArgs {
    /// Scene file (.toml, Mitsuba 3 .xml), mesh file (.obj, .ply, .gltf, .glb) or built-in scene name.
    #[arg(value_name = "FILE")]
    pub file: String,
    /// A glTF file (.gltf, .glb) with several animations: play this one, by name (`Walk`) or index (`2`) as `lamplight info`
    /// lists them; the frames follow it [default: the first]. In a scene file, a glTF mesh's `animation` key chooses it.
    #[arg(long, value_name = "NAME|INDEX")]
    pub animation: Option<AnimationChoice>,
}

/// An extra layer of the .exr output.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum ExrLayer {
    /// Variance of each pixel's mean, per channel.
    Variance,
    /// Samples taken per pixel.
    Samples,
    /// The denoiser's albedo feature: reflectance at the first non-specular hit.
    Albedo,
    /// The denoiser's normal feature: world-space shading normal there.
    Normal,
    /// The image before denoising (with --denoise).
    Noisy,
    /// Emitters and sky seen directly: the part --denoise leaves as it is.
    Emitted,
}

/// A render request, checked and with every default resolved.
#[derive(Debug)]
pub struct RenderJob {
    /// The scene.
    pub scene: SceneRequest,
    /// Where the image goes.
    pub output: PathBuf,
    /// Size, samples, depth, threads, seed, environment and layers.
    pub job: Job,
    /// Whether to stay silent.
    pub quiet: bool,
    /// Exposure and tone map for display formats.
    pub display: DisplayTransform,
    /// Where the path tracer's variance image goes.
    pub variance_output: Option<PathBuf>,
    /// Whether the output file itself holds the variance layer (`--exr-layers variance`).
    pub variance_in_output: bool,
    /// The frames to render, each to its own file (`--frames`); `None`: one image.
    pub sequence: Option<crate::frames::Sequence>,
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

impl From<RequestError> for UsageError {
    fn from(e: RequestError) -> UsageError {
        UsageError(e.0)
    }
}

/// A count given on the command line (pixels, samples, threads, a seed): a
/// whole number from 0 to `T`'s largest. Negative numbers are taken as values
/// (`allow_negative_numbers`) so that `--spp -1` is answered by this message
/// rather than by clap's "unexpected argument '-1'"; the request layer then
/// applies each option's own limits.
pub fn count<T: TryFrom<u128>>(text: &str) -> Result<T, String> {
    let digits = text.strip_prefix('+').unwrap_or(text);
    if let Some(rest) = digits.strip_prefix('-') {
        if !rest.is_empty() && rest.bytes().all(|b| b.is_ascii_digit()) {
            return Err("must be a positive number".to_string());
        }
    }
    if digits.is_empty() || !digits.bytes().all(|b| b.is_ascii_digit()) {
        return Err("must be a positive whole number".to_string());
    }
    let too_large = || format!("must be at most {}", max_of::<T>());
    let value: u128 = digits.parse().map_err(|_| too_large())?;
    T::try_from(value).map_err(|_| too_large())
}

/// The largest value of the unsigned type `T` (no standard trait gives it).
fn max_of<T: TryFrom<u128>>() -> u128 {
    (1..=128).rev().map(|bits| u128::MAX >> (128 - bits)).find(|&m| T::try_from(m).is_ok()).unwrap_or(0)
}

/// Fails when two of `outputs` (`(flag, path)` pairs) are the same file
/// ([`lamplight_scene::atomic::same_file`]: links and `..` included): the
/// second write would replace the first, and the data of one would be lost.
pub fn distinct_outputs(outputs: &[(&str, &Path)]) -> Result<(), UsageError> {
    for (i, (flag_a, a)) in outputs.iter().enumerate() {
        for (flag_b, b) in &outputs[i + 1..] {
            if lamplight_scene::atomic::same_file(a, b) {
                return Err(usage(format!(
                    "{flag_a} {} and {flag_b} {} are the same file; give each output a file of its own",
                    a.display(),
                    b.display()
                )));
            }
        }
    }
    Ok(())
}

fn usage(message: impl Into<String>) -> UsageError {
    UsageError(message.into())
}

impl RenderArgs {
    /// Checks the flags, reads a scene file, and resolves the defaults through
    /// the scene crate's request layer (shared with Python): flags override the
    /// file's settings, which override the program's defaults.
    pub fn validate(self) -> Result<RenderJob, UsageError> {
        self.scene.begin_memory_budget();
        let scene = self.scene.scene_request()?;
        if !self.exposure.is_finite() {
            return Err(usage("--exposure must be a finite number"));
        }
        let request = Request {
            time_limit: self.time_limit,
            window: self.window,
            layers: self
                .exr_layers
                .iter()
                .map(|l| match l {
                    ExrLayer::Variance => Layer::Variance,
                    ExrLayer::Samples => Layer::Samples,
                    ExrLayer::Albedo => Layer::Albedo,
                    ExrLayer::Normal => Layer::Normal,
                    ExrLayer::Noisy => Layer::Noisy,
                    ExrLayer::Emitted => Layer::Emitted,
                })
                .collect(),
            denoise: self.denoise.then_some(true),
            ..self.scene.request(self.threads)
        };
        let mut job = request.resolve(&scene.defaults, Naming::Flags)?;
        let (sequence, output) = crate::frames::sequence(&scene, self.frames.as_deref(), self.output, self.overwrite, self.video)?;
        if sequence.is_some() && self.variance_output.is_some() {
            return Err(usage(
                "--variance-output writes one file; for a frame sequence put the variance in each frame's .exr (--exr-layers variance)",
            ));
        }
        let format = Format::from_path(&output).map_err(|e| usage(e.to_string()))?;
        if !job.layers.is_empty() && format != Format::Exr {
            return Err(usage("--exr-layers needs an .exr output file"));
        }
        job.add_scene_layers(&scene.defaults, format == Format::Exr);
        let variance_output = self.variance_output;
        let variance_in_output = job.layers.contains(&Layer::Variance);
        if let Some(path) = &variance_output {
            if Format::from_path(path).map_err(|e| usage(e.to_string()))? != Format::Exr {
                return Err(usage("--variance-output must be an .exr file"));
            }
            if !job.layers.contains(&Layer::Variance) {
                job.layers.push(Layer::Variance);
            }
            distinct_outputs(&[("-o", &output), ("--variance-output", path)])?;
        }
        let display =
            DisplayTransform { exposure: self.exposure, tonemap: self.tonemap, transfer: self.transfer.unwrap_or(scene.defaults.transfer) };
        Ok(RenderJob { scene, output, job, quiet: self.quiet, display, variance_output, variance_in_output, sequence })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(args: &[&str]) -> Result<RenderJob, UsageError> {
        let cli = Cli::try_parse_from(["lamplight", "render"].iter().chain(args)).expect("clap accepts the flags");
        match cli.command {
            Command::Render(render) => render.validate(),
            _ => unreachable!("only render is parsed here"),
        }
    }

    #[test]
    fn defaults_come_from_the_first_builtin() {
        let job = parse(&[]).unwrap();
        let first = &builtin::BUILTINS[0];
        assert!(matches!(job.scene.spec, lamplight_scene::request::SceneSpec::Builtin(b) if b.name == first.name));
        assert_eq!(job.output, PathBuf::from(format!("{}.png", first.name)));
        assert_eq!((job.job.options.width, job.job.options.height), first.default_size);
        assert_eq!((job.job.options.spp, job.job.options.max_depth, job.job.options.threads, job.job.options.seed), (1, None, 0, 0));
        // The default render is anti-aliased, as POV-Ray's +A.
        assert_eq!(job.job.options.adaptive, Some(lamplight_core::Adaptive::Antialias(lamplight_core::Antialias::default())));
        assert!(!job.quiet);
    }

    #[test]
    fn a_scene_asking_for_variance_gets_the_layer_in_exr_outputs_only() {
        // Mitsuba's `moment` reads as `[render] variance = true`.
        let dir = tempfile::tempdir().unwrap();
        let scene = dir.path().join("moment.xml");
        std::fs::write(
            &scene,
            r#"<scene version="3.0.0"><integrator type="moment"><integrator type="path"/></integrator>
            <sensor type="perspective"><film type="hdrfilm"><integer name="width" value="8"/><integer name="height" value="8"/></film></sensor>
            </scene>"#,
        )
        .unwrap();
        let scene = scene.to_str().unwrap();
        let exr = dir.path().join("m.exr");
        let job = parse(&[scene, "-o", exr.to_str().unwrap()]).unwrap();
        assert_eq!(job.job.layers, vec![Layer::Variance]);
        assert!(job.variance_in_output);
        let png = dir.path().join("m.png");
        assert!(parse(&[scene, "-o", png.to_str().unwrap()]).unwrap().job.layers.is_empty(), "a PNG cannot hold it and is still written");
        // Asked twice (by the scene and the flag), the layer is written once.
        let both = parse(&[scene, "-o", exr.to_str().unwrap(), "--exr-layers", "variance,samples"]).unwrap();
        assert_eq!(both.job.layers, vec![Layer::Variance, Layer::Samples]);
    }

    #[test]
    fn flags_reach_the_options() {
        let job =
            parse(&["spheres", "-o", "x.EXR", "--width", "64", "--spp", "4", "--max-depth", "64", "--threads", "3", "--seed", "9", "-q"])
                .unwrap();
        assert_eq!(job.scene.name, "spheres");
        assert_eq!(job.output, PathBuf::from("x.EXR"));
        let o = &job.job.options;
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
        assert_eq!(job.job.options.integrator.name, "path");
        assert_eq!(job.job.options.time_limit, Some(std::time::Duration::from_millis(2500)));
        assert_eq!(job.job.options.filter, lamplight_core::film::Filter::Gaussian { sigma: 0.5 });
        assert_eq!((job.display.exposure, job.display.tonemap), (-1.5, ToneMap::Filmic));
        assert_eq!(parse(&[]).unwrap().job.options.integrator.name, "whitted", "whitted stays the default");
        assert_eq!(parse(&["--integrator", "photon"]).unwrap_err().0, "--integrator must be \"whitted\" or \"path\", got \"photon\"");
    }

    #[test]
    fn bad_input_is_a_one_line_usage_error() {
        let cases: &[(&[&str], &str)] = &[
            (&["foo"], "unknown scene \"foo\" (built-in scenes: luxo, business-card, cornell-box, spheres)"),
            (&["--time-limit", "0"], "--time-limit must be a positive number of seconds, got 0"),
            (&["--width", "0"], "--width must be at least 1"),
            (&["--height", "0"], "--height must be at least 1"),
            (&["--spp", "0"], "--spp must be between 1 and 1048576, got 0"),
            (&["--spp", "4294967295"], "--spp must be between 1 and 1048576, got 4294967295"),
            (&["--max-depth", "0"], "--max-depth must be between 1 and 64 (work grows as 2^depth), got 0"),
            (&["--max-depth", "65"], "--max-depth must be between 1 and 64 (work grows as 2^depth), got 65"),
            (&["--threads", "1025"], "--threads must be at most 1024 (0 uses all cores), got 1025"),
            (&["--width", "100000"], "image 100000x56250 is too large (at most 268435456 pixels)"),
            (&["-o", "out.jpg"], "cannot write out.jpg: unknown image format \"jpg\" (supported: .png, .ppm, .exr)"),
            (&["scene.txt"], "scene.txt: unknown scene file type, expected .toml, .xml or a mesh file (.obj, .ply, .gltf, .glb)"),
            (&["missing.toml"], "missing.toml: no such file"),
        ];
        for (args, expected) in cases {
            let err = parse(args).unwrap_err();
            assert_eq!(err.0, *expected, "{args:?}");
            assert!(!err.0.contains('\n'));
        }
    }
}
