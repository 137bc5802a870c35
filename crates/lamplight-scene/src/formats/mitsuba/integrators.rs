//! `<integrator>` to `[render]`: `path`, `direct`, `ptracer`, `volpath` and
//! `volpathmis` (scenes without media) all have the expected image of
//! lamplight's path tracer, which is used for them. So do the differentiable
//! integrators, whose primal image is that of the one they differentiate:
//! `prb`, `prb_basic` and `prb_projective` that of `path`, `prbvolpath` that of
//! `volpath`, `direct_projective` that of `direct`. Their gradient settings
//! (`sppc`, `sppp`, `sppi`, `guiding`, ...) change no primal pixel and are read
//! without a word.
//!
//! `max_depth` counts as in Mitsuba: 1 sees emitters only, 2 adds direct light
//! (lamplight's path tracer counts the same way, camera ray = 1); Mitsuba's
//! `-1` (no limit, its default) is lamplight's deepest, 64. `direct` is
//! `max_depth = 2`. `rr_depth` (default 5) is `[render] rr_depth`, counted the
//! same: Russian roulette from the segment of that number on (it changes only
//! the noise; lamplight survives with `min(1, max throughput)`, Mitsuba with
//! `min(0.95, max throughput eta^2)`). `hide_emitters = true` is
//! `[render] hide_emitters = true`: camera rays go through emitting surfaces
//! and see black where they leave the scene, as Mitsuba's do. `moment` is the
//! integrator it wraps with `[render] variance = true`: an `.exr` output holds
//! the layer `variance.R/G/B`, the variance of each pixel's mean (Mitsuba's
//! `m2 - m1^2` over the sample count), which `lamplight` writes unasked.

use lamplight_core::params::{Loc, ParamError};

use super::properties::Plugin;
use super::xml::El;
use super::{entry, int, text, Ctx};

const DEEPEST: i64 = crate::instantiate::MAX_DEPTH_LIMIT as i64;

fn err(loc: &Loc, message: impl Into<String>) -> ParamError {
    ParamError { loc: loc.clone(), message: message.into() }
}

/// The projective integrators' settings for their gradients (Mitsuba's
/// `PSIntegrator`, `ad/integrators/common.py`): none changes the primal image.
fn take_gradient_settings(p: &mut Plugin<'_>) {
    for key in ["sppc", "sppp", "sppi", "guiding", "guiding_proj", "guiding_rounds", "project_seed"] {
        let _ = p.take(key);
    }
}

/// Reads an `<integrator>`.
pub fn read<'a>(ctx: &mut Ctx<'a>, el: &'a El) -> Result<(), ParamError> {
    let mut p = Plugin::new(el)?;
    let depth = match p.kind.as_str() {
        "path" | "ptracer" | "volpath" | "volpathmis" | "prb" | "prb_basic" | "prb_projective" | "prbvolpath" => {
            // Mitsuba's `path` has no limit by default, its differentiable
            // integrators 6 (`ad/integrators/common.py`).
            let default_depth = if p.kind.starts_with("prb") { 6 } else { -1 };
            let (d, loc) = p.integer("max_depth")?.unwrap_or((default_depth, el.loc.clone()));
            // The same counting as lamplight's path tracer; Mitsuba's default is 5.
            let (rr, rloc) = p.integer("rr_depth")?.unwrap_or((5, el.loc.clone()));
            if rr < 1 {
                return Err(err(&rloc, format!("{}: rr_depth: must be a positive integer, got {rr}", p.label)));
            }
            ctx.render.retain(|e| e.key != "rr_depth");
            // Past the deepest path, roulette never starts either way.
            ctx.render.push(entry("rr_depth", int(rr.min(DEEPEST), &rloc)));
            if p.kind != "path" {
                let _ = p.take("samples_per_pass");
            }
            take_gradient_settings(&mut p);
            match d {
                -1 => (DEEPEST, loc),
                d if (1..=DEEPEST).contains(&d) => (d, loc),
                d if d > DEEPEST => {
                    ctx.warn(&loc, format!("{}: max_depth {d} is read as {DEEPEST}, lamplight's deepest", p.label));
                    (DEEPEST, loc)
                }
                d => return Err(err(&loc, format!("{}: max_depth: must be -1 or between 1 and {DEEPEST}, got {d}", p.label))),
            }
        }
        "direct" | "direct_projective" => {
            take_gradient_settings(&mut p);
            for key in ["emitter_samples", "bsdf_samples", "shading_samples"] {
                if let Some((_, loc)) = p.integer(key)? {
                    ctx.warn(&loc, format!("{}: {key} changes only the noise, ignored", p.label));
                }
            }
            (2, el.loc.clone())
        }
        "moment" => {
            // lamplight's layer is the variance of each pixel's mean: Mitsuba's (m2 - m1^2) / spp.
            ctx.render.retain(|e| e.key != "variance");
            ctx.render.push(entry("variance", super::boolean(true, &el.loc)));
            let inner = p.objects.iter().copied().find(|o| o.tag == "integrator");
            ctx.finish(p);
            return match inner {
                Some(i) => read(ctx, ctx.deref(i)?),
                None => Err(err(&el.loc, "integrator \"moment\": needs a nested <integrator>")),
            };
        }
        other => {
            let known = "path, direct, ptracer, volpath, the prb integrators and moment";
            return Err(err(&el.require("type")?.loc, format!("integrator: \"{other}\" is not supported (lamplight reads {known})")));
        }
    };
    let hide = p.boolean("hide_emitters")?;
    ctx.render.push(entry("integrator", text("path", &el.loc)));
    if let Some((true, loc)) = hide {
        ctx.render.push(entry("hide_emitters", super::boolean(true, &loc)));
    }
    ctx.render.push(entry("max_depth", int(depth.0, &depth.1)));
    ctx.finish(p);
    Ok(())
}
