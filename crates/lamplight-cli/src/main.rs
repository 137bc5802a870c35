//! `lamplight`: render a built-in scene or a scene file to an image file.
//!
//! ```text
//! lamplight render [SCENE|FILE] [-o FILE] [--width W] [--height H] [--spp N]
//!                  [--max-depth D] [--threads T] [--seed S] [--quiet]
//! lamplight list
//! lamplight info FILE
//! lamplight view [SCENE|FILE] [--listen ADDR] [--open] [render flags]
//! lamplight denoise IN.exr -o OUT [--threads T]
//! ```
//!
//! The binary is thin: it turns arguments into options ([`args`]), builds the
//! scene, calls [`lamplight_core::render`] and writes the image with
//! [`lamplight_scene::image_io`]. Errors print as one line,
//! `lamplight: error: ...`; the exit code is 2 for bad input, 1 for failures
//! while running (such as an unwritable output file), 130 after Ctrl-C, SIGTERM
//! or SIGHUP, which leave no temporary file behind ([`signals`]).

mod args;
mod denoise;
mod frames;
mod raycast;
mod signals;
mod view;

use std::io::{self, IsTerminal, Write};
use std::path::Path;
use std::process::ExitCode;
use std::time::{Duration, Instant};

use anyhow::Context;
use clap::Parser;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use lamplight_core::{RenderControl, RenderStats};
use lamplight_scene::request::{self, Job, Layer};
use lamplight_scene::{builtin, image_io};

use crate::args::{Cli, Command, ExplainJob, RenderJob, UsageError};

fn main() -> ExitCode {
    signals::install();
    match run() {
        Ok(()) => ExitCode::SUCCESS,
        // `lamplight list | head -1`: the reader leaving is not our failure.
        Err(err) if is_broken_pipe(&err) => ExitCode::SUCCESS,
        Err(err) => {
            eprintln!("lamplight: error: {err:#}");
            if err.downcast_ref::<UsageError>().is_some() {
                ExitCode::from(2)
            } else {
                ExitCode::FAILURE
            }
        }
    }
}

fn run() -> anyhow::Result<()> {
    match parse_args()?.command {
        Command::Render(render_args) => render_command(render_args.validate()?),
        Command::List => list_command(),
        Command::Info(info_args) => info_command(&info_args.file, info_args.animation.as_ref()),
        Command::Raycast(raycast_args) => raycast::raycast_command(raycast_args),
        Command::Explain(explain_args) => explain_command(explain_args.validate()?),
        Command::Convert(convert_args) => convert_command(&convert_args),
        Command::View(view_args) => view::view_command(view_args),
        Command::Denoise(denoise_args) => denoise::denoise_command(&denoise_args),
    }
}

fn convert_command(args: &args::ConvertArgs) -> anyhow::Result<()> {
    let converted = lamplight_scene::convert::convert_with(&args.input, &args.output, &args.define, args.animation.as_ref())
        .map_err(|e| UsageError(e.to_string()))?;
    print_warnings(&converted.warnings);
    for (path, bytes) in &converted.files {
        if let Some(dir) = path.parent() {
            std::fs::create_dir_all(dir).map_err(|e| UsageError(format!("{}: cannot create the folder: {e}", dir.display())))?;
        }
        lamplight_scene::atomic::write(path, bytes).map_err(|e| UsageError(format!("{}: cannot write: {e}", path.display())))?;
    }
    lamplight_scene::atomic::write(&args.output, converted.toml.as_bytes())
        .map_err(|e| UsageError(format!("{}: cannot write: {e}", args.output.display())))?;
    Ok(())
}

/// The parsed command line. clap prints help and version itself (exit code
/// 0); every usage error becomes one line, like every other bad input (exit
/// code 2): clap's message, its tips in parentheses (a misspelt flag's nearest
/// name) and, for a wrong command line rather than a wrong value, the usage.
fn parse_args() -> anyhow::Result<Cli> {
    use clap::error::ErrorKind;
    match Cli::try_parse() {
        Ok(cli) => Ok(cli),
        Err(e) if !e.use_stderr() || e.kind() == ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand => e.exit(),
        Err(e) => {
            let text = e.render().to_string();
            Err(UsageError(one_line_usage_error(&text, !matches!(e.kind(), ErrorKind::ValueValidation | ErrorKind::InvalidValue))).into())
        }
    }
}

