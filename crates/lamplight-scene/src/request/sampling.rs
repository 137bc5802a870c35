//! How many samples each pixel takes: fixed supersampling (`spp`), POV-Ray's
//! adaptive anti-aliasing (`antialias`) or Cycles' noise threshold
//! (`noise_threshold`, `min_spp`), resolved from the request, then the scene,
//! then the defaults, for the command line and Python alike.
//!
//! The defaults are what a user of POV-Ray or Cycles expects: the Whitted
//! tracer anti-aliases adaptively, and the path tracer, given no sample count,
//! samples each pixel until its noise falls below [`NOISE_DEFAULT_THRESHOLD`],
//! at least [`DEFAULT_MIN_SAMPLES`] and at most [`NOISE_DEFAULT_SPP`] samples,
//! rather than one speckled sample a pixel. The threshold is a preview's (the
//! Cornell box at 512x512: 127 samples a pixel on average, about 20 s on 2
//! cores; Cycles' final-render 0.01 took 894 and 145 s); a final image asks
//! for its own.

use lamplight_core::adaptive::DEFAULT_MIN_SAMPLES;
use lamplight_core::integrators::{IntegratorEntry, Schedule};
use lamplight_core::{Adaptive, Antialias, NoiseThreshold};

use super::{bad, Defaults, Naming, Request, RequestError};

/// Adaptive anti-aliasing as asked for (`--antialias`, `antialias=`, `[render] antialias`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum AntialiasRequest {
    /// One sample per pixel (or `spp`), nowhere more.
    Off,
    /// Refine pixels whose neighbours differ by more than `threshold`.
    On {
        /// POV-Ray's `Antialias_Threshold`.
        threshold: f64,
    },
}

impl std::str::FromStr for AntialiasRequest {
    type Err = String;

    /// `off`, `on` (threshold 0.3) or a threshold `>= 0`.
    fn from_str(s: &str) -> Result<AntialiasRequest, String> {
        match s {
            "off" | "false" => Ok(AntialiasRequest::Off),
            "on" | "true" => Ok(AntialiasRequest::On { threshold: Antialias::default().threshold }),
            _ => match s.parse::<f64>() {
                Ok(t) if t >= 0.0 && t.is_finite() => Ok(AntialiasRequest::On { threshold: t }),
                _ => Err(format!("expected `on`, `off` or a threshold >= 0 (POV-Ray's 0.3), got '{s}'")),
            },
        }
    }
}

/// Most samples per pixel a noise threshold may take when no `spp` is given.
pub const NOISE_DEFAULT_SPP: u32 = 1024;

/// The path tracer's noise threshold when neither a sample count nor a
/// threshold is given (a preview's, see the module doc).
pub const NOISE_DEFAULT_THRESHOLD: f64 = 0.05;

/// Samples per pixel and adaptive sampling. The request's own choice (`spp`
/// or `antialias`) comes before the scene's; a noise threshold (request's,
/// then scene's) makes `spp` the most a pixel takes. Without any, a one-pass
/// integrator (Whitted) anti-aliases adaptively and the others sample to
/// [`NOISE_DEFAULT_THRESHOLD`] (see the module doc).
pub(super) fn resolve(
    r: &Request,
    d: &Defaults,
    integrator: &IntegratorEntry,
    naming: Naming,
) -> Result<(u32, Option<Adaptive>), RequestError> {
    let n = |k: &str| naming.name(k);
    let one_pass = integrator.schedule == Schedule::OnePass;
    if let (Some(spp), Some(AntialiasRequest::On { .. })) = (r.spp, r.antialias) {
        return Err(bad(format!(
            "give {} (fixed supersampling, {spp} samples everywhere) or {} (adaptive: 16 samples where neighbours differ), not both",
            n("spp"),
            n("antialias")
        )));
    }
    // No sample count anywhere: a progressive integrator samples to the default
    // noise level. (A scene's `antialias` is the Whitted tracer's; the request's
    // under the path tracer is refused below.)
    let unspecified = r.spp.is_none() && d.spp.is_none() && r.antialias.is_none();
    let default_threshold = (unspecified && !one_pass).then_some(NOISE_DEFAULT_THRESHOLD);
    if let Some(threshold) = r.noise_threshold.or(d.noise_threshold).or(default_threshold) {
        if !(threshold.is_finite() && threshold > 0.0) {
            return Err(bad(format!("{} must be a positive number (a noise level, e.g. 0.01), got {threshold}", n("noise_threshold"))));
        }
        if one_pass {
            return Err(bad(format!(
                "{} is for the path tracer ({} path); {} takes its samples in one pass",
                n("noise_threshold"),
                n("integrator"),
                integrator.name
            )));
        }
        let spp = r.spp.or(d.spp).unwrap_or(NOISE_DEFAULT_SPP);
        let min_samples = r.min_spp.or(d.min_spp).unwrap_or(DEFAULT_MIN_SAMPLES.min(spp));
        if !(1..=spp).contains(&min_samples) {
            return Err(bad(format!("{} must be between 1 and {} ({}), got {min_samples}", n("min_spp"), n("spp"), spp)));
        }
        return Ok((spp, Some(Adaptive::NoiseThreshold(NoiseThreshold { threshold, min_samples }))));
    }
    if r.min_spp.is_some() {
        return Err(bad(format!("{} takes effect only with {}", n("min_spp"), n("noise_threshold"))));
    }
    // The request's choice, then the scene's: an explicit spp is fixed supersampling.
    let (spp, antialias) = if r.spp.is_some() || r.antialias.is_some() { (r.spp, r.antialias) } else { (d.spp, d.antialias) };
    let threshold = match (spp, antialias) {
        (Some(spp), Some(AntialiasRequest::On { .. })) => {
            // Only a scene's `[render]` gets here: the request's pair is refused above.
            return Err(bad(format!(
                "the scene's [render] gives both spp = {spp} (fixed supersampling) and antialias (adaptive); keep one"
            )));
        }
        (_, Some(AntialiasRequest::Off)) | (Some(_), None) => None,
        (_, Some(AntialiasRequest::On { threshold })) => Some(threshold),
        (None, None) => one_pass.then_some(Antialias::default().threshold),
    };
    match threshold {
        Some(threshold) if one_pass => {
            if !(threshold.is_finite() && threshold >= 0.0) {
                return Err(bad(format!("{} threshold must be a number >= 0, got {threshold}", n("antialias"))));
            }
            Ok((1, Some(Adaptive::Antialias(Antialias { threshold, ..Antialias::default() }))))
        }
        Some(_) if r.antialias.is_some() => Err(bad(format!(
            "{} is for the Whitted tracer; the {} integrator takes {} samples per pixel (or {})",
            n("antialias"),
            integrator.name,
            n("spp"),
            n("noise_threshold")
        ))),
        // A scene's `antialias` under another integrator: nothing to refine.
        _ => Ok((spp.unwrap_or(1), None)),
    }
}

#[cfg(test)]
mod tests;
