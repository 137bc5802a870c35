//! `<integrator>` to `[render]`: `path`, `direct`, `ptracer`, `volpath` and
//! `volpathmis` (scenes without media) all have the expected image of
//! lamplight's path tracer, which is used for them.
//!
//! `max_depth` counts as in Mitsuba: 1 sees emitters only, 2 adds direct light
//! (lamplight's path tracer counts the same way, camera ray = 1); Mitsuba's
//! `-1` (no limit, its default) is lamplight's deepest, 64. `direct` is
//! `max_depth = 2`. `rr_depth` changes only the noise (Russian roulette keeps
//! the estimate unbiased) and is read but not used. `hide_emitters = true` is
//! `[render] hide_emitters = true`: camera rays go through emitting surfaces
//! and see black where they leave the scene, as Mitsuba's do. `moment` is read as the
//! integrator it wraps: pass `--exr-layers variance` for the variance layer.

use lamplight_core::params::{Loc, ParamError};

use super::properties::Plugin;
use super::xml::El;
use super::{entry, int, text, Ctx};

const DEEPEST: i64 = crate::build::MAX_DEPTH_LIMIT as i64;

fn err(loc: &Loc, message: impl Into<String>) -> ParamError {
    ParamError { loc: loc.clone(), message: message.into() }
}

/// Reads an `<integrator>`.
pub fn read<'a>(ctx: &mut Ctx<'a>, el: &'a El) -> Result<(), ParamError> {
    let mut p = Plugin::new(el)?;
    let depth = match p.kind.as_str() {
        "path" | "ptracer" | "volpath" | "volpathmis" => {
            let (d, loc) = p.integer("max_depth")?.unwrap_or((-1, el.loc.clone()));
            let _ = p.integer("rr_depth")?;
            if p.kind != "path" {
                let _ = p.take("samples_per_pass");
            }
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
        "direct" => {
            for key in ["emitter_samples", "bsdf_samples", "shading_samples"] {
                if let Some((_, loc)) = p.integer(key)? {
                    ctx.warn(&loc, format!("{}: {key} changes only the noise, ignored", p.label));
                }
            }
            (2, el.loc.clone())
        }
        "moment" => {
            ctx.warn(&el.loc, "integrator \"moment\": read as the integrator it wraps; pass --exr-layers variance for the variance layer");
            let inner = p.objects.iter().copied().find(|o| o.tag == "integrator");
            ctx.finish(p);
            return match inner {
                Some(i) => read(ctx, ctx.deref(i)?),
                None => Err(err(&el.loc, "integrator \"moment\": needs a nested <integrator>")),
            };
        }
        other => {
            return Err(err(
                &el.require("type")?.loc,
                format!("integrator: \"{other}\" is not supported (lamplight reads path, direct, ptracer, volpath and moment)"),
            ))
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