/// clap's rendered error `text` (`error: ...`, blank lines, `tip: ...`,
/// `Usage: ...`, `For more information, try '--help'.`) as one line.
fn one_line_usage_error(text: &str, with_usage: bool) -> String {
    let mut lines = text.lines().map(str::trim).filter(|l| !l.is_empty());
    let first = lines.next().unwrap_or_default();
    let mut message = first.strip_prefix("error: ").unwrap_or(first).to_string();
    for line in text.lines().map(str::trim) {
        // The nearest flag is worth the line; how to pass a dash-value is not.
        if let Some(tip) = line.strip_prefix("tip: ").filter(|t| !t.starts_with("to pass ")) {
            message.push_str(&format!(" ({tip})"));
        }
    }
    if with_usage {
        if let Some(usage) = text.lines().map(str::trim).find_map(|l| l.strip_prefix("Usage: ")) {
            message.push_str(&format!("; usage: {usage} (more with --help)"));
        }
    }
    message
}

fn list_command() -> anyhow::Result<()> {
    let width = builtin::BUILTINS.iter().map(|b| b.name.len()).max().unwrap_or(0);
    let mut out = io::stdout().lock();
    for b in builtin::BUILTINS {
        let (w, h) = b.default_size;
        writeln!(out, "{:width$}  {:>9}  {}", b.name, format!("{w}x{h}"), b.summary)?;
    }
    out.flush()?;
    Ok(())
}

fn info_command(file: &str, animation: Option<&request::AnimationChoice>) -> anyhow::Result<()> {
    let scene =
        request::SceneRequest::resolve(file).and_then(|s| s.with_animation(animation, request::Naming::Flags)).map_err(UsageError::from)?;
    let text = lamplight_scene::info::describe(&scene).map_err(UsageError::from)?;
    let mut out = io::stdout().lock();
    out.write_all(text.as_bytes())?;
    out.flush()?;
    Ok(())
}

fn render_command(render: RenderJob) -> anyhow::Result<()> {
    if render.sequence.is_some() {
        return frames::render_sequence(&render);
    }
    // Fail before a long render, not after it, when the file cannot be written.
    image_io::check_writable(&render.output)?;
    render_to(&render, &render.job, &render.output, None)
}

