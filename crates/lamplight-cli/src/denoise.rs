//! `lamplight denoise IN.exr -o OUT`: an image file through Open Image Denoise
//! (`lamplight_scene::denoise`), with the feature layers the file holds.

use std::path::PathBuf;
use std::time::Instant;

use clap::Args;

use lamplight_scene::denoise::{read_denoise_input, Denoiser};
use lamplight_scene::image_io;

use crate::args::{count, UsageError};

/// `lamplight denoise` arguments.
#[derive(Debug, Args)]
pub struct DenoiseArgs {
    /// The noisy image: an .exr file of linear radiance (R, G, B), with `albedo`, `normal` and `emitted` layers if it has them.
    #[arg(value_name = "IN.exr")]
    pub input: PathBuf,
    /// The denoised image; the extension picks the format (.exr keeps linear radiance).
    #[arg(short, long, value_name = "FILE")]
    pub output: PathBuf,
    /// Worker threads of the denoiser; 0 uses all cores.
    #[arg(long, value_name = "T", default_value_t = 0, allow_negative_numbers = true, value_parser = count::<usize>)]
    pub threads: usize,
    /// No summary line.
    #[arg(short, long)]
    pub quiet: bool,
}

/// Reads the file (a bad one is told before the library is looked for), loads
/// the denoiser, denoises and writes, and prints what guided the filter.
pub fn denoise_command(args: &DenoiseArgs) -> anyhow::Result<()> {
    image_io::check_writable(&args.output)?;
    // A file that cannot be read or holds no image, and a missing library, are the user's to fix: exit code 2.
    let input = read_denoise_input(&args.input).map_err(|e| UsageError(e.0))?;
    let denoiser = Denoiser::load(&[]).map_err(|e| UsageError(e.0))?;
    let start = Instant::now();
    let image = input.denoise(&denoiser, args.threads)?;
    let seconds = start.elapsed().as_secs_f64();
    image_io::write_image(&args.output, &image)?;
    if !args.quiet {
        let present = [("albedo", input.albedo.is_some()), ("normal", input.normal.is_some()), ("emitted", input.emitted.is_some())];
        let guides: Vec<&str> = present.iter().filter_map(|(name, present)| present.then_some(*name)).collect();
        let with = match guides.split_last() {
            None => "the image alone".to_string(),
            Some((last, [])) => last.to_string(),
            Some((last, rest)) => format!("{} and {last}", rest.join(", ")),
        };
        eprintln!("{}x{} denoised with {with} in {seconds:.2} s -> {}", image.width, image.height, args.output.display());
    }
    Ok(())
}