/// Renders `job` (the render `render` asks for, at one frame) to `output`.
/// Within a sequence (`frame`), a frame that a signal interrupts is not
/// written: its file would look finished to the next run, which skips it.
pub(crate) fn render_to(render: &RenderJob, job: &Job, output: &Path, frame: Option<i64>) -> anyhow::Result<()> {
    let RenderJob { scene, quiet, display, variance_output, variance_in_output, .. } = render;
    let (quiet, display, variance_in_output) = (*quiet, *display, *variance_in_output);

    let build_start = Instant::now();
    let (width, height) = (job.options.width, job.options.height);
    // Scene errors are the user's input: exit code 2, one line naming file and place.
    let built = scene.instantiate(job).map_err(|e| UsageError(e.0))?;
    print_warnings(&built.warnings);
    let built = built.scene;
    print_warnings(&job.light_warnings(&built));
    let build_time = build_start.elapsed();

    let bar = progress_bar(quiet);
    let progress = |done: u64, total: u64| {
        if let Some(bar) = &bar {
            bar.set_length(total);
            bar.set_position(done);
        }
    };
    let graceful = signals::Graceful::start();
    let control = RenderControl { progress: &progress, cancel: None, stop: Some(graceful.stop_flag()) };
    let rendered = job.run(&built, &control);
    // From here a signal ends the program at once (a second Ctrl-C, or one during the write).
    drop(graceful);
    if let Some(bar) = &bar {
        bar.finish_and_clear();
    }
    if let (true, Some(frame)) = (signals::stop_requested(), frame) {
        eprintln!("lamplight: error: interrupted at frame {frame}, which was not written (the frames before it were)");
        std::process::exit(signals::INTERRUPTED);
    }
    if signals::stop_requested() && rendered.is_err() {
        // No pass was complete: nothing to write.
        eprintln!("lamplight: error: interrupted");
        std::process::exit(signals::INTERRUPTED);
    }
    let mut rendered = rendered.with_context(|| format!("cannot render scene '{}'", scene.name))?;
    print_warnings(&built.shape_warnings());
    // Stopped by a signal with fewer samples than asked: write them, then say so.
    let stopped_early = signals::stop_requested() && rendered.stats.samples_per_pixel < job.options.spp;
    if let Some(path) = &variance_output {
        let variance = rendered.layers.iter().find(|(l, _)| *l == Layer::Variance).map(|(_, image)| image.clone());
        image_io::write_image(path, &variance.expect("validate asks for the variance layer"))?;
        // Written to its own file only, unless --exr-layers asked for it too.
        if !variance_in_output {
            rendered.layers.retain(|(l, _)| *l != Layer::Variance);
        }
    }
    request::write(output, &rendered, display)?;

    let stats = rendered.stats;
    if stopped_early {
        eprintln!(
            "lamplight: interrupted: wrote the last complete pass ({} of {} samples per pixel) to {}",
            stats.samples_per_pixel,
            job.options.spp,
            output.display()
        );
        std::process::exit(signals::INTERRUPTED);
    }
    let name = match frame {
        Some(f) => format!("{} frame {f}", scene.name),
        None => scene.name.clone(),
    };
    let summary =
        Summary { scene: &name, width, height, spp: stats.samples_per_pixel, adaptive: job.options.adaptive.is_some(), build_time, stats };
    if !quiet {
        eprintln!("{} -> {}", summary, output.display());
        if let Some(t) = rendered.denoise_time {
            eprintln!("denoised in {:.2} s (Open Image Denoise)", t.as_secs_f64());
        }
    } else if stats.nonfinite_samples > 0 {
        eprintln!(
            "lamplight: warning: {} samples were NaN, infinite or brighter than {:e} and were replaced by black",
            stats.nonfinite_samples,
            lamplight_core::film::MAX_RADIANCE
        );
    }
    Ok(())
}

/// Prints the ray tree (or paths) of one pixel, as text or JSON, to stdout.
fn explain_command(job: ExplainJob) -> anyhow::Result<()> {
    let ExplainJob { scene, job, pixel, sample, json } = job;
    let built = scene.instantiate(&job).map_err(|e| UsageError(e.0))?;
    print_warnings(&built.warnings);
    let built = built.scene;
    let explained = lamplight_scene::explain::explain(&built, &job, pixel, sample, request::Naming::Flags).map_err(UsageError::from)?;
    let mut out = io::BufWriter::new(io::stdout().lock());
    if json {
        // Written as it is made: one string of a large tree would double its memory.
        serde_json::to_writer_pretty(&mut out, &explained.to_json())?;
        writeln!(out)?;
    } else {
        write!(out, "{explained}")?;
    }
    out.flush()?;
    Ok(())
}

/// Prints the importers' warnings to stderr, one line each (each is given once).
pub(crate) fn print_warnings(warnings: &[String]) {
    for warning in warnings {
        eprintln!("lamplight: warning: {warning}");
    }
}

/// A tile progress bar on stderr, only for a person watching a terminal.
fn progress_bar(quiet: bool) -> Option<ProgressBar> {
    if quiet || !io::stderr().is_terminal() {
        return None;
    }
    let bar = ProgressBar::with_draw_target(None, ProgressDrawTarget::stderr());
    let style = ProgressStyle::with_template("{spinner} [{elapsed_precise}] [{wide_bar}] {percent:>3}% tiles, eta {eta}")
        .expect("the template is valid")
        .progress_chars("=> ");
    bar.set_style(style);
    Some(bar)
}

/// The one-line report printed after a render.
struct Summary<'a> {
    scene: &'a str,
    width: u32,
    height: u32,
    spp: u32,
    /// Whether pixels took different sample counts.
    adaptive: bool,
    build_time: Duration,
    stats: RenderStats,
}

impl std::fmt::Display for Summary<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let Summary { scene, width, height, spp, adaptive, build_time, stats } = self;
        let rays = &stats.rays;
        let seconds = stats.elapsed.as_secs_f64();
        let spp = if *adaptive {
            let mean = stats.pixel_samples as f64 / (*width as f64 * *height as f64).max(1.0);
            format!("{mean:.2} spp adaptive (at most {spp})")
        } else {
            format!("{spp} spp")
        };
        write!(
            f,
            "rendered {scene} {width}x{height}, {spp} in {} (scene built in {}): \
             {} rays ({} camera, {} secondary, {} shadow), {} rays/s, {} thread{}",
            duration(stats.elapsed),
            duration(*build_time),
            si(rays.total() as f64),
            si(rays.camera as f64),
            si(rays.secondary as f64),
            si(rays.shadow as f64),
            si(rays.total() as f64 / seconds.max(1e-9)),
            stats.threads,
            if stats.threads == 1 { "" } else { "s" },
        )?;
        if stats.nonfinite_samples > 0 {
            write!(f, ", {} nonfinite samples set to black", stats.nonfinite_samples)?;
        }
        Ok(())
    }
}

/// A duration in milliseconds below one second, else in seconds: `3.3 ms`, `420.0 ms`, `12.35 s`.
fn duration(d: Duration) -> String {
    let seconds = d.as_secs_f64();
    if seconds < 1.0 {
        format!("{:.1} ms", seconds * 1e3)
    } else {
        format!("{seconds:.2} s")
    }
}

/// `x` with an SI prefix and one decimal: `412`, `4.1 k`, `3.1 M`, `1.2 G`.
fn si(x: f64) -> String {
    match x {
        x if x < 1e3 => format!("{x:.0}"),
        x if x < 1e6 => format!("{:.1} k", x / 1e3),
        x if x < 1e9 => format!("{:.1} M", x / 1e6),
        x => format!("{:.1} G", x / 1e9),
    }
}

fn is_broken_pipe(err: &anyhow::Error) -> bool {
    err.chain().any(|e| e.downcast_ref::<io::Error>().is_some_and(|e| e.kind() == io::ErrorKind::BrokenPipe))
}

#[cfg(test)]
mod tests {
    use super::*;
    use lamplight_core::integrators::RayCounts;

    #[test]
    fn si_prefixes() {
        assert_eq!(si(0.0), "0");
        assert_eq!(si(412.4), "412");
        assert_eq!(si(4_140.0), "4.1 k");
        assert_eq!(si(3_100_000.0), "3.1 M");
        assert_eq!(si(1.25e10), "12.5 G");
        assert_eq!(duration(Duration::from_micros(3_260)), "3.3 ms");
        assert_eq!(duration(Duration::from_millis(12_345)), "12.35 s");
    }

    #[test]
    fn summary_line() {
        let stats = RenderStats {
            rays: RayCounts { camera: 900_000, secondary: 400_000, shadow: 1_800_000 },
            nonfinite_samples: 0,
            elapsed: Duration::from_millis(420),
            threads: 2,
            samples_per_pixel: 1,
            pixel_samples: 1280 * 720,
        };
        let mut summary =
            Summary { scene: "luxo", width: 1280, height: 720, spp: 1, adaptive: false, build_time: Duration::from_millis(10), stats };
        assert_eq!(
            summary.to_string(),
            "rendered luxo 1280x720, 1 spp in 420.0 ms (scene built in 10.0 ms): 3.1 M rays (900.0 k camera, 400.0 k secondary, \
             1.8 M shadow), 7.4 M rays/s, 2 threads"
        );
        summary.stats.threads = 1;
        summary.stats.nonfinite_samples = 3;
        assert!(summary.to_string().ends_with(", 1 thread, 3 nonfinite samples set to black"), "{summary}");
        // Adaptive: the mean count and the most any pixel took.
        summary.adaptive = true;
        summary.spp = 16;
        summary.stats.pixel_samples = 1280 * 720 * 3 / 2;
        assert!(summary.to_string().starts_with("rendered luxo 1280x720, 1.50 spp adaptive (at most 16) in 420.0 ms"), "{summary}");
    }
}
